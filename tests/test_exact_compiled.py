"""The compiled exact flow of large batches (methods/compiled_exact.py) against the double-double
path (exact_kernel.EllipticMotion, itself checked against mpmath in test_exact.py): omega,
attitude and the flip interval of random bodies, next to the separatrix, symmetric and nearly
symmetric tops, steady spins; the bodies it leaves to double-double; the parallel kernel."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics.methods import exact_batch
from tumble.dynamics.methods import exact_parameters as ep


def _bodies(rng, n):
    I = np.sort(rng.uniform(0.1, 1.0, (n, 3)), axis=1)
    I[:, 2] = np.minimum(I[:, 2], I[:, 0] + I[:, 1])
    return I, rng.normal(size=(n, 3)), Rotation.random(n, random_state=int(rng.integers(1 << 30))).as_quat()


def _errors(I, w, q, t):
    """Compiled against double-double: (done, relative omega error, attitude error in rad) per body."""
    kernels = ep.compiled_kernels()
    N = len(I)
    omega, quat, done = np.zeros((N, len(t), 3)), np.zeros((N, len(t), 4)), np.empty(N, dtype=np.bool_)
    kernels.motion_serial(I, w, q, t, True, omega, quat, done)
    ref_w, ref_q = exact_batch._double_double(I, w, q, t, True)
    err_w = np.max(np.linalg.norm(omega - ref_w, axis=2) / np.linalg.norm(ref_w, axis=2), axis=1)
    turn = Rotation.from_quat(quat[done].reshape(-1, 4)).inv() * Rotation.from_quat(ref_q[done].reshape(-1, 4))
    err_q = np.zeros(N)
    err_q[done] = turn.magnitude().reshape(-1, len(t)).max(axis=1)
    return done, err_w, err_q


def test_random_bodies_agree_with_double_double_to_1e_12():
    """Random moments and spins (both sides of the separatrix) over 20 s and over 100 s (phases up
    to ~1000 rad): measured 4e-14 and 1.2e-13 rad at 20 s, 5.6e-13 and 5.8e-13 rad at 100 s."""
    I, w, q = _bodies(np.random.default_rng(9), 4000)
    for t_end, bound in ((20.0, 3e-13), (100.0, 1e-12)):
        done, err_w, err_q = _errors(I, w, q, np.array([0.0, t_end / 3.0, t_end]))
        assert done.mean() > 0.95
        assert np.max(err_w[done]) <= bound and np.max(err_q[done]) <= bound


def test_next_to_the_separatrix_the_double_double_path_takes_over():
    """k'^2 from 1e-6 to 0.3: above KP2_MIN the compiled path holds (measured 1.4e-14 and
    1.5e-13 rad); below it the body is left to double-double, and the batch gives each body the
    double-double answer there."""
    rng = np.random.default_rng(5)
    n = 3000
    I = np.sort(rng.uniform(0.1, 1.0, (n, 3)), axis=1)
    eps = 10.0 ** rng.uniform(-3.5, -0.5, n)
    w = np.stack([eps * rng.normal(size=n), rng.choice([-1.0, 1.0], n) * rng.uniform(0.5, 3.0, n),
                  eps * rng.normal(size=n)], axis=1)
    q = np.tile([0.0, 0.0, 0.0, 1.0], (n, 1))
    kp2 = ep._parameters(w, I).m1
    done, err_w, err_q = _errors(I, w, q, np.array([0.0, 5.0, 20.0]))
    kernels = ep.compiled_kernels()
    assert np.all(done[kp2 >= 1.01 * kernels.KP2_MIN]) and not np.any(done[kp2 < 0.99 * kernels.KP2_MIN])
    assert 0.2 < np.mean(done) < 0.8
    assert np.max(err_w[done]) <= 1e-13 and np.max(err_q[done]) <= 5e-13
    # the batch front: every body as the double-double path gives it, the marked ones exactly, after
    # the start, which is the state as given (the double-double path's was up to 2.5e-14 off it)
    omega, quat = exact_batch.free_rotation_batch(I, w, q, np.array([0.0, 5.0, 20.0]))
    ref_w, ref_q = exact_batch._double_double(I[~done], w[~done], q[~done], np.array([0.0, 5.0, 20.0]), True)
    np.testing.assert_allclose(omega[~done, 1:], ref_w[:, 1:], rtol=0, atol=1e-15 * np.max(np.abs(ref_w)))
    np.testing.assert_allclose(quat[~done, 1:], ref_q[:, 1:], rtol=0, atol=1e-14)
    assert np.array_equal(omega[:, 0], w) and np.array_equal(quat[:, 0], q)
    np.testing.assert_allclose(ref_q[:, 0], q[~done], rtol=0, atol=5e-14)


@pytest.mark.parametrize("kind", ["I1 = I2", "I2 = I3", "I2 near I3", "steady"])
def test_tops_and_steady_spins(kind):
    rng = np.random.default_rng(3)
    I, w, q = _bodies(rng, 1000)
    if kind == "I1 = I2":
        I[:, 1] = I[:, 0]
    elif kind == "I2 = I3":
        I[:, 1] = I[:, 2]
    elif kind == "I2 near I3":  # p tiny, |n| huge: Legendre's Pi itself (measured 3.9e-13 rad)
        I[:, 1] = I[:, 2] * (1.0 - 10.0 ** rng.uniform(-12.0, -3.0, 1000))
    else:
        w[:] = 0.0
        w[np.arange(1000), rng.integers(0, 3, 1000)] = 5.0 * rng.normal(size=1000)
    done, err_w, err_q = _errors(I, w, q, np.array([0.0, 5.0, 20.0]))
    assert np.all(done)
    assert np.max(err_w) <= 1e-13 and np.max(err_q) <= 1e-12


def test_components_whose_squares_underflow_are_left_to_double_double():
    kernels = ep.compiled_kernels()
    I = np.array([[1.0, 2.0, 3.0]] * 3)
    w = np.array([[1e-200, 1e-200, 1.0], [1e-170, 0.5, 1.0], [1e-60, 1e-60, 1e-60]])
    q = np.tile([0.0, 0.0, 0.0, 1.0], (3, 1))
    t = np.array([0.0, 3.0])
    omega, quat, done = np.zeros((3, 2, 3)), np.zeros((3, 2, 4)), np.empty(3, dtype=np.bool_)
    kernels.motion_serial(I, w, q, t, True, omega, quat, done)
    assert done.tolist() == [False, True, False]
    ref_w, ref_q = exact_batch._double_double(I, w, q, t, True)
    np.testing.assert_allclose(omega[1], ref_w[1], rtol=0, atol=1e-15)
    # cn(0) ~ 1e-170: u0 on a half period's edge, where q and -q (one rotation) both come out
    sign = np.sign(np.sum(quat[1] * ref_q[1], axis=-1))[:, None]
    np.testing.assert_allclose(sign * quat[1], ref_q[1], rtol=0, atol=1e-14)


def test_a_phase_beyond_the_limit_is_left_to_double_double():
    kernels = ep.compiled_kernels()
    I, w = np.array([[1.0, 2.0, 3.0]] * 2), np.array([[0.3, 1.0, 0.2]] * 2)
    t = np.array([0.0, 10.0 * kernels.PHASE_MAX])
    omega, quat, done = np.empty((2, 2, 3)), np.empty((2, 2, 4)), np.empty(2, dtype=np.bool_)
    kernels.motion_serial(I, w, np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)), t, True, omega, quat, done)
    assert not np.any(done)


def test_the_batch_front_runs_compiled_from_compiled_bodies_and_on_every_core(monkeypatch):
    """free_rotation_batch at N >= COMPILED_BODIES (compiled, on every core) against N below it
    (double-double), omega alone equal to omega with the attitude, the parallel kernel bit for
    bit the one-thread kernel."""
    I, w, q = _bodies(np.random.default_rng(1), 700)
    t = np.array([0.0, 7.0])
    slow = exact_batch.free_rotation_batch(I, w, q, t)
    monkeypatch.setattr(exact_batch, "COMPILED_BODIES", 100)
    fast = exact_batch.free_rotation_batch(I, w, q, t)
    alone, none = exact_batch.free_rotation_batch(I, w, q, t, attitude=False)
    assert none is None
    np.testing.assert_array_equal(alone, fast[0])
    scale = np.max(np.abs(slow[0]), axis=(1, 2))[:, None, None]
    assert np.max(np.abs(fast[0] - slow[0]) / scale) <= 1e-13
    np.testing.assert_allclose(fast[1], slow[1], rtol=0, atol=1e-13)  # the same sign (phi in [-pi, pi])
    kernels = ep.compiled_kernels()
    runs = []
    for kernel in (kernels.motion_serial, kernels.motion_parallel):
        out = np.empty((700, 2, 3)), np.empty((700, 2, 4)), np.empty(700, dtype=np.bool_)
        kernel(I, w, q, t, True, *out)
        runs.append(out)
    done = runs[0][2]
    np.testing.assert_array_equal(done, runs[1][2])
    for a, b in zip(runs[0][:2], runs[1][:2]):
        np.testing.assert_array_equal(a[done], b[done])


def test_elliptic_parameters_and_the_flip_interval_of_many_motions(monkeypatch):
    """From COMPILED_BODIES motions the parameters are compiled: each field within 1e-13 of the
    double-double one (1 - m next to KP2_MIN loses eps / (1 - m) to the gap's cancellation), and
    the flip interval 2 K / p within 1e-14; shapes as the double-double path gives them."""
    from tumble.analysis import flip_interval

    rng = np.random.default_rng(2)
    monkeypatch.setattr(ep, "COMPILED_BODIES", 1000)
    I, w, _ = _bodies(rng, 1010)
    w[:5] = [0.0, 0.0, 1.0]  # steady: double-double says what it has
    w[5:10, ::2] *= 1e-6  # next to the separatrix: double-double
    many = ep.elliptic_parameters(w, I)
    ref = ep._parameters(w, I)
    for name, a, b in zip(many._fields, many, ref):
        a, b = np.asarray(a, float), np.asarray(b, float)
        assert a.shape == b.shape, name
        np.testing.assert_allclose(a, b, rtol=1e-13, atol=0, err_msg=name)
    shaped = ep.elliptic_parameters(w.reshape(2, -1, 3), I.reshape(2, -1, 3))
    assert shaped.amplitudes.shape == (2, len(w) // 2, 3) and shaped.upper.dtype == bool
    T = flip_interval(w, I)
    one = np.array([flip_interval(w[i], I[i]) for i in range(0, len(w), 7)])
    np.testing.assert_allclose(T[::7], one, rtol=1e-14)


def test_a_large_batch_refuses_a_phase_beyond_max_phase_naming_the_body(monkeypatch):
    """The compiled kernel takes no phase beyond PHASE_MAX; the bodies it leaves are checked
    against MAX_PHASE (1e24 rad) as a small batch checks every body, named by their place."""
    monkeypatch.setattr(exact_batch, "COMPILED_BODIES", 10)
    I, w, q = _bodies(np.random.default_rng(8), 40)
    w[27] *= 1e13  # |omega| ~ 1e13 rad/s for 1e12 s: beyond 1e24 rad
    with pytest.raises(ValueError, match=r"omega0\[27\]"):
        exact_batch.free_rotation_batch(I, w, q, np.array([0.0, 1e12]))


def test_jacobis_functions_by_the_gauss_transformation_match_scipy():
    """compiled_exact._sncndn (Bulirsch's descending Gauss transformation) and K from its AGM
    against mpmath (scipy's ellipj is off by 1.5e-15 in dn at k'^2 = 1e-3), up to the half
    period's edge: measured 3e-16."""
    import mpmath
    from scipy.special import ellipk

    kernels = ep.compiled_kernels()
    work = np.empty(kernels.WORK)
    for kp2 in (1e-3, 0.01, 0.3, 0.9, 1.0):
        levels, mean = kernels._gauss(kp2, work)
        K = np.pi / (2.0 * mean)
        assert abs(K / ellipk(1.0 - kp2) - 1.0) < 5e-16
        m = 1 - mpmath.mpf(kp2)
        for u in np.concatenate([np.linspace(-K, K, 21), K * (1.0 - 10.0 ** -np.arange(1.0, 16.0, 2.0))]):
            ref = [float(mpmath.ellipfun(f, mpmath.mpf(float(u)), m=m)) for f in ("sn", "cn", "dn")]
            np.testing.assert_allclose(kernels._sncndn(float(u), levels, mean, work), ref, rtol=0, atol=1e-15)
