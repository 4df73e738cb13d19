"""A mission's mode logic: detumble with the magnetorquers, then point with the wheels.

After separation a small satellite tumbles at a few to tens of deg/s; the first mode of its
attitude control damps that spin with B-dot and magnetorquers (Stickler & Alfriend 1974; gain
of Avanzini & Giulietti 2012: :class:`~tumble.dynamics.control.bdot.BDot`), and only when the
rate is low does a fine mode take over and point with reaction wheels (MRP feedback, Schaub &
Junkins, *Analytical Mechanics of Space Systems*, 4th ed., sec. 8.3-8.4:
:class:`~tumble.dynamics.control.controllers.MRPFeedback`), optionally with the magnetorquers unloading
the wheels (:class:`~tumble.dynamics.control.controllers.MomentumDumping`). This is the usual mode
sequence of small-satellite attitude control: a detumbling mode on magnetometer and
magnetorquers after deployment, then pointing modes with the wheels (for example the SAGE
CubeSat's "ADCS operational modes", https://sage-docs.pages.dev/engineering/space-segment/ADCS/ADCS-Operational-Modes,
and the ArcticSat detumbling analysis, which tests the "transition to sun-pointing after
successfully detumbling"). The hand-over rule below (a rate threshold held for a dwell time)
is the obvious design, not taken from one source.

**The switch.** :class:`DetumbleThenPoint` reads the gyroscope at every control step; once
``|omega_gyro| < switch_rate`` at every step of a window of ``dwell`` s (``dwell / period + 1``
steps in a row; a step at or above the threshold starts the window again) it hands over to the
pointing controller at that step and never hands back. The dwell keeps a rate that dips below
the threshold for a moment, as a tumbling body's measured rate can with noise, from starting a
pointing manoeuvre the wheels cannot finish. It does not switch back because the pointing
mode's own transient (the slew to the target, when the wheels take up the body's momentum)
raises the rate for a while, and a law that switched back on it would chatter between modes;
going back to detumbling is a fault response (safe mode), outside this controller.

**Periods.** Both sub-controllers are called at the mission's one period: they must have the
same ``period`` (a ``ValueError`` names both otherwise).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..._html import field_repr
from ...typing import FloatArray
from ...validation import check_positive
from .bdot import BDot
from .controllers import MomentumDumping, MRPFeedback
from ..models.actuators import Command
from ..models.sensors import Measurement

__all__ = ["DetumbleThenPoint"]


@dataclass
class DetumbleThenPoint:
    """B-dot until the measured rate has stayed below ``switch_rate`` for ``dwell`` s, then pointing.

    Parameters
    ----------
    detumble : BDot
        The detumbling mode (magnetorquers).
    point : MRPFeedback or MomentumDumping
        The pointing mode (wheels; with :class:`~tumble.dynamics.control.controllers.MomentumDumping` the
        magnetorquers unload them).
    switch_rate : float
        Rate below which the gyroscope's ``|omega|`` must stay, rad/s (> 0).
    dwell : float
        How long it must stay below, s (>= 0; 0 switches at the first step below).

    Attributes
    ----------
    period : float
        The control period, s: the sub-controllers' (they must share it).
    switch_time : float or None
        The time of the step that handed over to pointing, s; None before (and in a run that
        never switches). :meth:`reset` clears it (the run calls it at its start).

    Examples
    --------
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> import numpy as np
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.controllers import MRPFeedback
    >>> from tumble.dynamics.control.mission import DetumbleThenPoint
    >>> from tumble.dynamics.models.sensors import Measurement
    >>> rw = ReactionWheels(np.eye(3), inertia=2e-5)
    >>> mission = DetumbleThenPoint(BDot(gain=3e-5, period=1.0, form="normalized"),
    ...     MRPFeedback(K=1e-3, P=6e-3, period=1.0, moments=[0.0067, 0.0419, 0.0419], wheels=rw),
    ...     switch_rate=0.01, dwell=2.0)
    >>> from scipy.spatial.transform import Rotation
    >>> def reading(t, rate):
    ...     return Measurement(t, np.array([rate, 0.0, 0.0]), np.array([0.0, 2e-5, 0.0]), Rotation.identity(), np.zeros(3))
    >>> [mission.mode for t, rate in enumerate([0.1, 0.005, 0.02, 0.005, 0.005, 0.005, 0.1]) if mission(t, reading(t, rate))]
    ['detumble', 'detumble', 'detumble', 'detumble', 'detumble', 'point', 'point']
    >>> mission.switch_time, mission.period   # below at t = 3, 4 and 5 s: 2 s of dwell
    (5.0, 1.0)
    >>> DetumbleThenPoint(BDot(gain=1e4, period=0.5), mission.point, switch_rate=0.01, dwell=10.0)
    Traceback (most recent call last):
    ...
    ValueError: detumble.period = 0.5 s and point.period = 1 s differ; the mission calls both at one period: give them the same
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    detumble: BDot
    point: MRPFeedback | MomentumDumping
    switch_rate: float
    dwell: float
    period: float = field(init=False)
    switch_time: float | None = field(default=None, init=False)
    _below_since: float | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.detumble, BDot):
            raise ValueError(f"detumble = {type(self.detumble).__name__} object must be a BDot controller")  # noqa: TRY004 - one error type
        if not isinstance(self.point, (MRPFeedback, MomentumDumping)):
            kind = type(self.point).__name__
            raise ValueError(f"point = {kind} object must be an MRPFeedback or a MomentumDumping controller")  # noqa: TRY004
        self.switch_rate = check_positive("switch_rate", self.switch_rate, "rad/s")
        self.dwell = check_positive("dwell", self.dwell, "s", allow_zero=True)
        a, b = float(self.detumble.period), float(self.point.period)
        if not math.isclose(a, b, rel_tol=1e-12):
            raise ValueError(f"detumble.period = {a:g} s and point.period = {b:g} s differ; the mission calls both "
                             "at one period: give them the same")
        self.period = a

    @property
    def mode(self) -> str:
        """``"detumble"`` before the switch, ``"point"`` from it on.

        Examples
        --------
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> import numpy as np
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.controllers import MRPFeedback
        >>> from tumble.dynamics.control.mission import DetumbleThenPoint
        >>> rw = ReactionWheels(np.eye(3), inertia=2e-5)
        >>> point = MRPFeedback(K=1e-3, P=6e-3, period=1.0, moments=[0.0067, 0.0419, 0.0419], wheels=rw)
        >>> DetumbleThenPoint(BDot(gain=1e4, period=1.0), point, switch_rate=0.01, dwell=0.0).mode
        'detumble'
        """
        return "detumble" if self.switch_time is None else "point"

    def reset(self) -> None:
        """Back to detumbling, the dwell window and the switch time cleared; the sub-controllers reset.

        Examples
        --------
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> from scipy.spatial.transform import Rotation
        >>> import numpy as np
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.controllers import MRPFeedback
        >>> from tumble.dynamics.control.mission import DetumbleThenPoint
        >>> from tumble.dynamics.models.sensors import Measurement
        >>> rw = ReactionWheels(np.eye(3), inertia=2e-5)
        >>> point = MRPFeedback(K=1e-3, P=6e-3, period=1.0, moments=[0.0067, 0.0419, 0.0419], wheels=rw)
        >>> mission = DetumbleThenPoint(BDot(gain=1e4, period=1.0), point, switch_rate=0.01, dwell=0.0)
        >>> still = Measurement(0.0, np.zeros(3), np.array([2e-5, 0.0, 0.0]), Rotation.identity(), np.zeros(3))
        >>> _ = mission(0.0, still)
        >>> mission.switch_time, mission.mode
        (0.0, 'point')
        >>> mission.reset()
        >>> mission.switch_time, mission.mode
        (None, 'detumble')
        """
        for sub in (self.detumble, self.point):
            reset = getattr(sub, "reset", None)
            if callable(reset):
                reset()
        self.switch_time = None
        self._below_since = None

    def __call__(self, t: float, measurement: Measurement) -> Command:
        """The detumbling mode's command until the switch, the pointing mode's from it on.

        Examples
        --------
        Before the switch the command is B-dot's dipole and no wheel torque; from the switch on
        it is MRP feedback's wheel torques:

        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> from scipy.spatial.transform import Rotation
        >>> import numpy as np
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.controllers import MRPFeedback
        >>> from tumble.dynamics.control.mission import DetumbleThenPoint
        >>> from tumble.dynamics.models.sensors import Measurement
        >>> rw = ReactionWheels(np.eye(3), inertia=2e-5)
        >>> bdot = BDot(gain=1e4, period=1.0)
        >>> point = MRPFeedback(K=1e-3, P=6e-3, period=1.0, moments=[0.0067, 0.0419, 0.0419], wheels=rw)
        >>> mission = DetumbleThenPoint(bdot, point, switch_rate=0.05, dwell=0.0)
        >>> spin = Measurement(0.0, np.array([0.0, 0.0, 0.1]), np.array([2e-5, 0.0, 0.0]), Rotation.identity(), np.zeros(3))
        >>> cmd = mission(0.0, spin)
        >>> np.array_equal(cmd.dipole, bdot(0.0, spin).dipole), cmd.wheel_torque is None
        (True, True)
        >>> slow = Measurement(1.0, np.array([0.0, 0.0, 0.01]), spin.field, Rotation.from_rotvec([0.1, 0.0, 0.0]), np.zeros(3))
        >>> np.array_equal(mission(1.0, slow).wheel_torque, point(1.0, slow).wheel_torque), mission.switch_time
        (True, 1.0)
        """
        if not self.observe(float(t), float(np.linalg.norm(measurement.omega))):
            return self.detumble(t, measurement)
        return self.point(t, measurement)

    def observe(self, t: float, rate: float) -> bool:
        """The switch (module docstring): whether the mission points from the step at ``t`` (s) on,
        given the gyroscope's ``|omega|`` there (rad/s); before the switch it updates the dwell window
        and, at the switch, :attr:`switch_time`.

        Examples
        --------
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> import numpy as np
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.controllers import MRPFeedback
        >>> from tumble.dynamics.control.mission import DetumbleThenPoint
        >>> point = MRPFeedback(K=1e-3, P=6e-3, period=1.0, moments=[0.0067, 0.0419, 0.0419],
        ...                     wheels=ReactionWheels(np.eye(3), inertia=2e-5))
        >>> mission = DetumbleThenPoint(BDot(gain=1e4, period=1.0), point, switch_rate=0.01, dwell=1.0)
        >>> [mission.observe(float(t), rate) for t, rate in enumerate([0.005, 0.02, 0.005, 0.005, 0.1])], mission.switch_time
        ([False, False, False, True, True], 3.0)
        """
        if self.switch_time is None:
            if rate < self.switch_rate:
                if self._below_since is None:
                    self._below_since = t
                if t - self._below_since >= self.dwell - 1e-9 * self.period:
                    self.switch_time = t
            else:
                self._below_since = None
        return self.switch_time is not None

    def compiled_run(self, kernel: Any, sensors: Any, wheels: Any, field: Any, y0: FloatArray, grid: FloatArray,
                     rods: FloatArray, limits: FloatArray, carry: bool = False) -> tuple[FloatArray, ...] | None:
        """The mission on the compiled closed loop (:meth:`~tumble.dynamics.control.control_kernel.ControlKernel.run`,
        ``kernel``), or None where a mode has no compiled law (:func:`~tumble.dynamics.control.control_kernel.compiled_law`):
        the whole run detumbling, the switch found from its rates at the control instants (:meth:`observe`; the
        sensors are ideal there), then the run from the switch pointing. The detumbling run up to the switch is the
        mission's own, step for step, and the pointing mode starts at the switch with nothing in its memory, as the
        Python path's; :attr:`switch_time` is set as a run in Python sets it. Returns the states, the dipoles, the
        wheels' torques and the fields at the instants ``grid`` (s).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.control_kernel import ControlKernel
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.controllers import MRPFeedback
        >>> from tumble.dynamics.control.mission import DetumbleThenPoint
        >>> from tumble.dynamics.environment.magnetic import UniformField
        >>> from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
        >>> I, rw, field = np.array([0.01, 0.02, 0.03]), ReactionWheels(np.eye(3), inertia=2e-5), UniformField((3e-5, 0.0, 0.0))
        >>> mission = DetumbleThenPoint(BDot(gain=2e-3, period=0.5, form="normalized"),
        ...                             MRPFeedback(K=1e-4, P=6e-4, period=0.5, moments=I, wheels=rw), switch_rate=0.05, dwell=1.0)
        >>> kernel = ControlKernel(I, np.linalg.inv(np.diag(I) - rw.locked_axial()), rw, field, None, 1e-10, 1e-12)
        >>> y0 = np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.01, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])   # 0.01 rad/s about z
        >>> Y, D, U, F = mission.compiled_run(kernel, None, rw, field, y0, np.arange(21) * 0.5, Magnetorquers(0.1).rods, np.full(3, 0.1))
        >>> mission.switch_time   # below 0.05 rad/s from t = 0: pointing after 1 s of dwell
        1.0
        >>> bool(np.all(D[:2, 1] != 0.0) and np.all(D[2:] == 0.0)), bool(np.any(U[2:] != 0.0))   # B-dot, then the wheels
        (True, True)
        """
        detumble, point = (kernel.law(mode, sensors, wheels, field) for mode in (self.detumble, self.point))
        if detumble is None or point is None:
            return None
        self.reset()
        Y, D, U, F = kernel.run(y0, grid, detumble, rods, limits, carry)
        for i in range(len(grid) - 1):
            if self.observe(float(grid[i]), float(np.linalg.norm(Y[i, 4:7]))):
                after = kernel.run(Y[i], grid[i:], point, rods, limits, carry)
                return tuple(np.concatenate([a[:i], b]) for a, b in zip((Y, D, U, F), after))
        return Y, D, U, F
