"""How an engine run ends, and the work it may take: one home for both, which the kernels, the
front and the Python path's budget read (imports nothing, so numba is not loaded with it).

Examples
--------
>>> from tumble.dynamics.engine.status import BUDGET_SPENT, MAX_EVALUATIONS, OK
>>> OK, BUDGET_SPENT, MAX_EVALUATIONS
(0, 2, 50000000)
"""

__all__ = ["BUDGET_SPENT", "MAX_ENGINE_EVALUATIONS", "MAX_EVALUATIONS", "NON_FINITE", "OK", "STEP_COLLAPSED"]

#: Right-hand sides a run may take before it is given up (about 40 per radian of rotation for
#: DOP853 at rtol 1e-12, so well above what ``simulate``'s rotation bound admits; it catches a
#: torque that grows during the run).
MAX_EVALUATIONS = 50_000_000
#: The same for a run of the compiled engine (:func:`~tumble.dynamics.engine.kernels.dop853`), whose
#: right-hand side costs ~30 ns against the Python path's ~20 us: about 3 minutes of it, above what
#: ``simulate``'s bound on a compiled run's rotation admits (40 a radian of 1e8 rad).
MAX_ENGINE_EVALUATIONS = 5_000_000_000
#: A run's status: done.
OK = 0
#: A run's status: the step fell below 10 ulp of t (scipy's smallest step).
STEP_COLLAPSED = 1
#: A run's status: :data:`MAX_EVALUATIONS` spent.
BUDGET_SPENT = 2
#: A run's status: the state overflowed (a NaN or inf at a sample).
NON_FINITE = 3
