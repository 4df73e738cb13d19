"""The ``tumble`` command line.

Every error is one line on stderr: exit status 2 for bad input (files, values, options), 1 for a
failure of the computation, never a traceback unless ``--debug`` is given. Heavy modules are
imported inside the commands so that ``tumble --help`` answers at once.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
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

    run_demo(args.out, animate=not args.no_animation, animation_format=args.animation_format, argv=args.argv)
    return EXIT_OK


def _cmd_examples(args) -> int:
    from .io.examples import copy_examples, list_examples

    if args.copy:
        written = copy_examples(args.copy)
        print(f"copied {len(written)} files to {args.copy}/; try: tumble simulate {args.copy}/seed_flip.toml --out run")
        return EXIT_OK
    examples = list_examples()
    width = max(len(e.path) for e in examples)
    for e in examples:
        print(f"{e.path:<{width}}  {e.kind:<8}  {e.description}")
    print("copy them with: tumble examples --copy DIR")
    return EXIT_OK


def _cmd_sweep(args) -> int:
    from .io.sweepfile import run_sweep_command
    from .viz.maps import figure_sweep

    if args.workers is not None and args.scheduler is not None:
        raise ValueError("give --workers (a local cluster) or --scheduler (an existing one), not both")
    if args.workers is not None and not 1 <= args.workers <= 256:
        raise ValueError(f"--workers = {args.workers} must be from 1 to 256")
    with _working("sweeping"):
        return run_sweep_command(args.sweep, args.out, workers=args.workers, scheduler=args.scheduler,
                                 argv=args.argv, figure=figure_sweep)


def _cmd_map(args) -> int:
    from .io.output import check_output_file
    from .validation import check_positive

    suffix = os.path.splitext(str(args.out))[1].lower()
    out = check_output_file(args.out, suffix if suffix in (".png", ".svg") else ".png")
    spin = check_positive("--spin", args.spin, "rad/s")
    perturbation = tuple(check_positive(f"--perturbation[{i}]", p, "rad/s") for i, p in enumerate(args.perturbation))
    if not 20 <= args.resolution <= 2000:
        raise ValueError(f"--resolution = {args.resolution} must be from 20 to 2000")
    from .viz import figure_stability_map, save_figure

    with _working("mapping"):
        save_figure(figure_stability_map(spin, perturbation, resolution=args.resolution), out)
    print(f"wrote {out}: flip interval and circulation axis over (I1/I3, I2/I3), spin {spin:g} rad/s "
          f"about the intermediate axis, perturbation {perturbation[0]:g}, {perturbation[1]:g} rad/s")
    return EXIT_OK


class _Bar:
    """A rich progress bar of the flights examined, on a terminal only (silent when piped)."""

    def __init__(self):
        self.bar = self.task = None
        if sys.stderr.isatty():
            from rich.console import Console
            from rich.progress import Progress

            self.bar = Progress(console=Console(stderr=True), transient=True)

    def __call__(self, done: int, total: int) -> None:
        if self.bar is None:
            return
        if self.task is None:
            self.bar.start()
            self.task = self.bar.add_task("fitting flights", total=total)
        self.bar.update(self.task, completed=done)

    def close(self) -> None:
        if self.bar is not None and self.task is not None:
            self.bar.stop()


def _cmd_fit(args) -> int:
    from .io.fitcommand import run_fit_command
    from .viz import figure_fit, figure_recording

    if args.saturation is not None and not (args.saturation > 0 and args.saturation < float("inf")):
        raise ValueError(f"--saturation = {args.saturation} must be a positive number of rad/s")
    bar = _Bar()
    try:
        return run_fit_command(args.data, args.out, argv=args.argv, figure=figure_fit, recording_figure=figure_recording,
                               start=args.start, end=args.end, body=args.body, progress=bar,
                               sensor_rotation=args.sensor, bias=not args.no_bias, drag=args.drag,
                               saturation=args.saturation, accept_inadequate=args.accept_inadequate)
    finally:
        bar.close()


def _resolve(args):
    """The run a scenario command asks for (scenario file, or body + --omega; options override)."""
    from .io.scenario import resolve_run

    return resolve_run(args.source, omega=args.omega, frame=args.frame, t_end=args.t_end,
                       samples=args.samples, dt=args.dt, method=args.method)


#: The files `tumble simulate` writes into its folder.
SIMULATE_WRITES = ("trajectory.csv", "trajectory.npz", "summary.json", "omega.png")
#: The figures `tumble simulate` adds for a control scenario (`tumble.viz.control.CONTROL_FIGURES`).
CONTROL_WRITES = ("attitude_error.png", "rates.png", "wheels.png", "dipole.png", "momentum.png")


def _cmd_simulate(args) -> int:
    from .io.output import check_output_dir

    scenario = _resolve(args)  # every check before anything is computed or written
    out = check_output_dir(args.out)
    if not hasattr(scenario, "method"):  # a closed-loop (control) scenario
        return _simulate_control(args, scenario, out)
    with _working(f"integrating {scenario.name} ({scenario.method or 'default method'})"):
        traj = scenario.run()

    from .analysis import trajectory_summary
    from .io.export import write_csv, write_json, write_npz
    from .io.output import output_dir
    from .io.provenance import provenance
    from .viz import figure_omega, save_figure

    summary = trajectory_summary(traj)
    if hasattr(scenario.torque, "jacobi_integral"):  # the gravity gradient: its own error measure
        from .analysis.summary import gravity_gradient_summary

        summary["gravity_gradient"] = gravity_gradient_summary(traj, scenario.torque)
    summary["scenario"] = str(args.source)
    summary["provenance"] = provenance(args.argv, scenario.sources)
    with output_dir(out, SIMULATE_WRITES) as stage:
        write_csv(traj, stage / "trajectory.csv")
        write_npz(traj, stage / "trajectory.npz", summary["provenance"])
        save_figure(figure_omega(traj, title=_run_title(scenario, traj)), stage / "omega.png")
        write_json(summary, stage / "summary.json")
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(_simulate_line(summary, out))
    return EXIT_OK


def _refuse_control(scenario, command: str) -> None:
    if not hasattr(scenario, "method"):
        raise ValueError(f"{scenario.name} is a control scenario ([control]); 'tumble {command}' does not take it yet: "
                         "use 'tumble simulate FILE --out DIR'")


def _simulate_control(args, scenario, out) -> int:
    """`tumble simulate` of a control scenario: the closed loop, its summary and trajectory."""
    from .io.controlfile import control_summary, write_control_run
    from .io.export import write_json
    from .io.output import output_dir
    from .io.provenance import provenance
    from .viz import control_figures, figure_omega, save_figure

    controller = scenario.controller()
    with _working(f"running {scenario.name} in closed loop ({scenario.kind})"):
        run = scenario.run(controller)
    summary = control_summary(scenario, run, controller)
    summary["scenario"] = str(args.source)
    summary["provenance"] = provenance(args.argv, scenario.sources)
    figures = control_figures(run, target=scenario.target, switch_time=summary.get("switch_time"),
                              title=f"{scenario.name} ({scenario.kind})")
    with output_dir(out, (*SIMULATE_WRITES, *CONTROL_WRITES)) as stage:
        write_control_run(run, stage)
        save_figure(figure_omega(scenario.trajectory(run), title=scenario.name), stage / "omega.png")
        for name, fig in figures.items():
            save_figure(fig, stage / name)
        write_json(summary, stage / "summary.json")
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        done = summary["detumble_time"]
        line = f"{summary['body']} ({scenario.kind}, {summary['t_end']:g} s): final rate {summary['final_rate']:.3g} rad/s"
        if summary.get("switch_time") is not None:
            line += f", pointing from t = {summary['switch_time']:g} s"
        if "pointing_error_final" in summary:
            line += f", pointing error {summary['pointing_error_final']:.3g} rad"
        elif done is not None:
            line += f", below {summary['threshold']:.3g} rad/s from t = {done:g} s"
        print(f"{line}; wrote {out}/")
    return EXIT_OK


#: The figures of `tumble plot`, in the order they are drawn; the spacecraft figures
#: (`tumble.viz.spacecraft_figures`) follow where they apply.
PLOTS = ("omega", "polhode", "herpolhode", "drift")
SPACECRAFT_PLOTS = ("energy", "nutation", "orbit_angles")


def _cmd_plot(args) -> int:
    import dataclasses

    from .io.output import check_output_dir

    scenario = _resolve(args)
    _refuse_control(scenario, "plot")
    out = check_output_dir(args.out)
    if scenario.times is None and scenario.dt is None:  # the phase portraits need a fine path
        scenario = dataclasses.replace(scenario, samples=max(scenario.sample_count, 5000))
    with _working(f"integrating {scenario.name}"):
        traj = scenario.run()

    from . import viz
    from .io.output import output_dir

    title = _run_title(scenario, traj)
    makers = {"omega": viz.figure_omega, "polhode": viz.figure_polhode,
              "herpolhode": viz.figure_herpolhode, "drift": viz.figure_drift}
    skipped = viz.phase_portrait_problem(traj)
    names = [n for n in PLOTS if not (skipped and n in viz.PHASE_PORTRAITS)]
    extra = viz.spacecraft_figures(traj, scenario.torque)  # energy, nutation, orbit angles
    written = []
    with output_dir(out, [f"{name}.*" for name in (*PLOTS, *SPACECRAFT_PLOTS)]) as stage:
        figures = [(name, makers[name](traj, title=title if name == "omega" else None)) for name in names]
        for name, fig in figures + [(name, make()) for name, make in extra]:
            for fmt in args.format:
                viz.save_figure(fig, stage / f"{name}.{fmt}")
                written.append(f"{name}.{fmt}")
    print(f"wrote {', '.join(written)} to {out}/")
    if skipped:
        print(f"skipped {', '.join(viz.PHASE_PORTRAITS)}: {skipped}")
    return EXIT_OK


def _cmd_view(args) -> int:
    from .io.output import check_output_file
    from .viz.scene import frame_indices

    out = check_output_file(args.out, ".html")
    scenario = _resolve(args)
    control = not hasattr(scenario, "method")  # a closed-loop (control) scenario
    frame_indices(2 if control else scenario.sample_count, args.frames)  # refuse a bad --frames before integrating
    if control:
        return _view_control(args, scenario, out)
    with _working(f"integrating {scenario.name}"):
        traj = scenario.run()

    from .viz.page import write_page

    write_page(scenario.body, traj, out, frames=args.frames, title=_run_title(scenario, traj))
    print(f"wrote {out} (self-contained: open it in any browser, no network needed)")
    return EXIT_OK


def _view_control(args, scenario, out) -> int:
    """`tumble view` of a control scenario: the page with the wheels, the commanded torque and the error."""
    with _working(f"running {scenario.name} in closed loop ({scenario.kind})"):
        run = scenario.run()

    from .viz.control_page import control_page_data
    from .viz.page import write_page

    traj = scenario.trajectory(run)
    control = control_page_data(run, frames=args.frames, wheel_axes=None if scenario.wheels is None else
                                scenario.wheels.axes, target=scenario.target, threshold=scenario.threshold)
    write_page(scenario.body, traj, out, frames=args.frames, title=_run_title(scenario, traj), live=False,
               control=control)
    print(f"wrote {out} (self-contained: open it in any browser, no network needed; closed loop: "
          "wheels, commanded torque, live mode off)")
    return EXIT_OK


def _run_title(scenario, traj) -> str:
    """``scenario: body, method``, without the body when the scenario is named after it."""
    name = scenario.name if scenario.name != traj.body_name else None
    return ", ".join(filter(None, (f"{name}: {traj.body_name}" if name else traj.body_name, traj.method)))


def _simulate_line(summary: dict, out) -> str:
    """One line for people: what the spin did and how well the invariants held."""
    s, d = summary["stability"], summary["drift"]
    head = f"{summary['body']} ({summary['method']}, {summary['t_end']:g} s)"
    spin = "started at rest" if s["axis"] is None else (
        f"spin mostly about axis {s['axis']} ({s['role']}), predicted {s['predicted']}, {s['flips']} flip{'' if s['flips'] == 1 else 's'}")
    period = s["flip_period_exact"] if s["flip_period_exact"] is not None else s["flip_period"]
    if summary["torque_free"] and s["flips"] and period is not None:
        spin += f" every {period:.4g} s"
    if "gravity_gradient" in summary:
        g = summary["gravity_gradient"]
        tail = (f"{g['orbits']:.3g} orbits, Jacobi integral drift {g['jacobi_drift']:.1e}, largest angle from the "
                f"orbiting frame {max(g['max_angle'].values()):.3g} rad")
    elif summary["torque_free"] and all(v is None for v in d.values()):
        tail = "energy and L start at 0, so there is no relative drift to give"
        work = summary.get("rotors", {}).get("motor_work")
        if work is not None:
            tail += f"; the motors did {work:.3g} J of work"
    elif summary["torque_free"]:
        drift = ", ".join(f"{k} {'n/a' if v is None else format(v, '.1e')}" for k, v in d.items())
        tail = f"relative drift: {drift}"
    else:
        tail = "torque acted, so energy and L change (no budget to check)"
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
    # --debug is accepted after the subcommand too; SUPPRESS keeps the top-level value otherwise
    debug = argparse.ArgumentParser(add_help=False)
    debug.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="show the traceback of an error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    p = sub.add_parser(
        "inertia",
        help="mass properties of a body file or preset",
        description="Mass, centre of mass, inertia tensor about the COM, principal moments and axes.",
        epilog="Examples: tumble inertia t-handle | tumble inertia iss-t-handle --json | "
        "tumble inertia examples/bodies/t_handle.toml",
        formatter_class=argparse.RawDescriptionHelpFormatter, parents=[debug],
    )
    p.add_argument("body", metavar="BODY", help="a body file (TOML) or a preset: t-handle, iss-t-handle")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a table")
    p.set_defaults(func=_cmd_inertia)

    def scenario_command(name, func, summary, description, example, out_metavar, out_help):
        cmd = sub.add_parser(name, help=summary, description=description, epilog=f"Examples: {example}",
                             parents=[debug])
        cmd.add_argument("source", metavar="INPUT",
                         help="a scenario file (TOML); or a body file or preset (t-handle, iss-t-handle) with --omega")
        cmd.add_argument("--out", required=True, metavar=out_metavar, help=out_help)
        run = cmd.add_argument_group("the run, without a scenario file (or overriding the file's values)")
        run.add_argument("--omega", nargs=3, type=float, metavar=("W1", "W2", "W3"),
                         help="initial angular velocity, rad/s (principal frame, axes ordered I1 <= I2 <= I3)")
        run.add_argument("--frame", metavar="FRAME", help="frame of --omega: principal (default) or design")
        run.add_argument("--t-end", type=float, metavar="S", help="duration, s (default 20)")
        run.add_argument("--samples", type=int, metavar="N", help="number of samples (default 500)")
        run.add_argument("--dt", type=float, metavar="S", help="sample every S seconds instead of --samples")
        run.add_argument("--method", metavar="NAME",
                         help="exact (default), dop853, rk45, seed, geometric, geometric2, geometric6")
        cmd.set_defaults(func=func)
        return cmd

    p = scenario_command(
        "simulate", _cmd_simulate, "integrate a scenario file and write trajectory, summary and plot",
        "Integrates the scenario and writes DIR/trajectory.csv, DIR/trajectory.npz, DIR/summary.json and "
        "DIR/omega.png. Nothing is written if the scenario is invalid.",
        "tumble simulate examples/seed_flip.toml --out runs/flip --json | "
        "tumble simulate t-handle --omega 0.1 10 0.1 --t-end 30 --out runs/flip2", "DIR", "output folder",
    )
    p.add_argument("--json", action="store_true", help="print the summary as JSON")

    p = scenario_command(
        "plot", _cmd_plot, "figures of a scenario: omega(t), polhode, herpolhode, drift",
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
        "view", _cmd_view, "one self-contained interactive HTML page of a scenario",
        "Writes ONE HTML file that works offline: the body tumbling in the ground frame with its omega and "
        "L arrows, the body-frame view, omega(t); play/pause, time slider, speed buttons. A control scenario "
        "([control]) adds its reaction wheels turning on the body, the commanded torque (and dipole) arrows, a "
        "readout and the attitude error or |omega| over time (only --t-end overrides it; no live mode).",
        "tumble view examples/seed_flip.toml --out flip.html | "
        "tumble view examples/control/point.toml --out point.html | "
        "tumble view iss-t-handle --omega 0.1 0.1 8 --out iss.html", "FILE.html", "the page to write",
    )
    p.add_argument("--frames", type=int, default=150, help="animation frames, 2 to 2000 (default 150)")

    p = sub.add_parser(
        "examples",
        help="list the example scenario and body files, or copy them",
        description="Lists the scenario and body files that ship with tumble; --copy DIR copies them, "
        "ready to run (scenarios name their bodies and meshes by relative paths).",
        epilog="Examples: tumble examples | tumble examples --copy my-examples", parents=[debug],
    )
    p.add_argument("--copy", metavar="DIR", help="copy every example into DIR (never overwrites a file)")
    p.set_defaults(func=_cmd_examples)

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
    p.set_defaults(func=_cmd_sweep)

    p = sub.add_parser(
        "map",
        help="stability map: flip interval over the triangle of inertia ratios",
        description="Draws the exact flip interval and the circulation axis of a spin about the intermediate axis "
        "with a small perturbation, over the triangle of inertia ratios (I1/I3, I2/I3).",
        epilog="Example: tumble map --out map.png --spin 10 --perturbation 0.01 0.01", parents=[debug],
    )
    p.add_argument("--out", required=True, metavar="FILE", help="the figure (.png or .svg)")
    p.add_argument("--spin", type=float, default=10.0, metavar="W", help="spin about the intermediate axis, rad/s (default 10)")
    p.add_argument("--perturbation", type=float, nargs=2, default=(0.01, 0.01), metavar=("W1", "W3"),
                   help="rates about the minor and major axes, rad/s (default 0.01 0.01)")
    p.add_argument("--resolution", type=int, default=300, metavar="N", help="grid points per side (default 300)")
    p.set_defaults(func=_cmd_map)

    p = sub.add_parser(
        "fit",
        help="inertia ratios from a gyroscope recording (phyphox export or t,wx,wy,wz CSV)",
        description="Finds the free flights of a whole recording of tosses (gyroscope alone; phyphox's "
        "pauses honoured), fits each with the exact torque-free motion (or with per-axis drag), fits them "
        "jointly (shared ratios, sensor rotation, bias and drag) and writes DIR/fit.json (pooled values with "
        "standard uncertainties and 95 percent intervals, every flight, provenance), DIR/tosses.csv and DIR/fit.png. "
        "With --start/--end the samples between are fitted as one flight.",
        epilog="Example: tumble fit examples/data/racquet_tosses.csv --out fitted", parents=[debug],
    )
    p.add_argument("data", metavar="RECORDING",
                   help="a CSV (phyphox's gyroscope export or t, wx, wy, wz in s, rad/s), or phyphox's export "
                   "folder or .zip (Raw Data.csv and meta/time.csv)")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder")
    p.add_argument("--sensor", choices=["fit", "identity"], default="fit",
                   help="fit the sensor's rotation to the principal axes (default) or take it as identity")
    p.add_argument("--no-bias", action="store_true", help="assume an unbiased gyroscope")
    p.add_argument("--drag", choices=["auto", "none", "linear", "quadratic"], default="auto",
                   help="aerodynamic drag about each principal axis: chosen by the BIC (default), or as named")
    p.add_argument("--saturation", type=float, metavar="RAD_S",
                   help="the gyroscope's full scale, rad/s (default: found from the data); samples at it are left out")
    p.add_argument("--body", metavar="FILE", help="a body file or preset: its ratios compared with the fit")
    p.add_argument("--start", type=float, metavar="S", help="fit one flight: first time, s")
    p.add_argument("--end", type=float, metavar="S", help="fit one flight: last time, s")
    p.add_argument("--accept-inadequate", action="store_true",
                   help="exit 0 even when the model does not describe the data (by default such a fit is written "
                   "with \"adequate\": false, a warning printed and the exit status 1)")
    p.set_defaults(func=_cmd_fit)

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
    p.set_defaults(func=_cmd_demo)
    return parser


class _Terminated(BaseException):
    """Raised by the SIGTERM handler, so that partial output is cleaned up as on Ctrl-C."""


def _on_sigterm(signum, frame):  # noqa: ARG001 - signal handler API
    raise _Terminated


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``tumble`` console command; returns the exit status.

    0: success; 2: bad input (nothing written); 1: a failed computation or an I/O failure
    (disk full, permissions: the path is named; nothing half-written); 130 / 143: interrupted
    by SIGINT / SIGTERM (nothing half-written). A reader that closes the pipe early
    (``tumble examples | head -2``) is a normal end: 0, quietly.
    """
    parser = build_parser()
    argv = sys.argv[1:] if argv is None else list(argv)
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return EXIT_USAGE
    args.argv = argv
    try:
        previous = signal.signal(signal.SIGTERM, _on_sigterm)
    except ValueError:  # not the main thread: leave signals alone
        previous = None
    try:
        with warnings.catch_warnings():
            # numeric trouble (overflow, invalid values) becomes a one-line failure, not noise
            warnings.simplefilter("error", RuntimeWarning)
            status = args.func(args)
            sys.stdout.flush()  # a closed pipe shows here, inside the handlers below, not at exit
            return status
    except KeyboardInterrupt:
        print("tumble: interrupted; nothing written", file=sys.stderr)
        return 130
    except _Terminated:
        print("tumble: terminated; nothing written", file=sys.stderr)
        return 143
    except ValueError as exc:
        if args.debug:
            raise
        print(f"tumble: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_USAGE
    except OSError as exc:  # the input was fine; writing failed (disk full, permissions)
        if isinstance(exc, BrokenPipeError) and exc.filename is None:
            return _reader_gone()
        if args.debug:
            raise
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"tumble: failed: {where}{exc.strerror or _one_line(exc)}; nothing written", file=sys.stderr)
        return EXIT_FAILURE
    except Exception as exc:  # a failure of the computation, not of the input
        if args.debug:
            raise
        print(f"tumble: computation failed: {type(exc).__name__}: {_one_line(exc)}", file=sys.stderr)
        return EXIT_FAILURE
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _reader_gone() -> int:
    """Standard output's reader closed the pipe (``tumble examples | head -2``): a normal end.

    Standard output is pointed at the null device, so that the interpreter's last flush at exit
    finds nothing to complain about (the recipe of Python's documentation of ``signal``).
    """
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    os.close(devnull)
    return EXIT_OK


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
