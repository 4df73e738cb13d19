"""The commands of ``tumble``; the closed-loop (control) runs are :mod:`tumble.cli.control`.

Heavy modules are imported inside the commands so that ``tumble --help`` answers at once.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

from ._common import EXIT_FAILURE, EXIT_OK, _positive, _run_title, _saturation, _working
from .control import SIMULATE_WRITES, refuse_control, simulate_control, view_control


def _cmd_inertia(args) -> int:
    from ..io import load_body, mass_properties_dict, mass_properties_table
    from ..io.bodyfile import body_from_mesh, is_mesh_file

    mesh_options = {f"--{k}": getattr(args, k) for k in ("density", "mass", "scale", "units")}
    given = {k: v for k, v in mesh_options.items() if v is not None}
    if is_mesh_file(args.body):
        if "--density" in given and "--mass" in given:
            raise ValueError(f"give --density = {args.density} (kg/m^3) or --mass = {args.mass} (kg), not both")
        if "--density" not in given and "--mass" not in given:
            raise ValueError(f"{args.body}: a mesh needs --density (kg/m^3) or --mass (kg): "
                             f"it is read as one uniform solid")
        if "--scale" in given and "--units" in given:
            raise ValueError(f"give --scale = {args.scale} or --units = {args.units}, not both")
        units = {"--density": "kg/m^3", "--mass": "kg", "--scale": "m per file unit"}
        checked = {k: _positive(k, v, units[k]) for k, v in given.items() if k in units}
        # a likely unit slip warns (MeshScaleWarning), in one line (cli.main's _show_warning)
        body = body_from_mesh(args.body, density=checked.get("--density"), mass=checked.get("--mass"),
                              scale=checked.get("--scale"), units=args.units)
    else:
        body = load_body(args.body)  # first: a file of another kind (a recording, a scenario) is named as what it is
        if given:
            option, value = next(iter(given.items()))
            raise ValueError(f"{option} = {value} applies to a mesh file (.stl, .obj, .ply) only; "
                             f"{args.body} is a body file or preset, whose parts carry their own (mass or density; "
                             f"a mesh part its scale, metres per file unit)")
    if args.json:
        print(json.dumps(mass_properties_dict(body), indent=2))
    else:
        print(mass_properties_table(body))
    return EXIT_OK


def _cmd_demo(args) -> int:
    from ..demo import run_demo

    run_demo(args.out, animate=not args.no_animation, animation_format=args.animation_format, argv=args.argv)
    return EXIT_OK


def _cmd_examples(args) -> int:
    from ..io.examples import copy_examples, list_examples

    if args.copy is not None:
        written = copy_examples(args.copy)
        print(f"copied {len(written)} files to {args.copy}/; try: tumble simulate {args.copy}/seed_flip.toml --out run")
        return EXIT_OK
    examples = list_examples()
    width = max(len(e.path) for e in examples)
    for e in examples:
        print(f"{e.path:<{width}}  {e.kind:<8}  {e.description}")
    print("copy them with: tumble examples --copy DIR")
    return EXIT_OK


def _cmd_compile(args) -> int:
    import time

    from ..commands.compile_ahead import GROUPS, check_groups, compile_ahead, processes
    from ..jit import kernel_cache_folder

    described = {group.name: group.description for group in GROUPS}
    width = max(len(name) for name in described)
    names = check_groups(args.groups, "GROUP")  # checked with --list too: it skipped them (a walkthrough)
    at_once = processes(len(names), args.jobs, "--jobs")
    if args.list:  # the groups named, or every group
        for name in names if args.groups else described:
            print(f"{name:<{width}}  {described[name]}")
        return EXIT_OK
    folder = kernel_cache_folder()
    if folder is None:
        print("tumble: failed: no folder here can hold numba's cache (the package's, $NUMBA_CACHE_DIR, "
              "~/.cache and the temporary folder are read-only), so each run compiles its own kernels; "
              "nothing compiled ahead", file=sys.stderr)
        return EXIT_FAILURE
    print(f"compiling {len(names)} group{'s' if len(names) > 1 else ''} of kernels into numba's cache ({folder}, "
          f"and likewise for each module of kernels), {at_once} at a time", flush=True)
    start = time.perf_counter()

    def done(compiled) -> None:  # noqa: ANN001 - a Compiled
        what = (f"{compiled.kernels:3d} kernels compiled in {compiled.compile_s:5.1f} s" if compiled.kernels
                else f"{'in the cache already':<32}")
        print(f"  {compiled.name:<{width}}  {what}  {described[compiled.name]}", flush=True)

    compile_ahead(names, jobs=args.jobs, done=done)
    print(f"done in {time.perf_counter() - start:.1f} s: a first run of these loads its kernels from the cache "
          f"instead of compiling them (until tumble's sources change)")
    return EXIT_OK


def _cmd_sweep(args) -> int:
    from ..commands.sweep import run_sweep_command
    from ..viz.maps import figure_sweep

    if args.workers is not None and args.scheduler is not None:
        raise ValueError("give --workers (a local cluster) or --scheduler (an existing one), not both")
    if args.workers is not None and not 1 <= args.workers <= 256:
        raise ValueError(f"--workers = {args.workers} must be from 1 to 256")
    with _working("sweeping"):
        return run_sweep_command(args.sweep, args.out, workers=args.workers, scheduler=args.scheduler,
                                 argv=args.argv, figure=figure_sweep)


def _cmd_map(args) -> int:
    from ..io.output import check_output_file
    from ..validation import MAX_RATE, check_positive

    out = check_output_file(args.out, (".png", ".svg"))
    spin = check_positive("--spin", args.spin, "rad/s", at_most=MAX_RATE)  # simulate's bound (1e20 was taken)
    perturbation = tuple(check_positive(f"--perturbation[{i}]", p, "rad/s", allow_zero=True, at_most=0.999 * spin)
                         for i, p in enumerate(args.perturbation))  # below the spin: a spin about the intermediate axis
    if not 10 <= args.resolution <= 2000:  # stability_map's range
        raise ValueError(f"--resolution = {args.resolution} must be from 10 to 2000")
    from ..viz import figure_stability_map, save_figure

    with _working("mapping"):  # the option is in rad/s, as its help says; the map takes fractions of the spin
        fractions = (perturbation[0] / spin, perturbation[1] / spin)
        save_figure(figure_stability_map(spin, fractions, resolution=args.resolution), out)
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
    from ..commands.fit import run_fit_command
    from ..viz import figure_fit, figure_recording

    saturation = _saturation(args.saturation)
    bar = _Bar()
    try:
        if len(args.data) > 1 and (args.start is not None or args.end is not None):
            raise ValueError(f"--start/--end select one flight of one recording; {len(args.data)} recordings given")
        data = args.data[0] if len(args.data) == 1 else args.data
        return run_fit_command(data, args.out, argv=args.argv, figure=figure_fit, recording_figure=figure_recording,
                               start=args.start, end=args.end, body=args.body, progress=bar,
                               sensor_rotation=args.sensor, bias=not args.no_bias, drag=args.drag, saturation=saturation,
                               accept_inadequate=args.accept_inadequate, scale_uncertainty=args.scale_uncertainty)
    finally:
        bar.close()


def _cmd_calibrate(args) -> int:
    from ..commands.tensor import run_calibrate_command

    saturation = _saturation(args.saturation)
    with _working("calibrating"):
        return run_calibrate_command(args.device, args.alone, args.proof, args.out, argv=args.argv,
                                     saturation=saturation, accept_inadequate=args.accept_inadequate)


def _cmd_tensor(args) -> int:
    from ..commands.tensor import run_tensor_command
    from ..viz import figure_tensor

    mass = _positive("--mass", args.mass, "kg")
    saturation = _saturation(args.saturation)
    with _working("fitting throws"):
        return run_tensor_command(args.throws, args.device, mass, args.out, argv=args.argv, figure=figure_tensor,
                                  accept_inadequate=args.accept_inadequate, saturation=saturation)


def _resolve(args):
    """The run a scenario command asks for (scenario file, or body + --omega; options override)."""
    from ..io.scenario import resolve_run

    try:
        return resolve_run(args.source, omega=args.omega, frame=args.frame, t_end=args.t_end,
                           samples=args.samples, dt=args.dt, method=args.method)
    except ValueError as exc:  # --frame 300 for --frames 300 (argparse took the option whole): name --frames
        if hasattr(args, "frames") and f"--frame = {args.frame!r} is not allowed" in str(exc):
            raise ValueError(f"{exc} (the page's number of frames is --frames)") from None
        if hasattr(args, "frames") and "is not a scenario file, a body file or a preset" in str(exc):
            raise type(exc)(str(exc).replace("a body file or a preset", "a body file, a preset, or the folder a "
                                                                          "tumble fit or tumble tensor wrote", 1)) from None
        raise


def _cmd_simulate(args) -> int:
    from ..io.output import check_output_dir

    scenario = _resolve(args)  # every check before anything is computed or written
    out = check_output_dir(args.out)
    if not hasattr(scenario, "method"):  # a closed-loop (control) scenario
        return simulate_control(args, scenario, out)
    from ..commands import run_scenario

    with _working(f"integrating {scenario.name} ({scenario.method or 'method auto'})"):
        traj = run_scenario(scenario)

    from ..analysis import trajectory_summary
    from ..dynamics.models.gravity import gravity_gradient_in
    from ..dynamics.models.orbit_gravity import OrbitGravityGradient
    from ..dynamics.models.torques import as_torque, terms_of
    from ..io.export import write_csv, write_json, write_npz
    from ..io.output import output_dir
    from ..io.provenance import provenance
    from ..viz import figure_omega, save_figure

    summary = trajectory_summary(traj)
    summary.update(method=getattr(traj, "method_label", traj.method), frame=scenario.frame, omega0_given=list(scenario.omega))
    orbit = gravity_gradient_in(scenario.torque)
    if orbit is not None:  # the gravity gradient, alone (its Jacobi integral the error measure) or in a sum
        from ..analysis.torque_summary import gravity_gradient_summary

        pitch_axis, yaw_axis = scenario.orbit_axes or (3, 1)  # the run's own axes (they were taken as 3, 1 always)
        summary["gravity_gradient"] = gravity_gradient_summary(traj, orbit, alone=orbit is scenario.torque,
                                                               pitch_axis=pitch_axis, yaw_axis=yaw_axis)
        summary["gravity_gradient"]["started_in_orbit_frame"] = scenario.orbit_axes is not None
    elif (along := next((t for t in terms_of(as_torque(scenario.torque)) if isinstance(t, OrbitGravityGradient)),
                        None)) is not None:  # an ellipse's or a TLE's: the spin beside its rate, no Jacobi integral
        from ..analysis.torque_summary import orbit_gradient_summary

        summary["gravity_gradient"] = {**orbit_gradient_summary(traj, along.orbit), "started_in_orbit_frame": False}
    if scenario.torque is not None:  # the torque the run took, principal frame and bound (check_inputs')
        from ..analysis.torque_summary import torque_budget
        from ..dynamics.simulate import check_inputs

        summary["torque_budget"] = torque_budget(traj, check_inputs(**scenario.arguments()).torque)
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


#: The figures of `tumble plot`, in the order they are drawn; the spacecraft figures
#: (`tumble.viz.spacecraft_figures`) follow where they apply.
PLOTS = ("omega", "polhode", "herpolhode", "drift")
SPACECRAFT_PLOTS = ("energy", "nutation", "orbit_angles")


def _cmd_plot(args) -> int:
    import dataclasses

    from ..io.output import check_output_dir

    scenario = _resolve(args)
    refuse_control(scenario, "plot", args.source)
    out = check_output_dir(args.out)
    if scenario.times is None and scenario.dt is None:  # the phase portraits need a fine path
        scenario = dataclasses.replace(scenario, samples=max(scenario.sample_count, 5000))
    from ..commands import run_scenario

    with _working(f"integrating {scenario.name}"):
        traj = run_scenario(scenario)

    from .. import viz
    from ..io.output import output_dir

    title = _run_title(scenario, traj)
    makers = {"omega": viz.figure_omega, "polhode": viz.figure_polhode,
              "herpolhode": viz.figure_herpolhode, "drift": viz.figure_drift}
    skipped = viz.phase_portrait_problem(traj)
    names = [n for n in PLOTS if not (skipped and n in viz.PHASE_PORTRAITS)]
    axes = dict(zip(("pitch_axis", "yaw_axis"), scenario.orbit_axes or ()))  # the run's own, as its summary's
    extra = viz.spacecraft_figures(traj, scenario.torque, **axes)  # energy, nutation, orbit angles
    written: list[str] = []
    owns = [f"{name}.*" for name in (*PLOTS, *SPACECRAFT_PLOTS)]  # the figures are replaced as a set
    earlier = sorted({p.name for pattern in owns for p in Path(out).glob(pattern)}) if Path(out).is_dir() else []
    with output_dir(out, owns) as stage:
        figures = [(name, makers[name](traj, title=title if name == "omega" else None)) for name in names]
        for name, fig in figures + [(name, make()) for name, make in extra]:
            for fmt in args.format:
                viz.save_figure(fig, stage / f"{name}.{fmt}")
                written.append(f"{name}.{fmt}")
    print(f"wrote {', '.join(written)} to {out}/")
    if skipped:
        print(f"skipped {', '.join(viz.PHASE_PORTRAITS)}: {skipped}")
    if removed := [name for name in earlier if name not in written]:
        print(f"removed an earlier run's {', '.join(removed)} (the folder holds one run's figures)")
    return EXIT_OK


def _cmd_view(args) -> int:
    from ..io.output import check_output_file
    from ..viz.scene import MAX_FRAME_TURN, frame_indices, frame_turn, frames_advice

    frames_given, args.frames = args.frames is not None, 150 if args.frames is None else args.frames  # the pages' default
    if os.path.isdir(args.source):  # a tumble fit or tumble tensor output folder
        return _view_folder(args, frames_given)
    out = check_output_file(args.out, ".html")
    scenario = _resolve(args)
    control = not hasattr(scenario, "method")  # a closed-loop (control) scenario
    frame_indices(2 if control else scenario.sample_count, args.frames, "--frames")  # refuse a bad --frames before integrating
    if control:
        return view_control(args, scenario, out)
    from ..commands import run_scenario

    with _working(f"integrating {scenario.name}"):
        traj = run_scenario(scenario)

    from ..viz.page import write_page

    write_page(scenario.body, traj, out, frames=args.frames, title=_run_title(scenario, traj))
    print(f"wrote {out} (self-contained: open it in any browser, no network needed)")
    indices = frame_indices(len(traj.t), args.frames, "--frames")
    turn = frame_turn(traj.t, traj.omega, indices)
    if turn > MAX_FRAME_TURN:  # a stroboscope's wheel: the page would show another motion than the run's
        print(f"note: the body turns up to {turn:.3g} rad between the page's {len(indices)} frames, past half a turn: "
              f"the animation shows another motion than the run's; {frames_advice(traj.t, traj.omega)}",
              file=sys.stderr)
    return EXIT_OK


def _view_folder(args, frames_given: bool = False) -> int:
    """`tumble view DIR`: a fit's output folder (fit.json) or a tensor's (tensor.json), else one line."""
    from ..io.fitfolder import FIT_FILE
    from ..io.tensorfolder import TENSOR_FILE

    fit, tensor = (os.path.isfile(os.path.join(args.source, name)) for name in (FIT_FILE, TENSOR_FILE))
    if fit and tensor:
        raise ValueError(f"{args.source}: holds both {FIT_FILE} and {TENSOR_FILE}; give a folder of one of tumble fit "
                         "and tumble tensor (their --out)")
    if not fit and not tensor:
        raise ValueError(f"{args.source}: a folder without {FIT_FILE} or {TENSOR_FILE}; give the output folder of "
                         "tumble fit (tumble fit REC --out DIR) or of tumble tensor (tumble tensor THROW... --out DIR)")
    given = [f"--{k.replace('_', '-')}" for k in ("omega", "frame", "t_end", "samples", "dt", "method")
             if getattr(args, k) is not None] + (["--frames"] if tensor and frames_given else [])  # it was ignored
    if given:
        what = "a fit's output folder replays its fitted flights" if fit else "a tensor's output folder shows its throws"
        to = ("a scenario, a body or a fit's folder (a tensor's page has no animation)" if given == ["--frames"]
              else "a scenario or a body")
        raise ValueError(f"{args.source}: {what}; {', '.join(given)} {'applies' if len(given) == 1 else 'apply'} to {to}")
    return _view_fit(args) if fit else _view_tensor(args)


def _view_tensor(args) -> int:
    """`tumble view DIR` of a tensor's output folder: its throws, the moments and the equivalent box."""
    from ..io.output import check_output_file
    from ..io.tensorfolder import read_tensor_folder

    folder = read_tensor_folder(args.source)  # bad input: one line naming the folder
    out = check_output_file(args.out, ".html")
    from ..viz.tensor_page import write_tensor_page

    write_tensor_page(folder, out)
    shown = sum(1 for s in folder.series if s.t.size)
    print(f"wrote {out}: {shown} throw{'' if shown == 1 else 's'} of {args.source} with the fitted model, the "
          "principal moments and the equivalent box (self-contained: open it in any browser, no network needed)")
    return EXIT_OK


def _view_fit(args) -> int:
    """`tumble view DIR` of a fit's output folder: the fitted body replaying each used flight."""
    from ..io.fitfolder import read_fit_folder
    from ..io.output import check_output_file
    from ..viz.scene import frame_indices

    fit = read_fit_folder(args.source)  # bad input: one line naming the folder, before anything is computed
    out = check_output_file(args.out, ".html")
    frame_indices(2, args.frames, "--frames")  # refuse a bad --frames before replaying
    from ..commands.view_fit import replay_fit
    from ..viz.fit_page import write_fit_page

    with _working(f"replaying {len(fit.models)} flights"):
        replays = replay_fit(fit)
    write_fit_page(replays, out, frames=args.frames)
    print(f"wrote {out}: {len(replays)} flight{'' if len(replays) == 1 else 's'} of {args.source} replayed by the "
          "fitted body (self-contained: open it in any browser, no network needed)")
    for note in dict.fromkeys(r.note for r in replays if r.note):
        print(f"warning: {note}", file=sys.stderr)
    return EXIT_OK


def _budget_words(name: str, budget: dict) -> str:
    """``L_world`` or the energy against the torque's impulse or work, as a fraction of it, and the
    quadrature's own error (:func:`~tumble.analysis.torque_summary.torque_budget`)."""
    what = {"momentum": "L_world followed the impulse", "energy": "the energy followed the work"}[name]
    scale = budget["change"]
    if not scale:
        return f"{what} (both 0)"
    quadrature = "" if budget["quadrature"] is None else f" (the samples' quadrature: {budget['quadrature'] / scale:.0e})"
    return f"{what} to {budget['gap'] / scale:.1e} of it{quadrature}"


#: A body's linear stability at rest in the orbiting frame, in words (STABILITY_REGIONS, docs/gravity-gradient.md).
_REGION_WORDS = {"lagrange": "linearly stable there (the Lagrange region)",
                 "debra-delp": "linearly stable there by the gyroscopic coupling of roll and yaw (the DeBra-Delp region)",
                 "pitch unstable": "unstable there in pitch", "roll-yaw unstable": "unstable there in roll and yaw",
                 "unstable": "unstable there in pitch and in roll and yaw",
                 "symmetric": "stable there but for a free turn about its symmetry axis"}


def _simulate_line(summary: dict, out) -> str:
    """One line for people: what the spin did and how well the invariants held."""
    from ..analysis.gravity_stability import FREE_BODY_SPIN
    from ..analysis.summary import SAMPLES_PER_FLIP

    s, d = summary["stability"], summary["drift"]
    head = f"{summary['body']} ({summary['method']}, {summary['t_end']:g} s)"
    flips = "flips not counted" if s["flips"] is None else f"{s['flips']} flip{'' if s['flips'] == 1 else 's'}"
    spin = "started at rest" if s["axis"] is None else (
        f"spin mostly about axis {s['axis']} ({s['role']}), predicted {s['predicted']}, {flips}")
    g = summary.get("gravity_gradient") or {}
    if g.get("started_in_orbit_frame"):  # librations in the orbiting frame: its stability, not the free body's nor flips
        spin = (f"started turning with the orbiting frame (pitch axis {g['pitch_axis']}, yaw axis {g['yaw_axis']}), "
                f"{_REGION_WORDS[g['region']]}")
    elif g and s["axis"] is not None and not g["free_body"]:  # the gradient is not small beside the spin
        spin = (f"spin mostly about axis {s['axis']} ({s['role']}), {flips}; "
                f"{'a free body would be ' + s['predicted'] + ', but ' if s['predicted'] else ''}"
                f"at {g['spin_over_n']:.2g} times the orbit rate the gravity "
                f"gradient is not small beside the spin (its torque some 3 (n / omega)^2 = "
                f"{3.0 / g['spin_over_n'] ** 2:.0%} of the gyroscopic terms"
                + (f", {3.0 / g['spin_over_n'] ** 2 / g['separatrix_offset']:.2g} times the spin's distance from the "
                   f"separatrix, {g['separatrix_offset']:.2g}, which it moves)" if g["separatrix_offset"] is not None
                   and g["spin_over_n"] >= FREE_BODY_SPIN else ")"))
    measured, exact = s["flip_period"], s["flip_period_exact"]
    aliased = s.get("samples_per_flip") is not None and s["samples_per_flip"] < SAMPLES_PER_FLIP
    if summary["torque_free"] and s["flips"] and (measured is not None or exact is not None):
        # what the run did; the closed form beside it where they differ in the digits shown (a method's
        # error, rk45's 0.9 % on the seed's flip), or alone where the samples are too few to measure it
        if measured is not None and not aliased:
            spin += f" every {measured:.4g} s"
            if exact is not None and f"{exact:.4g}" != f"{measured:.4g}":
                spin += f" (the closed form: {exact:.4g} s)"
        elif exact is not None and not aliased:
            spin += f" (the closed form: every {exact:.4g} s)"
    if s.get("note"):  # a symmetric body's roll, an unperturbed intermediate spin
        spin += f" ({s['note']})"
    if aliased:  # the count is aliased
        closed = f"; the closed form flips every {exact:.4g} s" if exact is not None and summary["torque_free"] else ""
        spin += (f" ({s['samples_per_flip']:.2g} samples a flip, too few to count them: give more "
                 f"samples{closed})")
    if "gravity_gradient" in summary and summary["gravity_gradient"]["jacobi_drift"] is not None:
        g = summary["gravity_gradient"]
        tail = (f"{g['orbits']:.3g} orbits, Jacobi integral drift {g['jacobi_drift']:.1e}, largest angle from the "
                f"orbiting frame {max(g['max_angle'].values()):.3g} rad")
        if g["symmetry_axis"] is not None:  # the turn about it changes nothing: how far the axis itself went
            tail += (f"; its symmetry axis ({g['symmetry_axis']}), about which it turns freely, at most "
                     f"{g['symmetry_axis_tilt']:.3g} rad from its place")
    elif summary["torque_free"] and all(v is None for v in d.values()):
        tail = "energy and L start at 0, so there is no relative drift to give"
        work = summary.get("rotors", {}).get("motor_work")
        if work is not None:
            tail += f"; the motors did {work:.3g} J of work"
    elif summary["torque_free"]:
        # the drift's energy is the energy balance (Trajectory.drift): name what it sums
        balance = "energy" + (" - motor work" if "rotors" in summary else "") + (" + dissipated" if "damper" in summary else "")
        drift = ", ".join(f"{balance if k == 'energy' else k} {'n/a' if v is None else format(v, '.1e')}" for k, v in d.items())
        tail = f"relative drift: {drift}"
    elif summary.get("torque_budget") and not summary["torque_budget"]["resolved"]:
        tail = (f"torque acted (the samples, up to {summary['torque_budget']['turn_per_sample']:.2g} rad apart, are too "
                "coarse to check its budget; more samples would)")
    elif summary.get("torque_budget"):
        b = summary["torque_budget"]
        tail = "torque acted: " + "; ".join(_budget_words(name, b[name]) for name in ("momentum", "energy") if name in b)
    else:
        tail = ("torque acted, so energy and L change (its budget is checked over 3 to 100,000 samples of a torque "
                "that varies, any number of a constant one)")
    if g and g["jacobi_drift"] is None and g["max_angle"] is not None:  # a sum: the orbit's angles too
        g = summary["gravity_gradient"]
        tail += f"; {g['orbits']:.3g} orbits, largest angle from the orbiting frame {max(g['max_angle'].values()):.3g} rad"
    return f"{head}: {spin}; {tail}; wrote {out}/"
