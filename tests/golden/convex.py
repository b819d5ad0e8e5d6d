# SPDX-License-Identifier: Apache-2.0
"""Convex polyhedron (isect_ray_convex): reference solver, shared entry/exit logic, cases.

The solid is the intersection of half-spaces n.x + d <= 0 (outward normals).
Seed (Ray-Polyhedron): for each plane with n.v != 0,
    t = -(d + n.o) / (n.v),
an entering candidate when n.v < 0 and an exiting one when n.v > 0;
enterMax = max of entering t, exitMin = min of exiting t (ties: lowest
plane index).  A plane parallel to the ray (|n.v| <= eps|n||v|) constrains it
by the origin's side: n.o + d > 0 means no hit at all (on the plane =
inside).  enterMax > exitMin: miss; enterMax == exitMin: one TOUCH (prim: the
lowest index of the planes involved); else ENTER at enterMax and EXIT at
exitMin, each only if finite (an unbounded solid may lack one).

``select`` is shared with the box and the capped cylinder.
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Callable, Sequence

from exact import NEAR, Real, cmp, dot, qv, refuse, rel_gap, unit
from model import INF, TIGHT, Ctx, Hit, XRay, case, nudged, opts, ray, surface_case
from plane import parallel

FAMILY = "convex"


@dataclass
class Cand:
    t: Real
    prim: int
    normal: Sequence[Real]
    exact_in_double: bool   # the library computes this t exactly (ties carry over)


def float_exact_dot_plus(n: Sequence[Fraction], o: Sequence[Fraction], d: Fraction) -> bool:
    """Is n.o + d computed exactly by doubles (left to right, no FMA needed)?"""
    acc = 0.0
    exact_acc = Fraction(0)
    for a, b in zip(n, o):
        p = float(a) * float(b)
        if Fraction(p) != a * b:
            return False
        acc += p
        exact_acc += a * b
        if Fraction(acc) != exact_acc:
            return False
    acc += float(d)
    return Fraction(acc) == exact_acc + d


def _pick(cands: list[Cand], want_max: bool, ctx: Ctx, what: str) -> Cand | None:
    """The extreme candidate, lowest prim on exact ties; refuses near-ties."""
    if not cands:
        return None
    best = cands[0]
    for c in cands[1:]:
        s = cmp(c.t, best.t)
        if (s > 0) if want_max else (s < 0):
            best = c
        elif s == 0 and c.prim < best.prim:
            best = c
    for c in cands:
        if c is best:
            continue
        if c.t == best.t:
            if not (ctx.exact and c.exact_in_double and best.exact_in_double):
                refuse(f"{what}: exact tie that doubles may not reproduce")
        elif rel_gap(c.t, best.t) < NEAR:
            refuse(f"{what}: near-tie between faces {c.prim} and {best.prim}")
    return best


def select(enter: list[Cand], exit_: list[Cand], ctx: Ctx) -> list[Hit]:
    """enterMax / exitMin of the seeds, with the library's tie and TOUCH rules."""
    e = _pick(enter, True, ctx, "enterMax")
    x = _pick(exit_, False, ctx, "exitMin")
    if e is not None and x is not None:
        if e.t == x.t:
            if not (ctx.exact and e.exact_in_double and x.exact_in_double):
                refuse("entry == exit but doubles may not reproduce the tie")
            first = e if e.prim < x.prim else x
            return [Hit(e.t, first.normal, "touch", first.prim)]
        if rel_gap(e.t, x.t) < NEAR:
            refuse("entry and exit nearly equal")
        if cmp(e.t, x.t) > 0:
            return []
    hits = []
    if e is not None:
        hits.append(Hit(e.t, e.normal, "enter", e.prim))
    if x is not None:
        hits.append(Hit(x.t, x.normal, "exit", x.prim))
    return hits


def clip_planes(planes: Sequence[tuple[Sequence[Fraction], Fraction]], r: XRay, ctx: Ctx,
                is_parallel: Callable[[Sequence[Fraction]], bool]) -> list[Hit]:
    """Candidates of half-spaces n.x + d <= 0 (prim = list index), then ``select``."""
    enter: list[Cand] = []
    exit_: list[Cand] = []
    for prim, (n, d) in enumerate(planes):
        side = dot(n, r.org) + d
        side_exact = ctx.exact and float_exact_dot_plus(n, r.org, d)
        if is_parallel(n):
            if side == 0 and not side_exact:
                refuse("origin exactly on a parallel plane, not exact in doubles")
            if side != 0 and not side_exact:
                mag = sum((abs(a * b) for a, b in zip(n, r.org)), abs(d))
                if abs(side) <= mag * Fraction(1, 10**9):
                    refuse("origin too close to a parallel plane")
            if side > 0:
                return []
            continue
        den = dot(n, r.dir)
        t = -side / den
        exact = side_exact and float_exact_dot_plus(n, r.dir, Fraction(0))
        (enter if den < 0 else exit_).append(Cand(t, prim, unit(n), exact))
    return select(enter, exit_, ctx)


def solve(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    planes = [(qv(p[:3]), qv(p[3:])[0]) for p in shape["planes"]]
    return clip_planes(planes, r, ctx, lambda n: parallel(n, r.dir, ctx.eps, "convex face parallel"))


def contains(shape: dict, p) -> bool:
    return all(dot(qv(pl[:3]), p) + qv(pl[3:])[0] <= 0 for pl in shape["planes"])


def convex(planes) -> dict:
    return {"type": "convex", "planes": [[float(x) for x in p] for p in planes]}


CUBE = convex([(1, 0, 0, -1), (-1, 0, 0, -1), (0, 1, 0, -1), (0, -1, 0, -1), (0, 0, 1, -1),
               (0, 0, -1, -1)])                                   # [-1, 1]^3
TETRA = convex([(-1, 0, 0, 0), (0, -1, 0, 0), (0, 0, -1, 0), (1, 1, 1, -1)])
OCTA = convex([(sx, sy, sz, -1) for sx in (1, -1) for sy in (1, -1) for sz in (1, -1)])


def cases() -> list[dict]:
    c = []
    c.append(case("cube: through the middle along +x", ["basic"], shape=CUBE,
                  ray=ray((-5, 0.25, 0.5), (1, 0, 0))))
    c.append(case("cube: along -z, non-unit direction", ["non-unit-dir"], shape=CUBE,
                  ray=ray((0.5, -0.5, 7), (0, 0, -2))))
    c.append(case("cube: oblique", ["basic"], shape=CUBE,
                  ray=ray((-3, -2, 0.5), (2, 1.5, -0.25))))
    c.append(case("cube: miss, parallel face with origin outside", ["miss", "parallel"], shape=CUBE,
                  ray=ray((-5, 2, 0), (1, 0, 0))))
    c.append(case("cube: miss, oblique", ["miss"], shape=CUBE, ray=ray((-5, 0, 0), (1, 2, 0))))
    c.append(case("cube: ray in the face plane y = 1 (on the plane = inside)", ["parallel", "in-plane"],
                  shape=CUBE, ray=ray((-5, 1, 0.5), (1, 0, 0))))
    c.append(case("cube: ray along the edge y = 1, z = 1", ["parallel", "in-plane", "edge"],
                  shape=CUBE, ray=ray((-5, 1, 1), (1, 0, 0))))
    c.append(case("cube: through edge x = -1, y = -1 (tie: plane 1 before 3)", ["tie", "edge"],
                  shape=CUBE, ray=ray((-2, -2, 0.5), (1, 1, 0))))
    c.append(case("cube: through two corners (ties on entry and exit)", ["tie", "vertex"], shape=CUBE,
                  ray=ray((-3, -3, -3), (1, 1, 1))))
    c.append(case("cube: grazing the edge x = 1, y = 1 (touch)", ["graze", "edge"], shape=CUBE,
                  ray=ray((0, 2, 0.5), (1, -1, 0))))
    c.append(case("cube: grazing the corner (1,1,1) (touch)", ["graze", "vertex"], shape=CUBE,
                  ray=ray((0, 2, 2), (1, -1, -1))))
    c.append(case("cube: origin inside", ["inside"], shape=CUBE, ray=ray((0.5, 0, 0), (0, 1, 0))))
    c.append(case("cube: origin inside, tmin = -inf", ["inside", "negative-t"], shape=CUBE,
                  ray=ray((0.5, 0, 0), (0, 1, 0), tmin=-INF)))
    c.append(case("cube: origin on a face, entering", ["on-surface"], shape=CUBE,
                  ray=ray((-1, 0.5, 0.5), (1, 0, 0))))
    c.append(case("cube: origin on a face, leaving", ["on-surface"], shape=CUBE,
                  ray=ray((-1, 0.5, 0.5), (-1, 0, 0))))
    c.append(case("cube: behind the origin", ["behind", "miss"], shape=CUBE,
                  ray=ray((5, 0, 0), (1, 0, 0))))
    c.append(case("cube: exit exactly at tmax", ["clip-exact"], shape=CUBE,
                  ray=ray((-5, 0, 0), (1, 0, 0), tmax=6.0)))
    c.append(case("cube: tmax between entry and exit", ["clip"], shape=CUBE,
                  ray=ray((-5, 0, 0), (1, 0, 0), tmax=5.0)))
    c.append(case("cube: near-parallel face, default eps (exits through it)", ["near-parallel"], shape=CUBE,
                  ray=ray((-5, 0.9999995, 0), (1, 1e-7, 0))))
    c.append(case("cube: near-parallel face, eps 1e-5 (face parallel, origin inside it)",
                  ["near-parallel", "eps"], shape=CUBE, ray=ray((-5, 0.9999995, 0), (1, 1e-7, 0)),
                  opts=opts(eps=1e-5)))
    c.append(case("non-unit plane normals (2x the cube)", ["basic"],
                  shape=convex([(2, 0, 0, -2), (-3, 0, 0, -3), (0, 0.5, 0, -0.5), (0, -4, 0, -4),
                                (0, 0, 8, -8), (0, 0, -0.25, -0.25)]),
                  ray=ray((0.25, 0.5, -9), (0.0625, 0, 1))))
    c.append(case("tetrahedron: through the slanted face", ["basic"], shape=TETRA,
                  ray=ray((1, 1, 1), (-1, -1.5, -2))))
    c.append(case("tetrahedron: from below through z = 0", ["basic"], shape=TETRA,
                  ray=ray((0.2, 0.3, -1), (0, 0, 1))))
    c.append(case("tetrahedron: grazing the edge x = 0, y + z = 1 (touch)", ["graze", "edge"],
                  shape=TETRA, ray=ray((-1, 0.25, 0.75), (1, 0.25, -0.25))))
    c.append(case("octahedron: crossing through the vertex (1,0,0)", ["tie", "vertex"], shape=OCTA,
                  ray=ray((2, -0.25, -0.25), (-1, 0.25, 0.25))))
    c.append(case("octahedron: grazing the vertex (1,0,0) (touch)", ["graze", "vertex"], shape=OCTA,
                  ray=ray((0, -1, -1), (1, 1, 1))))
    c.append(case("half-space z <= 0 from above: enter only", ["unbounded"],
                  shape=convex([(0, 0, 1, 0)]), ray=ray((1, 2, 3), (0, 0.5, -1))))
    c.append(case("half-space z <= 0 from below: exit only", ["unbounded", "inside"],
                  shape=convex([(0, 0, 1, 0)]), ray=ray((1, 2, -3), (0.5, 0, 1))))
    c.append(case("half-space, origin inside moving away", ["unbounded", "inside", "miss"],
                  shape=convex([(0, 0, 1, 0)]), ray=ray((1, 2, -3), (0, 0, -1))))
    c.append(case("slab |x| <= 1 crossed obliquely", ["unbounded"],
                  shape=convex([(1, 0, 0, -1), (-1, 0, 0, -1)]), ray=ray((-3, 0, 0), (1, 5, -7))))
    c.append(case("slab, ray parallel inside: no hits", ["unbounded", "parallel", "miss"],
                  shape=convex([(1, 0, 0, -1), (-1, 0, 0, -1)]), ray=ray((0, 0, 0), (0, 1, 0))))
    c.append(case("empty polyhedron x >= 1 and x <= -1", ["miss"],
                  shape=convex([(-1, 0, 0, 1), (1, 0, 0, 1)]), ray=ray((-5, 0, 0), (1, 0, 0))))
    c.append(case("contains: inside the tetrahedron", ["contains"], op="contains", shape=TETRA,
                  point=[0.25, 0.25, 0.25]))
    c.append(case("contains: on the slanted face", ["contains", "boundary"], op="contains",
                  shape=TETRA, point=[0.5, 0.25, 0.25]))
    c.append(case("contains: outside the cube", ["contains"], op="contains", shape=CUBE,
                  point=[1.0, 1.5, 0.0]))

    # --- revision 2: origins on the slanted face of the tetrahedron and near it (tmin = 0)
    on = (0.25, 0.25, 0.5)                       # on x + y + z = 1 (plane 3)
    into, out = (-1, -2, -3), (0.5, 1, 1.5)
    c.append(surface_case("tetrahedron: on the slanted face, inward: enter at t = 0", [], shape=TETRA,
                          ray=ray(on, into)))
    c.append(surface_case("tetrahedron: on the slanted face, outward: exit at t = 0 only", [], shape=TETRA,
                          ray=ray(on, out)))
    c.append(surface_case("tetrahedron: 1 ulp outside (z), inward", [], shape=TETRA,
                          ray=ray(nudged(on, 2, 1), into)))
    c.append(surface_case("tetrahedron: 1 ulp outside (z), outward: no hit", ["miss"], shape=TETRA,
                          ray=ray(nudged(on, 2, 1), out)))
    c.append(surface_case("tetrahedron: 1 ulp inside (x), outward: exit at t ~ +1e-16", [], shape=TETRA,
                          ray=ray(nudged(on, 0, -1), out)))
    c.append(surface_case("tetrahedron: 3 ulps inside (y), inward: exit only", [], shape=TETRA,
                          ray=ray(nudged(on, 1, -3), into)))
    c.append(surface_case("cube: 2 ulps outside face -x, inward", [], shape=CUBE,
                          ray=ray(nudged((-1.0, 0.375, 0.25), 0, -2), (1, 0.125, -0.0625))))

    # --- revision 2: grazing (a face nearly parallel, outside eps), t to about 4 ulp
    c.append(case("cube: grazing into face +y at slope 2^-30", ["grazing", "near-parallel"], shape=CUBE,
                  ray=ray((-0.75, 1 + 2.0 ** -32, 0.3), (1, -(2.0 ** -30), 0.0625)), tol=TIGHT))
    c.append(case("tetrahedron: grazing, 2^-30 inside the slanted face, out through it", ["grazing",
                  "near-parallel", "inside"], shape=TETRA,
                  ray=ray((0.25, 0.25, 0.5 - 2.0 ** -30), (1, -1, 2.0 ** -27)), tol=TIGHT))
    c.append(case("tetrahedron: the same with eps 1e-6: the face counts as parallel, out through y = 0",
                  ["grazing", "near-parallel", "inside", "eps"], shape=TETRA,
                  ray=ray((0.25, 0.25, 0.5 - 2.0 ** -30), (1, -1, 2.0 ** -27)), opts=opts(eps=1e-6), tol=TIGHT))

    # --- revision 2: far and small, t to about 4 ulp
    far_box = convex([(1, 0, 0, -(1e7 + 1e-3)), (-1, 0, 0, 1e7), (0, 1, 0, -5e-4), (0, -1, 0, -5e-4),
                      (0, 0, 1, -5e-4), (0, 0, -1, -5e-4)])
    c.append(case("far: a 1e-3 cube at x = 1e7, oblique ray from the origin", ["far"], shape=far_box,
                  ray=ray((0, 1e-4, -2e-4), (1, 2e-11, 1e-11)), tol=TIGHT))
    far_tetra = convex([(-1, 0, 0, 6e6), (0, -1, 0, 8e6), (0, 0, -1, 0), (1, 1, 1, -(14e6 + 1e-3))])
    c.append(case("far: a 1e-3 tetrahedron at (6e6, 8e6, 0), through its slanted face", ["far"],
                  shape=far_tetra, ray=ray((0, 4e-4, 2e-4), (3, 4, 0)), tol=TIGHT))
    return c
