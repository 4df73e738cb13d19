"""The calibration's statistics (issue #42): the throws' agreement scales the pooled covariance
(tumble.analysis.tensor.pool.birge_factor), and the centres' shared sensors' parts enter the
rotor inertia's variance but not its consistency check
(tumble.analysis.tensor.equations.rotor_inertia_from)."""

from __future__ import annotations

import numpy as np

from tumble.analysis.tensor import Proof
from tumble.analysis.tensor.calibrate import shared_center_covariance
from tumble.analysis.tensor.equations import rotor_inertia_from
from tumble.analysis.tensor.pool import SHRINK_DOF, Pooled, birge_factor

# chi^2 quantiles from a printed table (Abramowitz & Stegun, Handbook of Mathematical Functions,
# table 26.8): P(chi^2_nu <= q) = 0.05
CHI2_05 = {24: 13.848, 30: 18.493}


def test_birge_factor_against_the_tables_quantiles():
    assert abs(birge_factor(0.2, 5) - 0.2 * 24 / CHI2_05[24]) < 1e-4
    assert abs(birge_factor(0.3, 6) - 0.3 * 30 / CHI2_05[30]) < 1e-4
    assert birge_factor(3.0, 2) == 3.0 and birge_factor(3.0, 9) == 3.0  # the Birge ratio, any number of throws
    assert birge_factor(0.2, 4) == 1.0 and 6 * (4 - 1) < SHRINK_DOF  # too few degrees of freedom to shrink by
    assert birge_factor(0.95, 9) == 1.0  # the bound above 1: no shrink
    assert birge_factor(float("nan"), 1) == 1.0


def test_the_shrunk_variance_covers_the_true_one_in_95_percent():
    """The claim of the bound: where each throw states 5 times its true variance, the agreement is
    ``0.2 chi^2_dof / dof``; the factor is at least the true 0.2 in 95 % of sets (binomial std 0.2 %
    on 10^4 sets)."""
    rng = np.random.default_rng(7)
    for throws in (5, 8):
        dof = 6 * (throws - 1)
        ratios = 0.2 * rng.chisquare(dof, 10_000) / dof
        held = np.mean([birge_factor(r, throws) >= 0.2 for r in ratios])
        assert 0.94 <= held <= 0.96


def _point_device():
    """A device of ``J_r = 2e-6`` whose centre is 10 mm below the accelerometer and a proof 30 mm above,
    the pooled fits exact (``J_r (P - D) = B`` of calibrate's docstring)."""
    proof = Proof(0.3, [1e-4, 1.2e-4, 1.5e-4])
    m_d, m_p, J = 0.1, 0.3, 2e-6
    c_d, c_p = np.array([0.0, 0.0, -0.010]), np.array([0.0, 0.0, 0.030])
    M = m_d + m_p
    c_dp = (m_d * c_d + m_p * c_p) / M
    Id = np.diag([3e-5, 4e-5, 6e-5])
    S = lambda d: float(d @ d) * np.eye(3) - np.outer(d, d)  # noqa: E731
    Idp = Id + m_d * S(c_d - c_dp) + np.diag(proof.inertia.diagonal()) + m_p * S(c_p - c_dp)
    vec = lambda I: np.r_[I.diagonal(), I[0, 1], I[0, 2], I[1, 2]]  # noqa: E731
    x = np.r_[vec(Id) / J, c_d, vec(Idp) / J, c_dp]
    return x, m_d, proof, J


def test_the_centres_shared_scale_widens_j_r_but_not_the_check():
    """An accelerometer 1 % off along z moves both centres by 1 %: with their shared part stated
    (shared_center_covariance), the weights see it and J_r's interval holds the error it makes,
    while the consistency check's chi^2 (the centres' statistical covariance) is what it was."""
    x, m_d, proof, J = _point_device()
    off = x.copy()
    off[8] *= 1.01
    off[17] *= 1.01  # c_d and c_dp along z, both 1 % long
    cov = np.diag(np.r_[np.full(6, 1e-4), np.full(3, (2e-5) ** 2), np.full(6, 1e-4), np.full(3, (2e-5) ** 2)])
    Sa = np.diag([0.0, 0.0, 0.01 * x[8]])  # 1 % of the z scale, in each centre's own length
    Sb = np.diag([0.0, 0.0, 0.01 * x[17]])
    a = Pooled(np.zeros(6), np.eye(6), x[6:9], np.eye(3), 1.0, 5, center_columns=Sa)
    b = Pooled(np.zeros(6), np.eye(6), x[15:18], np.eye(3), 1.0, 5, center_columns=Sb)
    C = shared_center_covariance(a, b)
    assert C is not None and np.isclose(C[2, 5], Sa[2, 2] * Sb[2, 2])
    y0, cov0, check0, _ = rotor_inertia_from(off, cov, m_d, proof)
    y1, cov1, check1, _ = rotor_inertia_from(off, cov, m_d, proof, C)
    assert check1 == check0  # the check: the centres' statistical covariance only
    assert check0 > 4  # stated without the shared scale, the 1 % looks like a mis-stated proof: Birge widens J_r
    assert abs(y1[0] - J) < 0.1 * abs(y0[0] - J)  # the weights know the shared scale: J_r hardly moves
    assert cov1[0, 0] < 0.25 * cov0[0, 0]  # and its interval is not widened for what the centres lacked
    assert abs(y1[0] - J) / np.sqrt(cov1[0, 0]) < 1.0
    # and with the centres exact, the shared part changes nothing of J_r itself
    y2, _, _, _ = rotor_inertia_from(x, cov, m_d, proof, C)
    assert np.isclose(y2[0], J, rtol=1e-9)


def test_the_proofs_equations_fix_the_devices_centre_along_the_offset():
    """The device-alone throws spin about the rotor's axis and leave its centre loose along it; the
    proof's known tensor, mounted 30 mm along that axis, fixes the offset between the two sets'
    centres (tumble.analysis.tensor.equations). The alone set's centre 1 mm off along z with 2 mm
    stated, the tensors to 0.01 %: adjusted to within 0.05 mm of the truth, its std under 0.1 mm,
    and the rotor's inertia unchanged. With the tensors stated 3000 times looser (30 %) the
    equations carry little and the centre stays near where the accelerometer put it."""
    x, m_d, proof, J = _point_device()
    off = x.copy()
    off[8] += 1e-3
    tensor_var = lambda rel: np.r_[(rel * x[:6].max()) ** 2 * np.ones(6)]  # noqa: E731
    for rel, within in ((1e-4, 5e-5), (0.3, None)):
        v = tensor_var(rel)
        cov = np.diag(np.r_[v, np.full(3, (2e-5) ** 2), v, np.full(3, (2e-5) ** 2)])
        cov[8, 8] = (2e-3) ** 2
        y, cov_y, _, cov_c = rotor_inertia_from(off, cov, m_d, proof)
        if within is not None:
            assert abs(y[9] - x[8]) < within and np.sqrt(cov_c[2, 2]) < 1e-4
            assert abs(y[0] / J - 1) < 1e-3
            assert abs(y[9] - x[8]) < 2 * np.sqrt(cov_c[2, 2])  # the truth within its interval
        else:
            assert abs(y[9] - off[8]) < 0.3e-3 and np.sqrt(cov_c[2, 2]) > 1.5e-3
    # not adjusted: the measured centre and its covariance, as the check refuses a proof that is not as stated
    y, _, _, cov_c = rotor_inertia_from(off, cov, m_d, proof, adjust=False)
    assert y[9] == off[8] and np.isclose(cov_c[2, 2], cov[8, 8])
