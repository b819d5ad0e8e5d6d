# SPDX-License-Identifier: Apache-2.0
"""The Python batch with threads, run under ThreadSanitizer by scripts/run_tsan.sh.

Not a pytest module (pytest collects ``test_*.py``): it runs in a CPython that
is not instrumented, with libtsan preloaded and the package's extension
``isect._isect`` compiled with ``-fsanitize=thread`` (mk/tsan.mk, target
``tsan-py``), so every access libisect and the extension's own C loops make
is checked. cffi releases the GIL around each C call, so the chunks of a
``threads=`` batch and the calls of concurrent Python threads run at the same
time in C; the GIL's mutex is seen by the sanitizer, so Python-side code
cannot hide a race in C behind it except across the C calls themselves.

Checks, on every shape type (meshes of triangles and of polygons, transformed
copies included): ``intersect`` (closest, any-hit, cull-back),
``intersect_rays``, ``intersect_all_batch``, ``contains`` and ``spawn`` with
``threads=`` 2..8 give the bytes of ``threads=1``; eight Python threads
sharing the shapes get the same bytes too. Prints ``N passed, N failed``.

``--race`` instead makes a deliberate race (two threads writing one output
buffer through the C batch call), so the caller can check that the sanitizer
is live in this process and reports it.
"""

from __future__ import annotations

import sys
import threading
from concurrent.futures import ThreadPoolExecutor

import isect
import numpy as np
from isect._isect import ffi, lib

N = 4 * 4096  # 4 chunks of MIN_CHUNK at threads=4


def shapes() -> list[isect.Shape]:
    """Every shape type, and each one transformed."""
    cube_v = [[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    cube_quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2],
                  [1, 3, 7, 5]]
    tets = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
    base: list[isect.Shape] = [
        isect.Plane([0.25, -0.5, 1], 0.125),
        isect.Sphere([0.1, -0.2, 0.05], 1.0),
        isect.Box([-1, -0.5, -0.75], [1, 0.5, 0.75]),
        isect.Triangle([-1, -1, 0], [1, -1, 0.5], [0, 1, -0.25]),
        isect.Polygon([[0, 0, 0], [2, 0, 0], [2, 2, 0], [1, 0.5, 0], [0, 2, 0]], "nonzero"),
        isect.ConvexPolyhedron([[sx, sy, sz, -1] for sx in (1, -1) for sy in (1, -1)
                                for sz in (1, -1)]),
        isect.Cylinder([0, 0, -1], [0.25, 0.5, 1], 0.75),
        isect.Cylinder([0, 0, -1], [0.25, 0.5, 1], 0.75, capped=False),
        isect.InfiniteCylinder([0.5, 0, 0], [0, 1, 0.5], 0.5),
        isect.Ellipsoid([0, 0.25, 0], [1.25, 0.5, 0.75]),
        isect.Quadric([1, 1, -1, 0, 0, 0, 0, 0, 0, -0.25]),
        isect.Mesh(cube_v, cube_quads),
        isect.Mesh([[0, 0, 0], [1.5, 0, 0], [0, 1.5, 0], [0, 0, 1.5]], tets),
    ]
    m = [[1.2, -0.45, 0.4, 0.25], [0.9, 0.6, -0.3, -0.5], [-0.3, 0.3, 0.9, 0.125], [0, 0, 0, 1]]
    return base + [s.transformed(m) for s in base]


def rays() -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(13)
    targets = rng.uniform(-1.5, 1.5, size=(N, 3))
    targets[::5] = rng.integers(-2, 3, size=targets[::5].shape) * 0.5  # lattice points
    dirs = rng.normal(size=(N, 3))
    origins = targets - 3.0 * dirs / np.linalg.norm(dirs, axis=1)[:, None]
    origins[1234] = np.nan  # one bad ray: INVALID with errors="mark"
    return origins, dirs


class Tally:
    def __init__(self) -> None:
        self.passed = 0
        self.failed = 0
        self.lock = threading.Lock()

    def check(self, ok: bool, what: str) -> None:
        with self.lock:
            if ok:
                self.passed += 1
            else:
                self.failed += 1
                print(f"FAILED: {what}", file=sys.stderr)


def results(shape: isect.Shape, origins: np.ndarray, dirs: np.ndarray,
            threads: int | None) -> list[bytes]:
    """Every batch kind of ``shape`` with ``threads``, as bytes."""
    out = [
        shape.intersect(origins, dirs, errors="mark", threads=threads),
        shape.intersect(origins, dirs, errors="mark", any_hit=True, threads=threads),
        shape.intersect(origins, dirs, errors="mark", cull_back=True, threads=threads),
    ]
    rays_ = np.zeros(N, dtype=isect.RAY_DTYPE)
    rays_["org"], rays_["dir"], rays_["tmax"] = origins, dirs, np.inf
    out.append(shape.intersect_rays(rays_, errors="mark", threads=threads))
    offsets, hits = shape.intersect_all_batch(origins, dirs, errors="mark", threads=threads)
    out += [offsets, hits]
    if isinstance(shape, isect.Solid) and not (
        isinstance(shape, isect.Cylinder) and not shape.capped
    ):
        out.append(shape.contains(np.nan_to_num(origins), threads=threads))
    closest = out[0]
    found = closest[(closest["kind"] >= 1) & (closest["kind"] <= 3)]
    if len(found):
        # Along the normal: in front of the surface, which every hit allows
        # (against it, a hit on a box edge has no inside offset: E_DEGENERATE).
        out.append(shape.spawn(found, found["normal"], threads=threads))
    return [np.ascontiguousarray(a).tobytes() for a in out]


def run() -> int:
    tally = Tally()
    origins, dirs = rays()
    all_shapes = shapes()
    reference = [results(s, origins, dirs, 1) for s in all_shapes]
    for s, ref in zip(all_shapes, reference):
        for threads in (2, 4, None):  # None: every core
            tally.check(results(s, origins, dirs, threads) == ref,
                        f"{s!r}: threads={threads} differs from threads=1")

    def python_thread(k: int) -> None:
        # Eight Python threads share the shapes: each runs a third of them,
        # starting at another one, so every shape is used by two or more
        # threads at once.
        for j in range(0, len(all_shapes), 3):
            i = (j + k) % len(all_shapes)
            got = results(all_shapes[i], origins, dirs, 2 if k % 2 else None)
            tally.check(got == reference[i], f"{all_shapes[i]!r}: Python thread {k} differs")

    with ThreadPoolExecutor(max_workers=8) as pool:
        list(pool.map(python_thread, range(8)))
    print(f"{len(all_shapes)} shapes, {N} rays, threads= 2, 4 and None, and 8 Python threads")
    print(f"{tally.passed} passed, {tally.failed} failed")
    return 1 if tally.failed else 0


def race() -> int:
    """Two threads write one output buffer through the C batch call at once."""
    sphere = isect.Sphere([0, 0, 0], 1)
    origins, dirs = rays()
    r = np.zeros(N, dtype=isect.RAY_DTYPE)
    r["org"], r["dir"], r["tmax"] = np.nan_to_num(origins), dirs, np.inf
    out = np.zeros(N, dtype=isect.HIT_DTYPE)
    rp = ffi.from_buffer("isect_ray[]", r)
    op = ffi.from_buffer("isect_hit[]", out)
    c = sphere._c
    barrier = threading.Barrier(2)

    def write() -> None:
        barrier.wait()
        for _ in range(3):
            lib.isect_intersect_batch(c, rp, N, ffi.NULL, op)

    threads = [threading.Thread(target=write) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    print("--race: two threads wrote one buffer")
    return 0


if __name__ == "__main__":
    sys.exit(race() if sys.argv[1:] == ["--race"] else run())
