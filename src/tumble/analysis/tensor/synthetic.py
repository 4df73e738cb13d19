"""Synthetic throws of the device of issue #30, for tests, examples and the coverage benchmark.

A throw's log (:func:`synthetic_throw`), sensor frame, as a flight controller writes it:

- **hand** (0.2-0.3 s): the arm swings the body up to its spin; the accelerometer reads the
  hand's push (1-2.5 g); samples every 250 us with up to -200/+250 us jitter (a logger busy
  with other tasks before release); the rotor stopped (its speed reads 0);
- **flight** (0.45-0.55 s): released with 10-18 rad/s about a random axis; the rotor starts
  2-10 ms after release (the firmware's free-fall detection) and spins up as
  ``Omega (1 - exp(-s / tau))``, ``Omega`` 1400-1600 rad/s, ``tau`` = 30 ms (95 % in 0.09 s),
  with a ripple of 0.3 % (three tones of 20-80 Hz: the motor's torque ripple) in the true speed
  and white noise of 4 rad/s in the logged one; samples at 4 kHz with 1 % jitter;
  per-axis quadratic air drag (``b_i`` 0.5-2e-6 N m s^2, :mod:`tumble.dynamics.models.drag`);
- **catch** (0.08 s): the hand stops the spin in ~20 ms and pushes (3-5 g).

Sensors: gyroscope noise 0.01 rad/s, a constant bias (0.01 rad/s per axis), a vibration of
0.01 rad/s at the rotor's frequency, saturation at 2000 deg/s and 16-bit quantisation;
accelerometer noise 0.08 m/s^2, bias 0.05 m/s^2 per axis, range 16 g. In free fall the
accelerometer at ``r`` from the centre of mass reads ``f = w' x r + w x (w x r)`` (the
acceleration of a point of a rigid body, Goldstein, Poole & Safko, *Classical Mechanics*, 3rd
ed., sec. 4.10, less gravity, which a free-falling accelerometer does not sense).

The truth is integrated independently of the fit's model: Euler's equations of the gyrostat in
the angular-velocity form ``I w' = -w x (I w + h) - h' + tau_drag`` (Hughes, *Spacecraft
Attitude Dynamics*, 1986, ch. 7) with ``h'`` from the spin-up law in closed form, by scipy's
DOP853 at ``rtol = 1e-12`` (the fit integrates the momentum form by RK4 over the samples).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from ...mass.tensor import parallel_axis, rotate_inertia
from ...typing import ArrayLike, FloatArray, Matrix3, Vector3
from ..fit.endings import smooth_noise
from .device import Device, Proof, Throw

__all__ = ["DEVICE_MASS", "GYRO_RANGE", "ROTOR_AXIS", "ROTOR_INERTIA", "Rigid", "box", "calibrated_device", "combine", "drawn_device",
           "example_object", "random_object", "release_and_catch", "synthetic_throw", "true_device", "true_proof"]

#: The device of the issue: mass, kg; rotor axis, sensor frame; rotor inertia, kg m^2.
DEVICE_MASS = 0.10067
ROTOR_AXIS = (0.0, 0.0, -1.0)
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


def _spin_up(t: FloatArray, t_s: float, top: float, tau: float, ripple: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The rotor's true speed and its rate (rad/s, rad/s^2): 0 before ``t_s``, then
    ``top (1 - e) (1 + sum a sin(2 pi f s + phi))`` with ``e = exp(-s / tau)``."""
    s = np.maximum(t - t_s, 0.0)
    on = t >= t_s
    e = np.exp(-s / tau)
    a, f, phi = ripple[:, 0, None], ripple[:, 1, None], ripple[:, 2, None]
    wave = 1.0 + np.sum(a * np.sin(2 * np.pi * f * s + phi), axis=0) - np.sum(a * np.sin(phi), axis=0)
    dwave = np.sum(a * 2 * np.pi * f * np.cos(2 * np.pi * f * s + phi), axis=0)
    speed = top * (1.0 - e) * wave
    rate = top * (e / tau * wave + (1.0 - e) * dwave)
    return np.where(on, speed, 0.0), np.where(on, rate, 0.0)


def _flight(flown: Rigid, w0: FloatArray, times: FloatArray, t_r: float, t_s: float, hvec, drag: FloatArray):
    """omega and omega' of the free flight at ``times`` (w-form, DOP853, rtol 1e-12), split at the rotor's start."""
    I = flown.inertia
    Iinv = np.linalg.inv(I)

    def rates(w, h, hdot):
        return (-np.cross(w, w @ I + h) - hdot - drag * np.abs(w) * w) @ Iinv

    def rhs(t, w):
        h, hdot = hvec(np.array([t]))
        return rates(w, h[0], hdot[0])

    w = np.empty((times.size, 3))
    state, start = w0, t_r
    for lo, hi in ((t_r, t_s), (t_s, times[-1] + 1e-9)):
        sel = (times >= lo) & (times < hi)
        sol = solve_ivp(rhs, (start, hi), state, method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
        w[sel] = sol.sol(times[sel]).T
        state, start = sol.y[:, -1], hi
    return w, rates(w, *hvec(times))


def release_and_catch(seed: int) -> tuple[float, float]:
    """The true release and catch times (s) of :func:`synthetic_throw`'s throw ``seed``.

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import release_and_catch
    >>> t_r, t_c = release_and_catch(1)
    >>> 0.2 <= t_r <= 0.3, 0.45 <= t_c - t_r <= 0.55
    (True, True)
    """
    rng = np.random.default_rng(seed)
    t_r = float(rng.uniform(0.2, 0.3))
    return t_r, t_r + float(rng.uniform(0.45, 0.55))


def synthetic_throw(seed: int, flown: Rigid, *, rotor_inertia: float = ROTOR_INERTIA,
                    rotor_axis: ArrayLike = ROTOR_AXIS, input: str = "", rotor_top: float | None = None,
                    spin: tuple[float, float] = (10.0, 18.0)) -> Throw:
    """A throw's log: hand-held swing, release, flight with the rotor spinning up, catch (module docstring).

    Parameters
    ----------
    seed : int
        Everything random (times, spin, rotor, noise, biases, drag) follows from it.
    flown : Rigid
        The whole that flies (object and device, rotor included), sensor frame.
    rotor_inertia : float
        ``J_r``, kg m^2.
    rotor_axis : array_like, shape (3,)
        Unit, sensor frame.
    input : str
        The name the throw carries.
    rotor_top : float, optional
        The rotor's final speed, rad/s (default 1400-1600; 0 for a rotor that never starts).
    spin : (float, float)
        The range of the spin at release, rad/s (the device alone needs less: its rotor's
        reaction turns it faster).

    Returns
    -------
    Throw

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.synthetic import combine, example_object, synthetic_throw, true_device
    >>> throw = synthetic_throw(1, combine(true_device(), example_object()))
    >>> dt = np.diff(throw.t)
    >>> bool(dt.max() > 1.5 * np.median(dt)), round(float(throw.rotor.max()), -2)   # irregular; ~1500 rad/s
    (True, 1500.0)
    """
    rng = np.random.default_rng(seed)
    a = np.asarray(rotor_axis, float)
    a = a / np.linalg.norm(a)
    t_r, t_c = release_and_catch(seed)
    rng.uniform(size=2)  # the two draws of release_and_catch
    length = t_c - t_r
    hand = np.cumsum(250e-6 + rng.uniform(-200e-6, 250e-6, 2000))
    hand = hand[hand < t_r]
    fly = t_r + np.cumsum(250e-6 * (1.0 + 0.01 * rng.normal(size=int(1.2 * (length + 0.08) / 250e-6))))
    t = np.concatenate([hand, fly[fly < t_c + 0.08]])
    n = t.size
    inflight, after = (t >= t_r) & (t < t_c), t >= t_c

    # the rotor
    t_s = t_r + rng.uniform(0.002, 0.010)
    top = rng.uniform(1400.0, 1600.0) if rotor_top is None else float(rotor_top)
    ripple = np.column_stack([np.full(3, 0.003 / np.sqrt(3)), rng.uniform(20.0, 80.0, 3), rng.uniform(0, 2 * np.pi, 3)])

    def hvec(s):
        speed, rate = _spin_up(s, t_s, top, 0.03, ripple)
        return rotor_inertia * speed[:, None] * a, rotor_inertia * rate[:, None] * a

    speed, _ = _spin_up(t, t_s, top, 0.03, ripple)

    # the flight
    direction = rng.normal(size=3)
    w0 = rng.uniform(*spin) * direction / np.linalg.norm(direction)
    drag = rng.uniform(0.5e-6, 2e-6, 3)
    w, wdot = np.zeros((n, 3)), np.zeros((n, 3))
    w[inflight], wdot[inflight] = _flight(flown, w0, t[inflight], t_r, t_s, hvec, drag)
    # before: the arm brings the spin up; after: the hand stops it
    x = t[~inflight & ~after] / t_r
    w[~inflight & ~after] = w0 * (x * x * (3 - 2 * x))[:, None]
    w_end = w[inflight][-1]
    w[after] = w_end * np.exp(-(t[after] - t_c) / 0.02)[:, None]

    # the accelerometer
    r = -flown.center  # the accelerometer from the centre of mass
    f = np.cross(wdot, r) + np.cross(w, np.cross(w, r))
    push = smooth_noise(rng, n, 250e-6, 1.0, 3.0)
    way = np.column_stack([smooth_noise(rng, n, 250e-6, 1.0, 2.0) for _ in range(3)]) + rng.normal(size=3)
    way /= np.linalg.norm(way, axis=1, keepdims=True)
    held = ~inflight & ~after
    f[held] += (_G * (1.75 + 0.5 * np.tanh(push[held])))[:, None] * way[held]
    f[after] += (_G * rng.uniform(3.0, 5.0) * np.exp(-(t[after] - t_c) / 0.03) + _G)[:, None] * way[after]
    accel = f + rng.normal(0.0, 0.05, 3) + rng.normal(0.0, 0.08, (n, 3))
    accel = np.clip(accel, -16 * _G, 16 * _G)

    # the gyroscope: bias, noise, the rotor's vibration, range, quantisation
    phase = np.cumsum(np.r_[0.0, np.diff(t)] * speed)
    vib = 0.01 * np.column_stack([np.cos(phase), np.sin(phase), np.zeros(n)]) * (speed > 0)[:, None]
    gyro = w + rng.normal(0.0, 0.01, 3) + rng.normal(0.0, 0.01, (n, 3)) + vib
    lsb = GYRO_RANGE / 32768.0
    gyro = np.clip(np.round(gyro / lsb) * lsb, -GYRO_RANGE, GYRO_RANGE)

    rotor = np.where(speed > 0, speed + rng.normal(0.0, 4.0, n), 0.0)
    return Throw(t, gyro, rotor, accel, input)
