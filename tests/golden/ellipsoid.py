# SPDX-License-Identifier: Apache-2.0
"""Axis-aligned ellipsoid sum(((x - c)/R)^2) = 1 (isect_ray_ellipsoid): solver and cases.

Seed (Ray-Ellipsoid, (x/a)^2 + (y/b)^2 + (z/c)^2 = 1): in the scaled frame
x' = (x - c)/R the ellipsoid is the unit sphere and the ray is
o' = (o - c)/R, v' = v/R with the *same* t.  As for the sphere (centre 0):
    t_m = -(o'.v')/|v'|^2,   h'^2 = |o'|^2 - (o'.v')^2/|v'|^2,
    t = t_m -+ sqrt((1 - h'^2)/|v'|^2);
isect.h: TOUCH when |1 - h'^2| <= eps.  Normal: unit((x - c)/R^2), the
gradient direction.  A zero semi-axis is degenerate.
"""
from __future__ import annotations


from exact import dot, eps_le, norm2, point_on_ray, qv, sqrt, unit
from model import INF, TIGHT, Ctx, Hit, XRay, case, nudged, opts, ray, surface_case

FAMILY = "ellipsoid"


def solve(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    c, R = qv(shape["center"]), qv(shape["radii"])
    if any(x == 0 for x in R):
        return []
    o = tuple((a - b) / s for a, b, s in zip(r.org, c, R))
    v = tuple(a / s for a, s in zip(r.dir, R))
    vv, ov = norm2(v), dot(o, v)
    tm = -ov / vv
    disc = 1 - (norm2(o) - ov * ov / vv)           # 1 - h'^2

    # grad/2 = (x(t) - c)/R^2 = (o - c)/R^2 + t v/R^2
    g0 = tuple((a - b) / (s * s) for a, b, s in zip(r.org, c, R))
    g1 = tuple(a / (s * s) for a, s in zip(r.dir, R))

    def normal(t) -> tuple:
        return unit(point_on_ray(g0, g1, t))
    if eps_le(abs(disc), ctx.eps, "ellipsoid tangency"):
        return [Hit(tm, normal(tm), "touch")]
    if disc < 0:
        return []
    half = sqrt(disc / vv)
    return [Hit(tm - half, normal(tm - half), "enter"), Hit(tm + half, normal(tm + half), "exit")]


def contains(shape: dict, p) -> bool:
    c, R = qv(shape["center"]), qv(shape["radii"])
    if any(x == 0 for x in R):
        return False
    return sum(((a - b) / s) ** 2 for a, b, s in zip(p, c, R)) <= 1


def ell(c, radii) -> dict:
    return {"type": "ellipsoid", "center": [float(x) for x in c], "radii": [float(x) for x in radii]}


def cases() -> list[dict]:
    E = ell((1, 2, 3), (2, 1, 0.5))
    c = []
    c.append(case("along x through the centre", ["basic"], shape=E, ray=ray((-5, 2, 3), (1, 0, 0))))
    c.append(case("along -z through the centre", ["basic"], shape=E, ray=ray((1, 2, 10), (0, 0, -1))))
    c.append(case("oblique, non-unit direction", ["non-unit-dir"], shape=E,
                  ray=ray((-2, 0, 1), (1.5, 1, 1))))
    c.append(case("decimal data", ["basic"], shape=ell((0.1, 0.2, 0.3), (0.7, 1.3, 0.4)),
                  ray=ray((-1.0, 0.5, 0.35), (1.0, -0.1, 0.02))))
    c.append(case("miss", ["miss"], shape=E, ray=ray((-5, 3.5, 3), (1, 0, 0))))
    c.append(case("exact tangent at x = c.x + 2", ["tangent"], shape=E, ray=ray((3, 2, -5), (0, 0, 1))))
    c.append(case("exact tangent, oblique (scaled frame (1,0,1))", ["tangent", "non-unit-dir"], shape=E,
                  ray=ray((-1, 3, 2.5), (2, 0, 0.5))))
    c.append(case("exact tangent with eps = 0", ["tangent", "eps"], shape=E,
                  ray=ray((-4, 2, 3.5), (1, 0, 0)), opts=opts(eps=0.0)))
    c.append(case("near-tangent: h' = 1 - 1e-5, eps 1e-3 (touch; point may be snapped)",
                  ["near-tangent", "eps", "touch-snap"], shape=E, ray=ray((3 - 2e-5, 2, -5), (0, 0, 1)),
                  opts=opts(eps=1e-3), tol={"point": 1e-4}))
    c.append(case("near-tangent: h' = 1 - 1e-5, default eps (two hits)", ["near-tangent"], shape=E,
                  ray=ray((3 - 2e-5, 2, -5), (0, 0, 1))))
    c.append(case("origin at the centre", ["inside"], shape=E, ray=ray((1, 2, 3), (0, 1, 0))))
    c.append(case("origin on the surface, entering", ["on-surface"], shape=E, ray=ray((1, 2, 2.5), (0, 0, 1))))
    c.append(case("behind the origin", ["behind", "miss"], shape=E, ray=ray((1, 2, 10), (0, 0, 1))))
    c.append(case("behind, tmin = -inf", ["behind", "negative-t"], shape=E,
                  ray=ray((1, 2, 10), (0, 0, 1), tmin=-INF)))
    c.append(case("tmin between the hits", ["clip"], shape=E, ray=ray((-5, 2, 3), (1, 0, 0), tmin=5.0)))
    c.append(case("exit exactly at tmax", ["clip-exact"], shape=E, ray=ray((-5, 2, 3), (1, 0, 0), tmax=8.0)))
    c.append(case("equal radii: a sphere", ["basic"], shape=ell((0, 0, 0), (2, 2, 2)),
                  ray=ray((-3, 1, 0), (1, 0, 0))))
    c.append(case("very flat ellipsoid (1e-6 thick)", ["basic"], shape=ell((0, 0, 0), (1, 1, 1e-6)),
                  ray=ray((0.5, 0.25, 1), (0, 0, -1))))
    c.append(case("far: semi-axes ~1e-3 at x = 1e7 (t at default tol: no promise beyond spheres)",
                  ["far", "loose-normal"],
                  shape=ell((1e7, 0, 0), (1e-3, 2e-3, 5e-4)), ray=ray((0, 1e-3, 0), (1, 0, 0)),
                  tol={"normal": 1e-5}))
    c.append(case("zero semi-axis is degenerate", ["degenerate", "miss"], shape=ell((0, 0, 0), (1, 0, 1)),
                  ray=ray((0, 0, -5), (0, 0, 1))))
    c.append(case("contains: inside", ["contains"], op="contains", shape=E, point=[2.0, 2.5, 3.25]))
    c.append(case("contains: on the surface", ["contains", "boundary"], op="contains", shape=E,
                  point=[1.0, 3.0, 3.0]))
    c.append(case("contains: outside", ["contains"], op="contains", shape=E, point=[2.5, 2.75, 3.0]))

    # --- revision 2: origins on the surface and within a few ulps of it (tmin = 0)
    E3 = ell((1, 2, 3), (3, 6, 1.5))
    on = (3.0, 4.0, 4.0)                       # c + (2, 2, 1): (2/3)^2 + (1/3)^2 + (2/3)^2 = 1
    into, out = (-1, -1, -1), (1, 0.5, 1)
    c.append(surface_case("on the surface, inward: enter at t = 0, exit", [], shape=E3, ray=ray(on, into)))
    c.append(surface_case("on the surface, outward: exit at t = 0 only", [], shape=E3, ray=ray(on, out)))
    c.append(surface_case("1 ulp outside (x), inward", [], shape=E3, ray=ray(nudged(on, 0, 1), into)))
    c.append(surface_case("1 ulp outside (x), outward: no hit", ["miss"], shape=E3,
                          ray=ray(nudged(on, 0, 1), out)))
    c.append(surface_case("1 ulp inside (z), outward: t ~ +1e-16", [], shape=E3,
                          ray=ray(nudged(on, 2, -1), out)))
    c.append(surface_case("3 ulps inside (y), inward: exit only", [], shape=E3,
                          ray=ray(nudged(on, 1, -3), into)))
    c.append(surface_case("2 ulps outside (z), inward, non-unit direction", ["non-unit-dir"], shape=E3,
                          ray=ray(nudged(on, 2, 2), (-3, 0.5, -7))))

    # --- revision 2: grazing at the x extreme c + (3, 0, 0): in the scaled frame the line
    # x' = h' through y' = z' = 0 (at t = 2), t to about 4 ulp
    def graze(hx: float) -> dict:
        return ray((1 + 3 * hx, 2 - 12, 3 - 3), (0, 6, 1.5))
    c.append(case("grazing: h' = 1 - 2^-30, two close hits", ["grazing", "near-tangent"], shape=E3,
                  ray=graze(1 - 2.0 ** -30), tol=TIGHT))
    c.append(case("grazing: h' = 1 + 2^-30, miss", ["grazing", "near-tangent", "miss"], shape=E3,
                  ray=graze(1 + 2.0 ** -30)))
    c.append(case("grazing: h' = 1 - 2^-44, touch within eps", ["grazing", "near-tangent"], shape=E3,
                  ray=graze(1 - 2.0 ** -44), tol=TIGHT))
    c.append(case("grazing: h' = 1 - 2^-48, eps = 0: two hits", ["grazing", "near-tangent", "eps"], shape=E3,
                  ray=graze(1 - 2.0 ** -48), opts=opts(eps=0.0), tol=TIGHT))
    return c
