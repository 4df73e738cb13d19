"""Flight software as its own room: controllers, the closed loop, the mission logic, pointing targets
and the batched B-dot, with their compiled parts.

- :mod:`~tumble.dynamics.control.controllers`: the control laws (B-dot, MRP feedback, momentum
  dumping) behind one :class:`~tumble.dynamics.control.controllers.Controller` interface;
- :mod:`~tumble.dynamics.control.controlled`: the closed loop, :func:`simulate_controlled`, with
  the sensors, actuators and environment of :mod:`tumble.dynamics.models`;
- :mod:`~tumble.dynamics.control.mission`: detumble, then point (:class:`DetumbleThenPoint`);
- :mod:`~tumble.dynamics.control.estimated`: a controller fed the MEKF's estimate instead of the
  truth (:class:`Estimated`);
- :mod:`~tumble.dynamics.control.pointing`: pointing targets (inertial, nadir) and the tracking error;
- :mod:`~tumble.dynamics.control.detumble`: the B-dot detumble of many bodies at once;
- :mod:`~tumble.dynamics.control.laws`: the control laws over floats, written once for the Python
  controllers and the compiled loop;
- :mod:`~tumble.dynamics.control.compiled_loop` (the whole loop, or one hold interval, in one
  compiled call), :mod:`~tumble.dynamics.control.loop_terms` (its right-hand side),
  :mod:`~tumble.dynamics.control.control_kernel` (the loop bound to a run's parameters, which each
  model gives through its ``loop_form()``) and :mod:`~tumble.dynamics.control.detumble_kernels`
  (the B-dot batch): their numba kernels, compiled at import and imported only when asked for.

The room calls the models and the integrators, never the other way (tests/test_import_graph.py).
"""

from .bdot import BDot, bdot_gain
from .controlled import ControlledRun, simulate_controlled
from .controllers import Controller, MomentumDumping, MRPFeedback, pd_response
from .estimated import Estimated, Knowledge
from .mission import DetumbleThenPoint
from .pointing import NadirTarget

__all__ = ["BDot", "ControlledRun", "Controller", "DetumbleThenPoint", "Estimated", "Knowledge", "MRPFeedback", "MomentumDumping", "NadirTarget", "bdot_gain",
           "pd_response", "simulate_controlled"]
