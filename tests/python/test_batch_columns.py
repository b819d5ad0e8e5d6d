# SPDX-License-Identifier: Apache-2.0
"""Shape.intersect packs separate origin / direction / tmin / tmax columns
in C (``_soa_columns`` and ``pyisect_closest_soa``) instead of building a
RAY_DTYPE array; its records must be those of ``intersect_rays`` on the
same rays, byte for byte, in every combination of one value and one per ray,
with threads, and for bad rays."""

from __future__ import annotations

import isect
import numpy as np
import pytest

RNG = np.random.default_rng(7)
N = 1000
ORG = RNG.normal(size=(N, 3)) * 3.0
DIR = -ORG + RNG.normal(size=(N, 3))
TMIN = RNG.uniform(0.0, 1.0, size=N)
TMAX = RNG.uniform(2.0, 9.0, size=N)
SHAPES = [
    isect.Sphere([0.1, 0.2, 0.3], 1.5),
    isect.Box([-1, -1, -1], [1, 2, 1]),
    isect.Triangle([-1, -1, 0], [1, -1, 0], [0, 1, 0]),
    isect.Cylinder([0, 0, -1], [0, 0, 1], 0.7, capped=True),
]


def reference(shape: isect.Shape, org, dirs, tmin, tmax) -> np.ndarray:
    """The same batch through an explicit RAY_DTYPE array."""
    shape_b = np.broadcast_shapes(np.shape(org)[:-1], np.shape(dirs)[:-1], np.shape(tmin),
                                  np.shape(tmax))
    rays = np.empty(shape_b, dtype=isect.RAY_DTYPE)
    rays["org"], rays["dir"], rays["tmin"], rays["tmax"] = org, dirs, tmin, tmax
    return shape.intersect_rays(rays, errors="mark")


@pytest.mark.parametrize("shape", SHAPES, ids=lambda s: type(s).__name__)
@pytest.mark.parametrize("one_org, one_dir, one_lo, one_hi",
                         [(False, False, True, True), (True, False, True, True),
                          (False, True, False, True), (False, False, False, False)])
@pytest.mark.parametrize("threads", [None, 3])
def test_columns_match_ray_records(shape, one_org, one_dir, one_lo, one_hi, threads) -> None:
    org = ORG[0] if one_org else ORG
    dirs = DIR[0] if one_dir else DIR
    lo = 0.0 if one_lo else TMIN
    hi = np.inf if one_hi else TMAX
    got = shape.intersect(org, dirs, tmin=lo, tmax=hi, threads=threads)
    want = reference(shape, org, dirs, lo, hi)
    assert got.shape == want.shape == (N,)
    assert got.tobytes() == want.tobytes()
    assert np.count_nonzero(got["kind"] != isect.HitKind.MISS) > 0


def test_strided_and_other_dtypes() -> None:
    """Non-contiguous and float32 columns are converted, not misread."""
    shape = SHAPES[0]
    org = np.repeat(ORG, 2, axis=0)[::2]
    dirs = DIR.astype(np.float32)
    got = shape.intersect(org, dirs)
    want = reference(shape, ORG, dirs.astype(np.float64), 0.0, np.inf)
    assert got.tobytes() == want.tobytes()


def test_bad_rays() -> None:
    """errors='mark' gives INVALID records where the rays are bad; the
    default raises for the first bad ray with its index."""
    shape = SHAPES[0]
    org = ORG.copy()
    org[17, 1] = np.nan
    dirs = DIR.copy()
    dirs[400] = 0.0
    marked = shape.intersect(org, dirs, errors="mark")
    assert marked["kind"][17] == isect.HitKind.INVALID
    assert marked["kind"][400] == isect.HitKind.INVALID
    assert marked.tobytes() == reference(shape, org, dirs, 0.0, np.inf).tobytes()
    with pytest.raises(isect.NonFiniteError) as info:
        shape.intersect(org, dirs)
    assert info.value.index == 17
    with pytest.raises(isect.DegenerateError) as info2:
        shape.intersect(ORG, dirs, threads=4)
    assert info2.value.index == 400
