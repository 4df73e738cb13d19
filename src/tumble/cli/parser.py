"""The argument parser of ``tumble`` (also used to document the command line)."""

from __future__ import annotations

import argparse
import re
import sys

from .._version import __version__
from ..dynamics.methods.names import method_list
from . import commands as c
from ._common import EXIT_USAGE, number


class _Parser(argparse.ArgumentParser):
    """argparse with tumble's one-line error format and exit status 2, and an option or a command it
    does not know answered by the nearest (``--t_end``: did you mean ``--t-end``?; ``simulat``:
    did you mean ``simulate``?). Options are taken whole, never abbreviated (argparse's
    ``allow_abbrev``): ``--mas`` read silently as ``--mass`` would stop working, or start meaning
    another option, the day an option beginning ``--mas`` is added; it is answered by the nearest."""

    def __init__(self, *args, **kwargs) -> None:  # noqa: ANN002, ANN003 - argparse's signature
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)
        # a negative number with an exponent (--omega -1e-2 10 0.1) is a number, not an option: argparse's own
        # pattern knows -1 and -0.01 only, and "-1e-2" ended the list ("expected 3 arguments")
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

    #: Set while :meth:`parse_args` runs: a missing required option is then raised as
    #: :class:`_MissingRequired`, so that a misspelt option (``--otu`` for ``--out``) is named first.
    _deferring = 0

    def error(self, message: str):
        if _Parser._deferring and message.startswith("the following arguments are required"):
            raise _MissingRequired(self, message)
        for action in self._actions:  # a misspelt command (argparse names no alternative; Python 3.11)
            if isinstance(action, argparse._SubParsersAction) and message.startswith("argument COMMAND: invalid choice:"):
                from ..validation import nearest  # here: the parser's module imports no numpy

                word = message.split("'")[1] if message.count("'") >= 2 else ""
                near = nearest(word.lower(), action.choices, cutoff=0.6)
                message += f" (did you mean {near}?)" if near is not None else ""
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")

    def parse_args(self, args=None, namespace=None):  # noqa: ANN001, ANN201 - argparse's signature
        missing = None
        _Parser._deferring += 1
        try:
            parsed, extras = self.parse_known_args(args, namespace)
        except _MissingRequired as raised:
            missing = raised
        finally:
            _Parser._deferring -= 1
        if missing is not None:  # "--out is required" hid "--otu": the option misspelt is said first
            words = list(sys.argv[1:] if args is None else args)
            words = words[:words.index("--")] if "--" in words else words
            unknown = [w for w in words if w.startswith("--") and not _known(w, missing.parser)]
            missing.parser.error(unrecognized(unknown, missing.parser) + f"; and {missing.message}" if unknown
                                 else missing.message)
        if extras:
            command = self._command(getattr(parsed, "command", None))
            (command or self).error(unrecognized(extras, command or self))
        return parsed

    def _command(self, name: str | None) -> argparse.ArgumentParser | None:
        """The parser of the subcommand ``name``, or None."""
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction) and name in action.choices:
                return action.choices[name]
        return None


class _MissingRequired(Exception):
    """A required option left out, raised by :meth:`_Parser.error` while :meth:`_Parser.parse_args` runs."""

    def __init__(self, parser: argparse.ArgumentParser, message: str) -> None:
        super().__init__(message)
        self.parser, self.message = parser, message


def _known(word: str, parser: argparse.ArgumentParser) -> bool:
    """Whether the long option ``word`` (``--name`` or ``--name=value``) is one ``parser`` takes (whole: no
    abbreviation)."""
    name = word.split("=", 1)[0]
    return any(o == name for action in parser._actions for o in action.option_strings)


def unrecognized(extras: list[str], parser: argparse.ArgumentParser) -> str:
    """The error for arguments ``parser`` does not take, with the nearest of its options for each
    one that looks like an option (argparse's own message names no alternative; Python 3.11).

    Examples
    --------
    >>> from tumble.cli.parser import build_parser, unrecognized
    >>> simulate = build_parser()._command("simulate")
    >>> unrecognized(["--t_end", "30"], simulate)
    'unrecognized arguments: --t_end 30 (--t_end: did you mean --t-end?)'
    >>> unrecognized(["extra"], simulate)
    'unrecognized arguments: extra'
    """
    from ..validation import nearest  # here: the parser's module imports no numpy (tumble --help answers at once)

    options = [o for action in parser._actions for o in action.option_strings if o.startswith("--")]
    hints = []
    for word in extras:
        if word.startswith("--"):
            name = word.split("=", 1)[0]
            near = nearest(name.replace("_", "-").lower(), options, cutoff=0.8)
            hints += [f"{name}: did you mean {near}?"] if near is not None and near != name else []
    return f"unrecognized arguments: {' '.join(extras)}" + (f" ({'; '.join(hints)})" if hints else "")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (also used to document the CLI).

    Examples
    --------
    >>> from tumble.cli.parser import build_parser
    >>> args = build_parser().parse_args(["simulate", "examples/seed_flip.toml", "--out", "runs/flip"])
    >>> args.command, args.out
    ('simulate', 'runs/flip')
    """
    parser = _Parser(
        prog="tumble",
        description="Rigid-body rotation: mass properties, Euler's equations, the tennis-racket effect.",
        epilog="Example: tumble inertia t-handle --json",
    )
    parser.add_argument("--version", action="version", version=f"tumble {__version__}")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error")
    # --debug is accepted after the subcommand too; SUPPRESS keeps the top-level value otherwise
    debug = argparse.ArgumentParser(add_help=False)
    debug.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="show the traceback of an error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    p = sub.add_parser(
        "inertia",
        help="mass properties of a body file, a preset or a mesh file (STL, OBJ, PLY)",
        description="Mass, centre of mass, inertia tensor about the COM, principal moments and axes.\n\n"
        "BODY is a body file (TOML), a preset, or a mesh file (.stl, .obj, .ply): a closed triangle mesh read\n"
        "as one uniform solid, named after the file, which needs --density or --mass and may take --units or\n"
        "--scale (its coordinates are metres otherwise).",
        epilog="Examples: tumble inertia t-handle | tumble inertia iss-t-handle --json | "
        "tumble inertia examples/bodies/t_handle.toml | "
        "tumble inertia bracket.stl --density 2700 --units mm",
        formatter_class=argparse.RawDescriptionHelpFormatter, parents=[debug],
    )
    p.add_argument("body", metavar="BODY",
                   help="a body file (TOML), a preset (t-handle, iss-t-handle) or a mesh file (.stl, .obj, .ply)")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a table")
    solid = p.add_argument_group("a mesh file (not a body file or preset)")
    solid.add_argument("--density", metavar="RHO",
                       help="uniform density, kg/m^3 (give --density or --mass)")
    solid.add_argument("--mass", metavar="M", help="total mass, kg (give --density or --mass)")
    solid.add_argument("--units", choices=["m", "cm", "mm", "in"],
                       help="the length unit of the file's coordinates (default m)")
    solid.add_argument("--scale", metavar="FACTOR",
                       help="factor from the file's coordinates to metres, instead of --units (e.g. 0.001)")
    p.set_defaults(func=c._cmd_inertia, inputs=("body",))

    def scenario_command(name, func, summary, description, example, out_metavar, out_help):
        cmd = sub.add_parser(name, help=summary, description=description, epilog=f"Examples: {example}",
                             parents=[debug])
        cmd.add_argument("source", metavar="INPUT",
                         help="a scenario file (TOML); or a body file or preset (t-handle, iss-t-handle) with --omega")
        cmd.add_argument("--out", required=True, metavar=out_metavar, help=out_help)
        run = cmd.add_argument_group("the run, without a scenario file (or overriding the file's values)")
        run.add_argument("--omega", nargs=3, type=number, metavar=("W1", "W2", "W3"),
                         help="initial angular velocity, rad/s (principal frame, axes ordered I1 <= I2 <= I3)")
        run.add_argument("--frame", metavar="FRAME", help="frame of --omega: principal (default) or design")
        run.add_argument("--t-end", type=number, metavar="S", help="duration, s (default 20)")
        run.add_argument("--samples", type=int, metavar="N", help="number of samples (default 500)")
        run.add_argument("--dt", type=number, metavar="S", help="sample every S seconds instead of --samples")
        run.add_argument("--method", metavar="NAME", help=method_list())  # every method of the registry
        cmd.set_defaults(func=func, inputs=("source",))
        return cmd

    p = scenario_command(
        "simulate", c._cmd_simulate, "integrate a scenario file and write trajectory, summary and plot",
        "Integrates the scenario and writes DIR/trajectory.csv, DIR/trajectory.npz, DIR/summary.json and "
        "DIR/omega.png. Nothing is written if the scenario is invalid.",
        "tumble simulate examples/seed_flip.toml --out runs/flip --json | "
        "tumble simulate t-handle --omega 0.1 10 0.1 --t-end 30 --out runs/flip2", "DIR", "output folder",
    )
    p.add_argument("--json", action="store_true", help="print the summary as JSON")

    p = scenario_command(
        "plot", c._cmd_plot, "figures of a scenario: omega(t), polhode, herpolhode, drift",
        "Integrates the scenario and writes DIR/omega, DIR/polhode (L on the momentum sphere with the family "
        "of polhodes and the separatrices), DIR/herpolhode (omega in the invariable plane) and DIR/drift "
        "(energy, |L|, L_world errors), each as PNG and SVG; with a damper or rotors DIR/energy (and its "
        "budget) and DIR/nutation, under the gravity gradient DIR/orbit_angles (roll, pitch, yaw).",
        "tumble plot examples/seed_flip.toml --out figures | "
        "tumble plot examples/bodies/wing_nut.toml --omega 0.1 5 0.1 --out figures", "DIR", "output folder",
    )
    p.add_argument("--format", nargs="+", default=["png", "svg"], choices=["png", "svg", "pdf"],
                   help="file formats (default: png svg)")

    p = scenario_command(
        "view", c._cmd_view, "one self-contained interactive HTML page of a scenario, a fit or a tensor",
        "Writes ONE HTML file that works offline: the body tumbling in the ground frame with its omega and "
        "L arrows, the body-frame view, omega(t); play/pause, time slider, speed buttons. A control scenario "
        "([control]) adds its reaction wheels turning on the body, the commanded torque (and dipole) arrows, a "
        "readout and the attitude error or |omega| over time (only --t-end overrides it; no live mode). "
        "INPUT a folder holding fit.json (tumble fit's output): the fitted body (a box of the fitted ratios) "
        "replays the flight chosen in a selector, its model's rates next to the measured ones, and its polhode "
        "on the momentum sphere (the recordings are read again, as given to tumble fit). INPUT a folder holding "
        "tensor.json (tumble tensor's output): each throw's gyroscope samples against the fitted model and its rotor "
        "speed, the principal moments throw by throw with the pooled value, and the object's equivalent uniform box "
        "in the sensor frame (no animation).",
        "tumble view examples/seed_flip.toml --out flip.html | "
        "tumble view examples/control/point.toml --out point.html | "
        "tumble view iss-t-handle --omega 0.1 0.1 8 --out iss.html | "
        "tumble view fitted --out tosses.html | tumble view bracket --out bracket.html", "FILE.html", "the page to write",
    )
    p.add_argument("--frames", type=int, help="animation frames, 2 to 2000 (default 150; not for a tensor's folder)")

    p = sub.add_parser(
        "examples",
        help="list the example files (scenarios, bodies, meshes, recordings, throws, notebooks), or copy them",
        description="Lists every file of the examples that ship with tumble: scenario, control, body and sweep "
        "files, meshes, gyroscope recordings, a throwing device and its throws, and notebooks; --copy DIR copies "
        "them all, ready to run "
        "(scenarios name their bodies and meshes by relative paths).",
        epilog="Examples: tumble examples | tumble examples --copy my-examples", parents=[debug],
    )
    p.add_argument("--copy", metavar="DIR", nargs="?", const="examples",
                   help="copy every example into DIR (never overwrites a file); --copy alone: into examples/, the "
                        "folder the guides' commands name")
    p.set_defaults(func=c._cmd_examples)

    p = sub.add_parser(
        "sweep",
        help="a Monte Carlo sweep or a grid of cases from a sweep file",
        description="Runs every case of a sweep file (dispersed bodies and initial rates) and writes DIR/cases.csv "
        "(a row per case; DIR/cases.parquet with pyarrow), DIR/summary.json (statistics, the order-statistics "
        "confidence statement, provenance) and DIR/sweep.png. Interrupted, a re-run resumes from the finished "
        "chunks kept in DIR.resume/ (checked: another run's or a damaged chunk is computed again; a second run "
        "into the same DIR is refused while the first runs).",
        epilog="Examples: tumble sweep examples/sweeps/t_handle_dimensions.toml --out runs/sweep | "
        "tumble sweep SWEEP.toml --out DIR --workers 2", parents=[debug],
    )
    p.add_argument("sweep", metavar="SWEEP", help="a sweep file (TOML)")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder")
    p.add_argument("--workers", type=int, metavar="N", help="run on a local Dask cluster of N workers (tumble[cluster])")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on an existing Dask cluster: its scheduler's address, e.g. tcp://10.0.0.5:8786 "
                        "(tumble[cluster]); refused in seconds when no scheduler answers there")
    p.set_defaults(func=c._cmd_sweep, inputs=("sweep",))

    p = sub.add_parser(
        "map",
        help="stability map: flip interval over the triangle of inertia ratios",
        description="Draws the exact flip interval and the circulation axis of a spin about the intermediate axis "
        "with a small perturbation, over the triangle of inertia ratios (I1/I3, I2/I3).",
        epilog="Example: tumble map --out map.png --spin 10 --perturbation 0.01 0.01", parents=[debug],
    )
    p.add_argument("--out", required=True, metavar="FILE", help="the figure (.png or .svg)")
    p.add_argument("--spin", type=number, default=10.0, metavar="W", help="spin about the intermediate axis, rad/s (default 10)")
    p.add_argument("--perturbation", type=number, nargs=2, default=(0.01, 0.01), metavar=("W1", "W3"),
                   help="rates about the minor and major axes, rad/s (default 0.01 0.01)")
    p.add_argument("--resolution", type=int, default=300, metavar="N", help="grid points per side (default 300)")
    p.set_defaults(func=c._cmd_map)

    p = sub.add_parser(
        "fit",
        help="inertia ratios from a gyroscope recording (phyphox or Sensor Logger export, or t,wx,wy,wz CSV)",
        description="Finds the free flights of a whole recording of tosses (from the gyroscope, and where the "
        "recording has one the accelerometer's free fall; phyphox's pauses honoured), fits each with the exact "
        "torque-free motion (or with per-axis drag), fits them "
        "jointly (shared ratios, sensor rotation, bias and drag; given several recordings, all their flights, "
        "with the sensor rotation and bias each recording's own) and writes DIR/fit.json (pooled values with "
        "standard uncertainties and 95 percent intervals, every flight, provenance), DIR/tosses.csv and DIR/fit.png. "
        "With --start/--end the samples between are fitted as one flight.",
        epilog="Example: tumble fit examples/data/racquet_tosses.csv --out fitted", parents=[debug],
    )
    p.add_argument("data", metavar="RECORDING", nargs="+",
                   help="a CSV or other delimited text (phyphox's gyroscope export, Sensor Logger's Gyroscope.csv; "
                   "a header naming the time and the three rate columns, others ignored; or t, wx, wy, wz in s, "
                   "rad/s), or phyphox's or Sensor Logger's export folder or .zip; several recordings of one body "
                   "are pooled in one joint fit (sensor mount and bias per recording)")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder")
    p.add_argument("--sensor", choices=["fit", "identity"], default="fit",
                   help="fit the sensor's rotation to the principal axes (default) or take it as identity")
    p.add_argument("--no-bias", action="store_true", help="assume an unbiased gyroscope")
    p.add_argument("--drag", choices=["auto", "none", "linear", "quadratic"], default="auto",
                   help="aerodynamic drag about each principal axis: chosen by the BIC (default), or as named")
    p.add_argument("--saturation", metavar="RAD_S",
                   help="the gyroscope's full scale, rad/s (default: found from the data); samples at it are left out")
    p.add_argument("--scale-uncertainty", type=number, metavar="FRACTION",
                   help="the gyroscope's scale-factor standard uncertainty per axis, a fraction propagated into the "
                   "ratios (default 0.005: a datasheet's +-1 %% limits as two standard deviations; 0.01 for a "
                   "gyroscope known to be worse)")
    p.add_argument("--body", metavar="FILE", help="a body file or preset: its ratios compared with the fit")
    p.add_argument("--start", type=number, metavar="S",
                   help="fit one flight: its first time, s (one recording only; without --end, to the recording's end)")
    p.add_argument("--end", type=number, metavar="S",
                   help="fit one flight: its last time, s (without --start, from the recording's start)")
    p.add_argument("--accept-inadequate", action="store_true",
                   help="exit 0 even when the model does not describe the data (by default such a fit is written "
                   "with \"adequate\": false, a warning printed and the exit status 1)")
    p.set_defaults(func=c._cmd_fit, inputs=("data", "--body"))

    p = sub.add_parser(
        "calibrate",
        help="calibrate a throwing device with a flywheel: its rotor's inertia, its tensor and centre of mass",
        description="Estimates the rotor's inertia, the device's own inertia tensor (about its centre of mass, sensor "
        "frame) and its centre of mass, each with its standard uncertainty, from throws of the device alone and "
        "with the proof body of the device file's [proof], and writes them into [device] of CALIBRATED.toml as "
        "rotor_inertia, inertia, center_of_mass and their _std (whole or not at all). A throw is a CSV with t (s), "
        "wx, wy, wz (rad/s), rotor (rad/s), ax, ay, az (m/s^2) in the sensor frame. The example below runs on the "
        "shipped device and throws after tumble examples --copy.",
        epilog="Example: tumble calibrate examples/devices/flywheel_device.toml "
        "--alone examples/throws/a1.csv examples/throws/a2.csv --proof examples/throws/p1.csv examples/throws/p2.csv "
        "--out calibrated.toml", parents=[debug],
    )
    p.add_argument("device", metavar="DEVICE.toml", help="the device file: [device] mass, rotor_axis; [proof] mass, inertia")
    p.add_argument("--alone", nargs="+", required=True, metavar="THROW", help="throws of the device alone (CSV)")
    p.add_argument("--proof", nargs="+", required=True, metavar="THROW",
                   help="throws of the device with the proof body fixed to it (CSV)")
    p.add_argument("--out", required=True, metavar="CALIBRATED.toml", help="the calibrated device file to write")
    p.add_argument("--saturation", metavar="RAD_S",
                   help="the gyroscope's full scale, rad/s (default: the device's gyro_full_scale); samples at it "
                   "are left out")
    p.add_argument("--accept-inadequate", action="store_true",
                   help="exit 0 for a calibration that does not check itself out (written with [calibration] "
                   "adequate = false either way)")
    p.set_defaults(func=c._cmd_calibrate, inputs=("device", "--alone", "--proof"))

    p = sub.add_parser(
        "tensor",
        help="an object's whole inertia tensor (kg m^2), axes and centre of mass from throws with the flywheel device",
        description="Fits each throw of the object with the calibrated device strapped to it (the gyrostat's Euler "
        "equations with the measured rotor speed, an output-error fit) and all of them jointly, and writes "
        "DIR/tensor.json (the object's and the flown body's mass, inertia tensor and its covariance, principal "
        "moments with standard uncertainties, principal axes, centre of mass; every throw; adequate), "
        "DIR/tensor.png (the figure), DIR/throws.npz (each throw's fitted samples, the model's rates and the rotor's "
        "speed, for tumble view DIR), DIR/inertial.urdf and DIR/inertial.xml (the object as a URDF and a MuJoCo MJCF "
        "<inertial> element, sensor frame, its uncertainties in a comment), whole or not at all. The example below "
        "runs on the shipped throws of a 0.482 kg box after tumble examples --copy and tumble calibrate's example.",
        epilog="Example: tumble tensor examples/throws/o1.csv examples/throws/o2.csv "
        "examples/throws/o3.csv --device calibrated.toml --mass 0.482 --out bracket",
        parents=[debug],
    )
    p.add_argument("throws", nargs="+", metavar="THROW", help="throws of the object with the device (CSV)")
    p.add_argument("--device", required=True, metavar="CALIBRATED.toml", help="the calibrated device file (tumble calibrate)")
    p.add_argument("--mass", required=True, metavar="KG", help="the object's mass, kg (without the device)")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder")
    p.add_argument("--saturation", metavar="RAD_S",
                   help="the gyroscope's full scale, rad/s (default: the device's gyro_full_scale); samples at it "
                   "are left out")
    p.add_argument("--accept-inadequate", action="store_true",
                   help="use a device whose calibration did not check out ([calibration] adequate = false; by "
                   "default it is refused, exit status 1, nothing written)")
    p.set_defaults(func=c._cmd_tensor, inputs=("throws", "--device"))

    p = sub.add_parser(
        "compile",
        help="compile tumble's kernels ahead into numba's cache, so that first runs start at once (once per install)",
        description="numba compiles each kernel at its first use and keeps it in its cache, so the first "
        "run with a torque, a damper, a batch or a controller pays seconds of compiling (the first closed loop "
        "~20 s). This compiles them ahead in as many processes at a time as there are "
        "cores (all five: ~30 s on 2 cores), through small real runs; later runs load them. Run it once after "
        "installing or upgrading tumble; a change to tumble's sources compiles again at first use.",
        epilog="Examples: tumble compile --list | tumble compile damper",
        parents=[debug],
    )
    p.add_argument("groups", nargs="*", metavar="GROUP",
                   help="control, simulate, orbit, batch or damper (default: all; tumble compile --list describes them)")
    p.add_argument("--jobs", type=int, metavar="N", help="processes at a time (default: the cores this process may use)")
    p.add_argument("--list", action="store_true", help="list the groups and what each compiles, and compile nothing")
    p.set_defaults(func=c._cmd_compile)

    p = sub.add_parser(
        "demo",
        help="the T-handle study on built-in defaults",
        description="Runs the T-handle study (seed T-handle and space-station handle, spin about each "
        "axis) and writes figures, animations, trajectories and a summary table to a folder.",
        epilog="Example: tumble demo --out tumble-demo", parents=[debug],
    )
    p.add_argument("--out", default="tumble-demo", metavar="DIR", help="output folder (default: tumble-demo)")
    p.add_argument("--no-animation", action="store_true", help="skip the animations (faster)")
    p.add_argument("--animation-format", choices=["auto", "mp4", "gif"], default="auto",
                   help="auto (default): MP4 where an ffmpeg is found (tumble[video]), GIF otherwise")
    p.set_defaults(func=c._cmd_demo)
    return parser
