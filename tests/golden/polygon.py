# SPDX-License-Identifier: Apache-2.0
"""Planar polygon (isect_ray_polygon): reference solver and cases.

Plane (isect.h): Newell's normal through the vertex centroid m = (1/n) sum v_i,
    N = sum_i (v_i - m) x (v_{i+1} - m)  (= sum_i v_i x v_{i+1}; componentwise
    N_x = sum (y_i - y_{i+1})(z_i + z_{i+1}) etc.).
(The seed slide writes the factor as (z_i - z_next); Newell's method has
the sum (z_i + z_next), which is what both this reference and isect.h use.)
N = 0 (collinear, or a self-intersecting polygon whose areas cancel) is
degenerate.  No eps is involved (SPEC revision 2: triangles, polygons and
mesh faces use no eps at all): the exact winding test in the sheared frame
alone decides whether the polygon is crossed; only a ray exactly parallel to
the plane (N.v == 0 exactly) has no crossing point and is not hit.  The
plane is met at
    t = N.(m - o) / (N.v),
and the hit counts when the exact perturbed winding number w of the sheared
projection (module sheared) satisfies the rule: even-odd w odd, nonzero
w != 0.  Thin surface: normal unit(N), ENTER when v.N < 0, prim -1, uv 0.
"""
from __future__ import annotations

from fractions import Fraction
from typing import Sequence

from exact import add, cross, dot, is_zero, qv, scale, sub, unit
from model import TIGHT, Ctx, Group, Hit, XRay, case, nudged, opts, ray, surface_case
from sheared import winding_sheared
from triangle import exactly_parallel

FAMILY = "polygon"


def newell(vs: Sequence[Sequence[Fraction]]) -> tuple[tuple, tuple]:
    """(Newell normal, centroid) of the vertices, exactly."""
    n = len(vs)
    m = scale(Fraction(1, n), [sum(v[k] for v in vs) for k in range(3)])
    acc = (Fraction(0),) * 3
    for i in range(n):
        acc = add(acc, cross(sub(vs[i], m), sub(vs[(i + 1) % n], m)))
    return acc, m


def rule_name(rule) -> str:
    return {"evenodd": "evenodd", "nonzero": "nonzero", 0: "evenodd", 1: "nonzero"}[rule]


def solve(shape: dict, r: XRay, ctx: Ctx) -> list[Hit]:
    vs = [qv(v) for v in shape["vertices"]]
    n, m = newell(vs)
    if is_zero(n) or exactly_parallel(n, r.dir, ctx):
        return []
    w = winding_sheared(vs, r.org, r.dir, ctx.exact)
    inside = (w % 2 == 1) if rule_name(shape["rule"]) == "evenodd" else (w != 0)
    if not inside:
        return []
    nv = dot(n, r.dir)
    t = dot(n, sub(m, r.org)) / nv
    return [Hit(t, unit(n), "enter" if nv < 0 else "exit")]


def poly(vertices, rule: str | int = "evenodd") -> dict:
    vs = [[float(x) for x in (v if len(v) == 3 else (*v, 0))] for v in vertices]
    return {"type": "polygon", "vertices": vs, "rule": rule}


def up(x: float, y: float) -> dict:
    """A ray straight up (+z) through (x, y, 0): the sheared frame is the world xy."""
    return ray((x, y, -1), (0, 0, 1))


def down(x: float, y: float) -> dict:
    """A ray straight down through (x, y, 0): frame swapped, 2D = (y, x)."""
    return ray((x, y, 1), (0, 0, -1))


CUBE_FACES = {
    "x=0": [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)],
    "x=1": [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)],
    "y=0": [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)],
    "y=1": [(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)],
    "z=0": [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)],
    "z=1": [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],
}


def cases() -> list[dict]:
    sq = [(0, 0), (2, 0), (2, 2), (0, 2)]
    c = []
    c.append(case("square: interior, from above", ["basic", "evenodd", "frame-swap"], shape=poly(sq),
                  ray=down(0.5, 1.5)))
    c.append(case("square: interior, from below (nonzero)", ["basic", "nonzero"],
                  shape=poly(sq, "nonzero"), ray=up(1.5, 0.25)))
    c.append(case("square: back side culled", ["cull-back"], shape=poly(sq), ray=up(1.5, 0.25),
                  opts=opts(flags=["cull_back"])))
    c.append(case("square: miss outside", ["miss"], shape=poly(sq), ray=up(2.5, 1)))
    c.append(case("square: behind the origin", ["behind", "miss"], shape=poly(sq),
                  ray=ray((1, 1, 1), (0, 0, 1))))
    c.append(case("square: parallel", ["parallel", "miss"], shape=poly(sq), ray=ray((-1, 1, 1), (1, 0, 0))))
    c.append(case("square: ray in its plane", ["parallel", "in-plane", "miss"], shape=poly(sq),
                  ray=ray((-1, 1, 0), (1, 0.5, 0))))
    c.append(case("square: near-parallel 1e-7, eps 1e-6: still hit (revision 2: no eps for faces)",
                  ["near-parallel", "eps"],
                  shape=poly(sq), ray=ray((-0.5, 1, 1e-7), (1, 0, -1e-7)), opts=opts(eps=1e-6)))
    c.append(case("square: near-parallel 1e-7, default eps", ["near-parallel"],
                  shape=poly(sq), ray=ray((-0.5, 1, 1e-7), (1, 0, -1e-7))))
    c.append(case("square: ray along its bottom edge (in the plane)", ["parallel", "in-plane", "edge", "miss"],
                  shape=poly(sq), ray=ray((-1, 0, 0), (1, 0, 0))))
    c.append(case("square, clockwise: normal -z, from above exits", ["basic"],
                  shape=poly(list(reversed(sq))), ray=down(1.5, 0.5)))
    c.append(case("square: hit exactly at tmin", ["clip-exact"], shape=poly(sq),
                  ray=ray((1, 1, -3), (0, 0, 1), tmin=3.0)))
    c.append(case("square: tmax before the hit", ["clip", "miss"], shape=poly(sq),
                  ray=ray((1, 1, -3), (0, 0, 1), tmax=2.0)))
    c.append(case("square: origin on the polygon", ["on-surface"], shape=poly(sq),
                  ray=ray((0.5, 0.75, 0), (0.25, 0.5, -1))))
    hexa = [(2, 1, 0), (1, 2, 0), (0, 2, 1), (0, 1, 2), (1, 0, 2), (2, 0, 1)]   # in x+y+z = 3
    c.append(case("hexagon in x+y+z = 3, hit at its centroid", ["basic", "frame-tie", "frame-swap"],
                  shape=poly(hexa), ray=ray((2, 2, 2), (-1, -1, -1))))
    c.append(case("hexagon in x+y+z = 3, oblique miss", ["miss", "non-unit-dir"], shape=poly(hexa),
                  ray=ray((3, 3, 0), (-1, -0.5, 1))))
    c.append(case("far square 1e-3 at (1e7, -1e7)", ["far"],
                  shape=poly([(1e7, -1e7, 3), (1e7 + 1e-3, -1e7, 3), (1e7 + 1e-3, -1e7 + 1e-3, 3),
                              (1e7, -1e7 + 1e-3, 3)]),
                  ray=ray((1e7 + 4e-4, -1e7 + 7e-4, 0), (0, 0, 1))))
    c.append(case("triangle as a 3-gon, oblique", ["basic"], shape=poly([(1, 2, 3), (4, 0, 1), (2, 5, -1)]),
                  ray=ray((0, 0, 0), (2.1, 2.3, 1.2))))

    # concave U (notch opening up) and the same U upside down
    u_up = [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)]
    u_dn = [(0, 3), (1, 3), (1, 1), (2, 1), (2, 3), (3, 3), (3, 0), (0, 0)]
    c.append(case("U: through the notch", ["concave", "miss"], shape=poly(u_up), ray=up(1.5, 2)))
    c.append(case("U: through the left arm", ["concave"], shape=poly(u_up), ray=up(0.5, 2.5)))
    c.append(case("U: through the base", ["concave"], shape=poly(u_up, "nonzero"), ray=up(2.5, 0.5)))
    c.append(case("U: reflex vertex (2,1), perturbed into the base", ["reflex", "vertex"],
                  shape=poly(u_up), ray=up(2, 1)))
    c.append(case("U: reflex vertex (1,1), perturbed into the base", ["reflex", "vertex"],
                  shape=poly(u_up), ray=up(1, 1)))
    c.append(case("U: bottom of the notch (horizontal edge on the line)", ["edge", "horizontal-edge"],
                  shape=poly(u_up), ray=up(1.5, 1)))
    c.append(case("upside-down U: reflex vertex (2,2) perturbed into the notch", ["reflex", "vertex"],
                  shape=poly([(x, 3 - y) for x, y in u_up]), ray=up(2, 2)))
    c.append(case("upside-down U: top of the notch", ["edge", "horizontal-edge"],
                  shape=poly([(x, 3 - y) for x, y in u_up]), ray=up(1.5, 2)))
    c.append(case("U (other start vertex): reflex vertex (1,1), ray down", ["reflex", "vertex", "frame-swap"],
                  shape=poly(u_dn), ray=down(1, 1)))
    c.append(case("U (other start vertex): inner edge x = 2, ray down", ["edge", "frame-swap"],
                  shape=poly(u_dn), ray=down(2, 2)))

    # collinear and duplicate vertices
    col = [(0, 0), (1, 0), (2, 0), (2, 1), (2, 2), (0, 2)]
    c.append(case("collinear vertices: interior", ["collinear"], shape=poly(col), ray=up(1, 1)))
    c.append(case("collinear vertex (1,0) on the bottom edge", ["collinear", "vertex"],
                  shape=poly(col), ray=up(1, 0)))
    c.append(case("collinear vertex (2,1) on the right edge", ["collinear", "vertex"],
                  shape=poly(col), ray=up(2, 1)))
    dup = [(0, 0), (2, 0), (2, 0), (2, 2), (0, 2)]
    c.append(case("duplicate vertex: interior", ["duplicate-vertex"], shape=poly(dup), ray=up(1.5, 0.5)))
    c.append(case("duplicate vertex: through it", ["duplicate-vertex", "vertex"], shape=poly(dup),
                  ray=up(2, 0)))

    # self-intersecting pentagram: winding 2 in the centre
    star = [(0, 3), (2, -3), (-3, 1), (3, 1), (-2, -3)]
    c.append(case("pentagram centre, even-odd: outside", ["self-intersecting", "evenodd", "miss"],
                  shape=poly(star, "evenodd"), ray=up(0, 0)))
    c.append(case("pentagram centre, nonzero: inside", ["self-intersecting", "nonzero"],
                  shape=poly(star, "nonzero"), ray=up(0, 0)))
    c.append(case("pentagram tip, even-odd: inside", ["self-intersecting", "evenodd"],
                  shape=poly(star, "evenodd"), ray=up(0, 2.5)))

    # the test line through a horizontal edge, in the sheared frame
    sq2 = [(1, 0), (2, 0), (2, 1), (1, 1)]
    c.append(case("on the extension of a horizontal edge, left", ["horizontal-edge", "miss"],
                  shape=poly(sq2), ray=up(0, 0)))
    c.append(case("on the extension of a horizontal edge, right", ["horizontal-edge", "miss"],
                  shape=poly(sq2), ray=up(3, 0)))
    c.append(case("on a horizontal bottom edge (perturbed below)", ["horizontal-edge", "edge"],
                  shape=poly(sq2), ray=up(1.5, 0)))
    c.append(case("on a horizontal top edge (perturbed below: inside)", ["horizontal-edge", "edge"],
                  shape=poly(sq2), ray=up(1.5, 1)))
    wedge = [(1, 0), (2, -1), (2, 1)]
    c.append(case("test line through a vertex to the right", ["vertex", "miss"], shape=poly(wedge),
                  ray=up(0, 0)))
    c.append(case("test line through a vertex, point inside", ["basic"], shape=poly(wedge), ray=up(1.5, 0)))

    # the six faces of the unit cube as separate polygons: exactly-once
    groups = [
        ("cube corners (0,0,0) -> (1,1,1)", ray((-1, -1, -1), (1, 1, 1)), "enter-exit",
         ["vertex", "watertight", "frame-tie"]),
        ("cube edges x=y=0 -> x=y=1", ray((-1, -1, 0.5), (1, 1, 0)), "enter-exit",
         ["edge", "watertight", "frame-tie"]),
        ("cube edge graze at (0,1,0.5)", ray((-1, 0, 0.5), (1, 1, 0)), "even",
         ["edge", "watertight", "frame-tie"]),
        ("cube edge x=0,z=1 -> corner (1,1,0)", ray((-0.5, 0.25, 1.5), (1, 0.5, -1)),
         "enter-exit", ["edge", "vertex", "watertight", "frame-tie"]),
    ]
    for gname, r, kind, flags in groups:
        g = Group(gname, kind)
        for face, vs in CUBE_FACES.items():
            c.append(case(f"{gname}: face {face}", flags, g, shape=poly(vs), ray=r))

    c.append(case("bowtie with cancelling areas (zero Newell normal) is degenerate",
                  ["degenerate", "self-intersecting", "miss"],
                  shape=poly([(0, 0), (2, 2), (2, 0), (0, 2)]), ray=up(1, 0.5)))
    c.append(case("collinear polygon is degenerate", ["degenerate", "miss"],
                  shape=poly([(0, 0, 0), (1, 1, 1), (3, 3, 3)]), ray=ray((1, 1, 0), (0, 0, 1))))

    # --- revision 2: origins on a tilted concave polygon and within a few ulps of it (tmin = 0)
    # the U (notch opening up) lifted into the plane x + 2y + 4z = 8 (Newell normal ~ (1, 2, 4))
    tilted_u = poly([(x, y, (8 - x - 2 * y) / 4) for x, y in u_up])
    on = (0.5, 2.5, 0.625)                        # in the left arm
    back, front = (-0.5, -1, -1.5), (0.25, 0.5, 2)
    c.append(surface_case("tilted U: on it, toward the back: t = 0 (enter)", ["concave", "frame-swap"],
                          shape=tilted_u, ray=ray(on, back)))
    c.append(surface_case("tilted U: on it, toward the front: t = 0 (exit)", ["concave"],
                          shape=tilted_u, ray=ray(on, front)))
    c.append(surface_case("tilted U: 1 ulp in front (z), toward it", ["concave", "frame-swap"],
                          shape=tilted_u, ray=ray(nudged(on, 2, 1), back)))
    c.append(surface_case("tilted U: 1 ulp in front (z), away: no hit", ["concave", "miss"],
                          shape=tilted_u, ray=ray(nudged(on, 2, 1), front)))
    c.append(surface_case("tilted U: 2 ulps behind (y), toward it (exit)", ["concave"],
                          shape=tilted_u, ray=ray(nudged(on, 1, -2), front)))
    c.append(surface_case("tilted U: 3 ulps behind (x), away: no hit", ["concave", "miss", "frame-swap"],
                          shape=tilted_u, ray=ray(nudged(on, 0, -3), back)))
    c.append(surface_case("tilted U: on its plane in the notch: no hit", ["concave", "miss", "frame-swap"],
                          shape=tilted_u, ray=ray((1.5, 2, 0.625), back)))
    c.append(surface_case("tilted U, nonzero rule: 1 ulp behind (z), toward it", ["concave", "nonzero"],
                          shape=poly([(x, y, (8 - x - 2 * y) / 4) for x, y in u_up], "nonzero"),
                          ray=ray(nudged(on, 2, -1), front)))

    # --- revision 2: grazing rays, nearly parallel; the exact test decides at every eps
    s45 = 2.0 ** -45
    c.append(case("grazing: square, slope 2^-45 crossing inside", ["grazing", "near-parallel"], shape=poly(sq),
                  ray=ray((-0.5, 1.25, s45), (1, 0.25, -s45)), tol=TIGHT))
    c.append(case("grazing: square, slope 2^-45, eps 1e-3: still hit", ["grazing", "near-parallel", "eps"],
                  shape=poly(sq), ray=ray((-0.5, 1.25, s45), (1, 0.25, -s45)), opts=opts(eps=1e-3), tol=TIGHT))
    c.append(case("grazing: U, slope 2^-45 crossing the notch: miss", ["grazing", "near-parallel", "concave",
                  "miss"], shape=poly(u_up), ray=ray((1.5, -1, 2.5 * s45), (0, 1, -s45))))
    c.append(case("grazing: U, slope 2^-45 crossing the right arm from below", ["grazing", "near-parallel",
                  "concave"], shape=poly(u_up), ray=ray((2.5, -1, -3.5 * s45), (0, 1, s45)), tol=TIGHT))
    return c
