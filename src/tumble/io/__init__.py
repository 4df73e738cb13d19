"""Files in and out: body files (TOML), reports (JSON, text)."""

from .bodyfile import body_from_table, load_body, part_from_table, read_toml
from .report import mass_properties_dict, mass_properties_table

__all__ = [
    "body_from_table",
    "load_body",
    "mass_properties_dict",
    "mass_properties_table",
    "part_from_table",
    "read_toml",
]
