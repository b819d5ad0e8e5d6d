#!/usr/bin/env python3
"""Benchmark of the Python package ``isect`` (a benchmark, not a test).

For a sphere and a triangle at N = 1e6 rays it measures, in one process:

* the C batch: ``isect_intersect_batch`` called directly through the
  extension (one call over a prepared ray array, into a fresh output array);
* the Python batch: ``shape.intersect_rays(rays)`` (the same rays, zero-copy)
  and ``shape.intersect(origins, directions)`` (which also packs the rays);
  target: at most 1.10x the C batch;
* a vectorised numpy implementation of the same closest-hit test, written
  here (quadratic formula for the sphere, Moller-Trumbore for the
  triangle); target: the library at least 10x faster;
* the per-call overhead of ``intersect_all`` for one ray: its time minus the
  C library's own time per ray for the same query (from a large
  ``isect_intersect_all_batch`` of that ray); target: at most 2 us.

Times are the best of several repetitions. Prints a table and writes
bench/results/python.json. Run: ``.venv/bin/python bench/python_bench.py``
(``--n`` and ``--repeat`` to change the size).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import time
import timeit
from collections.abc import Callable
from pathlib import Path
from typing import Any

import isect
import numpy as np
from isect._isect import ffi, lib

RESULTS = Path(__file__).resolve().parent / "results" / "python.json"
TARGET_BATCH_RATIO = 1.10
TARGET_NUMPY_SPEEDUP = 10.0
TARGET_OVERHEAD_US = 2.0


def ms(seconds: float) -> str:
    """A time in milliseconds, 9 characters wide."""
    return f"{seconds * 1e3:7.1f}ms"


def best_of(fn: Callable[[], Any], repeat: int) -> float:
    """Best wall time of ``repeat`` calls, in seconds."""
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best


# --------------------------------------------------------- numpy references


def numpy_sphere(
    org: np.ndarray, dirs: np.ndarray, center: np.ndarray, radius: float
) -> dict[str, np.ndarray]:
    """Closest hit t >= 0 of each ray with a sphere (inf on a miss), with the
    hit point and outward normal, vectorised with numpy."""
    oc = org - center
    a = np.einsum("ij,ij->i", dirs, dirs)
    b = np.einsum("ij,ij->i", oc, dirs)
    c = np.einsum("ij,ij->i", oc, oc) - radius * radius
    disc = b * b - a * c
    hit = disc >= 0
    sq = np.sqrt(np.where(hit, disc, 0.0))
    t0 = (-b - sq) / a
    t1 = (-b + sq) / a
    t = np.where(t0 >= 0, t0, t1)
    t = np.where(hit & (t >= 0), t, np.inf)
    point = org + t[:, None] * dirs
    normal = (point - center) / radius
    return {"t": t, "point": point, "normal": normal}


def numpy_triangle(
    org: np.ndarray, dirs: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray
) -> dict[str, np.ndarray]:
    """Closest hit t >= 0 of each ray with a triangle (Moller-Trumbore), with
    the hit point, normal and barycentrics, vectorised with numpy."""
    e1, e2 = b - a, c - a
    p = np.cross(dirs, e2)
    det = p @ e1
    ok = np.abs(det) > 1e-12 * np.linalg.norm(e1) * np.linalg.norm(e2) * np.linalg.norm(
        dirs, axis=1
    )
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = org - a
    u = np.einsum("ij,ij->i", s, p) * inv
    q = np.cross(s, e1)
    v = np.einsum("ij,ij->i", dirs, q) * inv
    t = (q @ e2) * inv
    hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0)
    t = np.where(hit, t, np.inf)
    point = org + np.where(hit, t, 0.0)[:, None] * dirs
    n = np.cross(e1, e2)
    normal = np.broadcast_to(n / np.linalg.norm(n), point.shape)
    return {"t": t, "point": point, "normal": normal, "uv": np.column_stack([u, v])}


# ------------------------------------------------------------------- scenes


def make_rays(
    n: int, target: np.ndarray, spread: float, seed: int
) -> tuple[np.ndarray, np.ndarray]:
    """Origins on a shell around the target, aimed at points near it
    (about half the rays hit)."""
    rng = np.random.default_rng(seed)
    org = rng.normal(size=(n, 3))
    org *= 10.0 / np.linalg.norm(org, axis=1)[:, None]
    org += target
    aim = target + rng.uniform(-spread, spread, size=(n, 3))
    return org, aim - org


def c_batch(shape: isect.Shape, rays: np.ndarray) -> np.ndarray:
    """isect_intersect_batch called directly: the C baseline."""
    hits = np.empty(len(rays), dtype=isect.HIT_DTYPE)
    count = lib.isect_intersect_batch(
        shape._c,
        ffi.from_buffer("isect_ray[]", rays),
        len(rays),
        ffi.NULL,
        ffi.from_buffer("isect_hit[]", hits),
    )
    assert count >= 0
    return hits


def bench_shape(
    name: str,
    shape: isect.Shape,
    org: np.ndarray,
    dirs: np.ndarray,
    reference: Callable[[], dict[str, np.ndarray]],
    repeat: int,
) -> dict[str, Any]:
    """All batch measurements for one shape."""
    rays = np.empty(len(org), dtype=isect.RAY_DTYPE)
    rays["org"], rays["dir"], rays["tmin"], rays["tmax"] = org, dirs, 0.0, np.inf

    lib_hits = shape.intersect_rays(rays)
    assert lib_hits.tobytes() == c_batch(shape, rays).tobytes()
    ref = reference()
    lib_hit = np.isfinite(lib_hits["t"])
    ref_hit = np.isfinite(ref["t"])
    both = lib_hit & ref_hit
    agree = float(np.mean(lib_hit == ref_hit))
    max_dt = float(np.max(np.abs(lib_hits["t"][both] - ref["t"][both]))) if both.any() else 0.0

    # Interleave the candidates so that machine noise hits them alike.
    times: dict[str, float] = {
        k: math.inf for k in ("c_batch", "py_rays", "py_intersect", "py_threads2", "numpy")
    }
    runs: dict[str, Callable[[], Any]] = {
        "c_batch": lambda: c_batch(shape, rays),
        "py_rays": lambda: shape.intersect_rays(rays),
        "py_intersect": lambda: shape.intersect(org, dirs),
        "py_threads2": lambda: shape.intersect_rays(rays, threads=2),
        "numpy": reference,
    }
    for _ in range(repeat):
        for key, fn in runs.items():
            times[key] = min(times[key], best_of(fn, 1))
    n = len(rays)
    return {
        "shape": name,
        "n": n,
        "hit_fraction": float(lib_hit.mean()),
        "c_batch_s": times["c_batch"],
        "python_intersect_rays_s": times["py_rays"],
        "python_intersect_s": times["py_intersect"],
        "python_intersect_rays_threads2_s": times["py_threads2"],
        "numpy_s": times["numpy"],
        "ratio_intersect_rays_vs_c": times["py_rays"] / times["c_batch"],
        "ratio_intersect_vs_c": times["py_intersect"] / times["c_batch"],
        "speedup_vs_numpy": times["numpy"] / times["py_rays"],
        "speedup_intersect_vs_numpy": times["numpy"] / times["py_intersect"],
        "mrays_per_s_python": n / times["py_rays"] / 1e6,
        "numpy_agreement_hit_mask": agree,
        "numpy_max_abs_dt": max_dt,
    }


def bench_overhead(
    name: str, shape: isect.Shape, origin: list[float], direction: list[float], repeat: int
) -> dict[str, Any]:
    """Per-call time of intersect_all for one ray, and the C library's own
    time for the same query (from a batch of 200000 copies of the ray)."""
    hits = shape.intersect_all(origin, direction)
    number = 100_000
    py_us = (
        min(
            timeit.repeat(
                lambda: shape.intersect_all(origin, direction), number=number, repeat=repeat
            )
        )
        / number
        * 1e6
    )
    n = 200_000
    rays = np.zeros(n, dtype=isect.RAY_DTYPE)
    rays["org"], rays["dir"], rays["tmax"] = origin, direction, np.inf
    offsets = np.empty(n + 1, dtype=np.int64)
    out = np.empty(n * max(1, len(hits)), dtype=isect.HIT_DTYPE)
    rp, op = ffi.from_buffer("isect_ray[]", rays), ffi.from_buffer("int64_t[]", offsets)
    hp = ffi.from_buffer("isect_hit[]", out)
    c_s = best_of(
        lambda: lib.isect_intersect_all_batch(shape._c, rp, n, ffi.NULL, op, hp, len(out)), repeat
    )
    c_us = c_s / n * 1e6
    return {
        "case": name,
        "hits": len(hits),
        "python_us": py_us,
        "c_us": c_us,
        "overhead_us": py_us - c_us,
    }


def main() -> None:
    """Run the benchmark, print the table, write the JSON."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, default=1_000_000, help="rays per batch (default 1e6)")
    parser.add_argument("--repeat", type=int, default=5, help="repetitions, best taken")
    parser.add_argument("--out", type=Path, default=RESULTS, help="JSON output file")
    args = parser.parse_args()

    center, radius = np.array([0.5, -0.25, 1.0]), 1.5
    sphere = isect.Sphere(center, radius)
    a, b, c = np.array([-1.0, -1, 0.5]), np.array([1.5, -1, 0.25]), np.array([0.0, 1.5, 0.75])
    triangle = isect.Triangle(a, b, c)
    s_org, s_dir = make_rays(args.n, center, 2.0, seed=1)
    t_org, t_dir = make_rays(args.n, (a + b + c) / 3, 1.2, seed=2)

    batches = [
        bench_shape(
            "sphere",
            sphere,
            s_org,
            s_dir,
            lambda: numpy_sphere(s_org, s_dir, center, radius),
            args.repeat,
        ),
        bench_shape(
            "triangle",
            triangle,
            t_org,
            t_dir,
            lambda: numpy_triangle(t_org, t_dir, a, b, c),
            args.repeat,
        ),
    ]
    overheads = [
        bench_overhead("sphere, 2 hits", sphere, [0.5, -0.25, -5.0], [0.0, 0.0, 1.0], args.repeat),
        bench_overhead("sphere, miss", sphere, [0.5, -0.25, -5.0], [0.0, 1.0, 0.0], args.repeat),
        bench_overhead("triangle, 1 hit", triangle, [0.0, 0.0, -5.0], [0.0, 0.0, 1.0], args.repeat),
    ]

    print(
        f"isect {isect.version()} Python {platform.python_version()} numpy {np.__version__}, "
        f"{os.cpu_count()} CPUs, N = {args.n:,}, best of {args.repeat}"
    )
    print()
    head = (
        f"{'shape':<9} {'C batch':>9} {'py rays':>9} {'ratio':>6} {'py o,d':>9} {'ratio':>6} "
        f"{'2 thr':>9} {'numpy':>9} {'speedup':>8} {'Mray/s':>7}"
    )
    print(head)
    print("-" * len(head))
    for r in batches:
        cells = [
            ms(r["c_batch_s"]),
            ms(r["python_intersect_rays_s"]),
            f"{r['ratio_intersect_rays_vs_c']:5.2f}x",
            ms(r["python_intersect_s"]),
            f"{r['ratio_intersect_vs_c']:5.2f}x",
            ms(r["python_intersect_rays_threads2_s"]),
            ms(r["numpy_s"]),
            f"{r['speedup_vs_numpy']:7.1f}x",
            f"{r['mrays_per_s_python']:7.1f}",
        ]
        print(f"{r['shape']:<9} " + " ".join(cells))
    print(
        "(py rays: intersect_rays on a RAY_DTYPE array; py o,d: intersect(origins, directions),"
        " which also packs the rays; ratio: vs the C batch; speedup: numpy time / py rays time)"
    )
    print()
    print(f"{'intersect_all, one ray':<24} {'python':>9} {'C':>9} {'overhead':>9}")
    for o in overheads:
        print(
            f"{o['case']:<24} {o['python_us']:7.2f}us {o['c_us']:7.2f}us {o['overhead_us']:7.2f}us"
        )

    checks = {
        "batch_ratio_le_1.10": all(
            r["ratio_intersect_rays_vs_c"] <= TARGET_BATCH_RATIO for r in batches
        ),
        "numpy_speedup_ge_10": all(r["speedup_vs_numpy"] >= TARGET_NUMPY_SPEEDUP for r in batches),
        "intersect_all_overhead_le_2us": all(
            o["overhead_us"] <= TARGET_OVERHEAD_US for o in overheads
        ),
    }
    print()
    for key, ok in checks.items():
        print(f"target {key}: {'met' if ok else 'NOT met'}")

    doc = {
        "benchmark": "bench/python_bench.py",
        "isect_version": isect.version(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "machine": {
            "platform": platform.platform(),
            "processor": platform.processor(),
            "cpus": os.cpu_count(),
        },
        "n": args.n,
        "repeat": args.repeat,
        "targets": {
            "batch_ratio_max": TARGET_BATCH_RATIO,
            "numpy_speedup_min": TARGET_NUMPY_SPEEDUP,
            "intersect_all_overhead_us_max": TARGET_OVERHEAD_US,
        },
        "batch": batches,
        "intersect_all_overhead": overheads,
        "targets_met": checks,
    }
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(f"\nwrote {args.out}")


if __name__ == "__main__":
    main()
