# SPDX-License-Identifier: Apache-2.0
"""Embree (PyPI ``embreex``, float32) as an independent oracle for isect.Mesh.

10^5 random rays at an 81920-triangle icosphere. Both libraries get the same
float32-representable geometry and rays, so they should agree on hit/miss
except where a ray passes within rounding of an edge or vertex (Embree's
float32 test may leak or double-count there; libisect's is exact), and on t to
float32 precision.
"""

from __future__ import annotations

import isect
import numpy as np
import pytest
from meshes import icosphere

rtcs = pytest.importorskip("embreex.rtcore_scene", reason="embreex (Embree 4 for Python) not installed")
mc = pytest.importorskip("embreex.mesh_construction", reason="embreex not installed")

N_RAYS = 100_000
EDGE_TOL = 1e-5  # a barycentric coordinate this close to 0 is "at an edge or vertex"
T_RTOL = 1e-5


def _rays(rng: np.random.Generator, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Origins on the sphere of radius 3, aimed at random points of the ball of
    radius 1.15: about three quarters hit, many graze the silhouette."""
    o = rng.normal(size=(n, 3))
    o *= 3 / np.linalg.norm(o, axis=1, keepdims=True)
    target = rng.normal(size=(n, 3))
    target *= (1.15 * rng.uniform(size=(n, 1)) ** (1 / 3)) / np.linalg.norm(target, axis=1, keepdims=True)
    # float32-representable, so both libraries see the same rays
    return o.astype(np.float32).astype(np.float64), (target - o).astype(np.float32).astype(np.float64)


def _at_edge(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Barycentric (u, v) within EDGE_TOL of an edge (or vertex) of the triangle."""
    return np.minimum(np.minimum(u, v), 1 - u - v) < EDGE_TOL


def test_agrees_with_embree() -> None:
    v, f = icosphere(6)  # 20 * 4**6 = 81920 triangles
    assert len(f) >= 80_000
    v32 = v.astype(np.float32)
    mesh = isect.Mesh(v32.astype(np.float64), f)
    scene = rtcs.EmbreeScene()
    mc.TriangleMesh(scene, v32, f.astype(np.int32))

    origins, dirs = _rays(np.random.default_rng(20240611), N_RAYS)
    ours = mesh.intersect(origins, dirs, eps=0.0, threads=2)
    theirs = scene.run(origins.astype(np.float32), dirs.astype(np.float32), output=1)

    our_hit = ours["kind"] != isect.HitKind.MISS
    their_hit = theirs["geomID"] >= 0
    agree = our_hit == their_hit
    both = our_hit & their_hit
    t_ours = ours["t"][both]
    t_theirs = theirs["tfar"][both].astype(np.float64)
    rel = np.abs(t_ours - t_theirs) / t_ours
    only_ours = our_hit & ~their_hit
    only_theirs = their_hit & ~our_hit
    our_edge = _at_edge(ours["uv"][:, 0], ours["uv"][:, 1])
    their_edge = _at_edge(theirs["u"].astype(np.float64), theirs["v"].astype(np.float64))
    print(
        f"\nembree oracle: {N_RAYS} rays, {len(f)} triangles: hits libisect {our_hit.sum()}, "
        f"embree {their_hit.sum()}; agree {agree.mean():.6%}; only libisect {only_ours.sum()}, "
        f"only embree {only_theirs.sum()}; other prim {(both & (ours['prim'] != theirs['primID'])).sum()}; "
        f"t rel err max {rel.max():.3g}, p99.99 {np.quantile(rel, 0.9999):.3g}"
    )

    assert our_hit.sum() > N_RAYS // 2
    assert agree.mean() >= 0.999
    # every disagreement is a hit (of one of the two) at an edge or vertex
    assert our_edge[only_ours].all(), ours[only_ours & ~our_edge][:5]
    assert their_edge[only_theirs].all(), np.flatnonzero(only_theirs & ~their_edge)[:5]
    # rays that hit different triangles hit where two triangles meet: at
    # least one of the two hits is within EDGE_TOL of its triangle's edge
    other_prim = both & (ours["prim"] != theirs["primID"])
    assert (our_edge | their_edge)[other_prim].all()
    # t to float32 precision
    assert rel.max() <= T_RTOL, np.sort(rel)[-5:]


def test_aimed_at_vertices_and_edges() -> None:
    """Rays aimed exactly at vertices and edge midpoints from outside: libisect
    hits every one (exactly-once, never leaks); Embree's misses are counted."""
    v, f = icosphere(6)
    v32 = v.astype(np.float32).astype(np.float64)
    mesh = isect.Mesh(v32, f)
    scene = rtcs.EmbreeScene()
    mc.TriangleMesh(scene, v32.astype(np.float32), f.astype(np.int32))
    rng = np.random.default_rng(5)
    n = 60_000
    e = f[rng.integers(0, len(f), n), :]
    targets = np.concatenate([v32[e[: n // 2, 0]], 0.5 * (v32[e[n // 2 :, 0]] + v32[e[n // 2 :, 1]])])
    origins = rng.normal(size=(n, 3))
    origins *= 3 / np.linalg.norm(origins, axis=1, keepdims=True)
    origins = origins.astype(np.float32).astype(np.float64)
    dirs = targets - origins
    # the target faces the origin, not grazing (a ray tangent at a silhouette
    # vertex may rightly touch it an even number of times, i.e. miss)
    front = np.einsum("ij,ij->i", -dirs / np.linalg.norm(dirs, axis=1, keepdims=True), targets) > 0.2
    origins, dirs = origins[front], dirs[front]
    ours = mesh.intersect(origins, dirs, eps=0.0)
    theirs = scene.run(origins.astype(np.float32), dirs.astype(np.float32), output=1)
    our_miss = int((ours["kind"] == isect.HitKind.MISS).sum())
    their_miss = int((theirs["geomID"] < 0).sum())
    print(f"\naimed at vertices/edges: {len(origins)} rays; misses libisect {our_miss}, embree {their_miss}")
    assert our_miss == 0
