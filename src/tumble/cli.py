"""The ``tumble`` command line.

Every error is one line on stderr: exit status 2 for bad input (files, values, options), 1 for a
failure of the computation, never a traceback unless ``--debug`` is given. Heavy modules are
imported inside the commands so that ``tumble --help`` answers at once.
"""

from __future__ import annotations

import argparse
import json
import sys
import warnings

from ._version import __version__

EXIT_OK, EXIT_FAILURE, EXIT_USAGE = 0, 1, 2


def _working(message: str):
    """A spinner on stderr while a long computation runs on a terminal; silent when piped."""
    import contextlib

    if not sys.stderr.isatty():
        return contextlib.nullcontext()
    from rich.console import Console

    return Console(stderr=True).status(message)


class _Parser(argparse.ArgumentParser):
    """argparse with tumble's one-line error format and exit status 2."""

    def error(self, message: str):  # noqa: D102 - argparse API
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")


def _cmd_inertia(args) -> int:
    from .io import load_body, mass_properties_dict, mass_properties_table

    body = load_body(args.body)
    if args.json:
        print(json.dumps(mass_properties_dict(body), indent=2))
    else:
        print(mass_properties_table(body))
    return EXIT_OK


def _cmd_demo(args) -> int:
    from .demo import run_demo

    run_demo(args.out, animate=not args.no_animation)
    return EXIT_OK


def _cmd_simulate(args) -> int:
    from .io.scenario import load_scenario

    scenario = load_scenario(args.scenario)  # every check before anything is computed or written
    with _working(f"integrating {scenario.name} ({scenario.method or 'default method'})"):
        traj = scenario.run()

    from pathlib import Path

    from .analysis import trajectory_summary
    from .io.export import write_csv, write_json, write_npz
    from .viz import figure_omega

    out = Path(args.out)
    summary = trajectory_summary(traj)
    summary["scenario"] = str(args.scenario)
    write_csv(traj, out / "trajectory.csv")
    write_npz(traj, out / "trajectory.npz")
    figure_omega(traj, out / "omega.png", f"{scenario.name}: {traj.body_name}, {traj.method}")
    write_json(summary, out / "summary.json")
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(_simulate_line(summary, out))
    return EXIT_OK


#: The figures of `tumble plot`: name -> function in tumble.viz.
PLOTS = ("omega", "polhode", "herpolhode", "drift")


def _cmd_plot(args) -> int:
    from .io.scenario import load_scenario

    import dataclasses

    scenario = load_scenario(args.scenario)
    # the phase portraits need the path drawn finely: at least 5000 samples
    with _working(f"integrating {scenario.name}"):
        traj = dataclasses.replace(scenario, samples=max(scenario.samples, 5000)).run()

    from pathlib import Path

    from . import viz

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    title = f"{scenario.name}: {traj.body_name}, {traj.method}"
    makers = {"omega": viz.figure_omega, "polhode": viz.figure_polhode,
              "herpolhode": viz.figure_herpolhode, "drift": viz.figure_drift}
    written = []
    for name in PLOTS:
        for fmt in args.format:
            path = out / f"{name}.{fmt}"
            makers[name](traj, path, title if name == "omega" else None)  # written atomically
            written.append(path.name)
    print(f"wrote {', '.join(written)} to {out}/")
    return EXIT_OK


def _cmd_view(args) -> int:
    from pathlib import Path

    from .io.scenario import load_scenario

    out = Path(args.out)
    if out.suffix.lower() != ".html":
        raise ValueError(f"--out {out}: the page is written as one .html file")
    from .viz.page import write_page
    from .viz.scene import frame_indices

    scenario = load_scenario(args.scenario)
    frame_indices(scenario.samples, args.frames)  # refuse a bad --frames before integrating
    with _working(f"integrating {scenario.name}"):
        traj = scenario.run()

    write_page(scenario.body, traj, out, frames=args.frames, title=f"{scenario.name}: {traj.body_name}, {traj.method}")
    print(f"wrote {out} (self-contained: open it in any browser, no network needed)")
    return EXIT_OK


def _simulate_line(summary: dict, out) -> str:
    """One line for people: what the spin did and how well the invariants held."""
    s, d = summary["stability"], summary["drift"]
    head = f"{summary['body']} ({summary['method']}, {summary['t_end']:g} s)"
    spin = "started at rest" if s["axis"] is None else (
        f"spin mostly about axis {s['axis']} ({s['role']}), predicted {s['predicted']}, {s['flips']} flips")
    if summary["torque_free"]:
        drift = ", ".join(f"{k} {'-' if v is None else format(v, '.1e')}" for k, v in d.items())
        tail = f"relative drift: {drift}"
    else:
        tail = "torque acted, so energy and L change"
    return f"{head}: {spin}; {tail}; wrote {out}/"


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (also used to document the CLI)."""
    parser = _Parser(
        prog="tumble",
        description="Rigid-body rotation: mass properties, Euler's equations, the tennis-racket effect.",
        epilog="Example: tumble inertia t-handle --json",
    )
    parser.add_argument("--version", action="version", version=f"tumble {__version__}")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    p = sub.add_parser(
        "inertia",
        help="mass properties of a body file or preset",
        description="Mass, centre of mass, inertia tensor about the COM, principal moments and axes.",
        epilog="Examples: tumble inertia t-handle | tumble inertia iss-t-handle --json | "
        "tumble inertia examples/bodies/t_handle.toml",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("body", metavar="BODY", help="a body file (TOML) or a preset: t-handle, iss-t-handle")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a table")
    p.set_defaults(func=_cmd_inertia)

    def scenario_command(name, func, summary, description, example, out_metavar, out_help):
        cmd = sub.add_parser(name, help=summary, description=description, epilog=f"Example: {example}")
        cmd.add_argument("scenario", metavar="SCENARIO", help="a scenario file (TOML)")
        cmd.add_argument("--out", required=True, metavar=out_metavar, help=out_help)
        cmd.set_defaults(func=func)
        return cmd

    p = scenario_command(
        "simulate", _cmd_simulate, "integrate a scenario file and write trajectory, summary and plot",
        "Integrates the scenario and writes DIR/trajectory.csv, DIR/trajectory.npz, DIR/summary.json and "
        "DIR/omega.png. Nothing is written if the scenario is invalid.",
        "tumble simulate examples/seed_flip.toml --out runs/flip --json", "DIR", "output folder",
    )
    p.add_argument("--json", action="store_true", help="print the summary as JSON")

    p = scenario_command(
        "plot", _cmd_plot, "figures of a scenario: omega(t), polhode, herpolhode, drift",
        "Integrates the scenario and writes DIR/omega, DIR/polhode (L on the momentum sphere with the family "
        "of polhodes and the separatrices), DIR/herpolhode (omega in the invariable plane) and DIR/drift "
        "(energy, |L|, L_world errors), each as PNG and SVG.",
        "tumble plot examples/seed_flip.toml --out figures", "DIR", "output folder",
    )
    p.add_argument("--format", nargs="+", default=["png", "svg"], choices=["png", "svg", "pdf"],
                   help="file formats (default: png svg)")

    p = scenario_command(
        "view", _cmd_view, "one self-contained interactive HTML page of a scenario",
        "Writes ONE HTML file that works offline: the body tumbling in the ground frame with its omega and "
        "L arrows, the body-frame view, omega(t); play/pause, time slider, speed buttons.",
        "tumble view examples/seed_flip.toml --out flip.html", "FILE.html", "the page to write",
    )
    p.add_argument("--frames", type=int, default=150, help="animation frames, 2 to 2000 (default 150)")

    p = sub.add_parser(
        "demo",
        help="the T-handle study on built-in defaults",
        description="Runs the T-handle study (seed T-handle and space-station handle, spin about each "
        "axis) and writes figures, animations, trajectories and a summary table to a folder.",
        epilog="Example: tumble demo --out tumble-demo",
    )
    p.add_argument("--out", default="tumble-demo", metavar="DIR", help="output folder (default: tumble-demo)")
    p.add_argument("--no-animation", action="store_true", help="skip the GIF animations (faster)")
    p.set_defaults(func=_cmd_demo)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``tumble`` console command; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return EXIT_USAGE
    try:
        with warnings.catch_warnings():
            # numeric trouble (overflow, invalid values) becomes a one-line failure, not noise
            warnings.simplefilter("error", RuntimeWarning)
            return args.func(args)
    except KeyboardInterrupt:
        print("tumble: interrupted", file=sys.stderr)
        return 130
    except (ValueError, OSError) as exc:
        if args.debug:
            raise
        print(f"tumble: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_USAGE
    except Exception as exc:  # a failure of the computation, not of the input
        if args.debug:
            raise
        print(f"tumble: computation failed: {type(exc).__name__}: {_one_line(exc)}", file=sys.stderr)
        return EXIT_FAILURE


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
