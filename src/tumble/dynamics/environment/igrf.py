"""The International Geomagnetic Reference Field along an orbit, through the ``ppigrf`` package.

The field is IGRF-14 (IAGA Division V Working Group V-MOD, "International Geomagnetic
Reference Field: the fourteenth generation", 2024; the model file shipped with ``ppigrf``,
Laundal, https://github.com/klaundal/ppigrf), spherical harmonics to degree 13 with the Gauss
coefficients interpolated linearly between the five-yearly models (as IGRF prescribes). Install
it with ``pip install tumble[orbit]``. The built-in
:class:`~tumble.dynamics.environment.magnetic.DipoleField` is its degree-1 part at epoch 2020.0.

**Along an orbit.** At time ``t`` (s from ``epoch``) the spacecraft is at ``r_eci(t)`` (the
orbit's ``position_eci``); the Earth-fixed frame is ECI turned by the sidereal angle
``theta(t) = theta_GMST(epoch) + omega_E t``
(:func:`~tumble.dynamics.environment.sidereal.greenwich_sidereal_angle`; polar motion and the
difference between ECI and TEME are neglected, a few tenths of a degree); ``ppigrf`` gives
``(B_r, B_theta, B_phi)`` at the geocentric radius, colatitude and longitude, turned back into
the run's world frame.

**Cost and accuracy.** One call of the full model costs ~20 ms, and an integrator asks for the
field at every stage; so the field is sampled along the orbit every ``step`` seconds (one
vectorised call per block of an hour) and interpolated by a cubic spline in time (scipy's
``CubicSpline``), held as a :class:`~tumble.dynamics.environment.tabulated.CubicTable` per block:
:meth:`IGRFField.tabulate` hands the blocks covering a run to the compiled closed-loop kernel,
which evaluates them by the same rule as :meth:`IGRFField.world`. The field along a LEO orbit changes on scales of minutes (degree 13 over
~7.5 km/s): measured at 600 km, the interpolation error is 5e-13 of |B| at a 1 s step, 3e-10 at
the default 5 s, 8e-8 at 20 s and 6e-6 at 60 s, all far below IGRF's own uncertainty (tens of
nT in 30,000); :meth:`IGRFField.world_direct` evaluates without the spline. The coefficients are held at the epoch's values: the secular variation (at most ~100 nT
a year) moves the field by less than 0.3 nT in a day's run.
"""

from __future__ import annotations

import datetime as _dt
import functools
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..._optional import optional_import
from ...typing import ArrayLike, FloatArray, Vector3
from ...validation import check_positive
from .earth import earth_angle
from .magnetic import FIELD_PARAMETERS, FIELD_TABLE
from .sidereal import greenwich_sidereal_angle, julian_date, utc_datetime
from .tabulated import MARGIN, CubicTable, horner, spline_table

__all__ = ["IGRFField"]

#: Knots per interpolation block (an hour at the default 5 s step).
_BLOCK = 720


def _ppigrf() -> Any:
    return optional_import("ppigrf.ppigrf", "orbit", "the IGRF field (IGRFField)")


@functools.lru_cache(maxsize=1)
def _coefficients() -> tuple[Any, Any]:
    """The model file's Gauss coefficients ``(g, h)`` (nT, pandas tables by date), read once."""
    g, h = _ppigrf().read_shc()
    return g, h


@dataclass(frozen=True, eq=False)
class IGRFField:
    """IGRF-14 along an orbit, in the run's world frame (T); see the module docstring.

    Parameters
    ----------
    orbit : CircularOrbit, KeplerOrbit or TLEOrbit
        Where the spacecraft is (``position_eci(t)``, m, and ``eci_from_world``).
    epoch : datetime or ISO 8601 str, optional
        UTC at t = 0; default the TLE's epoch for a :class:`~tumble.dynamics.environment.ephemeris.TLEOrbit`
        (required otherwise). Must lie within the model's years (1900 to 2030 for IGRF-14).
    max_degree : int
        Highest degree of the expansion, 1 to 13 (1 is the tilted dipole).
    step : float
        Spacing of the interpolation knots, s (> 0, at most 60).

    Examples
    --------
    Over the north geomagnetic pole region the field points down and is about twice as strong
    as over the equator; at 500 km it is 20-50 microtesla:

    >>> import math
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> import numpy as np
    >>> from tumble.dynamics.environment.igrf import IGRFField
    >>> orbit = CircularOrbit(altitude=500e3, inclination=math.radians(97.4))
    >>> field = IGRFField(orbit, "2026-11-25T00:00:00")
    >>> B = np.linalg.norm(field.world(np.linspace(0.0, orbit.period, 60)), axis=1)
    >>> bool(18e-6 < B.min() < B.max() < 55e-6)
    True
    """

    orbit: Any
    epoch: _dt.datetime | str | None = None
    max_degree: int = 13
    step: float = 5.0
    _blocks: dict[int, FloatArray] = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        if not callable(getattr(self.orbit, "position_eci", None)) or not hasattr(self.orbit, "eci_from_world"):
            raise ValueError(f"orbit = {self.orbit!r} must be a CircularOrbit, KeplerOrbit or TLEOrbit")
        own = getattr(self.orbit, "epoch", None)  # a TLE's: its times count from it
        epoch = self.epoch if self.epoch is not None else own
        if epoch is None:
            raise ValueError("epoch is needed (the UTC date and time at t = 0, e.g. '2026-11-25T00:00:00')")
        when = utc_datetime(epoch, "epoch")
        if own is not None and abs((when - own).total_seconds()) > 1e-3:  # the Earth's angle read at another t = 0
            raise ValueError(f"epoch = {self.epoch!r} is not the TLE's own epoch {own.isoformat()}, from which its "
                             "orbit's times count: the field's must count from it too; leave epoch out")
        g, _ = _coefficients()
        first, last = g.index[0].to_pydatetime(), g.index[-1].to_pydatetime()
        if not first <= when.replace(tzinfo=None) <= last + _dt.timedelta(days=5 * 365.25):
            raise ValueError(f"epoch = {when.isoformat()} lies outside the model's years "
                             f"({first.year} to {last.year + 5})")
        object.__setattr__(self, "epoch", when)
        if isinstance(self.max_degree, bool) or not isinstance(self.max_degree, int) or not 1 <= self.max_degree <= 13:
            raise ValueError(f"max_degree = {self.max_degree!r} must be a whole number from 1 to 13")
        check_positive("step", self.step, "s", at_most=60.0)

    @property
    def gmst0(self) -> float:
        """The Greenwich sidereal angle at t = 0, rad.

        Examples
        --------
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> import numpy as np
        >>> from tumble.dynamics.environment.igrf import IGRFField
        >>> f = IGRFField(CircularOrbit(altitude=500e3), "1992-08-20T12:14:00")
        >>> round(f.gmst0 * 180 / np.pi, 6)   # deg: Vallado's example 3-5
        152.578788
        """
        return float(greenwich_sidereal_angle(julian_date(self._when)))

    @property
    def _when(self) -> _dt.datetime:
        assert isinstance(self.epoch, _dt.datetime)
        return self.epoch

    def gauss_degree1(self) -> tuple[float, float, float]:
        """The degree-1 Gauss coefficients ``(g10, g11, h11)`` at the epoch, T (linear in time between models).

        These make :class:`~tumble.dynamics.environment.magnetic.DipoleField` the degree-1 part of this field.

        Examples
        --------
        IGRF-14's definitive 2020 model (DGRF 2020), nT:

        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> from tumble.dynamics.environment.igrf import IGRFField
        >>> g = IGRFField(CircularOrbit(altitude=500e3), "2020-01-01T00:00:00").gauss_degree1()
        >>> [round(x * 1e9, 1) for x in g]
        [-29403.4, -1451.4, 4653.4]
        """
        g, h = _coefficients()
        stamps = np.array([t.timestamp() for t in g.index.to_pydatetime()])
        at = self._when.replace(tzinfo=None).timestamp()

        def value(table: Any, key: tuple[int, int]) -> float:
            return float(np.interp(at, stamps, np.asarray(table[key], float)) * 1e-9)

        return value(g, (1, 0)), value(g, (1, 1)), value(h, (1, 1))

    def world_direct(self, t: ArrayLike) -> Vector3:
        """B at ``t`` (s) from the full model, without interpolation, world frame, T; shape ``t.shape + (3,)``.

        Examples
        --------
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> import numpy as np
        >>> from tumble.dynamics.environment.igrf import IGRFField
        >>> f = IGRFField(CircularOrbit(altitude=500e3, inclination=1.0), "2026-01-01T00:00:00")
        >>> bool(np.allclose(f.world_direct([10.0, 2000.0]), f.world([10.0, 2000.0]), rtol=0, atol=1e-11))
        True
        """
        tt = np.asarray(t, float)
        return self._evaluate(tt.reshape(-1)).reshape(tt.shape + (3,))

    def _evaluate(self, t: FloatArray) -> FloatArray:
        r_eci = np.asarray(self.orbit.position_eci(t), float).reshape(-1, 3)
        theta = earth_angle(self.gmst0, t)
        c, s = np.cos(theta), np.sin(theta)
        x, y = c * r_eci[:, 0] + s * r_eci[:, 1], -s * r_eci[:, 0] + c * r_eci[:, 1]  # ECEF = R3(theta) ECI
        z = r_eci[:, 2]
        r = np.sqrt(x * x + y * y + z * z)
        colat, lon = np.arccos(z / r), np.arctan2(y, x)
        Br, Bt, Bp = (np.asarray(b, float).reshape(-1) * 1e-9 for b in _ppigrf().igrf_gc(
            r / 1e3, np.degrees(colat), np.degrees(lon), self._when.replace(tzinfo=None), max_degree=self.max_degree))
        st, ct, sp, cp = np.sin(colat), np.cos(colat), np.sin(lon), np.cos(lon)
        bx = Br * st * cp + Bt * ct * cp - Bp * sp  # ECEF from (r^, theta^, phi^)
        by = Br * st * sp + Bt * ct * sp + Bp * cp
        bz = Br * ct - Bt * st
        b_eci = np.stack([c * bx - s * by, s * bx + c * by, bz], axis=-1)
        return np.asarray(self.orbit.eci_from_world.inv().apply(b_eci), float)

    def _block(self, block: int) -> FloatArray:
        """The spline's coefficients ``(4, _BLOCK, 3)`` (T) on ``[block, block + 1) _BLOCK step``, made once."""
        coefficients = self._blocks.get(block)
        if coefficients is None:
            h = float(self.step)
            knots = np.asarray((block * _BLOCK + np.arange(-MARGIN, _BLOCK + MARGIN + 1)) * h, float)
            coefficients = spline_table(self._evaluate(knots), block * _BLOCK, h)
            coefficients.setflags(write=False)
            self._blocks[block] = coefficients
        return coefficients

    def tabulate(self, t_end: float) -> CubicTable:
        """The interpolating cubics over ``[0, t_end]`` (s), T: the blocks :meth:`world` evaluates, end to end.

        The table starts at t = 0 with knots ``step`` apart and ends at the end of the block that
        holds ``t_end``; it gives :meth:`world`'s values at every time in ``[0, t_end]`` (the same
        coefficients, the same interval ``floor(t / step)``, the same Horner sums). The compiled
        closed-loop kernel reads the field from it.

        Examples
        --------
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> import numpy as np
        >>> from tumble.dynamics.environment.igrf import IGRFField
        >>> f = IGRFField(CircularOrbit(altitude=500e3, inclination=1.0), "2026-01-01T00:00:00", step=10.0)
        >>> table = f.tabulate(9000.0)
        >>> table.t0, table.step, table.coefficients.shape   # two blocks of 720 intervals (2 h each at 10 s)
        (0.0, 10.0, (4, 1440, 3))
        >>> t = np.array([0.0, 3600.0, 4321.7, 9000.0])
        >>> bool(np.array_equal(table(t), f.world(t)))
        True
        """
        T = check_positive("t_end", t_end, "s")
        last = math.floor(T / (_BLOCK * float(self.step)))
        return CubicTable(0.0, float(self.step), np.concatenate([self._block(b) for b in range(last + 1)], axis=1))

    def loop_form(self) -> tuple[int, FloatArray] | None:
        """The compiled loop's form (:func:`~tumble.dynamics.environment.magnetic.field_form`):
        ``FIELD_TABLE`` and the start (0 s) and knot spacing (s) of the table the loop reads
        (:meth:`tabulate`, passed apart); None for a subclass with a ``world`` of its own.

        Examples
        --------
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> from tumble.dynamics.environment.igrf import IGRFField
        >>> from tumble.dynamics.environment.magnetic import FIELD_TABLE
        >>> kind, p = IGRFField(CircularOrbit(altitude=500e3), "2026-01-01T00:00:00").loop_form()
        >>> kind == FIELD_TABLE, p[:2].tolist()
        (True, [0.0, 5.0])
        """
        if type(self).world is not IGRFField.world:
            return None
        p = np.zeros(FIELD_PARAMETERS)
        p[:2] = (0.0, self.step)
        return FIELD_TABLE, p

    def world(self, t: ArrayLike) -> Vector3:
        """B at ``t`` (s from the epoch) in the world frame, T; shape ``t.shape + (3,)``.

        Examples
        --------
        The degree-1 field is the tilted dipole of
        :class:`~tumble.dynamics.environment.magnetic.DipoleField` with this epoch's coefficients:

        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> from tumble.dynamics.environment.magnetic import DipoleField
        >>> import numpy as np
        >>> from tumble.dynamics.environment.igrf import IGRFField
        >>> orbit = CircularOrbit(altitude=600e3, inclination=1.2, raan=0.3)
        >>> f = IGRFField(orbit, "2020-01-01T00:00:00", max_degree=1)
        >>> dipole = DipoleField(orbit, gmst0=f.gmst0, coefficients=f.gauss_degree1())
        >>> t = np.linspace(1.3, 3001.7, 7)   # between the spline's knots
        >>> bool(np.allclose(f.world(t), [dipole.world(x) for x in t], rtol=0, atol=1e-14))   # T, of ~4e-5
        True
        """
        tt = np.asarray(t, float)
        flat = tt.reshape(-1)
        if not np.all(np.isfinite(flat)):
            raise ValueError(f"t = {t!r} must be finite times, s from the epoch")
        h = float(self.step)
        knot = np.floor(flat / h)
        blocks = np.floor_divide(knot, _BLOCK).astype(int)
        out = np.empty((flat.size, 3))
        for block in np.unique(blocks):
            chosen = blocks == block
            c = self._block(int(block))[:, (knot[chosen] - block * _BLOCK).astype(int), :]
            out[chosen] = horner(c[0], c[1], c[2], c[3], (flat[chosen] - knot[chosen] * h)[:, None])
        return out.reshape(tt.shape + (3,))
