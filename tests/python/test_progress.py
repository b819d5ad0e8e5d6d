# SPDX-License-Identifier: Apache-2.0
"""progress=True: a progress display (tqdm, or a plain percentage without it)
that changes no byte of any batch result, with one thread or many."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from typing import Any

import isect
import numpy as np
import pytest
from isect import _batch, _progress
from meshes import icosphere

N = 30_000  # several chunks of MIN_CHUNK: the display has steps


@pytest.fixture(scope="module")
def rays() -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(7)
    return rng.normal(size=(N, 3)) * 3, rng.normal(size=(N, 3))


@pytest.fixture(scope="module")
def mesh() -> isect.Mesh:
    v, f = icosphere(2, 2.0)
    return isect.Mesh(v, f)


@pytest.fixture(params=["tqdm", "plain"])
def display(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """With tqdm, and as if tqdm were not installed (its import fails)."""
    if request.param == "tqdm":
        pytest.importorskip("tqdm.auto")
    else:
        monkeypatch.setitem(sys.modules, "tqdm", None)
        monkeypatch.setitem(sys.modules, "tqdm.auto", None)
        assert _progress._tqdm() is None
    yield request.param


def _batches(shape: isect.Shape, mesh: isect.Mesh, origins: np.ndarray,
             dirs: np.ndarray) -> dict[str, Callable[..., Any]]:
    """Every batch call that takes progress=, as f(**options) -> arrays."""
    points = np.nan_to_num(origins)
    rays = np.empty(len(origins), isect.RAY_DTYPE)
    rays["org"], rays["dir"], rays["tmin"], rays["tmax"] = origins, dirs, 0.0, np.inf
    hits = shape.intersect(origins, dirs, threads=1)
    found = hits[hits["kind"] != isect.HitKind.MISS]
    return {
        "intersect": lambda **kw: shape.intersect(origins, dirs, errors="mark", **kw),
        "intersect broadcast": lambda **kw: shape.intersect(origins[0], dirs, **kw),
        "intersect_rays": lambda **kw: shape.intersect_rays(rays, errors="mark", **kw),
        "intersect_all_batch": lambda **kw: shape.intersect_all_batch(origins, dirs, **kw),
        "contains": lambda **kw: shape.contains(points, **kw),
        "spawn": lambda **kw: shape.spawn(found, found["normal"], **kw),
        "mesh intersect": lambda **kw: mesh.intersect(origins, dirs, **kw),
        "mesh intersect_all_batch": lambda **kw: mesh.intersect_all_batch(origins, dirs, **kw),
        "mesh contains": lambda **kw: mesh.contains(points, **kw),
        "mesh contains winding": lambda **kw: mesh.contains(points, rule="winding", **kw),
        "mesh winding_number": lambda **kw: mesh.winding_number(points[:9000], **kw),
    }


def _bytes(result: Any) -> bytes:
    parts = result if isinstance(result, tuple) else (result,)
    return b"".join(np.ascontiguousarray(p).tobytes() for p in parts)


@pytest.mark.parametrize("threads", [1, 3, None])
def test_progress_changes_no_byte(
    threads: int | None, display: str, rays: tuple[np.ndarray, np.ndarray],
    mesh: isect.Mesh, capsys: pytest.CaptureFixture[str],
) -> None:
    """Each batch call gives the same bytes with and without a display, and
    the display reaches 100%."""
    shape = isect.Sphere([0.1, 0.2, -0.3], 1.5)
    for name, call in _batches(shape, mesh, *rays).items():
        plain = call(threads=1)
        capsys.readouterr()
        shown = call(threads=threads, progress=True)
        assert _bytes(shown) == _bytes(plain), name
        err = capsys.readouterr().err
        assert "100%" in err, (name, err)
        if display == "plain":
            assert err.endswith("\n") and err.count("\n") == 1, err


def test_plain_display_format(monkeypatch: pytest.MonkeyPatch,
                              capsys: pytest.CaptureFixture[str]) -> None:
    """Without tqdm: one stderr line rewritten at each whole percent."""
    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    sphere = isect.Sphere([0, 0, 0], 1)
    sphere.contains(np.zeros((5 * _batch.MIN_CHUNK, 3)), threads=1, progress=True)
    err = capsys.readouterr().err
    assert err.startswith("\rSphere.contains:   0% (0/20480 points)")
    assert err.endswith("\rSphere.contains: 100% (20480/20480 points)\n")
    assert [line.split(":")[0] for line in err.strip().split("\r")] == ["Sphere.contains"] * 6


def test_tqdm_display(capsys: pytest.CaptureFixture[str]) -> None:
    """With tqdm: its bar, named after the call, counting rays."""
    pytest.importorskip("tqdm.auto")
    sphere = isect.Sphere([0, 0, 0], 1)
    sphere.intersect(np.zeros((3 * _batch.MIN_CHUNK, 3)), [0, 0, 1], progress=True)
    err = capsys.readouterr().err
    assert "Sphere.intersect: 100%" in err and "ray/s" in err, err


def test_progress_chunks() -> None:
    """About PROGRESS_STEPS chunks of at least MIN_CHUNK (at least one per
    thread), covering the batch in order."""
    for n in (0, 1, 4095, 3 * 4096 + 7, 10**6):
        for threads in (1, 4, 300):
            parts = _batch.progress_chunks(n, threads)
            assert parts[0][0] == 0 and parts[-1][1] == n
            assert all(a[1] == b[0] for a, b in zip(parts, parts[1:]))
            assert len(parts) == 1 or min(hi - lo for lo, hi in parts) >= _batch.MIN_CHUNK
            assert len(parts) <= max(_batch.PROGRESS_STEPS, threads)
    assert len(_batch.progress_chunks(10**6, 2)) == _batch.PROGRESS_STEPS


def test_error_with_progress_closes_the_display(
    rays: tuple[np.ndarray, np.ndarray], capsys: pytest.CaptureFixture[str]
) -> None:
    """A bad ray still raises (naming the first bad ray) and the display is
    closed; the pool is usable afterwards."""
    origins, dirs = rays
    origins = origins.copy()
    origins[[20_000, 25_000], 0] = np.nan
    sphere = isect.Sphere([0, 0, 0], 1)
    for threads in (1, 3):
        with pytest.raises(isect.NonFiniteError) as info:
            sphere.intersect(origins, dirs, threads=threads, progress=True)
        assert info.value.index == 20_000
    assert "100%" in capsys.readouterr().err
    ok = sphere.intersect(np.nan_to_num(origins), dirs, threads=3, progress=True)
    assert ok.tobytes() == sphere.intersect(np.nan_to_num(origins), dirs, threads=1).tobytes()


def test_exception_in_a_chunk_is_raised_after_running_chunks_finish() -> None:
    """_batch.run with a display: the first exception of a chunk reaches the
    caller; the chunks not yet started are not run; the display is closed."""
    closed, seen = [], []

    class Recorder:
        def update(self, n: int) -> None:
            seen.append(n)

        def close(self) -> None:
            closed.append(True)

    def work(lo: int, hi: int) -> int:
        if lo >= 10 * _batch.MIN_CHUNK:
            raise KeyError(lo)
        return hi - lo

    with pytest.raises(KeyError):
        _batch.run(work, 100 * _batch.MIN_CHUNK, 3, Recorder())
    assert closed == [True] and sum(seen) <= 100 * _batch.MIN_CHUNK
    out = _batch.run(lambda lo, hi: (lo, hi), 100 * _batch.MIN_CHUNK, 3, Recorder())
    assert out == _batch.progress_chunks(100 * _batch.MIN_CHUNK, 3)


def test_progress_must_be_a_bool() -> None:
    """progress takes True or False; anything else names the argument."""
    sphere = isect.Sphere([0, 0, 0], 1)
    for value in (1, "yes", None):
        with pytest.raises(isect.InvalidArgumentError, match=r"\bprogress\b"):
            sphere.intersect([[0, 0, -5]], [0, 0, 1], progress=value)  # type: ignore[arg-type]
        with pytest.raises(isect.InvalidArgumentError, match=r"\bprogress\b"):
            sphere.contains([[0, 0, 0]], progress=value)  # type: ignore[arg-type]
