# SPDX-License-Identifier: Apache-2.0
"""Sphere |x - c| = r (isect_ray_sphere): reference solver and cases.

With f = c - o and the ray x = o + t v (seeds: A = v.v, B = -2 f.v,
C = f.f - r^2), the closest approach to c is at the midpoint
    t_m = f.v / |v|^2,
at squared distance  h^2 = |f|^2 - (f.v)^2 / |v|^2  (exact rationals), and
    t = t_m -+ sqrt((r^2 - h^2) / |v|^2).
isect.h: TOUCH (one hit at t_m) when |r^2 - h^2| <= eps r^2; else no hit
when h > r.  Normal: outward unit(x - c).  r = 0 is degenerate.
"""
from __future__ import annotations


from exact import dot, eps_le, norm2, point_on_ray, q, qv, sqrt, sub, unit
from model import INF, TIGHT, Ctx, Hit, XRay, case, nudged, opts, ray, surface_case

FAMILY = "sphere"


def solve(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    c, rad = qv(shape["center"]), q(shape["radius"])
    if rad == 0:
        return []
    f = sub(c, r.org)
    vv = norm2(r.dir)
    fv = dot(f, r.dir)
    tm = fv / vv
    h2 = norm2(f) - fv * fv / vv
    disc = rad * rad - h2                           # r^2 - h^2
    oc = sub(r.org, c)                              # x(t) - c = (o - c) + t v

    def normal(t) -> tuple:
        return unit(point_on_ray(oc, r.dir, t))
    if eps_le(abs(disc), ctx.eps * rad * rad, "sphere tangency"):
        return [Hit(tm, normal(tm), "touch")]
    if disc < 0:
        return []
    half = sqrt(disc / vv)
    return [Hit(tm - half, normal(tm - half), "enter"), Hit(tm + half, normal(tm + half), "exit")]


def contains(shape: dict, p) -> bool:
    """Closed ball: |p - c|^2 - r^2 <= 0 (degenerate r = 0 contains nothing)."""
    c, rad = qv(shape["center"]), q(shape["radius"])
    return rad > 0 and norm2(sub(p, c)) - rad * rad <= 0


def sphere(c, r) -> dict:
    return {"type": "sphere", "center": [float(x) for x in c], "radius": float(r)}


FAR_TOL = {"t": 4e-16}
FAR_TOL_LOOSE_N = {"t": 4e-16, "normal": 1e-5}


def cases() -> list[dict]:
    unit_s = sphere((0, 0, 0), 1)
    c = []
    c.append(case("straight through the centre", ["basic"], shape=unit_s,
                  ray=ray((0, 0, -5), (0, 0, 1))))
    c.append(case("off-centre chord", ["basic"], shape=sphere((1, 2, 3), 2),
                  ray=ray((-4, 2.5, 3.5), (1, 0, 0))))
    c.append(case("oblique ray, non-unit direction", ["non-unit-dir"], shape=sphere((1, -2, 0.5), 1.5),
                  ray=ray((-3, 1, 2), (2.5, -1.75, -0.5))))
    c.append(case("decimal data", ["basic"], shape=sphere((0.1, 0.2, 0.3), 0.7),
                  ray=ray((-1.1, 0.9, 0.05), (0.3, -0.2, 0.1))))
    c.append(case("miss beside the sphere", ["miss"], shape=unit_s, ray=ray((2, 0, -5), (0, 0, 1))))
    c.append(case("sphere behind the origin", ["behind", "miss"], shape=unit_s,
                  ray=ray((0, 0, 5), (0, 0, 1))))
    c.append(case("sphere behind, tmin = -inf", ["behind", "negative-t"], shape=unit_s,
                  ray=ray((0, 0, 5), (0, 0, 1), tmin=-INF)))
    c.append(case("origin at the centre", ["inside"], shape=unit_s, ray=ray((0, 0, 0), (0, 1, 0))))
    c.append(case("origin inside, off centre", ["inside"], shape=unit_s,
                  ray=ray((0.25, 0.5, 0), (1, 0, 0))))
    c.append(case("origin on the surface, entering", ["on-surface"], shape=unit_s,
                  ray=ray((0, 0, -1), (0, 0, 1))))
    c.append(case("origin on the surface, leaving", ["on-surface"], shape=unit_s,
                  ray=ray((0, 0, 1), (0, 0, 1))))
    c.append(case("exact tangent", ["tangent"], shape=unit_s, ray=ray((1, 0, -5), (0, 0, 1))))
    c.append(case("exact tangent with eps = 0", ["tangent", "eps"], shape=unit_s,
                  ray=ray((0, -1, -5), (0, 0, 2)), opts=opts(eps=0.0)))
    c.append(case("oblique exact tangent (3,4,0) at radius 5", ["tangent"], shape=sphere((0, 0, 0), 5),
                  ray=ray((-4, 3, 7), (0, 0, -1))))
    c.append(case("tangent behind the origin", ["tangent", "behind", "miss"], shape=unit_s,
                  ray=ray((1, 0, 5), (0, 0, 1))))
    c.append(case("h = 1 - 2^-45: within eps, touch", ["near-tangent"], shape=unit_s,
                  ray=ray((1 - 2.0**-45, 0, -5), (0, 0, 1))))
    c.append(case("h = 1 + 2^-44: within eps, touch", ["near-tangent"], shape=unit_s,
                  ray=ray((1 + 2.0**-44, 0, -5), (0, 0, 1))))
    c.append(case("h = 1 + 2^-44 with eps = 0: miss", ["near-tangent", "eps", "miss"], shape=unit_s,
                  ray=ray((1 + 2.0**-44, 0, -5), (0, 0, 1)), opts=opts(eps=0.0)))
    c.append(case("h = 1 - 2^-45 with eps = 0: two hits", ["near-tangent", "eps"], shape=unit_s,
                  ray=ray((1 - 2.0**-45, 0, -5), (0, 0, 1)), opts=opts(eps=0.0)))
    c.append(case("h = 1 - 2^-30: outside eps, two close hits", ["near-tangent"], shape=unit_s,
                  ray=ray((1 - 2.0**-30, 0, -5), (0, 0, 1))))
    c.append(case("h = 1 - 1e-5 with eps = 1e-3: touch (point may be snapped)", ["near-tangent", "eps",
                  "touch-snap"], shape=unit_s, ray=ray((0, 1 - 1e-5, -5), (0, 0, 1)), opts=opts(eps=1e-3),
                  tol={"point": 1e-4}))
    c.append(case("tmin between the hits: exit only", ["clip"], shape=unit_s,
                  ray=ray((0, 0, -5), (0, 0, 1), tmin=5.0)))
    c.append(case("tmax between the hits", ["clip"], shape=unit_s,
                  ray=ray((0, 0, -5), (0, 0, 1), tmax=5.0)))
    c.append(case("entry exactly at tmax", ["clip-exact"], shape=unit_s,
                  ray=ray((0, 0, -5), (0, 0, 1), tmax=4.0)))
    c.append(case("exit exactly at tmin", ["clip-exact"], shape=unit_s,
                  ray=ray((0, 0, -5), (0, 0, 1), tmin=6.0)))
    c.append(case("tmin > tmax", ["empty-interval", "miss"], shape=unit_s,
                  ray=ray((0, 0, -5), (0, 0, 1), tmin=6.0, tmax=4.0)))
    c.append(case("far: r = 1e-3 at distance 1e7 on the x axis", ["far"],
                  shape=sphere((1e7, 0, 0), 1e-3), ray=ray((0, 0, 0), (1, 0, 0)), tol=FAR_TOL))
    c.append(case("far: off-centre by 5e-4 (loose normal: p - c cancels)", ["far", "loose-normal"],
                  shape=sphere((1e7, 0, 0), 1e-3), ray=ray((0, 5e-4, 0), (1, 0, 0)),
                  tol=FAR_TOL_LOOSE_N))
    c.append(case("far: direction (3,4,0), centre 1e7 away (loose normal)", ["far", "non-unit-dir",
                  "loose-normal"], shape=sphere((6e6, 8e6, 0), 1e-3), ray=ray((0, 0, 0), (3, 4, 0)),
                  tol=FAR_TOL_LOOSE_N))
    c.append(case("far: oblique direction (5,6,7), off-centre (loose normal)", ["far", "non-unit-dir",
                  "loose-normal"], shape=sphere((5e6, 6e6, 7e6), 1e-3),
                  ray=ray((0, 3e-4, 0), (5, 6, 7)), tol=FAR_TOL_LOOSE_N))
    c.append(case("far: unit direction toward (1,1,1)/sqrt3 (loose normal)", ["far", "loose-normal"],
                  shape=sphere((5773502.691896258, 5773502.691896258, 5773502.691896258), 1e-3),
                  ray=ray((0, 0, 0), (0.5773502691896258, 0.5773502691896258, 0.5773502691896258)),
                  tol=FAR_TOL_LOOSE_N))
    c.append(case("tiny sphere r = 1e-100 near the origin", ["basic"],
                  shape=sphere((0, 0, 3e-100), 1e-100), ray=ray((0, 0, 0), (0, 0, 1))))
    c.append(case("zero radius is degenerate", ["degenerate", "miss"], shape=sphere((0, 0, 0), 0),
                  ray=ray((0, 0, -5), (0, 0, 1))))
    c.append(case("contains: interior point", ["contains"], op="contains", shape=unit_s,
                  point=[0.5, -0.25, 0.125]))
    c.append(case("contains: boundary point", ["contains", "boundary"], op="contains", shape=unit_s,
                  point=[0.0, 0.0, -1.0]))
    c.append(case("contains: outside point", ["contains"], op="contains", shape=unit_s,
                  point=[0.75, 0.75, 0.0]))

    # --- revision 2: origins on the surface and within a few ulps of it (tmin = 0)
    s5 = sphere((1, 2, 3), 5)
    on = (4.0, 6.0, 3.0)                        # c + (3, 4, 0): exactly on it
    into, out = (-1, -2, 0.5), (1, 1, -0.25)    # d.n < 0 / > 0 at that point
    c.append(surface_case("on the surface, inward: enter at t = 0, exit", [], shape=s5, ray=ray(on, into)))
    c.append(surface_case("on the surface, outward: exit at t = 0 only", [], shape=s5, ray=ray(on, out)))
    c.append(surface_case("1 ulp outside (x), inward: enter at t ~ +1e-16", [], shape=s5,
                          ray=ray(nudged(on, 0, 1), into)))
    c.append(surface_case("1 ulp outside (x), outward: both crossings behind", ["miss"], shape=s5,
                          ray=ray(nudged(on, 0, 1), out)))
    c.append(surface_case("1 ulp inside (x), outward: exit at t ~ +1e-16", [], shape=s5,
                          ray=ray(nudged(on, 0, -1), out)))
    c.append(surface_case("2 ulps inside (x), inward: entry behind, exit only", [], shape=s5,
                          ray=ray(nudged(on, 0, -2), into)))
    c.append(surface_case("3 ulps outside (y), outward: no hit", ["miss"], shape=s5,
                          ray=ray(nudged(on, 1, 3), out)))
    c.append(surface_case("3 ulps inside (y), outward, non-unit direction", ["non-unit-dir"], shape=s5,
                          ray=ray(nudged(on, 1, -3), (7, 3, -5))))

    # --- revision 2: grazing rays (line at distance h from the centre), t to about 4 ulp
    # direction (1, 2, 2) and offset direction (2, 1, -2)/3, both exact and orthogonal
    def graze(h: float, d0: float = 10) -> dict:
        foot = [1 + h * 2 / 3, 2 + h / 3, 3 - h * 2 / 3]
        return ray([x - d0 * v for x, v in zip(foot, (1, 2, 2))], (1, 2, 2))
    c.append(case("grazing: h = 5(1 - 2^-30), two close hits", ["grazing", "near-tangent"], shape=s5,
                  ray=graze(5 * (1 - 2.0 ** -30)), tol=TIGHT))
    c.append(case("grazing: h = 5(1 + 2^-30), miss", ["grazing", "near-tangent", "miss"], shape=s5,
                  ray=graze(5 * (1 + 2.0 ** -30))))
    c.append(case("grazing: h = 5(1 - 2^-44), within eps: touch", ["grazing", "near-tangent"], shape=s5,
                  ray=graze(5 * (1 - 2.0 ** -44)), tol=TIGHT))
    c.append(case("grazing: h = 5(1 - 2^-48) with eps = 0: two hits ~3e-7 apart", ["grazing", "near-tangent",
                  "eps"], shape=s5, ray=graze(5 * (1 - 2.0 ** -48)), opts=opts(eps=0.0), tol=TIGHT))
    c.append(case("grazing: h = 5(1 + 2^-48) with eps = 0: miss", ["grazing", "near-tangent", "eps", "miss"],
                  shape=s5, ray=graze(5 * (1 + 2.0 ** -48)), opts=opts(eps=0.0)))
    c.append(case("grazing, far: r = 1e-3 at 1e7, h = r(1 - 2^-12) (loose normal)", ["grazing", "far",
                  "loose-normal"], shape=sphere((1e7, 0, 0), 1e-3),
                  ray=ray((0, 1e-3 * (1 - 2.0 ** -12), 0), (1, 0, 0)), tol=FAR_TOL_LOOSE_N))
    return c
