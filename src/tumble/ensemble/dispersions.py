"""Dispersions that stay physical: uncertain parts, preset parameters, moments and axes.

A :class:`Dispersion` names one uncertain quantity and its spread:

- ``target = "preset"``: a parameter of the preset the body was made from
  (``shaft_length`` of :func:`tumble.t_handle`, ...): the body is built again from the
  perturbed parameters, so parts stay attached as the preset places them;
- ``target = "part"``: a field of ``body.parts[part]`` (``mass``, ``density``, a size such as
  ``length``, ``radius``, ``size``, ``semi_axes``, or ``center``); a vector field is perturbed
  component by component. A part given by density keeps its density (its mass follows its
  size); a part given by mass keeps its mass;
- ``target = "moments"``: each principal moment times ``1 + s z`` (relative spreads only);
- ``target = "axes"``: the principal axes turned by a small random rotation, the rotation
  vector ``s z`` (rad, absolute spreads only, one deviate per design axis x, y, z).

``z`` is a standard deviate (:func:`tumble.ensemble.sampling.deviates`): normal (``s`` is one
standard deviation) or uniform on [-1, 1] (``s`` is the half-width); ``relative = True`` makes
a field ``v (1 + s z)``, ``False`` makes it ``v + s z`` (in the field's unit).

Physical validity. The perturbed parts go through the part and body constructors, and the
perturbed tensor ``A diag(I) A^T`` through :meth:`tumble.mass.MassProperties.from_inertia`
(symmetric, positive semidefinite, triangle inequality ``I1 + I2 >= I3``; Goldstein sec. 5.4),
and a moment within :data:`tumble.mass.INERTIA_RTOL` of zero is refused as
:func:`tumble.simulate` refuses it: :meth:`BodySampler.sample` raises ``ValueError`` for a draw
that breaks any rule, and the caller draws again (:mod:`tumble.ensemble.cases`). A draw is
never clipped or repaired, so the accepted cases follow the dispersions *conditioned* on being
physical (for a planar body, whose moments sit on the triangle inequality, half of all
independent moment draws are refused).
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import warnings
from dataclasses import dataclass
from typing import cast

import numpy as np
from scipy.spatial.transform import Rotation

from ..mass import INERTIA_RTOL, PRESETS, Body, MassProperties, UnitSlipWarning, principal_frame
from ..typing import ArrayLike
from ._part_fields import _NOT_NUMBERS, _is_number, _perturb, _replace, _unit, _width
from .sampling import DISTRIBUTIONS, deviates

__all__ = ["MAX_AXES_SPREAD", "TARGETS", "BodySampler", "Dispersion", "Sampled"]

#: What a dispersion can act on.
TARGETS = ("preset", "part", "moments", "axes")
#: The largest spread of ``target = "axes"`` taken without a word (rad, ~57 deg): past it the axes are
#: not known at all, and a spread in degrees read as radians is likelier.
MAX_AXES_SPREAD = 1.0


@dataclass(frozen=True)
class Dispersion:
    """One uncertain quantity and its spread (module docstring).

    Parameters
    ----------
    target : {"preset", "part", "moments", "axes"}
        What is perturbed.
    spread : float
        ``s`` >= 0: a fraction below 1 with ``relative`` (0.05 for 5 %), else in the quantity's unit (rad for axes).
        One standard deviation (normal) or the half-width (uniform).
    field : str, optional
        The preset parameter or part field (targets "preset" and "part" only).
    part : int, optional
        Index into ``body.parts``, from 0 (target "part" only).
    relative : bool
        ``v (1 + s z)`` (True) or ``v + s z`` (False). Moments take relative spreads only,
        axes absolute ones only.
    distribution : {"normal", "uniform"}
        Of the deviate ``z``.

    Examples
    --------
    >>> from tumble.ensemble.dispersions import Dispersion
    >>> Dispersion("part", 0.02, field="length", part=1).label
    'parts[1].length'
    >>> Dispersion("moments", 0.01, relative=False)
    Traceback (most recent call last):
    ...
    ValueError: target 'moments' takes a relative spread only (a fraction of each moment)
    """

    target: str
    spread: float
    field: str | None = None
    part: int | None = None
    relative: bool = True
    distribution: str = "normal"

    def __post_init__(self) -> None:
        if not isinstance(self.target, str) or self.target not in TARGETS:
            raise ValueError(f"target = {self.target!r} is unknown; allowed: {', '.join(TARGETS)}")
        if not isinstance(self.distribution, str) or self.distribution not in DISTRIBUTIONS:
            raise ValueError(f"distribution = {self.distribution!r} is unknown; allowed: {', '.join(DISTRIBUTIONS)}")
        s = self.spread
        if isinstance(s, bool) or not isinstance(s, (int, float, np.integer, np.floating)) or not (
                math.isfinite(s) and s >= 0):
            raise ValueError(f"spread = {s!r} must be a finite number >= 0")
        object.__setattr__(self, "spread", float(s))
        if not isinstance(self.relative, bool):
            raise ValueError(f"relative = {self.relative!r} must be true or false")
        if self.relative and s >= 1.0:  # 5 for 5 %: a length drawn negative in a third of the cases or more
            raise ValueError(f"spread = {s!r} is a relative spread of {100 * s:g} %, which draws the quantity at zero or "
                             f"with the other sign: give a fraction (0.05 for 5 %), below 1")
        named = self.target in ("preset", "part")
        if named != isinstance(self.field, str):
            raise ValueError(f"field = {self.field!r}: target {self.target!r} "
                             f"{'needs a field name' if named else 'takes no field'}")
        if (self.target == "part") != (self.part is not None):
            raise ValueError(f"part = {self.part!r}: only target 'part' takes a part index, and it needs one")
        if self.part is not None and (isinstance(self.part, bool) or not isinstance(self.part, (int, np.integer))
                                      or self.part < 0):
            raise ValueError(f"part = {self.part!r} must be a whole number >= 0 (an index into the body's parts)")
        if self.target == "moments" and not self.relative:
            raise ValueError("target 'moments' takes a relative spread only (a fraction of each moment)")
        if self.target == "axes" and self.relative:
            raise ValueError("target 'axes' takes an absolute spread only (rad, the small rotation's size)")
        if self.target == "axes" and s > MAX_AXES_SPREAD:  # 5 meant as 5 deg turned the axes anywhere: 98.7 % -> 44 %
            warnings.warn(f'target "axes": absolute spread = {s!r} rad is past {MAX_AXES_SPREAD:g} rad '
                          f"({math.degrees(MAX_AXES_SPREAD):.0f} deg), principal axes not known at all: is it in "
                          f"degrees? Write radians ({s!r} deg is {math.radians(s):.4g} rad)", UnitSlipWarning, stacklevel=3)

    @property
    def label(self) -> str:
        """Its name in tables: ``shaft_length``, ``parts[1].length``, ``moments``, ``axes``.

        Examples
        --------
        >>> from tumble.ensemble.dispersions import Dispersion
        >>> Dispersion("preset", 0.05, field="shaft_length").label, Dispersion("axes", 0.01, relative=False).label
        ('shaft_length', 'axes')
        """
        if self.target == "preset":
            return str(self.field)
        if self.target == "part":
            return f"parts[{self.part}].{self.field}"
        return self.target


@dataclass(frozen=True, eq=False)
class Sampled:
    """One drawn body: what the dynamics needs and the values drawn.

    Attributes
    ----------
    moments : ndarray, shape (3,)
        Principal moments, ascending, kg m^2.
    axes : ndarray, shape (3, 3)
        Principal axes (columns) in the design frame: principal -> design.
    values : ndarray, shape (p,)
        The drawn quantities, in the order of :attr:`BodySampler.names`.

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble.dispersions import BodySampler
    >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
    >>> drawn = BodySampler(box).sample([])
    >>> drawn.moments.round(12).tolist(), drawn.values.shape  # the nominal body, m (b^2 + c^2) / 12
    ([5.0, 10.0, 13.0], (0,))
    """

    moments: np.ndarray
    axes: np.ndarray
    values: np.ndarray


@dataclass(frozen=True, eq=False)
class BodySampler:
    """A nominal body and its dispersions, checked against each other.

    Parameters
    ----------
    body : Body
        The nominal body (rigid: no rotors).
    dispersions : sequence of Dispersion
        Applied in order: preset parameters, then parts, then moments, then axes (whatever
        the order given), each taking its deviates in the order given.
    preset : str, optional
        The name of the preset the body was made from (needed by target "preset").
    parameters : dict, optional
        The keyword arguments the preset was called with.

    Raises
    ------
    ValueError
        One line naming the dispersion (by its index) and the rule: a part index out of range,
        a field the part does not have or that is not a number, a preset parameter that the
        preset does not take or that has no number to perturb, a body with rotors.

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble.dispersions import BodySampler, Dispersion
    >>> sampler = BodySampler(tumble.t_handle(), (Dispersion("preset", 0.05, field="shaft_length"),
    ...                                           Dispersion("axes", 0.01, relative=False)), preset="t-handle")
    >>> sampler.dims, sampler.names
    (4, ('shaft_length [m]', 'axes_rotvec_x [rad]', 'axes_rotvec_y [rad]', 'axes_rotvec_z [rad]'))
    >>> BodySampler(tumble.t_handle(), (Dispersion("part", 0.1, field="radius", part=0),))
    Traceback (most recent call last):
    ...
    ValueError: dispersions[0] (parts[0].radius): a rod has no number 'radius' to perturb; allowed: mass, center, length
    """

    body: Body
    dispersions: tuple[Dispersion, ...] = ()
    preset: str | None = None
    parameters: dict | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.body, Body):
            raise ValueError(f"body = {self.body!r} must be a tumble Body")
        if self.body.rotors:
            raise ValueError(f"the body has {len(self.body.rotors)} rotor(s); sweeps run rigid bodies only")
        items = tuple(self.dispersions)
        for k, d in enumerate(items):
            if not isinstance(d, Dispersion):
                raise ValueError(f"dispersions[{k}] = {d!r} is not a tumble.ensemble.Dispersion")
        if self.preset is not None and self.preset not in PRESETS:
            raise ValueError(f"preset = {self.preset!r} is unknown; allowed: {', '.join(PRESETS)}")
        object.__setattr__(self, "dispersions", items)
        object.__setattr__(self, "parameters", dict(self.parameters or {}))
        if self.preset is not None:
            self._check_preset_body()
        widths = [self._width(k, d) for k, d in enumerate(items)]
        object.__setattr__(self, "_widths", tuple(widths))

    def _check_preset_body(self) -> None:
        """Refuse a ``body`` that is not ``preset`` made with ``parameters``: a "preset" dispersion remakes the
        body from them, and a walkthrough's 0.5 m by 1.2 m T-handle (moments 0.078, 0.18, 0.258 kg m^2), given
        without its parameters, was swept as the default 1 m handle (0.125, 0.3125, 0.4375) without a word."""
        try:
            made = PRESETS[cast(str, self.preset)](**self.parameters)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"parameters = {self.parameters!r} do not make preset {self.preset!r}: {exc}") from None
        mine, theirs = self.body, made
        if not (math.isclose(mine.mass, theirs.mass, rel_tol=1e-9) and np.allclose(
                mine.principal_moments, theirs.principal_moments, rtol=1e-9, atol=0.0)):
            raise ValueError(
                f"body = {self.body.name!r} (mass {mine.mass:.6g} kg, moments "
                f"{', '.join(f'{x:.6g}' for x in mine.principal_moments)} kg m^2) is not preset {self.preset!r} made "
                f"with parameters = {self.parameters!r} ({theirs.mass:.6g} kg; "
                f"{', '.join(f'{x:.6g}' for x in theirs.principal_moments)}), which its 'preset' dispersions remake: "
                "give the keyword arguments the body was made with as parameters")

    def _nominal_parameters(self) -> dict:
        signature = inspect.signature(PRESETS[self.preset])
        defaults = {k: p.default for k, p in signature.parameters.items()}
        return {**defaults, **self.parameters}

    def _width(self, k: int, d: Dispersion) -> int:
        where = f"dispersions[{k}] ({d.label})"
        if d.target in ("moments", "axes"):
            return 3
        if d.target == "preset":
            if self.preset is None:
                raise ValueError(f"{where}: target 'preset' needs a body given as a preset ({', '.join(PRESETS)})")
            params = self._nominal_parameters()
            if d.field not in params:
                raise ValueError(f"{where}: preset {self.preset!r} has no parameter {d.field!r}; "
                                 f"allowed: {', '.join(k for k in params if k != 'name')}")
            if not _is_number(params[d.field]):
                raise ValueError(f"{where}: preset parameter {d.field} = {params[d.field]!r} has no number to "
                                 f"perturb; give it a value in the body table")
            return 1
        if d.part >= len(self.body.parts):
            raise ValueError(f"{where}: part = {d.part} is out of range; the body has parts 0 to "
                             f"{len(self.body.parts) - 1}")
        part = self.body.parts[d.part]
        fields = [f.name for f in dataclasses.fields(part) if f.init and f.name not in _NOT_NUMBERS]
        value = getattr(part, d.field, None) if d.field in fields else None
        width = _width(value)
        if not width:
            numeric = [f for f in fields if _width(getattr(part, f))]
            raise ValueError(f"{where}: a {part.kind} has no number {d.field!r} to perturb; "
                             f"allowed: {', '.join(numeric)}")
        if d.field == "density" and part.density is None:
            raise ValueError(f"{where}: this {part.kind} was given by its mass, not a density; perturb 'mass'")
        return width

    @property
    def widths(self) -> tuple[int, ...]:
        """Deviates each dispersion takes (1 or 3), in order.

        Examples
        --------
        >>> import tumble
        >>> from tumble.ensemble.dispersions import BodySampler, Dispersion
        >>> body = tumble.t_handle()
        >>> BodySampler(body, (Dispersion("part", 0.1, field="center", part=0, relative=False),
        ...                    Dispersion("part", 0.1, field="mass", part=1))).widths  # a vector takes 3
        (3, 1)
        """
        return self._widths  # type: ignore[attr-defined]

    @property
    def dims(self) -> int:
        """Deviates per case, in all.

        Examples
        --------
        >>> import tumble
        >>> from tumble.ensemble.dispersions import BodySampler, Dispersion
        >>> BodySampler(tumble.t_handle(), (Dispersion("moments", 0.02),)).dims
        3
        """
        return sum(self.widths)

    @property
    def distributions(self) -> tuple[str, ...]:
        """The distribution of each deviate, shape (dims,).

        Examples
        --------
        >>> import tumble
        >>> from tumble.ensemble.dispersions import BodySampler, Dispersion
        >>> BodySampler(tumble.t_handle(), (Dispersion("part", 0.1, field="mass", part=0, distribution="uniform"),
        ...                                 Dispersion("moments", 0.02))).distributions
        ('uniform', 'normal', 'normal', 'normal')
        """
        return tuple(d.distribution for d, w in zip(self.dispersions, self.widths) for _ in range(w))

    @property
    def names(self) -> tuple[str, ...]:
        """Column names (with units) of the drawn values :attr:`Sampled.values`.

        Examples
        --------
        >>> import tumble
        >>> from tumble.ensemble.dispersions import BodySampler, Dispersion
        >>> BodySampler(tumble.t_handle(), (Dispersion("part", 0.1, field="mass", part=1),
        ...                                 Dispersion("moments", 0.02))).names
        ('parts[1].mass [kg]', 'moment_factor_1', 'moment_factor_2', 'moment_factor_3')
        """
        out = []
        for d, w in zip(self.dispersions, self.widths):
            if d.target == "moments":
                out += [f"moment_factor_{j}" for j in (1, 2, 3)]
            elif d.target == "axes":
                out += [f"axes_rotvec_{c} [rad]" for c in "xyz"]
            elif w == 3:
                out += [f"{d.label}[{j}] [{_unit(d.field)}]" for j in range(3)]
            else:
                out.append(f"{d.label} [{_unit(d.field)}]")
        return tuple(out)

    def deviates(self, u: ArrayLike) -> np.ndarray:
        """Map unit-cube points (shape (dims,) or (m, dims)) to the deviates ``z`` of the dispersions.

        Examples
        --------
        >>> import tumble
        >>> from tumble.ensemble.dispersions import BodySampler, Dispersion
        >>> sampler = BodySampler(tumble.t_handle(), (Dispersion("part", 0.1, field="mass", part=0, distribution="uniform"),
        ...                                           Dispersion("part", 0.1, field="mass", part=1)))
        >>> sampler.deviates([0.75, 0.975]).round(3).tolist()  # uniform 2 u - 1, normal Phi^-1(u)
        [0.5, 1.96]
        """
        u = np.asarray(u, dtype=float)
        z = np.empty(u.shape[:-1] + (self.dims,))
        names = np.array(self.distributions)
        for name in set(self.distributions):
            z[..., names == name] = deviates(u[..., names == name], name)
        return z

    def sample_many(self, z: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
        """:meth:`sample` for many draws at once, where it can be done with arrays.

        Only for dispersions of the moments and axes (none of parts or preset parameters): the
        rows come out bit for bit as :meth:`sample` makes them one by one (tested). A row whose
        tensor lies within ``1e-6`` of its trace of a rule's edge (a zero or negative moment, the
        triangle inequality) is not decided here: the caller makes it with :meth:`sample`, which
        refuses it or not exactly as for a single draw.

        Parameters
        ----------
        z : ndarray, shape (m, dims)
            The deviates (:meth:`deviates`).

        Returns
        -------
        tuple or None
            ``(moments (m, 3), axes (m, 3, 3), values (m, p), decided (m,) of bool)``; None when
            a dispersion acts on parts or preset parameters.

        Examples
        --------
        >>> import tumble
        >>> import numpy as np
        >>> from tumble.ensemble.dispersions import BodySampler, Dispersion
        >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
        >>> sampler = BodySampler(box, (Dispersion("moments", 0.01),))
        >>> z = np.random.default_rng(0).normal(size=(5, 3))
        >>> moments, axes, values, decided = sampler.sample_many(z)
        >>> moments.shape, axes.shape, bool(decided.all())
        ((5, 3), (5, 3, 3), True)
        >>> bool(np.array_equal(moments[2], sampler.sample(z[2]).moments))  # bit for bit
        True
        """
        if any(d.target in ("preset", "part") for d in self.dispersions):
            return None
        z = np.asarray(z, dtype=float)
        m = len(z)
        chunks = np.split(z, np.cumsum(self.widths)[:-1], axis=1) if self.dispersions else []
        values = np.empty((m, 0)) if not chunks else np.empty((m, self.dims))
        moments, axes = self.body.principal_moments, self.body.principal_axes
        factor, turn = np.ones((m, 3)), Rotation.identity()
        col = np.cumsum((0,) + self.widths)
        for k, d in enumerate(self.dispersions):
            if d.target == "moments":
                values[:, col[k]:col[k + 1]] = 1.0 + d.spread * chunks[k]
        for k, d in enumerate(self.dispersions):
            if d.target == "moments":
                factor = factor * values[:, col[k]:col[k + 1]]
        for k, d in enumerate(self.dispersions):
            if d.target == "axes":
                values[:, col[k]:col[k + 1]] = d.spread * chunks[k]
                turn = Rotation.from_rotvec(values[:, col[k]:col[k + 1]]) * turn
        if not self.dispersions:  # the nominal body: sample's only rule is the zero moment
            ok = not np.any(moments <= INERTIA_RTOL * np.sum(moments))
            return np.tile(moments, (m, 1)), np.tile(axes, (m, 1, 1)), values, np.full(m, ok)
        else:
            A = turn.as_matrix().reshape(-1, 3, 3) @ axes
            D = np.zeros((m, 3, 3))
            D[:, [0, 1, 2], [0, 1, 2]] = moments * factor
            tensor = A @ D @ np.swapaxes(A, -1, -2)
            tensor = 0.5 * (tensor + np.swapaxes(tensor, -1, -2))  # as check_inertia returns it
            out_moments, out_axes = principal_frame(tensor)
        trace = np.sum(out_moments, axis=1)
        margin = 1e-6 * np.abs(trace)
        decided = (np.all(np.isfinite(out_moments), axis=1) & (out_moments[:, 0] > margin)
                   & (out_moments[:, 2] - out_moments[:, 0] - out_moments[:, 1] < -margin))
        return np.array(out_moments), np.array(out_axes), values, decided

    def sample(self, z: ArrayLike) -> Sampled:
        """The body for the deviates ``z`` (shape (dims,)).

        Raises
        ------
        ValueError
            When the draw is not a physical body (module docstring): the caller draws again.

        Examples
        --------
        >>> import tumble
        >>> import numpy as np
        >>> from tumble.ensemble.dispersions import BodySampler, Dispersion
        >>> sampler = BodySampler(tumble.t_handle(), (Dispersion("preset", 0.1, field="shaft_length"),), preset="t-handle")
        >>> drawn = sampler.sample([1.0])  # z = 1: a shaft 10 % longer
        >>> drawn.values.tolist(), bool(np.allclose(drawn.moments, tumble.t_handle(shaft_length=1.1).principal_moments))
        ([1.1], True)
        """
        z = np.asarray(z, dtype=float)
        chunks = np.split(z, np.cumsum(self.widths)[:-1]) if self.dispersions else []
        drawn = dict(zip(range(len(self.dispersions)), chunks))
        values: dict[int, np.ndarray] = {}
        body = self.body
        by_target = {t: [k for k, d in enumerate(self.dispersions) if d.target == t] for t in TARGETS}
        if by_target["preset"]:
            kwargs = dict(self.parameters)
            nominal = self._nominal_parameters()
            for k in by_target["preset"]:
                d = self.dispersions[k]
                kwargs[d.field] = _perturb(nominal[d.field], d.spread, d.relative, drawn[k])
                values[k] = np.atleast_1d(kwargs[d.field])
            body = PRESETS[self.preset](**kwargs)
        if by_target["part"]:
            parts = list(body.parts)
            for k in by_target["part"]:
                d = self.dispersions[k]
                new = _perturb(getattr(parts[d.part], d.field), d.spread, d.relative, drawn[k])
                parts[d.part] = _replace(parts[d.part], d.field, new)
                values[k] = np.atleast_1d(new)
            body = Body(tuple(parts), body.name)
        moments, axes = body.principal_moments, body.principal_axes
        if by_target["moments"] or by_target["axes"]:
            factor, turn = np.ones(3), Rotation.identity()
            for k in by_target["moments"]:
                values[k] = 1.0 + self.dispersions[k].spread * drawn[k]
                factor = factor * values[k]
            for k in by_target["axes"]:
                values[k] = self.dispersions[k].spread * drawn[k]
                turn = Rotation.from_rotvec(values[k]) * turn
            A = turn.as_matrix() @ axes
            tensor = A @ np.diag(moments * factor) @ A.T
            props = MassProperties.from_inertia(body.mass, body.com, tensor)
            moments, axes = props.principal_moments, props.principal_axes
        if np.any(moments <= INERTIA_RTOL * np.sum(moments)):
            raise ValueError(f"principal moments {moments.tolist()} kg m^2 include a zero moment")
        flat = [values[k] for k in range(len(self.dispersions))]
        return Sampled(np.array(moments), np.array(axes), np.concatenate(flat) if flat else np.empty(0))
