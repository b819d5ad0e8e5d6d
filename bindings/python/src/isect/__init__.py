# SPDX-License-Identifier: Apache-2.0
"""isect — ray–object intersection in double precision (libisect for Python).

A thin, numpy-first layer over libisect's C API, compiled into this package
with cffi: every number it returns is computed by the C library.

Shapes (each immutable, each with ``.transformed(matrix4x4)``):
    Thin surfaces: :class:`Plane`, :class:`Triangle`, :class:`Polygon`.
    Solids (with ``.contains``): :class:`Sphere`, :class:`Box`,
    :class:`ConvexPolyhedron`, :class:`Cylinder`, :class:`InfiniteCylinder`,
    :class:`Ellipsoid`, :class:`Quadric`.
    Meshes: :class:`Mesh` (triangle or polygon faces, with a BVH; a solid
    when closed), whose ``.check()`` returns a :class:`MeshReport`.

Queries: ``shape.intersect`` (closest hit per ray, batch, ``HIT_DTYPE``),
``shape.intersect_rays`` (the same over a ``RAY_DTYPE`` array, zero-copy),
``shape.intersect_all`` (every hit of one ray, a list of :class:`Hit`),
``shape.intersect_all_batch`` (every hit of every ray, CSR offsets + hits),
``solid.contains`` (points in a closed solid).

Helpers: :func:`polygon_normal`, :func:`plane_from_points`,
:func:`point_in_polygon`, :func:`winding_number`, :func:`version`,
:func:`abi_version`, :func:`default_threads` (the thread count of a batch
call's default ``threads=None``: every core this process may run on).

trimesh: ``isect.Mesh(a_trimesh)``, ``Mesh.to_trimesh()``, and
``isect.trimesh.RayMeshIntersector`` (trimesh's ray interface; the submodule
imports trimesh, on first use of ``isect.trimesh``).

Errors: :class:`IsectError` and its subclasses :class:`InvalidArgumentError`,
:class:`NonFiniteError`, :class:`DegenerateError` (all three also
``ValueError``) and :class:`OutOfMemoryError` (also ``MemoryError``), chosen
from the C status code.

Example:
    >>> import isect
    >>> s = isect.Sphere([0, 0, 0], 1.0)
    >>> [h.t for h in s.intersect_all([0, 0, -5], [0, 0, 1])]
    [4.0, 6.0]
"""

from __future__ import annotations

import importlib
from typing import Any

from ._batch import default_threads
from ._errors import (
    DegenerateError,
    InvalidArgumentError,
    IsectError,
    NonFiniteError,
    OutOfMemoryError,
)
from ._helpers import (
    abi_version,
    plane_from_points,
    point_in_polygon,
    polygon_normal,
    version,
    winding_number,
)
from ._mesh import Mesh, MeshLike, MeshReport
from ._shape import Shape, Solid
from ._shapes import (
    Box,
    ConvexPolyhedron,
    Cylinder,
    Ellipsoid,
    InfiniteCylinder,
    Plane,
    Polygon,
    Quadric,
    Sphere,
    Triangle,
)
from ._types import EPS_DEFAULT, HIT_DTYPE, RAY_DTYPE, Hit, HitKind

#: The version of the compiled libisect ("MAJOR.MINOR.PATCH").
__version__: str = version()


def __getattr__(name: str) -> Any:
    """``isect.trimesh``: the trimesh ray interface, imported on first use
    (so ``import isect`` does not import trimesh)."""
    if name == "trimesh":
        return importlib.import_module(".trimesh", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

__all__ = [
    "EPS_DEFAULT",
    "HIT_DTYPE",
    "RAY_DTYPE",
    "Box",
    "ConvexPolyhedron",
    "Cylinder",
    "DegenerateError",
    "Ellipsoid",
    "Hit",
    "HitKind",
    "InfiniteCylinder",
    "InvalidArgumentError",
    "Mesh",
    "MeshLike",
    "MeshReport",
    "IsectError",
    "NonFiniteError",
    "OutOfMemoryError",
    "Plane",
    "Polygon",
    "Quadric",
    "Shape",
    "Solid",
    "Sphere",
    "Triangle",
    "abi_version",
    "default_threads",
    "plane_from_points",
    "point_in_polygon",
    "polygon_normal",
    "version",
    "winding_number",
]
