# SPDX-License-Identifier: Apache-2.0
"""threads= gives the same bytes as one thread (the default threads=None, all
cores, included); shapes are safe to share."""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

import isect
import numpy as np
import pytest
from isect import _args, _batch
from meshes import icosphere
from strategies import one_of_each

N = 40_000  # > MIN_CHUNK * 4, so 2..4 threads really split the batch


@pytest.fixture(scope="module")
def rays() -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(2024)
    origins = rng.normal(size=(N, 3)) * 3
    dirs = rng.normal(size=(N, 3))
    origins[123] = np.nan  # one bad ray, marked in every run
    return origins, dirs


SHAPES = one_of_each() + [
    isect.Box([-1, -1, -1], [1, 1, 1]).transformed(
        [[0.8, -0.6, 0, 1], [0.6, 0.8, 0, 0], [0, 0, 2, 0], [0, 0, 0, 1]]
    )
]


def test_chunks_cover_the_batch() -> None:
    """The split covers range(n) in order, once."""
    for n in (0, 1, 4095, 4096 * 3 + 7, 100_000):
        for threads in (1, 2, 3, 8):
            parts = _batch.chunks(n, threads)
            assert parts[0][0] == 0 and parts[-1][1] == n
            assert all(a[1] == b[0] for a, b in zip(parts, parts[1:]))
            assert len(parts) <= threads


@pytest.mark.parametrize("shape", SHAPES, ids=lambda s: type(s).__name__)
def test_threads_identical(shape: isect.Shape, rays: tuple[np.ndarray, np.ndarray]) -> None:
    """intersect, intersect_all_batch and contains: same bytes for 1..4 threads."""
    origins, dirs = rays
    one = shape.intersect(origins, dirs, errors="mark")
    offsets1, hits1 = shape.intersect_all_batch(origins, dirs, errors="mark")
    inside1 = (
        shape.contains(np.nan_to_num(origins))
        if isinstance(shape, isect.Solid)
        and not (isinstance(shape, isect.Cylinder) and not shape.capped)
        else None
    )
    for threads in (2, 3, 4):
        many = shape.intersect(origins, dirs, errors="mark", threads=threads)
        assert many.tobytes() == one.tobytes()
        offsets, hits = shape.intersect_all_batch(origins, dirs, errors="mark", threads=threads)
        assert offsets.tobytes() == offsets1.tobytes() and hits.tobytes() == hits1.tobytes()
        if inside1 is not None:
            inside = shape.contains(np.nan_to_num(origins), threads=threads)
            assert np.array_equal(inside, inside1)


def test_one_shape_many_python_threads(rays: tuple[np.ndarray, np.ndarray]) -> None:
    """One shape queried from many Python threads at once (batch and scalar
    calls interleaved) gives every thread the single-threaded answer."""
    origins, dirs = rays
    origins = np.nan_to_num(origins)[:5000]
    shape = isect.Polygon([[0, 0, 0], [2, 0, 0], [2, 2, 0], [1, 0.5, 0], [0, 2, 0]])
    expected = shape.intersect(origins, dirs[:5000])
    expected_all = [shape.intersect_all(o, d) for o, d in zip(origins[:200], dirs[:200])]

    def work(_: int) -> bool:
        ok = shape.intersect(origins, dirs[:5000]).tobytes() == expected.tobytes()
        again = [shape.intersect_all(o, d) for o, d in zip(origins[:200], dirs[:200])]
        return ok and again == expected_all

    with ThreadPoolExecutor(max_workers=6) as pool:
        assert all(pool.map(work, range(24)))


def test_threads_error_reporting_matches(rays: tuple[np.ndarray, np.ndarray]) -> None:
    """errors="raise" names the same first bad ray with or without threads."""
    origins, dirs = rays
    s = isect.Sphere([0, 0, 0], 1)
    for threads in (None, 2, 4):
        with pytest.raises(isect.NonFiniteError) as info:
            s.intersect(origins, dirs, threads=threads)
        assert info.value.index == 123


# ------------------------------------------- threads=None: every core


def test_default_threads_counts_the_usable_cores() -> None:
    """threads=None means the cores this process may run on."""
    expected = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    assert isect.default_threads() == max(1, expected or 1)
    assert _args.as_threads(None) == isect.default_threads()
    assert _args.as_threads(1) == 1


def _default_vs_one(shape: isect.Shape, origins: np.ndarray, dirs: np.ndarray) -> None:
    """The default (threads=None) gives the bytes of threads=1, for the
    closest hits, every hit (intersect_all_batch) and, for solids, contains."""
    one = shape.intersect(origins, dirs, errors="mark", threads=1)
    assert shape.intersect(origins, dirs, errors="mark").tobytes() == one.tobytes()
    rays = np.empty(len(origins), isect.RAY_DTYPE)
    rays["org"], rays["dir"], rays["tmin"], rays["tmax"] = origins, dirs, 0.0, np.inf
    assert shape.intersect_rays(rays, errors="mark").tobytes() == one.tobytes()
    offsets1, hits1 = shape.intersect_all_batch(origins, dirs, errors="mark", threads=1)
    offsets, hits = shape.intersect_all_batch(origins, dirs, errors="mark")
    assert offsets.tobytes() == offsets1.tobytes() and hits.tobytes() == hits1.tobytes()
    if isinstance(shape, isect.Solid):
        points = np.nan_to_num(origins)
        inside1 = shape.contains(points, threads=1)
        assert shape.contains(points).tobytes() == inside1.tobytes()


@pytest.fixture(params=["cores", "forced 4"])
def default_split(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> int:
    """threads=None as the machine has it, and forced to 4 threads (so the
    batch is really split on a machine of 1 or 2 cores too)."""
    if request.param == "forced 4":
        monkeypatch.setattr(_args, "default_threads", lambda: 4)
    return _args.as_threads(None)


def test_default_threads_bit_identical_sphere(
    default_split: int, rays: tuple[np.ndarray, np.ndarray]
) -> None:
    """A sphere: closest hits, every hit and contains, threads=None == 1."""
    assert len(_batch.chunks(N, default_split)) == min(default_split, N // _batch.MIN_CHUNK)
    _default_vs_one(isect.Sphere([0.1, -0.2, 0.3], 1.5), *rays)


def test_default_threads_bit_identical_mesh(
    default_split: int, rays: tuple[np.ndarray, np.ndarray]
) -> None:
    """A closed triangle mesh, plain and transformed, and its winding numbers."""
    v, f = icosphere(3, 2.0)
    mesh = isect.Mesh(v, f)
    origins, dirs = rays
    _default_vs_one(mesh, origins, dirs)
    _default_vs_one(mesh.transformed(np.diag([1.0, 2.0, 0.5, 1.0])), origins, dirs)
    points = np.nan_to_num(origins)
    open_mesh = isect.Mesh(v, f[: len(f) // 2])  # an open one: the summed winding numbers
    for m in (mesh, open_mesh):
        w1 = m.winding_number(points[:10_000], threads=1)
        assert m.winding_number(points[:10_000]).tobytes() == w1.tobytes()
    inside1 = open_mesh.contains(points, rule="winding", threads=1)
    assert open_mesh.contains(points, rule="winding").tobytes() == inside1.tobytes()
