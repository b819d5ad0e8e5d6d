# SPDX-License-Identifier: Apache-2.0
"""Winding numbers: isect against libigl (and trimesh's containment).

For each mesh, the same points go through

* ``Mesh.winding_number(points)`` (accuracy 0: exact to the rounding of the
  terms) against ``igl.winding_number`` (libigl's generalized winding number),
* ``Mesh.winding_number(points, 1e-2)`` (the far field, a proven bound)
  against ``igl.fast_winding_number`` (Barill et al., libigl's defaults),
* on the closed mesh, ``Mesh.contains(points, rule=...)`` against
  ``trimesh.Trimesh.contains`` (its ray-based test),

interleaved, ``--repeat`` times; medians of points per second and of the
ratios isect / other, with their ranges; the worst difference to the exact
values (isect's accuracy-0 result, itself checked against igl's to ~1e-14).
libigl runs on every core (its own parallel loop); isect on ``--threads``.

    .venv/bin/python bench/winding_bench.py [--points N] [--repeat R] [--threads T]
"""
from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import trimesh

import isect

try:
    import igl
except ImportError:  # pragma: no cover - libigl is pinned in requirements.txt
    igl = None


def timed(fn: Callable[[], Any]) -> tuple[float, Any]:
    t = time.perf_counter()
    out = fn()
    return time.perf_counter() - t, out


def meshes() -> list[tuple[str, np.ndarray, np.ndarray]]:
    out = []
    for sub in (4, 5, 6):
        s = trimesh.creation.icosphere(subdivisions=sub)
        keep = s.triangles_center[:, 2] <= 0.6
        out.append((f"open icosphere {int(keep.sum())} tris", np.asarray(s.vertices, float),
                    np.asarray(s.faces[keep], np.int64)))
    rng = np.random.default_rng(2)
    n = 3000
    out.append((f"soup of {n} random triangles", rng.uniform(-1, 1, (3 * n, 3)),
                np.arange(3 * n, dtype=np.int64).reshape(n, 3)))
    s = trimesh.creation.icosphere(subdivisions=5)
    out.append((f"closed icosphere {len(s.faces)} tris", np.asarray(s.vertices, float),
                np.asarray(s.faces, np.int64)))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, default=20000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    args = ap.parse_args()
    if igl is None:
        raise SystemExit("libigl is not installed (pip install -r requirements.txt)")
    rng = np.random.default_rng(1)
    pts = rng.uniform(-1.5, 1.5, (args.points, 3))
    print(f"isect {isect.version()}, {args.points} points in [-1.5, 1.5]^3, isect threads "
          f"{args.threads}, {args.repeat} interleaved repetitions, medians (ranges)\n")
    head = (f"{'mesh':<32} {'isect exact/s':>13} {'igl exact/s':>11} {'ratio':>17} {'max|diff|':>9}"
            f" | {'isect 1e-2/s':>12} {'err':>8} {'igl fast/s':>10} {'err':>8} {'ratio':>17}")
    print(head)
    for name, v, f in meshes():
        m = isect.Mesh(v, f.astype(np.int32))
        t_ie, t_ge, t_if, t_gf = [], [], [], []
        for _ in range(args.repeat):
            t, w = timed(lambda: m.winding_number(pts, 0.0, threads=args.threads))
            t_ie.append(t)
            t, wi = timed(lambda: igl.winding_number(v, f, pts))
            t_ge.append(t)
            t, wf = timed(lambda: m.winding_number(pts, 1e-2, threads=args.threads))
            t_if.append(t)
            t, wgf = timed(lambda: igl.fast_winding_number(v, f, pts))
            t_gf.append(t)
        r_e = [g / i for g, i in zip(t_ge, t_ie)]
        r_f = [g / i for g, i in zip(t_gf, t_if)]
        n = len(pts)
        print(f"{name:<32} {n / statistics.median(t_ie):>13.0f} {n / statistics.median(t_ge):>11.0f}"
              f" {statistics.median(r_e):>6.2f} ({min(r_e):.2f}-{max(r_e):.2f})"
              f" {np.abs(w - wi).max():>9.1e} | {n / statistics.median(t_if):>12.0f}"
              f" {np.abs(wf - w).max():>8.1e} {n / statistics.median(t_gf):>10.0f}"
              f" {np.abs(wgf - w).max():>8.1e} {statistics.median(r_f):>6.2f}"
              f" ({min(r_f):.2f}-{max(r_f):.2f})")
        if name.startswith("closed"):
            tm = trimesh.Trimesh(v, f, process=False)
            t_tm, inside_tm = timed(lambda: tm.contains(pts))
            for rule in ("evenodd", "nonzero", "winding"):
                t_r, inside = timed(lambda: m.contains(pts, rule=rule, threads=args.threads))
                print(f"  contains rule={rule:<8} {n / t_r:>10.0f} points/s; trimesh.contains"
                      f" {n / t_tm:>8.0f} points/s, {int((inside != inside_tm).sum())} of {n}"
                      " points disagree")


if __name__ == "__main__":
    main()
