"""Calibrating the device: the rotor's inertia, the device's tensor and its centre of mass
(:func:`calibrate_device`).

Without a known rotor inertia the throws determine tensors in units of ``J_r`` only: the
gyrostat's equations are unchanged when ``I``, ``h`` (so ``J_r``) and ``L`` are multiplied by
one factor. So both sets of throws are fitted with ``J_r = 1``:

- the device **alone** gives ``D = I_d / J_r`` and its centre ``c_d`` (the accelerometer gives
  centres in metres, whatever ``J_r``);
- the device with the **proof** body gives ``P = I_dp / J_r`` and the centre ``c_dp`` of both,
  hence the proof's centre ``c_p = (M c_dp - m_d c_d) / m_p``, ``M = m_d + m_p``.

The parallel-axis theorem about the accelerometer (Goldstein, Poole & Safko, *Classical
Mechanics*, 3rd ed., sec. 5.3; ``S(d) = |d|^2 E - d d^T``),
``J_r P + M S(c_dp) = J_r D + m_d S(c_d) + I_p + m_p S(c_p)``, gives six equations for ``J_r``:

    ``J_r (P - D) = B``,  ``B = I_p + m_p S(c_p) + m_d S(c_d) - M S(c_dp)``,

solved by weighted least squares (weights the inverse covariance of ``J_r (P - D) - B``, two
passes) with ``chi^2`` on 5 degrees of freedom; a ``chi^2 / 5 > 1`` inflates ``J_r``'s variance
(Birge, as in :mod:`~tumble.analysis.tensor.pool`). Then ``I_d = J_r D``. All the
uncertainties (the pooled ``D``, ``P``, ``c_d``, ``c_dp``; the proof taken as exact) are
propagated to ``(J_r, I_d, c_d)`` through the map's Jacobian (central differences; the law of
propagation of uncertainty, JCGM 100:2008, sec. 5.1).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ...mass.tensor import point_mass_inertia
from ...typing import FloatArray
from .device import Device, Proof, Throw
from .estimate import tensor_of, vector_of
from .pool import pool_throws

__all__ = ["calibrate_device", "rotor_inertia_from"]


def _known(x: FloatArray, m_d: float, m_p: float, Ip: FloatArray) -> FloatArray:
    """``B`` of the module docstring from ``x = (D, c_d, P, c_dp)``."""
    c_d, c_dp = x[6:9], x[15:18]
    M = m_d + m_p
    c_p = (M * c_dp - m_d * c_d) / m_p
    return vector_of(Ip + point_mass_inertia(m_p, c_p) + point_mass_inertia(m_d, c_d) - point_mass_inertia(M, c_dp))


def _solve(x: FloatArray, m_d: float, m_p: float, Ip: FloatArray, W: FloatArray) -> tuple[FloatArray, float]:
    """``(J_r, I_d entries, c_d)`` and ``chi^2`` from ``x = (D, c_d, P, c_dp)`` (module docstring)."""
    B = _known(x, m_d, m_p, Ip)
    A = x[9:15] - x[:6]
    J = float(A @ W @ B) / float(A @ W @ A)
    r = J * A - B
    return np.concatenate([[J], J * x[:6], x[6:9]]), float(r @ W @ r)


def _jacobian(f, x: FloatArray) -> FloatArray:
    """Central differences of ``f`` at ``x = (D, c_d, P, c_dp)``: steps 1e-6 of the entries' size, 1 nm for the centres."""
    size = np.r_[np.full(6, np.abs(x[:6]).max()), np.full(3, 1e-3), np.full(6, np.abs(x[9:15]).max()), np.full(3, 1e-3)]
    cols = []
    for k in range(18):
        d = np.zeros(18)
        d[k] = 1e-6 * size[k]
        cols.append((f(x + d) - f(x - d)) / (2 * d[k]))
    return np.array(cols).T


def rotor_inertia_from(x: FloatArray, cov_x: FloatArray, device_mass: float, proof: Proof) -> tuple[FloatArray, FloatArray, float]:
    """``(J_r, I_d entries, c_d)``, their covariance and ``chi^2 / 5`` from the pooled fits (module docstring).

    Parameters
    ----------
    x : ndarray, shape (18,)
        ``D`` (6, units of ``J_r``), ``c_d`` (3, m), ``P`` (6), ``c_dp`` (3).
    cov_x : ndarray, shape (18, 18)
    device_mass : float
        kg.
    proof : Proof

    Examples
    --------
    A device of ``J_r = 2e-6`` that is a point at the origin, and a proof of 1e-4 kg m^2 at its centre:

    >>> import numpy as np
    >>> from tumble.analysis.tensor import Proof
    >>> from tumble.analysis.tensor.calibrate import rotor_inertia_from
    >>> proof = Proof(0.3, [1e-4, 1e-4, 1e-4])
    >>> D = np.array([10.0, 10.0, 10.0, 0, 0, 0])   # the device alone, units of J_r
    >>> P = D + np.array([50.0, 50.0, 50.0, 0, 0, 0])   # with the proof: + 1e-4 / 2e-6
    >>> y, cov, ratio = rotor_inertia_from(np.r_[D, 0, 0, 0, P, 0, 0, 0], np.eye(18) * 1e-6, 0.1, proof)
    >>> float(y[0].round(15)), y[1:4].round(12).tolist()
    (2e-06, [2e-05, 2e-05, 2e-05])
    """
    m_d, m_p, Ip = float(device_mass), float(proof.mass), proof.inertia
    B = _known(x, m_d, m_p, Ip)
    W = np.eye(6) / max(float(B @ B), 1e-300)
    for _ in range(2):
        J = _solve(x, m_d, m_p, Ip, W)[0][0]
        G = _jacobian(lambda z: J * (z[9:15] - z[:6]) - _known(z, m_d, m_p, Ip), x)
        W = np.linalg.pinv(G @ cov_x @ G.T)
    y, chi2 = _solve(x, m_d, m_p, Ip, W)
    Jy = _jacobian(lambda z: _solve(z, m_d, m_p, Ip, W)[0], x)
    cov = Jy @ cov_x @ Jy.T
    ratio = chi2 / 5.0
    inflate = np.ones(10)
    inflate[0] = np.sqrt(max(1.0, ratio))
    return y, cov * np.outer(inflate, inflate), ratio


def calibrate_device(device: Device, alone: Sequence[Throw], proof_throws: Sequence[Throw], proof: Proof, *,
                     saturation: float | None = None) -> Device:
    """The device with ``rotor_inertia``, ``inertia``, ``center_of_mass`` and their ``_std`` estimated
    (module docstring).

    Parameters
    ----------
    device : Device
        Its mass and rotor axis (anything else it holds is replaced).
    alone : sequence of Throw
        Throws of the device alone.
    proof_throws : sequence of Throw
        Throws of the device with the proof body fixed to it.
    proof : Proof
        The proof body's known mass and tensor (about its centre, sensor axes).
    saturation : float, optional
        The gyroscope's range, rad/s (else found from the data).

    Returns
    -------
    Device

    Raises
    ------
    ValueError
        Bad input (no throws, not throws, not a device or proof).
    NoThrowError
        No throw of a set could be fitted (:class:`tumble.analysis.tensor.NoThrowError`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Device, calibrate_device
    >>> from tumble.analysis.tensor.synthetic import ROTOR_INERTIA, combine, synthetic_throw, true_device, true_proof
    >>> proof, placed = true_proof()
    >>> alone = [synthetic_throw(s, true_device(), rotor_top=300.0, spin=(3.0, 6.0)) for s in (1, 2, 3)]
    >>> with_proof = [synthetic_throw(s, combine(true_device(), placed)) for s in (4, 5, 6)]
    >>> cal = calibrate_device(Device(0.10067, [0, 0, -1]), alone, with_proof, proof)
    >>> bool(abs(cal.rotor_inertia / ROTOR_INERTIA - 1) < 0.02), bool(cal.rotor_inertia_std < 0.02 * ROTOR_INERTIA)
    (True, True)
    """
    if not isinstance(device, Device):
        raise ValueError(f"device must be a Device, got {type(device).__name__}")
    if not isinstance(proof, Proof):
        raise ValueError(f"proof must be a Proof, got {type(proof).__name__}")
    a, _ = pool_throws(alone, device.rotor_axis, 1.0, saturation=saturation)
    p, _ = pool_throws(proof_throws, device.rotor_axis, 1.0, saturation=saturation)
    x = np.concatenate([a.inertia, a.center, p.inertia, p.center])
    cov = np.zeros((18, 18))
    cov[:6, :6], cov[6:9, 6:9], cov[9:15, 9:15], cov[15:, 15:] = a.inertia_cov, a.center_cov, p.inertia_cov, p.center_cov
    y, cov_y, _ = rotor_inertia_from(x, cov, device.mass, proof)
    std = np.sqrt(np.maximum(np.diag(cov_y), 0.0))
    return Device(device.mass, device.rotor_axis, float(y[0]), float(std[0]), tensor_of(y[1:7]), tensor_of(std[1:7]),
                  y[7:10], std[7:10])
