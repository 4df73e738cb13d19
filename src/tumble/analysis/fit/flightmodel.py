"""What replays one fitted flight: :class:`FlightModel`, the fit's model of it in a few numbers.

A flight's model (:mod:`tumble.analysis.fit.model`) is Euler's equations for the body of the
fitted ratios ``(I1/I3, I2/I3, 1)``, torque-free or with the fitted per-axis drag
(:mod:`tumble.dynamics.models.drag`), through ``omega0`` (principal frame) at the time ``t0``
(the flight's first sample, or where the flight search anchored it: samples before it are the
motion integrated backward), seen by the sensor as ``R^T omega + b``. Of a joint fit of many
flights the ratios and the drag are the shared ones, ``omega0`` the flight's own, ``R`` and
``b`` its recording's. ``tumble fit`` writes one per used flight in fit.json's
``"flight_models"``; ``tumble view DIR`` replays them.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike
from ...validation import check_number, check_vector, triangle_excess
from .. import _display
from .model import DRAG_MODELS, principal_rates
from .result import RotationFit
from .solve import Solution

__all__ = ["FLIGHT_MODEL_KEYS", "FlightModel"]

#: The keys of a fit.json ``"flight_models"`` entry (``tumble fit`` adds ``"input"``).
FLIGHT_MODEL_KEYS = ("toss", "recording", "start", "end", "t0", "I1_over_I3", "I2_over_I3", "omega0", "drag",
                     "drag_coefficients", "sensor_rotation_rotvec", "bias")


@dataclass(frozen=True)
class FlightModel:
    """The fit's model of one flight (module docstring), SI units.

    Attributes
    ----------
    start, end : float
        The flight's first and last sample time, s (its recording's clock).
    t0 : float
        The time of ``omega0``, s (same clock).
    ratios : ndarray, shape (2,)
        ``I1/I3``, ``I2/I3`` of the model (dimensionless).
    omega0 : ndarray, shape (3,)
        Angular velocity at ``t0``, principal frame, rad/s.
    drag : str
        ``"none"``, ``"linear"`` or ``"quadratic"``.
    drag_coefficients : ndarray, shape (3,)
        The drag about each principal axis divided by ``I3``: 1/s (linear) or 1/rad (quadratic).
    rotvec : ndarray, shape (3,)
        The rotation from the sensor's axes to the principal axes, as a rotation vector, rad.
    bias : ndarray, shape (3,)
        The gyroscope's bias, sensor axes, rad/s.
    recording : int
        The recording it is in (index in the list fitted; 0 for one).
    toss : int or None
        Its index in fit.json's ``"tosses"`` (None for a ``--start``/``--end`` fit).

    Examples
    --------
    >>> from tumble.analysis.fit.flightmodel import FlightModel
    >>> m = FlightModel(start=2.0, end=2.8, t0=2.0, ratios=[0.3, 0.8], omega0=[0.5, 9.0, 0.4], drag="none",
    ...                 drag_coefficients=[0.0, 0.0, 0.0], rotvec=[0.0, 0.0, 0.0], bias=[0.0, 0.0, 0.0])
    >>> m.moments.tolist(), FlightModel.from_summary(m.summary()) == m
    ([0.3, 0.8, 1.0], True)
    >>> FlightModel.from_summary({**m.summary(), "drag": "cubic"}, "flight_models[0]")
    Traceback (most recent call last):
    ...
    ValueError: flight_models[0].drag = 'cubic' must be one of 'none', 'linear', 'quadratic'
    """

    start: float
    end: float
    t0: float
    ratios: np.ndarray
    omega0: np.ndarray
    drag: str
    drag_coefficients: np.ndarray
    rotvec: np.ndarray
    bias: np.ndarray
    recording: int = 0
    toss: int | None = None

    def __repr__(self) -> str:
        return _display.model_repr(self)

    def __post_init__(self) -> None:
        self._check("")

    def _check(self, where: str) -> None:
        name = (where + ".") if where else ""
        for key, unit in (("start", "s"), ("end", "s"), ("t0", "s")):
            object.__setattr__(self, key, check_number(name + key, getattr(self, key), unit))
        if not self.start < self.end:
            raise ValueError(f"{name}start = {self.start} must be before {name}end = {self.end} (s)")
        for key, unit in (("omega0", "rad/s"), ("drag_coefficients", "1/s or 1/rad"), ("rotvec", "rad"),
                          ("bias", "rad/s")):
            object.__setattr__(self, key, np.array(check_vector(name + key, _listed(getattr(self, key)), unit)))
        x, y = (check_number(f"{name}{k}", v, "dimensionless") for k, v in
                zip(("I1_over_I3", "I2_over_I3"), _pair(self.ratios, name)))
        # the closed triangle of a rigid body (tumble.analysis.fit.triangle), with room for round-off
        if not (0.0 < x <= y + 1e-12 and y <= 1.0 + 1e-12 and triangle_excess((x, y, 1.0)) <= 1e-9):
            raise ValueError(f"{name}I1_over_I3, I2_over_I3 = {x}, {y} must lie in the triangle of a rigid body: "
                             "0 < I1/I3 <= I2/I3 <= 1 and I1/I3 + I2/I3 >= 1")
        object.__setattr__(self, "ratios", np.array([x, y]))
        if self.drag not in DRAG_MODELS:
            raise ValueError(f"{name}drag = {self.drag!r} must be one of " + ", ".join(map(repr, DRAG_MODELS)))
        if np.any(self.drag_coefficients < 0):
            raise ValueError(f"{name}drag_coefficients = {self.drag_coefficients.tolist()} must not be negative")
        if isinstance(self.recording, bool) or not isinstance(self.recording, (int, np.integer)) or self.recording < 0:
            raise ValueError(f"{name}recording = {self.recording!r} must be a whole number >= 0")
        if self.toss is not None and (isinstance(self.toss, bool) or not isinstance(self.toss, (int, np.integer))
                                      or self.toss < 0):
            raise ValueError(f"{name}toss = {self.toss!r} must be a whole number >= 0, or null")

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, FlightModel):
            return NotImplemented
        return self.summary() == other.summary()

    @property
    def moments(self) -> np.ndarray:
        """``(I1/I3, I2/I3, 1)``: the principal moments in units of ``I3``.

        Examples
        --------
        >>> from tumble.analysis.fit.flightmodel import FlightModel
        >>> FlightModel(0.0, 1.0, 0.0, [0.5, 0.5], [0.0, 0.0, 3.0], "none", [0.0] * 3, [0.0] * 3, [0.0] * 3).moments.tolist()
        [0.5, 0.5, 1.0]
        """
        return np.array([self.ratios[0], self.ratios[1], 1.0])

    @property
    def sensor_rotation(self) -> Rotation:
        """Sensor axes to principal axes: ``omega_principal = sensor_rotation.apply(omega_sensor - bias)``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.flightmodel import FlightModel
        >>> m = FlightModel(0.0, 1.0, 0.0, [0.5, 0.5], [0.0, 0.0, 3.0], "none", [0.0] * 3, [0.0, 0.0, np.pi / 2], [0.0] * 3)
        >>> m.sensor_rotation.apply([1.0, 0.0, 0.0]).round(12).tolist()   # the sensor's x is the principal 2 axis
        [0.0, 1.0, 0.0]
        """
        return Rotation.from_rotvec(self.rotvec)

    def omega(self, t: ArrayLike) -> np.ndarray:
        """The model's angular velocity at the times ``t`` (s, the recording's clock; before ``t0``
        integrated backward), principal frame, rad/s, shape (len(t), 3): the fit's own model
        function (:func:`~tumble.analysis.fit.model.principal_rates`).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.flightmodel import FlightModel
        >>> m = FlightModel(0.0, 1.0, 0.5, [0.5, 0.5], [1.0, 0.0, 2.0], "none", [0.0] * 3, [0.0] * 3, [0.0] * 3)
        >>> w = m.omega([0.0, 0.5, 1.0])   # a symmetric top: omega_3 constant, (omega_1, omega_2) turning at 2 rad/s
        >>> w[:, 2].tolist(), bool(np.allclose(w[0, :2], [np.cos(1.0), -np.sin(1.0)]))
        ([2.0, 2.0, 2.0], True)
        """
        tau = np.asarray(t, float).reshape(-1) - self.t0
        with np.errstate(all="ignore"):
            return principal_rates(self.moments[None], self.omega0[None], tau, self.drag, self.drag_coefficients[None])[0]

    def to_principal(self, omega_sensor: ArrayLike) -> np.ndarray:
        """Gyroscope samples (sensor axes, rad/s, shape (..., 3)) in the principal frame, bias removed.

        Examples
        --------
        >>> from tumble.analysis.fit.flightmodel import FlightModel
        >>> m = FlightModel(0.0, 1.0, 0.0, [0.5, 0.5], [0.0, 0.0, 3.0], "none", [0.0] * 3, [0.0] * 3, [0.1, 0.0, 0.0])
        >>> m.to_principal([[1.1, 2.0, 3.0]]).round(12).tolist()
        [[1.0, 2.0, 3.0]]
        """
        w = np.asarray(omega_sensor, float)
        return np.asarray(self.sensor_rotation.apply((w - self.bias).reshape(-1, 3)), float).reshape(w.shape)

    def summary(self) -> dict[str, Any]:
        """The fit.json ``"flight_models"`` entry (:data:`FLIGHT_MODEL_KEYS`), JSON-ready.

        Examples
        --------
        >>> from tumble.analysis.fit.flightmodel import FLIGHT_MODEL_KEYS, FlightModel
        >>> m = FlightModel(0.0, 1.0, 0.0, [0.5, 0.5], [0.0, 0.0, 3.0], "none", [0.0] * 3, [0.0] * 3, [0.0] * 3, toss=4)
        >>> tuple(m.summary()) == FLIGHT_MODEL_KEYS, m.summary()["toss"], m.summary()["omega0"]
        (True, 4, [0.0, 0.0, 3.0])
        """
        return {"toss": None if self.toss is None else int(self.toss), "recording": int(self.recording),
                "start": float(self.start), "end": float(self.end), "t0": float(self.t0),
                "I1_over_I3": float(self.ratios[0]), "I2_over_I3": float(self.ratios[1]),
                "omega0": [float(v) for v in self.omega0], "drag": self.drag,
                "drag_coefficients": [float(v) for v in self.drag_coefficients],
                "sensor_rotation_rotvec": [float(v) for v in self.rotvec], "bias": [float(v) for v in self.bias]}

    @classmethod
    def from_summary(cls, entry: Mapping[str, Any], where: str = "flight model") -> FlightModel:
        """The model of a fit.json ``"flight_models"`` entry; a bad entry gets one line naming
        ``where`` and the key.

        Examples
        --------
        >>> from tumble.analysis.fit.flightmodel import FlightModel
        >>> FlightModel.from_summary({"toss": 3, "recording": 0, "start": 0.0}, "flight_models[2]")
        Traceback (most recent call last):
        ...
        ValueError: flight_models[2] lacks "end" (and 8 more keys): expected toss, recording, start, end, t0, I1_over_I3, I2_over_I3, omega0, drag, drag_coefficients, sensor_rotation_rotvec, bias
        """
        if not isinstance(entry, Mapping):
            raise ValueError(f"{where} = {str(entry)[:60]!r} must be an object with the keys "
                             + ", ".join(FLIGHT_MODEL_KEYS))
        missing = [k for k in FLIGHT_MODEL_KEYS if k not in entry]
        if missing:
            more = f" (and {len(missing) - 1} more keys)" if len(missing) > 1 else ""
            raise ValueError(f'{where} lacks "{missing[0]}"{more}: expected ' + ", ".join(FLIGHT_MODEL_KEYS))
        model = object.__new__(cls)
        values = {"start": entry["start"], "end": entry["end"], "t0": entry["t0"], "ratios": (entry["I1_over_I3"], entry["I2_over_I3"]),
                  "omega0": entry["omega0"], "drag": entry["drag"], "drag_coefficients": entry["drag_coefficients"],
                  "rotvec": entry["sensor_rotation_rotvec"], "bias": entry["bias"], "recording": entry["recording"],
                  "toss": entry["toss"]}
        for key, value in values.items():
            object.__setattr__(model, key, value)
        model._check(where)
        return model

    @classmethod
    def of_solution(cls, sol: Solution, j: int, start: float, end: float, t0: float, recording: int = 0,
                    toss: int | None = None) -> FlightModel:
        """The model of flight ``j`` of a solved (one- or many-flight) model whose times are counted from ``t0``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.flightmodel import FlightModel
        >>> from tumble.analysis.fit.single import fit_solution
        >>> from tumble.dynamics.methods.exact_omega import free_omega
        >>> t = np.linspace(1.0, 2.0, 101)   # omega0 at t = 1.2 s, samples before it fitted backward
        >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t - 1.2)[0] + np.random.default_rng(1).normal(0.0, 0.01, (101, 3))
        >>> sol = fit_solution(t, w, np.ones(w.shape, bool), rotation=False, bias=False, drag="none", t0=1.2)
        >>> m = FlightModel.of_solution(sol, 0, start=1.0, end=2.0, t0=1.2)
        >>> m.t0, m.ratios.round(2).tolist(), m.omega0.round(1).tolist()
        (1.2, [0.5, 0.8], [3.0, 1.0, 6.0])
        """
        m, P = sol.model, sol.P
        g = int(m.groups[j])
        rotvec = P[m.index["rotvec_x"] + 3 * g:m.index["rotvec_x"] + 3 * g + 3] if m.rotation else np.zeros(3)
        return cls(start=start, end=end, t0=t0, ratios=m.moments(P)[:2], omega0=m.omega0(P)[j], drag=m.drag,
                   drag_coefficients=m.drag_vector(P), rotvec=np.array(rotvec, float), bias=m.bias_vector(P, g),
                   recording=recording, toss=toss)

    @classmethod
    def of_fit(cls, fit: RotationFit, recording: int = 0, toss: int | None = None) -> FlightModel:
        """The model of a one-flight fit of :func:`~tumble.analysis.fit.fit_rotation` (its own ratios,
        drag, rotation and bias; ``omega0`` at its first sample).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit import fit_rotation
        >>> from tumble.analysis.fit.flightmodel import FlightModel
        >>> from tumble.dynamics.methods.exact_omega import free_omega
        >>> t = np.linspace(1.0, 2.0, 101)
        >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t - 1.0)[0]
        >>> fit = fit_rotation(t, w + np.random.default_rng(1).normal(0.0, 0.01, w.shape), sensor_rotation="identity", bias=False)
        >>> m = FlightModel.of_fit(fit)
        >>> m.start, m.end, m.ratios.round(2).tolist(), m.omega0.round(1).tolist()
        (1.0, 2.0, [0.5, 0.8], [3.0, 1.0, 6.0])
        """
        return cls(start=float(fit.t[0]), end=float(fit.t[-1]), t0=float(fit.t[0]), ratios=np.asarray(fit.ratios, float),
                   omega0=np.asarray(fit.omega0, float), drag=fit.drag,
                   drag_coefficients=np.nan_to_num(np.asarray(fit.drag_coefficients, float)),
                   rotvec=np.asarray(fit.sensor_rotation.as_rotvec(), float), bias=np.asarray(fit.bias, float),
                   recording=recording, toss=toss)


def _listed(value: object) -> object:
    return value.tolist() if isinstance(value, np.ndarray) else value


def _pair(value: object, name: str) -> tuple[object, object]:
    items = _listed(value)
    if not isinstance(items, (list, tuple)) or len(items) != 2:
        raise ValueError(f"{name}ratios = {value!r} must be the two numbers I1/I3, I2/I3")
    return items[0], items[1]
