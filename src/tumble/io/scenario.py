"""Scenario files (TOML): a body, an initial spin and how to integrate it.

::

    body = "t-handle"          # a preset name, a body file (relative to this file), or a [body] table

    [initial]
    omega = [0.1, 10.0, 0.1]   # rad/s
    frame = "principal"        # "principal" (axes ordered I1 <= I2 <= I3) or "design"

    [simulation]
    t_end = 20.0               # s
    samples = 500              # or dt = 0.01 (s), or times = [0.0, 0.5, 2.0] instead of t_end
    method = "auto"            # "auto" (the default), "exact", "dop853", "rk8", "rk4", "rk45", "geometric", ...
    # rtol = 1e-12             # optional tolerances (auto, dop853, rk45, seed; rk4 and rk8 without a step)
    # atol = 1e-12
    # step = 1e-3              # optional largest step of the fixed-step methods, s

    [torque]                   # optional: a constant torque
    vector = [0.0, 0.0, 0.01]  # N m
    frame = "body"             # "body" or "world"

    # or the gravity gradient of a circular orbit (tumble.GravityGradient):
    # [torque]
    # kind = "gravity_gradient"
    # (several torques acting together, their sum: a [[torque]] table for each)
    # orbit_period = 5400.0    # s (or orbit_radius, m; mu, m^3/s^2, default the Earth's)
    # [initial.orbit_frame]    # instead of omega: start at rest in the orbiting frame
    # pitch = 0.01             # rad (roll, pitch, yaw; pitch_axis = 3, yaw_axis = 1)
    # or along an ellipse about the Earth (world frame ECI), or a TLE's orbit (tle = [line1, line2]):
    # semi_major_axis = 12e6   # m (eccentricity; inclination, raan, arg_perigee, mean_anomaly, rad)

    [damper]                   # optional: a spherical nutation damper (tumble.SphericalDamper)
    inertia = 0.01             # kg m^2, the sphere's moment of inertia
    damping = 0.05             # N m s, the viscous coupling

Rotors are parts of the body (``kind = "rotor"`` in a body file).

Keys are checked strictly; every error is one line naming the file and the key.
:func:`resolve_run` is what the CLI uses: a scenario file, or a body file or preset name plus
an initial spin, with command-line values overriding the file's.
"""

from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..dynamics import SphericalDamper, TorqueModel
from ..dynamics.methods.names import ALLOWED
from ..dynamics.models.gravity import gravity_gradient_in
from ..dynamics.models.orbit_gravity import OrbitGravityGradient
from ..dynamics.simulate import DEFAULT_SAMPLES, check_inputs, sample_times
from ..mass import PRESETS, Body
from ..typing import ArrayLike
from ..validation import NoSuchFileError, nearest, unknown_name
from .bodyfile import body_from_table, body_path, is_mesh_file, load_body, named_presets, preset_body, read_toml
from .controlfile import CONTROL_SECTIONS, ControlScenario, is_control_file, load_control_scenario
from .gravitytables import ORBIT_FRAME_TABLE, gravity_gradient_from_table, lvlh_state_from_table
from .torquetables import TORQUE_TABLE, torque_of

#: Where a residual dipole is taken: a file with a magnetic field.
_DIPOLE_ELSEWHERE = "control files take a residual_dipole, in their [orbit]'s magnetic field"
from .keys import FileFormat, Key, Table
from .provenance import file_sha256

__all__ = ["SCENARIO_FORMAT", "TORQUE_TABLE", "Scenario", "gravity_gradient_from_table", "load_scenario", "lvlh_state_from_table", "resolve_run",
           "scenario_from_table"]

#: Duration of a run when neither the file nor the command line says, s.
DEFAULT_T_END = 20.0

_BODY = Key("body", "string or table", required=True, allowed="a preset name, a body file or a [body] table",
            example='"t-handle"', doc="the body: a preset, a body file (relative to this file) or a [body] table")
_OMEGA = Key("omega", "3 numbers", "rad/s", example="[0.1, 10.0, 0.1]", doc="the initial angular velocity")
_T_END = Key("t_end", "number", "s", f"{DEFAULT_T_END}", example="20.0", doc="duration of the run", low=0.0)
_SAMPLES = Key("samples", "whole number", "", f"{DEFAULT_SAMPLES}", example="400", doc="samples returned, t = 0 to t_end",
               low=2, low_included=True, high=1_000_000)
_TIMES = Key("times", "list of numbers", "s", allowed=">= 0, increasing", example="[0.0, 0.5, 2.0]",
             doc="the sample times, instead of t_end, samples and dt")
_METHOD = Key("method", "string", "", '"auto"', example='"dop853"', choices=ALLOWED,
              doc="the integration method (auto: chosen from what the run has, and named in the output)")
_STEP = Key("step", "number", "s", "(the method's)", example="0.001", low=0.0,
            doc="the largest step of a fixed-step or splitting method")
_RTOL = Key("rtol", "number", "", "(the method's)", example="1e-12", low=2.22e-14, low_included=True, high=0.1,
            doc="relative tolerance (auto, dop853, rk45, seed; rk4 and rk8 without a step: the step that meets it)")
_ATOL = Key("atol", "number", "rad/s", "(the method's)", example="1e-12", low=0.0, high=0.1,
            doc="absolute tolerance (relative to the spin for auto and dop853; the quaternion's components take it too)")
#: The tables of a scenario file (without ``[control]``; a closed-loop run's are
#: :data:`tumble.io.controlfile.CONTROL_FORMAT`'s) and their keys.
SCENARIO_FORMAT = FileFormat("scenario", (
    Table("top level", (_BODY,
                        Key("initial", "table", required=True, example="{omega = [0.1, 10.0, 0.1]}", doc="[initial]"),
                        Key("simulation", "table", example="{t_end = 20.0}", doc="[simulation]"),
                        Key("torque", "table", example='{vector = [0.0, 0.0, 0.01]}',
                            doc="[torque], or a [[torque]] table for each of several torques"),
                        Key("damper", "table", example="{inertia = 0.01, damping = 0.05}", doc="[damper]"))),
    Table("[initial]", (
        _OMEGA,
        Key("frame", "string", "", '"principal"', choices=("principal", "design"), example='"design"',
            doc="the frame of omega: principal axes (I1 <= I2 <= I3) or the body file's design frame"),
        Key("orbit_frame", "table", example="{pitch = 0.01}",
            doc="instead of omega: start at rest in the orbiting frame (needs the gravity-gradient torque)"),
    ), "The initial spin: ``omega`` (required) or ``[initial.orbit_frame]``."),
    ORBIT_FRAME_TABLE,
    Table("[simulation]", (
        _T_END, _SAMPLES,
        Key("dt", "number", "s", example="0.01", low=0.0, doc="the sample interval, instead of samples"),
        _TIMES, _METHOD,
        _RTOL, _ATOL,
        _STEP,
    ), "When to sample and how to integrate."),
    TORQUE_TABLE,
    Table("[damper]", (
        Key("inertia", "number", "kg m^2", required=True, example="0.01", low=0.0, doc="the sphere's moment of inertia"),
        Key("damping", "number", "N m s", required=True, example="0.05", low=0.0, low_included=True,
            doc="the viscous coupling"),
    ), "Optional: a spherical nutation damper (:class:`tumble.dynamics.SphericalDamper`)."),
), "A body, an initial spin and how to integrate it: ``tumble simulate``, ``tumble plot`` and "
   "``tumble view`` read it; a file with a ``[control]`` table is a control scenario instead.")
_SECTIONS = {t.title.strip("[]"): t for t in SCENARIO_FORMAT.tables[1:] if t.title != "[initial.orbit_frame]"}


@dataclass(frozen=True, eq=False)
class Scenario:
    """A parsed scenario: everything :func:`tumble.simulate` needs.

    Examples
    --------
    >>> import tumble
    >>> from tumble.io.scenario import Scenario
    >>> scenario = Scenario(body=tumble.t_handle(), omega=(0.0, 0.0, 2.0), t_end=4.0, samples=5)
    >>> traj = tumble.simulate(**scenario.arguments())
    >>> traj.t.tolist(), traj.method
    ([0.0, 1.0, 2.0, 3.0, 4.0], 'exact')
    """

    body: Body
    omega: tuple[float, float, float]
    frame: str = "principal"
    t_end: float | None = DEFAULT_T_END
    samples: int | None = None
    method: str | None = None
    rtol: float | None = None
    atol: float | None = None
    step: float | None = None
    torque: TorqueModel | None = None
    name: str = "scenario"
    dt: float | None = None
    times: tuple[float, ...] | None = None
    #: ``(path, sha256)`` of the files it was read from (provenance).
    sources: tuple[tuple[str, str], ...] = ()
    #: Design frame to world at t = 0 (scipy Rotation), or None for the identity.
    attitude0: object = None
    damper: SphericalDamper | None = None
    #: ``(pitch_axis, yaw_axis)`` of a run started at rest in the orbiting frame (``[initial.orbit_frame]``),
    #: else None: the axes its angles from that frame and its stability are judged with.
    orbit_axes: tuple[int | str, int | str] | None = None

    def arguments(self) -> dict[str, Any]:
        """The keyword arguments of :func:`tumble.simulate` that run this scenario.

        Running it belongs to the command layer, :func:`tumble.commands.run_scenario`; this file
        layer only reads and describes it.

        Examples
        --------
        >>> import tumble
        >>> from tumble.io.scenario import Scenario
        >>> given = Scenario(body=tumble.t_handle(), omega=(0.0, 5.0, 0.0), t_end=2.0, method="rk8", step=0.01).arguments()
        >>> given["omega0"], given["method"], given["step"], given["torque"] is None
        ((0.0, 5.0, 0.0), 'rk8', 0.01, True)
        >>> float(tumble.simulate(**given).t[-1])   # s
        2.0
        """
        return dict(body=self.body, omega0=self.omega, t_end=self.t_end, samples=self.samples, dt=self.dt,
                    times=self.times, method=self.method, frame=self.frame, torque=self.torque, rtol=self.rtol,
                    atol=self.atol, step=self.step, attitude0=self.attitude0, damper=self.damper)

    @property
    def sample_count(self) -> int:
        """How many samples a run of it returns.

        Examples
        --------
        >>> import tumble
        >>> from tumble.io.scenario import Scenario
        >>> Scenario(body=tumble.t_handle(), omega=(0.0, 0.0, 1.0), t_end=1.0, dt=0.25).sample_count   # 0, 0.25, ..., 1
        5
        """
        t, keep = sample_times(self.t_end, self.samples, self.dt, self.times)
        return len(t[keep])


def scenario_from_table(data: dict, *, base_dir: Path | None = None, name: str = "scenario") -> Scenario:
    """Build a scenario from parsed TOML; values are validated by the constructors they feed.

    Examples
    --------
    >>> from tumble.io.scenario import scenario_from_table
    >>> scenario = scenario_from_table({"body": "t-handle", "initial": {"omega": [0.0, 10.0, 0.0], "frame": "design"},
    ...                                 "simulation": {"t_end": 2.0, "samples": 21}}, name="flip")
    >>> scenario.frame, scenario.t_end, scenario.sample_count
    ('design', 2.0, 21)
    """
    unknown = sorted(set(data) - set(SCENARIO_FORMAT.tables[0].names()))
    if unknown:
        near = nearest("control", unknown, cutoff=0.75)
        if near is not None:  # a control scenario's [control] table misspelt: its other tables would be named instead
            raise ValueError(f"unknown table {near!r}: did you mean [control] (a control scenario's controller)?")
        loop = [k for k in unknown if k in CONTROL_SECTIONS]
        if loop:
            raise ValueError(f"[{loop[0]}] belongs to a control scenario, which needs a [control] table (kind = ...; "
                             f"see 'tumble examples', control/); a scenario without one allows: body, {', '.join(_SECTIONS)}")
        raise ValueError(unknown_name("", unknown[0], ["body", *_SECTIONS]))
    if "body" not in data:
        raise ValueError("missing key 'body' (a preset name, a body file or a [body] table)")
    body = _body(data["body"], base_dir)
    tables = {section: keys.check(section, data.get(section, {})) for section, keys in _SECTIONS.items()
              if section != "torque"}  # one [torque] table or several [[torque]]: torque_of checks them
    initial, sim = tables["initial"], tables["simulation"]
    model = torque_of(data.get("torque"), elsewhere=_DIPOLE_ELSEWHERE)
    omega, frame, attitude0, orbit_axes = _initial(initial, model, body)
    damper = None
    if tables["damper"]:
        missing = sorted(set(_SECTIONS["damper"].names()) - set(tables["damper"]))
        if missing:
            key = _SECTIONS["damper"].key(missing[0])
            raise ValueError(f"damper: missing key {missing[0]!r} ({key.doc}, {key.unit}: {key.allowed_text()})")
        try:
            damper = SphericalDamper(**tables["damper"])
        except ValueError as exc:
            raise ValueError(f"damper: {exc}") from None
    times = sim.get("times")
    scenario = Scenario(
        body=body, omega=omega, frame=frame,
        t_end=sim.get("t_end", None if times is not None else DEFAULT_T_END),
        samples=sim.get("samples"), dt=sim.get("dt"), times=times, method=sim.get("method"), rtol=sim.get("rtol"),
        atol=sim.get("atol"), step=sim.get("step"), torque=model, name=name, attitude0=attitude0, damper=damper,
        orbit_axes=orbit_axes,
    )
    _validate(scenario)
    return scenario


def _initial(table: dict, model, body: Body):
    """``omega``, its frame, the initial attitude (or None) and the orbiting frame's ``(pitch_axis, yaw_axis)``
    (or None) from the ``[initial]`` table."""
    if "orbit_frame" not in table:
        if "omega" not in table:
            raise ValueError("initial: missing key 'omega' (rad/s), or an [initial.orbit_frame] table")
        return table["omega"], table.get("frame", "principal"), None, None
    if "omega" in table or "frame" in table:
        raise ValueError("initial: give omega (and frame) or [initial.orbit_frame], not both")
    circle = gravity_gradient_in(model)
    if circle is None:
        if any(isinstance(term, OrbitGravityGradient) for term in getattr(model, "terms", (model,))):
            raise ValueError("initial.orbit_frame needs a circular orbit (orbit_period or orbit_radius); along an "
                             "ellipse or a TLE give omega (the design axes start along the inertial frame's)")
        raise ValueError('initial.orbit_frame needs the orbit: a [torque] table with kind = "gravity_gradient"')
    model = circle
    sub = table["orbit_frame"]
    if not isinstance(sub, dict):
        raise ValueError("initial.orbit_frame must be a table [initial.orbit_frame]")
    start = lvlh_state_from_table(sub, model, body)
    return tuple(start.omega0), "principal", start.attitude0, (sub.get("pitch_axis", 3), sub.get("yaw_axis", 1))


def _body(spec, base_dir: Path | None) -> Body:
    if isinstance(spec, dict):
        return body_from_table(spec, base_dir=base_dir)
    if not isinstance(spec, str):
        raise ValueError(f"body = {spec!r} must be a preset name, a body file path or a [body] table")
    if spec in PRESETS:
        return preset_body(spec)
    return load_body(body_path(spec, base_dir))


#: Where each argument of :func:`simulate` comes from in a scenario file and on the command line.
_FILE_KEYS = {"omega0": "initial.omega", "frame": "initial.frame", "t_end": "simulation.t_end",
              "samples": "simulation.samples", "dt": "simulation.dt", "times": "simulation.times",
              "method": "simulation.method", "rtol": "simulation.rtol", "atol": "simulation.atol",
              "step": "simulation.step"}
_OPTIONS = {"omega0": "--omega", "frame": "--frame", "t_end": "--t-end", "samples": "--samples",
            "dt": "--dt", "method": "--method"}


def _validate(s: Scenario, options=()) -> None:
    """Check the numbers now, so that nothing is computed or written for a bad file.

    :func:`simulate`'s own checks keep one source of truth for the messages; the argument
    names are replaced by the file's keys, or by the command-line options for the arguments
    named in ``options`` (those the command line set).
    """
    keys = {arg: _OPTIONS[arg] if arg in options else key for arg, key in _FILE_KEYS.items()}
    try:
        check_inputs(s.body, s.omega, t_end=s.t_end, samples=s.samples, dt=s.dt, times=s.times,
                     method=s.method, frame=s.frame, rtol=s.rtol, atol=s.atol, step=s.step, torque=s.torque,
                     attitude0=s.attitude0, damper=s.damper)
    except ValueError as exc:
        message = str(exc)
        for old, new in keys.items():
            if message.startswith(old):
                message = new + message[len(old):]
                break
        else:  # the one message that names two arguments
            message = message.replace("give samples or dt", f"give {keys['samples']} or {keys['dt']}", 1)
        raise ValueError(message) from None


def load_scenario(path: str | os.PathLike[str]) -> Scenario | ControlScenario:
    """Read and validate a scenario file (TOML); the file's format is in the README.

    Parameters
    ----------
    path : str or os.PathLike
        The scenario file. Body and mesh files it names are read relative to its folder.

    Returns
    -------
    Scenario or ControlScenario
        The body, initial state, times, method and torque; :func:`tumble.run_scenario` runs it. A
        file with a ``[control]`` table is a closed-loop run (:mod:`tumble.io.controlfile`).

    Raises
    ------
    ValueError
        Any problem with the file or its values, in one line starting with the file's name.

    Examples
    --------
    >>> import pathlib, tempfile, tumble
    >>> text = '''
    ... body = "t-handle"
    ... [initial]
    ... omega = [0.0, 0.0, 2.0]
    ... [simulation]
    ... t_end = 1.0
    ... samples = 11
    ... '''
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "spin.toml")
    ...     _ = path.write_text(text)
    ...     scenario = tumble.load_scenario(path)
    >>> scenario.name, scenario.body.name, scenario.omega, scenario.sample_count
    ('spin', 'T-handle', [0.0, 0.0, 2.0], 11)
    >>> tumble.run_scenario(scenario).omega[-1].round(6).tolist()   # a steady spin about the major axis
    [0.0, 0.0, 2.0]
    """
    path = Path(path)
    data = read_toml(path)
    try:
        if "sweep" in data:  # a sweep file given to simulate, view or plot
            raise ValueError("a sweep file ([sweep]): run it with 'tumble sweep FILE --out DIR'")
        if is_control_file(data):  # a closed-loop run: tumble.io.controlfile
            if "body" not in data:
                raise ValueError("missing key 'body' (a preset name, a body file or a [body] table)")
            scenario = load_control_scenario(path, data, _body(data["body"], path.parent))
        else:
            scenario = scenario_from_table(data, base_dir=path.parent, name=path.stem)
    except ValueError as exc:
        message = str(exc)
        raise ValueError(message if message.startswith(f"{path}: ") else f"{path}: {message}") from None
    files = [path]
    if isinstance(data.get("body"), str) and data["body"] not in PRESETS:
        files.append(path.parent / data["body"])
    return dataclasses.replace(scenario, sources=tuple((str(f), file_sha256(f)) for f in files))


def resolve_run(source: str | os.PathLike[str], *, omega: ArrayLike | None = None, frame: str | None = None,
                t_end: float | None = None, samples: int | None = None, dt: float | None = None,
                method: str | None = None) -> Scenario:
    """The run the command line asks for: a scenario file, or a body file or preset name plus
    ``omega`` (rad/s); any value given here overrides the file's.

    ``t_end``, ``samples`` and ``dt`` given here replace the file's sampling (its ``times``
    too). Errors are one line naming the file, or the option (``--omega``, ``--t-end``, ...).

    Examples
    --------
    >>> from tumble.io.scenario import resolve_run
    >>> run = resolve_run("t-handle", omega=[0.1, 5.0, 0.1], t_end=10.0, samples=101)
    >>> run.name, run.t_end, run.samples
    ('t-handle', 10.0, 101)
    >>> resolve_run("t-handle")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: 't-handle' is a preset body; a run also needs an initial spin: add --omega W1 W2 W3 (rad/s, principal frame) ...
    """
    given = {k: v for k, v in dict(omega=omega, frame=frame, t_end=t_end, samples=samples, dt=dt,
                                   method=method).items() if v is not None}
    if isinstance(source, str) and source in PRESETS and not Path(source).exists():
        body, name, what, sources = preset_body(source), source, f"{source!r} is a preset body", ()
    else:
        path = Path(source)
        if not path.exists() and not path.is_symlink() and path.suffix == "":
            raise NoSuchFileError(f"{source!r} is not a scenario file, a body file or a preset (presets: "
                                  f"{', '.join(named_presets())}); {source}: no such file")
        if is_mesh_file(path):  # read as TOML it was "not a text file (not valid UTF-8)" (a walkthrough)
            raise ValueError(f"{source}: a mesh file, not a scenario or body file: name it in a body file's part "
                             f'([[body.parts]] kind = "mesh", mesh = "{path.name}", mass or density), or give it to '
                             f"tumble inertia with --mass or --density")
        data = read_toml(path)
        if set(data) != {"body"} or not isinstance(data["body"], dict):
            scenario = load_scenario(path)
            if isinstance(scenario, ControlScenario):
                return scenario.override(given) if given else scenario
            return _override(scenario, given, where=f"{path}: ") if given else scenario
        body, name, what = load_body(path), path.stem, f"{path} is a body file"
        sources = ((str(path), file_sha256(path)),)
    if omega is None:
        raise ValueError(
            f"{what}; a run also needs an initial spin: add --omega W1 W2 W3 (rad/s, principal frame) "
            f"and optionally --t-end, --samples or --dt, --method; or write a scenario file, which adds "
            f"[initial] omega and [simulation] t_end, samples, method (see 'tumble examples')"
        )
    return _override(Scenario(body=body, omega=omega, name=name, sources=sources), given, where="")


def _override(scenario: Scenario, given: dict, where: str) -> Scenario:
    """``scenario`` with the command line's values; sampling given there replaces the file's."""
    changes = dict(given)
    if {"t_end", "samples", "dt"} & set(given):
        changes.setdefault("t_end", scenario.t_end if scenario.t_end is not None else DEFAULT_T_END)
        changes["times"] = None
        if "dt" in given:
            changes.setdefault("samples", None)
        if "samples" in given:
            changes.setdefault("dt", None)
    updated = dataclasses.replace(scenario, **changes)
    try:
        _validate(updated, options={"omega0" if k == "omega" else k for k in given})
    except ValueError as exc:
        raise ValueError(f"{where}{exc}") from None
    return updated
