"""An object's mass properties as a simulator's inertial element: URDF and MuJoCo's MJCF.

``tumble tensor`` writes both into its folder (``inertial.urdf``, ``inertial.xml``); they are the
object alone (``tensor.json``'s ``"object"``): its mass, its centre of mass and its tensor about
that centre, in the **device's sensor frame** (origin at the accelerometer, axes the
gyroscope's). Paste one into the link (URDF) or the body (MJCF) whose frame is the sensor frame,
or turn it into the frame you have. A comment above the element names the frame and the
standard uncertainties (which neither format can hold).

- **URDF** ``<inertial>`` (ROS, http://wiki.ros.org/urdf/XML/link): ``<origin xyz rpy>`` places
  the centre of mass in the link's frame and turns the axes the tensor is written in; ``rpy="0
  0 0"`` here, so the tensor is about the centre of mass along the link's (the sensor's) axes;
  ``<mass value>`` kg; ``<inertia ixx ixy ixz iyy iyz izz>`` kg m^2.
- **MJCF** ``<inertial pos mass fullinertia>`` (MuJoCo's XML reference, ``body/inertial``):
  ``pos`` the centre of mass in the body's frame, ``fullinertia`` the six entries in the order
  ``M(1,1) M(2,2) M(3,3) M(1,2) M(1,3) M(2,3)``, i.e. ``ixx iyy izz ixy ixz iyz``, about ``pos``
  along the body's axes. MuJoCo refuses a tensor that is not positive definite.

**The sign of the off-diagonal entries.** tumble's tensor is ``I_ij = sum m (|r|^2 delta_ij -
r_i r_j)`` (docs/conventions.md), so ``I_xy = -sum m x y``: its off-diagonal entries are the
tensor's own, not the "products of inertia" ``+sum m x y`` that some CAD tools print. URDF and
MJCF both take the tensor's entries: SDFormat's ``<inertia>`` (which Gazebo reads URDF into)
states ``ixy`` "where the product of inertia convention -m x y (not +m x y) is used"
(sdformat.org, ``inertial.sdf``, spec 1.10), URDF's ``<inertia>`` is "the 3x3 rotational inertia
matrix" whose above-diagonal elements are given, and MuJoCo's ``fullinertia`` is the "full
inertia matrix M". So the entries are written as they are, with no sign changed (a test builds a
MuJoCo model from the MJCF element and finds the principal moments and the centre again).

Numbers are written to 15 significant digits (as short as that allows: ``0.482``, not
``0.48200000000000004``, the double a subtraction left): within 1e-15 of ``tensor.json``'s, far
below the estimates' uncertainties (a part in 100 to 10,000).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Protocol

import numpy as np

from ..mass.tensor import check_inertia
from ..validation import check_positive, check_vectors

__all__ = ["MJCF_ORDER", "mjcf_inertial", "urdf_inertial"]

#: The order of ``fullinertia``'s six numbers in MJCF (MuJoCo's XML reference): M(1,1), M(2,2),
#: M(3,3), M(1,2), M(1,3), M(2,3).
MJCF_ORDER = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")
_INDEX = {"ixx": (0, 0), "iyy": (1, 1), "izz": (2, 2), "ixy": (0, 1), "ixz": (0, 2), "iyz": (1, 2)}
#: The order of a tensor's entries in ``inertia_cov`` (:data:`tumble.analysis.tensor.estimate.ENTRIES`).
_COV_ORDER = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")


class _Estimate(Protocol):
    """What is read of a :class:`tumble.analysis.tensor.MassEstimate`."""

    def as_dict(self) -> dict[str, Any]: ...


def _num(x: float) -> str:
    return repr(float(f"{float(x):.15g}"))  # 15 significant digits, the shortest way: 0.482, not 0.48200000000000004


def _short(values: object, digits: int = 6) -> str:
    return "[" + ", ".join(f"{float(v):.{digits}g}" for v in np.ravel(np.asarray(values, float))) + "]"


def _read(estimate: _Estimate | Mapping[str, Any]) -> tuple[float, np.ndarray, np.ndarray, dict[str, Any]]:
    """``(mass, centre, tensor, the rest)`` of a MassEstimate or a mapping of its keys, checked."""
    record = estimate.as_dict() if hasattr(estimate, "as_dict") else estimate
    if not isinstance(record, Mapping):
        raise ValueError(f"estimate = {type(estimate).__name__}: give a MassEstimate or a mapping with mass, "
                         "center_of_mass and inertia (as tensor.json's \"object\")")
    missing = [key for key in ("mass", "center_of_mass", "inertia") if key not in record]
    if missing:
        raise ValueError(f"estimate has no {', '.join(missing)}: give mass (kg), center_of_mass (m) and inertia "
                         "(kg m^2, about the centre of mass)")
    mass = check_positive("mass", record["mass"], "kg")
    center = check_vectors("center_of_mass", record["center_of_mass"], "m")
    inertia = check_vectors("inertia", record["inertia"], "kg m^2", size=None)
    if inertia.shape != (3, 3):
        raise ValueError(f"inertia must be a 3x3 tensor (kg m^2), not shape {inertia.shape}")
    scale = max(float(np.abs(inertia).max()), 1e-300)
    if np.abs(inertia - inertia.T).max() > 1e-9 * scale:
        raise ValueError(f"inertia = {inertia.tolist()} must be symmetric (kg m^2)")
    inertia = 0.5 * (inertia + inertia.T)
    record = dict(record)
    try:  # an estimate near the edge may break it by its uncertainty: written, and said so in the comment
        check_inertia(inertia, what="the tensor")
    except ValueError as err:
        record["_not_physical"] = " ".join(str(err).split())
    return mass, center, inertia, record


def _comment(kind: str, mass: float, center: np.ndarray, inertia: np.ndarray, record: dict[str, Any],
             note: str) -> str:
    """The comment above the element: what it is, its frame, the uncertainties and the sign convention."""
    lines = [f"{kind} inertial element of an object measured by tumble tensor" + (f":\n{note}" if note else "") + ".",
             "Frame: the device's sensor frame, origin at the accelerometer, axes the gyroscope's; put it in the",
             "link/body whose frame that is. Tensor about the centre of mass, along the frame's axes; off-diagonal",
             "entries are the tensor's own (ixy = -sum m x y), as URDF and MJCF take them.",
             f"mass {mass:.6g} kg, as weighed (not estimated)."]
    c_std = record.get("center_of_mass_std")
    lines.append(f"centre of mass {_short(center)} m" + ("" if c_std is None else f" +/- {_short(c_std, 2)} m") + ".")
    cov = record.get("inertia_cov")
    std = None if cov is None else np.sqrt(np.maximum(np.diag(np.asarray(cov, float)), 0.0))
    entries = []
    for k, name in enumerate(_COV_ORDER):
        i, j = _INDEX[name]
        entries.append(f"{name} {inertia[i, j]:.6g}" + ("" if std is None else f" +/- {std[k]:.2g}"))
    lines.append("tensor, kg m^2: " + ", ".join(entries[:3]) + ",")
    lines.append("  " + ", ".join(entries[3:]) + ".")
    moments = record.get("principal_moments")
    if "_not_physical" in record:
        lines.append(f"WARNING: not a physical tensor ({record['_not_physical']}); MuJoCo refuses it.")
    if moments is not None:
        m_std = record.get("principal_moments_std")
        lines.append(f"principal moments {_short(moments)} kg m^2"
                     + ("" if m_std is None else f" +/- {_short(m_std, 2)} kg m^2") + ".")
    if std is not None or c_std is not None:
        lines.append("+/- : standard uncertainties (one standard deviation), as tensor.json's.")
    text = "\n".join(lines)
    while "--" in text:  # "--" may not stand in an XML comment (XML 1.0, sec. 2.5)
        text = text.replace("--", "- -")
    text = "\n     ".join(text.splitlines())
    return f"<!-- {text} -->"


def urdf_inertial(estimate: _Estimate | Mapping[str, Any], *, note: str = "") -> str:
    """The URDF ``<inertial>`` element of a body (module docstring), with a comment above it.

    Parameters
    ----------
    estimate : MassEstimate or mapping
        :class:`tumble.analysis.tensor.MassEstimate` (e.g. ``TensorFit.object``), or a mapping
        with its keys (``tensor.json``'s ``"object"``): ``mass`` (kg), ``center_of_mass`` (m),
        ``inertia`` (3 x 3, kg m^2, about the centre of mass); with ``center_of_mass_std``,
        ``inertia_cov`` (6 x 6, entries xx, yy, zz, xy, xz, yz), ``principal_moments`` and
        ``principal_moments_std`` the comment states the uncertainties.
    note : str
        Said in the comment's first line (e.g. how many throws).

    Returns
    -------
    str
        The comment and ``<inertial>`` (``<origin xyz rpy="0 0 0">``, ``<mass value>``,
        ``<inertia ixx ixy ixz iyy iyz izz>``), lines ending in ``\\n``.

    Raises
    ------
    ValueError
        A mass not positive, a centre not 3 finite numbers, a tensor that is not 3 x 3, finite and
        symmetric. A tensor that is not physical (:func:`tumble.mass.tensor.check_inertia`: an
        estimate whose uncertainty reaches past the triangle inequality) is written, with a
        warning in the comment.

    Examples
    --------
    >>> import xml.etree.ElementTree as ET
    >>> from tumble.io.inertial import urdf_inertial
    >>> text = urdf_inertial({"mass": 0.5, "center_of_mass": [0.01, 0.0, 0.02],
    ...                       "inertia": [[2e-4, -1e-5, 0.0], [-1e-5, 3e-4, 0.0], [0.0, 0.0, 4e-4]]})
    >>> print(text.split("-->")[1].strip())
    <inertial>
      <origin xyz="0.01 0.0 0.02" rpy="0 0 0"/>
      <mass value="0.5"/>
      <inertia ixx="0.0002" ixy="-1e-05" ixz="0.0" iyy="0.0003" iyz="0.0" izz="0.0004"/>
    </inertial>
    >>> ET.fromstring(text).find("inertia").get("ixy")   # the tensor's entry, its sign kept
    '-1e-05'
    """
    mass, center, inertia, record = _read(estimate)
    values = " ".join(f'{name}="{_num(inertia[_INDEX[name]])}"' for name in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"))
    return "\n".join([_comment("URDF", mass, center, inertia, record, note),
                      "<inertial>",
                      f'  <origin xyz="{" ".join(_num(x) for x in center)}" rpy="0 0 0"/>',
                      f'  <mass value="{_num(mass)}"/>',
                      f"  <inertia {values}/>",
                      "</inertial>", ""])


def mjcf_inertial(estimate: _Estimate | Mapping[str, Any], *, note: str = "") -> str:
    """The MJCF (MuJoCo) ``<inertial>`` element of a body (module docstring), with a comment above it.

    Parameters
    ----------
    estimate : MassEstimate or mapping
        As :func:`urdf_inertial`'s.
    note : str
        Said in the comment's first line.

    Returns
    -------
    str
        The comment and ``<inertial pos mass fullinertia/>`` (``fullinertia`` in the order
        :data:`MJCF_ORDER`), lines ending in ``\\n``.

    Raises
    ------
    ValueError
        As :func:`urdf_inertial`.

    Examples
    --------
    >>> import xml.etree.ElementTree as ET
    >>> from tumble.io.inertial import mjcf_inertial
    >>> text = mjcf_inertial({"mass": 0.5, "center_of_mass": [0.01, 0.0, 0.02],
    ...                       "inertia": [[2e-4, -1e-5, 0.0], [-1e-5, 3e-4, 0.0], [0.0, 0.0, 4e-4]]})
    >>> print(text.split("-->")[1].strip())
    <inertial pos="0.01 0.0 0.02" mass="0.5" fullinertia="0.0002 0.0003 0.0004 -1e-05 0.0 0.0"/>
    >>> ET.fromstring(text).get("mass")
    '0.5'
    """
    mass, center, inertia, record = _read(estimate)
    full = " ".join(_num(inertia[_INDEX[name]]) for name in MJCF_ORDER)
    return "\n".join([_comment("MJCF (MuJoCo)", mass, center, inertia, record, note),
                      f'<inertial pos="{" ".join(_num(x) for x in center)}" mass="{_num(mass)}" fullinertia="{full}"/>',
                      ""])
