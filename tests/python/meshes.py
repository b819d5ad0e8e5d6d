# SPDX-License-Identifier: Apache-2.0
"""Test meshes built in numpy: cubes of quads, a torus, icospheres.

Shared by test_mesh.py, test_embree_oracle.py and bench/python_mesh_bench.py.
Only the meshes are built here; every query goes to libisect.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]

#: The unit cube's corners and its six quads, outward by the right-hand rule.
CUBE_VERTICES: F64 = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
    dtype=np.float64,
)
CUBE_QUADS: list[list[int]] = [
    [0, 3, 2, 1],  # z = 0
    [4, 5, 6, 7],  # z = 1
    [0, 1, 5, 4],  # y = 0
    [2, 3, 7, 6],  # y = 1
    [1, 2, 6, 5],  # x = 1
    [0, 4, 7, 3],  # x = 0
]


def cube_triangles() -> I64:
    """The cube's quads split into 12 triangles (same orientation)."""
    q = np.array(CUBE_QUADS, dtype=np.int64)
    return np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])


def torus(
    major: float = 2.0, minor: float = 0.5, nu: int = 24, nv: int = 12
) -> tuple[F64, I64]:
    """A triangulated torus around the z axis (genus 1), outward triangles."""
    u = 2 * np.pi * np.arange(nu) / nu
    v = 2 * np.pi * np.arange(nv) / nv
    uu, vv = np.meshgrid(u, v, indexing="ij")
    ring = major + minor * np.cos(vv)
    verts = np.stack([ring * np.cos(uu), ring * np.sin(uu), minor * np.sin(vv)], axis=-1)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a = (i * nv + j).ravel()
    b = (((i + 1) % nu) * nv + j).ravel()
    c = (((i + 1) % nu) * nv + (j + 1) % nv).ravel()
    d = (i * nv + (j + 1) % nv).ravel()
    faces = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return verts.reshape(-1, 3), faces


_T = (1 + 5**0.5) / 2
_ICO_V = np.array(
    [
        [-1, _T, 0], [1, _T, 0], [-1, -_T, 0], [1, -_T, 0],
        [0, -1, _T], [0, 1, _T], [0, -1, -_T], [0, 1, -_T],
        [_T, 0, -1], [_T, 0, 1], [-_T, 0, -1], [-_T, 0, 1],
    ],
    dtype=np.float64,
)  # fmt: skip
_ICO_F = np.array(
    [
        [0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11],
        [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
        [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
        [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1],
    ],
    dtype=np.int64,
)  # fmt: skip


def icosphere(subdivisions: int, radius: float = 1.0) -> tuple[F64, I64]:
    """A subdivided icosahedron: 20 * 4**subdivisions outward triangles with
    every vertex on the sphere of ``radius`` about the origin."""
    v = _ICO_V / np.linalg.norm(_ICO_V, axis=1, keepdims=True)
    f = _ICO_F
    for _ in range(subdivisions):
        edges = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
        unique, inverse = np.unique(np.sort(edges, axis=1), axis=0, return_inverse=True)
        mid = v[unique].sum(axis=1)
        mid /= np.linalg.norm(mid, axis=1, keepdims=True)
        ab, bc, ca = inverse.reshape(3, -1) + len(v)
        a, b, c = f.T
        f = np.concatenate(
            [
                np.stack([a, ab, ca], 1),
                np.stack([b, bc, ab], 1),
                np.stack([c, ca, bc], 1),
                np.stack([ab, bc, ca], 1),
            ]
        )
        v = np.vstack([v, mid])
    return v * radius, f


def inradius(vertices: F64, faces: I64) -> float:
    """The smallest distance from the origin to a face plane (a ball of this
    radius lies inside an icosphere centred at the origin)."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    n = np.cross(b - a, c - a)
    return float(np.min(np.abs(np.einsum("ij,ij->i", n, a)) / np.linalg.norm(n, axis=1)))
