"""Double-double arithmetic: a number carried as the unevaluated sum ``hi + lo`` of two doubles.

About 32 significant digits (a relative rounding unit of ``2^-104 ~ 5e-32``), with plain numpy
operations, so every function works alike on Python floats and on arrays (broadcasting). The
exact solution of the free rigid body needs it for its phases: ``u = u0 + p t`` and the
precession angle grow without bound, and a phase of 1e17 rad computed in double precision is
wrong by more than a period (:mod:`tumble.dynamics.methods.exact`).

References
----------
- Dekker, "A floating-point technique for extending the available precision", Numer. Math. 18
  (1971) 224: ``split`` and ``two_prod`` (Veltkamp's splitting) without a fused multiply-add.
- Knuth, *The Art of Computer Programming* vol. 2, 3rd ed., sec. 4.2.2, Theorem B: ``two_sum``.
- Hida, Li & Bailey, "Algorithms for quad-double precision floating point arithmetic", Proc.
  ARITH-15 (2001) 155, and their QD library: the double-double ``add``, ``mul``, ``div`` and
  ``sqrt`` below.

The constants were rounded from 80-digit mpmath values.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TypeAlias

import numpy as np

from ...typing import BoolArray, FloatOrArray, IntArray

__all__ = [
    "LN2",
    "PI_2",
    "add",
    "div",
    "mul",
    "mul_d",
    "mul_scaled",
    "neg",
    "norm",
    "reduce_2pi",
    "sqrt",
    "two_prod",
    "two_sum",
    "where",
]

#: A double-double ``(hi, lo)``: two floats (one number) or two float arrays (elementwise).
DoubleDouble: TypeAlias = tuple[FloatOrArray, FloatOrArray]

#: pi / 2 and ln 2 as double-doubles; 2 pi as a triple (for reductions of angles up to ~1e30).
PI_2 = (1.5707963267948966, 6.123233995736766e-17)
#: ln 2 as a double-double (head, tail).
LN2 = (0.6931471805599453, 2.3190468138462996e-17)
_TWO_PI = (6.283185307179586, 2.4492935982947064e-16, -5.989539619436679e-33)
_SPLITTER = 134217729.0  # 2^27 + 1 (Dekker 1971)


def two_sum(a: FloatOrArray, b: FloatOrArray) -> DoubleDouble:
    """``s + e == a + b`` exactly, ``s = fl(a + b)`` (Knuth, Theorem 4.2.2B).

    Examples
    --------
    >>> from tumble.dynamics.special.ddouble import two_sum
    >>> two_sum(1.0, 1e-17)   # 1e-17 is lost in the rounded sum and kept whole in the error
    (1.0, 1e-17)
    >>> from fractions import Fraction
    >>> s, e = two_sum(0.1, 0.2)
    >>> Fraction(s) + Fraction(e) == Fraction(0.1) + Fraction(0.2)   # exact
    True
    """
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def _fast_two_sum(a: FloatOrArray, b: FloatOrArray) -> DoubleDouble:
    """``two_sum`` for ``|a| >= |b|`` (Dekker 1971)."""
    s = a + b
    return s, b - (s - a)


def _split(a: FloatOrArray) -> DoubleDouble:
    t = _SPLITTER * a
    hi = t - (t - a)
    return hi, a - hi


def two_prod(a: FloatOrArray, b: FloatOrArray) -> DoubleDouble:
    """``p + e == a * b`` exactly, ``p = fl(a * b)`` (Dekker 1971); ``|a|, |b| < ~1e300``.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from tumble.dynamics.special.ddouble import two_prod
    >>> p, e = two_prod(0.1, 0.3)
    >>> Fraction(p) + Fraction(e) == Fraction(0.1) * Fraction(0.3)   # the product, exactly
    True
    >>> two_prod(2.0**27 + 1.0, 2.0**27 - 1.0)   # 2^54 - 1 needs 54 bits: the 1 goes to the error
    (1.8014398509481984e+16, -1.0)
    """
    p = a * b
    ah, al = _split(a)
    bh, bl = _split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


def add(x: DoubleDouble, y: DoubleDouble) -> DoubleDouble:
    """``x + y`` for double-doubles (Hida, Li & Bailey 2001, the IEEE-style sum).

    Examples
    --------
    >>> from tumble.dynamics.special.ddouble import add
    >>> add((1.0, 1e-20), (1e-17, 0.0))   # both small parts are kept: 1 + 1.001e-17
    (1.0, 1.0010000000000001e-17)
    """
    s, e = two_sum(x[0], y[0])
    t, f = two_sum(x[1], y[1])
    s, e = _fast_two_sum(s, e + t)
    return _fast_two_sum(s, e + f)


def mul(x: DoubleDouble, y: DoubleDouble) -> DoubleDouble:
    """``x * y`` for double-doubles (Hida, Li & Bailey 2001).

    Examples
    --------
    >>> from fractions import Fraction
    >>> from tumble.dynamics.special.ddouble import div, mul
    >>> third = div((1.0, 0.0), (3.0, 0.0))
    >>> hi, lo = mul(third, (3.0, 0.0))
    >>> abs(Fraction(hi) + Fraction(lo) - 1) < Fraction(1, 10**31)   # (1/3) * 3 = 1 to ~32 digits
    True
    """
    p, e = two_prod(x[0], y[0])
    return _fast_two_sum(p, e + (x[0] * y[1] + x[1] * y[0]))


def mul_d(x: DoubleDouble, b: FloatOrArray) -> DoubleDouble:
    """``x * b`` for a double-double ``x`` and a double ``b``.

    Examples
    --------
    >>> from tumble.dynamics.special.ddouble import PI_2, mul_d
    >>> mul_d(PI_2, 2.0)   # pi to 32 digits: 3.14159265358979323846...
    (3.141592653589793, 1.2246467991473532e-16)
    """
    p, e = two_prod(x[0], b)
    return _fast_two_sum(p, e + x[1] * b)


def mul_scaled(x: DoubleDouble, b: FloatOrArray) -> DoubleDouble:
    """``x * b`` for a double-double ``x`` and doubles ``b``, both scaled by powers of two
    first (exactly), so that Dekker's splitting cannot overflow however large ``x`` is.

    Elementwise with numpy broadcasting: ``x`` of shape (N, 1) and ``b`` of shape (T,) give
    (N, T), one row per value of ``x``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.special.ddouble import mul_d, mul_scaled
    >>> big = (1e305, 1e288)
    >>> mul_d(big, 1e-10)   # Dekker's splitting of 1e305 overflows
    (nan, nan)
    >>> float(mul_scaled(big, 1e-10)[0])   # scaled by powers of two first
    1e+295
    >>> [a.shape for a in mul_scaled((np.ones((2, 1)), np.zeros((2, 1))), np.arange(5.0))]   # (N, 1) by (T,)
    [(2, 5), (2, 5)]
    """
    e = np.frexp(x[0])[1]
    return mul_d((np.ldexp(x[0], -e), np.ldexp(x[1], -e)), np.ldexp(b, e))


def where(cond: bool | BoolArray, x: DoubleDouble, y: DoubleDouble) -> DoubleDouble:
    """``x`` where ``cond``, else ``y``, for double-doubles (``numpy.where`` on both parts).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.special.ddouble import where
    >>> hi, lo = where(np.array([True, False]), (np.ones(2), np.full(2, 1e-20)), (np.zeros(2), np.zeros(2)))
    >>> hi.tolist(), lo.tolist()
    ([1.0, 0.0], [1e-20, 0.0])
    """
    return np.where(cond, x[0], y[0]), np.where(cond, x[1], y[1])


def div(x: DoubleDouble, y: DoubleDouble) -> DoubleDouble:
    """``x / y`` for double-doubles: two quotient digits, ~2^-104 relative (the "sloppy"
    division of Hida, Li & Bailey 2001).

    Examples
    --------
    >>> from fractions import Fraction
    >>> from tumble.dynamics.special.ddouble import div
    >>> hi, lo = div((1.0, 0.0), (3.0, 0.0))
    >>> abs(Fraction(hi) + Fraction(lo) - Fraction(1, 3)) < Fraction(1, 10**32)   # 1/3 to ~32 digits
    True
    """
    q1 = x[0] / y[0]
    p, e = two_prod(y[0], q1)
    r = ((x[0] - p) - e + x[1]) - q1 * y[1]
    return _fast_two_sum(q1, r / y[0])


def sqrt(x: DoubleDouble) -> DoubleDouble:
    """``sqrt(x)`` for a double-double ``x >= 0``: one Newton step from the double root
    (Hida, Li & Bailey 2001, after Karp & Markstein).

    Examples
    --------
    >>> from fractions import Fraction
    >>> from tumble.dynamics.special.ddouble import mul, sqrt
    >>> root2 = sqrt((2.0, 0.0))
    >>> hi, lo = mul(root2, root2)
    >>> abs(Fraction(hi) + Fraction(lo) - 2) < Fraction(1, 10**31)   # sqrt(2)^2 = 2 to ~32 digits
    True
    """
    if isinstance(x[0], float):  # a scalar: keep to Python's math (fast)
        if not 0.0 < x[0] < math.inf:  # 0, inf; nan for negative numbers, as numpy
            return (math.sqrt(x[0]) if x[0] >= 0 else math.nan), 0.0
        y: FloatOrArray = math.sqrt(x[0])
        p, e = two_prod(y, y)
        return _fast_two_sum(y, ((x[0] - p) - e + x[1]) / (2.0 * y))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        y = np.sqrt(x[0])
        p, e = two_prod(y, y)
        corr = ((x[0] - p) - e + x[1]) / (2.0 * y)
        return _fast_two_sum(y, np.where((y > 0) & (y < np.inf), corr, 0.0))


def neg(x: DoubleDouble) -> DoubleDouble:
    """``-x`` for a double-double (exact).

    Examples
    --------
    >>> from tumble.dynamics.special.ddouble import PI_2, add, neg
    >>> add(PI_2, neg(PI_2))
    (0.0, 0.0)
    """
    return -x[0], -x[1]


def norm(v: Sequence[DoubleDouble]) -> tuple[DoubleDouble, int | IntArray]:
    """``|v|`` of a sequence of double-doubles (floats or arrays, elementwise), as a double-double
    mantissa ``s`` and a power of two ``e``: ``|v| = s 2^e``. Each component is scaled by the
    power of two of the largest first (exactly), so that no square underflows or overflows.

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.special.ddouble import norm
    >>> (s, s_lo), e = norm([(3e200, 0.0), (4e200, 0.0)])   # the squares would overflow
    >>> math.isclose(math.ldexp(s, e), 5e200, rel_tol=1e-15)
    True
    """
    e: int | IntArray
    if np.ndim(v[0][0]) == 0:  # one vector: keep to Python's math (fast), as sqrt does
        e = e_int = math.frexp(max(abs(float(x[0])) for x in v))[1]  # 0 for a zero vector

        def scaled(x: DoubleDouble) -> DoubleDouble:
            return math.ldexp(float(x[0]), -e_int), math.ldexp(float(x[1]), -e_int)
    else:
        big = np.abs(v[0][0])  # an array on this branch (np.abs and abs are the same ufunc)
        for x in v[1:]:
            big = np.maximum(big, np.abs(x[0]))
        e = np.frexp(big)[1]  # 0 where big = 0

        def scaled(x: DoubleDouble) -> DoubleDouble:
            return ldexp(x, -e)
    acc: DoubleDouble = (0.0, 0.0)
    for x in v:
        x = scaled(x)
        acc = add(acc, mul(x, x))
    return sqrt(acc), e


def ldexp(x: DoubleDouble, e: int | IntArray) -> DoubleDouble:
    """``x * 2^e`` for a double-double (exact unless it leaves the normal range)."""
    return np.ldexp(x[0], e), np.ldexp(x[1], e)


def reduce_2pi(x: DoubleDouble) -> FloatOrArray:
    """A double-double angle reduced to ``[-pi, pi]``, rounded to double, rad.

    ``x - q 2 pi`` with ``q = rint(x / 2 pi)`` and ``2 pi`` carried to three doubles
    (Cody & Waite's reduction, extended); twice, because beyond 2^53 the first ``q`` is not the
    nearest integer itself. Good for ``|x|`` up to ~1e32; the reduction adds ~1e-32 |x|.

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.special.ddouble import PI_2, mul_d, reduce_2pi
    >>> float(reduce_2pi(mul_d(PI_2, 2.0**52 + 1.0)))   # 2^50 turns and a quarter: pi / 2
    1.5707963267948966
    >>> math.remainder(2 * math.pi * 2.0**50 + math.pi / 2, 2 * math.pi)   # in doubles: off by 0.43 rad
    2.0
    """
    r = x
    for _ in range(2):
        q = np.rint(r[0] / _TWO_PI[0])
        r = add(r, neg(two_prod(q, _TWO_PI[0])))
        r = add(r, neg(two_prod(q, _TWO_PI[1])))
        r = add(r, (-q * _TWO_PI[2], 0.0 * q))
    return r[0] + r[1]
