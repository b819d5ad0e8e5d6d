# SPDX-License-Identifier: Apache-2.0
"""Every class of bad input raises the documented exception.

The table pairs a call with the exception class the Python API documents for
it; errors found by libisect arrive through the one status table
(isect._errors.STATUS_ERRORS), errors found in Python (shapes of arrays, option
values) use the class of the matching C status.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import isect
import numpy as np
import pytest

NAN, INF = math.nan, math.inf
S = isect.Sphere([0, 0, 0], 1.0)
TRI = isect.Triangle([0, 0, 0], [1, 0, 0], [0, 1, 0])
SQ2 = [[0, 0], [1, 0], [1, 1], [0, 1]]
ORG, DIR = [0.0, 0.0, -5.0], [0.0, 0.0, 1.0]

E_ARG = isect.InvalidArgumentError
E_NONFINITE = isect.NonFiniteError
E_DEGENERATE = isect.DegenerateError

CASES: list[tuple[str, Callable[[], Any], type[isect.IsectError]]] = [
    # --- bad rays: scalar call, batch (raise), batch of all hits
    ("nan origin", lambda: S.intersect_all([NAN, 0, 0], DIR), E_NONFINITE),
    ("inf direction", lambda: S.intersect_all(ORG, [0, INF, 1]), E_NONFINITE),
    ("nan tmin", lambda: S.intersect_all(ORG, DIR, tmin=NAN), E_NONFINITE),
    ("nan tmax", lambda: S.intersect_all(ORG, DIR, tmax=NAN), E_NONFINITE),
    ("zero direction", lambda: S.intersect_all(ORG, [0, 0, 0]), E_DEGENERATE),
    ("batch nan origin", lambda: S.intersect([[NAN, 0, 0]], DIR), E_NONFINITE),
    ("batch zero direction", lambda: S.intersect(ORG, [[0, 0, 1], [0, 0, 0]]), E_DEGENERATE),
    ("batch nan tmin", lambda: S.intersect(ORG, DIR, tmin=[0.0, NAN]), E_NONFINITE),
    ("all-batch inf origin", lambda: S.intersect_all_batch([[INF, 0, 0]], DIR), E_NONFINITE),
    ("rays array nan", lambda: S.intersect_rays(np.full(2, np.nan, isect.RAY_DTYPE)), E_NONFINITE),
    # --- ray arguments of the wrong shape or type
    ("origin of 2 numbers", lambda: S.intersect_all([0, 0], DIR), E_ARG),
    ("origin of 4 numbers", lambda: S.intersect_all([0, 0, 0, 0], DIR), E_ARG),
    ("origin not numbers", lambda: S.intersect_all("abc", DIR), E_ARG),
    ("tmin not a number", lambda: S.intersect_all(ORG, DIR, tmin="x"), E_ARG),  # type: ignore[arg-type]
    ("batch origins (n, 2)", lambda: S.intersect(np.zeros((5, 2)), DIR), E_ARG),
    ("batch scalar origin", lambda: S.intersect(1.0, DIR), E_ARG),
    (
        "batch shapes do not broadcast",
        lambda: S.intersect(np.zeros((4, 3)), np.ones((5, 3))),
        E_ARG,
    ),
    (
        "batch tmin does not broadcast",
        lambda: S.intersect(np.zeros((4, 3)), DIR, tmin=[0, 1]),
        E_ARG,
    ),
    ("rays of another dtype", lambda: S.intersect_rays(np.zeros((4, 8))), E_ARG),
    # --- options
    ("negative eps", lambda: S.intersect_all(ORG, DIR, eps=-1e-9), E_ARG),
    ("nan eps", lambda: S.intersect_all(ORG, DIR, eps=NAN), E_NONFINITE),
    ("inf eps batch", lambda: S.intersect(ORG, DIR, eps=INF), E_NONFINITE),
    ("eps not a number", lambda: S.intersect(ORG, DIR, eps="big"), E_ARG),  # type: ignore[arg-type]
    ("errors unknown", lambda: S.intersect(ORG, DIR, errors="ignore"), E_ARG),
    ("threads zero", lambda: S.intersect(ORG, DIR, threads=0), E_ARG),
    ("threads float", lambda: S.intersect(ORG, DIR, threads=2.5), E_ARG),  # type: ignore[arg-type]
    ("threads bool", lambda: S.intersect(ORG, DIR, threads=True), E_ARG),
    # --- shapes: C validation at construction
    ("negative radius", lambda: isect.Sphere([0, 0, 0], -1), E_ARG),
    ("nan center", lambda: isect.Sphere([NAN, 0, 0], 1), E_NONFINITE),
    ("inf radius", lambda: isect.Sphere([0, 0, 0], INF), E_NONFINITE),
    ("box lo > hi", lambda: isect.Box([1, 0, 0], [0, 1, 1]), E_ARG),
    ("plane nan d", lambda: isect.Plane([0, 0, 1], NAN), E_NONFINITE),
    ("triangle inf vertex", lambda: isect.Triangle([0, 0, INF], [1, 0, 0], [0, 1, 0]), E_NONFINITE),
    ("polygon of 2 vertices", lambda: isect.Polygon([[0, 0, 0], [1, 0, 0]]), E_ARG),
    ("polygon of 0 vertices", lambda: isect.Polygon(np.zeros((0, 3))), E_ARG),
    ("polygon rule unknown name", lambda: isect.Polygon(np.eye(3), rule="winding"), E_ARG),
    ("polygon rule unknown int", lambda: isect.Polygon(np.eye(3), rule=7), E_ARG),
    ("polygon rule beyond int32", lambda: isect.Polygon(np.eye(3), rule=2**40), E_ARG),
    ("polygon vertices (n, 2)", lambda: isect.Polygon(np.zeros((4, 2))), E_ARG),
    ("convex without planes", lambda: isect.ConvexPolyhedron(np.zeros((0, 4))), E_ARG),
    ("convex nan plane", lambda: isect.ConvexPolyhedron([[0, 0, 1, NAN]]), E_NONFINITE),
    ("cylinder negative radius", lambda: isect.Cylinder([0, 0, 0], [0, 0, 1], -0.5), E_ARG),
    ("cylinder capped flag 2", lambda: isect.Cylinder([0, 0, 0], [0, 0, 1], 1, capped=2), E_ARG),
    (
        "infinite cylinder nan axis",
        lambda: isect.InfiniteCylinder([0, 0, 0], [NAN, 0, 1], 1),
        E_NONFINITE,
    ),
    ("ellipsoid negative radius", lambda: isect.Ellipsoid([0, 0, 0], [1, -1, 1]), E_ARG),
    ("quadric of 9 coefficients", lambda: isect.Quadric(np.ones(9)), E_ARG),
    ("quadric inf coefficient", lambda: isect.Quadric([INF] + [0] * 9), E_NONFINITE),
    ("center of 2 numbers", lambda: isect.Sphere([0, 0], 1), E_ARG),
    ("radius an array", lambda: isect.Sphere([0, 0, 0], [1, 2]), E_ARG),  # type: ignore[arg-type]
    # --- transforms
    ("singular transform", lambda: S.transformed(np.diag([1.0, 0.0, 1.0, 1.0])), E_DEGENERATE),
    ("last row not 0 0 0 1", lambda: S.transformed(np.full((4, 4), 1.0) + np.eye(4)), E_ARG),
    ("nan in transform", lambda: S.transformed(np.where(np.eye(4) > 0, NAN, 0.0)), E_NONFINITE),
    ("transform 3x3", lambda: S.transformed(np.eye(3)), E_ARG),
    # --- contains
    ("contains nan point", lambda: S.contains([[0, 0, 0], [NAN, 0, 0]]), E_NONFINITE),
    (
        "contains open cylinder",
        lambda: isect.Cylinder([0, 0, 0], [0, 0, 1], 1, capped=False).contains([0, 0, 0]),
        E_ARG,
    ),
    ("contains points (n, 2)", lambda: S.contains(np.zeros((3, 2))), E_ARG),
    # --- helpers
    (
        "polygon_normal collinear",
        lambda: isect.polygon_normal([[0, 0, 0], [1, 1, 1], [2, 2, 2]]),
        E_DEGENERATE,
    ),
    ("polygon_normal 2 vertices", lambda: isect.polygon_normal([[0, 0, 0], [1, 1, 1]]), E_ARG),
    (
        "plane_from_points collinear",
        lambda: isect.plane_from_points([[0, 0, 0], [1, 0, 0], [2, 0, 0]]),
        E_DEGENERATE,
    ),
    (
        "point_in_polygon 2 vertices",
        lambda: isect.point_in_polygon([[0, 0], [1, 0]], [0, 0]),
        E_ARG,
    ),
    ("point_in_polygon bad rule", lambda: isect.point_in_polygon(SQ2, [0.5, 0.5], rule=5), E_ARG),
    (
        "point_in_polygon nan point",
        lambda: isect.point_in_polygon(SQ2, [[0, 0], [NAN, 0]]),
        E_NONFINITE,
    ),
    (
        "point_in_polygon nan vertex",
        lambda: isect.point_in_polygon([[NAN, 0], [1, 0], [1, 1]], [0, 0]),
        E_NONFINITE,
    ),
    ("winding_number inf point", lambda: isect.winding_number(SQ2, [INF, 0]), E_NONFINITE),
    ("winding_number points (n, 3)", lambda: isect.winding_number(SQ2, np.zeros((2, 3))), E_ARG),
]


@pytest.mark.parametrize(("call", "error"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_input_raises(call: Callable[[], Any], error: type[isect.IsectError]) -> None:
    """The call raises exactly the documented class, carrying its C status."""
    with pytest.raises(isect.IsectError) as info:
        call()
    assert type(info.value) is error, f"{type(info.value).__name__}: {info.value}"
    assert info.value.status == error.status


def test_hierarchy() -> None:
    """IsectError is the base; the input errors are also ValueErrors."""
    for cls in (isect.InvalidArgumentError, isect.NonFiniteError, isect.DegenerateError):
        assert issubclass(cls, isect.IsectError) and issubclass(cls, ValueError)
    assert issubclass(isect.OutOfMemoryError, MemoryError)
    assert issubclass(isect.IsectError, Exception) and not issubclass(isect.IsectError, ValueError)


def test_error_names_the_first_bad_ray() -> None:
    """The batch error names the first bad ray's flat index, in the message
    and in ``.index``, for each batch entry point."""
    origins = np.tile(ORG, (10, 1))
    origins[[4, 7], 1] = np.inf
    for call in (
        lambda: S.intersect(origins, DIR),
        lambda: S.intersect(origins, DIR, threads=3),
        lambda: S.intersect_all_batch(origins, DIR),
        lambda: S.contains(origins),
    ):
        with pytest.raises(isect.NonFiniteError, match=r"\b4\b") as info:
            call()
        assert info.value.index == 4


def test_nothing_leaks_after_errors() -> None:
    """A failed call leaves the shape usable and the per-thread buffers sane."""
    with pytest.raises(isect.NonFiniteError):
        S.intersect_all([NAN, 0, 0], DIR)
    assert [h.t for h in S.intersect_all(ORG, DIR)] == [4.0, 6.0]
    assert TRI.intersect_all([0.2, 0.2, 1], [0, 0, -1])[0].uv == pytest.approx((0.2, 0.2))
