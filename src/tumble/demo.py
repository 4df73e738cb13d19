"""The T-handle study, run by ``make demo``: the seed's sections 2-7, done right.

Cases (t in [0, 20] s, 500 samples, as in the seed):

- the seed's T-handle (thin rods, 1 m, 1.5 kg): 10 rad/s about each principal axis with
  0.1 rad/s on the other two (seed sec. 6's three cases, with the axes decided by the computed
  tensor), and the seed's own vectors [10, 0.1, 0.1] and [1, 0.1, 0.1] read in the design frame
  (x along the crossbar) -- both about the intermediate axis, so both flip;
- the same three principal cases for the space-station handle, whose shaft flips.

Every case runs with the accurate default method; the seed's literal vectors also run with the
seed's own computation ("seed": RK45 at default tolerances + R <- R exp([w] dt)) to show its
drift. Outputs: omega(t) per case and combined (PNG), ground- and body-frame animations of each
handle's first two flips (MP4 where an ffmpeg is found, GIF otherwise), trajectories (CSV), and a summary table (Markdown and
JSON).
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from .analysis import trajectory_summary
from .dynamics import Trajectory, simulate
from .io.atomic import atomic_write_text
from .io.export import write_csv, write_json
from .io.output import check_output_dir, output_dir
from .io.provenance import provenance
from .io.report import describe_axis, mass_properties_dict
from .mass import AXIS_ROLES, Body, iss_t_handle, t_handle

__all__ = ["CASES", "Case", "animation_suffix", "run_demo"]

T_END, SAMPLES = 20.0, 500
#: The animations show the first ``FLIPS`` flips of the run (its exact flip interval), a frame each
#: ``FRAME_TURN`` rad of spin: the whole 20 s in 100 frames turned the handle up to 160 deg a frame, and it
#: seemed to jump (a teacher's walkthrough, 2026-12-03). At 20 frames a second they play slowed ~1.7 times.
FLIPS, FRAME_TURN = 2.2, 0.3


@dataclass(frozen=True)
class Case:
    """One run of the study.

    Examples
    --------
    >>> from tumble.demo import CASES
    >>> CASES[1].omega, CASES[1].frame  # 10 rad/s about the intermediate axis, 0.1 on the others
    ((0.1, 10.0, 0.1), 'principal')
    >>> [c.key for c in CASES if c.method == "seed"]  # the seed's own computation, to show its drift
    ['seed_literal_10_seedmethod', 'seed_literal_1_seedmethod']
    """

    key: str
    body: str  # "seed" or "iss"
    omega: tuple[float, float, float]
    frame: str
    method: str | None
    label: str


def _principal_cases(body: str, name: str) -> list[Case]:
    cases = []
    for j in range(3):
        w = [0.1, 0.1, 0.1]
        w[j] = 10.0
        cases.append(Case(f"{body}_axis{j + 1}", body, tuple(w), "principal", None,
                          f"{name}: spin about axis {j + 1} ({AXIS_ROLES[j]})"))
    return cases


#: The demo's runs (the module's docstring says which): the seed's T-handle about each principal
#: axis, the seed's own vectors read in the design frame, and the space-station handle.
CASES: list[Case] = [
    *_principal_cases("seed", "seed T-handle"),
    Case("seed_literal_10", "seed", (10.0, 0.1, 0.1), "design", None, "seed T-handle: seed's [10, 0.1, 0.1], design frame"),
    Case("seed_literal_1", "seed", (1.0, 0.1, 0.1), "design", None, "seed T-handle: seed's [1, 0.1, 0.1], design frame"),
    Case("seed_literal_10_seedmethod", "seed", (10.0, 0.1, 0.1), "design", "seed",
         "seed T-handle: [10, 0.1, 0.1] with the seed's own computation"),
    Case("seed_literal_1_seedmethod", "seed", (1.0, 0.1, 0.1), "design", "seed",
         "seed T-handle: [1, 0.1, 0.1] with the seed's own computation"),
    *_principal_cases("iss", "ISS T-handle"),
]

#: The runs animated: the flip of each handle.
ANIMATED = ("seed_axis2", "iss_axis2")


class _Progress:
    """A rich progress bar on a terminal; one plain line per step when piped."""

    def __init__(self, total: int):
        self.total, self.done = total, 0
        self.bar = None
        if sys.stdout.isatty():
            from rich.progress import Progress

            self.bar = Progress(transient=True)
            self.task = self.bar.add_task("T-handle study", total=total)
            self.bar.start()

    def step(self, what: str) -> None:
        self.done += 1
        if self.bar is not None:
            self.bar.update(self.task, advance=1, description=what)
        else:
            print(f"[{self.done}/{self.total}] {what}", flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()


#: Glob patterns of the files the study writes (a rerun replaces them as a set).
DEMO_WRITES = ("omega_*.png", "ground_*.gif", "body_*.gif", "ground_*.mp4", "body_*.mp4",
               "trajectory_*.csv", "summary.json", "summary.md")


def animation_suffix(animation_format: str = "auto") -> tuple[str, str | None]:
    """The suffix of the study's animations and a one-line note when MP4 was wanted but cannot be.

    ``"auto"``: ``.mp4`` where an ffmpeg is found (:func:`tumble.viz.ffmpeg_path`), else
    ``.gif`` with a note; ``"gif"``: ``.gif``; ``"mp4"``: ``.mp4``, and a ``ValueError`` where
    no ffmpeg is found (asked for by name, MP4 is not replaced silently).

    Examples
    --------
    >>> from tumble.demo import animation_suffix
    >>> animation_suffix("gif")
    ('.gif', None)
    >>> animation_suffix("avi")
    Traceback (most recent call last):
    ...
    ValueError: animation_format = 'avi' must be 'auto', 'mp4' or 'gif'
    """
    from .viz import animation_path

    if animation_format not in ("auto", "mp4", "gif"):
        raise ValueError(f"animation_format = {animation_format!r} must be 'auto', 'mp4' or 'gif'")
    path, note = animation_path("x.gif" if animation_format == "gif" else "x.mp4")
    if note and animation_format == "mp4":
        raise ValueError("animation_format = 'mp4' needs ffmpeg and none was found: install tumble[video] or put "
                         "ffmpeg on PATH, or ask for 'auto' or 'gif'")
    return path.suffix, note


def animation_plan(suffix: str, note: str | None, count: int = 2 * len(ANIMATED)) -> str:
    """The line the study prints before it starts: what its animations will be written as, and why.

    Examples
    --------
    >>> from tumble.demo import animation_plan
    >>> animation_plan(".mp4", None)
    'animations: 4 MP4 files (ffmpeg found)'
    >>> animation_plan(".gif", "no ffmpeg found (install tumble[video] or put ffmpeg on PATH): GIF written instead of MP4")
    'animations: 4 GIF files instead of MP4: no ffmpeg found (install tumble[video] or put ffmpeg on PATH)'
    >>> animation_plan(".gif", None)   # asked for
    'animations: 4 GIF files (as asked)'
    """
    kind = suffix.lstrip(".").upper()
    if note:
        return f"animations: {count} {kind} files instead of MP4: {note.split(':')[0]}"
    return f"animations: {count} {kind} files ({'ffmpeg found' if kind == 'MP4' else 'as asked'})"


def _animated_run(body: Body, traj: Trajectory, t_end: float) -> tuple[Trajectory, int]:
    """The stretch of ``traj`` an animation shows, run again at its frames: its first :data:`FLIPS` flips
    (at most ``t_end``, s), a frame every :data:`FRAME_TURN` rad of spin; and the number of frames."""
    import math

    import numpy as np

    from .analysis import flip_interval

    w0 = traj.omega[0]
    window = min(t_end, FLIPS * float(flip_interval(w0, traj.moments)))
    rate = float(np.max(np.linalg.norm(traj.omega[traj.t <= window], axis=1)))  # the fastest |omega| there, rad/s
    frames = max(2, math.ceil(window * rate / FRAME_TURN) + 1)
    return simulate(body, w0, t_end=window, samples=frames), frames


def run_demo(out: str | os.PathLike[str] = "tumble-demo", *, t_end: float = T_END, samples: int = SAMPLES, animate: bool = True,
             animation_format: str = "auto", argv: Sequence[str] | None = None) -> Path:
    """Run the whole study and write its figures and data to ``out``; return the folder.

    The folder appears whole or not at all (:func:`tumble.io.output.output_dir`); ``argv``
    (the command line, if any) is recorded in the summary's provenance. The animations are
    MP4 or GIF (:func:`animation_suffix` of ``animation_format``).

    Parameters
    ----------
    out : str or path
        The folder to write (new, or a folder of plain files: the study's files are replaced).
    t_end : float
        Duration of each run, s.
    samples : int
        Samples of each run.
    animate : bool
        Whether to make the four animations (the slow part).
    animation_format : {"auto", "mp4", "gif"}
        See :func:`animation_suffix`.
    argv : sequence of str, optional
        The command line, recorded in the summary's provenance.

    Examples
    --------
    A short study without animations still writes a figure and a CSV for each of the 10 runs,
    the combined figure and the summary; its 11 figures take a few seconds, so it is not run here:

    >>> import contextlib, io, json, tempfile
    >>> from pathlib import Path
    >>> from tumble.demo import run_demo
    >>> with tempfile.TemporaryDirectory() as tmp, contextlib.redirect_stdout(io.StringIO()):  # doctest: +SKIP
    ...     out = run_demo(Path(tmp) / "demo", t_end=0.5, samples=20, animate=False)
    ...     names = sorted(p.name for p in out.iterdir())
    ...     cases = json.loads((out / "summary.json").read_text())["cases"]
    >>> len(names), len(cases), names[-1]   # doctest: +SKIP
    (23, 10, 'trajectory_seed_literal_1_seedmethod.csv')

    Bad input is refused before any run, and nothing is written:

    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     try:
    ...         run_demo(Path(tmp) / "demo", animation_format="avi")
    ...     except ValueError as exc:
    ...         print(exc, "/", (Path(tmp) / "demo").exists())
    animation_format = 'avi' must be 'auto', 'mp4' or 'gif' / False
    """
    from .viz import animate_body_frame, animate_ground_frame, figure_omega, figure_omega_grid, save_figure

    suffix, note = animation_suffix(animation_format)

    out = check_output_dir(out)
    bodies: dict[str, Body] = {
        "seed": t_handle(name="seed T-handle"),
        "iss": iss_t_handle(),
    }
    if animate:  # said first: the animations are the slow part, and a GIF is not what the README promised
        print(animation_plan(suffix, note), flush=True)
    start = time.perf_counter()
    progress = _Progress(len(CASES) + 2 * len(ANIMATED) * animate + 2)
    runs: dict[str, Trajectory] = {}
    rows = []
    try:
        with output_dir(out, DEMO_WRITES) as stage:
            for case in CASES:
                traj = simulate(bodies[case.body], case.omega, t_end=t_end, samples=samples,
                                method=case.method, frame=case.frame)
                runs[case.key] = traj
                save_figure(figure_omega(traj, title=case.label), stage / f"omega_{case.key}.png")
                write_csv(traj, stage / f"trajectory_{case.key}.csv")
                summary = trajectory_summary(traj)
                summary.update(case=case.key, label=case.label, omega0_given=list(case.omega), frame=case.frame)
                rows.append(summary)
                progress.step(case.label)
            grid = figure_omega_grid([(c.label, runs[c.key]) for c in CASES if c.method is None],
                                     suptitle="Angular velocity in the principal frame (cf. the seed's Figure 1)")
            save_figure(grid, stage / "omega_all.png", dpi=100)
            progress.step("combined figure")
            if animate:
                for key in ANIMATED:
                    case = next(c for c in CASES if c.key == key)
                    shown, frames = _animated_run(bodies[case.body], runs[key], t_end)
                    animate_ground_frame(bodies[case.body], shown, stage / f"ground_{key}{suffix}", title=case.label,
                                         max_frames=frames)
                    progress.step(f"ground-frame animation {key}")
                    animate_body_frame(bodies[case.body], shown, stage / f"body_{key}{suffix}", title=case.label,
                                       max_frames=frames)
                    progress.step(f"body-frame animation {key}")
            data = {
                "bodies": {k: mass_properties_dict(b) for k, b in bodies.items()},
                "cases": rows,
                "provenance": provenance(argv),
            }
            write_json(data, stage / "summary.json")
            atomic_write_text(stage / "summary.md", summary_markdown(bodies, rows))
            progress.step("summary")
    finally:
        progress.close()
    print(summary_markdown(bodies, rows))
    if animate and note:
        print(animation_plan(suffix, note))
    print(f"wrote {out}/ in {time.perf_counter() - start:.1f} s")
    return out


def _fmt(x, spec=".3g") -> str:
    return "-" if x is None else format(x, spec)


def summary_markdown(bodies: dict[str, Body], rows: list[dict]) -> str:
    """The study's summary table, with the findings stated in words."""
    seed = bodies["seed"].properties
    lines = ["# The T-handle study", ""]
    for key, body in bodies.items():
        p = body.properties
        axes = ", ".join(f"I{j + 1} = {p.principal_moments[j]:.6g} kg m^2 along {describe_axis(p.principal_axes[:, j])}"
                         for j in range(3))
        lines.append(f"- **{body.name}**: mass {p.mass:.6g} kg; {axes}.")
    lines += [
        "",
        f"For the seed's rods the shaft (z) is the **minor** axis and the crossbar "
        f"({describe_axis(seed.intermediate_axis)}) the **intermediate** one, so the seed's own runs "
        "[10, 0.1, 0.1] and [1, 0.1, 0.1] (x along the crossbar) spin about the intermediate axis and "
        "**flip**; the seed's total-tensor formula hides this (\"The seed study and its errors\", a page "
        "of tumble's documentation). For the space-station handle the shaft (z) is the intermediate axis.",
        "",
        "| case | method | axis | predicted | flips | flip period (s) | exact (s) | growth (1/s) | energy drift | abs(L) drift | L_world drift |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        s, d = r["stability"], r["drift"]
        lines.append(
            f"| {r['label']} | {r['method']} | {s['axis']} ({s['role']}) | {s['predicted']} | {s['flips']} "
            f"| {_fmt(s['flip_period'], '.4f')} | {_fmt(s['flip_period_exact'], '.4f')} | {_fmt(s['growth_rate'], '.4f')} "
            f"| {d['energy']:.1e} | {d['L_norm']:.1e} | {d['L_world']:.1e} |"
        )
    seed_rows = [r for r in rows if r["method"] == "seed"]
    if seed_rows:
        worst = max(r["drift"]["energy"] for r in seed_rows)
        best = max(r["drift"]["energy"] for r in rows if r["method"] != "seed")
        lines += ["", f"The seed's computation drifts the energy by up to {100 * worst:.2g}% in 20 s; "
                  f"the default method by at most {best:.1e} (relative)."]
    return "\n".join(lines) + "\n"
