"""``tumble compile`` (issue 40, first use): the kernels compiled ahead are those the first runs use.

A group's small runs must compile every kernel, for every argument type, that a user's run of
that kind calls, or the user's first run compiles after all. Checked here in a fresh process: the
group's runs first, then the runs the guides show (the tour's first torque ``simulate``, a sum of
torques, sample times, a rotor, each method; dampers; an ellipse's gravity gradient and a
residual dipole in the dipole and IGRF fields; batches on every core); not one tumble kernel
may gain a compiled signature (numba's dispatchers' ``overloads``, whether compiled or loaded
from the cache) in the second part. Whether numba's cache then serves another process is
numba's and tests/test_jit_cache.py's.
"""

from __future__ import annotations

import re
import subprocess
import sys
import textwrap

import pytest

from tumble.cli import EXIT_OK, EXIT_USAGE, main
from tumble.commands.compile_ahead import GROUPS, check_groups, compile_ahead, compile_group, group_names
from limits import HANG_S

#: Run in a fresh interpreter: the groups named in argv[1:], then the users' runs; prints the kernels
#: that gained a signature in the groups' runs (one line), then those that gained one in the users'
#: runs, one per line, and "none" where none did.
_PROBE = textwrap.dedent("""
    import gc, sys
    import numpy as np
    import tumble
    from numba.core.dispatcher import Dispatcher
    from tumble.commands.compile_ahead import compile_group
    from tumble.jit import PARALLEL_BODIES

    def signatures():
        return {f"{d.py_func.__module__}.{d.py_func.__qualname__}": set(d.overloads) for d in gc.get_objects()
                if isinstance(d, Dispatcher) and d.py_func.__module__.startswith("tumble")}

    start = signatures()
    for name in sys.argv[1:]:
        compile_group(name)
    before = signatures()
    print(" ".join(sorted(name for name, sigs in before.items() if sigs - start.get(name, set()))))
    body = tumble.t_handle()
    torque = tumble.ConstantTorque((0.0, 0.0, 0.01))
    gg = tumble.GravityGradient(orbit_period=5400.0)
    if "simulate" in sys.argv:
        tumble.simulate(body, [0, 0, 0], t_end=5.0, torque=torque)   # the tour's first torque run
        tumble.simulate(body, [0.1, 10, 0.1], t_end=2.0, torque=[gg, torque], dt=0.01)
        tumble.simulate(body, [0.1, 10, 0.1], times=[0.5, 1.7864, 3.5728], torque=gg + torque,
                        attitude0=[0.0, 0.0, 0.38268343, 0.92387953])
        for method in ("auto", "dop853", "rk8", "rk4"):
            tumble.simulate(body, [0.1, 10, 0.1], t_end=2.0, torque=gg, method=method, rtol=1e-8)
        tumble.simulate(body, [0.1, 10, 0.1], t_end=2.0, torque=torque, method="rk4", step=0.01)
        wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.03, axis=(1, 0, 0), center=(0, 0, 0.5), spin_rate=500.0)
        tumble.simulate(tumble.Body([*body.parts, wheel]), [0.1, 10, 0.1], t_end=2.0)
    if "damper" in sys.argv:
        for damping in (0.01, 100.0):   # N m s: a stiff one too
            for method in ("auto", "dop853", "rk8"):
                damper = tumble.SphericalDamper(inertia=0.01, damping=damping)
                if method != "rk8" or damping < 1.0:
                    tumble.simulate(body, [10, 0.3, 0.2], t_end=1.0, damper=damper, method=method)
    if "orbit" in sys.argv:
        from tumble.dynamics import (CircularOrbit, DipoleField, IGRFField, KeplerOrbit, OrbitGravityGradient,
                                     ResidualDipole)
        orbit = KeplerOrbit(12_000e3, 0.4, 0.9)   # docs/gravity-gradient.md's
        ellipse = OrbitGravityGradient(orbit)
        tumble.simulate(body, [0.02, -0.03, 0.015], t_end=60.0, torque=ellipse)
        tumble.simulate(body, [0.02, -0.03, 0.015], t_end=60.0, torque=ellipse, method="dop853", rtol=1e-9)
        circle = CircularOrbit(altitude=600e3, inclination=0.5)
        fields = [DipoleField(circle)]
        try:
            fields.append(IGRFField(circle, "2026-11-25T00:00:00"))
        except ImportError:   # without tumble[orbit] no run can ask for it
            pass
        for field in fields:
            dipole = ResidualDipole((0.0, 0.2, 0.0), field)
            tumble.simulate(body, [0.1, 0.0, 0.0], t_end=60.0, torque=dipole, dt=1.0)
            tumble.simulate(body, [0.1, 0.0, 0.0], t_end=60.0, torque=[dipole, ellipse], method="rk4")
    if "batch" in sys.argv:
        rng = np.random.default_rng(1)
        n = PARALLEL_BODIES + 3
        moments = np.sort(rng.uniform(0.5, 1.0, (n, 3)), axis=1)
        omega = rng.normal(size=(n, 3))
        from scipy.spatial.transform import Rotation
        quat = Rotation.random(n, random_state=1).as_quat()
        for method, options in (("dop853", {}), ("rk8", {"step": 0.05}), ("rk4", {"step": 0.05})):
            tumble.simulate_batch(moments, [0.1, 10.0, 0.1], t_end=1.0, samples=3, torque=torque, method=method, **options)
            tumble.simulate_batch(moments, omega, t_end=1.0, samples=3, attitude0=quat, torque=gg, method=method, **options)
    after = signatures()
    gained = sorted(name for name, sigs in after.items() if sigs - before.get(name, set()))
    print("\\n".join(gained) or "none")
""")


def test_a_groups_kernels_are_all_that_its_users_first_runs_call():
    """The users' runs gain no signature after the groups'; and the probe sees a gain where there
    is one: the groups' own runs gained the engine's and the loop's kernels (compiled or loaded)."""
    done = subprocess.run([sys.executable, "-c", _PROBE, "simulate", "damper", "orbit", "batch"], capture_output=True,
                          text=True, timeout=HANG_S)
    assert done.returncode == 0, done.stderr
    by_groups, *by_users = done.stdout.splitlines()
    assert by_users == ["none"]
    assert {"tumble.dynamics.engine.kernels.dop853", "tumble.dynamics.engine.lanes.lanes_rk8",
            "tumble.dynamics.control.compiled_loop._loop"} <= set(by_groups.split()), by_groups


def test_the_groups_names_and_errors():
    assert group_names() == [group.name for group in GROUPS] == ["control", "simulate", "batch", "orbit", "damper"]
    with pytest.raises(ValueError, match=r"group = 'simulation' is not a group of kernels; choose from control"):
        compile_group("simulation")
    with pytest.raises(ValueError, match=r"group = 'all' is not a group"):
        compile_ahead(["all"])
    with pytest.raises(ValueError, match=r"jobs = 0 must be a whole number >= 1"):
        compile_ahead(["damper"], jobs=0)
    with pytest.raises(ValueError, match=r"jobs = 1.5 must be a whole number >= 1"):
        compile_ahead(["damper"], jobs=1.5)
    assert check_groups("damper") == ["damper"]   # one name, not its letters


def test_the_command_lists_the_groups_and_refuses_bad_input_in_one_line(capsys):
    assert main(["compile", "--list"]) == EXIT_OK
    listed = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in listed] == group_names()
    assert main(["compile", "simulation"]) == EXIT_USAGE
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "GROUP = 'simulation' is not a group of kernels; choose from control" in err
    with pytest.raises(SystemExit) as exited:   # argparse's own refusal, in one line
        main(["compile", "--jobs", "two"])
    assert exited.value.code == EXIT_USAGE
    assert capsys.readouterr().err == "tumble compile: error: argument --jobs: invalid int value: 'two'\n"
    assert main(["compile", "damper", "--jobs", "0"]) == EXIT_USAGE
    assert capsys.readouterr().err == "tumble: error: --jobs = 0 must be a whole number >= 1\n"
    # --list lists the groups named and checks what it is given (a walkthrough: it listed all and took --jobs -1)
    assert main(["compile", "--list", "damper"]) == EXIT_OK
    assert [line.split()[0] for line in capsys.readouterr().out.splitlines()] == ["damper"]
    assert main(["compile", "--list", "--jobs", "-1"]) == EXIT_USAGE
    assert capsys.readouterr().err == "tumble: error: --jobs = -1 must be a whole number >= 1\n"


def test_the_command_compiles_a_group_and_says_so_as_it_ends(capsys):
    """`tumble compile damper`: one group (in the command's own process, one at a time); its kernels
    compiled or found in the cache, said as it ends."""
    assert main(["compile", "damper", "--jobs", "1"]) == EXIT_OK
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("compiling 1 group of kernels into numba's cache (") and out[0].endswith("1 at a time")
    assert re.fullmatch(r"  damper +(\d+ kernels compiled in +\d+\.\d s|in the cache already) +"
                        r"a body with a nutation damper: rk8, dop853", out[1]), out[1]
    assert out[2].startswith("done in ") and "loads its kernels from the cache" in out[2]
    assert len(out) == 3


def test_the_command_fails_in_one_line_where_no_folder_can_hold_the_cache(capsys, monkeypatch):
    import tumble.jit

    monkeypatch.setattr(tumble.jit, "kernel_cache_folder", lambda: None)
    assert main(["compile"]) == 1
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1
    assert captured.err.startswith("tumble: failed: no folder here can hold numba's cache")
