# SPDX-License-Identifier: Apache-2.0
"""Mesh.winding_number and the containment rules of Mesh.contains.

Expected values are worked out by hand (integers of closed shells, the
principal values 1/2, 1/4, 1/8 on a cube's face, edge and vertex, the
rectangle formula for the solid angle of a unit square on its axis) or come
from libigl's independent implementation (igl.winding_number).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import isect

#: The unit cube's corners (index x + 2y + 4z) and its quads, outward.
CORNERS = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float)
QUADS = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
TOP = 1


def cube(*, drop_top: bool = False, flip_top: bool = False, reverse: bool = False) -> isect.Mesh:
    faces = []
    for i, q in enumerate(QUADS):
        if i == TOP and drop_top:
            continue
        flip = reverse != (i == TOP and flip_top)
        faces.append(q[::-1] if flip else q)
    return isect.Mesh(CORNERS, faces)


def square_angle(z: float) -> float:
    """Signed solid angle of the unit top square (z = 1, normal +z) seen from
    (0.5, 0.5, z): positive from below (the rectangle formula)."""
    d = abs(1.0 - z)
    omega = 4.0 * math.asin(1.0 / (1.0 + 4.0 * d * d))
    return omega if z < 1.0 else -omega


def test_closed_cube_integers_and_principal_values() -> None:
    m = cube()
    w = m.winding_number([[0.5, 0.25, 0.75], [1.5, 0.5, 0.5], [0.5, 0.5, 1e-300]])
    assert w.tolist() == [1.0, 0.0, 1.0]
    assert cube(reverse=True).winding_number([0.5, 0.5, 0.5]) == -1.0
    on = m.winding_number([[0.5, 0.5, 0.0], [0.5, 0.0, 0.0], [0.0, 0.0, 0.0]])
    np.testing.assert_allclose(on, [0.5, 0.25, 0.125], rtol=0, atol=1e-14)


@pytest.mark.parametrize("accuracy", [None, 0.0, 1e-3])
def test_open_cube_on_axis(accuracy: float | None) -> None:
    m = cube(drop_top=True)
    zs = np.array([0.5, 0.25, 2.0**-40, -(2.0**-40), 0.999, 1.5, 1e6, -1e6, 3.0, -7.5] * 2)
    pts = np.column_stack([np.full_like(zs, 0.5), np.full_like(zs, 0.5), zs])
    want = [(1.0 if 0.0 < z < 1.0 else 0.0) - square_angle(z) / (4.0 * math.pi) for z in zs]
    got = m.winding_number(pts, accuracy)
    tol = 1e-13 if not accuracy else accuracy
    np.testing.assert_allclose(got, want, rtol=1e-13, atol=tol)
    assert m.winding_number([0.5, 0.5, 0.5]) == pytest.approx(5.0 / 6.0, abs=1e-14)


def test_rules() -> None:
    two = isect.Mesh(np.vstack([CORNERS * 3.0 - [1.0, 0.0, 0.0], CORNERS]),
                     QUADS + [[i + 8 for i in q] for q in QUADS])
    inner = [0.5, 0.5, 0.5]
    assert two.winding_number(inner) == 2.0
    assert not two.contains(inner)                  # even-odd: two crossings
    assert two.contains(inner, rule="nonzero")
    assert two.contains(inner, rule="winding")
    opened = cube(drop_top=True)
    assert opened.contains([[0.5, 0.5, 0.5], [0.5, 0.5, 0.999], [0.5, 0.5, 1.5]],
                           rule="winding").tolist() == [True, True, False]
    with pytest.raises(isect.InvalidArgumentError, match="closed"):
        opened.contains(inner)
    with pytest.raises(isect.InvalidArgumentError, match="consistently oriented"):
        cube(flip_top=True).contains(inner, rule="nonzero")
    # a closed mesh with one face turned over: parity still works, and the
    # generalized number is 1 - 2/6 at the centre
    flipped = cube(flip_top=True)
    assert flipped.contains(inner)
    assert flipped.winding_number(inner) == pytest.approx(2.0 / 3.0, abs=1e-14)
    with pytest.raises(isect.InvalidArgumentError, match="rule"):
        opened.contains(inner, rule="inside")


def test_mirrored_transform_negates() -> None:
    m = cube().transformed(np.diag([-1.0, 1.0, 1.0, 1.0]))
    assert m.winding_number([-0.5, 0.5, 0.5]) == -1.0
    assert m.contains([-0.5, 0.5, 0.5], rule="nonzero")
    assert not m.contains([-0.5, 0.5, 0.5], rule="winding")


def test_bad_input() -> None:
    m = cube(drop_top=True)
    with pytest.raises(isect.NonFiniteError) as err:
        m.winding_number([[0.5, 0.5, 0.5], [0.0, math.nan, 0.0]])
    assert err.value.index == 1
    with pytest.raises(isect.InvalidArgumentError):
        m.winding_number([0.5, 0.5, 0.5], -1.0)
    with pytest.raises(isect.InvalidArgumentError):
        m.winding_number([0.5, 0.5, 0.5], math.nan)
    with pytest.raises(isect.InvalidArgumentError):
        m.winding_number([0.5, 0.5, 0.5], "fine")  # type: ignore[arg-type]
    with pytest.raises(isect.InvalidArgumentError):
        m.winding_number([[0.5, 0.5]])


def soup(seed: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Random triangles: no topology at all."""
    rng = np.random.default_rng(seed)
    v = rng.uniform(-1.0, 1.0, (3 * n, 3))
    return v, np.arange(3 * n, dtype=np.int32).reshape(n, 3)


def test_soup_against_libigl_and_threads() -> None:
    igl = pytest.importorskip("igl")
    v, f = soup(5, 400)
    m = isect.Mesh(v, f)
    rng = np.random.default_rng(6)
    pts = rng.uniform(-1.5, 1.5, (9000, 3))
    w = m.winding_number(pts, threads=1)
    ref = igl.winding_number(v, f.astype(np.int64), pts)
    np.testing.assert_allclose(w, ref, rtol=0, atol=1e-11)
    assert np.array_equal(m.winding_number(pts, threads=2), w)  # the same bytes
    far = m.winding_number(pts, 1e-4, threads=2)
    assert np.abs(far - w).max() <= 1e-4
