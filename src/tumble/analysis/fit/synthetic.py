"""Realistic synthetic phone recordings of tossed bodies: test data and the shipped example.

A recording is what a phone's gyroscope logs (phyphox, ~100 Hz) while someone holds a body,
throws it spinning, catches it, holds it again, and so on: :func:`synthetic_recording`.
What it reproduces, and where each trait comes from:

- **Flights** of 0.5-1.5 s, spin 5-25 rad/s about the intermediate axis, 1-10 deg off it (the
  tennis-racket toss). The motion is Euler's equations with an aerodynamic torque, integrated by
  DOP853 (rtol 1e-9): strip theory on a flat plate in the body's 1-2 plane, each element
  pushed back by ``0.5 rho C_D |v_n| v_n`` (``v_n`` its normal speed; Hoerner, *Fluid-Dynamic
  Drag*, 1965, ch. 3: ``C_D ~ 1.17`` for a plate normal to the flow), so a rectangle ``L x W``
  turning about its width's axis feels ``rho C_D W L^4 / 64 w |w|``: quadratic in omega and
  strongly anisotropic (none about the plate's normal but skin friction). This is **not** the
  fit's drag model (a torque along ``L``): the fit meets a model error, as on real data. For a
  racquet the effective ``C_D`` is set so the torque is 0.05 N m at 10 rad/s (the student
  measurement quoted in issue #16); a phone gets the plate value (a few per cent per second).
- **The body flexes** (a racquet frame, a phone in a case or strapped to a mount): a damped
  oscillation of 15-35 Hz, 0.01-0.06 rad/s, decaying in 0.1-0.3 s after the release.
- **Between flights**: a throw (0.15-0.3 s of wrist flick, the spin ramping up and the hand's
  torque ending abruptly at release), a catch (the spin killed in 40-120 ms, with a jolt) and a
  hold (1-4 s: slow hand motion of 0.05-0.4 rad/s below 3 Hz plus 8-12 Hz physiological
  tremor of 0.005-0.03 rad/s).
- **The gyroscope** (MEMS datasheets: Bosch BMI160/BMI270, ST LSM6DSO; noise density
  0.004-0.008 deg/s/sqrt(Hz), full scale 2000 deg/s = 34.9 rad/s at 16 bits): white noise
  (0.002-0.006 rad/s per sample at 100 Hz, above the datasheet figure as phones show), a
  coloured component (first-order Gauss-Markov, 50 ms, 0.001-0.003 rad/s), a bias of
  ~0.01 rad/s per axis with a slow random walk, scale errors of 0.5 % (sensitivity tolerance
  of about +-1 %), quantisation of
  2000 deg/s / 2^15, and clipping at the full scale.
- **Timing**: sample intervals with 5 % jitter, 1 % of samples dropped and a rare gap of
  50-200 ms; phyphox's START/PAUSE: a pause removes a stretch of the hold, and the experiment
  time carries on from the pause without a gap (as phyphox's export does; its
  ``meta/time.csv`` lists the events).
- **The mount**: the phone's axes are a signed permutation of the principal axes turned by a
  few degrees (it is strapped on by hand); the phone is not at the centre of mass, which a
  gyroscope does not see.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from ..._html import fmt, result_html
from ...dynamics.euler import euler_rhs
from .. import _display
from .accelsynth import SyntheticAccel, synthetic_accel
from .tossbody import RHO_AIR, TOSS_BODIES, TossBody, plate_drag_torque  # noqa: F401 - re-exported
from .endings import ENDINGS, _unit, after_hand, after_landing, gyrostat_flight, smooth_noise, spun_on_table, turned_in_hand

__all__ = ["EXAMPLE_RECORDING", "TOSS_BODIES", "SyntheticRecording", "TossBody", "example_recording", "plate_drag_torque",
           "synthetic_recording"]

#: 2000 deg/s, the common smartphone gyroscope full scale, rad/s.
FULL_SCALE = np.deg2rad(2000.0)


def _flight(body: TossBody, w0, duration, times):
    I = np.asarray(body.moments, float)

    def rhs(_, w):
        return euler_rhs(w, I, plate_drag_torque(body, w))

    sol = solve_ivp(rhs, (0.0, duration), w0, method="DOP853", rtol=1e-9, atol=1e-10, dense_output=True)
    return sol.sol(times).T


@dataclass(frozen=True)
class SyntheticRecording:
    """A synthetic phone recording and the truth behind it.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Sample times (phyphox's experiment time), s.
    omega : ndarray, shape (n, 3)
        The gyroscope's samples, sensor axes, rad/s.
    flights : ndarray, shape (k, 2)
        Each flight's release and catch, s.
    omega0 : ndarray, shape (k, 3)
        Angular velocity at each release, principal frame, rad/s.
    ratios : ndarray, shape (2,)
        The body's true ``I1/I3``, ``I2/I3``.
    sensor_rotation : scipy Rotation
        Sensor axes to principal axes.
    bias : ndarray, shape (3,)
        The gyroscope's mean bias, sensor axes, rad/s.
    events : list of (str, float)
        phyphox's START/PAUSE events, experiment time, s.
    body : TossBody
    rate : float
        Nominal sample rate, Hz.
    endings : tuple of str
        How each flight ended (``"catch"``, ``"hand"`` or ``"landing"``).
    rotor : float
        The internal rotor's final momentum over ``|L|`` (0: a rigid body).
    accel : SyntheticAccel or None
        The accelerometer (``accel=True``; :mod:`~tumble.analysis.fit.accelsynth`): its samples
        ``accel.f`` (n, 3), m/s^2, sensor axes, at the gyroscope's times, its offset from the
        centre of mass and its bias.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(7, tosses=2, flight=(0.5, 0.8))
    >>> rec.omega.shape == (len(rec.t), 3), rec.flights.shape, rec.rate
    (True, (2, 2), 100.0)
    >>> I = np.array(rec.body.moments)
    >>> bool(np.allclose(rec.ratios, I[:2] / I[2])), bool(np.all(np.diff(rec.t) > 0))   # the truth, and times that increase
    (True, True)
    """

    t: np.ndarray
    omega: np.ndarray
    flights: np.ndarray
    omega0: np.ndarray
    ratios: np.ndarray
    sensor_rotation: Rotation
    bias: np.ndarray
    events: list = field(default_factory=list)
    body: TossBody | None = None
    rate: float = 100.0
    endings: tuple = ()
    rotor: float = 0.0
    accel: SyntheticAccel | None = None

    def __repr__(self) -> str:
        return _display.synthetic_repr(self)

    def _repr_html_(self) -> str:
        t = self.t
        return result_html("SyntheticRecording", [
            ("samples", len(t)), ("span", f"{fmt(t[-1] - t[0], 3)} s" if len(t) else "none"), ("rate", f"{fmt(self.rate)} Hz"),
            ("flights", len(self.flights)), ("I1/I3", fmt(self.ratios[0])), ("I2/I3", fmt(self.ratios[1])),
            ("endings", ", ".join(self.endings) or "none"), ("rotor's momentum over |L|", fmt(self.rotor))])

    def csv_text(self, comment: str = "") -> str:
        """phyphox's gyroscope export ("Raw Data.csv"), comma-separated; ``comment`` lines
        (each prefixed with ``#`` and a space) first, when given. The whole export, a folder or a
        zip with the events and the accelerometer, is :func:`tumble.io.phyphoxwrite.write_phyphox`'s
        (``write_phyphox("toss.zip", rec.t, rec.omega, accel=rec.accel.f, events=rec.events)``).

        Examples
        --------
        >>> import io
        >>> import numpy as np
        >>> from tumble.analysis.fit.synthetic import synthetic_recording
        >>> rec = synthetic_recording(7, tosses=1, flight=(0.5, 0.6))
        >>> text = rec.csv_text("synthetic")
        >>> text.splitlines()[:2]
        ['# synthetic', '"Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)","Gyroscope z (rad/s)","Absolute (rad/s)"']
        >>> table = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=2)
        >>> bool(np.allclose(table[:, 1:4], rec.omega, rtol=1e-9)), bool(np.allclose(table[:, 4], np.linalg.norm(rec.omega, axis=1)))
        (True, True)
        """
        lines = [f"# {line}" for line in comment.splitlines()] + ['"Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)","Gyroscope z (rad/s)","Absolute (rad/s)"']
        a = np.linalg.norm(self.omega, axis=1)
        for ti, (x, y, z), ai in zip(self.t, self.omega, a):
            lines.append(f"{ti:.9E},{x:.9E},{y:.9E},{z:.9E},{ai:.9E}")
        return "\n".join(lines) + "\n"

    def time_csv_text(self) -> str:
        """phyphox's ``meta/time.csv``: the START/PAUSE events.

        Examples
        --------
        >>> from tumble.analysis.fit.synthetic import synthetic_recording
        >>> rec = synthetic_recording(7, tosses=2, flight=(0.5, 0.6), pauses=1)
        >>> lines = rec.time_csv_text().splitlines()
        >>> lines[0], len(lines) == 1 + len(rec.events), [name for name, _ in rec.events]
        ('"event","experiment time","system time","system time text"', True, ['START', 'PAUSE', 'START'])
        """
        lines = ['"event","experiment time","system time","system time text"']
        for name, te in self.events:
            lines.append(f'"{name}",{te:.9E},{1.7e9 + te:.3f},"2026-11-25 12:00:00.000 UTC+00:00"')
        return "\n".join(lines) + "\n"


def _tilted(rng, spin, about, tilt_deg):
    """omega0 of ``spin`` rad/s about principal axis ``about`` (0-2), tilted by ``tilt_deg``."""
    tilt = np.deg2rad(tilt_deg)
    phase = rng.uniform(0, 2 * np.pi)
    others = [k for k in range(3) if k != about]
    w = np.zeros(3)
    w[about] = np.cos(tilt) * rng.choice([-1.0, 1.0])
    w[others[0]], w[others[1]] = np.sin(tilt) * np.cos(phase), np.sin(tilt) * np.sin(phase)
    return spin * w


def synthetic_recording(seed: int, *, body: str | TossBody = "racquet", tosses: int = 10, rate: float = 100.0,
                        spin: tuple[float, float] = (5.0, 25.0), flight: tuple[float, float] = (0.5, 1.5),
                        tilt: tuple[float, float] = (1.0, 10.0), noise: tuple[float, float] = (0.002, 0.006),
                        bias: float = 0.01, saturation: float = FULL_SCALE, pauses: int = 0,
                        stable: int = 0, flex: bool = True, drag: float = 1.0,
                        scale_error: float = 0.005, ending: str = "catch", after: tuple[float, float] = (0.3, 1.0),
                        after_spin: tuple[float, float] = (5.0, 20.0), hand: tuple[float, float] = (0.05, 0.4),
                        rotor: float = 0.0, accel: bool = False) -> SyntheticRecording:
    """A whole phone recording of ``tosses`` tosses of a body (module docstring).

    Parameters
    ----------
    seed : int
        Seed of everything random.
    body : str or TossBody
        ``"racquet"`` (near-planar), ``"phone"`` (a box phone) or a :class:`TossBody`.
    tosses : int
        Number of flights.
    rate : float
        Nominal sample rate, Hz.
    spin, flight, tilt, noise : (float, float)
        Ranges drawn uniformly: spin rate (rad/s), flight time (s), tilt of omega0 off the
        intermediate axis (deg), white noise per sample (rad/s).
    bias : float
        Standard deviation of the gyroscope's bias per axis, rad/s.
    saturation : float
        Full scale, rad/s.
    pauses : int
        Number of phyphox pauses (each in a hold).
    stable : int
        Number of flights spun about a stable axis (1 or 3) instead.
    flex : bool
        Whether the body flexes.
    drag : float
        Factor on the body's drag coefficient (0: no air).
    scale_error : float
        Standard deviation of the scale factor's error per sensor axis.
    ending : {"catch", "hand", "landing", "mixed", "turn", "table"}
        How each flight ends (:mod:`~tumble.analysis.fit.endings`): the spin killed in the hand
        (the default), caught and turned on in the hand, a landing with bounces and rolling, one
        of these three drawn per toss, caught and turned smoothly in the fingers (a motion a
        torque-free model follows), or landed flat and spun on a table.
    after, after_spin : (float, float)
        Ranges of the motion after a ``"hand"``, ``"landing"``, ``"turn"`` or ``"table"`` end: its length (s) and its
        initial spin (rad/s).
    hand : (float, float)
        Range of the hand's slow motion while holding (RMS per axis, rad/s); (3, 10) for a
        phone swung about between tosses.
    rotor : float
        An internal rotor spinning up during each flight, its final axial momentum as a fraction
        of the body's ``|L|`` at release (0: a rigid body): the body is a gyrostat
        (:func:`~tumble.analysis.fit.endings.gyrostat_flight`).
    accel : bool
        Whether the phone's accelerometer is recorded too (:mod:`~tumble.analysis.fit.accelsynth`;
        its own random stream: the gyroscope's samples are the same either way).

    Returns
    -------
    SyntheticRecording

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(1, tosses=3)
    >>> rec.flights.shape, bool(rec.t[-1] > 3 * 0.5)
    ((3, 2), True)

    A phone tossed once at 400 Hz, landing on a table, keeps turning at several rad/s after the
    impact:

    >>> rec = synthetic_recording(3, body="phone", tosses=1, rate=400.0, ending="landing")
    >>> (release, land), = rec.flights
    >>> after = (rec.t > land + 0.01) & (rec.t < land + 0.2)
    >>> rec.endings, bool(np.median(np.linalg.norm(rec.omega[after], axis=1)) > 3.0)
    (('landing',), True)
    """
    if ending not in ENDINGS:
        raise ValueError(f"ending = {ending!r} is not a way a toss ends; allowed: {', '.join(map(repr, ENDINGS))}")
    extra = np.random.default_rng([seed, 29])  # the new traits' own stream (module docstring of endings)
    rng = np.random.default_rng(seed)
    body = TOSS_BODIES[body] if isinstance(body, str) else body
    if drag != 1.0:
        body = TossBody(body.name, body.moments, body.length, body.width, body.drag_coefficient * drag)
    I = np.asarray(body.moments, float)
    dt = 1.0 / rate
    # the mount: a signed permutation turned by a few degrees (sensor -> principal)
    perm = np.eye(3)[rng.permutation(3)] * rng.choice([-1.0, 1.0], 3)[:, None]
    if np.linalg.det(perm) < 0:
        perm[2] *= -1.0
    mount = Rotation.from_rotvec(rng.normal(0, np.deg2rad(3.0), 3)) * Rotation.from_matrix(perm)
    R = mount.as_matrix()
    # the timeline: hold, (throw, flight, catch, hold) x tosses
    segments, t_now = [], 0.0
    hold0 = rng.uniform(1.0, 2.5)
    segments.append(("hold", t_now, hold0, None))
    t_now += hold0
    stable_idx = set(rng.choice(tosses, size=min(stable, tosses), replace=False).tolist()) if stable else set()
    flights, omega0s, ends = [], [], []
    for k in range(tosses):
        throw = rng.uniform(0.15, 0.3)
        T = rng.uniform(*flight)
        s = rng.uniform(*spin)
        about = rng.choice([0, 2]) if k in stable_idx else 1
        w0 = _tilted(rng, s, about, rng.uniform(*tilt))
        segments.append(("throw", t_now, throw, w0))
        t_now += throw
        segments.append(("flight", t_now, T, w0))
        flights.append((t_now, t_now + T))
        omega0s.append(w0)
        t_now += T
        catch = rng.uniform(0.04, 0.12)
        end = str(extra.choice(ENDINGS[:3])) if ending == "mixed" else ending
        ends.append(end)
        if end != "catch":  # caught and turned on in the hand, or landed: the spin goes on
            catch = extra.uniform(*after)
            spin_after = extra.uniform(*after_spin)
        segments.append((end, t_now, catch, None if end == "catch" else spin_after))
        t_now += catch
        hold = rng.uniform(1.0, 4.0)
        segments.append(("hold", t_now, hold, None))
        t_now += hold
    total = t_now
    # sample times: jitter, drops, a rare gap
    n_max = int(total * rate * 1.2) + 10
    steps = dt * (1.0 + 0.05 * rng.standard_normal(n_max)).clip(0.5, 1.5)
    tt = np.cumsum(np.r_[rng.uniform(0, dt), steps])
    tt = tt[tt < total]
    keep = rng.random(len(tt)) > 0.01
    if rng.random() < 0.5:
        g0 = rng.uniform(0, total)
        keep &= ~((tt > g0) & (tt < g0 + rng.uniform(0.05, 0.2)))
    tt = tt[keep]
    w_body = np.zeros((len(tt), 3))  # principal frame
    wdot = np.full((len(tt), 3), np.nan)  # its exact derivative in the flights (accel)
    held = np.stack([smooth_noise(rng, len(tt), dt, rng.uniform(*hand), 1.5) for _ in range(3)], axis=1)
    tremor_f = rng.uniform(8, 12)
    tremor = rng.uniform(0.005, 0.03) * np.sin(2 * np.pi * tremor_f * tt[:, None] + rng.uniform(0, 2 * np.pi, 3))
    last_flight_end = None
    for kind, t0, length, w0 in segments:
        sel = (tt >= t0) & (tt < t0 + length)
        tau = tt[sel] - t0
        if kind == "hold":
            w_body[sel] = held[sel] + tremor[sel]
        elif kind == "throw":
            x = tau / length
            ramp = 0.7 * x * x * (3 - 2 * x) + 0.3 * x
            wob = np.sin(np.pi * x)[:, None] * rng.normal(0, 0.15 * np.linalg.norm(w0), 3)
            w_body[sel] = ramp[:, None] * w0 + (1 - ramp)[:, None] * held[sel] + wob
        elif kind == "flight":
            n = len(tau)  # with the accelerometer, also at tau +- 1e-5 s: the dense output's derivative
            pts = np.r_[tau, length, tau + 1e-5, tau - 1e-5] if accel else np.r_[tau, length]
            if rotor:
                h_final = rotor * float(np.linalg.norm(I * w0))
                w = gyrostat_flight(body, w0, length, pts, _unit(extra), h_final,
                                    extra.uniform(0.6, 1.0) * length, lambda x: plate_drag_torque(body, x))
            else:
                w = _flight(body, w0, length, pts)
            last_flight_end = w[n]
            w, tau = np.delete(w, n, axis=0), np.delete(pts, n)
            if flex:
                f = rng.uniform(15, 35)
                amp = rng.uniform(0.01, 0.06)
                decay = rng.uniform(0.1, 0.3)
                axis = rng.normal(size=3)
                axis /= np.linalg.norm(axis)
                w = w + (amp * np.exp(-tau / decay) * np.sin(2 * np.pi * f * tau + rng.uniform(0, 6.3)))[:, None] * axis
            w_body[sel] = w[:n]
            if accel:
                wdot[sel] = (w[n:2 * n] - w[2 * n:]) / 2e-5
        elif kind == "hand":
            w_body[sel] = after_hand(extra, tau, length, last_flight_end, w0, held[sel] + tremor[sel], dt)
        elif kind == "landing":
            w_body[sel] = after_landing(extra, body, tau, length, w0, held[sel] + tremor[sel])
        elif kind == "turn":
            w_body[sel] = turned_in_hand(extra, tau, length, last_flight_end, w0, held[sel] + tremor[sel])
        elif kind == "table":
            w_body[sel] = spun_on_table(extra, body, tau, length, w0, held[sel] + tremor[sel])
        else:  # catch
            x = tau / length
            kill = np.exp(-5.0 * x) * (1 - x)
            jolt = np.sin(np.pi * x)[:, None] * rng.normal(0, 0.3 * np.linalg.norm(last_flight_end), 3)
            w_body[sel] = kill[:, None] * last_flight_end + (1 - kill)[:, None] * held[sel] + jolt
    # the sensor: mount, scale errors, bias (with a random walk), white and coloured noise
    w_s = w_body @ R  # omega_sensor = R^T omega_principal (row vectors)
    w_s = w_s * (1.0 + rng.normal(0, scale_error, 3))
    b = rng.normal(0, bias, 3)
    walk = np.cumsum(rng.normal(0, 1e-4 * np.sqrt(dt), (len(tt), 3)), axis=0)
    sigma = rng.uniform(*noise)
    coloured = np.stack([smooth_noise(rng, len(tt), dt, rng.uniform(0.001, 0.003), 1 / (2 * np.pi * 0.05))
                         for _ in range(3)], axis=1)
    w_s = w_s + b + walk + coloured + rng.normal(0, sigma, w_s.shape)
    lsb = FULL_SCALE / 32768
    w_s = np.clip(np.round(w_s / lsb) * lsb, -saturation, saturation)
    flights = np.array(flights)
    # phyphox pauses: cut a stretch out of holds, experiment time carrying on
    events = [("START", 0.0)]
    holds = [(t0, length) for kind, t0, length, _ in segments if kind == "hold"][1:]
    cuts = []
    for i in rng.permutation(len(holds))[:pauses]:
        t0, length = holds[i]
        cuts.append((t0 + 0.3 * length, t0 + 0.7 * length))
    shift = np.zeros(len(tt))
    f_shift = np.zeros(len(flights))
    keep = np.ones(len(tt), bool)
    for a, c in sorted(cuts):
        keep &= ~((tt >= a) & (tt < c))
        shift[tt >= c] += c - a
        f_shift[flights[:, 0] >= c] += c - a
    for a, c in sorted(cuts):
        te = a - float(np.sum([c2 - a2 for a2, c2 in cuts if c2 <= a]))
        events += [("PAUSE", te), ("START", te)]
    t_out = (tt - shift)[keep]
    w_out = w_s[keep]
    acc = synthetic_accel(np.random.default_rng([seed, 29, 1]), tt, w_body, wdot, segments, R, body) if accel else None
    return SyntheticRecording(t=t_out, omega=w_out, flights=flights - f_shift[:, None], omega0=np.array(omega0s),
                              ratios=I[:2] / I[2], sensor_rotation=mount, bias=b, events=events, body=body, rate=rate,
                              endings=tuple(ends), rotor=rotor,
                              accel=None if acc is None else replace(acc, f=acc.f[keep]))


#: The shipped example (``examples/data/racquet_tosses.csv``): its generator's arguments.
EXAMPLE_RECORDING = {"seed": 16, "body": "racquet", "tosses": 12}


def example_recording() -> tuple[SyntheticRecording, str]:
    """The shipped example recording and its file's text (a comment header saying what it is).

    Examples
    --------
    >>> from tumble.analysis.fit.synthetic import example_recording
    >>> rec, text = example_recording()
    >>> text.startswith("# SYNTHETIC")
    True
    """
    rec = synthetic_recording(**EXAMPLE_RECORDING)
    I = rec.body.moments
    comment = (
        "SYNTHETIC phone recording of 12 hand tosses of a tennis racquet about its intermediate axis: not a\n"
        "measurement. Made by tumble.analysis.fit.synthetic.example_recording() (synthetic_recording(seed=16,\n"
        "body='racquet', tosses=12)): Brody's racquet (I = 0.00121, 0.01638, 0.01748 kg m^2; I1 + I2 = I3 within\n"
        "0.6 %), strip-theory air drag (0.05 N m at 10 rad/s), flex, throws, catches and holds, a 100 Hz\n"
        "gyroscope with jitter, drops, bias, scale errors, coloured noise and quantisation.\n"
        f"True ratios: I1/I3 = {I[0] / I[2]:.7f}, I2/I3 = {I[1] / I[2]:.7f}. Columns in phyphox's layout.")
    return rec, rec.csv_text(comment)
