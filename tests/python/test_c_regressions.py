# SPDX-License-Identifier: Apache-2.0
"""Regression tests for C library defects found by the property tests.

Each test pins one minimal case of a behaviour that disagrees with isect.h;
the expected values follow from the header and the accuracy contract alone
(and agree with the corresponding analytic shape or exact rationals).
"""

from __future__ import annotations

import math
from fractions import Fraction

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


# Four points, two of them equal, whose cross products all round to zero
# (np.cross(v0, v3) == 0 in doubles) but are not zero: the exact Newell
# normal of the given doubles is about 5e-17 long. By the accuracy contract
# (revision 2: right is the exact answer for the given doubles) this is a
# sliver with a well-defined plane, not a degenerate polygon.
COLLINEAR = np.array(
    [
        [-1.2785560344827585, 0.7306034482758621, 0.9741379310344828],
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [1.4482758620689653, -0.8275862068965517, -1.103448275862069],
    ]
)


def _exact_newell(v: np.ndarray) -> list[Fraction]:
    """sum over the fan from v0 of (v_i - v0) x (v_{i+1} - v0), in rationals."""
    p = [[Fraction(float(x)) for x in row] for row in v]
    n = [Fraction(0)] * 3
    for i in range(1, len(p) - 1):
        a = [p[i][k] - p[0][k] for k in range(3)]
        b = [p[i + 1][k] - p[0][k] for k in range(3)]
        n = [n[0] + a[1] * b[2] - a[2] * b[1], n[1] + a[2] * b[0] - a[0] * b[2],
             n[2] + a[0] * b[1] - a[1] * b[0]]
    return n


def test_sliver_polygon_normal_is_the_exact_one() -> None:
    """isect_polygon_normal of the sliver: the direction of the exact Newell
    normal (a rounded Newell sum would be 0, or noise in any direction)."""
    assert not np.any(np.cross(COLLINEAR[0], COLLINEAR[3]))
    exact = _exact_newell(COLLINEAR)
    length = math.sqrt(sum(float(x * x * Fraction(10) ** 34) for x in exact)) / 1e17
    want = np.array([float(x) / length for x in exact])
    got = isect.polygon_normal(COLLINEAR)
    assert np.linalg.norm(got - want) < 1e-15


def test_sliver_polygon_is_not_hit() -> None:
    """The ray crosses the sliver's plane outside the sliver (exact
    reference: tests/accuracy/reference.py gives no hit)."""
    d = [-0.23343211206896564, -0.024245689655172403, -0.03232758620689655]
    assert isect.Polygon(COLLINEAR).intersect_all([1.0, 0.0, 0.0], d) == []
