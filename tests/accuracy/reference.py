# SPDX-License-Identifier: Apache-2.0
"""The exact reference: the solvers of ``tests/golden`` deciding exactly.

The golden solvers evaluate everything rational with ``fractions.Fraction``
(exact) and square roots with mpmath (80 digits by default).  Written for
corpus design, they refuse configurations decided "by a hair"; inside
``exact.deciding_exactly()`` those refusals fall through to the exact
decision, which is what the harness needs.  When mpmath at the working
precision cannot separate two irrational values (``exact.PrecisionError``)
the solve is repeated with more digits (200, then 600).  What is still
refused is left undefined by the contract (a ray along a cylinder's side
surface, a hit at a singular point of a quadric): ``Undecided``.

Epsilon policy (SPEC, revision 2): planes, convex faces and cylinder caps are
parallel when |n.d| <= eps |n||d|, quadric surfaces TOUCH by their documented
scale-invariant test, both with eps = ``EPS`` (the library default 1e-12).
Triangles, polygons and mesh faces use no eps: the golden solvers are called
with eps = 0, so only an exactly parallel ray (n.d = 0) is "parallel", which
is the exact sheared-frame test's own answer (such a ray cannot cross).
"""
from __future__ import annotations

import functools
import math
import sys
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Callable, Sequence

import mpmath

GOLDEN = Path(__file__).resolve().parents[1] / "golden"
if str(GOLDEN) not in sys.path:
    sys.path.insert(0, str(GOLDEN))
_WRITE_BYTECODE = sys.dont_write_bytecode
sys.dont_write_bytecode = True          # keep tests/golden free of __pycache__

import box  # noqa: E402
import convex  # noqa: E402
import cylinder  # noqa: E402
import ellipsoid  # noqa: E402
import exact  # noqa: E402
import mesh  # noqa: E402
import model  # noqa: E402
import plane  # noqa: E402
import polygon  # noqa: E402
import quadric  # noqa: E402
import sphere  # noqa: E402
import transformed  # noqa: E402
import triangle  # noqa: E402
from exact import Real  # noqa: E402

sys.dont_write_bytecode = _WRITE_BYTECODE

# transformed.solve inverts the same 3x3 matrix (exactly, in Fractions) twice
# per ray; memoising that pure function changes no result and saves a third
# of the time of a transformed solve.
transformed.inverse3 = functools.lru_cache(maxsize=64)(transformed.inverse3)

#: the library's default eps (ISECT_EPS_DEFAULT), as an exact rational
EPS = Fraction(1e-12)
#: digits tried in turn when a comparison cannot be decided
PRECISIONS = (80, 200, 600)

Solver = Callable[[dict, "model.XRay", "model.Ctx"], list]

SOLVERS: dict[str, Solver] = {
    "plane": plane.solve, "sphere": sphere.solve, "box": box.solve, "triangle": triangle.solve,
    "polygon": polygon.solve, "convex": convex.solve, "cylinder": cylinder.solve_finite,
    "infinite_cylinder": cylinder.solve_infinite, "ellipsoid": ellipsoid.solve,
    "quadric": quadric.solve,
}
#: shape types that use no eps at all (SPEC revision 2)
NO_EPS = frozenset({"triangle", "polygon", "mesh"})


class Undecided(Exception):
    """The contract does not define the answer for this ray (excluded, counted)."""


@dataclass(frozen=True)
class RefHit:
    """One exact crossing of the ray's line with the surface.

    t is a Fraction (exact) or an mpf; ``normal`` the exact unit normal at the
    exact point (world space); ``inside`` whether t lies in [tmin, tmax].
    """
    t: Real
    kind: str                    # "enter" | "exit" | "touch"
    prim: int
    normal: tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]
    inside: bool


@dataclass(frozen=True)
class RefResult:
    """Every crossing of the line (sorted by t, then prim) and those in range."""
    hits: tuple[RefHit, ...]

    @property
    def kept(self) -> tuple[RefHit, ...]:
        return tuple(h for h in self.hits if h.inside)


def to_xray(org: Sequence[float], d: Sequence[float], tmin: float, tmax: float) -> "model.XRay":
    """The exact ray of four doubles (infinite bounds stay floats)."""
    def bound(x: float) -> Fraction | float:
        return x if math.isinf(x) else Fraction(x)
    return model.XRay(exact.qv(org), exact.qv(d), bound(tmin), bound(tmax))


def _mesh_solve(shape: dict, r: "model.XRay", ctx: "model.Ctx") -> list:
    """mesh.solve's union of face hits (prim = face index), skipping faces the
    line provably misses.

    The skip is sound: with w = centre - org of a face's bounding sphere
    (radius R), the line's squared distance |w|^2 - (w.d)^2/|d|^2 is evaluated
    in doubles with an error far below the margin m = 1e-6 (|w| + R), and a
    face is skipped only when that distance exceeds R + m.
    """
    org = [float(x) for x in r.org]
    d = [float(x) for x in r.dir]
    dd = sum(x * x for x in d)
    hits = []
    for i, f in enumerate(shape["faces"]):
        vs = [shape["vertices"][k] for k in f]
        c = [sum(v[k] for v in vs) / len(vs) for k in range(3)]
        rad = max(math.dist(c, v) for v in vs)
        w = [c[k] - org[k] for k in range(3)]
        ww = sum(x * x for x in w)
        wd = sum(a * b for a, b in zip(w, d))
        dist2 = ww - wd * wd / dd
        margin = 1e-6 * (math.sqrt(ww) + rad)
        if dist2 > (rad + margin) ** 2:
            continue
        fs = mesh.face_shape(shape, f)
        solver = triangle.solve if fs["type"] == "triangle" else polygon.solve
        for h in solver(fs, r, ctx):
            h.prim = i
            hits.append(h)
    return hits


def _hits(spec: dict, r: "model.XRay", eps: Fraction) -> list:
    """The golden solver's hits (world space), sorted by t then prim."""
    kind = spec["type"]
    ctx = model.Ctx(eps)
    solver = _mesh_solve if kind == "mesh" else SOLVERS[kind]
    m = spec.get("transform")
    hits = transformed.solve(m, solver, spec, r, ctx) if m is not None else solver(spec, r, ctx)

    def order(a, b) -> int:
        c = exact.cmp(a.t, b.t) if a.t != b.t else 0
        return c if c else (a.prim > b.prim) - (a.prim < b.prim)
    return sorted(hits, key=functools.cmp_to_key(order))


def _decided(spec: dict, r: "model.XRay", eps: Fraction) -> RefResult:
    """Solve deciding exactly, with more digits while mpmath cannot separate values."""
    with exact.deciding_exactly():
        for digits in PRECISIONS:
            try:
                with mpmath.workdps(digits):
                    ctx = model.Ctx(eps)
                    return RefResult(tuple(
                        RefHit(h.t, h.kind, h.prim, tuple(exact.mp(x) for x in h.normal),
                               model.in_range(h.t, r, ctx))
                        for h in _hits(spec, r, eps)))
            except exact.PrecisionError:
                continue
            except exact.DesignError as e:
                raise Undecided(str(e)) from None
    raise Undecided(f"not decided with {PRECISIONS[-1]} digits")


def solve(spec: dict, org: Sequence[float], d: Sequence[float], tmin: float = 0.0,
          tmax: float = math.inf) -> RefResult:
    """Every exact crossing of the ray's line with the shape ``spec`` (golden
    format, with an optional ``transform``: 16 numbers, row-major
    object-to-world), each marked whether it lies in [tmin, tmax]."""
    eps = Fraction(0) if spec["type"] in NO_EPS else EPS
    return _decided(spec, to_xray(org, d, tmin, tmax), eps)


def solve_eps0(spec: dict, org: Sequence[float], d: Sequence[float]) -> RefResult:
    """The same with eps = 0 for every shape: an exactly tangent ray gives one
    TOUCH, a ray off tangency by any amount two hits or none."""
    return _decided(spec, to_xray(org, d, -math.inf, math.inf), Fraction(0))
