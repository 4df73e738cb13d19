"""The engine: one compiled integration core over the body's state, with interchangeable steppers.

The room of :mod:`tumble.dynamics` where runs are integrated in compiled code. Its parts:

- :mod:`~tumble.dynamics.engine.kernels`: the state ``(omega, q)``, its right-hand side under the
  built-in models (each model's own formula, compiled), and the steppers (DOP853 with error
  control and dense output, step for step scipy's; fixed-step RK4 and RK8), one body or a batch
  on every core;
- :mod:`~tumble.dynamics.engine.lanes`: the fixed-step batch in vector lanes, a block of bodies
  stepped together, one in each lane of a vector register, the blocks on every core;
- :mod:`~tumble.dynamics.engine.tableau`: their Butcher tableaux;
- :mod:`~tumble.dynamics.engine.status`: how a run ends and the work it may take;
- :mod:`~tumble.dynamics.engine.front`: the Python front that :func:`tumble.simulate` and
  :func:`tumble.simulate_batch` call: it reads a model's compiled form, lays the bodies out and
  turns a kernel's status into an error.

**How a model gets its compiled form.** A torque model declares it through one interface,
:class:`~tumble.dynamics.models.torques.KernelForm`: ``kernel_form()`` returns a kind and its
parameters. The formula itself is a function over plain floats in the model's module (e.g.
:func:`~tumble.dynamics.models.gravity.gradient_components`), which the numpy path calls on
arrays and :func:`~tumble.dynamics.engine.kernels.external_torque` compiles for its kind: one
writing. A model without a kernel form (a user's Python function) runs on the Python path, which
calls it.

The older kernels (the splittings' and the exact flow's in :mod:`tumble.dynamics.methods`, the
closed loop's and the B-dot batch's in :mod:`tumble.dynamics.control`) are still compiled by
rewriting their module's globals, and the closed loop still carries its own DOP853 for one hold
interval: moving them onto this core is open work.
"""

from .front import ENGINE_METHODS, run_bodies, run_body

__all__ = ["ENGINE_METHODS", "run_bodies", "run_body"]
