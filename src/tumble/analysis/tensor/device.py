"""The inputs of the absolute tensor fit: the device and the proof body (frozen value objects; one throw's log
is :mod:`~tumble.analysis.tensor.throwlog`'s :class:`~tumble.analysis.tensor.throwlog.Throw`).

The **device** is a flight controller logging its gyroscope and accelerometer with a motor and a
flywheel (the rotor) fixed to it (Blaha, Kuijper, Pop & Smeur, "Rapid and Inexpensive Inertia
Tensor Estimation from a Single Object Throw", arXiv:2503.13137). Everything is given in the
device's **sensor frame**, whose origin is the accelerometer: the rotor's axis, the device's
tensor about its own centre of mass, and centres of mass as positions from the accelerometer.
The flight controller's own log (a Betaflight blackbox, :mod:`tumble.io.blackbox`) is read with
the device's motor (its pole count, which of the logged motors is the rotor's), its gyroscope's
full scale and the board's mounting: the sensor frame's axes as signed axes of the log.

The **proof** body has known mass properties; fixed to the device it fixes the absolute scale in
:func:`~tumble.analysis.tensor.calibrate.calibrate_device`.

A **throw** is one log (one CSV file): real sample times (irregular), the gyroscope's angular
velocity, the rotor's speed relative to the device and the accelerometer's specific force.

Validation lives in the constructors (one message whether the value came from Python, TOML or a
CSV): the field, the value as given, and what is allowed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..._html import fmt, headline_html, headline_repr, result_html, result_repr, vec, with_std
from ...mass.tensor import check_inertia
from ...typing import FloatArray, Matrix3, Vector3
from ...validation import check_direction, check_positive, check_vectors, short_repr

__all__ = ["AXIS_NAMES", "MAX_DEVICE_MASS", "MAX_DEVICE_SIZE", "MAX_DISTORTION", "MAX_ROTOR_SPEED", "MAX_THROWN_MASS", "MIN_THROWN_MASS", "ROTOR_SPEED_RATIO",
           "Device", "Proof", "axes_matrix",
           "check_thrown_mass"]

#: The heaviest device, kg: it is thrown by hand (a value beyond it is a unit slip).
MAX_DEVICE_MASS = 10.0
#: The largest radius of gyration of a device (``sqrt(J / m)``, its rotor's and its own) and the farthest
#: its centre of mass lies from its sensor, m: it is held and thrown in one hand (a value beyond it is a
#: unit slip: a moment in g cm^2 or with its exponent lost, a centre in mm).
MAX_DEVICE_SIZE = 0.5
#: The heaviest proof body or object thrown with the device, kg.
MAX_THROWN_MASS = 100.0
#: The lightest, kg: a gram 3 cm across has moments ~1e-7 kg m^2 against the device's ~5e-5, far below what
#: its throws resolve (the tensor's standard uncertainties there ~3e-6 kg m^2, docs/tensor.md).
MIN_THROWN_MASS = 1e-3
#: How far beyond the calibration throws' top speeds (``Device.rotor_speed_range``) an object's
#: throw's may lie, as a ratio: the firmware's plateau was 1230-1360 rad/s over the published
#: device's throws (docs/tensor.md), a battery's sag slows an open-loop motor by ~10-20 %; rpm
#: read as rad/s is 9.5 times, an eRPM turned with half or twice the poles 2 times.
ROTOR_SPEED_RATIO = 1.5
#: The fastest a thrown device's flywheel is taken to spin, rad/s (95,000 rpm): the fastest small
#: brushless motors turn ~83,000 rpm unloaded (19,000 rpm/V on a 4.35 V cell), a flywheel slows
#: them, and the published device's plateau is 1230-1360 rad/s (docs/tensor.md). Beyond it, a rotor
#: speed logged in rpm (9.5 times the rad/s) or eRPM and read as rad/s is likelier; read so in every
#: throw, the calibration's rotor inertia comes out that many times too small and its checks pass.
MAX_ROTOR_SPEED = 1.0e4
def check_thrown_mass(field: str, value: object) -> float:
    """An object's or a proof's mass, kg: positive and at most :data:`MAX_THROWN_MASS`; beyond it, a
    mass in grams is likelier, and the message says so.

    Examples
    --------
    >>> from tumble.analysis.tensor.device import check_thrown_mass
    >>> check_thrown_mass("--mass", 0.482)
    0.482
    >>> check_thrown_mass("--mass", 482)
    Traceback (most recent call last):
    ...
    ValueError: --mass = 482 kg is beyond 100 kg, more than anything thrown by hand: in grams? (482 g is 0.482 kg)
    """
    mass = check_positive(field, value, "kg")
    if mass < MIN_THROWN_MASS:  # 1e-300 read as "the part's mass 0.10067 kg must be less than the whole's 0.10067 kg"
        raise ValueError(f"{field} = {value!r} kg is below {MIN_THROWN_MASS:g} kg (a gram), too light to show in a throw "
                         f"with a device: in tonnes? ({value!r} t is {mass * 1000:g} kg)")
    if mass > MAX_THROWN_MASS:
        raise ValueError(f"{field} = {value!r} kg is beyond {MAX_THROWN_MASS:g} kg, more than anything thrown by hand: "
                         f"in grams? ({value!r} g is {mass / 1000:g} kg)")
    return mass


#: The signed axes ``Device.sensor_axes`` may name: an axis of the log, ``-`` for its opposite.
AXIS_NAMES = ("x", "-x", "y", "-y", "z", "-z")
_AXES_ALLOWED = ('3 of "x", "-x", "y", "-y", "z", "-z", one for each of the sensor frame\'s x, y, z, '
                 'together a proper rotation (each log axis once, determinant +1)')


def _optional_positive(field_name: str, value: object, unit: str) -> float | None:
    return None if value is None else check_positive(field_name, value, unit)


def _tensor(field_name: str, value: object) -> Matrix3:
    """A (3,) of principal moments along the sensor axes or a symmetric (3, 3), kg m^2, physical."""
    a = check_vectors(field_name, value, "kg m^2", size=None)  # type: ignore[arg-type]
    if a.shape == (3,):
        a = np.diag(a)
    if a.shape != (3, 3):
        raise ValueError(f"{field_name} = {short_repr(value)} must be 3 moments or a 3x3 tensor (kg m^2), "
                         f"not shape {a.shape}")
    return check_inertia(a, what=field_name)


def axes_matrix(axes: object, field_name: str = "sensor_axes") -> Matrix3:
    """The rotation ``R`` that takes a vector from the log's axes to the sensor frame's,
    ``v_frame = R v_log``, from the sensor frame's axes named as signed axes of the log.

    ``axes[i]`` is the log's axis along the frame's axis ``i`` (``"-y"``: the log's ``-y``), so
    ``R[i, j] = +-1`` where ``axes[i]`` names the log's axis ``j``: a signed permutation, which is
    a rotation (not a reflection) only when its determinant is +1 (e.g. ``["x", "-y", "-z"]``, a
    board mounted upside down, is the half turn about x; ``["x", "y", "-z"]`` is a mirror and is
    refused).

    Parameters
    ----------
    axes : sequence of 3 str
        Each of :data:`AXIS_NAMES` (``"+x"`` is ``"x"``), the log's axes each once.
    field_name : str
        How a message names the value.

    Returns
    -------
    ndarray, shape (3, 3)
        Entries 0 and +-1.

    Raises
    ------
    ValueError
        One line naming the field, the value as given and what is allowed.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.device import axes_matrix
    >>> R = axes_matrix(["x", "-y", "-z"])   # a board mounted upside down: the half turn about x
    >>> R.astype(int).tolist(), (R @ [1.0, 2.0, 3.0]).tolist()
    ([[1, 0, 0], [0, -1, 0], [0, 0, -1]], [1.0, -2.0, -3.0])
    >>> axes_matrix(["x", "y", "-z"])
    Traceback (most recent call last):
    ...
    ValueError: sensor_axes = ['x', 'y', '-z'] is a mirror image (determinant -1), not a rotation; allowed: 3 of "x", "-x", "y", "-y", "z", "-z", one for each of the sensor frame's x, y, z, together a proper rotation (each log axis once, determinant +1)
    """
    names = _axis_names(axes, field_name)
    R = np.zeros((3, 3))
    for i, name in enumerate(names):
        R[i, "xyz".index(name[-1])] = -1.0 if name.startswith("-") else 1.0
    if sorted(name[-1] for name in names) != ["x", "y", "z"]:
        raise ValueError(f"{field_name} = {short_repr(axes)} names a log axis twice; allowed: {_AXES_ALLOWED}")
    if np.linalg.det(R) < 0:
        raise ValueError(f"{field_name} = {short_repr(axes)} is a mirror image (determinant -1), not a rotation; "
                         f"allowed: {_AXES_ALLOWED}")
    return R


def _axis_names(axes: object, field_name: str) -> tuple[str, str, str]:
    """``axes`` as three of :data:`AXIS_NAMES` (a leading ``+`` dropped, spaces and case ignored)."""
    if not isinstance(axes, (list, tuple)) or len(axes) != 3:
        raise ValueError(f"{field_name} = {short_repr(axes)} must be a list of 3 axes; allowed: {_AXES_ALLOWED}")
    names = []
    for a in axes:
        name = a.strip().lower().removeprefix("+") if isinstance(a, str) else None
        if name not in AXIS_NAMES:
            raise ValueError(f"{field_name} = {short_repr(axes)}: {a!r} is not an axis; allowed: {_AXES_ALLOWED}")
        names.append(name)
    return names[0], names[1], names[2]


def _motor_poles(value: object) -> int:
    """The motor's magnet poles: a whole number, even, >= 2."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 2 or value % 2:
        raise ValueError(f"device.motor_poles = {short_repr(value)} must be an even whole number >= 2 (the motor's "
                         "magnet poles: 14 on most small brushless motors)")
    return int(value)


def _motor_index(value: object) -> int:
    """Which motor of the log is the rotor's: 0 to 7 (Betaflight logs up to 8)."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 0 <= value <= 7:
        raise ValueError(f"device.motor_index = {short_repr(value)} must be a whole number from 0 to 7 (eRPM[0] to "
                         "eRPM[7] of the log)")
    return int(value)


def _optional_array(field_name: str, value: object, shape: tuple[int, ...], unit: str, *,
                    nonnegative: bool = False) -> FloatArray | None:
    if value is None:
        return None
    a = check_vectors(field_name, value, unit, size=None)  # type: ignore[arg-type]
    if a.shape != shape:
        raise ValueError(f"{field_name} = {short_repr(value)} must have shape {shape} ({unit}), not {a.shape}")
    if nonnegative and np.any(a < 0):
        raise ValueError(f"{field_name} = {short_repr(value)} must not be negative ({unit})")
    return a


#: The largest entry of a gyroscope's distortion: a MEMS gyroscope's sensitivity and cross-axis
#: errors are within +-1 % and 2 % on their data sheets; beyond 10 % the readings are not a
#: gyroscope's rates (a unit, an axis or a sign wrong).
MAX_DISTORTION = 0.1


def _speed_range(value: object) -> tuple[float, float] | None:
    """The calibration throws' lowest and highest rotor top speeds, rad/s: two numbers, 0 < low <= high."""
    a = _optional_array("device.rotor_speed_range", value, (2,), "rad/s", nonnegative=True)
    if a is None:
        return None
    if not 0.0 < a[0] <= a[1]:
        raise ValueError(f"device.rotor_speed_range = {short_repr(value)} must be the lowest and the highest top speed, "
                         "0 < low <= high (rad/s; tumble calibrate writes it)")
    return float(a[0]), float(a[1])


def _distortion(value: object) -> FloatArray | None:
    """A gyroscope's distortion: 3 x 3, symmetric, trace-free, entries within :data:`MAX_DISTORTION`."""
    D = _optional_array("device.gyro_distortion", value, (3, 3), "")
    if D is None:
        return None
    scale = max(float(np.abs(D).max()), 1e-12)
    if np.abs(D - D.T).max() > 1e-9 * scale or abs(float(np.trace(D))) > 1e-9 * scale:
        raise ValueError(f"device.gyro_distortion = {short_repr(value)} must be symmetric and trace-free (the part "
                         "of a gyroscope's distortion that throws determine: tumble calibrate writes it)")
    if np.abs(D).max() > MAX_DISTORTION:
        raise ValueError(f"device.gyro_distortion = {short_repr(value)} must have entries within +-{MAX_DISTORTION:g} "
                         "(a gyroscope's sensitivity and cross-axis errors are of 1-2 %)")
    return D


@dataclass(frozen=True)
class Device:
    """The measuring device: its mass, rotor and (once calibrated) its own mass properties.

    Attributes
    ----------
    mass : float
        kg, the device with its rotor.
    rotor_axis : ndarray, shape (3,)
        Unit vector, sensor frame: the rotor's angular velocity relative to the device for a
        positive logged speed (given any length, stored normalised).
    rotor_inertia, rotor_inertia_std : float or None
        ``J_r``, the rotor's axial moment of inertia and its standard uncertainty, kg m^2; None
        when not known (then only ratios of tensors are determined: calibrate first).
    inertia, inertia_std : ndarray, shape (3, 3), or None
        The device's tensor about its own centre of mass, sensor frame, and the standard
        uncertainty of each entry, kg m^2.
    center_of_mass, center_of_mass_std : ndarray, shape (3,), or None
        The device's centre of mass from the accelerometer, sensor frame, m, and its std.
    motor_poles : int
        The rotor's motor's magnet poles (even, >= 2; 14 by default, most small brushless
        motors): its electrical speed is ``motor_poles / 2`` times the mechanical one.
    motor_index : int
        Which motor of a blackbox log drives the rotor: ``eRPM[motor_index]`` (0 to 7, default 0).
    gyro_full_scale : float
        The gyroscope's full scale, **deg/s** (as flight controllers state it; default 2000).
    gyro_resolution : float or None
        deg/s per count of a blackbox log's gyroscope (``gyroADC``), > 0 and at most the full
        scale; None (default): the sensor's LSB, ``gyro_full_scale / 32768`` (16 bits).
    sensor_axes : tuple of 3 str
        The sensor frame's x, y, z as signed axes of a blackbox log (:func:`axes_matrix`; the
        board's mounting), default ``("x", "y", "z")``. Throw files in the sensor frame itself
        (:mod:`tumble.io.throwfile`) are not turned.
    gyro_scale_std, gyro_misalignment_std, rotor_axis_std : float
        The stated standard uncertainties of the gyroscope's scale factor per axis (relative,
        default 0.003), its misalignment per pair of axes (rad, default 0.005) and the rotor
        axis's direction (rad, default 0.0175, 1 degree), carried into every tensor's
        uncertainty (:class:`tumble.analysis.tensor.sensors.SensorErrors`: a typical MEMS data
        sheet's values; 0 for a device whose sensors were calibrated to better).
    gyro_distortion, gyro_distortion_std : ndarray, shape (3, 3), or None
        The gyroscope's distortion as calibrated (``tumble calibrate``), ``omega_read = (E +
        gyro_distortion) omega``, symmetric and trace-free (the part throws can see; the common
        scale and the axes' turn stay with ``gyro_scale_std`` and ``gyro_misalignment_std``;
        the calibration writes its cross-axis terms, the diagonal 0 with the stated scale's
        std: :func:`~tumble.analysis.tensor.calibrate.calibrated_sensors`), and each entry's
        standard uncertainty. With it, the readings are corrected before every fit and
        ``rotor_axis`` is the calibrated axis, whose uncertainty is ``rotor_axis_std``.
    rotor_speed_range : (float, float) or None
        The lowest and highest of the rotor's top speeds (:attr:`Throw.top_speed
        <tumble.analysis.tensor.Throw.top_speed>`) in the calibration's throws, rad/s (``tumble
        calibrate`` writes it). The firmware spins the rotor to the same plateau in every throw,
        and the tensor's scale is the rotor's: :func:`~tumble.analysis.tensor.fit_tensor` leaves
        out a throw whose top speed is more than :data:`ROTOR_SPEED_RATIO` times beyond this range
        (a speed in rpm read as rad/s makes the tensor 9.5 times too large).

    Examples
    --------
    >>> from tumble.analysis.tensor import Device
    >>> device = Device(mass=0.10067, rotor_axis=[0.0, 0.0, -2.0], rotor_inertia=1.7e-6)
    >>> device.rotor_axis.tolist(), device.calibrated
    ([0.0, 0.0, -1.0], False)
    >>> device.motor_poles, device.gyro_lsb, device.sensor_axes   # the defaults: deg/s per count
    (14, 0.06103515625, ('x', 'y', 'z'))
    >>> Device(mass=0.1, rotor_axis=[0, 0, 1], motor_poles=13)   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: device.motor_poles = 13 must be an even whole number >= 2 (the motor's magnet poles: ...)
    >>> Device(mass=-1.0, rotor_axis=[0, 0, 1])
    Traceback (most recent call last):
    ...
    ValueError: device.mass = -1.0 must be a positive finite number (kg)
    """

    mass: float
    rotor_axis: Vector3
    rotor_inertia: float | None = None
    rotor_inertia_std: float | None = None
    inertia: Matrix3 | None = field(default=None, repr=False)
    inertia_std: Matrix3 | None = field(default=None, repr=False)
    center_of_mass: Vector3 | None = None
    center_of_mass_std: Vector3 | None = None
    motor_poles: int = 14
    motor_index: int = 0
    gyro_full_scale: float = 2000.0
    gyro_resolution: float | None = None
    sensor_axes: tuple[str, str, str] = ("x", "y", "z")
    gyro_scale_std: float = 0.003
    gyro_misalignment_std: float = 0.005
    rotor_axis_std: float = 0.0175
    gyro_distortion: Matrix3 | None = field(default=None, repr=False)
    gyro_distortion_std: Matrix3 | None = field(default=None, repr=False)
    rotor_speed_range: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        s = object.__setattr__
        s(self, "mass", check_positive("device.mass", self.mass, "kg", at_most=MAX_DEVICE_MASS))
        s(self, "rotor_axis", np.array(check_direction("device.rotor_axis", self.rotor_axis)))
        s(self, "rotor_inertia", _optional_positive("device.rotor_inertia", self.rotor_inertia, "kg m^2"))
        if self.rotor_inertia_std is not None:
            s(self, "rotor_inertia_std", check_positive("device.rotor_inertia_std", self.rotor_inertia_std, "kg m^2",
                                                        allow_zero=True))
        if self.inertia is not None:
            s(self, "inertia", _tensor("device.inertia", self.inertia))
        s(self, "inertia_std", _optional_array("device.inertia_std", self.inertia_std, (3, 3), "kg m^2",
                                               nonnegative=True))
        s(self, "center_of_mass", _optional_array("device.center_of_mass", self.center_of_mass, (3,), "m"))
        s(self, "center_of_mass_std", _optional_array("device.center_of_mass_std", self.center_of_mass_std, (3,), "m",
                                                      nonnegative=True))
        s(self, "motor_poles", _motor_poles(self.motor_poles))
        s(self, "motor_index", _motor_index(self.motor_index))
        s(self, "gyro_full_scale", check_positive("device.gyro_full_scale", self.gyro_full_scale, "deg/s"))
        if self.gyro_resolution is not None:
            lsb = check_positive("device.gyro_resolution", self.gyro_resolution, "deg/s")
            if lsb > self.gyro_full_scale:
                raise ValueError(f"device.gyro_resolution = {self.gyro_resolution!r} must be at most the full scale "
                                 f"gyro_full_scale = {self.gyro_full_scale:g} (deg/s per count)")
            s(self, "gyro_resolution", lsb)
        for name, unit in (("gyro_scale_std", ""), ("gyro_misalignment_std", "rad"), ("rotor_axis_std", "rad")):
            s(self, name, check_positive(f"device.{name}", getattr(self, name), unit, allow_zero=True))
        s(self, "gyro_distortion", _distortion(self.gyro_distortion))
        s(self, "gyro_distortion_std", _optional_array("device.gyro_distortion_std", self.gyro_distortion_std, (3, 3),
                                                       "", nonnegative=True))
        if (self.gyro_distortion is None) != (self.gyro_distortion_std is None):
            given = "gyro_distortion" if self.gyro_distortion is not None else "gyro_distortion_std"
            raise ValueError(f"device.{given} given without the other: gyro_distortion and gyro_distortion_std come "
                             "together (tumble calibrate writes both)")
        s(self, "rotor_speed_range", _speed_range(self.rotor_speed_range))
        axes_matrix(self.sensor_axes, "device.sensor_axes")  # the value as given in its messages
        s(self, "sensor_axes", _axis_names(self.sensor_axes, "device.sensor_axes"))
        self._check_sizes()

    def _check_sizes(self) -> None:
        """Refuse a rotor, a tensor or a centre of mass no hand-thrown device of this mass has
        (:data:`MAX_DEVICE_SIZE`), and a rotor whose axial moment exceeds the device's own about
        its axis: the rotor is part of the device (parallel axes: ``J_r <= a . I a``)."""
        slip = "(a unit slip: a moment in g cm^2 or with its exponent lost?)"
        moments = {"rotor_inertia": self.rotor_inertia}
        if self.inertia is not None:
            moments["inertia"] = float(np.max(np.linalg.eigvalsh(self.inertia)))
        for name, J in moments.items():
            if J is not None and math.sqrt(J / self.mass) > MAX_DEVICE_SIZE:
                raise ValueError(f"device.{name}: a moment of {J:.6g} kg m^2 is a radius of gyration of "
                                 f"{math.sqrt(J / self.mass):.3g} m on a {self.mass:g} kg device, beyond any thrown by "
                                 f"hand ({MAX_DEVICE_SIZE:g} m) {slip}")
        if self.rotor_inertia is not None and self.inertia is not None:
            own = float(self.rotor_axis @ self.inertia @ self.rotor_axis)
            if self.rotor_inertia > own:
                raise ValueError(f"device.rotor_inertia = {self.rotor_inertia:.6g} kg m^2 exceeds the device's own moment "
                                 f"about the rotor's axis, {own:.6g} kg m^2, of which the rotor is a part {slip}")
        if self.center_of_mass is not None and float(np.linalg.norm(self.center_of_mass)) > MAX_DEVICE_SIZE:
            raise ValueError(f"device.center_of_mass = {np.round(self.center_of_mass, 6).tolist()} m lies "
                             f"{float(np.linalg.norm(self.center_of_mass)):.3g} m from the sensor, beyond any device "
                             f"thrown by hand ({MAX_DEVICE_SIZE:g} m): a centre in mm?")

    def _parts(self) -> list[tuple[str, str]]:
        """What the device's repr and table show: its mass, its rotor and, once calibrated, its tensor
        (principal moments) and centre of mass."""
        rows = [("mass", f"{fmt(self.mass)} kg"), ("rotor axis", vec(self.rotor_axis))]
        if self.rotor_inertia is not None:
            rows.append(("rotor inertia", f"{with_std(self.rotor_inertia, self.rotor_inertia_std)} kg m^2"))
        if self.inertia is not None:
            rows.append(("principal moments", f"{vec(np.linalg.eigvalsh(self.inertia))} kg m^2"))
        if self.center_of_mass is not None:
            rows.append(("centre of mass", f"{vec(1e3 * self.center_of_mass)} mm"))
        rows.append(("calibrated", ("yes" + (", its gyroscope's distortion too" if self.gyro_distortion is not None else ""))
                     if self.calibrated else "no"))
        return rows

    def __repr__(self) -> str:
        """``Device(mass 0.1007 kg, rotor axis (0, 0, -1), rotor inertia 1.699e-06 +- 2.4e-09 kg m^2, ...)``.

        Examples
        --------
        >>> from tumble.analysis.tensor import Device
        >>> Device(mass=0.10067, rotor_axis=[0.0, 0.0, -2.0], rotor_inertia=1.7e-6)
        Device(mass 0.1007 kg, rotor axis (0, 0, -1), rotor inertia 1.7e-06 kg m^2, calibrated no)
        """
        return result_repr("Device", [f"{label} {value}" for label, value in self._parts()])

    def _repr_html_(self) -> str:
        return result_html("Device", self._parts())

    @property
    def gyro_lsb(self) -> float:
        """deg/s per count of a blackbox log's gyroscope: :attr:`gyro_resolution`, else the
        sensor's LSB ``gyro_full_scale / 32768`` (a 16-bit reading spans +-full scale).

        Examples
        --------
        >>> from tumble.analysis.tensor import Device
        >>> Device(0.1, [0, 0, 1], gyro_full_scale=1000).gyro_lsb, Device(0.1, [0, 0, 1], gyro_resolution=1).gyro_lsb
        (0.030517578125, 1.0)
        """
        return self.gyro_resolution if self.gyro_resolution is not None else self.gyro_full_scale / 32768.0

    @property
    def sensor_rotation(self) -> Matrix3:
        """:func:`axes_matrix` of :attr:`sensor_axes`: ``v_sensor_frame = R v_log``.

        Examples
        --------
        >>> from tumble.analysis.tensor import Device
        >>> Device(0.1, [0, 0, 1], sensor_axes=("y", "-x", "z")).sensor_rotation.astype(int).tolist()
        [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]
        """
        return axes_matrix(self.sensor_axes, "device.sensor_axes")

    @property
    def calibrated(self) -> bool:
        """Whether the rotor's inertia, the device's tensor and its centre of mass are all known.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor import Device
        >>> Device(0.1, [0, 0, 1], 1.7e-6, 0.0, np.diag([3e-5, 3e-5, 5e-5]), None, [0.0, 0.0, 0.01]).calibrated
        True
        """
        return self.rotor_inertia is not None and self.inertia is not None and self.center_of_mass is not None


@dataclass(frozen=True)
class Proof:
    """A body of known mass properties fixed to the device for the calibration.

    Attributes
    ----------
    mass : float
        kg.
    inertia : ndarray, shape (3, 3)
        About its own centre of mass, along the sensor axes, kg m^2 (given as 3 moments along
        the sensor axes or a 3x3 tensor).

    Examples
    --------
    >>> from tumble.analysis.tensor import Proof
    >>> Proof(0.346, [1.675805e-4, 1.300972e-4, 2.450833e-4]).inertia.diagonal().tolist()
    [0.0001675805, 0.0001300972, 0.0002450833]
    """

    mass: float
    inertia: Matrix3

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", check_thrown_mass("proof.mass", self.mass))
        object.__setattr__(self, "inertia", _tensor("proof.inertia", self.inertia))
        J = float(np.max(np.linalg.eigvalsh(self.inertia)))
        if math.sqrt(J / self.mass) > MAX_DEVICE_SIZE:  # thrown by hand with the device: kg cm^2 read as kg m^2
            raise ValueError(f"proof.inertia: a moment of {J:.6g} kg m^2 is a radius of gyration of "
                             f"{math.sqrt(J / self.mass):.3g} m on a {self.mass:g} kg body, beyond any thrown by hand "
                             f"({MAX_DEVICE_SIZE:g} m) (a unit slip: moments in kg cm^2 or g cm^2? They are kg m^2)")
