#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Mesh benchmark of the Python package ``isect`` (a benchmark, not a test).

Closest hit of random rays on an 81920-triangle icosphere (6 subdivisions of
an icosahedron, built in numpy) through:

* ``isect.Mesh.intersect`` (float64; one thread, and ``--threads``);
* Embree through PyPI ``embreex`` (float32; ``EmbreeScene.run``, which runs
  on one thread: its user CPU time equals its wall time);
* trimesh's pure-numpy ``RayMeshIntersector`` (``trimesh.ray.ray_triangle``,
  rtree broad phase). It manages about 10^2 rays/s here, so it runs on the
  first ``--trimesh-rays`` rays only and its rate is reported per second.

Rays start on the sphere of radius 3 and aim at random points of the ball of
radius 1.15 (about 89% hit). Build times are for the acceleration structure
from the same numpy arrays. Times are the best of ``--repeat``. Prints a table
and writes bench/results/python_mesh.json. A library that is not installed is
skipped with a message. Run: ``.venv/bin/python bench/python_mesh_bench.py``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import isect
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
from meshes import icosphere  # noqa: E402  (test-mesh builder shared with the tests)

RESULTS = ROOT / "bench" / "results" / "python_mesh.json"


def best_of(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """Best wall time of ``repeat`` calls (seconds) and the last result."""
    best, out = math.inf, None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - start)
    return best, out


def make_rays(n: int, seed: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """n rays from the sphere of radius 3 towards the ball of radius 1.15 (float32-exact)."""
    rng = np.random.default_rng(seed)
    o = rng.normal(size=(n, 3))
    o *= 3 / np.linalg.norm(o, axis=1, keepdims=True)
    t = rng.normal(size=(n, 3))
    t *= 1.15 * rng.uniform(size=(n, 1)) ** (1 / 3) / np.linalg.norm(t, axis=1, keepdims=True)
    return o.astype(np.float32).astype(np.float64), (t - o).astype(np.float32).astype(np.float64)


def main() -> None:
    """Run the benchmark, print the table, write the JSON."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[100_000, 1_000_000])
    ap.add_argument("--subdivisions", type=int, default=6)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--trimesh-rays", type=int, default=1000)
    args = ap.parse_args()

    v, f = icosphere(args.subdivisions)
    v = v.astype(np.float32).astype(np.float64)
    v32, f32 = v.astype(np.float32), f.astype(np.int32)
    ntri = len(f)
    rows: list[dict[str, Any]] = []
    notes: list[str] = []

    build, mesh = best_of(lambda: isect.Mesh(v, f), args.repeat)
    builds = {"libisect": build}
    print(f"icosphere: {ntri} triangles; libisect mesh {mesh.nbytes / ntri:.1f} bytes/triangle")

    try:
        import embreex.mesh_construction as mc
        import embreex.rtcore_scene as rtcs

        def embree_build() -> Any:
            scene = rtcs.EmbreeScene()
            mc.TriangleMesh(scene, v32, f32)
            scene.run(np.zeros((1, 3), np.float32), np.ones((1, 3), np.float32))  # commit
            return scene

        builds["embreex"], scene = best_of(embree_build, args.repeat)
    except ImportError as exc:
        scene = None
        notes.append(f"embreex skipped: {exc}")
    try:
        import trimesh
        from trimesh.ray.ray_triangle import RayMeshIntersector

        def trimesh_build() -> Any:
            r = RayMeshIntersector(trimesh.Trimesh(v, f, process=False))
            r.mesh.triangles_tree  # the rtree broad phase, built lazily
            return r

        builds["trimesh"], tri = best_of(trimesh_build, 1)
        trimesh.util.log.setLevel("ERROR")
    except ImportError as exc:
        tri = None
        notes.append(f"trimesh skipped: {exc}")

    for n in args.sizes:
        origins, dirs = make_rays(n)
        o32, d32 = origins.astype(np.float32), dirs.astype(np.float32)
        runs: dict[str, tuple[float, int]] = {}
        t, hits = best_of(lambda: mesh.intersect(origins, dirs, threads=1), args.repeat)
        ref = hits["kind"] != isect.HitKind.MISS
        runs["libisect 1 thread"] = (t, n)
        t, _ = best_of(lambda: mesh.intersect(origins, dirs, threads=args.threads), args.repeat)
        runs[f"libisect {args.threads} threads"] = (t, n)
        if scene is not None:
            t, res = best_of(lambda: scene.run(o32, d32, output=1), args.repeat)
            runs["embreex (float32, 1 thread)"] = (t, n)
            agree = float(np.mean((res["geomID"] >= 0) == ref))
            notes.append(f"n={n}: embreex hit/miss agreement with libisect {agree:.6%}")
        if tri is not None and n == args.sizes[0]:  # its rate does not depend on n
            m = min(n, args.trimesh_rays)
            t, first = best_of(lambda: tri.intersects_first(origins[:m], dirs[:m]), 1)
            runs[f"trimesh numpy ({m} rays)"] = (t, m)
            agree = float(np.mean((first >= 0) == ref[:m]))
            notes.append(f"n={n}: trimesh hit/miss agreement on {m} rays {agree:.4%}")
        base = runs["libisect 1 thread"][1] / runs["libisect 1 thread"][0]
        for name, (seconds, count) in runs.items():
            rate = count / seconds
            rows.append(
                {
                    "rays": n,
                    "method": name,
                    "rays_timed": count,
                    "seconds": seconds,
                    "rays_per_s": rate,
                    "vs_libisect_1t": rate / base,
                }
            )

    print(f"{'rays':>9} {'method':<28} {'time':>10} {'rays/s':>10} {'vs libisect 1t':>15}")
    for r in rows:
        print(
            f"{r['rays']:>9} {r['method']:<28} {r['seconds'] * 1e3:8.1f}ms "
            f"{r['rays_per_s']:10.3g} {r['vs_libisect_1t']:14.3g}x"
        )
    print("build: " + ", ".join(f"{k} {s * 1e3:.1f} ms ({s / ntri * 1e9:.0f} ns/tri)" for k, s in builds.items()))
    for note in notes:
        print(note)

    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    RESULTS.write_text(
        json.dumps(
            {
                "triangles": ntri,
                "bytes_per_triangle": mesh.nbytes / ntri,
                "build_seconds": builds,
                "rows": rows,
                "notes": notes,
                "machine": {"platform": platform.platform(), "cpus": os.cpu_count(), "python": platform.python_version()},
                "isect": isect.__version__,
            },
            indent=2,
        )
        + "\n",
        encoding="utf-8",
    )
    print(f"wrote {RESULTS.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
