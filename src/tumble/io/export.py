"""Trajectories out: CSV (one row per sample), NPZ (every array), JSON summaries.

All writes are atomic (a temporary file renamed into place), so a failure leaves no
half-written file behind.
"""

from __future__ import annotations

import io
import json

import numpy as np

from ..dynamics import Trajectory
from .atomic import atomic_write_bytes, atomic_write_text

__all__ = ["CSV_COLUMNS", "trajectory_csv", "write_csv", "write_json", "write_npz"]

#: Columns of the trajectory CSV, each with its SI unit in brackets (the quaternion has none):
#: omega in the principal frame; the quaternion maps body to world, scalar last (scipy); L in
#: the world frame; kinetic energy.
CSV_COLUMNS = (
    "t [s]", "omega_1 [rad/s]", "omega_2 [rad/s]", "omega_3 [rad/s]", "q_x", "q_y", "q_z", "q_w",
    "L_world_x [kg m^2/s]", "L_world_y [kg m^2/s]", "L_world_z [kg m^2/s]", "energy [J]",
)


def trajectory_csv(traj: Trajectory) -> str:
    """The CSV text of a trajectory (header + one row per sample, full double precision)."""
    table = np.column_stack([traj.t, traj.omega, traj.quat, traj.angular_momentum_world, traj.energy])
    buf = io.StringIO()
    np.savetxt(buf, table, delimiter=",", header=",".join(CSV_COLUMNS), comments="", fmt="%.17g")
    return buf.getvalue()


def write_csv(traj: Trajectory, path) -> None:
    """Write :func:`trajectory_csv` to ``path`` atomically."""
    atomic_write_text(path, trajectory_csv(traj))


def write_npz(traj: Trajectory, path, provenance: dict | None = None) -> None:
    """Every array of the trajectory in one compressed NPZ file, written atomically.

    Arrays: ``t`` (s), ``omega``, ``omega_world`` (rad/s), ``quat`` (body to world, scalar
    last), ``L``, ``L_world`` (kg m^2/s), ``energy`` (J), ``moments`` (kg m^2),
    ``principal_axes`` (principal -> design; columns are the axes), ``method``, and
    ``provenance`` (a JSON string, :func:`tumble.io.provenance.provenance`) when given.
    """
    buf = io.BytesIO()
    extra = {} if provenance is None else {"provenance": np.array(json.dumps(provenance))}
    np.savez_compressed(
        buf, t=traj.t, omega=traj.omega, omega_world=traj.omega_world, quat=traj.quat,
        L=traj.angular_momentum, L_world=traj.angular_momentum_world, energy=traj.energy,
        moments=traj.moments, principal_axes=traj.principal_axes, method=np.array(traj.method), **extra,
    )
    atomic_write_bytes(path, buf.getvalue())


def write_json(data, path) -> None:
    """Pretty JSON, written atomically."""
    atomic_write_text(path, json.dumps(data, indent=2) + "\n")
