#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
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
* one ray, for one shape of every class (and transformed ones): the time of
  a call of ``shape.intersect(origin, direction)`` (target: at most 3 us) and
  of ``shape.intersect_all(origin, direction)`` (target: at most 2 us), with
  origin and direction lists of 3 floats, and each one's overhead: its time
  minus the C library's own time per ray for the same query (from a large
  ``isect_intersect_batch`` / ``isect_intersect_all_batch`` of that ray).

Batch times are the best of several repetitions; one-ray times are medians
of ``--repeat`` timeit runs of ``--number`` calls. Prints the tables and writes
bench/results/python.json. Run: ``.venv/bin/python bench/python_bench.py``
(``--n`` and ``--repeat`` to change the size, ``--one-ray`` for the one-ray
table alone).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import sys
import time
import timeit
from collections.abc import Callable
from pathlib import Path
from typing import Any

import isect
import numpy as np
from isect._isect import ffi, lib

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
from meshes import icosphere  # noqa: E402  (test-mesh builder shared with the tests)

RESULTS = ROOT / "bench" / "results" / "python.json"
TARGET_BATCH_RATIO = 1.10
TARGET_NUMPY_SPEEDUP = 10.0
TARGET_INTERSECT_US = 3.0
TARGET_INTERSECT_ALL_US = 2.0


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
        "py_rays": lambda: shape.intersect_rays(rays, threads=1),
        "py_intersect": lambda: shape.intersect(org, dirs, threads=1),
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


def one_ray_cases() -> list[tuple[str, isect.Shape, list[float], list[float]]]:
    """A shape of every class, and transformed ones, each with one ray that
    hits it (twice for solids), plus a miss: (name, shape, origin, direction)."""
    turn = np.array(
        [[0.8, -0.6, 0.0, 1.0], [0.6, 0.8, 0.0, -2.0], [0.0, 0.0, 2.0, 0.5], [0.0, 0.0, 0.0, 1.0]]
    )
    sphere = isect.Sphere([0, 0, 0], 1.0)
    ball = isect.Mesh(*icosphere(2))  # 320 triangles
    cube = [
        [1, 0, 0, -1],
        [-1, 0, 0, -1],
        [0, 1, 0, -1],
        [0, -1, 0, -1],
        [0, 0, 1, -1],
        [0, 0, -1, -1],
    ]
    return [
        ("Plane", isect.Plane([0, 0, 1], -0.5), [0.1, 0.2, -5.0], [0.0, 0.0, 1.0]),
        ("Sphere", sphere, [0.0, 0.0, -5.0], [0.0, 0.0, 1.0]),
        ("Sphere, miss", sphere, [0.0, 0.0, -5.0], [0.0, 1.0, 0.0]),
        ("Box", isect.Box([-1, -2, -3], [1, 2, 3]), [0.1, 0.2, -5.0], [0.0, 0.0, 1.0]),
        (
            "Triangle",
            isect.Triangle([-2, -2, 0], [2, -2, 0], [0, 2, 0]),
            [0.1, 0.2, -5.0],
            [0.0, 0.0, 1.0],
        ),
        (
            "Polygon",
            isect.Polygon([[-1.0, -1, 0], [1.0, -1, 0], [1.0, 1, 0], [0.0, 0.2, 0], [-1.0, 1, 0]]),
            [0.1, -0.2, -5.0],
            [0.0, 0.0, 1.0],
        ),
        ("ConvexPolyhedron", isect.ConvexPolyhedron(cube), [0.1, 0.2, -5.0], [0.0, 0.0, 1.0]),
        (
            "Cylinder",
            isect.Cylinder([0, 0, -1], [0, 0, 1], 0.5),
            [-5.0, 0.1, 0.2],
            [1.0, 0.0, 0.0],
        ),
        (
            "InfiniteCylinder",
            isect.InfiniteCylinder([0, 0, 0], [0, 1, 0], 0.75),
            [-5.0, 0.1, 0.2],
            [1.0, 0.0, 0.0],
        ),
        ("Ellipsoid", isect.Ellipsoid([0, 0, 0], [1, 2, 0.5]), [0.1, 0.2, -5.0], [0.0, 0.0, 1.0]),
        (
            "Quadric",
            isect.Quadric([1, 1, 1, 0, 0, 0, 0, 0, 0, -1]),
            [0.1, 0.2, -5.0],
            [0.0, 0.0, 1.0],
        ),
        ("Mesh (320 triangles)", ball, [0.1, 0.2, -5.0], [0.0, 0.0, 1.0]),
        ("Sphere, transformed", sphere.transformed(turn), [1.1, -1.8, -5.0], [0.0, 0.0, 1.0]),
        ("Mesh, transformed", ball.transformed(turn), [1.1, -1.8, -5.0], [0.0, 0.0, 1.0]),
    ]


def per_call_us(fn: Callable[[], Any], number: int, repeat: int) -> float:
    """Median over ``repeat`` timeit runs of the time of one call, in us."""
    return statistics.median(timeit.repeat(fn, number=number, repeat=repeat)) / number * 1e6


def c_one_ray_us(
    shape: isect.Shape, origin: list[float], direction: list[float], hits: int, repeat: int
) -> tuple[float, float]:
    """The C library's own time per ray for the closest hit and for all hits
    of one ray: a batch of 100000 copies of it, best of ``repeat``, in us."""
    n = 100_000
    rays = np.zeros(n, dtype=isect.RAY_DTYPE)
    rays["org"], rays["dir"], rays["tmax"] = origin, direction, np.inf
    rp = ffi.from_buffer("isect_ray[]", rays)
    closest = np.empty(n, dtype=isect.HIT_DTYPE)
    cp = ffi.from_buffer("isect_hit[]", closest)
    offsets = np.empty(n + 1, dtype=np.int64)
    op = ffi.from_buffer("int64_t[]", offsets)
    out = np.empty(n * max(1, hits), dtype=isect.HIT_DTYPE)
    hp = ffi.from_buffer("isect_hit[]", out)
    closest_s = best_of(lambda: lib.isect_intersect_batch(shape._c, rp, n, ffi.NULL, cp), repeat)
    all_s = best_of(
        lambda: lib.isect_intersect_all_batch(shape._c, rp, n, ffi.NULL, op, hp, len(out)),
        repeat,
    )
    return closest_s / n * 1e6, all_s / n * 1e6


def bench_one_ray(
    name: str,
    shape: isect.Shape,
    origin: list[float],
    direction: list[float],
    number: int,
    repeat: int,
) -> dict[str, Any]:
    """Per-call times of intersect and intersect_all for one ray (medians),
    and the C library's own time for the same queries."""
    hits = shape.intersect_all(origin, direction)
    record = shape.intersect(origin, direction)
    assert isinstance(record, np.void) and record.dtype == isect.HIT_DTYPE
    closest_c, all_c = c_one_ray_us(shape, origin, direction, len(hits), repeat)
    intersect_us = per_call_us(lambda: shape.intersect(origin, direction), number, repeat)
    all_us = per_call_us(lambda: shape.intersect_all(origin, direction), number, repeat)
    return {
        "case": name,
        "hits": len(hits),
        "intersect_us": intersect_us,
        "intersect_c_us": closest_c,
        "intersect_overhead_us": intersect_us - closest_c,
        "intersect_all_us": all_us,
        "intersect_all_c_us": all_c,
        "intersect_all_overhead_us": all_us - all_c,
    }


def print_one_ray(rows: list[dict[str, Any]]) -> None:
    """The one-ray table."""
    head = (
        f"{'one ray':<22} {'hits':>4} {'intersect':>10} {'C':>7} {'overhead':>9}"
        f" {'int._all':>10} {'C':>7} {'overhead':>9}"
    )
    print(head)
    print("-" * len(head))
    for o in rows:
        print(
            f"{o['case']:<22} {o['hits']:>4} {o['intersect_us']:8.2f}us"
            f" {o['intersect_c_us']:5.2f}us {o['intersect_overhead_us']:7.2f}us"
            f" {o['intersect_all_us']:8.2f}us"
            f" {o['intersect_all_c_us']:5.2f}us {o['intersect_all_overhead_us']:7.2f}us"
        )
    print(
        f"(medians per call; origin and direction lists of 3 floats; targets: intersect <= "
        f"{TARGET_INTERSECT_US} us, intersect_all <= {TARGET_INTERSECT_ALL_US} us per call; "
        "C: the library's own time per ray, from a batch of copies of the ray)"
    )


def main() -> None:
    """Run the benchmark, print the table, write the JSON."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, default=1_000_000, help="rays per batch (default 1e6)")
    parser.add_argument(
        "--repeat",
        type=int,
        default=5,
        help="repetitions (best of for batches, median for one ray)",
    )
    parser.add_argument(
        "--number", type=int, default=50_000, help="calls per one-ray timing run (default 5e4)"
    )
    parser.add_argument("--one-ray", action="store_true", help="only the one-ray table")
    parser.add_argument("--out", type=Path, default=RESULTS, help="JSON output file")
    args = parser.parse_args()

    one_ray = [
        bench_one_ray(name, shape, o, d, args.number, args.repeat)
        for name, shape, o, d in one_ray_cases()
    ]
    batches = [] if args.one_ray else bench_batches(args.n, args.repeat)

    print(
        f"isect {isect.version()} Python {platform.python_version()} numpy {np.__version__}, "
        f"{os.cpu_count()} CPUs, N = {args.n:,}, repeat {args.repeat}"
    )
    if batches:
        print()
        print_batches(batches)
    print()
    print_one_ray(one_ray)

    checks = {
        f"intersect_one_ray_le_{TARGET_INTERSECT_US:g}us": all(
            o["intersect_us"] <= TARGET_INTERSECT_US for o in one_ray
        ),
        f"intersect_all_one_ray_le_{TARGET_INTERSECT_ALL_US:g}us": all(
            o["intersect_all_us"] <= TARGET_INTERSECT_ALL_US for o in one_ray
        ),
    }
    if batches:
        checks["batch_ratio_le_1.10"] = all(
            r["ratio_intersect_rays_vs_c"] <= TARGET_BATCH_RATIO for r in batches
        )
        checks["numpy_speedup_ge_10"] = all(
            r["speedup_vs_numpy"] >= TARGET_NUMPY_SPEEDUP for r in batches
        )
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
        "number": args.number,
        "targets": {
            "batch_ratio_max": TARGET_BATCH_RATIO,
            "numpy_speedup_min": TARGET_NUMPY_SPEEDUP,
            "intersect_one_ray_us_max": TARGET_INTERSECT_US,
            "intersect_all_one_ray_us_max": TARGET_INTERSECT_ALL_US,
        },
        "batch": batches,
        "one_ray": one_ray,
        "targets_met": checks,
    }
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(f"\nwrote {args.out}")


def bench_batches(n: int, repeat: int) -> list[dict[str, Any]]:
    """The batch measurements: a sphere and a triangle at n rays."""
    center, radius = np.array([0.5, -0.25, 1.0]), 1.5
    sphere = isect.Sphere(center, radius)
    a, b, c = np.array([-1.0, -1, 0.5]), np.array([1.5, -1, 0.25]), np.array([0.0, 1.5, 0.75])
    triangle = isect.Triangle(a, b, c)
    s_org, s_dir = make_rays(n, center, 2.0, seed=1)
    t_org, t_dir = make_rays(n, (a + b + c) / 3, 1.2, seed=2)
    return [
        bench_shape(
            "sphere",
            sphere,
            s_org,
            s_dir,
            lambda: numpy_sphere(s_org, s_dir, center, radius),
            repeat,
        ),
        bench_shape(
            "triangle",
            triangle,
            t_org,
            t_dir,
            lambda: numpy_triangle(t_org, t_dir, a, b, c),
            repeat,
        ),
    ]


def print_batches(batches: list[dict[str, Any]]) -> None:
    """The batch table."""
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
        "(best of the repetitions; py rays: intersect_rays on a RAY_DTYPE array; py o,d:"
        " intersect(origins, directions), which also packs the rays; ratio: vs the C batch;"
        " speedup: numpy time / py rays time)"
    )


if __name__ == "__main__":
    main()
