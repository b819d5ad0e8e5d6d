# SPDX-License-Identifier: Apache-2.0
"""Error measures and their accumulation.

Units (SPEC, "Accuracy contract (revision 2)"):

* ``ulp(x) = 2^(floor(log2|x|) - 52)`` for a normal double x (2^-1074 below);
  t error = |t_lib - t_exact| / ulp(t_exact), t_exact the exact crossing
  parameter.  When t_exact = 0 the library must return exactly 0: such hits
  are counted apart (``t0_bad``), not in ulps.
* point: exact distance from the reported point P to the exact surface, in
  ulps of max_k |P_k| (the resolution of P itself), and in ulps of the
  object's own scale (e.g. a sphere's max(|c|_inf, r)).
* normal: | |n| - 1 | in ulps of 1.0 (2^-52), and the angle between the
  reported normal and the exact unit normal at the exact hit point,
  atan2(|n x m|, n.m), in units of 2^-53 rad.
* decisions, per ray, over every crossing of the line (exact reference) and
  every reported hit: ``outside`` a reported hit whose exact t is outside
  [tmin, tmax]; ``missing`` an exact crossing in [tmin, tmax] not reported;
  ``kind`` ENTER / EXIT / TOUCH differ; ``count`` the number of hits differs;
  ``prim`` the face / part index differs; ``closest`` the closest-hit query
  (batch) reports another hit, or hit versus miss.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Sequence

import mpmath
import numpy as np

from .reference import RefHit, RefResult, exact

KIND_NAMES = {1: "enter", 2: "exit", 3: "touch"}
DECISIONS = ("outside", "missing", "kind", "count", "prim", "closest")
#: the per-hit measures (name -> unit), in table order
MEASURES = ("t", "t_closest", "point", "point_obj", "norm", "angle")


def ulp_exp(x: float) -> int:
    """e with ulp(x) = 2^e: floor(log2|x|) - 52, at least -1074."""
    if x == 0 or not math.isfinite(x):
        return -1074
    return max(math.frexp(x)[1] - 53, -1074)


def ulp_of_real(x: exact.Real) -> mpmath.mpf:
    """ulp of an exact value (its binade taken from the nearest double)."""
    return mpmath.ldexp(mpmath.mpf(1), ulp_exp(exact.to_double(x)))


def t_error_ulps(t_lib: float, t_exact: exact.Real) -> float:
    """|t_lib - t_exact| / ulp(t_exact) (t_exact != 0)."""
    return float(abs(mpmath.mpf(Fraction(t_lib)) - exact.mp(t_exact)) / ulp_of_real(t_exact))


def length_error_ulps(n: Sequence[float]) -> float:
    """| |n| - 1 | in ulps of 1.0 (2^-52), |n| exact to 80 digits."""
    s = sum(Fraction(x) ** 2 for x in n)
    return float(abs(mpmath.sqrt(mpmath.mpf(s)) - 1) * 2**52)


def angle_units(n: Sequence[float], m: Sequence[mpmath.mpf]) -> float:
    """Angle between n and m in units of 2^-53 rad."""
    a = [mpmath.mpf(x) for x in n]
    c = (a[1] * m[2] - a[2] * m[1], a[2] * m[0] - a[0] * m[2], a[0] * m[1] - a[1] * m[0])
    s = mpmath.sqrt(sum(x * x for x in c))
    return float(mpmath.atan2(s, sum(x * y for x, y in zip(a, m))) * 2**53)


@dataclass
class Tally:
    """Everything measured over one batch of rays, for one implementation."""
    rays: int = 0
    undecided: int = 0
    hits: int = 0
    t0_bad: int = 0
    self_hits: int = 0
    exact_self_hits: int = 0
    values: dict[str, list[float]] = field(default_factory=lambda: {k: [] for k in MEASURES})
    decisions: dict[str, int] = field(default_factory=lambda: {k: 0 for k in DECISIONS})
    worst: dict[str, tuple[float, str]] = field(default_factory=dict)

    def add(self, measure: str, value: float, where: str) -> None:
        self.values[measure].append(value)
        if value > self.worst.get(measure, (-1.0, ""))[0]:
            self.worst[measure] = (value, where)

    def merge(self, other: "Tally") -> None:
        for k in ("rays", "undecided", "hits", "t0_bad", "self_hits", "exact_self_hits"):
            setattr(self, k, getattr(self, k) + getattr(other, k))
        for k, v in other.values.items():
            self.values[k].extend(v)
        for k, v in other.decisions.items():
            self.decisions[k] += v
        for k, (v, w) in other.worst.items():
            if v > self.worst.get(k, (-1.0, ""))[0]:
                self.worst[k] = (v, w)

    def summary(self) -> "Summary":
        def stat(k: str) -> tuple[float, float] | None:
            v = self.values[k]
            if not v:
                return None
            arr = np.asarray(v)
            return float(arr.max()), float(np.quantile(arr, 0.999, method="higher"))
        return Summary(self.rays, self.undecided, self.hits, self.t0_bad, self.self_hits,
                       self.exact_self_hits, {k: stat(k) for k in MEASURES}, dict(self.decisions),
                       dict(self.worst))


@dataclass(frozen=True)
class Summary:
    """A Tally reduced to max / 99.9th percentile per measure (picklable, small)."""
    rays: int
    undecided: int
    hits: int
    t0_bad: int
    self_hits: int
    exact_self_hits: int
    stats: dict[str, tuple[float, float] | None]
    decisions: dict[str, int]
    worst: dict[str, tuple[float, str]]

    @property
    def decision_errors(self) -> int:
        return sum(self.decisions.values())

    def max(self, measure: str) -> float:
        s = self.stats.get(measure)
        return s[0] if s else 0.0


@dataclass(frozen=True)
class LibHit:
    """One reported hit (from a HIT_DTYPE record)."""
    t: float
    point: tuple[float, float, float]
    normal: tuple[float, float, float]
    prim: int
    kind: int

    @staticmethod
    def of(rec: np.void) -> "LibHit":
        return LibHit(float(rec["t"]), tuple(float(x) for x in rec["point"]),
                      tuple(float(x) for x in rec["normal"]), int(rec["prim"]), int(rec["kind"]))


def _gap(h: LibHit, r: RefHit) -> mpmath.mpf:
    return abs(mpmath.mpf(Fraction(h.t)) - exact.mp(r.t)) if math.isfinite(h.t) else mpmath.inf


def match(lib: Sequence[LibHit], ref: RefResult, by_prim: bool) -> tuple[list[tuple[LibHit, RefHit]], dict[str, int]]:
    """Pair reported hits with exact crossings and count the decision errors.

    When the reported list has the expected length and kinds, hits pair in
    order.  Otherwise each reported hit pairs with the nearest exact crossing
    (same prim first for meshes, whose faces are distinct surfaces), and the
    unpaired exact crossings in range are ``missing``.
    """
    kept = ref.kept
    errs = {k: 0 for k in DECISIONS}
    if len(lib) == len(kept) and all(KIND_NAMES.get(h.kind) == r.kind for h, r in zip(lib, kept)) \
            and (not by_prim or all(h.prim == r.prim for h, r in zip(lib, kept))):
        pairs = list(zip(lib, kept))
    else:
        if len(lib) != len(kept):
            errs["count"] += 1
        pairs, used = [], set()
        for h in lib:
            cands = [i for i, r in enumerate(ref.hits) if i not in used]
            if by_prim and any(ref.hits[i].prim == h.prim for i in cands):
                cands = [i for i in cands if ref.hits[i].prim == h.prim]
            if not cands:
                errs["outside"] += 1
                continue
            i = min(cands, key=lambda i: _gap(h, ref.hits[i]))
            used.add(i)
            r = ref.hits[i]
            if not r.inside:
                errs["outside"] += 1
                continue
            if KIND_NAMES.get(h.kind) != r.kind:
                errs["kind"] += 1
            pairs.append((h, r))
        errs["missing"] += sum(1 for i, r in enumerate(ref.hits) if r.inside and i not in used)
    for h, r in pairs:
        if h.prim != r.prim:
            errs["prim"] += 1
    return pairs, errs

