# SPDX-License-Identifier: Apache-2.0
"""Cylinders: finite capped/open (isect_ray_cylinder) and infinite (isect_ray_cylinder_inf).

Side (seeds: "orthogonal projection to the plane defined by C, A", and the
closest points of two lines): with axis point p, axis vector a, w = o - p and
the components perpendicular to a,
    v_perp = v - (v.a/|a|^2) a,   w_perp = w - (w.a/|a|^2) a,
the squared distance to the axis along the ray is |w_perp + t v_perp|^2.
Its minimum is at t_m = -(w_perp.v_perp)/|v_perp|^2 and equals h^2, the
squared distance between the ray's line and the axis:
    h^2 = |w_perp|^2 - (w_perp.v_perp)^2 / |v_perp|^2,
so the side is met at  t = t_m -+ sqrt((r^2 - h^2) / |v_perp|^2).
isect.h: parallel to the axis when |v x a| <= eps|v||a| (no side hit; note
|v x a|^2 = |v_perp|^2 |a|^2); TOUCH when |r^2 - h^2| <= eps r^2.
Normal: the outward radial unit vector.

Finite cylinder p0-p1 (a = p1 - p0), axial coordinate s(t) = (x(t)-p0).a/|a|^2:
  open:   side hits with 0 <= s <= 1 (thin surface, outward radial normal);
  capped: the convex solid (infinite solid) n (0 <= s <= 1): cap at p0
          (prim 1, normal -a/|a|) and cap at p1 (prim 2, normal a/|a|),
          entry/exit/ties/TOUCH as for a convex polyhedron (side prim 0);
          the caps are parallel to the ray when |v.a| <= eps|v||a|, and then
          constrain it by the origin's axial coordinate s(0).
r = 0 or p0 == p1 (axis 0) is degenerate.
"""
from __future__ import annotations

from fractions import Fraction
from typing import Sequence

from convex import Cand, select
from exact import (NEAR, DesignError, Real, cross, dot, eps_le, is_zero, mp, norm2, point_on_ray, q, qv,
                   refuse, rel_gap, representable, scale, sqrt, sub, unit)
from model import INF, TIGHT, Ctx, Hit, XRay, case, nudged, opts, ray, surface_case

FAMILY = "cylinder"


class Side:
    """The side of the infinite cylinder around p + s a along one ray."""

    def __init__(self, p, a, rad: Fraction, r: XRay, ctx: Ctx):
        self.p, self.a, self.rad, self.r = p, a, rad, r
        self.a2 = norm2(a)
        w = sub(r.org, p)
        self.w = w
        vp = sub(r.dir, scale(dot(r.dir, a) / self.a2, a))
        wp = sub(w, scale(dot(w, a) / self.a2, a))
        self.wp, self.vp = wp, vp
        A = norm2(vp)
        vxa = norm2(cross(r.dir, a))
        self.parallel = eps_le(vxa, ctx.eps ** 2 * norm2(r.dir) * self.a2, "cylinder axis parallel")
        if self.parallel:
            h2 = norm2(wp)
            if h2 == rad * rad:
                raise DesignError("ray parallel to the axis exactly on the side surface")
            self.inside_parallel = h2 < rad * rad
            self.roots: list[tuple[Real, str]] = []
            return
        tm = -dot(wp, vp) / A
        h2 = norm2(wp) - dot(wp, vp) ** 2 / A
        disc = rad * rad - h2
        if eps_le(abs(disc), ctx.eps * rad * rad, "cylinder tangency"):
            self.roots = [(tm, "touch")]
        elif disc < 0:
            self.roots = []
        else:
            half = sqrt(disc / A)
            self.roots = [(tm - half, "enter"), (tm + half, "exit")]

    def normal(self, t: Real) -> tuple:
        """Outward radial unit vector: the perpendicular part w_perp + t v_perp."""
        return unit(point_on_ray(self.wp, self.vp, t))

    def s(self, t: Real) -> Real:
        """Axial coordinate (0 at p, 1 at p + a)."""
        return (dot(self.w, self.a) + t * dot(self.r.dir, self.a)) / self.a2


def in_unit(s: Real, ctx: Ctx) -> bool:
    """0 <= s <= 1, refusing near-ties (and exact ties the library may not see)."""
    for bound in (Fraction(0), Fraction(1)):
        if s == bound:
            if not (ctx.exact and isinstance(s, Fraction)):
                refuse("hit exactly on a cylinder rim")
            return True
        if rel_gap(s, bound) < NEAR:
            refuse("hit within 1e-12 of a cylinder rim")
    return 0 <= mp(s) <= 1


def _exact(t: Real) -> bool:
    return isinstance(t, Fraction) and representable(t)


def solve_finite(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    p0, p1, rad = qv(shape["p0"]), qv(shape["p1"]), q(shape["radius"])
    a = sub(p1, p0)
    if rad == 0 or is_zero(a):
        return []
    side = Side(p0, a, rad, r, ctx)
    if not shape["capped"]:
        return [Hit(t, side.normal(t), kind, 0) for t, kind in side.roots if in_unit(side.s(t), ctx)]
    # capped: the convex solid
    if side.parallel and not side.inside_parallel:
        return []
    if len(side.roots) == 1:                       # tangent to the side: a touch inside the slab
        tm = side.roots[0][0]
        return [Hit(tm, side.normal(tm), "touch", 0)] if in_unit(side.s(tm), ctx) else []
    if not side.parallel and not side.roots:
        return []
    enter: list[Cand] = []
    exit_: list[Cand] = []
    if side.roots:
        (t1, _), (t2, _) = side.roots
        enter.append(Cand(t1, 0, side.normal(t1), _exact(t1)))
        exit_.append(Cand(t2, 0, side.normal(t2), _exact(t2)))
    va = dot(r.dir, a)
    wa = dot(side.w, a)
    # the caps are parallel to the ray when |v.a| <= eps |v||a| (isect.h): they
    # then constrain it by the origin's axial coordinate
    if va == 0 or eps_le(va * va, ctx.eps ** 2 * norm2(r.dir) * side.a2, "cylinder cap parallel"):
        s0 = wa / side.a2
        if s0 == 0 or s0 == 1:
            if not ctx.exact:
                refuse("ray in a cap plane under an inexact transform")
        if not 0 <= s0 <= 1:
            return []
    else:
        if abs(va) ** 2 <= norm2(r.dir) * side.a2 * Fraction(1, 10**12):
            refuse("ray nearly parallel to the caps")
        n1 = unit(a)
        t_p0, t_p1 = -wa / va, (side.a2 - wa) / va
        c0 = Cand(t_p0, 1, tuple(-x for x in n1), _exact(t_p0))
        c1 = Cand(t_p1, 2, n1, _exact(t_p1))
        if va > 0:
            enter.append(c0)
            exit_.append(c1)
        else:
            enter.append(c1)
            exit_.append(c0)
    return select(enter, exit_, ctx)


def solve_infinite(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    p, a, rad = qv(shape["point"]), qv(shape["axis"]), q(shape["radius"])
    if rad == 0 or is_zero(a):
        return []
    side = Side(p, a, rad, r, ctx)
    return [Hit(t, side.normal(t), kind, 0) for t, kind in side.roots]


def _h2_s(p, a, x) -> tuple[Fraction, Fraction]:
    rel = sub(x, p)
    s = dot(rel, a) / norm2(a)
    return norm2(sub(rel, scale(s, a))), s


def contains_finite(shape: dict, x) -> bool:
    p0, p1, rad = qv(shape["p0"]), qv(shape["p1"]), q(shape["radius"])
    a = sub(p1, p0)
    if rad == 0 or is_zero(a):
        return False
    h2, s = _h2_s(p0, a, x)
    return h2 <= rad * rad and 0 <= s <= 1


def contains_infinite(shape: dict, x) -> bool:
    p, a, rad = qv(shape["point"]), qv(shape["axis"]), q(shape["radius"])
    if rad == 0 or is_zero(a):
        return False
    return _h2_s(p, a, x)[0] <= rad * rad


def cyl(p0: Sequence[float], p1: Sequence[float], r: float, capped: bool | int = True) -> dict:
    return {"type": "cylinder", "p0": [float(x) for x in p0], "p1": [float(x) for x in p1],
            "radius": float(r), "capped": capped}


def icyl(p: Sequence[float], axis: Sequence[float], r: float) -> dict:
    return {"type": "infinite_cylinder", "point": [float(x) for x in p],
            "axis": [float(x) for x in axis], "radius": float(r)}


def cases() -> list[dict]:
    C = cyl((0, 0, 0), (0, 0, 2), 1)
    O = cyl((0, 0, 0), (0, 0, 2), 1, False)
    Inf = icyl((0, 0, 0), (0, 0, 3), 2)
    c = []
    # capped
    c.append(case("capped: across the side", ["basic"], shape=C, ray=ray((-5, 0, 1), (1, 0, 0))))
    c.append(case("capped: along the axis, cap to cap", ["parallel", "cap"], shape=C,
                  ray=ray((0, 0, -1), (0, 0, 1))))
    c.append(case("capped: parallel to the axis, downward, non-unit", ["parallel", "cap", "non-unit-dir"],
                  shape=C, ray=ray((0.5, 0, 5), (0, 0, -2))))
    c.append(case("capped: parallel to the axis outside the radius", ["parallel", "miss"], shape=C,
                  ray=ray((1.5, 0, -1), (0, 0, 1))))
    c.append(case("capped: in through cap p0, out through the side", ["cap"], shape=C,
                  ray=ray((0, 0, -1), (1, 0, 2))))
    c.append(case("capped: in through the side, out through cap p1", ["cap"], shape=C,
                  ray=ray((-2, 0, 1), (2, 0, 1))))
    c.append(case("capped: oblique chord, decimal data", ["basic"], shape=cyl((0.1, 0.2, 0.3), (0.4, -0.5, 2.6), 0.7),
                  ray=ray((-2.0, 0.3, 1.1), (1.0, 0.05, 0.1))))
    c.append(case("capped: exact side tangent", ["tangent"], shape=C, ray=ray((1, -5, 1), (0, 1, 0))))
    c.append(case("capped: side tangent beyond cap p1", ["tangent", "miss"], shape=C,
                  ray=ray((1, -5, 3), (0, 1, 0))))
    c.append(case("capped: near-tangent within eps 1e-6", ["near-tangent", "eps"], shape=C,
                  ray=ray((-5, 1 - 1e-8, 1), (1, 0, 0)), opts=opts(eps=1e-6)))
    c.append(case("capped: near-tangent outside default eps", ["near-tangent"], shape=C,
                  ray=ray((-5, 1 - 1e-8, 1), (1, 0, 0))))
    c.append(case("capped: grazing the rim of cap p1 (touch)", ["graze", "edge", "cap"], shape=C,
                  ray=ray((2, 0, 1), (-1, 0, 1))))
    c.append(case("capped: ray in the plane of cap p1 (closed solid)", ["in-plane", "cap"], shape=C,
                  ray=ray((-5, 0, 2), (1, 0, 0))))
    c.append(case("capped: origin inside", ["inside"], shape=C, ray=ray((0, 0.5, 1), (1, 0, 0))))
    c.append(case("capped: origin on the side, entering", ["on-surface"], shape=C,
                  ray=ray((1, 0, 1), (-1, 0, 0))))
    c.append(case("capped: origin on cap p1, leaving", ["on-surface", "cap"], shape=C,
                  ray=ray((0.5, 0, 2), (0, 0, 1))))
    c.append(case("capped: behind the origin", ["behind", "miss"], shape=C,
                  ray=ray((5, 0, 1), (1, 0, 0))))
    c.append(case("capped: tmax between the hits", ["clip"], shape=C,
                  ray=ray((-5, 0, 1), (1, 0, 0), tmax=5.0)))
    c.append(case("capped: exit exactly at tmax", ["clip-exact"], shape=C,
                  ray=ray((-5, 0, 1), (1, 0, 0), tmax=6.0)))
    c.append(case("capped: oblique axis (1,1,1)-(3,3,3), side hits", ["basic"],
                  shape=cyl((1, 1, 1), (3, 3, 3), 0.5), ray=ray((0, 4, 2), (1, -1, 0))))
    c.append(case("capped: oblique axis, cap to cap along the axis", ["parallel", "cap"],
                  shape=cyl((1, 1, 1), (3, 3, 3), 0.5), ray=ray((0, 0, 0), (1, 1, 1))))
    c.append(case("capped: reversed axis (p1 below p0)", ["cap"], shape=cyl((0, 0, 2), (0, 0, 0), 1),
                  ray=ray((0, 0, -1), (1, 0, 2))))
    # open
    c.append(case("open: across the side", ["open"], shape=O, ray=ray((-5, 0, 1), (1, 0, 0))))
    c.append(case("open: across the side, cull_back keeps the entry", ["open", "cull-back"], shape=O,
                  ray=ray((-5, 0, 1), (1, 0, 0)), opts=opts(flags=["cull_back"])))
    c.append(case("open: from inside", ["open", "inside"], shape=O, ray=ray((0, 0, 1), (1, 0, 0))))
    c.append(case("open: from inside, culled", ["open", "inside", "cull-back"], shape=O,
                  ray=ray((0, 0, 1), (1, 0, 0)), opts=opts(flags=["cull_back"])))
    c.append(case("open: along the axis (no side hit)", ["open", "parallel", "miss"], shape=O,
                  ray=ray((0, 0, -1), (0, 0, 1))))
    c.append(case("open: in through the open end, out through the side", ["open"], shape=O,
                  ray=ray((0, 0, -1), (1, 0, 2))))
    c.append(case("open: through both open ends", ["open", "miss"], shape=O,
                  ray=ray((0.5, 0, -1), (0, 0.1, 1))))
    c.append(case("open: exact tangent", ["open", "tangent"], shape=O, ray=ray((-1, -5, 1), (0, 1, 0))))
    c.append(case("open: tangent below p0", ["open", "tangent", "miss"], shape=O,
                  ray=ray((-1, -5, -0.5), (0, 1, 0))))
    # infinite
    c.append(case("infinite: across", ["basic"], shape=Inf, ray=ray((-5, 0, 100), (1, 0, 0))))
    c.append(case("infinite: oblique ray", ["non-unit-dir"], shape=Inf, ray=ray((-4, 1, -7), (1, 0, 3))))
    c.append(case("infinite: parallel inside (no hits)", ["parallel", "miss"], shape=Inf,
                  ray=ray((1, 1, 0), (0, 0, -1))))
    c.append(case("infinite: parallel outside", ["parallel", "miss"], shape=Inf,
                  ray=ray((3, 0, 0), (0, 0, 1))))
    c.append(case("infinite: exact tangent", ["tangent"], shape=Inf, ray=ray((2, -5, 0), (0, 1, 0))))
    c.append(case("infinite: exact tangent, oblique ray", ["tangent"], shape=Inf,
                  ray=ray((-5, -2, 0), (1, 0, 1))))
    c.append(case("infinite: near-tangent within eps 1e-6", ["near-tangent", "eps"], shape=Inf,
                  ray=ray((-5, 2 - 1e-7, 0), (1, 0, 0)), opts=opts(eps=1e-6)))
    c.append(case("infinite: origin inside", ["inside"], shape=Inf, ray=ray((0, 1, 50), (1, 0, 1))))
    c.append(case("infinite: miss", ["miss"], shape=Inf, ray=ray((-5, 2.5, 0), (1, 0, 0.5))))
    c.append(case("infinite: oblique axis (1,1,0) through (1,0,0)", ["basic"],
                  shape=icyl((1, 0, 0), (1, 1, 0), 1), ray=ray((0, 3, 0.5), (0, -1, 0))))
    c.append(case("infinite: behind, tmin = -inf", ["behind", "negative-t"], shape=Inf,
                  ray=ray((5, 0, 0), (1, 0, 0), tmin=-INF)))
    # contains
    c.append(case("contains: capped, inside", ["contains"], op="contains", shape=C, point=[0.5, 0.5, 1.0]))
    c.append(case("contains: capped, on the rim", ["contains", "boundary"], op="contains", shape=C,
                  point=[0.0, 1.0, 2.0]))
    c.append(case("contains: capped, beyond cap p1", ["contains"], op="contains", shape=C,
                  point=[0.0, 0.0, 2.5]))
    c.append(case("contains: infinite, far along the axis", ["contains"], op="contains", shape=Inf,
                  point=[1.0, -1.0, 1e6]))
    c.append(case("contains: infinite, outside", ["contains"], op="contains", shape=Inf,
                  point=[2.0, 0.5, 0.0]))
    # degenerate
    c.append(case("zero radius is degenerate", ["degenerate", "miss"], shape=cyl((0, 0, 0), (0, 0, 2), 0),
                  ray=ray((-5, 0, 1), (1, 0, 0))))
    c.append(case("zero-length axis is degenerate", ["degenerate", "miss"], shape=cyl((0, 0, 1), (0, 0, 1), 1),
                  ray=ray((-5, 0, 1), (1, 0, 0))))

    # --- revision 2: origins on the surface and within a few ulps of it (tmin = 0)
    # axis p0 = (1, 2, 3), a = (0, 3, 4) (|a| = 5), radius 5
    C5 = cyl((1, 2, 3), (1, 5, 7), 5)
    O5 = cyl((1, 2, 3), (1, 5, 7), 5, False)
    I5 = icyl((1, 2, 3), (0, 3, 4), 5)
    side = (1.0, 7.5, 2.0)                      # p0 + a/2 + (0, 4, -3): on the side, radial (0, 4, -3)/5
    s_in, s_out = (0.5, -1, 0.5), (0.25, 1, -0.5)
    cap = (3.0, 7.0, 5.5)                       # p1 + (2, 2, -1.5): on cap p1, inside its disk
    c_in, c_out = (-0.5, -1, -1), (0.25, 1, 0.5)
    for label, sh, extra in (("capped", C5, []), ("open", O5, ["open"]), ("infinite", I5, [])):
        c.append(surface_case(f"{label}: on the side, inward: t = 0 and the far side", extra, shape=sh,
                              ray=ray(side, s_in)))
        c.append(surface_case(f"{label}: on the side, outward: t = 0 only", extra, shape=sh,
                              ray=ray(side, s_out)))
        c.append(surface_case(f"{label}: 1 ulp outside the side (y), inward", extra, shape=sh,
                              ray=ray(nudged(side, 1, 1), s_in)))
        c.append(surface_case(f"{label}: 1 ulp outside the side (y), outward: no hit", extra + ["miss"],
                              shape=sh, ray=ray(nudged(side, 1, 1), s_out)))
        c.append(surface_case(f"{label}: 2 ulps inside the side (z), outward: t ~ +1e-16", extra, shape=sh,
                              ray=ray(nudged(side, 2, 2), s_out)))
        c.append(surface_case(f"{label}: 3 ulps inside the side (y), inward", extra, shape=sh,
                              ray=ray(nudged(side, 1, -3), s_in)))
    c.append(surface_case("capped: on cap p1, inward: enter at t = 0 (prim 2)", ["cap"], shape=C5,
                          ray=ray(cap, c_in)))
    c.append(surface_case("capped: on cap p1, outward: exit at t = 0 only", ["cap"], shape=C5,
                          ray=ray(cap, c_out)))
    c.append(surface_case("capped: 1 ulp outside cap p1 (z), inward", ["cap"], shape=C5,
                          ray=ray(nudged(cap, 2, 1), c_in)))
    c.append(surface_case("capped: 1 ulp outside cap p1 (z), outward: no hit", ["cap", "miss"], shape=C5,
                          ray=ray(nudged(cap, 2, 1), c_out)))
    c.append(surface_case("capped: 1 ulp inside cap p1 (y), outward: t ~ +1e-16", ["cap"], shape=C5,
                          ray=ray(nudged(cap, 1, -1), c_out)))

    # --- revision 2: grazing rays (line at distance h from the axis), t to about 4 ulp
    # direction (0, 5.5, -1) = (0, 4, -3) + a/2; the line passes at distance h along x from
    # the axis, at axial coordinate 1/2 (t = 3)
    def graze(h: float) -> dict:
        return ray((1 + h, -13, 8), (0, 5.5, -1))
    for label, sh, extra in (("capped", C5, []), ("open", O5, ["open"]), ("infinite", I5, [])):
        c.append(case(f"{label}: grazing the side, h = 5(1 - 2^-30): two close hits", ["grazing",
                      "near-tangent"] + extra, shape=sh, ray=graze(5 - 5 * 2.0 ** -30), tol=TIGHT))
        c.append(case(f"{label}: grazing the side, h = 5(1 + 2^-30): miss", ["grazing", "near-tangent",
                      "miss"] + extra, shape=sh, ray=graze(5 + 5 * 2.0 ** -30)))
        c.append(case(f"{label}: grazing the side, h = 5(1 - 2^-44): touch within eps", ["grazing",
                      "near-tangent"] + extra, shape=sh, ray=graze(5 - 5 * 2.0 ** -44), tol=TIGHT))
        c.append(case(f"{label}: grazing the side, h = 5(1 - 2^-48), eps = 0: two hits", ["grazing",
                      "near-tangent", "eps"] + extra, shape=sh, ray=graze(5 - 5 * 2.0 ** -48),
                      opts=opts(eps=0.0), tol=TIGHT))
    c.append(case("infinite: nearly parallel to the axis (2^-28 of |d|), exit ~1e9 away", ["grazing",
                  "near-parallel", "inside"], shape=I5, ray=ray((2, 3, 2.25), (2.0 ** -28, 3, 4)), tol=TIGHT))
    c.append(case("infinite: the same with eps 1e-6: parallel to the axis, no hit", ["grazing",
                  "near-parallel", "inside", "eps", "miss"], shape=I5, ray=ray((2, 3, 2.25), (2.0 ** -28, 3, 4)),
                  opts=opts(eps=1e-6)))

    # --- revision 2: far and small, t to about 4 ulp (radial normals loose: p - axis cancels)
    far_tol = {"t": 1e-15, "normal": 1e-5}
    fc = cyl((1e7, 0, -1e-3), (1e7, 0, 1e-3), 1e-3)
    c.append(case("far: capped r = 1e-3 at x = 1e7, across the side", ["far", "loose-normal"], shape=fc,
                  ray=ray((0, 3e-4, 2.5e-4), (1, 0, 0)), tol=far_tol))
    c.append(case("far: open r = 1e-3 at x = 1e7, across the side", ["far", "loose-normal", "open"],
                  shape=cyl((1e7, 0, -1e-3), (1e7, 0, 1e-3), 1e-3, False),
                  ray=ray((0, -6e-4, -5e-4), (1, 0, 0)), tol=far_tol))
    c.append(case("far: capped, cap to cap 1e7 along the axis", ["far", "cap"],
                  shape=cyl((0, 0, 1e7), (0, 0, 1e7 + 1e-3), 1e-3),
                  ray=ray((2e-4, -1e-4, 0), (1e-11, 2e-11, 1)), tol=TIGHT))
    c.append(case("far: infinite r = 1e-3 around (6e6, 8e6), oblique", ["far", "loose-normal"],
                  shape=icyl((6e6, 8e6, 0), (0, 0, 1), 1e-3), ray=ray((0, 5e-4, 0), (3, 4, 0.5)), tol=far_tol))
    return c
