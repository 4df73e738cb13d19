"""Butcher tableaux of the engine's explicit Runge-Kutta steppers, as plain arrays.

- ``RK4``: the classical 4th-order method (Kutta 1901; Hairer, Norsett & Wanner, *Solving
  Ordinary Differential Equations I*, 2nd ed., sec. II.1, table 1.2).
- ``DOP853``: Dormand & Prince's 8(5,3) pair with its 7th-order dense output (HNW sec. II.10
  and II.6), the coefficients taken from :class:`scipy.integrate.DOP853` (which copies them
  from Hairer's Fortran code), so the compiled stepper takes scipy's steps. Its 12-stage
  8th-order weights ``B`` are also the fixed-step ``"rk8"`` method.

Examples
--------
>>> from tumble.dynamics.engine.tableau import DOP853_A, DOP853_B, RK4_B
>>> DOP853_A.shape, round(float(DOP853_B.sum()), 14), RK4_B.tolist()
((16, 16), 1.0, [0.16666666666666666, 0.3333333333333333, 0.3333333333333333, 0.16666666666666666])
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import DOP853 as _SCIPY_DOP853

__all__ = ["DOP853_A", "DOP853_B", "DOP853_C", "DOP853_D", "DOP853_E3", "DOP853_E5", "RK4_A", "RK4_B", "RK4_C"]

#: The classical RK4's stage coefficients ``a_sr`` (4, 4), lower triangular.
RK4_A = np.array([[0.0, 0.0, 0.0, 0.0], [0.5, 0.0, 0.0, 0.0], [0.0, 0.5, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]])
#: Its weights ``b_s`` (4,): 1/6, 1/3, 1/3, 1/6.
RK4_B = np.array([1.0, 2.0, 2.0, 1.0]) / 6.0
#: Its nodes ``c_s`` (4,), fractions of the step.
RK4_C = np.array([0.0, 0.5, 0.5, 1.0])

#: The stage coefficients of all 16 stages (16, 16): 12 of the step, the 13th (the new state's
#: slope, FSAL), 3 for the dense output.
DOP853_A = np.zeros((16, 16))
DOP853_A[:12, :12] = _SCIPY_DOP853.A
DOP853_A[13:, :] = _SCIPY_DOP853.A_EXTRA
#: The 8th-order weights ``b_s`` of the 12 stages (also the fixed-step ``"rk8"``).
DOP853_B = np.ascontiguousarray(_SCIPY_DOP853.B, dtype=float)
#: The nodes ``c_s`` of all 16 stages, fractions of the step.
DOP853_C = np.zeros(16)
DOP853_C[:12] = _SCIPY_DOP853.C
DOP853_C[12] = 1.0
DOP853_C[13:] = _SCIPY_DOP853.C_EXTRA
#: The 3rd-order error estimate's weights over the 13 slopes (the 12 stages and the new state's).
DOP853_E3 = np.ascontiguousarray(_SCIPY_DOP853.E3, dtype=float)
#: The 5th-order error estimate's weights over the 13 slopes.
DOP853_E5 = np.ascontiguousarray(_SCIPY_DOP853.E5, dtype=float)
#: The dense output's coefficients (4, 16): the interpolant's terms of degree 4 to 7 (HNW sec. II.6).
DOP853_D = np.ascontiguousarray(_SCIPY_DOP853.D, dtype=float)
