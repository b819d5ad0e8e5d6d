# SPDX-License-Identifier: Apache-2.0
"""Polygon helpers and version queries: thin wrappers of the C functions."""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from ._args import ArrayLike, Rule, as_points, as_rows, as_rule
from ._errors import check, error_for, nonfinite_element, too_few
from ._isect import ffi, lib
from ._shape import point_problem, raise_bad_element

_INT32_MIN = -(2**31)
_RULE_VALUES = (int(lib.ISECT_EVEN_ODD), int(lib.ISECT_NONZERO))


def version() -> str:
    """The version of the compiled libisect, "MAJOR.MINOR.PATCH"."""
    return str(ffi.string(lib.isect_version_string()).decode("ascii"))


def abi_version() -> int:
    """The ABI version of the compiled libisect (the soname's number)."""
    return int(lib.isect_abi_version())


def polygon_normal(vertices: ArrayLike) -> npt.NDArray[np.float64]:
    """Unit normal of a 3D polygon by Newell's method (``isect_polygon_normal``).

    Args:
        vertices: (n, 3), n >= 3; convex or concave; the normal follows the
            right-hand rule over the vertex order.

    Returns:
        The unit normal, shape (3,).

    Raises:
        InvalidArgumentError: fewer than 3 vertices or a wrong shape.
        DegenerateError: a polygon of zero area (collinear vertices).
    """
    v = as_rows(vertices, 3, "vertices")
    _check_polygon(v, "vertices", "polygon_normal", "a polygon")
    out = np.empty(3, dtype=np.float64)
    _check_area(
        lib.isect_polygon_normal(
            ffi.from_buffer("double[]", v), v.shape[0], ffi.from_buffer("double[]", out)
        ),
        "polygon_normal",
    )
    return out


def plane_from_points(vertices: ArrayLike) -> npt.NDArray[np.float64]:
    """Plane (a, b, c, d) through points: unit Newell normal (a, b, c) and
    d = -normal·centroid (``isect_plane_from_points``).

    Raises:
        InvalidArgumentError: fewer than 3 points or a wrong shape.
        DegenerateError: collinear points.
    """
    v = as_rows(vertices, 3, "vertices")
    _check_polygon(v, "vertices", "plane_from_points", "a plane")
    out = np.empty(4, dtype=np.float64)
    _check_area(
        lib.isect_plane_from_points(
            ffi.from_buffer("double[]", v), v.shape[0], ffi.from_buffer("double[]", out)
        ),
        "plane_from_points",
    )
    return out


def _check_polygon(v: npt.NDArray[np.float64], name: str, context: str, what: str) -> None:
    """The C helpers' checks of a polygon's vertices, in their order, naming
    the element: fewer than 3 vertices, then NaN or infinity."""
    detail = too_few(v.shape[0], 3, name, what)
    if detail is not None:
        raise error_for(int(lib.ISECT_E_ARG), context, detail=detail)
    detail = nonfinite_element(v, name)
    if detail is not None:
        raise error_for(int(lib.ISECT_E_NONFINITE), context, detail=detail)


def _check_area(status: int, context: str) -> None:
    """The status of a normal or plane through points: DEGENERATE said as
    what it is for them (zero area)."""
    if status == lib.ISECT_E_DEGENERATE:
        raise error_for(status, context, detail=(
            "vertices: the polygon has zero area (collinear or coincident vertices): "
            "no normal"))
    check(status, context, "vertices")


def _polygon_and_points(
    polygon: ArrayLike, points: ArrayLike
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], tuple[int, ...]]:
    """The (n, 2) polygon, the points flattened to (m, 2), and the points' batch shape."""
    poly = as_rows(polygon, 2, "polygon")
    pts = as_points(points, 2, "points")
    shape = pts.shape[:-1]
    return poly, np.ascontiguousarray(pts.reshape(-1, 2)), shape


def point_in_polygon(polygon: ArrayLike, points: ArrayLike, rule: Rule = "evenodd") -> Any:
    """Whether 2D points lie inside a polygon (``isect_point_in_polygon2_batch``).

    Exact, with the half-open rule: a point on an edge shared by two polygons
    of opposite orientation belongs to exactly one of them.

    Args:
        polygon: (n, 2) vertices, n >= 3.
        points: (..., 2).
        rule: "evenodd" or "nonzero".

    Returns:
        A bool array of shape (...), or a bool for one (2,) point.

    Raises:
        InvalidArgumentError: fewer than 3 vertices, an unknown rule, wrong shapes.
        NonFiniteError: NaN/Inf in the polygon, or in a point (``index``
            names the first).
    """
    poly, pts, shape = _polygon_and_points(polygon, points)
    r = as_rule(rule)
    if r not in _RULE_VALUES:  # the C order: the rule, then the polygon
        raise error_for(int(lib.ISECT_E_ARG), "point_in_polygon", detail=(
            f"rule = {r} is not a fill rule: 'evenodd' (ISECT_EVEN_ODD = "
            f"{int(lib.ISECT_EVEN_ODD)}) or 'nonzero' (ISECT_NONZERO = "
            f"{int(lib.ISECT_NONZERO)})"))
    _check_polygon(poly, "polygon", "point_in_polygon", "a polygon")
    inside = np.empty(pts.shape[0], dtype=np.uint8)
    pp = ffi.from_buffer("double[]", poly)
    qp = ffi.from_buffer("double[]", pts)
    check(
        lib.isect_point_in_polygon2_batch(
            pp, poly.shape[0], qp, pts.shape[0], r, ffi.from_buffer("uint8_t[]", inside)
        ),
        "point_in_polygon",
        "rule" if r not in _RULE_VALUES else "polygon",
    )
    bad = inside == lib.ISECT_INVALID
    if bad.any():
        i = int(bad.argmax())
        status = lib.isect_point_in_polygon2(pp, poly.shape[0], qp + 2 * i, r)
        raise_bad_element(status, "point_in_polygon", i, "point", "points",
                          point_problem(pts[i]))
    result = inside.view(np.bool_).reshape(shape)
    return bool(result) if shape == () else result


def winding_number(polygon: ArrayLike, points: ArrayLike) -> Any:
    """Integer winding number of a 2D polygon around points
    (``isect_winding_number2_batch``); counter-clockwise loops count +1.

    Args:
        polygon: (n, 2) vertices, n >= 3.
        points: (..., 2).

    Returns:
        An int32 array of shape (...), or an int for one (2,) point.

    Raises:
        InvalidArgumentError: fewer than 3 vertices, wrong shapes.
        NonFiniteError: NaN/Inf in the polygon, or in a point (``index``
            names the first).
    """
    poly, pts, shape = _polygon_and_points(polygon, points)
    _check_polygon(poly, "polygon", "winding_number", "a polygon")
    winding = np.empty(pts.shape[0], dtype=np.int32)
    pp = ffi.from_buffer("double[]", poly)
    qp = ffi.from_buffer("double[]", pts)
    check(
        lib.isect_winding_number2_batch(
            pp, poly.shape[0], qp, pts.shape[0], ffi.from_buffer("int32_t[]", winding)
        ),
        "winding_number",
        "polygon",
    )
    bad = winding == _INT32_MIN
    if bad.any():
        i = int(bad.argmax())
        status = lib.isect_winding_number2(pp, poly.shape[0], qp + 2 * i, ffi.new("int32_t *"))
        raise_bad_element(status, "winding_number", i, "point", "points", point_problem(pts[i]))
    result = winding.reshape(shape)
    return int(result) if shape == () else result
