"""The aerodynamic drag torque about each principal axis: the law, written once.

About each principal axis ``i`` the air's torque opposes the body's own rate ``w_i``::

    tau_i = -(a_i + b_i |w_i|) w_i

with a **linear** drag ``a_i`` (N m s: viscous, skin friction at low Reynolds number; a sphere
in a viscous fluid feels ``8 pi mu R^3 w``, Lamb, *Hydrodynamics*, 6th ed., sec. 334) and a
**quadratic** drag ``b_i`` (N m s^2: pressure drag at high Reynolds number; strip theory gives
``b = rho C_D W L^4 / 64`` for a plate ``L x W`` turning about its width's axis, each strip at
radius ``r`` feeling ``0.5 rho C_D W (w r)^2``: Hoerner, *Fluid-Dynamic Drag*, 1965, ch. 3).
The usual per-axis approximation of a tumbling body's aerodynamic damping.

A module of its own, importing nothing of tumble: the fronts (:mod:`tumble.dynamics.models.drag`,
:mod:`tumble.dynamics.models.gyrostat`) and the compiled kernels
(:mod:`tumble.dynamics.models.fit_kernels`) import it, and nothing imports back.
"""

from __future__ import annotations

from typing import Any

__all__ = ["drag_component"]


def drag_component(linear: Any, quadratic: Any, w: Any) -> Any:
    """The drag torque about one axis, ``-(a + b |w|) w``, N m (module docstring): the law written
    once, over floats (or arrays, elementwise: a float in a kernel, an array in numpy), for the
    Python path and every compiled kernel.

    Examples
    --------
    >>> from tumble.dynamics.models.aero import drag_component
    >>> drag_component(0.1, 1.0, 2.0), drag_component(0.1, 1.0, -2.0)   # always against the rotation
    (-4.2, 4.2)
    """
    return -(linear + quadratic * abs(w)) * w
