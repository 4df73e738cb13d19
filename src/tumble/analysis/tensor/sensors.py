"""The device's sensors as built, as the tensor's fits see them (issue #42): the stated
uncertainties of the gyroscope and the rotor's axis (:class:`SensorErrors`, type B), the
gyroscope's distortion that throws can determine (its trace-free symmetric part,
:data:`GYRO_BASIS`) and the rotor axis's tilt (:func:`tilted_axis`): the seven
:data:`SENSOR_NAMES` a joint fit (:mod:`~tumble.analysis.tensor.joint`) finds and a calibration
(:func:`~tumble.analysis.tensor.calibrate.calibrated_sensors`) keeps.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..._html import headline_html, headline_repr
from ...typing import FloatArray

__all__ = ["GYRO_BASIS", "GYRO_ENTRIES", "SENSOR_NAMES", "SensorErrors", "axis_normals", "distortion_coefficients", "gyro_matrix",
           "tilted_axis"]


@dataclass(frozen=True)
class SensorErrors:
    """The stated standard uncertainties of the device's sensors as built (type B): the
    gyroscope's scale factor per axis (relative), its misalignment per pair of axes (rad) and
    the rotor axis's direction (rad, about each axis normal to it). Defaults, assumed (not read
    off this device's parts): a sensitivity error of 0.3 % and a cross-axis sensitivity of 0.5 %,
    inside the +-1 % limits MEMS data sheets state
    (:data:`tumble.analysis.fit.uncertainty.SCALE_UNCERTAINTY`), and a motor mounted to within 1
    degree; the synthetic devices draw theirs from the same sizes.

    Examples
    --------
    >>> from tumble.analysis.tensor.sensors import SensorErrors
    >>> SensorErrors().variances().round(8).tolist()[:4]
    [9e-06, 9e-06, 9e-06, 2.5e-05]
    """

    HEADLINE = (("gyro_scale", "gyroscope scale", ""), ("gyro_misalignment", "misalignment", "rad"),
                ("rotor_axis", "rotor axis", "rad"))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    gyro_scale: float = 0.003
    gyro_misalignment: float = 0.005
    rotor_axis: float = float(np.deg2rad(1.0))
    #: The standard uncertainties of a calibrated distortion's five coefficients (:data:`GYRO_BASIS`),
    #: or None where the device's gyroscope is not calibrated (then ``gyro_misalignment`` stands for
    #: its whole misalignment); with it, ``rotor_axis`` is the calibrated axis's.
    distortion: FloatArray | None = None

    @property
    def calibrated(self) -> bool:
        """Whether the gyroscope's distortion and the rotor's axis come from a calibration
        (:func:`~tumble.analysis.tensor.calibrate.calibrate`): the fits hold them there and
        carry their calibrated uncertainties, :meth:`held_std`.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.sensors import SensorErrors
        >>> SensorErrors().calibrated, SensorErrors(distortion=np.full(5, 1e-4)).calibrated
        (False, True)
        """
        return self.distortion is not None

    def held_std(self) -> FloatArray:
        """The standard uncertainties of the seven :data:`SENSOR_NAMES` held at a calibration's values.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.sensors import SensorErrors
        >>> SensorErrors(rotor_axis=0.002, distortion=np.full(5, 1e-4)).held_std().tolist()
        [0.0001, 0.0001, 0.0001, 0.0001, 0.0001, 0.002, 0.002]
        """
        d = np.zeros(5) if self.distortion is None else np.asarray(self.distortion, float)
        return np.r_[d, self.rotor_axis, self.rotor_axis]

    def variances(self, fitted: bool = False) -> FloatArray:
        """The variances of the 9 gyroscope entries (3 scales, 6 misalignments) and 2 rotor angles;
        with ``fitted`` (the joint fit determined the rest) that of the rates' common scale, the
        mean of the three scale factors.

        Examples
        --------
        >>> from tumble.analysis.tensor.sensors import SensorErrors
        >>> SensorErrors(0.0, 0.0, 0.0).variances().tolist() == [0.0] * 11
        True
        >>> SensorErrors(0.003).variances(fitted=True).round(8).tolist()
        [3e-06]
        """
        if fitted:
            return np.array([self.gyro_scale ** 2 / 3.0])
        return np.r_[np.full(3, self.gyro_scale ** 2), np.full(6, self.gyro_misalignment ** 2),
                     np.full(2, self.rotor_axis ** 2)]


#: The gyroscope's entries ``(i, j)`` of ``omega_read = (E + e) omega``: scales, then misalignments.
GYRO_ENTRIES = ((0, 0), (1, 1), (2, 2), (0, 1), (1, 0), (0, 2), (2, 0), (1, 2), (2, 1))


def _symmetric_basis() -> FloatArray:
    """The five trace-free symmetric unit matrices: ``xx - zz``, ``yy - zz``, ``xy``, ``xz``, ``yz``."""
    out = []
    for i, j in ((0, 0), (1, 1), (0, 1), (0, 2), (1, 2)):
        E = np.zeros((3, 3))
        E[i, j] = E[j, i] = 1.0
        if i == j:
            E[2, 2] = -1.0
        out.append(E)
    return np.array(out)


#: The gyroscope's distortion that a joint fit determines (``omega_read = (E + sum g_k B_k) omega``).
GYRO_BASIS = _symmetric_basis()
#: The joint fit's shared sensor parameters: the five of :data:`GYRO_BASIS`, the rotor axis's two angles.
SENSOR_NAMES = ("gyro_xx_zz", "gyro_yy_zz", "gyro_xy", "gyro_xz", "gyro_yz", "rotor_tilt_1", "rotor_tilt_2")


def axis_normals(axis: FloatArray) -> FloatArray:
    """Two unit vectors normal to ``axis`` (rows): the directions about which the rotor's axis
    tilts (:data:`SENSOR_NAMES`' ``rotor_tilt_1``, ``rotor_tilt_2``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.sensors import axis_normals
    >>> n = axis_normals(np.array([0.0, 0.0, -1.0]))
    >>> bool(np.allclose(n @ [0, 0, 1], 0)), bool(np.allclose(n @ n.T, np.eye(2)))
    (True, True)
    """
    a = np.asarray(axis, float)
    return np.linalg.svd((a / np.linalg.norm(a))[None])[2][1:]


def tilted_axis(axis: FloatArray, tilt: FloatArray) -> FloatArray:
    """``axis`` (unit) turned by the two angles ``tilt`` (rad) about :func:`axis_normals`.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.sensors import tilted_axis
    >>> a = tilted_axis(np.array([0.0, 0.0, 1.0]), [0.01, 0.0])
    >>> round(float(np.degrees(np.arccos(a[2]))), 4)
    0.573
    """
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    return Rotation.from_rotvec(np.asarray(tilt, float) @ axis_normals(a)).apply(a)


def gyro_matrix(distortion: FloatArray) -> FloatArray:
    """``omega_read = gyro_matrix @ omega``: the identity plus the distortion's five coefficients
    (:data:`GYRO_BASIS`).

    Examples
    --------
    >>> from tumble.analysis.tensor.sensors import gyro_matrix
    >>> gyro_matrix([0.01, 0.0, 0.002, 0.0, 0.0]).round(6).tolist()
    [[1.01, 0.002, 0.0], [0.002, 1.0, 0.0], [0.0, 0.0, 0.99]]
    """
    return np.eye(3) + np.tensordot(np.asarray(distortion, float), GYRO_BASIS, 1)


def distortion_coefficients(D: FloatArray) -> FloatArray:
    """The five :data:`GYRO_BASIS` coefficients of a symmetric trace-free distortion ``D`` (its
    ``xx``, ``yy``, ``xy``, ``xz``, ``yz``): the inverse of :func:`gyro_matrix` less the identity.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.sensors import distortion_coefficients, gyro_matrix
    >>> g = np.array([0.01, -0.002, 0.003, 0.0, 0.001])
    >>> bool(np.allclose(distortion_coefficients(gyro_matrix(g) - np.eye(3)), g))
    True
    """
    D = np.asarray(D, float)
    return np.array([D[0, 0], D[1, 1], D[0, 1], D[0, 2], D[1, 2]])
