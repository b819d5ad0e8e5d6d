# SPDX-License-Identifier: Apache-2.0
"""Shape.bounds (isect_shape_bounds): conservative world boxes."""
from __future__ import annotations

import numpy as np

import isect


def _hit_points(shape: isect.Shape, center: np.ndarray, spread: float, n: int = 2000) -> np.ndarray:
    """The hit points of n rays from around center toward points near it."""
    rng = np.random.default_rng(5)
    org = center + 10 * spread * rng.uniform(-1, 1, (n, 3))
    target = center + spread * rng.uniform(-1, 1, (n, 3))
    hits = shape.intersect(org, target - org)
    return hits["point"][hits["kind"] != isect.HitKind.MISS]


def test_sphere_box_is_its_extent_widened_by_rounding_only() -> None:
    lo, hi = isect.Sphere([1.0, -2.0, 0.5], 0.75).bounds()
    assert lo.dtype == np.float64 and lo.shape == (3,)
    np.testing.assert_array_less(lo, [0.25, -2.75, -0.25 + 1e-300])
    assert np.all(lo <= [0.25, -2.75, -0.25]) and np.all(hi >= [1.75, -1.25, 1.25])
    assert np.all(np.abs(lo - [0.25, -2.75, -0.25]) < 1e-11)
    assert np.all(np.abs(hi - [1.75, -1.25, 1.25]) < 1e-11)


def test_hits_of_transformed_shapes_lie_in_their_boxes() -> None:
    m = np.array([[0.0, -2.0, 0.5, 10.0], [1.5, 0.0, 0.0, -4.0], [0.25, 0.0, 3.0, 7.0], [0, 0, 0, 1]])
    shapes = [
        isect.Sphere([0.0, 0.0, 0.0], 1.0),
        isect.Box([-1.0, -0.5, 0.0], [1.0, 0.5, 2.0]),
        isect.Cylinder([0.0, 0.0, -1.0], [0.0, 0.5, 1.0], 0.5, capped=True),
        isect.Triangle([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.5]),
    ]
    for shape in shapes:
        placed = shape.transformed(m)
        lo, hi = placed.bounds()
        center = (lo + hi) / 2
        points = _hit_points(placed, center, float(np.max(hi - lo)))
        assert len(points) > 30
        assert np.all(points >= lo) and np.all(points <= hi), type(shape).__name__


def test_unbounded_and_mesh_boxes() -> None:
    lo, hi = isect.Plane([0.0, 0.0, 1.0], -2.0).bounds()
    assert np.all(np.isneginf(lo)) and np.all(np.isposinf(hi))
    verts = np.array([[0, 0, 0], [2, 0, 0], [0, 3, 0], [0, 0, 4]], dtype=float)
    faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    lo, hi = isect.Mesh(verts, faces).bounds()
    assert np.all(lo <= 0) and np.all(lo > -1e-10)
    assert np.all(hi >= [2, 3, 4]) and np.all(hi < np.array([2, 3, 4]) + 1e-10)
