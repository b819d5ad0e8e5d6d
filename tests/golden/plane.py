# SPDX-License-Identifier: Apache-2.0
"""Plane n.x + d = 0 (isect_ray_plane): reference solver and cases.

Along the ray x = o + t v:  n.o + t (n.v) + d = 0, so
    t = -(d + n.o) / (n.v)                         (seed: Ray-Plane)
unless the ray is parallel: |n.v| <= eps |n| |v|, tested exactly as
(n.v)^2 <= eps^2 |n|^2 |v|^2.  Thin surface: normal n/|n|, ENTER when v.n < 0.
n = 0 is degenerate (never hit).
"""
from __future__ import annotations

from exact import dot, eps_le, is_zero, norm2, q, qv, unit
from model import INF, TIGHT, Ctx, Hit, XRay, case, nudged, opts, ray, surface_case

FAMILY = "plane"


def parallel(n, v, eps, what: str = "parallel test") -> bool:
    """|n.v| <= eps |n| |v|, squared so it is exact."""
    nv = dot(n, v)
    return eps_le(nv * nv, eps * eps * norm2(n) * norm2(v), what)


def solve(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    n, d = qv(shape["normal"]), q(shape["d"])
    if is_zero(n) or parallel(n, r.dir, ctx.eps):
        return []
    nv = dot(n, r.dir)
    t = -(d + dot(n, r.org)) / nv
    return [Hit(t, unit(n), "enter" if nv < 0 else "exit")]


def plane(n, d) -> dict:
    return {"type": "plane", "normal": [float(x) for x in n], "d": float(d)}


def cases() -> list[dict]:
    z1 = plane((0, 0, 1), -1)                 # the plane z = 1, normal +z
    c = []
    c.append(case("front side, straight down", ["basic"], shape=z1, ray=ray((0, 0, 5), (0, 0, -1))))
    c.append(case("back side, straight up", ["basic"], shape=z1, ray=ray((0, 0, -3), (0, 0, 1))))
    c.append(case("back side culled", ["cull-back"], shape=z1, ray=ray((0, 0, -3), (0, 0, 1)),
                  opts=opts(flags=["cull_back"])))
    c.append(case("front side kept with cull_back", ["cull-back"], shape=z1,
                  ray=ray((0, 0, 5), (0, 0, -1)), opts=opts(flags=["cull_back"])))
    c.append(case("oblique ray, non-unit direction", ["non-unit-dir"], shape=z1,
                  ray=ray((1, 2, 7), (0.5, -0.25, -3))))
    c.append(case("plane behind the origin", ["behind", "miss"], shape=z1,
                  ray=ray((0, 0, 5), (0, 0, 1))))
    c.append(case("plane behind, tmin = -inf", ["behind", "negative-t"], shape=z1,
                  ray=ray((0, 0, 5), (0, 0, 1), tmin=-INF)))
    c.append(case("origin on the plane", ["on-surface"], shape=z1,
                  ray=ray((3, 2, 1), (0.5, 0, -1))))
    c.append(case("origin on the plane, leaving", ["on-surface"], shape=z1,
                  ray=ray((-3, 2, 1), (0, 0.5, 2))))
    c.append(case("parallel above the plane", ["parallel", "miss"], shape=z1,
                  ray=ray((0, 0, 2), (1, 0, 0))))
    c.append(case("ray lying in the plane", ["parallel", "in-plane", "miss"], shape=z1,
                  ray=ray((0, 0, 1), (1, 1, 0))))
    c.append(case("exactly parallel with eps = 0", ["parallel", "eps", "miss"], shape=z1,
                  ray=ray((0, 0, 2), (3, -1, 0)), opts=opts(eps=0.0)))
    c.append(case("near-parallel 1e-9 slope, default eps: hit", ["near-parallel"],
                  shape=plane((0, 0, 1), 0), ray=ray((0, 0, -1e-3), (1, 0, 1e-9))))
    c.append(case("near-parallel 1e-9 slope, eps 1e-6: parallel", ["near-parallel", "eps", "miss"],
                  shape=plane((0, 0, 1), 0), ray=ray((0, 0, -1e-3), (1, 0, 1e-9)),
                  opts=opts(eps=1e-6)))
    c.append(case("slope 1e-300 with eps = 0 is not parallel", ["near-parallel", "eps"],
                  shape=plane((0, 0, 1), 0), ray=ray((0, 0, -1), (1, 0, 1e-300)),
                  opts=opts(eps=0.0)))
    c.append(case("tilted plane, non-unit normal (1,2,2)", ["basic"],
                  shape=plane((1, 2, 2), -6), ray=ray((0, 0, 0), (1, 1, 1))))
    c.append(case("tilted plane hit from the front", ["basic"],
                  shape=plane((1, 2, 2), -6), ray=ray((4, 4, 4), (-1, -1, -1))))
    c.append(case("normal pointing down: ray from above exits", ["basic"],
                  shape=plane((0, 0, -2), 2), ray=ray((0, 0, 5), (0, 0, -1))))
    c.append(case("plane with decimal coefficients", ["basic"],
                  shape=plane((0.1, 0.2, 0.3), -0.7), ray=ray((0.3, -0.1, 2.9), (0.01, 0.05, -1.0))))
    c.append(case("tiny normal (1e-150) is scale invariant", ["basic"],
                  shape=plane((0, 1e-150, 0), 0), ray=ray((0, 5, 0), (0, -1, 0))))
    c.append(case("huge normal (1e150) is scale invariant", ["basic"],
                  shape=plane((1e150, 0, 0), -2e150), ray=ray((0, 0, 0), (0.5, 3, 0))))
    c.append(case("hit beyond tmax", ["clip", "miss"], shape=z1,
                  ray=ray((0, 0, 5), (0, 0, -1), tmax=3.9)))
    c.append(case("hit exactly at tmax", ["clip-exact"], shape=z1,
                  ray=ray((0, 0, 5), (0, 0, -1), tmax=4.0)))
    c.append(case("hit exactly at tmin", ["clip-exact"], shape=z1,
                  ray=ray((0, 0, 5), (0, 0, -1), tmin=4.0)))
    c.append(case("hit before tmin", ["clip", "miss"], shape=z1,
                  ray=ray((0, 0, 5), (0, 0, -1), tmin=4.5)))
    c.append(case("tmin > tmax", ["empty-interval", "miss"], shape=z1,
                  ray=ray((0, 0, 5), (0, 0, -1), tmin=5.0, tmax=1.0)))
    c.append(case("far plane z = 1e7", ["far"], shape=plane((0, 0, 1), -1e7),
                  ray=ray((1e7, -1e7, 0), (1e-3, 0, 1))))
    c.append(case("zero normal is degenerate", ["degenerate", "miss"], shape=plane((0, 0, 0), 1),
                  ray=ray((0, 0, 5), (0, 0, -1))))

    # --- revision 2: origins on the surface and within a few ulps of it (tmin = 0)
    tilt = plane((1, 2, 2), -6)                  # x + 2y + 2z = 6, front side +n
    on = (2.0, 1.0, 1.0)                          # exactly on it
    down, up = (-0.5, -1, 0.25), (0.25, 0.5, 1)   # n.d < 0 (toward the back) / > 0
    c.append(surface_case("on the plane, toward the back: t = 0 (enter)", [], shape=tilt, ray=ray(on, down)))
    c.append(surface_case("on the plane, toward the front: t = 0 (exit)", [], shape=tilt, ray=ray(on, up)))
    c.append(surface_case("1 ulp in front (x), toward the plane: t ~ +1e-16", [], shape=tilt,
                          ray=ray(nudged(on, 0, 1), down)))
    c.append(surface_case("1 ulp in front (x), away: t < 0, no hit", ["miss"], shape=tilt,
                          ray=ray(nudged(on, 0, 1), up)))
    c.append(surface_case("2 ulps behind (z), toward the plane: t ~ +1e-16 (exit)", [], shape=tilt,
                          ray=ray(nudged(on, 2, -2), up)))
    c.append(surface_case("3 ulps behind (y), away: t < 0, no hit", ["miss"], shape=tilt,
                          ray=ray(nudged(on, 1, -3), down)))
    c.append(surface_case("1 ulp behind (y), toward, non-unit direction", ["non-unit-dir"], shape=tilt,
                          ray=ray(nudged(on, 1, -1), (3, 5, 7))))

    # --- revision 2: grazing (nearly parallel, outside eps), t to about 4 ulp
    e = 2.0 ** -30
    along = (2 + e, -1 + 2 * e, 2 * e)           # (2, -1, 0) + e (1, 2, 2): n.d = 9e
    c.append(case("grazing from the back: n.d/(|n||d|) ~ 1.3e-9, hit at t ~ 7.2e8", ["grazing", "near-parallel"],
                  shape=tilt, ray=ray((0, 0, 0), along), tol=TIGHT))
    c.append(case("grazing from the front, the reversed direction", ["grazing", "near-parallel"],
                  shape=tilt, ray=ray((0, 0, 6), (-along[0], -along[1], -along[2])), tol=TIGHT))
    c.append(case("grazing with eps 1e-6: the plane counts as parallel (eps still applies to planes)",
                  ["grazing", "near-parallel", "eps", "miss"], shape=tilt, ray=ray((0, 0, 0), along),
                  opts=opts(eps=1e-6)))
    c.append(case("grazing at slope 2^-45 with eps = 0", ["grazing", "near-parallel", "eps"],
                  shape=plane((0, 0, 1), -0.5), ray=ray((-3, 0.25, 0.5 + 2.0 ** -40), (1, 0.5, -2.0 ** -45)),
                  opts=opts(eps=0.0), tol=TIGHT))
    return c
