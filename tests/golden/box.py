# SPDX-License-Identifier: Apache-2.0
"""Closed axis-aligned box lo <= x <= hi (isect_ray_aabb): reference solver and cases.

Seed (Axis-Aligned Cuboid): per axis k with v_k != 0 the slab is crossed at
    t = (lo_k - o_k) / v_k  and  t = (hi_k - o_k) / v_k;
with v_k == 0 the ray is inside the slab for all t iff lo_k <= o_k <= hi_k.
This is the convex solver over the six half-spaces in face order
0..5 = -x, +x, -y, +y, -z, +z (so ties go to the lowest face index),
with "parallel" meaning an exactly zero direction component.  Entry == exit
is one TOUCH.  lo == hi on any axis: degenerate (never hit).
"""
from __future__ import annotations

from fractions import Fraction

from convex import clip_planes
from exact import qv
from model import INF, TIGHT, Ctx, Hit, XRay, case, nudged, ray, surface_case

FAMILY = "box"


def faces(lo, hi) -> list[tuple[tuple[Fraction, ...], Fraction]]:
    """Half-spaces n.x + d <= 0 of the six faces, in prim order."""
    out = []
    for k in range(3):
        e = tuple(Fraction(1 if j == k else 0) for j in range(3))
        out.append((tuple(-x for x in e), lo[k]))      # -x_k + lo_k <= 0
        out.append((e, -hi[k]))                        #  x_k - hi_k <= 0
    return out


def solve(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    lo, hi = qv(shape["lo"]), qv(shape["hi"])
    if any(a == b for a, b in zip(lo, hi)):
        return []
    return clip_planes(faces(lo, hi), r, ctx, lambda n: sum(a * b for a, b in zip(n, r.dir)) == 0)


def contains(shape: dict, p) -> bool:
    lo, hi = qv(shape["lo"]), qv(shape["hi"])
    return all(a < b for a, b in zip(lo, hi)) and all(a <= x <= b for a, x, b in zip(lo, p, hi))


def box(lo, hi) -> dict:
    return {"type": "box", "lo": [float(x) for x in lo], "hi": [float(x) for x in hi]}


def cases() -> list[dict]:
    b = box((-1, -1, -1), (1, 1, 1))
    u = box((0, 0, 0), (1, 1, 1))
    c = []
    c.append(case("through the middle along +x", ["basic"], shape=b, ray=ray((-5, 0.5, 0.25), (1, 0, 0))))
    c.append(case("along -y", ["basic"], shape=b, ray=ray((0.5, 5, 0), (0, -1, 0))))
    c.append(case("along -z, non-unit direction", ["non-unit-dir"], shape=b, ray=ray((0, 0, 5), (0, 0, -2))))
    c.append(case("oblique, non-unit direction", ["non-unit-dir"], shape=box((-1, -2, -3), (4, 5, 6)),
                  ray=ray((-3, -1, -1), (2, 1, 0.5))))
    c.append(case("decimal box", ["basic"], shape=box((0.1, 0.2, 0.3), (0.7, 0.9, 1.3)),
                  ray=ray((0.4, -1.0, 0.5), (0.01, 1.0, 0.2))))
    c.append(case("miss, parallel outside the y slab", ["miss", "parallel"], shape=b,
                  ray=ray((-5, 2, 0), (1, 0, 0))))
    c.append(case("miss, oblique", ["miss"], shape=b, ray=ray((-5, 0, 0), (1, 2, 0))))
    c.append(case("box behind the origin", ["behind", "miss"], shape=b, ray=ray((5, 0, 0), (1, 0, 0))))
    c.append(case("box behind, tmin = -inf", ["behind", "negative-t"], shape=b,
                  ray=ray((5, 0, 0), (1, 0, 0), tmin=-INF)))
    c.append(case("origin inside", ["inside"], shape=b, ray=ray((0.5, 0, 0), (0, 0, 1))))
    c.append(case("origin on face -x, entering", ["on-surface"], shape=b, ray=ray((-1, 0, 0), (1, 0, 0))))
    c.append(case("origin on face +x, leaving", ["on-surface"], shape=b, ray=ray((1, 0, 0), (1, 0, 0))))
    c.append(case("ray in the face plane y = 1 (closed box)", ["parallel", "in-plane"], shape=b,
                  ray=ray((-5, 1, 0), (1, 0, 0))))
    c.append(case("ray in the face plane y = -1 (closed box)", ["parallel", "in-plane"], shape=b,
                  ray=ray((0.5, -1, 7), (0, 0, -1))))
    c.append(case("ray along the edge y = 1, z = 1", ["parallel", "in-plane", "edge"], shape=b,
                  ray=ray((-5, 1, 1), (1, 0, 0))))
    c.append(case("direction component -0.0 is parallel", ["parallel", "neg-zero"], shape=b,
                  ray=ray((-5, 0.5, 0.5), (1, -0.0, 0))))
    c.append(case("grazing the edge x = 0, y = 1 (touch)", ["graze", "edge"], shape=u,
                  ray=ray((-1, 0, 0.5), (1, 1, 0))))
    c.append(case("grazing the corner (0,0,0) (touch)", ["graze", "vertex"], shape=u,
                  ray=ray((-1, 1, 1), (1, -1, -1))))
    c.append(case("through the edge x = 0, y = 0 (tie -x/-y)", ["tie", "edge"], shape=u,
                  ray=ray((-1, -1, 0.5), (1, 1, 0))))
    c.append(case("space diagonal through two corners", ["tie", "vertex"], shape=u,
                  ray=ray((-1, -1, -1), (1, 1, 1))))
    c.append(case("through the edge +y/-z (tie 3 before 4)", ["tie", "edge"], shape=u,
                  ray=ray((0.5, 2, -1), (0, -1, 1))))
    c.append(case("tmax between entry and exit", ["clip"], shape=b,
                  ray=ray((-5, 0, 0), (1, 0, 0), tmax=5.0)))
    c.append(case("tmin between entry and exit", ["clip"], shape=b,
                  ray=ray((-5, 0, 0), (1, 0, 0), tmin=5.0)))
    c.append(case("entry exactly at tmax", ["clip-exact"], shape=b,
                  ray=ray((-5, 0, 0), (1, 0, 0), tmax=4.0)))
    c.append(case("tmin > tmax", ["empty-interval", "miss"], shape=b,
                  ray=ray((-5, 0, 0), (1, 0, 0), tmin=5.0, tmax=4.5)))
    c.append(case("far: 1e-3 box at x = 1e7", ["far"],
                  shape=box((1e7, -5e-4, -5e-4), (1e7 + 1e-3, 5e-4, 5e-4)),
                  ray=ray((0, 1e-4, -2e-4), (1, 0, 0))))
    c.append(case("flat box (lo.z == hi.z) is degenerate", ["degenerate", "miss"],
                  shape=box((0, 0, 0), (1, 1, 0)), ray=ray((0.5, 0.5, 1), (0, 0, -1))))
    c.append(case("contains: interior point", ["contains"], op="contains", shape=b, point=[0.5, -0.5, 0.0]))
    c.append(case("contains: corner point", ["contains", "boundary"], op="contains", shape=b,
                  point=[1.0, -1.0, 1.0]))
    c.append(case("contains: outside point", ["contains"], op="contains", shape=b, point=[1.5, 0.0, 0.0]))

    # --- revision 2: origins on the face +x and within a few ulps of it (tmin = 0)
    d = box((-1, -0.5, 0.25), (0.7, 1.5, 2))
    on = (0.7, 0.3, 1.1)                       # on face +x (prim 1), inside the face
    into, out = (-1, 0.25, 0.5), (1, 0.125, -0.25)
    c.append(surface_case("on face +x, inward: enter at t = 0, exit", [], shape=d, ray=ray(on, into)))
    c.append(surface_case("on face +x, outward: exit at t = 0 only", [], shape=d, ray=ray(on, out)))
    c.append(surface_case("1 ulp outside face +x, inward: enter at t ~ +1e-16", [], shape=d,
                          ray=ray(nudged(on, 0, 1), into)))
    c.append(surface_case("1 ulp outside face +x, outward: no hit", ["miss"], shape=d,
                          ray=ray(nudged(on, 0, 1), out)))
    c.append(surface_case("1 ulp inside face +x, outward: exit at t ~ +1e-16", [], shape=d,
                          ray=ray(nudged(on, 0, -1), out)))
    c.append(surface_case("3 ulps inside face +x, inward: exit only", [], shape=d,
                          ray=ray(nudged(on, 0, -3), into)))
    c.append(surface_case("2 ulps outside face -z, inward, non-unit direction", ["non-unit-dir"], shape=d,
                          ray=ray(nudged((0.5, 1.25, 0.25), 2, -2), (-0.5, -1, 3))))

    # --- revision 2: grazing (nearly parallel to a face), t to about 4 ulp
    c.append(case("grazing: into face +y at slope 2^-38, out through +x", ["grazing", "near-parallel"], shape=b,
                  ray=ray((-0.9, 1 + 2.0 ** -40, 0.3), (1, -(2.0 ** -38), 0.0625)), tol=TIGHT))
    c.append(case("grazing: 2^-40 inside face +y, slope 2^-44, through x", ["grazing", "near-parallel"],
                  shape=b, ray=ray((-5, 1 - 2.0 ** -40, 0.1), (1.5, 2.0 ** -44, -0.03125)), tol=TIGHT))
    c.append(case("grazing: 2^-40 outside face +y, slope -2^-46: miss", ["grazing", "near-parallel", "miss"],
                  shape=b, ray=ray((-5, 1 + 2.0 ** -40, 0.1), (1.5, -(2.0 ** -46), -0.03125))))
    return c
