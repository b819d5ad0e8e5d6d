# SPDX-License-Identifier: Apache-2.0
"""2D and polygon helpers: point_in_polygon2, winding_number2, polygon_normal,
plane_from_points (reference and cases).

point_in_polygon2 / winding_number2 use the exact rule of isect.h directly
in the plane (no projection): the query point p is moved to
p + (-e^2, -e), so a point on an edge or vertex belongs to exactly one of two
polygons sharing that edge with opposite orientation (module sheared,
``winding_at``).  The winding number is the integer crossing sum
(Sunday / Hormann & Agathos): upward edge with p on its left +1, downward
edge with p on its right -1; counter-clockwise loops count +1.
even-odd: inside iff w is odd; nonzero: inside iff w != 0.

polygon_normal: unit Newell normal N = sum (v_i - m) x (v_{i+1} - m)
(m the centroid), E_DEGENERATE when N = 0.  plane_from_points:
(N/|N|, -N.m/|N|).
"""
from __future__ import annotations

import math
from fractions import Fraction
from typing import Sequence

from exact import dot, is_zero, qv, to_double, unit
from model import Group, case
from polygon import newell
from sheared import winding_at

FAMILY = "polygon2d"


def _finite(*arrays) -> bool:
    return all(math.isfinite(x) for a in arrays for row in a for x in (row if isinstance(row, list) else [row]))


def evaluate(c: dict) -> dict:
    op = c["op"]
    if op in ("point_in_polygon2", "winding_number2"):
        poly, pt = c["polygon"], c["point"]
        if len(poly) < 3:
            return {"status": "E_ARG"}
        if op == "point_in_polygon2" and c["rule"] not in ("evenodd", "nonzero", 0, 1):
            return {"status": "E_ARG"}
        if not _finite(poly, [pt]):
            return {"status": "E_NONFINITE"}
        w = winding_at([qv(v) for v in poly], qv(pt))
        if op == "winding_number2":
            return {"status": "ok", "winding": w}
        evenodd = c["rule"] in ("evenodd", 0)
        return {"status": "ok", "inside": int(w % 2 == 1 if evenodd else w != 0)}
    if op in ("polygon_normal", "plane_from_points"):
        vs = c["vertices"]
        if len(vs) < 3:
            return {"status": "E_ARG"}
        if not _finite(vs):
            return {"status": "E_NONFINITE"}
        n, m = newell([qv(v) for v in vs])
        if is_zero(n):
            return {"status": "E_DEGENERATE"}
        u = unit(n)
        if op == "polygon_normal":
            return {"status": "ok", "normal": [to_double(x) for x in u]}
        return {"status": "ok", "plane": [to_double(x) for x in u] + [to_double(-dot(u, m))]}
    raise ValueError(op)


def fl2(vs: Sequence[Sequence[float]]) -> list[list[float]]:
    return [[float(x) for x in v] for v in vs]


def pip(name, flags, polygon, point, rule="evenodd", group=None) -> dict:
    return case(name, flags, group, op="point_in_polygon2", polygon=fl2(polygon),
                point=[float(x) for x in point], rule=rule)


def wn(name, flags, polygon, point, group=None) -> dict:
    return case(name, ["winding"] + flags, group, op="winding_number2", polygon=fl2(polygon),
                point=[float(x) for x in point])


def pn(name, flags, vertices, op="polygon_normal") -> dict:
    return case(name, ["normal-op"] + flags, op=op, vertices=fl2(vertices))


def robust_point() -> tuple[list[tuple[float, float]], tuple[float, float]]:
    """A triangle and a point next to its edge where naive double predicates err.

    Edge A -> B of a counter-clockwise triangle; p is a few ulps off the line
    AB.  Three usual double-precision evaluations -- (A - p) x (B - p),
    (B - A) x (p - A), and comparing p.x with the x of AB at height p.y --
    all give the wrong side, so only an exact predicate is right.
    """
    A, B = (0.1, 0.3), (7.7, 9.1)
    qa, qb = (Fraction(A[0]), Fraction(A[1])), (Fraction(B[0]), Fraction(B[1]))
    for i in range(1, 4000):
        x = 0.1 + i * (7.6 / 4000)
        y0 = 0.3 + (x - 0.1) * (8.8 / 7.6)
        for k in range(-3, 4):
            y = y0 + k * math.ulp(y0)
            ex = (qa[0] - Fraction(x)) * (qb[1] - Fraction(y)) - (qa[1] - Fraction(y)) * (qb[0] - Fraction(x))
            if ex == 0:
                continue
            left = ex > 0               # p left of A -> B: inside
            naive1 = (A[0] - x) * (B[1] - y) - (A[1] - y) * (B[0] - x) > 0
            naive2 = (B[0] - A[0]) * (y - A[1]) - (B[1] - A[1]) * (x - A[0]) > 0
            naive3 = x < A[0] + (y - A[1]) * (B[0] - A[0]) / (B[1] - A[1])
            if naive1 != left and naive2 != left and naive3 != left:
                return [A, B, (0.1, 9.1)], (x, y)
    raise RuntimeError("no robustness witness found")


def cases() -> list[dict]:
    sq = [(0, 0), (2, 0), (2, 2), (0, 2)]
    cw = list(reversed(sq))
    c = []
    c.append(pip("square: interior", ["basic"], sq, (1, 1)))
    c.append(pip("square: outside", ["miss"], sq, (3, 1)))
    c.append(pip("square: left edge (perturbed left: outside)", ["edge"], sq, (0, 1)))
    c.append(pip("square: right edge (perturbed left: inside)", ["edge"], sq, (2, 1)))
    c.append(pip("square: bottom edge (perturbed down: outside)", ["edge", "horizontal-edge"], sq, (1, 0)))
    c.append(pip("square: top edge (perturbed down: inside)", ["edge", "horizontal-edge"], sq, (1, 2)))
    for v in sq:
        c.append(pip(f"square: vertex {v}", ["vertex"], sq, v))
    c.append(pip("clockwise square: right edge, nonzero", ["edge", "nonzero"], cw, (2, 1), "nonzero"))
    c.append(pip("clockwise square: interior, nonzero", ["nonzero"], cw, (0.5, 1.5), "nonzero"))
    u_up = [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)]
    c.append(pip("U: in the notch", ["concave", "miss"], u_up, (1.5, 2)))
    c.append(pip("U: in the arm", ["concave"], u_up, (2.5, 2)))
    c.append(pip("U: reflex vertex (1,1)", ["concave", "reflex", "vertex"], u_up, (1, 1)))
    c.append(pip("U: notch bottom edge", ["concave", "edge", "horizontal-edge"], u_up, (1.5, 1)))
    c.append(pip("U: on the line y = 3 between the arms", ["concave", "horizontal-edge", "miss"], u_up, (1.5, 3)))
    star = list(reversed([(0, 3), (2, -3), (-3, 1), (3, 1), (-2, -3)]))     # counter-clockwise
    c.append(pip("pentagram centre, even-odd", ["self-intersecting", "evenodd", "miss"], star, (0, 0)))
    c.append(pip("pentagram centre, nonzero", ["self-intersecting", "nonzero"], star, (0, 0), "nonzero"))
    c.append(pip("pentagram centre, rule given as the integer ISECT_NONZERO = 1", ["self-intersecting", "nonzero",
                 "c-only"], star, (0, 0), 1))
    c.append(pip("collinear vertex on the right edge", ["collinear", "vertex"],
                 [(0, 0), (2, 0), (2, 1), (2, 2), (0, 2)], (2, 1)))
    tri, p = robust_point()
    c.append(pip("point a few ulps from an edge (naive double predicates say inside)", ["robust"], tri, p))
    c.append(pip("huge coordinates 1e150", ["basic"], [(-1e150, -1e150), (1e150, -1e150), (0, 1e150)], (0, 0)))
    c.append(pip("tiny coordinates 1e-150, on the right edge", ["edge"], [(0, 0), (1e-150, 0), (1e-150, 1e-150)],
                 (1e-150, 5e-151)))

    # tilings: the shared vertex / edge belongs to exactly one tile
    g = Group("four unit squares around the origin", "one-inside")
    for sx in (-1, 0):
        for sy in (-1, 0):
            tile = [(sx, sy), (sx + 1, sy), (sx + 1, sy + 1), (sx, sy + 1)]
            c.append(pip(f"tile [{sx},{sx + 1}]x[{sy},{sy + 1}] at the shared corner", ["tiling", "vertex"],
                         tile, (0, 0), group=g))
    g = Group("two triangles sharing a diagonal edge", "one-inside")
    for tile in ([(0, 0), (3, 1), (1, 2)], [(3, 1), (0, 0), (2, -2)]):
        c.append(pip(f"triangle {tile} at a point of the shared edge", ["tiling", "edge"], tile, (1.5, 0.5),
                     group=g))
    g = Group("hexagonal fan around a shared vertex", "one-inside")
    rim = [(2, 0), (1, 2), (-1, 2), (-2, 0), (-1, -2), (1, -2)]
    for i in range(6):
        c.append(pip(f"fan triangle {i} at the centre", ["tiling", "vertex"],
                     [(0, 0), rim[i], rim[(i + 1) % 6]], (0, 0), group=g))

    # winding numbers
    c.append(wn("counter-clockwise square", ["basic"], sq, (1, 1)))
    c.append(wn("clockwise square", ["basic"], cw, (1, 1)))
    c.append(wn("outside", ["miss"], sq, (-1, 1)))
    c.append(wn("pentagram centre: 2", ["self-intersecting"], star, (0, 0)))
    c.append(wn("pentagram tip: 1", ["self-intersecting"], star, (0, 2.5)))
    c.append(wn("square traced twice: 2", ["self-intersecting", "duplicate-vertex"], sq + sq, (0.5, 0.5)))
    c.append(wn("clockwise square traced twice: -2", ["self-intersecting", "duplicate-vertex"], cw + cw, (0.5, 0.5)))
    c.append(wn("right edge of a clockwise square", ["edge"], cw, (2, 0.5)))
    c.append(wn("top-right vertex of the square", ["vertex"], sq, (2, 2)))
    c.append(wn("figure eight: right lobe", ["self-intersecting"], [(0, 0), (2, 2), (2, 0), (0, 2)], (1.75, 1)))
    c.append(wn("figure eight: left lobe", ["self-intersecting"], [(0, 0), (2, 2), (2, 0), (0, 2)],
                (0.25, 1)))
    c.append(wn("figure eight: the crossing point of two edges", ["self-intersecting", "edge"], [(0, 0), (2, 2), (2, 0), (0, 2)],
                (1, 1)))

    # normals and planes (Newell about the centroid)
    c.append(pn("triangle in z = 0", ["basic"], [(0, 0, 0), (1, 0, 0), (0, 1, 0)]))
    c.append(pn("clockwise square: -z", ["basic"], [(0, 2, 0), (2, 2, 0), (2, 0, 0), (0, 0, 0)]))
    c.append(pn("hexagon in x + y + z = 3", ["basic"], [(2, 1, 0), (1, 2, 0), (0, 2, 1), (0, 1, 2), (1, 0, 2), (2, 0, 1)]))
    c.append(pn("concave U in the plane y = 1", ["concave"],
                [(x, 1, z) for x, z in [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)]]))
    c.append(pn("collinear middle vertex", ["collinear"], [(0, 0, 0), (1, 0, 0), (2, 0, 0), (2, 1, 1), (0, 1, 1)]))
    c.append(pn("nearly collinear triangle (height 1e-8) in z = 0", ["collinear"],
                [(0, 0, 0), (1, 0, 0), (2, 1e-8, 0)]))
    c.append(pn("thin tilted triangle (height 1e-3)", ["collinear"], [(0, 0, 0), (1, 1, 1), (2, 2.001, 1.999)]))
    c.append(pn("square far from the origin (1e8)", ["far"],
                [(1e8, 1e8, 1e8), (1e8 + 1, 1e8, 1e8 + 0.5), (1e8 + 1, 1e8 + 1, 1e8 + 1), (1e8, 1e8 + 1, 1e8 + 0.5)]))
    c.append(pn("decimal quadrilateral", ["basic"], [(0.1, 0.2, 0.3), (1.1, 0.2, 0.4), (1.1, 1.3, 0.5), (0.1, 1.3, 0.4)]))
    c.append(pn("collinear points: zero area", ["degenerate"], [(0, 0, 0), (1, 1, 1), (3, 3, 3)]))
    c.append(pn("bowtie with cancelling areas: zero Newell normal", ["degenerate", "self-intersecting"],
                [(0, 0, 0), (2, 2, 0), (2, 0, 0), (0, 2, 0)]))
    c.append(pn("plane of a triangle", ["basic"], [(1, 0, 0), (0, 2, 0), (0, 0, 3)], "plane_from_points"))
    c.append(pn("plane of a far square", ["far"],
                [(1e8, 1e8, 3e8), (1e8 + 1, 1e8, 3e8 + 0.5), (1e8 + 1, 1e8 + 1, 3e8 + 1), (1e8, 1e8 + 1, 3e8 + 0.5)],
                "plane_from_points"))
    c.append(pn("plane of a concave pentagon", ["concave"],
                [(0, 0, 1), (4, 0, 1), (4, 4, 1), (2, 1, 1), (0, 4, 1)], "plane_from_points"))
    c.append(pn("plane of collinear points", ["degenerate"], [(0, 0, 0), (1, 2, 3), (2, 4, 6)], "plane_from_points"))
    return c
