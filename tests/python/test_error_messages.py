# SPDX-License-Identifier: Apache-2.0
"""Error messages name the offending element and its value.

Where Python can tell what is wrong before (or instead of) the C library's
generic status text, the message says which element holds which value:
``Mesh: faces[12][1] = 99 is outside [0, 40)``, ``Sphere: radius = -1.0 is
negative``, ``Sphere.intersect: origins: ray 4: origin = [nan, 0.0, -5.0] is
not finite``. One test per class of message; the last tests check that the
Python checks refuse exactly what the C library refuses, with the same status
(the C library stays the judge: Python only names).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import Any

import isect
import numpy as np
import pytest
from isect._isect import ffi, lib

NAN, INF = math.nan, math.inf
S = isect.Sphere([0, 0, 0], 1.0)
ORG, DIR = [0.0, 0.0, -5.0], [0.0, 0.0, 1.0]
TET_V = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
TETS = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
SQ2 = [[0, 0], [1, 0], [1, 1], [0, 1]]

E_ARG = isect.InvalidArgumentError
E_NONFINITE = isect.NonFiniteError
E_DEGENERATE = isect.DegenerateError


def raises(error: type[isect.IsectError], message: str,
           call: Callable[[], Any]) -> isect.IsectError:
    """``call()`` raises exactly ``error`` whose message is ``message``."""
    with pytest.raises(isect.IsectError) as info:
        call()
    assert type(info.value) is error, f"{type(info.value).__name__}: {info.value}"
    assert str(info.value) == message
    return info.value


# ------------------------------------------------------------- shapes


def test_negative_radius_names_the_argument_and_value() -> None:
    raises(E_ARG, "Sphere: radius = -1.0 is negative (a radius must be >= 0)",
           lambda: isect.Sphere([0, 0, 0], -1))
    raises(E_ARG, "Cylinder: radius = -0.5 is negative (a radius must be >= 0)",
           lambda: isect.Cylinder([0, 0, 0], [0, 0, 1], -0.5))
    raises(E_ARG, "InfiniteCylinder: radius = -2.0 is negative (a radius must be >= 0)",
           lambda: isect.InfiniteCylinder([0, 0, 0], [0, 0, 1], -2))
    raises(E_ARG, "Ellipsoid: radii[2] = -3.0 is negative (a radius must be >= 0)",
           lambda: isect.Ellipsoid([0, 0, 0], [1, 2, -3]))
    isect.Sphere([0, 0, 0], -0.0)  # -0.0 is not negative (C: r < 0)


def test_box_lo_above_hi_names_the_axis() -> None:
    raises(E_ARG, "Box: lo[1] = 2.0 > hi[1] = 1.0 (a box needs lo <= hi in every axis)",
           lambda: isect.Box([0, 2, 0], [1, 1, 1]))


def test_too_few_vertices_or_planes() -> None:
    raises(E_ARG, "Polygon: vertices: 2 given (a polygon needs at least 3)",
           lambda: isect.Polygon([[0, 0, 0], [1, 0, 0]]))
    raises(E_ARG, "ConvexPolyhedron: planes: 0 given (a convex polyhedron needs at least 1)",
           lambda: isect.ConvexPolyhedron(np.zeros((0, 4))))
    raises(E_ARG, "polygon_normal: vertices: 2 given (a polygon needs at least 3)",
           lambda: isect.polygon_normal([[0, 0, 0], [1, 1, 1]]))
    raises(E_ARG, "plane_from_points: vertices: 1 given (a plane needs at least 3)",
           lambda: isect.plane_from_points([[0, 0, 0]]))
    raises(E_ARG, "point_in_polygon: polygon: 2 given (a polygon needs at least 3)",
           lambda: isect.point_in_polygon([[0, 0], [1, 0]], [0, 0]))
    raises(E_ARG, "winding_number: polygon: 2 given (a polygon needs at least 3)",
           lambda: isect.winding_number([[0, 0], [1, 0]], [0, 0]))


def test_unknown_fill_rule_names_the_value() -> None:
    rule = ("is not a fill rule: 'evenodd' (ISECT_EVEN_ODD = 0) or 'nonzero' "
            "(ISECT_NONZERO = 1)")
    raises(E_ARG, f"Polygon: rule = 7 {rule}", lambda: isect.Polygon(np.eye(3), rule=7))
    raises(E_ARG, f"point_in_polygon: rule = 5 {rule}",
           lambda: isect.point_in_polygon(SQ2, [0.5, 0.5], rule=5))


def test_cylinder_capped_flag() -> None:
    raises(E_ARG, "Cylinder: capped = 2 is not True, False, 0 or ISECT_CAPPED (1)",
           lambda: isect.Cylinder([0, 0, 0], [0, 0, 1], 1, capped=2))


def test_nonfinite_shape_number_names_the_element() -> None:
    raises(E_NONFINITE, "Sphere: center[1] = nan is not finite",
           lambda: isect.Sphere([0, NAN, 0], 1))
    raises(E_NONFINITE, "Sphere: radius = inf is not finite", lambda: isect.Sphere([0, 0, 0], INF))
    raises(E_NONFINITE, "Plane: d = -inf is not finite", lambda: isect.Plane([0, 0, 1], -INF))
    raises(E_NONFINITE, "Triangle: c[1] = inf is not finite",
           lambda: isect.Triangle([0, 0, 0], [1, 0, 0], [0, INF, 0]))
    raises(E_NONFINITE, "Polygon: vertices[2][0] = nan is not finite",
           lambda: isect.Polygon([[0, 0, 0], [1, 0, 0], [NAN, 1, 0]]))
    raises(E_NONFINITE, "ConvexPolyhedron: planes[1][3] = nan is not finite",
           lambda: isect.ConvexPolyhedron([[0, 0, 1, -1], [0, 0, -1, NAN]]))
    raises(E_NONFINITE, "Quadric: coeffs[9] = inf is not finite",
           lambda: isect.Quadric([1, 1, 1, 0, 0, 0, 0, 0, 0, INF]))
    raises(E_NONFINITE, "Cylinder: p1[1] = nan is not finite",
           lambda: isect.Cylinder([0, 0, 0], [0, NAN, 1], 1))
    raises(E_NONFINITE, "polygon_normal: vertices[1][2] = inf is not finite",
           lambda: isect.polygon_normal([[0, 0, 0], [1, 0, INF], [0, 1, 0]]))
    raises(E_NONFINITE, "winding_number: polygon[0][0] = nan is not finite",
           lambda: isect.winding_number([[NAN, 0], [1, 0], [1, 1]], [0, 0]))


def test_zero_area_polygon_normal() -> None:
    raises(E_DEGENERATE,
           "polygon_normal: vertices: the polygon has zero area (collinear or coincident "
           "vertices): no normal",
           lambda: isect.polygon_normal([[0, 0, 0], [1, 1, 1], [2, 2, 2]]))


# ---------------------------------------------------------- transforms


def test_matrix_messages() -> None:
    raises(E_NONFINITE, "Sphere.transformed: matrix[1][2] = nan is not finite",
           lambda: S.transformed(np.where(np.arange(16).reshape(4, 4) == 6, NAN, np.eye(4))))
    raises(E_ARG, "Sphere.transformed: matrix[3] = [0.0, 0.0, 1.0, 1.0] is not "
           "[0.0, 0.0, 0.0, 1.0] (the last row of an affine object-to-world matrix)",
           lambda: S.transformed(np.eye(4) + np.eye(4, k=-1) * [[0], [0], [0], [1]]))
    raises(E_DEGENERATE, "Sphere.transformed: matrix: the linear part [[1.0, 0.0, 0.0], "
           "[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]] is singular (the determinant of its rows scaled "
           "to unit length is at most 2^-40 in magnitude)",
           lambda: S.transformed(np.diag([1.0, 0.0, 1.0, 1.0])))


# -------------------------------------------------------------- meshes


def test_mesh_index_out_of_range_names_face_corner_and_value() -> None:
    v = np.zeros((40, 3))
    faces = np.array([[0, 1, 2]] * 20)
    faces[12, 1] = 99
    raises(E_ARG, "Mesh: faces[12][1] = 99 is outside [0, 40) (the vertex indices)",
           lambda: isect.Mesh(v, faces))
    faces[12, 1] = 1
    faces[3, 2] = -1  # a negative index, the first in order
    faces[5, 0] = 40
    raises(E_ARG, "Mesh: faces[3][2] = -1 is outside [0, 40) (the vertex indices)",
           lambda: isect.Mesh(v, faces))
    raises(E_ARG, "Mesh: faces[2][3] = 2147483648 is outside [0, 4) (the vertex indices)",
           lambda: isect.Mesh(TET_V, [[0, 1, 2], [0, 1, 3, 2], [0, 2, 1, 2**31]]))
    raises(E_ARG, "Mesh: faces[1][3] = 7 is outside [0, 4) (the vertex indices)",
           lambda: isect.Mesh(TET_V, np.array([[0, 1, 2, 3], [0, 1, 2, 7]], dtype=np.uint64)))


def test_mesh_face_too_small() -> None:
    raises(E_ARG, "Mesh: faces[1] has 2 vertices (a face needs at least 3)",
           lambda: isect.Mesh(TET_V, [[0, 1, 2], [0, 1], [0, 9, 9]]))
    raises(E_ARG, "Mesh: faces[0] has 0 vertices (a face needs at least 3)",
           lambda: isect.Mesh(TET_V, [[]]))


def test_mesh_face_not_flat() -> None:
    raises(E_ARG, "faces[1]: expected a flat sequence of vertex indices, got an array of "
           "shape (1, 3)", lambda: isect.Mesh(TET_V, [[0, 1, 2], [[0, 1, 3]], [1, 2, 3, 4]]))


def test_mesh_nonfinite_vertex() -> None:
    raises(E_NONFINITE, "Mesh: vertices[3][1] = -inf is not finite",
           lambda: isect.Mesh([*TET_V[:3], [0, -INF, 1]], TETS))


# ------------------------------------------------------------ contains


def test_contains_of_an_open_cylinder() -> None:
    raises(E_ARG, "Cylinder.contains: capped = False: an open cylinder is a thin surface (its "
           "side alone) and has no inside; make it with capped=True for contains",
           lambda: isect.Cylinder([0, 0, 0], [0, 0, 1], 1, capped=False).contains([0, 0, 0]))


def test_nonfinite_points_show_their_value() -> None:
    mesh = isect.Mesh(TET_V, TETS)
    err = raises(E_NONFINITE, "Sphere.contains: points: point 1: [nan, 0.0, 0.0] is not finite",
                 lambda: S.contains([[0, 0, 0], [NAN, 0, 0]]))
    assert err.index == 1
    raises(E_NONFINITE, "Mesh.contains: points: point 0: [0.0, inf, 0.0] is not finite",
           lambda: mesh.contains([[0, INF, 0]]))
    raises(E_NONFINITE, "Mesh.winding_number: points: point 2: [0.0, 0.0, nan] is not finite",
           lambda: mesh.winding_number([[0, 0, 0], [1, 1, 1], [0, 0, NAN]]))
    raises(E_NONFINITE, "point_in_polygon: points: point 1: [nan, 1.0] is not finite",
           lambda: isect.point_in_polygon(SQ2, [[0, 0], [NAN, 1]]))
    raises(E_NONFINITE, "winding_number: points: point 0: [inf, 0.0] is not finite",
           lambda: isect.winding_number(SQ2, [INF, 0]))


# --------------------------------------------------------------- rays


def test_bad_rays_show_the_field_and_value() -> None:
    err = raises(E_NONFINITE, "Sphere.intersect: origins: ray 1: origin = [0.0, inf, -5.0] is "
                 "not finite", lambda: S.intersect([ORG, [0, INF, -5]], DIR))
    assert err.index == 1
    raises(E_NONFINITE, "Sphere.intersect: directions: ray 2: direction = [nan, 0.0, 1.0] is "
           "not finite", lambda: S.intersect(ORG, [DIR, DIR, [NAN, 0, 1]]))
    raises(E_DEGENERATE, "Sphere.intersect: directions: ray 1: direction = [0.0, 0.0, 0.0] is "
           "zero (a ray needs a direction)", lambda: S.intersect(ORG, [DIR, [0, 0, 0]]))
    raises(E_NONFINITE, "Sphere.intersect: tmin: ray 1: tmin = nan is not a number",
           lambda: S.intersect(ORG, DIR, tmin=[0.0, NAN]))
    raises(E_NONFINITE, "Sphere.intersect_all_batch: tmax: ray 0: tmax = nan is not a number",
           lambda: S.intersect_all_batch([ORG], DIR, tmax=NAN))
    raises(E_NONFINITE, "Sphere.intersect_rays: rays: ray 0: origin = [nan, nan, nan] is not "
           "finite", lambda: S.intersect_rays(np.full(2, np.nan, isect.RAY_DTYPE)))
    raises(E_DEGENERATE, "Sphere.intersect_all: direction = [0.0, 0.0, 0.0] is zero (a ray "
           "needs a direction)", lambda: S.intersect_all(ORG, [0, 0, 0]))
    raises(E_NONFINITE, "Sphere.intersect_all: origin = [nan, 0.0, -5.0] is not finite",
           lambda: S.intersect_all([NAN, 0, -5], DIR))
    # NaN or infinity comes first, as in the C check: a NaN tmin beats a zero direction
    raises(E_NONFINITE, "Sphere.intersect_all: tmin = nan is not a number",
           lambda: S.intersect_all(ORG, [0, 0, 0], tmin=NAN))


# -------------------------------------------------------------- spawn


def test_spawn_rows_show_the_field_and_value() -> None:
    hits = S.intersect([ORG, ORG, [5, 5, -5]], DIR)
    err = raises(E_ARG, "Sphere.spawn: hits: hit 2: kind = 0 (MISS) is not a hit: ENTER, EXIT or "
                 "TOUCH (a batch writes MISS for a ray that hit nothing, INVALID for a bad ray)",
                 lambda: S.spawn(hits, DIR))
    assert err.index == 2
    good = hits[:2].copy()
    zero = good.copy()
    zero["normal"][1] = 0
    raises(E_ARG, "Sphere.spawn: hits: hit 1: normal = [0.0, 0.0, 0.0] is zero (not the record "
           "of a hit)", lambda: S.spawn(zero, DIR))
    bad_point = good.copy()
    bad_point["point"][0, 2] = NAN
    raises(E_NONFINITE, "Sphere.spawn: hits: hit 0: point = [0.0, 0.0, nan] is not finite",
           lambda: S.spawn(bad_point, DIR))
    raises(E_DEGENERATE, "Sphere.spawn: directions: hit 1: direction = [0.0, 0.0, 0.0] is zero",
           lambda: S.spawn(good, [DIR, [0, 0, 0]]))
    raises(E_NONFINITE, "Sphere.spawn: directions: hit 0: direction = [inf, 0.0, 1.0] is not "
           "finite", lambda: S.spawn(good, [INF, 0, 1]))
    mesh = isect.Mesh(TET_V, TETS)
    hit = mesh.intersect([0.2, 0.2, -1], DIR)
    moved = np.array(hit)
    moved["prim"] = 9
    raises(E_ARG, "Mesh.spawn: hits: hit 0: prim = 9 is outside [0, 4) (the mesh's faces)",
           lambda: mesh.spawn(moved, DIR))
    box = isect.Box([-1, -1, -1], [1, 1, 1])
    edge = box.intersect([5, 1, 0], [-1, 0, 0])  # on the edge of the faces +x and +y
    raises(E_DEGENERATE, "Box.spawn: hits: hit 0: no offset of point = [1.0, 1.0, 0.0] along "
           "its normal leaves the surface in direction [-1.0, 0.0, 0.0] (a point not near the "
           "surface, a degenerate shape, or a direction running inward along another face "
           "through the edge or corner the hit lies on)",
           lambda: box.spawn(edge, [-1, 0, 0]))


# ----------------------------------------- Python names, C judges: the same


def _c_status(cls: type[isect.Shape], data: list[float], n: int = 0, flags: int = 0) -> int:
    """The status libisect's own check gives the shape's numbers."""
    c = ffi.new("isect_shape *")
    c.type, c.n, c.flags = cls._type, n, flags
    buf = ffi.new("double[]", data) if data else ffi.new("double[]", 1)
    c.data = buf
    ray = ffi.new("isect_ray *", ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.0, INF))
    return int(lib.isect_intersect(c, ray, ffi.NULL, ffi.NULL, 0))


SHAPE_INPUTS: list[tuple[type[isect.Shape], list[float], int, int]] = [
    (isect.Sphere, [0, 0, 0, -1], 0, 0),
    (isect.Sphere, [NAN, 0, 0, -1], 0, 0),  # NaN first
    (isect.Sphere, [0, 0, 0, -0.0], 0, 0),
    (isect.Box, [0, 2, 0, 1, 1, 1], 0, 0),
    (isect.Box, [0, 2, 0, 1, 1, INF], 0, 0),
    (isect.Polygon, [0, 0, 0, 1, 0, 0], 2, 0),
    (isect.Polygon, [0, 0, 0, 1, 0, 0, NAN, 1, 0], 3, 7),  # the rule first
    (isect.Polygon, [0, 0, 0, 1, 0, 0, NAN, 1, 0], 3, 0),
    (isect.ConvexPolyhedron, [], 0, 0),
    (isect.ConvexPolyhedron, [0, 0, 1, NAN], 1, 0),
    (isect.Cylinder, [0, 0, 0, 0, 0, 1, -1], 0, 2),  # the flag first
    (isect.Cylinder, [0, 0, 0, 0, NAN, 1, -1], 0, 1),
    (isect.Cylinder, [0, 0, 0, 0, 0, 1, -1], 0, 0),
    (isect.InfiniteCylinder, [0, 0, 0, 0, 0, 1, -1], 0, 0),
    (isect.Ellipsoid, [0, 0, 0, 1, -1, 1], 0, 0),
    (isect.Ellipsoid, [0, 0, INF, 1, -1, 1], 0, 0),
    (isect.Quadric, [1, 1, 1, 0, 0, 0, 0, 0, 0, NAN], 0, 0),
    (isect.Triangle, [0, 0, 0, 1, 0, 0, 0, INF, 0], 0, 0),
    (isect.Plane, [0, 0, 1, NAN], 0, 0),
]


@pytest.mark.parametrize(("cls", "data", "n", "flags"), SHAPE_INPUTS,
                         ids=[f"{c.__name__}-{i}" for i, (c, *_) in enumerate(SHAPE_INPUTS)])
def test_python_checks_give_the_c_status(
    cls: type[isect.Shape], data: list[float], n: int, flags: int
) -> None:
    """The Python checks refuse what the C check refuses, with its status."""
    expected = _c_status(cls, data, n, flags)
    shape = object.__new__(cls)
    try:
        shape._setup(np.array(data, dtype=np.float64), n, flags)
    except isect.IsectError as exc:
        assert exc.status == expected, str(exc)
        assert re.search(r" = | given ", str(exc)), str(exc)  # the element and its value
    else:
        assert expected >= 0


MESH_INPUTS: list[tuple[Any, list[list[int]]]] = [
    (TET_V, [[0, 1, 4]]),
    ([[0, 0, NAN], *TET_V[1:]], [[0, 1, 4]]),  # indices before the vertices' values
    ([[0, 0, NAN], *TET_V[1:]], TETS),
    (TET_V, [[0, 1], [0, 1, 9]]),  # face sizes before indices
    (TET_V, [[0, 1, -1, 2]]),
    (TET_V, TETS),
]


@pytest.mark.parametrize(("verts", "faces"), MESH_INPUTS)
def test_mesh_checks_give_the_c_status(verts: Any, faces: list[list[int]]) -> None:
    """Mesh construction refuses what isect_mesh_create refuses, with its status."""
    v = np.array(verts, dtype=np.float64)
    idx = np.array([i for f in faces for i in f], dtype=np.int32)
    offsets = np.cumsum([0] + [len(f) for f in faces]).astype(np.int64)
    out = ffi.new("isect_mesh **")
    expected = int(lib.isect_mesh_create(ffi.from_buffer("double[]", v), len(v),
                                         ffi.from_buffer("int32_t[]", idx),
                                         ffi.from_buffer("int64_t[]", offsets), len(faces), out))
    if expected >= 0:
        lib.isect_mesh_destroy(out[0])
    try:
        isect.Mesh(v, faces)
    except isect.IsectError as exc:
        assert exc.status == expected, str(exc)
    else:
        assert expected >= 0
