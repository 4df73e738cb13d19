"""Trajectories out: CSV (one row per sample), NPZ (every array), JSON summaries.

All writes are atomic (a temporary file renamed into place), so a failure leaves no
half-written file behind.
"""

from __future__ import annotations

import io
import json
import os
import zipfile

import numpy as np

from ..dynamics import Trajectory
from ..validation import NoSuchFileError, short_repr
from .atomic import atomic_write_bytes, atomic_write_text

__all__ = ["CSV_COLUMNS", "read_npz", "trajectory_csv", "write_csv", "write_json", "write_npz"]

#: Columns of the trajectory CSV, each with its SI unit in brackets (the quaternion has none):
#: omega in the principal frame; the quaternion maps body to world, scalar last (scipy); L in
#: the world frame; kinetic energy.
CSV_COLUMNS = (
    "t [s]", "omega_1 [rad/s]", "omega_2 [rad/s]", "omega_3 [rad/s]", "q_x", "q_y", "q_z", "q_w",
    "L_world_x [kg m^2/s]", "L_world_y [kg m^2/s]", "L_world_z [kg m^2/s]", "energy [J]",
)


#: Columns added after :data:`CSV_COLUMNS` when the run has them: the damper's dissipated energy
#: and the rotors' motor work since t = 0 (``energy`` is then the total kinetic energy).
CSV_BUDGET_COLUMNS = {"dissipated": "dissipated [J]", "motor_work": "motor_work [J]"}


def _check_run(traj: object, call: str) -> None:
    """A TypeError naming ``traj`` unless it is a Trajectory (the run comes first: ``call``)."""
    if not isinstance(traj, Trajectory):
        raise TypeError(f"traj = {short_repr(traj)} is not a Trajectory: {call} takes the run first")


def trajectory_csv(traj: Trajectory) -> str:
    """The CSV text of a trajectory (header + one row per sample, full double precision).

    Examples
    --------
    >>> import tumble
    >>> from tumble.io.export import trajectory_csv
    >>> lines = trajectory_csv(tumble.simulate(tumble.t_handle(), [0.0, 0.0, 2.0], t_end=1.0, samples=3)).splitlines()
    >>> len(lines), lines[0].split(",")[:4]   # a header and one row per sample
    (4, ['t [s]', 'omega_1 [rad/s]', 'omega_2 [rad/s]', 'omega_3 [rad/s]'])
    """
    _check_run(traj, "trajectory_csv(traj)")
    extra = {k: getattr(traj, k) for k in CSV_BUDGET_COLUMNS if getattr(traj, k) is not None}
    table = np.column_stack([traj.t, traj.omega, traj.quat, traj.angular_momentum_world, traj.energy, *extra.values()])
    header = [*CSV_COLUMNS, *(CSV_BUDGET_COLUMNS[k] for k in extra)]
    buf = io.StringIO()
    np.savetxt(buf, table, delimiter=",", header=",".join(header), comments="", fmt="%.17g")
    return buf.getvalue()


def write_csv(traj: Trajectory, path: str | os.PathLike[str]) -> None:
    """Write :func:`trajectory_csv` to ``path`` atomically.

    Examples
    --------
    >>> import pathlib, tempfile, numpy as np, tumble
    >>> from tumble.io.export import write_csv
    >>> traj = tumble.simulate(tumble.t_handle(), [0.1, 2.0, 0.1], t_end=1.0, samples=5)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_csv(traj, pathlib.Path(folder, "run.csv"))
    ...     table = np.loadtxt(pathlib.Path(folder, "run.csv"), delimiter=",", skiprows=1)
    >>> bool(np.array_equal(table[:, 1:4], traj.omega))   # full double precision
    True
    """
    _check_run(traj, "write_csv(traj, path)")
    atomic_write_text(path, trajectory_csv(traj))


def write_npz(traj: Trajectory, path: str | os.PathLike[str], provenance: dict | None = None) -> None:
    """Every array of the trajectory in one compressed NPZ file, written atomically.

    Arrays: ``t`` (s), ``omega``, ``omega_world`` (rad/s), ``quat`` (body to world, scalar
    last), ``L``, ``L_world`` (kg m^2/s), ``energy`` (J), ``moments`` (kg m^2),
    ``principal_axes`` (principal -> design; columns are the axes), ``method``, ``auto``,
    ``torque_free``, ``body_name``, and ``provenance`` (a JSON string,
    :func:`tumble.io.provenance.provenance`) when given; with rotors ``internal_momentum``
    (kg m^2/s, principal frame), ``rotor_spin`` (rad/s), ``rotor_axial_moments`` (kg m^2),
    ``motor_work`` (J); with a damper ``damper_inertia`` (kg m^2), ``damper_omega`` (rad/s),
    ``dissipated`` (J) and ``nutation_angle`` (rad). :func:`read_npz` gives the trajectory back.

    Examples
    --------
    >>> import pathlib, tempfile, numpy as np, tumble
    >>> from tumble.io.export import write_npz
    >>> traj = tumble.simulate(tumble.t_handle(), [0.1, 2.0, 0.1], t_end=1.0, samples=5)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_npz(traj, pathlib.Path(folder, "run.npz"))
    ...     with np.load(pathlib.Path(folder, "run.npz")) as data:
    ...         print(str(data["method"]), bool(np.array_equal(data["quat"], traj.quat)))
    exact True
    """
    _check_run(traj, "write_npz(traj, path)")
    buf = io.BytesIO()
    extra = {} if provenance is None else {"provenance": np.array(json.dumps(provenance))}
    for name in _INTERNAL:
        if getattr(traj, name) is not None:
            extra[name] = getattr(traj, name)
    if traj.damper_omega is not None:
        extra["nutation_angle"] = traj.nutation_angle
    np.savez_compressed(
        buf, t=traj.t, omega=traj.omega, omega_world=traj.omega_world, quat=traj.quat,
        L=traj.angular_momentum, L_world=traj.angular_momentum_world, energy=traj.energy,
        moments=traj.moments, principal_axes=traj.principal_axes, method=np.array(traj.method), auto=np.array(traj.auto),
        torque_free=np.array(traj.torque_free), body_name=np.array(traj.body_name), **extra,
    )
    atomic_write_bytes(path, buf.getvalue())


#: The optional fields of a trajectory (rotors, a damper) that :func:`write_npz` keeps when present.
_INTERNAL = ("internal_momentum", "rotor_spin", "rotor_axial_moments", "motor_work", "damper_inertia", "damper_omega",
             "dissipated")
#: The arrays every trajectory file has.
_REQUIRED = ("t", "omega", "quat", "moments", "principal_axes", "method")


def read_npz(path: str | os.PathLike[str]) -> Trajectory:
    """The :class:`~tumble.dynamics.Trajectory` of a file :func:`write_npz` wrote
    (``tumble simulate``'s ``DIR/trajectory.npz`` among them): the samples, the body's moments and
    axes, the method, and the rotors' and the damper's arrays, so that every derived quantity
    (energy, momentum, the flip's analysis, the figures) is the run's again. A file written before
    ``torque_free`` was kept (2026-11-30) reads as torqued: nothing is claimed conserved.

    Raises
    ------
    FileNotFoundError
        For a missing file (:class:`~tumble.validation.NoSuchFileError`, also a ``ValueError``).
    ValueError
        For a file that is not an NPZ or lacks a trajectory's arrays, naming the path and the
        first missing array; or for arrays that are not a trajectory's (the trajectory's own checks).

    Examples
    --------
    >>> import pathlib, tempfile, numpy as np, tumble
    >>> from tumble.io.export import read_npz, write_npz
    >>> traj = tumble.simulate(tumble.t_handle(), [0.1, 2.0, 0.1], t_end=1.0, samples=5)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_npz(traj, pathlib.Path(folder, "run.npz"))
    ...     back = read_npz(pathlib.Path(folder, "run.npz"))
    >>> back.method_label, bool(np.array_equal(back.omega, traj.omega)), bool(np.array_equal(back.energy, traj.energy))
    ('exact (auto)', True, True)
    """
    where = os.fspath(path)
    if os.path.isdir(where):
        raise ValueError(f"{where} is a folder, not a trajectory's NPZ file (tumble simulate writes DIR/trajectory.npz)")
    if not os.path.isfile(where):
        raise NoSuchFileError(f"{where}: no such file")
    try:
        with np.load(where, allow_pickle=False) as data:
            arrays = {name: data[name] for name in data.files}
    except (OSError, ValueError, zipfile.BadZipFile) as exc:
        raise ValueError(f"{where}: not a trajectory's NPZ file ({exc})") from None
    missing = [name for name in _REQUIRED if name not in arrays]
    if missing:
        raise ValueError(f"{where}: no {missing[0]!r} array: not a trajectory's NPZ file (tumble.io.export.write_npz)")
    n = len(arrays["t"]) if arrays["t"].ndim == 1 else -1
    shapes = {"t": (n,), "omega": (n, 3), "quat": (n, 4), "moments": (3,), "principal_axes": (3, 3)}
    internal = {name: arrays[name] for name in _INTERNAL if name in arrays}
    for name, value in [*((k, arrays[k]) for k in shapes), *internal.items()]:
        shape = shapes.get(name, {"damper_inertia": (), "rotor_axial_moments": value.shape[:1]}.get(name, (n, *value.shape[1:])))
        if value.shape != shape or value.dtype.kind != "f" or not np.all(np.isfinite(value)):
            raise ValueError(f"{where}: {name} has shape {value.shape} and dtype {value.dtype}; a trajectory's of "
                             f"{n} samples is finite floats of shape {shape}")
    if "damper_inertia" in internal:
        internal["damper_inertia"] = float(internal["damper_inertia"])
    return Trajectory.of_samples(arrays["t"], arrays["omega"], arrays["quat"], arrays["moments"], arrays["principal_axes"],
                                 str(arrays["method"]), torque_free=bool(arrays.get("torque_free", False)),
                                 body_name=str(arrays.get("body_name", "body")), auto=bool(arrays.get("auto", False)),
                                 **internal)


def write_json(data: object, path: str | os.PathLike[str]) -> None:
    """Pretty JSON, written atomically.

    Examples
    --------
    >>> import json, pathlib, tempfile
    >>> from tumble.io.export import write_json
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_json({"moments": [0.125, 0.3125, 0.4375]}, pathlib.Path(folder, "out.json"))
    ...     print(json.loads(pathlib.Path(folder, "out.json").read_text()))
    {'moments': [0.125, 0.3125, 0.4375]}
    """
    atomic_write_text(path, json.dumps(data, indent=2) + "\n")
