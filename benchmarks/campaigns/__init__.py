"""Campaigns: the many-seed checks too slow for make test (conftest.py)."""
