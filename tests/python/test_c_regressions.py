"""Regression tests for C library defects found by the property tests.

Each test pins one minimal case of a behaviour that disagrees with isect.h;
the expected values follow from the header alone (and agree with the
corresponding analytic shape). They fail until the C library is fixed.
"""

from __future__ import annotations

import isect
import numpy as np
import pytest


@pytest.mark.parametrize("tiny", [1e-200, 1e-289, 4.9e-324])
def test_quadric_origin_with_tiny_coordinate(tiny: float) -> None:
    """quadric.c scales coordinates by the exponent of the largest origin
    coordinate; when that is tiny (|org| < ~1e-154, not 0) the quadratic
    coefficients underflow to 0 and the hit is lost. The unit sphere as a
    quadric must be hit like the Sphere: once, leaving at t = 1."""
    unit = isect.Quadric([1, 1, 1, 0, 0, 0, 0, 0, 0, -1])
    hits = unit.intersect_all([tiny, 0, 0], [0, 1, 0])
    sphere = isect.Sphere([0, 0, 0], 1).intersect_all([tiny, 0, 0], [0, 1, 0])
    assert [(h.t, h.kind) for h in sphere] == [(1.0, isect.HitKind.EXIT)]
    assert [(h.t, h.kind) for h in hits] == [(1.0, isect.HitKind.EXIT)]


# Four points, two of them equal, exactly collinear in double precision:
# v0 x v3 == (0, 0, 0) and the other cross products vanish too.
COLLINEAR = np.array(
    [
        [-1.2785560344827585, 0.7306034482758621, 0.9741379310344828],
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [1.4482758620689653, -0.8275862068965517, -1.103448275862069],
    ]
)


def test_collinear_polygon_normal_is_degenerate() -> None:
    """isect_polygon_normal: zero area must give ISECT_E_DEGENERATE; the
    centroid-relative Newell sum leaves rounding noise that is normalised
    into an arbitrary unit vector instead."""
    assert not np.any(np.cross(COLLINEAR[0], COLLINEAR[3]))
    with pytest.raises(isect.DegenerateError):
        isect.polygon_normal(COLLINEAR)


def test_collinear_polygon_is_never_hit() -> None:
    """A collinear polygon is degenerate and never hit; it is reported hit
    0.01 away from the line it lies on, on the noise plane."""
    d = [-0.23343211206896564, -0.024245689655172403, -0.03232758620689655]
    assert isect.Polygon(COLLINEAR).intersect_all([1.0, 0.0, 0.0], d) == []
