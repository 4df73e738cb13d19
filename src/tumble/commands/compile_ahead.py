"""Compiling tumble's kernels ahead of their first use, into numba's on-disk cache (``tumble compile``).

numba compiles a kernel the first time it is called with new argument types and keeps the machine
code in its on-disk cache (:func:`tumble.jit.jit`), so only the first run of an install pays: the
first ``simulate`` with a torque spent ~5 s compiling on a fresh install and the first closed loop
~20 s, where the same first call that loads them from the cache takes ~0.7 s
(``benchmarks/bench_first_call.py``, 2026-12-01). numba offers no compiling ahead of time for its
just-in-time kernels (its ``pycc`` is deprecated and builds a separate extension module), but a
kernel compiled once is there for every later process: so this module runs each group of kernels
once, through small real runs of the public functions, in as many processes at a time as there
are cores. A real run compiles exactly the argument types that a user's
run of that kind asks for (numba compiles a kernel per type signature), which a list of signatures
kept by hand would have to follow; tests/test_compile_ahead.py holds the groups to the runs the
guides show.

The groups (:data:`GROUPS`), by what a user runs:

- ``simulate``: one body under built-in torques (constant, gravity gradient, rotors at constant
  spin), with ``dop853`` (the default), ``rk8`` and ``rk4``;
- ``orbit``: one body along an ellipse (the gravity gradient; a TLE's orbit runs the same kernel)
  or with a residual magnetic dipole in a uniform, dipole or IGRF field, the closed loop's kernel
  without a controller (:mod:`tumble.dynamics.control.free_loop`);
- ``damper``: a body with a nutation damper, ``rk8`` (what ``auto`` runs) and ``dop853``;
- ``batch``: :func:`tumble.simulate_batch` with a torque on every core (from
  :data:`tumble.jit.PARALLEL_BODIES` bodies), ``dop853`` and the fixed-step methods;
- ``control``: the closed loops of every control scenario that ships with ``tumble examples``.

Examples
--------
>>> from tumble.commands.compile_ahead import GROUPS
>>> [group.name for group in GROUPS]
['control', 'simulate', 'batch', 'orbit', 'damper']
"""

from __future__ import annotations

import concurrent.futures
import multiprocessing
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any, ClassVar

from .._html import Headline, headline_html, headline_repr

__all__ = ["GROUPS", "Compiled", "Group", "check_groups", "compile_ahead", "compile_group", "group_names", "processes"]


def _simulate() -> None:
    import tumble

    body = tumble.t_handle()
    torque = tumble.ConstantTorque((0.0, 0.0, 0.01))  # N m
    for method in ("dop853", "rk8", "rk4"):
        tumble.simulate(body, [0.1, 10.0, 0.1], t_end=0.1, torque=torque, method=method)


def _damper() -> None:
    import tumble

    damper = tumble.SphericalDamper(inertia=0.01, damping=0.01)  # kg m^2, N m s
    for method in ("auto", "dop853"):
        tumble.simulate(tumble.t_handle(), [10.0, 0.3, 0.2], t_end=0.1, damper=damper, method=method)


def _orbit() -> None:
    import tumble
    from tumble.dynamics import (CircularOrbit, DipoleField, IGRFField, KeplerOrbit, OrbitGravityGradient,
                                 ResidualDipole, UniformField)

    body, omega = tumble.t_handle(), [0.02, -0.03, 0.015]  # rad/s
    circle = CircularOrbit(altitude=500e3, inclination=1.7)  # m, rad
    torques = [OrbitGravityGradient(KeplerOrbit(8_000e3, 0.1, 0.9))]  # a (m), e, inclination (rad)
    # the loop's kernel is compiled for each kind of field (its arguments' types) and each method
    fields = [UniformField((0.0, 3e-5, 0.0)), DipoleField(circle)]  # T
    try:
        fields.append(IGRFField(circle, "2026-01-01T00:00:00"))
    except ImportError:  # without tumble[orbit] (ppigrf) no run can ask for the IGRF field's kernel
        pass
    torques += [ResidualDipole((0.1, 0.0, 0.0), field) for field in fields]  # A m^2
    for torque in torques:
        for method in ("dop853", "rk8", "rk4"):
            tumble.simulate(body, omega, t_end=10.0, torque=torque, method=method)


def _batch() -> None:
    import numpy as np

    import tumble
    from tumble.jit import PARALLEL_BODIES

    moments = np.tile([0.125, 0.3125, 0.4375], (PARALLEL_BODIES, 1))  # kg m^2, the T-handle's
    torque = tumble.ConstantTorque((0.0, 0.0, 0.01))  # N m
    for method in ("dop853", "rk8", "rk4"):
        tumble.simulate_batch(moments, [0.1, 10.0, 0.1], t_end=0.01, samples=2, torque=torque, method=method)


def _control() -> None:
    from importlib import resources

    from tumble.commands.scenario import run_scenario
    from tumble.io import load_scenario
    from tumble.io.examples import list_examples

    root = resources.files("tumble").joinpath("examples")
    for example in list_examples():
        if example.kind == "control":
            with resources.as_file(root.joinpath(example.path)) as path:
                try:
                    scenario = load_scenario(path)
                except ImportError:  # a TLE's orbit without tumble[orbit]: no run can ask for it here
                    continue
            run_scenario(replace(scenario, t_end=3.0))  # s: a few of the controller's periods


@dataclass(frozen=True)
class Group:
    """A group of kernels compiled together: its ``name``, a one-line ``description`` and the
    small runs that compile them (``run``, called with no arguments).

    Examples
    --------
    >>> from tumble.commands.compile_ahead import GROUPS
    >>> damper = GROUPS[-1]
    >>> damper.name, damper.description
    ('damper', 'a body with a nutation damper: rk8, dop853')
    """

    name: str
    description: str
    run: Callable[[], None]


#: The groups, in the order the processes take them: the closed loop (the longest) beside one body's,
#: whose kernels the batch then finds in the cache, and the orbits after the closed loop, whose
#: steps they share (on 2 cores, 32 s in all against 41-45 s in other orders; 2026-12-01).
GROUPS = (
    Group("control", "the closed loops of the control examples (B-dot, pointing, wheels, the MEKF)", _control),
    Group("simulate", "one body under built-in torques: dop853, rk8, rk4", _simulate),
    Group("batch", "simulate_batch with a torque on every core: dop853, rk8, rk4", _batch),
    Group("orbit", "one body along an ellipse (gravity gradient) or in a magnetic field (residual dipole)", _orbit),
    Group("damper", "a body with a nutation damper: rk8, dop853", _damper),
)


def group_names() -> list[str]:
    """The names of :data:`GROUPS`, in their order.

    Examples
    --------
    >>> from tumble.commands.compile_ahead import group_names
    >>> group_names()
    ['control', 'simulate', 'batch', 'orbit', 'damper']
    """
    return [group.name for group in GROUPS]


def check_groups(names: Sequence[str] | str | None, field: str = "group") -> list[str]:
    """The groups ``names`` asks for, each once, in the order given: every group for None (or an
    empty sequence), one for a string.

    Parameters
    ----------
    names : sequence of str, str or None
        Groups' names (:func:`group_names`).
    field : str
        What the caller calls them, for the error (``"GROUP"`` on the command line).

    Raises
    ------
    ValueError
        For a name that is not a group's, naming it and the groups.

    Examples
    --------
    >>> from tumble.commands.compile_ahead import check_groups
    >>> check_groups(["damper", "simulate", "damper"]), check_groups("batch"), len(check_groups(None))
    (['damper', 'simulate'], ['batch'], 5)
    >>> check_groups(["simulation"])
    Traceback (most recent call last):
    ...
    ValueError: group = 'simulation' is not a group of kernels; choose from control, simulate, batch, orbit, damper
    """
    known = group_names()
    chosen = [names] if isinstance(names, str) else list(dict.fromkeys(names or known))
    for name in chosen:
        if name not in known:
            raise ValueError(f"{field} = {name!r} is not a group of kernels; choose from {', '.join(known)}")
    return chosen


def processes(groups: int, jobs: int | None = None, field: str = "jobs") -> int:
    """How many processes :func:`compile_ahead` runs at a time for ``groups`` groups: ``jobs``
    (default the cores this process may use, :func:`tumble.jit.cores`), at most one a group.

    Raises
    ------
    ValueError
        For ``jobs`` not a whole number >= 1 (named ``field``).

    Examples
    --------
    >>> from tumble.commands.compile_ahead import processes
    >>> processes(5, 2), processes(1, 4)
    (2, 1)
    """
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise ValueError(f"{field} = {jobs!r} must be a whole number >= 1")
    from ..jit import cores

    return max(1, min(jobs or cores(), groups))


@dataclass(frozen=True)
class Compiled:
    """What compiling one group did: the group's ``name``, the ``kernels`` numba compiled (0 where
    the cache held them all), the time spent compiling them (``compile_s``, s) and the time the
    group's runs took in all (``seconds``, s; both wall clock, in the process that ran them).

    Examples
    --------
    >>> from tumble.commands.compile_ahead import Compiled
    >>> Compiled("damper", 10, 3.04, 4.5)
    Compiled(group damper, kernels compiled 10, compiling 3.04 s, in all 4.5 s)
    """

    HEADLINE: ClassVar[Headline] = (("name", "group", ""), ("kernels", "kernels compiled", ""),
                                    ("compile_s", "compiling", "s"), ("seconds", "in all", "s"))

    name: str
    kernels: int
    compile_s: float
    seconds: float

    __repr__ = headline_repr
    _repr_html_ = headline_html


def compile_group(name: str) -> Compiled:
    """Compile one group of :data:`GROUPS` in this process (its small runs), into numba's cache.

    Parameters
    ----------
    name : str
        A group's name (:func:`group_names`).

    Returns
    -------
    Compiled
        How many kernels were compiled and how long that took; kernels the cache held are loaded,
        not counted.

    Raises
    ------
    ValueError
        For a name that is not a group's.

    Examples
    --------
    >>> from tumble.commands.compile_ahead import compile_group
    >>> done = compile_group("simulate")   # a second call compiles nothing: the kernels are loaded
    >>> compile_group("simulate").kernels
    0
    """
    check_groups([name])
    group = next(group for group in GROUPS if group.name == name)
    from numba.core import event

    from ..jit import compile_counter

    counter = compile_counter()
    start = time.perf_counter()
    with event.install_listener("numba:compile", counter):
        group.run()
    return Compiled(name, counter.kernels, counter.seconds, time.perf_counter() - start)


def compile_ahead(names: Sequence[str] | None = None, *, jobs: int | None = None,
                  done: Callable[[Compiled], None] | None = None) -> list[Compiled]:
    """Compile the named groups (default all of :data:`GROUPS`) in ``jobs`` processes at a time
    (default: the cores this process may use), each group in one of them; with one at a time,
    in this process.

    Parameters
    ----------
    names : sequence of str, str, optional
        Groups' names (:func:`group_names`), or one; default every group (:func:`check_groups`).
    jobs : int, optional
        Processes at a time (>= 1); default :func:`tumble.jit.cores` (:func:`processes`).
    done : callable, optional
        Called with each group's :class:`Compiled` as it ends (to report progress).

    Returns
    -------
    list of Compiled
        One per group, in the order given.

    Raises
    ------
    ValueError
        For a name that is not a group's, or ``jobs`` below 1.
    RuntimeError
        Where a group's runs fail (naming the group and the error).

    Notes
    -----
    The processes are started by ``multiprocessing``'s "spawn", which imports the calling
    script again in each: called from a script of one's own (not from ``tumble compile``, a
    notebook or a prompt), call it under ``if __name__ == "__main__":``.

    Examples
    --------
    >>> from tumble.commands.compile_ahead import compile_ahead
    >>> [c.name for c in compile_ahead(["damper"], jobs=1)]
    ['damper']
    """
    chosen = check_groups(names)
    workers = processes(len(chosen), jobs)
    order = sorted(chosen, key=group_names().index)  # the order of GROUPS
    results: dict[str, Compiled] = {}
    if workers == 1:  # one at a time: here, without a process's start (~1.5 CPU-s of imports)
        for name in order:
            results[name] = _reported(name, compile_group, done)
        return [results[name] for name in chosen]
    # Fresh interpreters ("spawn", not a fork of this one, whose numba may be running threads), each
    # compiling one group after another: a kernel that two groups share is compiled or loaded once
    # per process, and a process's start (its imports, ~1.5 CPU-s) is paid once per core.
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(workers, mp_context=context) as pool:
        futures = {pool.submit(compile_group, name): name for name in order}
        for future in concurrent.futures.as_completed(futures):
            name = futures[future]
            results[name] = _reported(name, lambda _: future.result(), done)
    return [results[name] for name in chosen]


def _reported(name: str, compile_one: Callable[[str], Compiled], done: Callable[[Compiled], None] | None) -> Compiled:
    """``compile_one(name)``, told to ``done``; a failure of the group's own runs (tumble's defect,
    not the caller's input) as a RuntimeError naming the group."""
    try:
        compiled = compile_one(name)
    except Exception as exc:
        raise RuntimeError(f"compiling the group {name!r} failed: {type(exc).__name__}: {exc}") from exc
    if done is not None:
        done(compiled)
    return compiled
