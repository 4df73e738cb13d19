"""Synthetic throws of the real device (issue #42), for tests, examples and the coverage benchmark.

A throw's log (:func:`synthetic_throw`), sensor frame, as the device's flight controller writes it
(what its real logs show; :mod:`~tumble.analysis.tensor.firmware` holds the rotor's schedule and
the sensors' imperfections):

- **hand** (0.2-0.3 s): the arm swings the body up to its spin; the accelerometer reads the
  hand's push (1-2.5 g); samples at irregular 190-300 us steps; the rotor stopped (it reads 0);
- **the sensed release** (``apparent``): the accelerometer reads free fall, but the fingers still
  touch the body for 10-20 ms: their last push turns the rates by 0.2-0.6 rad/s away from any
  free motion (and the accelerometer reads 0.05-0.3 g of it); the free flight starts after it
  (``release``); samples every 248 us from here;
- **the rotor** starts 0.06-0.12 s after the sensed release and follows the firmware's schedule:
  idle ~200 rad/s, spin-up to 1230-1360 rad/s 0.16-0.17 s later, the brake back to ~210 rad/s
  ~0.36 s after its start; the air's drag on the flywheel, ``-k Omega^2`` along its axis (``k``
  2-8e-11 N m s^2, an external torque on the whole); the logged speed is the motor's eRPM,
  quantised, turned into rad/s with the pole count, its stamps up to 0.5 ms off the gyroscope's;
- **the log stops in flight** 0.55-0.59 s after the rotor's start (no catch: ``caught=True`` adds
  one, for loggers that run on);
- per-axis quadratic air drag on the body (``b_i`` 0.5-2e-6 N m s^2, :mod:`tumble.dynamics.models.drag`).

Sensors: the gyroscope's scale factors and misalignment (:class:`~tumble.analysis.tensor.firmware.Imperfections`,
one per device), a constant bias (0.01 rad/s per axis), white noise 0.01 rad/s, a vibration of
0.01 rad/s at the rotor's frequency, saturation at 2000 deg/s and 16-bit quantisation. The
accelerometer: at ``r`` from the centre of mass a free-falling accelerometer reads ``f = w' x r +
w x (w x r)`` (the acceleration of a point of a rigid body, Goldstein, Poole & Safko, *Classical
Mechanics*, 3rd ed., sec. 4.10, less gravity, which it does not sense), plus the air's drag
(0.05-0.5 m/s^2, fixed in the world and changing with the speed, so turning in the body frame), a jolt of 5-20 m/s^2 over 2-4 ms at each of the rotor's
switches (the motor's reaction shakes the structure), the flywheel's imbalance (``6e-7 m x
Omega^2``, ~1 m/s^2 at the plateau, turning with it) and white noise 0.3 m/s^2, all smoothed by
the firmware's low-pass (second-order, 100-200 Hz, causal), then the sensor's scale errors and
bias (the device's, :class:`~tumble.analysis.tensor.firmware.Imperfections`: 1 %, up to 0.1 m/s^2),
2048 LSB per g and the 16 g range.

The truth is integrated independently of the fit's model: Euler's equations of the gyrostat in
the angular-velocity form ``I w' = -w x (I w + h) - h' + tau`` (Hughes, *Spacecraft Attitude
Dynamics*, 1986, ch. 7) with ``h`` and ``h'`` from the schedule in closed form, by scipy's DOP853
at ``rtol = 1e-10``, in pieces between the rotor's switches (the fit integrates the momentum
form by RK4 over the samples, with the logged speed).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from ...dynamics.euler import momentum_rate_components
from ...dynamics.models.aero import drag_component
from ...mass.tensor import parallel_axis, rotate_inertia
from ...typing import ArrayLike, FloatArray, Matrix3, Vector3
from ..fit.accelsynth import attitude_from_rates
from ..fit.endings import smooth_noise
from .device import Device, Proof
from .throwlog import Throw
from .firmware import Imperfections, RotorSchedule, draw_imperfections, draw_schedule, logged_speed

__all__ = ["DEVICE_MASS", "GYRO_RANGE", "ROTOR_AXIS", "ROTOR_INERTIA", "TYPICAL_SEED", "Rigid", "ThrowTimes", "box",
           "calibrated_device", "combine", "drawn_device", "example_object", "random_object", "synthetic_throw",
           "throw_times", "true_device", "true_proof", "typical_imperfections"]

#: The device of the issue: mass, kg; rotor axis, sensor frame; rotor inertia, kg m^2.
DEVICE_MASS = 0.10067
#: The device's rotor axis, sensor frame (unit vector).
ROTOR_AXIS = (0.0, 0.0, -1.0)
#: The device's rotor inertia about its axis, kg m^2.
ROTOR_INERTIA = 1.7e-6
#: The gyroscope's range, rad/s (2000 deg/s).
GYRO_RANGE = np.deg2rad(2000.0)
_G = 9.80665


@dataclass(frozen=True)
class Rigid:
    """A rigid body's true mass properties, sensor frame: mass (kg), tensor about its own centre
    of mass (kg m^2) and the centre's position from the accelerometer (m).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.synthetic import Rigid
    >>> Rigid(1.0, np.eye(3), np.zeros(3)).mass
    1.0
    """

    mass: float
    inertia: Matrix3 = field(repr=False)
    center: Vector3


def box(mass: float, size: ArrayLike, center: ArrayLike, rotvec: ArrayLike = (0.0, 0.0, 0.0)) -> Rigid:
    """A uniform box of ``size`` (m, along its own axes), its axes turned by ``rotvec`` (rad)
    from the sensor's, its centre at ``center`` (m): ``I = m (b^2 + c^2) / 12, ...`` (Goldstein
    sec. 5.3) rotated as ``R I R^T``.

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import box
    >>> (box(12.0, (1.0, 2.0, 3.0), (0, 0, 0)).inertia.diagonal()).tolist()   # m (b^2 + c^2) / 12, ...
    [13.0, 10.0, 5.0]
    """
    a, b, c = (float(x) for x in size)
    I = mass / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    return Rigid(float(mass), rotate_inertia(I, Rotation.from_rotvec(np.asarray(rotvec, float))),
                 np.asarray(center, float))


def combine(*parts: Rigid) -> Rigid:
    """The rigid union of parts: ``M = sum m``, ``c = sum m c / M``, ``I = sum (I_k + m_k S(c_k - c))``
    (the parallel-axis theorem, Goldstein sec. 5.3).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.synthetic import Rigid, combine
    >>> dot = lambda x: Rigid(1.0, np.zeros((3, 3)), np.array([x, 0.0, 0.0]))
    >>> whole = combine(dot(-1.0), dot(1.0))   # two unit masses 2 m apart
    >>> whole.mass, whole.center.tolist(), whole.inertia.diagonal().tolist()
    (2.0, [0.0, 0.0, 0.0], [0.0, 2.0, 2.0])
    """
    M = sum(p.mass for p in parts)
    c = sum(p.mass * p.center for p in parts) / M
    I = sum(parallel_axis(p.inertia, p.mass, p.center - c) for p in parts)
    return Rigid(float(M), np.asarray(I), np.asarray(c))


def true_device() -> Rigid:
    """The synthetic device's true mass properties, rotor included: 0.10067 kg, principal
    moments 3.1, 4.4, 6.2e-5 kg m^2 turned a little from the sensor axes, its centre 11 mm below
    the accelerometer (the motor and flywheel under the board).

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import true_device
    >>> d = true_device()
    >>> d.mass, d.center.tolist()
    (0.10067, [0.004, -0.002, -0.011])
    """
    I = rotate_inertia(np.diag([3.1e-5, 4.4e-5, 6.2e-5]), Rotation.from_rotvec([0.1, -0.05, 0.2]))
    return Rigid(DEVICE_MASS, I, np.array([0.004, -0.002, -0.011]))


def true_proof() -> tuple[Proof, Rigid]:
    """The proof body of the issue (0.346 kg, moments along the sensor axes) and the truth of it
    fixed on the synthetic device (its centre 32 mm above the accelerometer).

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import true_proof
    >>> proof, placed = true_proof()
    >>> proof.mass, placed.center.tolist()
    (0.346, [0.002, 0.001, 0.032])
    """
    proof = Proof(0.346, [1.675805e-4, 1.300972e-4, 2.450833e-4])
    return proof, Rigid(proof.mass, proof.inertia, np.array([0.002, 0.001, 0.032]))


def example_object() -> Rigid:
    """An object to measure: a 0.6 kg box of 200 x 120 x 50 mm turned 0.3 rad about z, its
    centre 45 mm above the accelerometer and a little aside.

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import example_object
    >>> example_object().mass
    0.6
    """
    return box(0.6, (0.2, 0.12, 0.05), (0.01, -0.005, 0.045), (0.0, 0.0, 0.3))


def calibrated_device(relative_std: float = 0.0, center_std: float = 0.0) -> Device:
    """The synthetic device as a calibration would give it: its true values, with the rotor
    inertia's and the tensor's entries' std ``relative_std`` of their size and the centre's
    ``center_std`` (m).

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import calibrated_device
    >>> d = calibrated_device(0.01, 5e-4)
    >>> d.calibrated, d.rotor_inertia_std
    (True, 1.7e-08)
    """
    d = true_device()
    return Device(DEVICE_MASS, ROTOR_AXIS, ROTOR_INERTIA, relative_std * ROTOR_INERTIA, d.inertia,
                  relative_std * np.abs(d.inertia), d.center, np.full(3, float(center_std)))


def random_object(rng: np.random.Generator) -> Rigid:
    """A box of 0.3-1 kg and 120-250 x 80-160 x 30-80 mm, turned at random (0.3 rad per axis),
    its centre 30-60 mm above the accelerometer and up to 10 mm aside: an object to measure.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.synthetic import random_object
    >>> 0.3 <= random_object(np.random.default_rng(0)).mass <= 1.0
    True
    """
    return box(rng.uniform(0.3, 1.0), rng.uniform([0.12, 0.08, 0.03], [0.25, 0.16, 0.08]),
               rng.uniform([-0.01, -0.01, 0.03], [0.01, 0.01, 0.06]), rng.normal(0.0, 0.3, 3))


def drawn_device(rng: np.random.Generator, relative_std: float = 0.005, center_std: float = 3e-4) -> Device:
    """The synthetic device as one calibration gives it: its rotor inertia, tensor entries and
    centre off the truth by draws from their stated std (``relative_std`` of each size; ``center_std``, m).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.synthetic import ROTOR_INERTIA, drawn_device
    >>> d = drawn_device(np.random.default_rng(0))
    >>> bool(abs(d.rotor_inertia / ROTOR_INERTIA - 1) < 0.05), d.rotor_inertia_std == 0.005 * ROTOR_INERTIA
    (True, True)
    """
    dev = true_device()
    noise = np.triu(rng.normal(size=(3, 3)))
    I_std = relative_std * np.abs(dev.inertia)
    return Device(dev.mass, ROTOR_AXIS, ROTOR_INERTIA * (1 + relative_std * rng.normal()), relative_std * ROTOR_INERTIA,
                  dev.inertia + I_std * (noise + np.triu(noise, 1).T), I_std,
                  dev.center + center_std * rng.normal(size=3), np.full(3, float(center_std)))


#: The device as the synthetic throws build it by default: its imperfections drawn once
#: (:func:`~tumble.analysis.tensor.firmware.draw_imperfections`, seed 2025), the same in every
#: throw, as one real device's are.
TYPICAL_SEED = 2025


def typical_imperfections(rotor_axis: ArrayLike = ROTOR_AXIS) -> Imperfections:
    """The default device's imperfections (:data:`TYPICAL_SEED`), about the nominal ``rotor_axis``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.synthetic import typical_imperfections
    >>> imp = typical_imperfections()
    >>> bool(np.abs(np.diag(imp.gyro) - 1).max() < 0.01), imp.poles
    (True, 14)
    """
    return draw_imperfections(np.random.default_rng(TYPICAL_SEED), rotor_axis)


@dataclass(frozen=True)
class ThrowTimes:
    """A synthetic throw's true times, s: the firmware's sensed release (the accelerometer reads
    free fall: ``apparent``), the fingers' last touch (``release``: the free flight's start), the
    rotor's start and the log's end (in flight, or the catch for a throw ``caught``).

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import throw_times
    >>> tt = throw_times(1)
    >>> 0.01 <= tt.release - tt.apparent <= 0.02, 0.06 <= tt.rotor - tt.apparent <= 0.12
    (True, True)
    """

    apparent: float
    release: float
    rotor: float
    end: float


def _times(rng: np.random.Generator, plateau: float | None) -> tuple[ThrowTimes, RotorSchedule]:
    t_a = float(rng.uniform(0.2, 0.3))
    t_r = t_a + float(rng.uniform(0.010, 0.020))
    t_s = t_a + float(rng.uniform(0.06, 0.12))
    sched = draw_schedule(rng, plateau)
    if plateau == 0.0:
        sched = replace(sched, idle=0.0, idle_after=0.0)
    return ThrowTimes(t_a, t_r, t_s, t_s + sched.log_end), sched


def throw_times(seed: int) -> ThrowTimes:
    """The true times of :func:`synthetic_throw`'s throw ``seed`` (:class:`ThrowTimes`).

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import throw_times
    >>> tt = throw_times(1)
    >>> 0.2 <= tt.apparent <= 0.3, 0.55 <= tt.end - tt.rotor <= 0.59
    (True, True)
    """
    return _times(np.random.default_rng(seed), None)[0]


def _flight(flown: Rigid, w0: FloatArray, times: FloatArray, t0: float, breaks, hvec, drag: FloatArray, rotor_drag):
    """omega and omega' of the free flight at ``times`` (w-form, DOP853, rtol 1e-10), split where the rotor's rate jumps."""
    I = flown.inertia
    Iinv = np.linalg.inv(I)

    def rates(t, w):  # I w' = L x w + tau - h', L = I w + h: the momentum form (Hughes 1986, ch. 7)
        h, hdot, tau_r = hvec(t)
        L = w @ I + h
        tau = drag_component(0.0, drag, w) + tau_r * rotor_drag
        dL = momentum_rate_components(L[..., 0], L[..., 1], L[..., 2], w[..., 0], w[..., 1], w[..., 2], tau[..., 0],
                                      tau[..., 1], tau[..., 2])
        return (np.stack(dL, axis=-1) - hdot) @ Iinv

    def rhs(t, w):  # one time (a float) and one omega (3,): no arrays of one sample to build
        return rates(t, w)

    w = np.empty((times.size, 3))
    state, start = w0, t0
    edges = [b for b in breaks if t0 < b < times[-1]] + [times[-1] + 1e-9]
    for hi in edges:
        sel = (times >= start) & (times < hi)
        sol = solve_ivp(rhs, (start, hi), state, method="DOP853", rtol=1e-10, atol=1e-12, dense_output=True)
        w[sel] = sol.sol(times[sel]).T
        state, start = sol.y[:, -1], hi
    return w, rates(times, w)


def _air(rng: np.random.Generator, s: FloatArray, w: FloatArray) -> FloatArray:
    """The air's drag on the flying body over its mass, body frame, m/s^2, at ``s`` s from the
    release: ``-c |v| v`` with ``v = v_0 + g s`` (the throw's velocity, 3-5 m/s at 45-80 degrees up;
    ``c = rho C_d A / 2m`` 0.005-0.03 1/m: 0.05-0.5 m/s^2), a world-fixed force that turns in the
    body frame as the body tumbles (its attitude integrated from ``w``)."""
    up = rng.uniform(np.deg2rad(45.0), np.deg2rad(80.0))
    heading = rng.uniform(0.0, 2 * np.pi)
    v0 = rng.uniform(3.0, 5.0) * np.array([np.cos(up) * np.cos(heading), np.cos(up) * np.sin(heading), np.sin(up)])
    v = v0 + np.outer(s, [0.0, 0.0, -_G])
    force = -rng.uniform(0.005, 0.03) * np.linalg.norm(v, axis=1, keepdims=True) * v
    attitude = Rotation.random(random_state=rng) * Rotation.from_quat(attitude_from_rates(s, w))
    return attitude.inv().apply(force)


def _firmware_lowpass(x: FloatArray, dt: float, cutoff: float) -> FloatArray:
    """The firmware's smoothing of the accelerometer: a second-order Butterworth low-pass at
    ``cutoff`` Hz (scipy.signal.butter), run forward (causal: it delays, as the firmware's does)."""
    from scipy.signal import butter, lfilter, lfilter_zi

    b, a = butter(2, cutoff, fs=1.0 / dt)
    return lfilter(b, a, x, axis=0, zi=lfilter_zi(b, a)[:, None] * x[:1])[0]


def synthetic_throw(seed: int, flown: Rigid, *, rotor_inertia: float = ROTOR_INERTIA,
                    rotor_axis: ArrayLike = ROTOR_AXIS, input: str = "", rotor_top: float | None = None,
                    spin: tuple[float, float] = (10.0, 18.0), imperfections: Imperfections | None = None,
                    caught: bool = False) -> Throw:
    """A throw's log as the real device writes it (module docstring).

    :func:`tumble.io.throwfile.write_throw` writes it as a throw file for ``tumble calibrate``
    and ``tumble tensor`` (``compact=True``: a third smaller); the examples' throws
    (``examples/throws/``) are such throws (docs/tensor.md, "Try it on synthetic throws").

    Parameters
    ----------
    seed : int
        Everything random of the throw (times, spin, rotor schedule, noise, biases, drag) follows from it.
    flown : Rigid
        The whole that flies (object and device, rotor included), sensor frame.
    rotor_inertia : float
        ``J_r``, kg m^2.
    rotor_axis : array_like, shape (3,)
        The rotor's nominal axis, sensor frame (its true one is ``imperfections.rotor_axis``).
    input : str
        The name the throw carries.
    rotor_top : float, optional
        The plateau's speed, rad/s (default 1230-1360; 0 for a rotor that never starts).
    spin : (float, float)
        The range of the spin at release, rad/s.
    imperfections : Imperfections, optional
        The device's gyroscope and rotor as built (default :func:`typical_imperfections` about
        ``rotor_axis``; ``Imperfections.none(rotor_axis)`` for a perfect one).
    caught : bool
        The log goes on through a catch at its end (0.08 s more: the hand stops the spin).

    Returns
    -------
    Throw

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.synthetic import combine, example_object, synthetic_throw, throw_times, true_device
    >>> throw = synthetic_throw(1, combine(true_device(), example_object()))
    >>> dt = np.diff(throw.t)
    >>> tt = throw_times(1)
    >>> bool(dt[throw.t[1:] < tt.apparent].std() > 20e-6), round(float(np.median(dt[throw.t[1:] > tt.release])), 6)
    (True, 0.000248)
    >>> round(float(throw.rotor.max()), -2), round(float(throw.rotor[-1]), -1), bool(abs(throw.t[-1] - tt.end) < 3e-4)
    (1300.0, 210.0, True)
    """
    rng = np.random.default_rng(seed)
    tt, sched = _times(rng, rotor_top)
    imp = typical_imperfections(rotor_axis) if imperfections is None else imperfections
    a = np.asarray(imp.rotor_axis, float)
    last = tt.end + (0.08 if caught else 0.0)
    hand = np.cumsum(rng.uniform(190e-6, 300e-6, 2000))
    hand = hand[hand < tt.apparent]
    fly = tt.apparent + 248e-6 * np.arange(1, int((last - tt.apparent) / 248e-6) + 1)
    fly += 1e-6 * rng.normal(size=fly.size)
    t = np.concatenate([hand, fly[fly <= last]])
    n = t.size
    held, contact = t < tt.apparent, (t >= tt.apparent) & (t < tt.release)
    inflight, after = t >= tt.apparent, t > tt.end if caught else np.zeros(n, bool)
    inflight &= ~after

    # the rotor: its schedule, the air's drag on it (an external torque on the whole, along its axis)
    rotor_drag = rng.uniform(2e-11, 8e-11)  # N m s^2: -k Omega^2, 0.3-1.2 % of the spin-up's momentum over the plateau

    def hvec(s):  # at one time (float) or many (array)
        speed, rate = sched.speed_and_rate(s - tt.rotor)
        return (np.multiply.outer(rotor_inertia * speed, a), np.multiply.outer(rotor_inertia * rate, a),
                np.multiply.outer(-(speed * np.abs(speed)), a))

    speed, _ = sched.speed_and_rate(t - tt.rotor)

    # the flight from the sensed release; the fingers' touch until the release proper
    direction = rng.normal(size=3)
    w_a = rng.uniform(*spin) * direction / np.linalg.norm(direction)
    drag = rng.uniform(0.5e-6, 2e-6, 3)
    w, wdot = np.zeros((n, 3)), np.zeros((n, 3))
    breaks = [tt.rotor + x for x in sched.switches]
    w[inflight], wdot[inflight] = _flight(flown, w_a, t[inflight], tt.apparent, breaks, hvec, drag, rotor_drag)
    kick = rng.normal(size=3)
    kick *= rng.uniform(0.2, 0.6) / np.linalg.norm(kick)  # the fingers' last push, rad/s
    s = (t[contact] - tt.apparent) / (tt.release - tt.apparent)
    w[contact] += kick * ((1 - s) ** 2)[:, None]
    wdot[contact] += -kick * (2 * (1 - s) / (tt.release - tt.apparent))[:, None]
    x = t[held] / tt.apparent  # the arm brings the spin up
    w[held] = (w_a + kick) * (x * x * (3 - 2 * x))[:, None]
    wdot[held] = (w_a + kick) * (6 * x * (1 - x) / tt.apparent)[:, None]
    if caught:
        w_end = w[inflight][-1]
        w[after] = w_end * np.exp(-(t[after] - tt.end) / 0.02)[:, None]

    # the accelerometer: free fall at r from the centre, the hand, the air, the rotor's jolts and imbalance
    r = -flown.center
    f = np.cross(wdot, r) + np.cross(w, np.cross(w, r))
    push = smooth_noise(rng, n, 250e-6, 1.0, 3.0)
    way = np.column_stack([smooth_noise(rng, n, 250e-6, 1.0, 2.0) for _ in range(3)]) + rng.normal(size=3)
    way /= np.linalg.norm(way, axis=1, keepdims=True)
    f[held] += (_G * (1.75 + 0.5 * np.tanh(push[held])))[:, None] * way[held]
    f[contact] += (_G * rng.uniform(0.05, 0.3) * (1 - s))[:, None] * way[contact]
    f[after] += (_G * rng.uniform(3.0, 5.0) * np.exp(-(t[after] - tt.end) / 0.03) + _G)[:, None] * way[after]
    f[inflight] += _air(rng, t[inflight] - tt.apparent, w[inflight])
    for t_k in breaks:
        width = rng.uniform(0.002, 0.004)
        pulse = np.where((t >= t_k) & (t < t_k + width), np.sin(np.pi * (t - t_k) / width), 0.0)
        jolt = rng.normal(size=3)
        f += np.outer(pulse, rng.uniform(6.0, 24.0) * jolt / np.linalg.norm(jolt))
    phase = np.cumsum(np.r_[0.0, np.diff(t)] * speed)
    e1 = np.cross(a, [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    f += (6e-7 * speed ** 2)[:, None] * (np.outer(np.cos(phase), e1) + np.outer(np.sin(phase), e2))
    f = f + rng.normal(0.0, 0.3, (n, 3))
    f = _firmware_lowpass(f, 248e-6, rng.uniform(100.0, 200.0))
    accel = f * imp.accel_scale + imp.accel_bias
    lsb_a = _G / 2048.0
    accel = np.clip(np.round(accel / lsb_a) * lsb_a, -16 * _G, 16 * _G)

    # the gyroscope: scale and misalignment, bias, noise, the rotor's vibration, range, quantisation
    vib = 0.01 * (np.outer(np.cos(phase), e1) + np.outer(np.sin(phase), e2)) * (speed > 0)[:, None]
    gyro = w @ imp.gyro.T + rng.normal(0.0, 0.01, 3) + rng.normal(0.0, 0.01, (n, 3)) + vib
    lsb = GYRO_RANGE / 32768.0
    gyro = np.clip(np.round(gyro / lsb) * lsb, -GYRO_RANGE, GYRO_RANGE)

    # the rotor's speed as logged: eRPM telemetry, its stamps a fraction of a millisecond off the gyroscope's
    lag = rng.uniform(-5e-4, 5e-4)
    rotor = logged_speed(sched.speed_and_rate(t - tt.rotor - lag)[0], imp.poles, rng)
    return Throw(t, gyro, rotor, accel, input)
