"""``tumble view DIR`` of a fit's output folder: each used flight replayed by the fitted body.

The body shown is a uniform box whose principal moments stand in the fitted ratios
(:func:`fit_box`: longest edge 1 m, mass such that ``I3 = 1 kg m^2``; so L reads in units of
``I3`` times rad/s). Each flight (:func:`replay_flight`) starts at its first sample with the
fit's model's angular velocity there (:meth:`FlightModel.omega
<tumble.analysis.fit.flightmodel.FlightModel.omega>`, integrated backward from the model's
``t0`` where the flight search anchored it later) and runs through the flight's sample times by
:func:`tumble.simulate`: the exact torque-free motion, or Euler's equations with the fitted
drag (:func:`~tumble.dynamics.models.drag.drag_torque`, DOP853), which turn the attitude too. The
world frame is chosen with L at the start along +z. The measured rates are the recording's
samples of the flight (found again by :func:`tumble.io.fitfolder.find_recording`) turned into
the principal frame with the fitted sensor rotation and bias removed.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from ..analysis.fit.flightmodel import FlightModel
from ..dynamics import Trajectory, simulate
from ..dynamics.models.drag import drag_torque
from ..io.fitfolder import FitFolder, find_recording
from ..io.gyrodata import load_recording
from ..mass import Body, Box
from ..typing import ArrayLike

__all__ = ["FlightReplay", "fit_box", "replay_fit", "replay_flight"]

#: Samples drawn for a flight whose recording is not found (its model only).
MODEL_ONLY_SAMPLES = 200


@dataclass(frozen=True)
class FlightReplay:
    """One used flight of a fit, replayed (module docstring).

    Attributes
    ----------
    model : FlightModel
    input : str
        Its recording, as given to ``tumble fit``.
    body : Body
        The box of the fitted ratios (:func:`fit_box`).
    run : Trajectory
        The replay at the flight's sample times, t = 0 at its first sample (s), principal frame
        and attitude (principal -> world).
    t : ndarray, shape (n,)
        The sample times on the recording's clock, s.
    measured : ndarray, shape (n, 3), or None
        The gyroscope's samples in the principal frame, bias removed, rad/s; None when the
        recording was not found (``note`` says why).
    note : str

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.flightmodel import FlightModel
    >>> from tumble.commands.view_fit import FlightReplay, fit_box, replay_flight
    >>> m = FlightModel(2.0, 3.0, 2.0, [0.3, 0.8], [0.5, 9.0, 0.4], "none", [0.0] * 3, [0.0] * 3, [0.0] * 3)
    >>> t = np.linspace(2.0, 3.0, 11)
    >>> r = FlightReplay(m, "toss.csv", fit_box(m.ratios), replay_flight(m, t), t, note="model only")
    >>> r.input, len(r.run), r.measured is None
    ('toss.csv', 11, True)
    """

    model: FlightModel
    input: str
    body: Body = field(repr=False)
    run: Trajectory = field(repr=False)
    t: np.ndarray = field(repr=False)
    measured: np.ndarray | None = field(default=None, repr=False)
    note: str = ""


def fit_box(ratios: ArrayLike) -> Body:
    """A uniform box with principal moments ``(I1/I3, I2/I3, 1) kg m^2``, its longest edge 1 m.

    A box of edges ``a, b, c`` and mass ``m`` has ``I1 = m (b^2 + c^2) / 12`` and its cyclic
    companions, so ``a^2 = 6 (I2 + I3 - I1) / m``, ``b^2 = 6 (I3 + I1 - I2) / m`` and
    ``c^2 = 6 (I1 + I2 - I3) / m`` (the triangle inequality makes them non-negative); ``a = 1 m``
    fixes ``m``. A planar body (``I1 + I2 = I3``) gets a thickness of 1e-6 m.

    Examples
    --------
    >>> from tumble.commands.view_fit import fit_box
    >>> box = fit_box([0.3, 0.8])
    >>> box.principal_moments.round(12).tolist(), max(box.parts[0].size)
    ([0.3, 0.8, 1.0], 1.0)
    """
    x, y = (float(v) for v in np.asarray(ratios, float))
    m = 6.0 * (y + 1.0 - x)  # kg: a = 1 m
    b, c = np.sqrt(max(x + 1.0 - y, 0.0) * 6.0 / m), np.sqrt(max(x + y - 1.0, 1e-12 * m / 6.0) * 6.0 / m)
    return Body([Box(mass=m, size=(1.0, float(b), float(c)))], name="fitted body (box)")


def replay_flight(model: FlightModel, t: ArrayLike, body: Body | None = None) -> Trajectory:
    """The flight's replay at the times ``t`` (s, recording clock, ascending, ``t[0]`` its start)
    by ``body`` (default :func:`fit_box` of its ratios); module docstring.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.flightmodel import FlightModel
    >>> from tumble.commands.view_fit import replay_flight
    >>> m = FlightModel(2.0, 3.0, 2.2, [0.3, 0.8], [0.5, 9.0, 0.4], "none", [0.0] * 3, [0.0] * 3, [0.0] * 3)
    >>> t = np.linspace(2.0, 3.0, 101)
    >>> run = replay_flight(m, t)
    >>> bool(np.allclose(run.omega, m.omega(t), atol=1e-9)), float(run.t[0])   # the model's rates, from t = 0
    (True, 0.0)
    >>> L = run.angular_momentum_world
    >>> bool(np.allclose(L / np.linalg.norm(L, axis=1)[:, None], [0.0, 0.0, 1.0]))   # torque-free: L fixed along +z
    True
    """
    body = fit_box(model.ratios) if body is None else body
    t = np.asarray(t, float)
    w_start = model.omega(t[:1])[0]
    moments = np.asarray(body.principal_moments, float)
    L = moments * w_start
    if np.linalg.norm(L) > 0:
        R0 = Rotation.align_vectors([[0.0, 0.0, 1.0]], [L / np.linalg.norm(L)])[0]  # principal -> world: L up
    else:
        R0 = Rotation.identity()
    attitude0 = R0 * Rotation.from_matrix(body.principal_axes).inv()  # design -> world
    if model.drag == "none":
        return simulate(body, w_start, times=t - t[0], attitude0=attitude0)
    lin, quad = (model.drag_coefficients, None) if model.drag == "linear" else (None, model.drag_coefficients)
    I3 = moments[2]
    lin = None if lin is None else lin * I3  # N m s (the fit's coefficients are divided by I3)
    quad = None if quad is None else quad * I3  # N m s^2

    def drag(_t, w, _attitude):
        return drag_torque(w, lin, quad)

    return simulate(body, w_start, times=t - t[0], attitude0=attitude0, torque=drag, method="dop853", rtol=1e-11)


def replay_fit(fit: FitFolder) -> list[FlightReplay]:
    """Every used flight of a fit's output folder replayed (:class:`FlightReplay`), in fit.json's order.

    Examples
    --------
    >>> import tempfile
    >>> from importlib import resources
    >>> from pathlib import Path
    >>> from tumble.commands.fit import run_fit_command
    >>> from tumble.commands.view_fit import replay_fit
    >>> from tumble.io.fitfolder import read_fit_folder
    >>> record = resources.files("tumble") / "examples/data/phone_toss.csv"
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = run_fit_command(record, Path(folder) / "fit", end=2.0)  # doctest: +ELLIPSIS
    ...     replays = replay_fit(read_fit_folder(Path(folder) / "fit"))
    fit ...
    >>> len(replays), replays[0].measured.shape == replays[0].run.omega.shape, replays[0].note
    (1, True, '')
    """
    out = []
    loaded: dict[str, tuple] = {}
    for model, label in zip(fit.models, fit.inputs):
        if label not in loaded:
            path, why = find_recording(fit, label)
            loaded[label] = (load_recording(path), "") if path is not None else (None, why)
        rec, why = loaded[label]
        if rec is not None:
            sel = (rec.t >= model.start) & (rec.t <= model.end)
            t, measured = rec.t[sel], model.to_principal(rec.omega[sel])
            if len(t) < 2:
                t, measured, why = None, None, f"{label} holds no samples from {model.start} s to {model.end} s"
        else:
            t, measured = None, None
        if t is None:
            t = np.linspace(model.start, model.end, MODEL_ONLY_SAMPLES)
        body = fit_box(model.ratios)
        out.append(FlightReplay(model, label, body, replay_flight(model, t, body), t, measured,
                                "" if measured is not None else f"measured rates not shown: {why}"))
    return out
