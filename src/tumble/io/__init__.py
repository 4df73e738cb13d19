"""Files in and out: body and scenario files (TOML); reports, trajectories (CSV, NPZ, JSON)."""

from typing import TYPE_CHECKING

from .._lazy import lazy_package

if TYPE_CHECKING:  # the names, as the type checker sees them; each is imported on its first use
    from .bodyfile import body_from_table, load_body, part_from_table, read_toml
    from .export import read_npz, write_npz
    from .scenario import Scenario, load_scenario
    from .report import mass_properties_dict, mass_properties_table

lazy_package(__name__)

__all__ = [
    "body_from_table",
    "load_body",
    "mass_properties_dict",
    "mass_properties_table",
    "part_from_table",
    "read_npz",
    "read_toml",
    "write_npz",
    "Scenario",
    "load_scenario",
]
