"""A Trajectory indexed by a slice, a mask or sample numbers: every per-sample array taken alike, the
body's constants kept, what is derived (energy, L_world, drift) that of the kept samples, and the
indices that make no trajectory refused in one line."""

from __future__ import annotations

import numpy as np
import pytest

import tumble

PER_SAMPLE = ("t", "omega", "quat", "internal_momentum", "rotor_spin", "motor_work", "damper_omega", "dissipated")
#: Computed again from the kept samples: scipy's Rotation.apply takes other arithmetic for stacks of other sizes
#: (measured: 3e-15 of the largest), so these agree to round-off
DERIVED = ("energy", "angular_momentum_world")


def _runs():
    rigid = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=5.0, samples=51)
    wheel = tumble.Rotor(mass=0.05, radius=0.1, length=0.01, axis=(1.0, 0.0, 0.0), center=(0.0, 0.0, 0.5),
                         spin_rate=0.0, spin_acceleration=20.0)
    rotors = tumble.simulate(tumble.Body([*tumble.t_handle().parts, wheel]), [0.1, 10.0, 0.1], t_end=5.0, samples=51)
    damped = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 2.5]), [1.0, 0.05, 0.0], t_end=50.0,
                             samples=51, damper=tumble.SphericalDamper(inertia=0.3, damping=0.3))
    return {"rigid": rigid, "rotors": rotors, "damper": damped}


@pytest.mark.parametrize("kind", ["rigid", "rotors", "damper"])
@pytest.mark.parametrize("index", [slice(10, None, 5), slice(-1, None), "mask", [0, 7, 50]],
                         ids=["slice", "last", "mask", "list"])
def test_every_per_sample_array_is_taken_alike(kind, index):
    run = _runs()[kind]
    if isinstance(index, str):
        index = run.t >= 2.5
    part = run[index]
    for name in PER_SAMPLE:
        whole = getattr(run, name)
        if whole is None:
            assert getattr(part, name) is None, name
        else:
            np.testing.assert_array_equal(getattr(part, name), whole[index], err_msg=name)
    for name in DERIVED:
        whole = getattr(run, name)
        np.testing.assert_allclose(getattr(part, name), whole[index], rtol=0, atol=1e-14 * np.max(np.abs(whole)),
                                   err_msg=name)
    np.testing.assert_array_equal(part.attitude.as_quat(), run.attitude[index].as_quat())
    assert (part.method, part.body_name, part.auto, part.torque_free) == (run.method, run.body_name, run.auto,
                                                                          run.torque_free)
    np.testing.assert_array_equal(part.moments, run.moments)
    assert part.rigid == run.rigid and part.damper_inertia == run.damper_inertia


def test_drift_is_that_of_the_kept_samples():
    run = _runs()["rigid"]
    late = run[25:]
    energy = late.energy
    assert late.drift["energy"] == pytest.approx(np.max(np.abs(energy - energy[0])) / abs(energy[0]), abs=1e-300)


@pytest.mark.parametrize(("index", "error", "pattern"), [
    (-1, TypeError, r"^traj\[-1\]: a Trajectory is indexed by a slice.*traj\[-1:\] keeps the sample"),
    (np.int64(3), TypeError, r"^traj\[np.int64\(3\)\]"),
    (slice(60, None), IndexError, r"^traj\[60:\] selects no sample of 51 \(t = 0\.\.\d+ s\)$"),
    (np.zeros(3, bool), IndexError, r"^the mask has 3 entries; the trajectory has 51 samples$"),
    (np.zeros((2, 2), int), TypeError, r"a Trajectory is indexed by"),
    # a mask that selects nothing is named, not printed (500 samples printed 3,900 characters)
    (np.zeros(51, bool), IndexError, r"^the mask selects no sample of 51 \(t = 0\.\.\d+ s\)$"),
    ([], IndexError, r"^traj\[\[\]\] selects no sample of 51"),
    (0.5, TypeError, r"^traj\[0\.5\]: .* sample numbers \(whole numbers from 0 to 50; .*traj\[traj\.t >= t0\]\)$"),
    ([0.5, 1.0], TypeError, r"^traj\[\[0\.5, 1\.0\]\]: .* sample numbers"),
    (60, TypeError, r"^traj\[60\]: .*whole numbers from 0 to 50"),  # not "traj[60:] keeps the sample": it has none
    (slice(None, None, -1), IndexError, r"^traj\[::-1\]: a Trajectory keeps its samples in time order"),
    ([5, 2], IndexError, r"^traj\[\[5, 2\]\]: a Trajectory keeps its samples in time order, each once"),
    ([3, 3], IndexError, r"^traj\[\[3, 3\]\]: a Trajectory keeps its samples in time order, each once"),
    ([0, 60], IndexError, r"^traj\[\[0, 60\]\]: a sample number beyond the 51 samples \(0 to 50\)$"),
])
def test_indices_that_make_no_trajectory_are_refused(index, error, pattern):
    with pytest.raises(error, match=pattern):
        _runs()["rigid"][index]


def test_a_trajectory_is_not_iterated_by_sample():
    with pytest.raises(TypeError, match="not iterable"):
        list(_runs()["rigid"])
