# SPDX-License-Identifier: Apache-2.0
"""Triangles of planar polygon faces, for :meth:`isect.Mesh.to_trimesh`.

A convex face (every corner turns the same way about the face's Newell
normal) becomes a fan from its first vertex; any other face is cut by ear
clipping in the plane of its largest normal component, so a concave face
gives triangles that cover exactly the face (no triangle outside it, none
overlapping). Faces of zero area (collinear vertices) become fans of zero-area
triangles, as degenerate as the face. Only geometry for export: no query of
the library goes through these triangles.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt


def triangulate(
    vertices: npt.NDArray[np.float64], indices: npt.NDArray[np.int32],
    offsets: npt.NDArray[np.int64],
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    """Triangles (T, 3) of the CSR polygon faces, each with the vertex order
    (so the normal) of its face, and for each triangle the face it came from.

    Args:
        vertices: (V, 3) positions.
        indices: every face's vertex indices, concatenated.
        offsets: CSR offsets (F + 1): face f is ``indices[offsets[f]:offsets[f+1]]``.
    """
    sizes = np.diff(offsets)
    tris: list[npt.NDArray[np.int64]] = []
    owners: list[npt.NDArray[np.int64]] = []
    for k in np.unique(sizes):
        faces = np.flatnonzero(sizes == k)
        corners = indices[offsets[faces][:, None] + np.arange(k)].astype(np.int64)  # (n, k)
        convex = _convex(vertices[corners])
        fan = np.stack([np.repeat(corners[convex][:, :1], k - 2, axis=1),
                        corners[convex][:, 1:-1], corners[convex][:, 2:]], axis=-1)
        tris.append(fan.reshape(-1, 3))
        owners.append(np.repeat(faces[convex], k - 2))
        for face, loop in zip(faces[~convex], corners[~convex]):
            ears = _ear_clip(vertices[loop])
            tris.append(loop[ears])
            owners.append(np.full(len(ears), face, dtype=np.int64))
    if not tris:
        return np.zeros((0, 3), dtype=np.int64), np.zeros(0, dtype=np.int64)
    tri = np.concatenate(tris)
    owner = np.concatenate(owners)
    order = np.argsort(owner, kind="stable")  # the faces' order, each face's triangles together
    return tri[order], owner[order]


def _convex(points: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
    """For polygons (n, k, 3): no corner turns against the Newell normal."""
    nxt = np.roll(points, -1, axis=1)
    normal = np.cross(points, nxt).sum(axis=1)  # Newell: twice the vector area
    turn = np.cross(points - np.roll(points, 1, axis=1), nxt - points)
    result: npt.NDArray[np.bool_] = (np.einsum("nkd,nd->nk", turn, normal) >= 0).all(axis=1)
    return result


def _ear_clip(points: npt.NDArray[np.float64]) -> npt.NDArray[np.int64]:
    """Triangles (k - 2, 3) of one planar polygon (k, 3), as indices into it."""
    normal = np.cross(points, np.roll(points, -1, axis=0)).sum(axis=0)
    axis = int(np.argmax(np.abs(normal)))
    uv = np.delete(points, axis, axis=1)
    # counter-clockwise in the (u, v) plane: drop x -> (y, z), y -> (z, x), z -> (x, y)
    if axis == 1:
        uv = uv[:, ::-1]
    if normal[axis] < 0:
        uv = uv[:, ::-1]
    left = list(range(len(points)))
    out: list[tuple[int, int, int]] = []
    while len(left) > 3:
        m = len(left)
        for j in range(m):
            a, b, c = left[j - 1], left[j], left[(j + 1) % m]
            if _cross(uv[a], uv[b], uv[c]) <= 0:
                continue  # a reflex or flat corner is no ear
            if any(_inside(uv[p], uv[a], uv[b], uv[c]) for p in left if p not in (a, b, c)):
                continue
            out.append((a, b, c))
            del left[j]
            break
        else:  # no ear: a face of (nearly) zero area; the rest as a fan
            out.extend((left[0], left[i], left[i + 1]) for i in range(1, len(left) - 1))
            left = []
    if len(left) == 3:
        out.append((left[0], left[1], left[2]))
    return np.array(out, dtype=np.int64).reshape(-1, 3)


def _cross(a: npt.NDArray[np.float64], b: npt.NDArray[np.float64],
           c: npt.NDArray[np.float64]) -> float:
    """Twice the signed area of the 2D triangle a, b, c (> 0: counter-clockwise)."""
    return float((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))


def _inside(p: npt.NDArray[np.float64], a: npt.NDArray[np.float64],
            b: npt.NDArray[np.float64], c: npt.NDArray[np.float64]) -> bool:
    """p in the closed counter-clockwise triangle a, b, c."""
    return _cross(a, b, p) >= 0 and _cross(b, c, p) >= 0 and _cross(c, a, p) >= 0
