# SPDX-License-Identifier: Apache-2.0
"""Triangle a, b, c (isect_ray_triangle): reference solver and cases.

Plane: n = (b - a) x (c - a); n = 0 is degenerate.  No eps is involved
(SPEC revision 2: triangles, polygons and mesh faces use no eps at all): the
exact test in the sheared frame alone decides whether the triangle is
crossed, so a nearly parallel ray that crosses it is a hit whatever eps is.
Only a ray exactly parallel to the plane (n.v == 0, exactly) has no crossing
point and is not hit (its projection is a segment through which the
perturbed query point never passes, so the winding test agrees).  Otherwise
the plane is met at
    t = n.(a - o) / (n.v)                          (seed: Ray-Plane)
and the hit counts when the winding number of the projected triangle around
the ray is nonzero, evaluated exactly in the ray's sheared frame with the
symbolic perturbation of isect.h (module sheared).  Thin surface: normal
unit(n), ENTER when v.n < 0.  uv = barycentric weights of b and c:
in the sheared frame the hit projects to the origin O, so with 2D images
A, B, C:  u = det(O - A, C - A) / det(B - A, C - A),
          v = det(B - A, O - A) / det(B - A, C - A)
(an affine projection keeps barycentric coordinates).
"""
from __future__ import annotations

from fractions import Fraction

from exact import cross, dot, is_zero, qv, refuse, sub, unit
from model import INF, TIGHT, Ctx, Group, Hit, XRay, case, nudged, opts, ray, surface_case
from sheared import Frame, winding_sheared

FAMILY = "triangle"


def exactly_parallel(n, v, ctx: Ctx) -> bool:
    """n.v == 0 exactly: the ray has no crossing point with the face's plane.

    The library sees exactly this ray unless a transform rounds the object-space
    ray (ctx.exact False); then an exactly parallel ray could be seen as
    slightly tilted, and the case is refused.
    """
    if dot(n, v) != 0:
        return False
    if not ctx.exact:
        refuse("ray exactly parallel to a face under an inexact transform")
    return True


def solve(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    a, b, c = qv(shape["a"]), qv(shape["b"]), qv(shape["c"])
    n = cross(sub(b, a), sub(c, a))
    if is_zero(n) or exactly_parallel(n, r.dir, ctx):
        return []
    if winding_sheared([a, b, c], r.org, r.dir, ctx.exact) == 0:
        return []
    nv = dot(n, r.dir)
    t = dot(n, sub(a, r.org)) / nv
    f = Frame.of(r.org, r.dir)
    A, B, C = (f.project(p)[0] for p in (a, b, c))

    def det(p, q) -> Fraction:
        return p[0] * q[1] - p[1] * q[0]
    ab, ac = sub(B, A), sub(C, A)
    oa = (-A[0], -A[1])
    area = det(ab, ac)
    u, v = det(oa, ac) / area, det(ab, oa) / area
    return [Hit(t, unit(n), "enter" if nv < 0 else "exit", -1, (u, v))]


def tri(a, b, c) -> dict:
    return {"type": "triangle", "a": [float(x) for x in a], "b": [float(x) for x in b],
            "c": [float(x) for x in c]}


def octa_face(sx: int, sy: int, sz: int) -> dict:
    """Face of the octahedron |x|+|y|+|z| = 1 in octant (sx, sy, sz), outward (right-hand)."""
    a, b, c = (sx, 0, 0), (0, sy, 0), (0, 0, sz)
    # (b-a) x (c-a) = sx*sy*sz * (sx, sy, sz): swap b, c when that points inward
    return tri(a, b, c) if sx * sy * sz > 0 else tri(a, c, b)


def cases() -> list[dict]:
    t0 = tri((0, 0, 0), (1, 0, 0), (0, 1, 0))         # normal +z
    c = []
    c.append(case("front side, straight down", ["basic", "frame-swap"], shape=t0,
                  ray=ray((0.25, 0.25, 1), (0, 0, -1))))
    c.append(case("back side, straight up", ["basic"], shape=t0, ray=ray((0.25, 0.5, -1), (0, 0, 1))))
    c.append(case("back side culled", ["cull-back"], shape=t0, ray=ray((0.25, 0.5, -1), (0, 0, 1)),
                  opts=opts(flags=["cull_back"])))
    c.append(case("front side kept with cull_back", ["cull-back", "frame-swap"], shape=t0,
                  ray=ray((0.25, 0.25, 1), (0, 0, -1)), opts=opts(flags=["cull_back"])))
    c.append(case("miss outside the hypotenuse", ["miss"], shape=t0, ray=ray((0.75, 0.5, 1), (0, 0, -1))))
    c.append(case("triangle behind the origin", ["behind", "miss"], shape=t0,
                  ray=ray((0.25, 0.25, 1), (0, 0, 1))))
    c.append(case("behind, tmin = -inf", ["behind", "negative-t"], shape=t0,
                  ray=ray((0.25, 0.25, 1), (0, 0, 1), tmin=-INF)))
    c.append(case("origin in the triangle", ["on-surface"], shape=t0,
                  ray=ray((0.25, 0.25, 0), (0.5, -1, 2))))
    c.append(case("parallel above", ["parallel", "miss"], shape=t0, ray=ray((-1, 0.25, 0.5), (1, 0, 0))))
    c.append(case("ray in the triangle's plane", ["parallel", "in-plane", "miss"], shape=t0,
                  ray=ray((-1, 0.25, 0), (1, 0, 0))))
    c.append(case("near-parallel (slope 1e-8), default eps: hit", ["near-parallel"], shape=t0,
                  ray=ray((-0.75, 0.25, 1e-8), (1, 0, -1e-8))))
    c.append(case("near-parallel (slope 1e-8), eps 1e-6: still hit (revision 2: no eps for faces)",
                  ["near-parallel", "eps"],
                  shape=t0, ray=ray((-0.75, 0.25, 1e-8), (1, 0, -1e-8)), opts=opts(eps=1e-6)))
    c.append(case("general triangle, oblique ray (uv check)", ["basic", "non-unit-dir"],
                  shape=tri((1, 2, 3), (4, 0, 1), (2, 5, -1)), ray=ray((0, 0, 0), (2.1, 2.3, 1.2))))
    c.append(case("decimal triangle", ["basic"], shape=tri((0.1, 0.2, 0.3), (1.1, -0.3, 0.2), (0.4, 0.9, 0.7)),
                  ray=ray((0.5, 0.3, -2.0), (0.01, -0.02, 1.0))))
    c.append(case("hit exactly at tmax", ["clip-exact"], shape=t0,
                  ray=ray((0.25, 0.25, 3), (0, 0, -1), tmax=3.0)))
    c.append(case("hit beyond tmax", ["clip", "miss"], shape=t0,
                  ray=ray((0.25, 0.25, 3), (0, 0, -1), tmax=2.5)))
    c.append(case("far: 1e-3 triangle at (1e7, 1e7)", ["far"],
                  shape=tri((1e7, 1e7, 5), (1e7 + 1e-3, 1e7, 5), (1e7, 1e7 + 1e-3, 5.5)),
                  ray=ray((1e7 + 2.5e-4, 1e7 + 2.5e-4, 0), (0, 0, 1))))
    c.append(case("zero area (collinear vertices) is degenerate", ["degenerate", "miss"],
                  shape=tri((0, 0, 0), (1, 1, 0), (2, 2, 0)), ray=ray((1, 1, 1), (0, 0, -1))))

    # vertices and edges of a single triangle, decided by the perturbation rule
    c.append(case("through vertex a, dir -z (query moves to world -x)", ["vertex", "frame-swap"], shape=t0,
                  ray=ray((0, 0, 1), (0, 0, -1))))
    c.append(case("through vertex b, dir +z", ["vertex"], shape=t0, ray=ray((1, 0, -1), (0, 0, 1))))
    c.append(case("through vertex c, dir +z", ["vertex"], shape=t0, ray=ray((0, 1, -1), (0, 0, 1))))
    c.append(case("through vertex a of (0,0,0),(0,-1,0),(-1,0,0): perturbed inside, hit", ["vertex"],
                  shape=tri((0, 0, 0), (0, -1, 0), (-1, 0, 0)), ray=ray((0, 0, -1), (0, 0, 1))))
    c.append(case("ray along edge ab (in the plane): parallel", ["parallel", "in-plane", "edge", "miss"],
                  shape=t0, ray=ray((-1, 0, 0), (1, 0, 0))))
    c.append(case("on the line of edge ab beyond b", ["horizontal-edge", "miss"], shape=t0,
                  ray=ray((1.5, 0, -1), (0, 0, 1))))
    c.append(case("through the middle of edge ab, oblique (1,1,-2)", ["edge", "frame-swap"], shape=t0,
                  ray=ray((0, -0.5, 1), (1, 1, -2))))

    # exactly once across a shared edge: t0 and its mirror across ab
    g = Group("triangle edge ab shared by two triangles", "one")
    below = tri((1, 0, 0), (0, 0, 0), (0.5, -1, 0))
    for nm, sh in (("t0", t0), ("mirror", below)):
        c.append(case(f"shared edge ab: ray +z through (0.5,0,0), {nm}", ["edge", "horizontal-edge", "watertight"], g,
                      shape=sh, ray=ray((0.5, 0, -1), (0, 0, 1))))
    g = Group("hypotenuse shared by two triangles", "one")
    other = tri((0, 1, 0), (1, 0, 0), (1, 1, 0))
    for nm, sh in (("t0", t0), ("square half", other)):
        c.append(case(f"shared hypotenuse: ray -z through (0.5,0.5,0), {nm}",
                      ["edge", "watertight", "frame-swap"], g, shape=sh, ray=ray((0.5, 0.5, 1), (0, 0, -1))))

    # a fan of six triangles around the origin: the centre vertex counted once
    rim = [(2, 0, 0), (1, 2, 0), (-1, 2, 0), (-2, 0, 0), (-1, -2, 0), (1, -2, 0)]
    for d, tag in (((0.25, 0.5, 1), "dir (0.25,0.5,1)"), ((-0.5, 0.25, -1), "dir (-0.5,0.25,-1)")):
        g = Group(f"hexagonal fan, centre vertex, {tag}", "one")
        for i in range(6):
            sh = tri((0, 0, 0), rim[i], rim[(i + 1) % 6])
            org = tuple(-x for x in d)
            flags = ["vertex", "watertight"] + (["frame-swap"] if d[2] < 0 else [])
            c.append(case(f"fan centre vertex, {tag}, triangle {i}", flags, g, shape=sh, ray=ray(org, d)))
    # shared fan edge 0-(1,2,0), through its midpoint (0.5, 1, 0)
    g = Group("hexagonal fan, edge to (1,2,0)", "one")
    for i in (0, 1):
        sh = tri((0, 0, 0), rim[i], rim[(i + 1) % 6])
        c.append(case(f"fan edge midpoint (0.5,1,0), dir (0.5,0.5,-1), triangle {i}",
                      ["edge", "watertight", "frame-swap"], g, shape=sh, ray=ray((0, 0.5, 1), (0.5, 0.5, -1))))

    # octahedron around its vertex (1,0,0): crossing once, grazing evenly
    faces = [(1, sy, sz) for sy in (1, -1) for sz in (1, -1)]
    g = Group("octahedron vertex (1,0,0), crossing", "one")
    for f in faces:
        c.append(case(f"octahedron vertex crossing, face {f}", ["vertex", "watertight", "frame-swap"], g,
                      shape=octa_face(*f), ray=ray((2, -0.25, -0.25), (-1, 0.25, 0.25))))
    g = Group("octahedron vertex (1,0,0), grazing", "even")
    for f in faces:
        c.append(case(f"octahedron vertex graze, face {f}", ["vertex", "watertight", "frame-tie"], g,
                      shape=octa_face(*f), ray=ray((0, -1, -1), (1, 1, 1))))
    g = Group("octahedron edge (1,0,0)-(0,1,0), crossing", "one")
    for f in ((1, 1, 1), (1, 1, -1)):
        c.append(case(f"octahedron edge crossing, face {f}", ["edge", "watertight", "frame-swap"], g,
                      shape=octa_face(*f), ray=ray((2.5, 1.5, 0), (-2, -1, 0))))

    # --- revision 2: origins on the triangle and within a few ulps of it (tmin = 0)
    slant = tri((1, 0, 0), (0, 1, 0), (0, 0, 1))     # x + y + z = 1, normal (1, 1, 1)
    on = (0.25, 0.25, 0.5)
    back, front = (-1, -2, -3), (0.5, 1, 1.5)         # toward the back / the front side
    c.append(surface_case("on the triangle, toward the back: t = 0 (enter)", ["frame-swap"], shape=slant,
                          ray=ray(on, back)))
    c.append(surface_case("on the triangle, toward the front: t = 0 (exit)", [], shape=slant,
                          ray=ray(on, front)))
    c.append(surface_case("1 ulp in front (z), toward it: t ~ +1e-16", ["frame-swap"], shape=slant,
                          ray=ray(nudged(on, 2, 1), back)))
    c.append(surface_case("1 ulp in front (z), away: no hit", ["miss"], shape=slant,
                          ray=ray(nudged(on, 2, 1), front)))
    c.append(surface_case("1 ulp behind (z), toward it: t ~ +1e-16 (exit)", [], shape=slant,
                          ray=ray(nudged(on, 2, -1), front)))
    c.append(surface_case("2 ulps behind (x), away: no hit", ["miss", "frame-swap"], shape=slant,
                          ray=ray(nudged(on, 0, -2), back)))
    c.append(surface_case("3 ulps in front (y), toward it, cull_back keeps the front", ["cull-back",
                          "frame-swap"], shape=slant, ray=ray(nudged(on, 1, 3), back),
                          opts=opts(flags=["cull_back"])))
    c.append(surface_case("on the plane beside the triangle: no hit", ["miss"], shape=slant,
                          ray=ray((0.75, 0.75, -0.5), back)))

    # --- revision 2: grazing rays, nearly parallel; the exact test decides at every eps
    s45 = 2.0 ** -45                                   # slope far below the default eps
    c.append(case("grazing: slope 2^-45 crossing inside (default eps): hit", ["grazing", "near-parallel"],
                  shape=t0, ray=ray((-0.75, 0.375, s45), (1, 0, -s45)), tol=TIGHT))
    c.append(case("grazing: slope 2^-45 crossing inside, eps 1e-3: still hit", ["grazing", "near-parallel",
                  "eps"], shape=t0, ray=ray((-0.75, 0.375, s45), (1, 0, -s45)), opts=opts(eps=1e-3), tol=TIGHT))
    c.append(case("grazing: slope 2^-45 crossing beside the hypotenuse: miss", ["grazing", "near-parallel",
                  "miss"], shape=t0, ray=ray((-0.75, 0.875, s45), (1, 0, -s45))))
    c.append(case("grazing: slope 2^-45 from below, back side", ["grazing", "near-parallel"],
                  shape=t0, ray=ray((-0.5, 0.125, -3 * s45), (1, 0.5, 4 * s45)), tol=TIGHT))
    c.append(case("grazing: slanted triangle, direction in its plane tilted by 2^-40", ["grazing",
                  "near-parallel"], shape=slant,
                  ray=ray((1.25, -0.5, 0.25 + 2.0 ** -40), (-1, 1, -(2.0 ** -40))), tol=TIGHT))
    return c
