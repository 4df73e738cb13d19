"""Mass properties as JSON-ready data and as a readable table."""

from __future__ import annotations

import numpy as np

from ..analysis.stability import stable_spin_range
from ..analysis.summary import axis_role
from ..mass import Body
from ..typing import ArrayLike

__all__ = ["mass_properties_dict", "mass_properties_table", "rotor_stable_spin"]

_DESIGN_AXES = ("x", "y", "z")


def mass_properties_dict(body: Body) -> dict:
    """The public JSON form of ``tumble inertia --json`` (SI units, design frame).

    Parameters
    ----------
    body : Body
        The body.

    Returns
    -------
    dict
        Keys: ``name``, ``units`` (of mass, length, inertia), ``mass`` (kg), ``com`` (m),
        ``inertia`` (3x3 about the COM, kg m^2), ``principal_moments`` ([I1, I2, I3] ascending,
        kg m^2), ``principal_axes`` (the 3x3 matrix ``body.principal_axes`` as nested lists, row by
        row: principal -> design, its *columns* are the axes of I1, I2, I3 in the design frame, so
        ``np.array(d["principal_axes"]) == body.principal_axes``), ``intermediate_axis`` (unit
        vector, or null when two moments are equal), ``symmetry``; for a body with rotors also
        ``rotor_momentum`` (their momentum at t = 0 in the principal frame, kg m^2/s) and
        ``intermediate_stable_spin`` (:func:`rotor_stable_spin`: the spin rates about the
        intermediate axis, rad/s, that the rotors keep stable, or null).

    Examples
    --------
    >>> import tumble
    >>> from tumble.io.report import mass_properties_dict
    >>> d = mass_properties_dict(tumble.t_handle())
    >>> d["mass"], d["principal_moments"], d["intermediate_axis"], d["symmetry"]
    (3.0, [0.125, 0.3125, 0.4375], [1.0, 0.0, 0.0], 'asymmetric')
    """
    p = body.properties
    axis = p.intermediate_axis
    rotors = {}
    if body.rotors:
        rotors = {"rotor_momentum": body.internal_momentum(0.0).tolist(),
                  "intermediate_stable_spin": rotor_stable_spin(body)}
    return {
        "name": body.name,
        "units": {"mass": "kg", "length": "m", "inertia": "kg m^2"},
        "mass": p.mass,
        "com": p.com.tolist(),
        "inertia": p.inertia.tolist(),
        "principal_moments": p.principal_moments.tolist(),
        "principal_axes": p.principal_axes.tolist(),
        "intermediate_axis": None if axis is None else axis.tolist(),
        "symmetry": p.degeneracy,
        **rotors,
    }


def rotor_stable_spin(body: Body) -> list[float] | None:
    """The spin rates about the intermediate axis that the body's rotors keep stable, rad/s.

    Their momentum along that axis at t = 0 (:meth:`Body.internal_momentum`) turns the tennis-racket
    theorem into a range (:func:`tumble.analysis.stable_spin_range`, linearised): ``[W_low,
    W_high]``, signed along ``body.properties.intermediate_axis``. None for a body without an
    intermediate axis or whose rotors have no momentum along it (the axis is then unstable).

    Examples
    --------
    >>> import tumble
    >>> from importlib import resources
    >>> import numpy as np
    >>> from tumble.io.report import rotor_stable_spin
    >>> body = tumble.load_body(resources.files("tumble") / "examples/bodies/t_handle_wheel.toml")
    >>> low, high = rotor_stable_spin(body)
    >>> I1, I2, I3 = body.principal_moments
    >>> h = float(body.internal_momentum(0.0)[1])  # 2.5 kg m^2/s along the intermediate axis
    >>> bool(np.allclose([low, high], [-h / (I2 - I1), h / (I3 - I2)]))  # where (I2 - I1) W + h or (I2 - I3) W + h vanish
    True
    >>> rotor_stable_spin(tumble.t_handle()) is None  # no rotor: no stable spin
    True
    """
    if body.properties.intermediate_axis is None:
        return None
    h = float(body.internal_momentum(0.0)[1])
    if h == 0.0:
        return None
    return list(stable_spin_range(body.principal_moments, h))


def describe_axis(v: ArrayLike) -> str:
    """``"+x"`` for a vector along a design axis, else the rounded components."""
    v = np.asarray(v, float)
    k = int(np.argmax(np.abs(v)))
    if abs(abs(v[k]) - 1.0) < 1e-9:
        return ("+" if v[k] > 0 else "-") + _DESIGN_AXES[k]
    return "(" + ", ".join(f"{c:+.4f}" for c in v) + ")"


def mass_properties_table(body: Body) -> str:
    """A plain-text table for people (the default output of ``tumble inertia``).

    Parameters
    ----------
    body : Body
        The body.

    Returns
    -------
    str
        Mass (kg), centre of mass (m), inertia about the COM in the design frame (kg m^2), the
        principal moments with their roles and axes, and the intermediate axis.

    Examples
    --------
    >>> import tumble
    >>> from tumble.io.report import mass_properties_table
    >>> print(mass_properties_table(tumble.t_handle()))  # doctest: +ELLIPSIS
    T-handle: 2 parts
      mass              3 kg
    ...
        I2       0.3125 kg m^2  intermediate  axis +x
        I3       0.4375 kg m^2  major         axis +y
      intermediate axis +x: spin about it is unstable (tennis-racket theorem)
    """
    p = body.properties

    def vec(v) -> str:
        return "  ".join(f"{x:12.6g}" for x in v)

    lines = [
        f"{body.name}: {len(body.parts)} part{'s' if len(body.parts) != 1 else ''}",
        f"  mass              {p.mass:.6g} kg",
        f"  centre of mass    {vec(p.com)}   m",
        "  inertia about the COM, design frame (kg m^2)",
    ]
    lines += [f"                    {vec(row)}" for row in p.inertia]
    lines.append("  principal axes (design frame), ascending moments")
    for j in range(3):  # a symmetric body's roles: no "intermediate" beside "no intermediate axis" (a walkthrough)
        role = axis_role(p.principal_moments, j + 1, p.degeneracy)
        axis = p.principal_axes[:, j]
        lines.append(
            f"    I{j + 1} {p.principal_moments[j]:12.6g} kg m^2  {role:<12}  axis {describe_axis(axis)}"
        )
    if np.any(np.isclose(np.abs(p.principal_axes), 1.0) & (p.principal_axes < 0)):
        lines.append("  (an axis's sign keeps the principal frame right-handed)")
    if p.intermediate_axis is None:
        lines.append(f"  {p.degeneracy} body: no intermediate axis, no tennis-racket flip")
    elif (spins := rotor_stable_spin(body)) is not None:
        h = body.internal_momentum(0.0)
        lines.append(f"  rotors' momentum at t = 0 (principal frame) {vec(h)}   kg m^2/s")
        lines.append(
            f"  intermediate axis {describe_axis(p.intermediate_axis)}: the rotors' {h[1]:.6g} kg m^2/s along it keep "
            f"spin about it stable from {spins[0]:.4g} to {spins[1]:.4g} rad/s (linearised gyrostat); "
            f"faster spin tumbles"
        )
    else:
        lines.append(
            f"  intermediate axis {describe_axis(p.intermediate_axis)}: spin about it is unstable "
            f"(tennis-racket theorem)"
        )
    return "\n".join(lines)
