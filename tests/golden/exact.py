# SPDX-License-Identifier: Apache-2.0
"""Exact and high-precision numbers for the golden reference.

Every input of the corpus is an IEEE double.  ``Fraction(x)`` of a double is
exact, so everything that needs only + - * / (dot products, cross products,
determinants, ray parameters of planes, barycentric coordinates, tie
decisions) is computed *exactly* with ``fractions.Fraction``.  Square roots
(sphere, cylinder, ellipsoid and quadric roots, normalisation of normals) are
computed with mpmath at 80 significant digits (about 265 bits), whose error
is far below the 2^-53 rounding to the double that the JSON stores.

A value of type ``Real`` is either a Fraction (exact) or an mpmath ``mpf``
(80 digits).  ``to_double`` rounds either one correctly to the nearest double.

``DesignError`` is raised when a case is built so that its answer would be
decided by a hair: a comparison that 80 digits cannot separate, or an eps
decision too close to its threshold.  The generator refuses such cases, so a
disagreement with the library is never an artefact of the corpus design.

Inside ``deciding_exactly()`` (the accuracy harness, tests/accuracy) the
design refusals (``refuse``) return instead of raising and every such
decision is taken exactly; only ``PrecisionError`` (the working precision
``mpmath.mp.dps`` cannot separate two values) and the cases the contract
leaves undefined still raise.  The corpus generator enters that mode only
for the cases flagged "rounded-frame" (generate.py: "_exact").
"""
from __future__ import annotations

import contextlib
import contextvars
import math
from fractions import Fraction
from typing import Iterable, Iterator, Sequence, Union

import mpmath

mpmath.mp.dps = 80

Real = Union[Fraction, mpmath.mpf]
Vec = tuple[Real, Real, Real]

ZERO = Fraction(0)
ONE = Fraction(1)
#: unit roundoff of IEEE double precision
U = Fraction(1, 2**53)
#: two values the library computes (each to a few ulps) are only compared
#: when their relative gap is at least this (else the case is refused)
NEAR = Fraction(1, 10**12)


class DesignError(Exception):
    """A case whose expected answer is not robustly decided (fix the case)."""


class PrecisionError(DesignError):
    """mpmath at the working precision cannot decide a sign or comparison.

    Raised in both modes; the accuracy harness recomputes with more digits.
    """


_DECIDE_EXACTLY: contextvars.ContextVar[bool] = contextvars.ContextVar("decide_exactly", default=False)


@contextlib.contextmanager
def deciding_exactly() -> Iterator[None]:
    """Within the block, ``refuse`` returns: decisions by a hair are taken exactly."""
    token = _DECIDE_EXACTLY.set(True)
    try:
        yield
    finally:
        _DECIDE_EXACTLY.reset(token)


def refuse(reason: str) -> None:
    """Refuse a case decided by a hair (corpus design): raise DesignError.

    Inside ``deciding_exactly()`` return instead, and the caller goes on to
    the exact decision.
    """
    if not _DECIDE_EXACTLY.get():
        raise DesignError(reason)


# ----------------------------------------------------------------- scalars
def q(x: float | int | Fraction) -> Fraction:
    """The exact rational value of a finite double (or int/Fraction)."""
    if isinstance(x, Fraction):
        return x
    if isinstance(x, float) and not math.isfinite(x):
        raise ValueError(f"non-finite value {x!r} has no exact rational value")
    return Fraction(x)


def qv(v: Sequence[float]) -> tuple[Fraction, ...]:
    """Exact rational vector of doubles."""
    return tuple(q(x) for x in v)


def mp(x: Real) -> mpmath.mpf:
    """80-digit value of x (correctly rounded for a Fraction)."""
    return x if isinstance(x, mpmath.mpf) else mpmath.mpf(x)


def sqrt(x: Real) -> Real:
    """Square root; exact (a Fraction) when x is the square of a rational."""
    if isinstance(x, Fraction):
        if x < 0:
            raise ValueError("sqrt of a negative number")
        rn, rd = math.isqrt(x.numerator), math.isqrt(x.denominator)
        if rn * rn == x.numerator and rd * rd == x.denominator:
            return Fraction(rn, rd)
    return mpmath.sqrt(mp(x))


def to_double(x: Real) -> float:
    """The double nearest to x (ties to even).

    Fraction -> float is int/int true division, which CPython rounds
    correctly; an mpf is first converted to its exact binary rational.
    """
    if isinstance(x, Fraction):
        return float(x)
    sgn, man, exp, _ = x._mpf_          # x = (-1)^sgn * man * 2^exp
    if man == 0:
        if exp != 0:
            raise ValueError(f"non-finite mpf {x}")
        return 0.0
    v = float(Fraction(man) * Fraction(2) ** exp)
    return -v if sgn else v


def is_exact(x: Real) -> bool:
    return isinstance(x, Fraction)


def sign(x: Real) -> int:
    """Sign of x.  An mpf (irrational) value must be clearly nonzero
    (|x| >= 10^-(dps - 10), 10^-70 at the default 80 digits)."""
    if isinstance(x, Fraction):
        return (x > 0) - (x < 0)
    if abs(x) < mpmath.mpf(10) ** -(mpmath.mp.dps - 10):
        raise PrecisionError(f"sign of an irrational quantity too close to 0: {x}")
    return 1 if x > 0 else -1


def cmp(a: Real, b: Real) -> int:
    """Exact three-way comparison; refuses irrational near-ties (closer than
    10^-(dps - 20) relative to max(|a|, |b|, 1): 10^-60 at 80 digits)."""
    if isinstance(a, Fraction) and isinstance(b, Fraction):
        return (a > b) - (a < b)
    d = mp(a) - mp(b)
    scale = max(abs(mp(a)), abs(mp(b)), mpmath.mpf(1))
    if abs(d) <= scale * mpmath.mpf(10) ** -(mpmath.mp.dps - 20):
        raise PrecisionError(f"cannot separate {a} and {b} in {mpmath.mp.dps} digits")
    return 1 if d > 0 else -1


def rel_gap(a: Real, b: Real) -> mpmath.mpf:
    """|a - b| / max(|a|, |b|) in 80 digits (0 when both are 0)."""
    m = max(abs(mp(a)), abs(mp(b)))
    return abs(mp(a) - mp(b)) / m if m else mpmath.mpf(0)


def representable(x: Fraction) -> bool:
    """True when the rational x is exactly a double."""
    try:
        return Fraction(float(x)) == x
    except OverflowError:
        return False


# ----------------------------------------------------------------- vectors
def add(a: Sequence[Real], b: Sequence[Real]) -> tuple:
    return tuple(x + y for x, y in zip(a, b))


def sub(a: Sequence[Real], b: Sequence[Real]) -> tuple:
    return tuple(x - y for x, y in zip(a, b))


def scale(s: Real, a: Sequence[Real]) -> tuple:
    return tuple(s * x for x in a)


def dot(a: Sequence[Real], b: Sequence[Real]) -> Real:
    return sum((x * y for x, y in zip(a, b)), ZERO)


def cross(a: Sequence[Real], b: Sequence[Real]) -> tuple:
    return (a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0])


def norm2(a: Sequence[Real]) -> Real:
    return dot(a, a)


def is_zero(a: Iterable[Real]) -> bool:
    return all(x == 0 for x in a)


def unit(a: Sequence[Real]) -> tuple:
    """a / |a| (exact when |a| is rational)."""
    n = sqrt(norm2(a))
    if n == 0:
        raise ValueError("unit() of a zero vector")
    return tuple(x / n for x in a)


def point_on_ray(org: Sequence[Real], d: Sequence[Real], t: Real) -> tuple:
    """org + t*dir, componentwise; a component with dir = 0 stays exactly org.

    Every quantity that is affine in t (points, sphere/ellipsoid offsets,
    cylinder radial vectors, quadric gradients) is evaluated through this, so
    a coordinate that is exactly constant along the ray is never polluted by
    80-digit rounding of an irrational t.
    """
    return tuple(o if x == 0 else o + t * x for o, x in zip(org, d))


# ------------------------------------------------------------ eps decisions
def eps_le(lhs: Fraction, rhs: Fraction, what: str, noise_scale: Fraction | None = None) -> bool:
    """Exact ``lhs <= rhs`` for non-negative *squared* test quantities.

    The library evaluates these tests in floating point, so a case must not
    sit near the threshold: unless lhs is exactly 0 (deliberate exact
    tangency / parallelism), the ratio lhs/rhs must be outside [1/4, 4]
    (a factor 2 on the unsquared quantities).  With rhs = 0 (eps = 0), a
    nonzero lhs must also stand well above floating-point noise relative to
    ``noise_scale`` (a squared magnitude of the same dimension).
    Inside ``deciding_exactly()`` these refusals fall through to the exact
    ``lhs <= rhs``.
    """
    if lhs < 0 or rhs < 0:
        raise ValueError("eps_le expects non-negative quantities")
    if lhs == 0:
        return True
    if rhs == 0:
        if noise_scale is not None and lhs < noise_scale * Fraction(1, 10**16):
            refuse(f"{what}: eps = 0 and the test quantity is within noise")
        return False
    ratio = lhs / rhs
    if Fraction(1, 4) <= ratio <= 4:
        refuse(f"{what}: eps decision too close to its threshold (ratio {float(ratio):.3g})")
    return ratio <= 1
