# SPDX-License-Identifier: Apache-2.0
"""Polygon helpers and version queries: thin wrappers of the C functions."""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from ._args import ArrayLike, Rule, as_points, as_rows, as_rule
from ._errors import check
from ._isect import ffi, lib
from ._shape import raise_bad_element

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
    out = np.empty(3, dtype=np.float64)
    check(
        lib.isect_polygon_normal(
            ffi.from_buffer("double[]", v), v.shape[0], ffi.from_buffer("double[]", out)
        ),
        "polygon_normal",
        "vertices",
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
    out = np.empty(4, dtype=np.float64)
    check(
        lib.isect_plane_from_points(
            ffi.from_buffer("double[]", v), v.shape[0], ffi.from_buffer("double[]", out)
        ),
        "plane_from_points",
        "vertices",
    )
    return out


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
        raise_bad_element(status, "point_in_polygon", i, "point", "points")
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
        raise_bad_element(status, "winding_number", i, "point", "points")
    result = winding.reshape(shape)
    return int(result) if shape == () else result
