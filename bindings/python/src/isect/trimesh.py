# SPDX-License-Identifier: Apache-2.0
"""trimesh's ray interface on libisect.

``mesh.ray = isect.trimesh.RayMeshIntersector(mesh)`` makes a
``trimesh.Trimesh`` answer its ray queries (``mesh.ray.intersects_*``,
``mesh.contains``, and what trimesh builds on them) with libisect: exact
crossings in double precision, each crossing of a closed mesh reported exactly
once (also through shared edges and vertices), the batch on every core.

The class has the methods, signatures and return conventions of trimesh's own
``trimesh.ray.ray_triangle.RayMeshIntersector`` (the interface trimesh's
embree intersector shares): ``intersects_id``, ``intersects_location``,
``intersects_first``, ``intersects_any`` and ``contains_points``. Where the
answers differ, by design (README, "trimesh's ray interface"):

* Each crossing is reported once. trimesh reports a hit on an edge shared by
  two triangles once per triangle (``intersects_id``) and merges hits at one
  location (``intersects_location``); here there is nothing to merge, and a
  ray that only grazes the surface (touching a silhouette edge or vertex) has
  an even number of hits (0 or 2), so hit counts keep the inside/outside
  parity.
* Hits are kept for t >= 0 exactly (trimesh keeps t > -1e-6).
* A ray lying in the plane of a face never hits that face. A ray running
  along the surface of a closed mesh (in a side face of a box, along its
  edges) is moved off it symbolically, to one side, by the library's
  tie-breaking rule: it crosses the neighbouring faces twice or not at all.
* A ray with NaN or infinity or a zero direction hits nothing, and a point
  with NaN or infinity is outside (trimesh's answers for them), instead of an
  error.
* ``contains_points`` is the library's exact containment: the crossing parity
  for a closed mesh (the same rule as trimesh's two-way ray count, without
  its retries), the generalized winding number >= 1/2 for any other mesh;
  points on the surface of a closed mesh are inside.

This module is ``isect.trimesh``; the package it wraps is imported as the
absolute ``trimesh`` (``from __future__ import annotations`` and absolute
imports are the default in Python 3, so the name of this module shadows
nothing). ``import isect`` does not import it; ``isect.trimesh`` (an attribute
that imports it on first use) or ``import isect.trimesh`` does.
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np
import numpy.typing as npt

try:
    import trimesh as _trimesh
except ImportError as _exc:  # pragma: no cover - exercised in a process without trimesh
    raise ImportError(
        "isect.trimesh needs the trimesh package, which is not installed (pip install "
        "trimesh); the rest of isect does not depend on it"
    ) from _exc

from ._args import as_points
from ._errors import invalid
from ._mesh import Mesh
from ._types import HitKind

__all__ = ["RayMeshIntersector"]

_HIT = (int(HitKind.ENTER), int(HitKind.EXIT), int(HitKind.TOUCH))


def _is_hit(kinds: npt.NDArray[np.int32]) -> npt.NDArray[np.bool_]:
    """ENTER, EXIT or TOUCH (not MISS, not INVALID)."""
    return (kinds >= _HIT[0]) & (kinds <= _HIT[-1])


def _ray_arrays(
    ray_origins: Any, ray_directions: Any
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Origins and directions as (m, 3) float64 arrays of one length (a single
    origin or direction is broadcast against the other's rows)."""
    origins = as_points(ray_origins, 3, "ray_origins").reshape(-1, 3)
    directions = as_points(ray_directions, 3, "ray_directions").reshape(-1, 3)
    if len(origins) != len(directions) and 1 not in (len(origins), len(directions)):
        raise invalid(f"ray_origins {origins.shape} and ray_directions {directions.shape}: "
                      "expected one origin per direction")
    o, d = np.broadcast_arrays(origins, directions)
    return o, d


class RayMeshIntersector:
    """Ray queries on a mesh with libisect, in trimesh's interface.

    Args:
        mesh: a ``trimesh.Trimesh`` (or any object with ``vertices`` and
            ``faces``, or an :class:`isect.Mesh`, used as it is, transform
            included). The :class:`isect.Mesh` and its BVH are built on the
            first query and rebuilt when the trimesh's content changes
            (trimesh's content hash, as its own intersector caches); another
            object is read once.

    Attributes:
        mesh: the mesh given.
    """

    def __init__(self, mesh: Any) -> None:
        """Keep the mesh; nothing is built until the first query."""
        self.mesh = mesh
        self._lock = threading.Lock()
        self._built: tuple[Any, Mesh, str] | None = None

    # ------------------------------------------------------------ the mesh

    def _key(self) -> Any:
        """What the built mesh depends on: a Trimesh's content hash."""
        if isinstance(self.mesh, _trimesh.Trimesh):
            return hash(self.mesh)  # trimesh: a hash of the content
        return None

    def _prepared(self) -> tuple[Mesh, str]:
        """The isect.Mesh and its containment rule, built when needed."""
        key = self._key()
        built = self._built
        if built is not None and built[0] == key:
            return built[1], built[2]
        with self._lock:
            built = self._built
            if built is None or built[0] != key:
                mesh = self.mesh if isinstance(self.mesh, Mesh) else Mesh(self.mesh)
                rule = "evenodd" if mesh.check().closed else "winding"
                built = self._built = (key, mesh, rule)
        return built[1], built[2]

    @property
    def isect_mesh(self) -> Mesh:
        """The :class:`isect.Mesh` the queries run on (built on first use)."""
        return self._prepared()[0]

    # ------------------------------------------------------------ queries

    def intersects_id(
        self,
        ray_origins: npt.ArrayLike,
        ray_directions: npt.ArrayLike,
        return_locations: bool = False,
        multiple_hits: bool = True,
        **kwargs: Any,
    ) -> Any:
        """The triangles the rays hit.

        Args:
            ray_origins: (m, 3) ray origins.
            ray_directions: (m, 3) ray directions (any length, not normalised).
            return_locations: also return the hit points.
            multiple_hits: every hit of each ray (True), or its first (False).
            **kwargs: accepted and ignored, as by trimesh's intersectors.

        Returns:
            ``(index_tri, index_ray)``, or ``(index_tri, index_ray,
            locations)`` with return_locations: the face index (int64, h)
            and the ray index (int64, h) of each hit, and its point (float64,
            (h, 3)). Hits are ordered by ray, then along the ray.
        """
        origins, directions = _ray_arrays(ray_origins, ray_directions)
        mesh, _ = self._prepared()
        if multiple_hits:
            offsets, hits = mesh.intersect_all_batch(origins, directions, errors="mark")
            index_ray = np.repeat(np.arange(len(origins), dtype=np.int64), np.diff(offsets))
            keep = _is_hit(hits["kind"])
            hits, index_ray = hits[keep], index_ray[keep]
        else:
            closest = mesh.intersect(origins, directions, errors="mark").reshape(-1)
            keep = _is_hit(closest["kind"])
            hits, index_ray = closest[keep], np.flatnonzero(keep).astype(np.int64)
        index_tri = hits["prim"].astype(np.int64)
        if return_locations:
            return index_tri, index_ray, np.array(hits["point"], dtype=np.float64).reshape(-1, 3)
        return index_tri, index_ray

    def intersects_location(
        self, ray_origins: npt.ArrayLike, ray_directions: npt.ArrayLike, **kwargs: Any
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], npt.NDArray[np.int64]]:
        """Where the rays hit: ``(locations (h, 3), index_ray (h,), index_tri
        (h,))``; keywords (``multiple_hits``) as for :meth:`intersects_id`."""
        index_tri, index_ray, locations = self.intersects_id(
            ray_origins=ray_origins, ray_directions=ray_directions, return_locations=True,
            **kwargs,
        )
        return locations, index_ray, index_tri

    def intersects_first(
        self, ray_origins: npt.ArrayLike, ray_directions: npt.ArrayLike, **kwargs: Any
    ) -> npt.NDArray[np.int64]:
        """The first triangle each ray hits: (m,) int64, -1 for a miss."""
        origins, directions = _ray_arrays(ray_origins, ray_directions)
        mesh, _ = self._prepared()
        closest = mesh.intersect(origins, directions, errors="mark").reshape(-1)
        hit = _is_hit(closest["kind"])
        return np.where(hit, closest["prim"], -1).astype(np.int64)

    def intersects_any(
        self, ray_origins: npt.ArrayLike, ray_directions: npt.ArrayLike, **kwargs: Any
    ) -> npt.NDArray[np.bool_]:
        """Whether each ray hits the mesh: (m,) bool (an any-hit query)."""
        origins, directions = _ray_arrays(ray_origins, ray_directions)
        mesh, _ = self._prepared()
        found = mesh.intersect(origins, directions, any_hit=True, errors="mark").reshape(-1)
        return _is_hit(found["kind"])

    def contains_points(self, points: npt.ArrayLike) -> npt.NDArray[np.bool_]:
        """Whether each point is inside the mesh: (n,) bool.

        A closed mesh: the exact crossing parity (points on the surface are
        inside). Any other mesh: the generalized winding number is >= 1/2.
        A point with NaN or infinity is outside.
        """
        pts = as_points(points, 3, "points")
        if pts.ndim != 2:
            raise invalid(f"points: expected an array of shape (n, 3), got {pts.shape}")
        mesh, rule = self._prepared()
        finite = np.isfinite(pts).all(axis=1)
        inside = np.zeros(len(pts), dtype=bool)
        if finite.any():
            inside[finite] = mesh.contains(pts[finite], rule=rule)
        return inside

    def __repr__(self) -> str:
        """The class and the mesh it queries."""
        return f"isect.trimesh.RayMeshIntersector({self.mesh!r})"
