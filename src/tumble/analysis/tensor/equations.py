"""The calibration's parallel-axis equations: the rotor's inertia and the device's tensor and
centre of mass adjusted to them (:func:`rotor_inertia_from`).

The pooled fits give ``x = (D, c_d, P, c_dp)``: the device alone's tensor ``D = I_d / J_r`` and
centre ``c_d``, the device with the proof's ``P = I_dp / J_r`` and ``c_dp`` (tensors in units of
``J_r``, centres in m, sensor frame; :mod:`~tumble.analysis.tensor.calibrate`). The
parallel-axis theorem about the accelerometer (Goldstein, Poole & Safko, *Classical Mechanics*,
3rd ed., sec. 5.3; ``S(d) = |d|^2 E - d d^T``) holds six equations

    ``g(x, J_r) = J_r (P - D) - B = 0``,  ``B = I_p + m_p S(c_p) + m_d S(c_d) - M S(c_dp)``,

with ``c_p = (M c_dp - m_d c_d) / m_p`` the proof's centre, ``M = m_d + m_p``; the centres'
terms are the two bodies' reduced mass about each other,
``m_d S(c_d) + m_p S(c_p) - M S(c_dp) = (m_d M / m_p) S(c_d - c_dp)``.

**An adjustment, not only an estimate of J_r.** The equations are conditions on the measured
``x`` with one unknown, ``J_r``: the Gauss-Helmert model (Förstner & Wrobel, *Photogrammetric
Computer Vision*, Springer 2016, ch. 4). Linearised at the measurement (``G = dg/dx``, ``x``'s
covariance ``Sigma``, weights ``W = (G Sigma G^T)^-1``), ``J_r`` minimises ``r^T W r``,
``r = g(x, J_r)``, with ``chi^2 = r^T W r`` on 6 - 1 = 5 degrees of freedom, and the measured
quantities adjusted to the equations are ``x_hat = x - Sigma G^T W r``, whose covariance
``Sigma - Sigma G^T Q G Sigma`` (``Q`` the weights less ``J_r``'s share) is smaller than
``Sigma``: the equations carry information of their own. Where it matters is the device's centre
**along the rotor's axis**. The device-alone throws spin 70-95 % about that axis once the rotor
has spun up, and a centripetal reading ``w x (w x r)`` of a spin about ``z`` holds no ``r_z``: the
accelerometer alone left ``c_d`` loose along ``z`` (std 0.15-0.75 mm, 0.02-0.1 mm across). The
rates say nothing of any centre (a gyrostat's motion about its centre of mass does not depend on
where that is, nor on where the rotor sits: its momentum relative to the body is ``J_r Omega a``
wherever it turns). The proof's known tensor does: its centre 43 mm along ``z`` from the
device's, ``B_xx`` and ``B_yy`` move by ``2 (m_d M / m_p) d_z`` per metre of ``d_z``
(``d = c_d - c_dp``), 8.6e-6 kg m^2 a millimetre for the synthetic device, some 40 times the
tensors' uncertainty, and ``B_zz`` does not, so ``J_r``'s common scale cannot take it up. The
adjusted ``c_d`` is the proof set's better seen centre plus that offset, combined with the
device-alone one: on the 25 realistic devices of benchmarks/tensor_coverage.py its std along
``z`` is 0.12-0.36 mm (median 0.19), where the device-alone throws' own is 0.15-0.75 mm, and its
errors are 0.75 std rms along ``z``, all within 1.96 std (the device-alone centre's: 0.74 std
rms). It rests on the proof's tensor as stated, as ``J_r`` does: a proof ``xx`` stated 0.5 %
off moves it by ~0.1 mm.

The weights, ``J_r``'s variance and the Birge ratio use the whole covariance, the centres'
shared sensors' parts in it; the consistency check (the calibration's ``chi2_dof``) the
centres' statistical covariance only (:mod:`~tumble.analysis.tensor.calibrate`). A ``chi^2 / 5``
above 1 inflates the adjusted quantities' covariance by it (Birge, as
:mod:`~tumble.analysis.tensor.pool` does). The covariances are propagated through the map's
Jacobian (central differences; JCGM 100:2008, sec. 5.1), the weights and the gain held.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ...mass.tensor import point_mass_inertia
from ...typing import FloatArray
from .device import Proof
from .estimate import vector_of

__all__ = ["Adjusted", "rotor_inertia_from"]


def _known(x: FloatArray, m_d: float, m_p: float, Ip: FloatArray) -> FloatArray:
    """``B`` of the module docstring from ``x = (D, c_d, P, c_dp)``."""
    c_d, c_dp = x[6:9], x[15:18]
    M = m_d + m_p
    c_p = (M * c_dp - m_d * c_d) / m_p
    return vector_of(Ip + point_mass_inertia(m_p, c_p) + point_mass_inertia(m_d, c_d) - point_mass_inertia(M, c_dp))


def _solve(x: FloatArray, m_d: float, m_p: float, Ip: FloatArray, W: FloatArray,
           gain: FloatArray | None = None) -> tuple[FloatArray, float]:
    """``(J_r, I_d entries, c_d)`` and ``chi^2`` from ``x = (D, c_d, P, c_dp)`` (module docstring);
    with the ``gain`` ``Sigma G^T W``, ``D`` and ``c_d`` adjusted to the equations."""
    B = _known(x, m_d, m_p, Ip)
    A = x[9:15] - x[:6]
    J = float(A @ W @ B) / float(A @ W @ A)
    r = J * A - B
    z = x if gain is None else x - gain @ r
    return np.concatenate([[J], J * z[:6], z[6:9]]), float(r @ W @ r)


def _jacobian(f, x: FloatArray) -> FloatArray:
    """Central differences of ``f`` at ``x = (D, c_d, P, c_dp)``: steps 1e-6 of the entries' size, 1 nm for the centres."""
    size = np.r_[np.full(6, np.abs(x[:6]).max()), np.full(3, 1e-3), np.full(6, np.abs(x[9:15]).max()), np.full(3, 1e-3)]
    cols = []
    for k in range(18):
        d = np.zeros(18)
        d[k] = 1e-6 * size[k]
        cols.append((f(x + d) - f(x - d)) / (2 * d[k]))
    return np.array(cols).T


def _weighted(x: FloatArray, cov_x: FloatArray, m_d: float, m_p: float,
              Ip: FloatArray) -> tuple[float, FloatArray, FloatArray]:
    """``chi^2``, the weights ``W`` and the gain ``Sigma G^T W`` from ``x`` with covariance
    ``cov_x`` (two passes: ``G`` depends on ``J_r``)."""
    B = _known(x, m_d, m_p, Ip)
    W = np.eye(6) / max(float(B @ B), 1e-300)
    for _ in range(2):
        J = _solve(x, m_d, m_p, Ip, W)[0][0]
        G = _jacobian(lambda z: J * (z[9:15] - z[:6]) - _known(z, m_d, m_p, Ip), x)
        W = np.linalg.pinv(G @ cov_x @ G.T)
    return _solve(x, m_d, m_p, Ip, W)[1], W, cov_x @ G.T @ W


class Adjusted(NamedTuple):
    """What :func:`rotor_inertia_from` gives.

    Attributes
    ----------
    value : ndarray, shape (10,)
        ``J_r`` (kg m^2), the device's tensor entries ``xx, yy, zz, xy, xz, yz`` (kg m^2) and its
        centre ``c_d`` (m), adjusted to the equations.
    cov : ndarray, shape (10, 10)
        Their covariance, the centres' shared sensors' parts in it.
    check : float
        ``chi^2 / 5`` with the centres' statistical covariance only (the calibration's check).
    center_cov : ndarray, shape (3, 3)
        ``c_d``'s covariance from the statistical parts only: an object's centre carries the
        sensors' parts through its own columns, the same device's.

    Examples
    --------
    A tuple, unpacked where it is made:

    >>> import numpy as np
    >>> from tumble.analysis.tensor.equations import Adjusted
    >>> value, cov, check, center_cov = Adjusted(np.zeros(10), np.eye(10), 1.2, np.eye(3))
    >>> check, value.shape, center_cov.shape
    (1.2, (10,), (3, 3))
    """

    value: FloatArray
    cov: FloatArray
    check: float
    center_cov: FloatArray


def rotor_inertia_from(x: FloatArray, cov_x: FloatArray, device_mass: float, proof: Proof,
                       center_cov: FloatArray | None = None, adjust: bool = True) -> Adjusted:
    """``J_r`` and the device's tensor and centre adjusted to the parallel-axis equations, their
    covariance and the consistency check's ``chi^2 / 5`` (module docstring).

    Parameters
    ----------
    x : ndarray, shape (18,)
        ``D`` (6, units of ``J_r``), ``c_d`` (3, m), ``P`` (6), ``c_dp`` (3).
    cov_x : ndarray, shape (18, 18)
    device_mass : float
        kg.
    proof : Proof
    center_cov : ndarray, shape (6, 6), optional
        The centres' ``(c_d, c_dp)`` sensors' part
        (:func:`~tumble.analysis.tensor.calibrate.shared_center_covariance`): in the weights,
        the covariance and the Birge ratio, not in the check's ``chi^2`` nor ``center_cov``.
    adjust : bool, optional
        Whether ``D`` and ``c_d`` are adjusted to the equations (default); without, they are the
        measured ones, with their covariance (for equations the check refuses: adjusted to
        equations that do not hold, a proof mounted turned gave the device a tensor no body has).

    Returns
    -------
    Adjusted

    Examples
    --------
    A device of ``J_r = 2e-6`` that is a point at the origin, and a proof of 1e-4 kg m^2 at its centre:

    >>> import numpy as np
    >>> from tumble.analysis.tensor import Proof
    >>> from tumble.analysis.tensor.equations import rotor_inertia_from
    >>> proof = Proof(0.3, [1e-4, 1e-4, 1e-4])
    >>> D = np.array([10.0, 10.0, 10.0, 0, 0, 0])   # the device alone, units of J_r
    >>> P = D + np.array([50.0, 50.0, 50.0, 0, 0, 0])   # with the proof: + 1e-4 / 2e-6
    >>> y, cov, ratio, _ = rotor_inertia_from(np.r_[D, 0, 0, 0, P, 0, 0, 0], np.eye(18) * 1e-6, 0.1, proof)
    >>> float(y[0].round(15)), y[1:4].round(12).tolist()
    (2e-06, [2e-05, 2e-05, 2e-05])
    """
    m_d, m_p, Ip = float(device_mass), float(proof.mass), proof.inertia
    check = _weighted(x, cov_x, m_d, m_p, Ip)[0] / 5.0
    full = np.array(cov_x, float, copy=True)
    if center_cov is not None:
        idx = np.r_[6:9, 15:18]
        full[np.ix_(idx, idx)] += center_cov
    chi2, W, gain = _weighted(x, full, m_d, m_p, Ip)
    gain = gain if adjust else None
    y = _solve(x, m_d, m_p, Ip, W, gain)[0]
    Jy = _jacobian(lambda z: _solve(z, m_d, m_p, Ip, W, gain)[0], x)
    birge = max(1.0, chi2 / 5.0)
    stat = Jy[7:10] @ np.asarray(cov_x, float) @ Jy[7:10].T
    return Adjusted(y, Jy @ full @ Jy.T * birge, check, 0.5 * (stat + stat.T) * birge)
