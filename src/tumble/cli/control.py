"""``tumble simulate`` and ``tumble view`` of a closed-loop (control) scenario."""

from __future__ import annotations

import json
import math

from ._common import EXIT_OK, _run_title, _working

#: The files `tumble simulate` writes into its folder (every run).
SIMULATE_WRITES = ("trajectory.csv", "trajectory.npz", "summary.json", "omega.png")
#: The figures `tumble simulate` adds for a control scenario (`tumble.viz.control.CONTROL_FIGURES`): all of them
#: are the command's, so an earlier run's are replaced as a set, though a run without wheels writes no
#: wheels.png and one without a target no attitude_error.png.
CONTROL_WRITES = ("attitude_error.png", "rates.png", "wheels.png", "dipole.png", "momentum.png")
#: The figure `tumble simulate` adds when the controller sees an [estimator]'s estimate (tumble.viz.knowledge).
ESTIMATOR_WRITES = ("knowledge.png",)


def figure_title(name: str, kind: str) -> str:
    """The control figures' title: the scenario's name, and its controller's kind when that says more.

    Examples
    --------
    >>> from tumble.cli.control import figure_title
    >>> figure_title("3U CubeSat", "bdot"), figure_title("detumble_point", "detumble_point")
    ('3U CubeSat (bdot)', 'detumble_point')
    """
    return name if name == kind else f"{name} ({kind})"


def refuse_control(scenario, command: str, source: str | None = None) -> None:
    """Refuse a control scenario to a command that does not run one, naming the file as given (``source``)."""
    if not hasattr(scenario, "method"):
        raise ValueError(f"{source or scenario.name} is a control scenario ([control]); 'tumble {command}' does not "
                         f"take it yet: use 'tumble simulate {source or 'FILE'} --out DIR'")


def simulate_control(args, scenario, out) -> int:
    """`tumble simulate` of a control scenario: the closed loop, its summary and trajectory."""
    from ..commands import run_scenario
    from ..io.controlfile import control_summary, write_control_run
    from ..io.export import write_json
    from ..io.output import output_dir
    from ..io.provenance import provenance
    from ..viz import control_figures, figure_omega, save_figure

    controller = scenario.controller()
    with _working(f"running {scenario.name} in closed loop ({scenario.kind})"):
        run = run_scenario(scenario, controller)
    summary = control_summary(scenario, run, controller)
    summary["scenario"] = str(args.source)
    summary["provenance"] = provenance(args.argv, scenario.sources)
    figures = control_figures(run, target=scenario.target, switch_time=summary.get("switch_time"),
                              title=figure_title(scenario.name, scenario.kind))
    if "knowledge_error_rms_deg" in summary:
        from ..viz import figure_knowledge

        figures["knowledge.png"] = figure_knowledge(run, controller.knowledge(), switch_time=summary.get("switch_time"),
                                                    title=figure_title(scenario.name, scenario.kind),
                                                    bias=scenario.sensors.gyro_bias)
    with output_dir(out, (*SIMULATE_WRITES, *CONTROL_WRITES, *ESTIMATOR_WRITES)) as stage:
        write_control_run(run, stage)
        save_figure(figure_omega(scenario.trajectory(run), title=scenario.name, control_period=controller.period),
                    stage / "omega.png")
        for name, fig in figures.items():
            save_figure(fig, stage / name)
        write_json(summary, stage / "summary.json")
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        done = summary["detumble_time"]
        line = f"{summary['body']} ({scenario.kind}, {summary['t_end']:g} s): final rate {summary['final_rate']:.3g} rad/s"
        never = scenario.kind == "detumble_point" and summary.get("switch_time") is None  # a mission that failed
        if summary.get("switch_time") is not None:
            line += f", pointing from t = {summary['switch_time']:g} s"
            if summary["initial_rate"] < getattr(controller, "switch_rate", 0.0):  # as the detumbling above
                line += " (it started below switch_rate: nothing was detumbled)"
        if never:  # its pointing error would read as the pointing's, which never began
            line += ", never switched to pointing (the rate did not stay below switch_rate for the dwell)"
        if "pointing_error_final" in summary and not never:
            line += f", pointing error {summary['pointing_error_final']:.3g} rad"
        elif done is not None:
            line += f", below {summary['threshold']:.3g} rad/s from t = {done:g} s"
            if done == 0:  # already below at the start: a threshold in deg/s read as rad/s, or nothing to detumble
                line += " (it started below the threshold: nothing was detumbled)"
        else:  # a run that ends before it detumbles says so, rather than nothing
            line += f", not below the threshold {summary['threshold']:.3g} rad/s by the end: not detumbled"
        limit = None if scenario.wheels is None else float(max(scenario.wheels.max_speed))
        started = 0.0 if scenario.speed0 is None else max(abs(x) for x in scenario.speed0)
        if limit is not None and started > limit:  # the input put them there; a motor brings them down (issue 27)
            line += (f", wheels started at up to {started:.6g} rad/s, past their {limit:.6g} rad/s limit (speed0; "
                     "beyond it a motor gives no outward torque)")
        elif limit is not None and summary["max_wheel_speed"] > limit:  # speeds relative to a tumbling body
            line += (f", wheels up to {summary['max_wheel_speed']:.6g} rad/s, past their {limit:.6g} rad/s limit (the "
                     f"body's own turning carries them there; beyond it a motor gives no outward torque)")
        if "knowledge_error_rms_deg" in summary:  # the pointing error beside it in deg too: one unit in one line
            pointing = (f" (pointing {math.degrees(summary['pointing_error_final']):.3g} deg)"
                        if "pointing_error_final" in summary else "")
            line += (f", knowledge error {summary['knowledge_error_rms_deg']:.3g} deg RMS, "
                     f"{summary['knowledge_error_final_deg']:.3g} deg at the end{pointing}")
        print(f"{line}; wrote {out}/")
    return EXIT_OK


def view_control(args, scenario, out) -> int:
    """`tumble view` of a control scenario: the page with the wheels, the commanded torque and the error."""
    from ..commands import run_scenario

    controller = scenario.controller()
    with _working(f"running {scenario.name} in closed loop ({scenario.kind})"):
        run = run_scenario(scenario, controller)

    from ..viz.control_page import control_page_data
    from ..viz.page import write_page

    traj = scenario.trajectory(run)
    control = control_page_data(run, frames=args.frames, wheel_axes=None if scenario.wheels is None else
                                scenario.wheels.axes, target=scenario.target, threshold=scenario.threshold,
                                knowledge=controller.knowledge() if hasattr(controller, "knowledge") else None)
    write_page(scenario.body, traj, out, frames=args.frames, title=_run_title(scenario, traj), live=False,
               control=control)
    shown = ", ".join(what for what, has in (("wheels", scenario.wheels is not None), ("commanded torque", scenario.wheels
                                              is not None), ("dipole", scenario.magnetorquers is not None)) if has)
    print(f"wrote {out} (self-contained: open it in any browser, no network needed; closed loop: "
          f"{shown or 'no actuator'}, live mode off)")
    return EXIT_OK
