"""A trajectory saved and read back (``tumble.io.write_npz`` and ``read_npz``): every field and
every derived quantity the same, for a torque-free run, a torqued one, rotors and a damper; the
file ``tumble simulate`` writes read back as the Python call's run; bad files refused by name."""

from __future__ import annotations

import numpy as np
import pytest

import tumble
from tumble.io import read_npz, write_npz

FIELDS = ("t", "omega", "quat", "moments", "principal_axes", "method", "auto", "torque_free", "body_name",
          "internal_momentum", "rotor_spin", "rotor_axial_moments", "motor_work", "damper_inertia", "damper_omega",
          "dissipated")
DERIVED = ("energy", "angular_momentum_world", "omega_world", "angular_momentum")


def _runs():
    wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.03, axis=(1, 0, 0), center=(0, 0, 0.5), spin_rate=500.0)
    return {
        "torque-free": tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=5.0, samples=51),
        "torqued": tumble.simulate(tumble.t_handle(), [0.1, 2.0, 0.1], t_end=5.0, samples=51, method="dop853",
                                   torque=tumble.ConstantTorque((0.0, 0.0, 0.01))),
        "rotors": tumble.simulate(tumble.Body([*tumble.t_handle().parts, wheel]), [0.1, 10, 0.1], t_end=2.0, samples=21),
        "damper": tumble.simulate(tumble.t_handle(), [10, 0.3, 0.2], t_end=20.0, samples=21,
                                  damper=tumble.SphericalDamper(inertia=0.01, damping=0.01)),
    }


@pytest.mark.parametrize("name", ["torque-free", "torqued", "rotors", "damper"])
def test_a_trajectory_comes_back_whole(tmp_path, name):
    run = _runs()[name]
    write_npz(run, tmp_path / "run.npz")
    back = read_npz(tmp_path / "run.npz")
    for field in FIELDS:
        a, b = getattr(run, field), getattr(back, field)
        assert (a is None and b is None) or np.array_equal(a, b), field
    for quantity in DERIVED:  # from the same samples: to round-off (the attitude is a Rotation of the saved quat)
        a = getattr(run, quantity)
        np.testing.assert_allclose(getattr(back, quantity), a, rtol=0, atol=1e-14 * np.abs(a).max(), err_msg=quantity)
    assert repr(back) == repr(run)
    present = [f for f in FIELDS if getattr(run, f) is not None]
    assert ("damper_omega" in present) == (name == "damper") and ("rotor_spin" in present) == (name == "rotors")


def test_the_file_of_tumble_simulate_reads_back_as_the_python_run(tmp_path):
    from tumble.cli import main

    assert main(["simulate", "t-handle", "--omega", "0.1", "10", "0.1", "--t-end", "5", "--samples", "51",
                 "--out", str(tmp_path / "run")]) == 0
    back = read_npz(tmp_path / "run" / "trajectory.npz")
    run = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=5.0, samples=51)
    assert np.array_equal(back.omega, run.omega) and np.abs(back.quat - run.quat).max() < 1e-15  # the command's quat: 1 ulp
    assert back.method_label == run.method_label and back.torque_free


def test_bad_files_are_refused_by_name(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"nope.npz: no such file$"):
        read_npz(tmp_path / "nope.npz")
    with pytest.raises(ValueError, match=r" is a folder, not a trajectory's NPZ file"):
        read_npz(tmp_path)
    text = tmp_path / "notes.npz"
    text.write_text("not a zip", encoding="utf-8")
    with pytest.raises(ValueError, match=r"notes.npz: not a trajectory's NPZ file"):
        read_npz(text)
    other = tmp_path / "other.npz"
    np.savez(other, t=np.arange(3.0), omega=np.zeros((3, 3)))
    with pytest.raises(ValueError, match=r"other.npz: no 'quat' array"):
        read_npz(other)
    bad = tmp_path / "bad.npz"
    np.savez(bad, t=np.arange(3.0), omega=np.zeros((2, 3)), quat=np.tile([0.0, 0.0, 0.0, 1.0], (3, 1)),
             moments=np.array([1.0, 2.0, 3.0]), principal_axes=np.eye(3), method=np.array("rk8"))
    with pytest.raises(ValueError, match=r"^.*bad.npz: omega has shape \(2, 3\) and dtype float64; a trajectory's of 3 "
                                         r"samples is finite floats of shape \(3, 3\)$"):
        read_npz(bad)


def test_a_file_from_before_torque_free_was_kept_reads_as_torqued(tmp_path):
    run = _runs()["torque-free"]
    old = tmp_path / "old.npz"
    np.savez(old, t=run.t, omega=run.omega, quat=run.quat, moments=run.moments, principal_axes=run.principal_axes,
             method=np.array(run.method))
    back = read_npz(old)
    assert not back.torque_free and not back.auto and back.body_name == "body"
