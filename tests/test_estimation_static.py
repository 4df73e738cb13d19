"""TRIAD and QUEST (tumble.dynamics.estimation.static): the attitude against scipy's
``align_vectors`` to round-off, and the stated covariance against the spread of many seeded trials."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from scipy.stats import chi2

import tumble
from tumble.dynamics.estimation.static import quest, triad

N_TRIALS = 2000


def _noisy(b: np.ndarray, sigma: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Shuster's model: ``b + v``, ``v`` across ``b`` with covariance ``sigma^2 (I - b b^T)``, normalised."""
    v = sigma[..., None] * rng.standard_normal(b.shape)
    v -= np.sum(v * b, axis=-1, keepdims=True) * b
    out = b + v
    return out / np.linalg.norm(out, axis=-1, keepdims=True)


def _directions(rng: np.random.Generator, shape: tuple[int, ...]) -> np.ndarray:
    v = rng.standard_normal((*shape, 3))
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def test_top_level_names():
    assert tumble.triad is triad and tumble.quest is quest


def test_quest_is_align_vectors_to_round_off():
    rng = np.random.default_rng(1)
    for n in (2, 3, 7):
        r = _directions(rng, (n,))
        truth = Rotation.random(random_state=rng)
        b = _noisy(truth.inv().apply(r), np.full(n, 1e-2), rng)
        w = rng.uniform(0.5, 2.0, n) * 1e4
        A, _ = quest(b, r, w)
        ref, _ = Rotation.align_vectors(r, b, weights=w)
        assert (A * ref.inv()).magnitude() < 1e-13


def test_triad_is_align_vectors_primary_to_round_off():
    """scipy's infinite weight keeps the first vector exactly and the second's plane: TRIAD itself."""
    rng = np.random.default_rng(2)
    r = _directions(rng, (50, 2))
    truth = Rotation.random(50, random_state=rng)
    b = _noisy(np.stack([truth.inv().apply(r[:, 0]), truth.inv().apply(r[:, 1])], axis=1), np.full((50, 2), 1e-2), rng)
    A, P = triad(b, r)
    assert P.shape == (50, 3, 3)
    for k in range(50):
        ref, _ = Rotation.align_vectors(r[k], b[k], weights=[np.inf, 1.0])
        assert (A[k] * ref.inv()).magnitude() < 1e-12
        one, P1 = triad(b[k], r[k])
        assert (one * A[k].inv()).magnitude() < 1e-15 and np.allclose(P1, P[k], rtol=1e-14)


def test_quest_covariance_is_scipys_sensitivity_turned_to_the_body():
    """scipy's sensitivity (reference axes, weights normalised to their mean) is an independent
    computation of the same information matrix."""
    rng = np.random.default_rng(3)
    r = _directions(rng, (4,))
    truth = Rotation.random(random_state=rng)
    b = truth.inv().apply(r)
    w = np.array([1e4, 4e4, 2.5e5, 1e6])
    A, P = quest(b, r, w)
    _, _, S = Rotation.align_vectors(r, b, weights=w, return_sensitivity=True)
    M = A.as_matrix()
    assert np.allclose(M @ P @ M.T * w.mean(), S, rtol=1e-9)


def _nees(A: Rotation, truth: Rotation, P: np.ndarray) -> np.ndarray:
    err = (A.inv() * truth).as_rotvec()   # A_true = A_est exp(dtheta), body axes
    return np.einsum("...i,...ij,...j->...", err, np.linalg.inv(P), err)


def _check_band(nees: np.ndarray) -> None:
    n = len(nees)
    lo, hi = chi2.ppf([0.025, 0.975], 3 * n) / n
    assert lo < nees.mean() < hi, (nees.mean(), lo, hi)
    inside = np.mean(nees < chi2.ppf(0.95, 3))
    assert abs(inside - 0.95) < 3.0 * np.sqrt(0.95 * 0.05 / n), inside


def test_triad_covariance_covers_the_truth():
    """2,000 seeded trials: the average NEES lies in chi2(3 N) / N's 95 % band and 95 % of the
    errors lie inside the 95 % ellipsoid, with unequal noises and random geometry."""
    rng = np.random.default_rng(4)
    r = _directions(rng, (N_TRIALS, 2))
    truth = Rotation.random(N_TRIALS, random_state=rng)
    sig = np.stack([rng.uniform(1e-3, 5e-3, N_TRIALS), rng.uniform(5e-3, 2e-2, N_TRIALS)], axis=1)
    b = np.stack([truth.inv().apply(r[:, 0]), truth.inv().apply(r[:, 1])], axis=1)
    bm = _noisy(b, sig, rng)
    A, P = triad(bm, r, sig)
    _check_band(_nees(A, truth, P))


def test_quest_covariance_covers_the_truth():
    rng = np.random.default_rng(5)
    nees = np.empty(N_TRIALS)
    for k in range(N_TRIALS):
        n = 2 + k % 3
        r = _directions(rng, (n,))
        truth = Rotation.random(random_state=rng)
        sig = rng.uniform(1e-3, 2e-2, n)
        A, P = quest(_noisy(truth.inv().apply(r), sig, rng), r, 1.0 / sig**2)
        nees[k] = _nees(A, truth, P)
    _check_band(nees)


@pytest.mark.parametrize(("call", "message"), [
    (lambda: triad([[1, 0, 0], [2, 0, 0]], [[1, 0, 0], [0, 1, 0]]),
     r"body_vectors = \[\[1.0, 0.0, 0.0\], \[1.0, 0.0, 0.0\]\] are parallel: TRIAD needs two distinct directions"),
    (lambda: triad([[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [0, 1, 0]]),
     r"body_vectors\[0\] = \[0.0, 0.0, 0.0\] must not be zero"),
    (lambda: triad([[1, 0, 0], [0, 1, 0]], [[1, 0, 0], [0, 1, 0]], sigmas=(0.0, 1.0)),
     r"sigmas = \[0.0, 1.0\] must be two positive finite numbers \(rad\)"),
    # swapped forms (a walkthrough of docs/estimation.md, 2026-12-03: sigmas of 1e4 and 1e6 rad, and 9.5-31.6 rad
    # from weights of sigmas, were returned without a word)
    (lambda: triad([[1, 0, 0], [0, 1, 0]], [[1, 0, 0], [0, 1, 0]], sigmas=(1e6, 1e4)),
     r"^sigmas = \[1000000.0, 10000.0\]: each at most pi rad \(a direction's angular noise\); QUEST's weights 1/sigma\^2 "
     r"given as TRIAD's sigmas\?$"),
    (lambda: quest([[1, 0, 0], [0, 1, 0]], [[1, 0, 0], [0, 1, 0]], [1e-3, 1e-2]),
     r"^weights = \[0.001, 0.01\]: each at least 1/pi\^2 rad\^-2 \(1/sigma\^2, sigma at most pi rad\); TRIAD's sigmas "
     r"given as QUEST's weights\?$"),
    (lambda: quest([[1, 0, 0]], [[1, 0, 0]], [1.0]), r"must both have shape \(n, 3\) with n >= 2"),
    (lambda: quest([[1, 0, 0], [0, 1, 0]], [[1, 0, 0], [0, 1, 0]], [1.0, -1.0]),
     r"weights = \[1.0, -1.0\] must be 2 positive finite numbers"),
    (lambda: quest([[1, 0, 0], [-1, 0, 0]], [[1, 0, 0], [-1, 0, 0]], [1.0, 1.0]), r"all parallel"),
    (lambda: quest([[1, 0, float("nan")], [0, 1, 0]], [[1, 0, 0], [0, 1, 0]], [1.0, 1.0]),
     r"body_vectors\[0\] = \[1.0, 0.0, nan\] must be finite numbers"),
])
def test_bad_input_one_line(call, message):
    with pytest.raises(ValueError, match=message) as info:
        call()
    assert "\n" not in str(info.value)
