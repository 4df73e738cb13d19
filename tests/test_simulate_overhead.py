"""The memos that cut simulate's fixed cost (issue 18, target b) change no answer.

Each memo is checked against what it stands for: the protocol answers against ``isinstance``
(and an instance that gains a member later), the initial attitude against scipy's own product,
the rotors' spins against a fresh evaluation, and whole runs against runs of a fresh, equal body
(which no memo has seen).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics.models.rotors import Rotors
from tumble.dynamics.models.torques import (
    BoundsSpin,
    ConstantTorque,
    NeedsBody,
    TorqueModel,
    conforms,
)
from tumble.dynamics.simulate import _initial_quat
from tumble.validation import check_rotation

TAU = (0.01, -0.02, 0.015)


def _wheel_body(spin_rate=200.0):
    return tumble.Body([tumble.Box(mass=120.0, size=(1.2, 1.0, 0.8)),
                        tumble.Rotor(mass=2.0, radius=0.15, length=0.05, axis=(0, 0, 1), spin_rate=spin_rate)])


class _Open:
    """A torque model that is not a frozen dataclass: an instance may gain ``bind`` later."""

    frame = "body"

    def __call__(self, t, omega, attitude):
        return np.zeros(3)


def test_conforms_answers_as_isinstance_and_rechecks_what_an_instance_can_change():
    models = [ConstantTorque(TAU), tumble.GravityGradient(orbit_period=5400.0), _Open(),
              lambda t, w, a: np.zeros(3), None, 3.0]
    for _ in range(2):  # the second round answers from the memo where there is one
        for model in models:
            for protocol in (TorqueModel, NeedsBody, BoundsSpin):
                assert conforms(model, protocol) == isinstance(model, protocol), (model, protocol)
    late = _Open()
    assert not conforms(late, NeedsBody)
    late.bind = lambda body: late  # the instance, not its class, now has the member
    assert conforms(late, NeedsBody) and isinstance(late, NeedsBody)
    assert not conforms(_Open(), NeedsBody)


@pytest.mark.parametrize("attitude", [None, (0.0, 0.0, 0.0, 1.0), (-0.0, 0.0, 0.0, 1.0),
                                      tuple(Rotation.from_euler("xyz", [0.3, -0.2, 0.5]).as_quat())])
def test_the_initial_attitude_is_scipys_product_bit_for_bit(attitude):
    axes = tumble.t_handle().principal_axes
    design_to_world = Rotation.identity() if attitude is None else Rotation.from_quat(check_rotation("a", attitude))
    expected = (design_to_world * Rotation.from_matrix(axes)).as_quat()
    raw = None if attitude is None else np.array(check_rotation("a", attitude)).tobytes()
    for _ in range(2):
        got = np.array(_initial_quat(raw, np.asarray(axes, float).tobytes()))
        assert got.tobytes() == expected.tobytes()


def test_check_rotation_keeps_scipys_unit_quaternion():
    q = [0.1, -0.2, 0.3, 0.9272]  # within the tolerance of unit norm: renormalised by scipy
    expected = tuple(float(x) for x in Rotation.from_quat(q).as_quat())
    assert check_rotation("q", q) == expected and check_rotation("q", np.array(q)) == expected
    assert np.signbit(check_rotation("q", [-0.0, 0.0, 0.0, 1.0])[0]) == np.signbit(Rotation.from_quat([-0.0, 0.0, 0.0, 1.0]).as_quat()[0])


def test_a_bodys_rotors_are_kept_and_their_spins_handed_out_as_copies():
    body = _wheel_body()
    rotors = Rotors.of(body)
    assert Rotors.of(body) is rotors and Rotors.of(body.properties) is None
    t = np.linspace(0.0, 2.0, 5)
    spins = rotors.spins(t)
    np.testing.assert_array_equal(spins, np.full((5, 1), 200.0))
    spins[:] = -1.0  # the caller's copy
    np.testing.assert_array_equal(rotors.spins(t), np.full((5, 1), 200.0))
    np.testing.assert_array_equal(rotors.spins(0.5), [200.0])  # another time, another entry


def test_a_spin_function_is_called_at_every_evaluation():
    calls = []

    def spin(t):
        calls.append(1)
        return 100.0 + 0.0 * np.asarray(t, float)

    rotors = Rotors.of(_wheel_body(spin))
    t = np.linspace(0.0, 1.0, 3)
    rotors.spins(t)
    before = len(calls)
    rotors.spins(t)
    assert len(calls) > before  # an impure function would see each call, as before


@pytest.mark.parametrize("spec", ["wheel", "rigid"])
def test_repeated_runs_equal_a_fresh_bodys_run_bit_for_bit(spec):
    def make():
        return _wheel_body() if spec == "wheel" else tumble.MassProperties.from_moments([10.0, 12.0, 15.0])

    body = make()
    attitude = Rotation.from_euler("xyz", [0.3, -0.2, 0.5])
    kw = {"t_end": 2.0, "samples": 11, "attitude0": attitude, "method": "geometric6", "torque": ConstantTorque(TAU), "step": 0.025}
    runs = [tumble.simulate(body, [0.05, 1.0, 0.05], **kw) for _ in range(3)]
    fresh = tumble.simulate(make(), [0.05, 1.0, 0.05], **kw)
    for run in runs:
        for name in ("t", "omega", "quat", "internal_momentum", "rotor_spin", "rotor_axial_moments", "motor_work"):
            a, b = getattr(run, name), getattr(fresh, name)
            assert (a is None and b is None) or np.asarray(a).tobytes() == np.asarray(b).tobytes(), name
    if spec == "wheel":  # a run's own arrays are its own: changing one leaves the next run alone
        runs[0].rotor_axial_moments[:] = 0.0
        runs[0].rotor_spin[:] = 0.0
        again = tumble.simulate(body, [0.05, 1.0, 0.05], **kw)
        assert again.rotor_axial_moments.tobytes() == fresh.rotor_axial_moments.tobytes()
        assert again.rotor_spin.tobytes() == fresh.rotor_spin.tobytes()
