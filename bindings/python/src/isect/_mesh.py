# SPDX-License-Identifier: Apache-2.0
"""Polygon meshes: :class:`Mesh` (``ISECT_MESH``) and its :class:`MeshReport`.

A :class:`Mesh` owns one ``isect_mesh`` handle made by ``isect_mesh_create``
(which copies the input and builds the BVH) and released by
``isect_mesh_destroy`` through a cffi finalizer, exactly once, when the last
Python object holding the handle goes away — transformed copies share it.
The handle is immutable, so a mesh may be queried from many threads at once.
Every query is the C library's; this module only marshals the input.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

import numpy as np
import numpy.typing as npt

from . import _batch, _progress
from ._args import ArrayLike, as_points, as_rows, as_threads
from ._errors import (
    InvalidArgumentError,
    check,
    error_for,
    invalid,
    nonfinite_element,
    value_text,
)
from ._isect import ffi, lib
from ._shape import Solid, frozen, point_problem, readonly_view
from ._triangulate import triangulate

if TYPE_CHECKING:  # pragma: no cover - trimesh is optional, imported by to_trimesh
    import trimesh

#: Faces: an (F, k) integer array (k = 3: triangles; k > 3: polygons of k
#: vertices each) or a sequence of index sequences (polygons of any sizes).
Faces = npt.ArrayLike | Sequence[Sequence[int]]


@runtime_checkable
class MeshLike(Protocol):
    """What :class:`Mesh` takes in one argument: an object with ``vertices``
    ((V, 3) numbers) and ``faces`` (as the ``faces`` argument) attributes, such
    as a ``trimesh.Trimesh``."""

    @property
    def vertices(self) -> Any:
        """(V, 3) vertex positions."""

    @property
    def faces(self) -> Any:
        """Faces, as :class:`Mesh` takes them."""


def _mesh_arrays(vertices: Any, faces: Any) -> tuple[Any, Any]:
    """The (vertices, faces) arrays of Mesh's arguments: as given, or read
    from a mesh object's ``vertices`` and ``faces`` attributes when faces is
    omitted."""
    is_object = hasattr(vertices, "vertices") and hasattr(vertices, "faces")
    if faces is None:
        if not is_object:
            raise invalid("faces: missing; pass Mesh(vertices, faces), or Mesh(mesh) with an "
                          "object that has vertices and faces attributes (a trimesh.Trimesh), "
                          f"not {type(vertices).__name__}")
        return vertices.vertices, vertices.faces
    if is_object:
        raise invalid(f"faces: given, but vertices is a {type(vertices).__name__} with its own "
                      "vertices and faces; pass Mesh(mesh) alone")
    return vertices, faces
_INT32_MAX = np.iinfo(np.int32).max
_E_ARG = int(lib.ISECT_E_ARG)


@dataclasses.dataclass(frozen=True, slots=True)
class MeshReport:
    """Topology and measures of a mesh (``isect_mesh_report``).

    Edges are the undirected vertex pairs of face boundaries.

    Attributes:
        vertices: vertices referenced by at least one face.
        edges: distinct edges.
        faces: faces, degenerate ones included.
        boundary_edges: edges used by exactly one face.
        nonmanifold_edges: edges used by three or more faces.
        misoriented_edges: edges used twice in the same direction.
        degenerate_faces: faces of zero area (never hit).
        components: connected components (through shared edges).
        euler_characteristic: V - E + F.
        genus: for a closed, oriented mesh the sum over components of
            (2 - chi_c) / 2; -1 otherwise.
        closed: no boundary and no non-manifold edges.
        oriented: no misoriented edges.
        volume: signed enclosed volume (divergence theorem), > 0 when the
            faces are ordered for outward normals.
        area: total face area.
    """

    vertices: int
    edges: int
    faces: int
    boundary_edges: int
    nonmanifold_edges: int
    misoriented_edges: int
    degenerate_faces: int
    components: int
    euler_characteristic: int
    genus: int
    closed: bool
    oriented: bool
    volume: float
    area: float

    @classmethod
    def _from_c(cls, r: Any) -> MeshReport:
        """Copy a filled ``isect_mesh_report``."""
        values: dict[str, Any] = {}
        for f in dataclasses.fields(cls):
            raw = getattr(r, f.name)
            values[f.name] = (
                bool(raw) if f.type == "bool" else float(raw) if f.type == "float" else int(raw)
            )
        return cls(**values)


def _as_indices(a: npt.NDArray[Any], name: str) -> npt.NDArray[Any]:
    """``a`` if it holds integers (any integer dtype; the range is checked
    against the vertex count later), else an InvalidArgumentError."""
    if a.size and a.dtype.kind not in "iu":
        raise invalid(f"{name}: vertex indices must be integers, got dtype {a.dtype}")
    return a


def _as_faces(
    faces: Faces,
) -> tuple[npt.NDArray[Any], npt.NDArray[np.int64] | None, int]:
    """Flat integer indices (not yet range-checked), CSR offsets (None for a
    triangle array) and the face count."""
    try:
        a = np.asarray(faces)
    except ValueError:  # ragged: numpy refuses an inhomogeneous nested sequence
        a = None
    if a is not None and a.dtype != object and a.ndim == 2:
        nf, k = a.shape
        idx = _as_indices(a.reshape(-1), "faces")
        if k == 3:
            return idx, None, nf
        return idx, np.arange(nf + 1, dtype=np.int64) * k, nf
    if a is not None and a.dtype != object and a.ndim == 1 and a.size == 0:
        return np.zeros(0, dtype=np.int32), None, 0
    if isinstance(faces, np.ndarray) and faces.dtype != object:
        raise invalid(f"faces: expected an (F, k) integer array, got shape {faces.shape}")
    try:
        polys = [np.asarray(f) for f in faces]  # type: ignore[union-attr]
        polys = [p if p.size else p.astype(np.int64) for p in polys]
    except (TypeError, ValueError):
        raise invalid("faces: expected an (F, k) array or a sequence of index sequences") from None
    for f, p in enumerate(polys):
        if p.ndim != 1:
            raise invalid(f"faces[{f}]: expected a flat sequence of vertex indices, got an "
                          f"array of shape {p.shape}")
    counts = np.fromiter((p.size for p in polys), dtype=np.int64, count=len(polys))
    offsets = np.zeros(len(polys) + 1, dtype=np.int64)
    np.cumsum(counts, out=offsets[1:])
    flat = np.concatenate(polys) if polys else np.zeros(0, dtype=np.int32)
    return _as_indices(flat, "faces"), offsets, len(polys)


def _check_mesh_args(verts: npt.NDArray[np.float64], flat: npt.NDArray[Any],
                     offsets: npt.NDArray[np.int64] | None, nf: int) -> None:
    """Raise for what ``isect_mesh_create`` refuses, in its order (counts,
    face sizes, indices, then the vertices' values), naming the element and
    its value: ``faces[3] has 2 vertices``, ``faces[12][1] = 99 is outside
    [0, 40)``, ``vertices[5][2] = inf is not finite``."""
    nv = verts.shape[0]
    if nv > _INT32_MAX:
        raise error_for(_E_ARG, "Mesh", detail=f"vertices: {nv} vertices (at most 2^31 - 1)")
    if nf > _INT32_MAX:
        raise error_for(_E_ARG, "Mesh", detail=f"faces: {nf} faces (at most 2^31 - 1)")
    if offsets is not None and nf:
        sizes = np.diff(offsets)
        small = sizes < 3
        if small.any():
            f = int(small.argmax())
            raise error_for(_E_ARG, "Mesh", detail=(
                f"faces[{f}] has {int(sizes[f])} vertices (a face needs at least 3)"))
    if flat.size:
        bad = (flat < 0) | (flat >= nv)
        if bad.any():
            i = int(bad.argmax())
            f = i // 3 if offsets is None else int(np.searchsorted(offsets, i, side="right")) - 1
            j = i - (3 * f if offsets is None else int(offsets[f]))
            raise error_for(_E_ARG, "Mesh", detail=(
                f"faces[{f}][{j}] = {value_text(flat[i])} is outside [0, {nv}) (the vertex "
                "indices)"))
    detail = nonfinite_element(verts, "vertices")
    if detail is not None:
        raise error_for(int(lib.ISECT_E_NONFINITE), "Mesh", detail=detail)


class Mesh(Solid):
    """A triangle or polygon mesh with its BVH (``ISECT_MESH``).

    Faces are planar polygons (convex or concave) whose vertex order gives the
    outward normal by the right-hand rule. Every hit of a closed mesh is
    reported exactly once, also at shared edges and vertices, at every eps
    (SPEC revision 2: faces use no eps; see isect.h). Hit ``prim`` is the face
    index; triangles carry barycentric ``uv``. :meth:`contains` decides
    containment by a rule: ``"evenodd"`` (exact crossing parity) for closed
    meshes, ``"nonzero"`` (exact integer winding number) for closed,
    consistently oriented ones, ``"winding"`` (generalized winding number >=
    1/2) for any mesh; :meth:`winding_number` gives the number itself.
    Degenerate faces are kept (never hit) and counted by :meth:`check`.
    """

    __slots__ = ("_handle", "_indices", "_offsets")

    _type = lib.ISECT_MESH
    _layout = (("vertices", 0),)

    _handle: Any
    _indices: npt.NDArray[np.int32]
    _offsets: npt.NDArray[np.int64] | None

    def __init__(self, vertices: ArrayLike | MeshLike, faces: Faces | None = None) -> None:
        """Build the mesh (the input is copied).

        Args:
            vertices: an (V, 3) array of vertex positions; or, with faces
                omitted, a mesh object: a ``trimesh.Trimesh`` or any object
                with ``vertices`` and ``faces`` attributes that convert to
                such arrays (duck typing; trimesh is not imported).
            faces: an (F, 3) integer array of triangles, an (F, k) array of
                k-gons, or a sequence of index sequences (polygons of any
                sizes >= 3, stored as CSR offsets).

        Raises:
            InvalidArgumentError: vertices not (V, 3); faces not integers; an
                index outside [0, V); a face of fewer than 3 vertices; faces
                omitted for an object without ``vertices`` and ``faces``, or
                given with one.
            NonFiniteError: NaN or infinity in the vertices.
            OutOfMemoryError: the C library could not allocate the mesh.
        """
        vertex_array, face_array = _mesh_arrays(vertices, faces)
        verts = as_rows(vertex_array, 3, "vertices")
        flat, offsets, nf = _as_faces(face_array)
        _check_mesh_args(verts, flat, offsets, nf)
        idx = np.ascontiguousarray(flat, dtype=np.int32)  # every index is in [0, V)
        out = ffi.new("isect_mesh **")
        check(
            lib.isect_mesh_create(
                ffi.from_buffer("double[]", verts),
                verts.shape[0],
                ffi.from_buffer("int32_t[]", idx),
                ffi.NULL if offsets is None else ffi.from_buffer("int64_t[]", offsets),
                nf,
                out,
            ),
            "Mesh",
            "vertices" if not np.isfinite(verts).all() else "faces",
        )
        size = int(lib.isect_mesh_bytes(out[0]))
        self._handle = ffi.gc(out[0], lib.isect_mesh_destroy, size=size)
        self._indices = frozen(idx)
        self._offsets = None if offsets is None else frozen(offsets)
        self._setup(verts)

    def _geometry(self) -> tuple[Any, Any]:
        """A mesh descriptor has data NULL and the handle as ``mesh``."""
        return ffi.NULL, self._handle

    def _validate(self) -> None:
        """Nothing: the input was checked before ``isect_mesh_create``."""

    def _prim_count(self) -> int:
        """Hit prims are face indices."""
        return self.n_faces

    # ----------------------------------------------------------- properties

    @property
    def vertices(self) -> npt.NDArray[np.float64]:
        """The (V, 3) vertex positions (read-only copy of the input)."""
        return self._data

    @property
    def face_indices(self) -> npt.NDArray[np.int32]:
        """All faces' vertex indices, concatenated (int32, read-only)."""
        return self._indices

    @property
    def face_offsets(self) -> npt.NDArray[np.int64] | None:
        """CSR offsets (F + 1) of polygon faces, or None for a triangle array."""
        return self._offsets

    @property
    def n_faces(self) -> int:
        """The number of faces, degenerate ones included."""
        return len(self._indices) // 3 if self._offsets is None else len(self._offsets) - 1

    @property
    def faces(self) -> npt.NDArray[np.int32] | list[npt.NDArray[np.int32]]:
        """The (F, 3) triangle array, or a list of index arrays for polygon faces."""
        if self._offsets is None:
            return readonly_view(self._indices.reshape(-1, 3))  # type: ignore[arg-type, return-value]
        return np.split(self._indices, self._offsets[1:-1])

    @property
    def nbytes(self) -> int:
        """Bytes the C mesh occupies: its copy of the input and the BVH
        (``isect_mesh_bytes``)."""
        return int(lib.isect_mesh_bytes(self._handle))

    def to_trimesh(self) -> trimesh.Trimesh:
        """The mesh as a ``trimesh.Trimesh`` (``process=False``: vertices and
        faces as they are, nothing merged or removed).

        The vertices are in world space: a transformed mesh's are mapped by
        its matrix, and a mirroring matrix (negative determinant) reverses
        each face's vertex order, so that the faces' right-hand normals point
        the way this mesh's hits report (outward for a closed mesh).
        Triangles keep their face indices (``prim``). Polygon faces are cut
        into triangles (a fan for convex faces, ear clipping for concave
        ones; the faces' orientation kept); then ``face_attributes
        ["isect_face"]`` holds, for each triangle, the polygon face (the hit
        ``prim``) it belongs to.

        trimesh is imported here, not by ``import isect``.

        Raises:
            ImportError: trimesh is not installed.
        """
        try:
            import trimesh
        except ImportError as exc:
            raise ImportError(
                "Mesh.to_trimesh needs the trimesh package, which is not installed "
                "(pip install trimesh); isect itself does not depend on it"
            ) from exc
        verts = np.array(self._data, dtype=np.float64)
        mirrored = False
        if self._matrix is not None:
            verts = verts @ self._matrix[:3, :3].T + self._matrix[:3, 3]
            mirrored = bool(np.linalg.det(self._matrix[:3, :3]) < 0)
        attributes: dict[str, Any] = {}
        if self._offsets is None:
            tris = self._indices.reshape(-1, 3).astype(np.int64)
        else:
            tris, owner = triangulate(self._data, self._indices, self._offsets)
            attributes["isect_face"] = owner
        if mirrored:
            tris = tris[:, ::-1]
        return trimesh.Trimesh(vertices=verts, faces=np.ascontiguousarray(tris),
                               face_attributes=attributes or None, process=False)

    # -------------------------------------------------------------- queries

    def check(self) -> MeshReport:
        """Topology and measures of the mesh in object space (``isect_mesh_check``;
        a transform is not applied)."""
        report = ffi.new("isect_mesh_report *")
        check(lib.isect_mesh_check(self._handle, report), "Mesh.check")
        return MeshReport._from_c(report)

    def contains(  # type: ignore[override]
        self,
        points: ArrayLike,
        *,
        rule: str = "evenodd",
        threads: int | None = None,
        progress: bool = False,
    ) -> Any:
        """Whether each point lies inside, by a containment rule (``isect_contains_batch``).

        Args:
            points: shape (..., 3).
            rule: ``"evenodd"``: the parity of the exact crossings (closed
                meshes); ``"nonzero"``: the exact integer winding number is
                not 0 (closed, consistently oriented meshes: nested and
                self-intersecting shells count); ``"winding"``: the
                generalized winding number is >= 1/2 (any mesh: open,
                non-manifold, soups; exact on closed oriented meshes, where
                it means w >= 1). On a closed mesh, points on the surface are
                inside.
            threads: split the batch over this many threads; None (the
                default): every core; the result is the same for every value.
            progress: show a progress bar while the batch runs (as for
                :meth:`~Shape.intersect`).

        Returns:
            A bool array of shape (...), or a bool for a single (3,) point.

        Raises:
            NonFiniteError: a point with NaN/Inf (``index`` names the first).
            InvalidArgumentError: points not of shape (..., 3); an unknown
                rule; ``"evenodd"`` on a mesh that is not closed, or
                ``"nonzero"`` on one that is not closed and consistently
                oriented.
        """
        name = "Mesh.contains"
        flags = _RULES.get(rule) if isinstance(rule, str) else None
        if flags is None:
            raise invalid(f"{name}: rule must be one of {sorted(_RULES)}, not {rule!r}")
        c = ffi.new("isect_shape *", self._c[0])
        c.flags = flags
        try:
            return self._contains(c, points, threads, name, progress)
        except InvalidArgumentError:
            if rule == "winding":
                raise
            needs = "closed" if rule == "evenodd" else "closed and consistently oriented"
            raise invalid(f"{name}: rule {rule!r} needs a {needs} mesh (this one is not); "
                          "rule='winding' works for any mesh") from None

    def winding_number(
        self,
        points: ArrayLike,
        accuracy: float | None = None,
        *,
        threads: int | None = None,
        progress: bool = False,
    ) -> npt.NDArray[np.float64] | float:
        """The generalized winding number at each point (``isect_winding_number_batch``).

        The signed solid angle of the faces at the point over 4 pi (Jacobson et
        al. 2013), faces oriented by the right-hand rule: 1 inside a closed
        mesh with outward normals, 0 outside, fractional near an open mesh's
        holes. A closed, consistently oriented mesh gets the exact integer off
        its surface (and the principal value, e.g. 1/2, on it), whatever the
        accuracy.

        Args:
            points: shape (..., 3).
            accuracy: 0 (or None): the sum of the faces' solid angles, exact
                to the rounding of the terms (each solid angle's error bound is
                documented in isect.h; about 1e-15 per face away from edges),
                fast through the boundaries of face clusters (Jacobson et al.
                2013). > 0: a second-order far field for distant clusters,
                within ``accuracy`` of that (a proven bound).
            threads: split the batch over this many threads (each builds its
                own cluster tree); None (the default): every core; the result
                is the same for every value.
            progress: show a progress bar while the batch runs (as for
                :meth:`~Shape.intersect`).

        Returns:
            A float64 array of shape (...), or a float for a single (3,) point;
            NaN is never returned for finite points.

        Raises:
            NonFiniteError: a point with NaN/Inf (``index`` names the first).
            InvalidArgumentError: points not of shape (..., 3); accuracy
                negative or NaN.
        """
        name = "Mesh.winding_number"
        if accuracy is None:
            accuracy = 0.0
        try:
            acc = float(accuracy)
        except (TypeError, ValueError, OverflowError):
            raise invalid(f"{name}: accuracy must be a number, not {accuracy!r}") from None
        if not acc >= 0.0:
            raise invalid(f"{name}: accuracy must be >= 0, not {accuracy!r}")
        pts = as_points(points, 3, "points")
        shape = pts.shape[:-1]
        flat = np.ascontiguousarray(pts.reshape(-1, 3))
        n = flat.shape[0]
        w = np.empty(n, dtype=np.float64)
        pp = ffi.from_buffer("double[]", flat)
        wp = ffi.from_buffer("double[]", w)
        c = self._c

        def work(lo: int, hi: int) -> int:
            """One chunk of the batch: the C call over [lo, hi)."""
            return int(lib.isect_winding_number_batch(c, pp + 3 * lo, hi - lo, acc, wp + lo))

        nthreads = as_threads(threads)
        report = _progress.reporter(progress, name, n, "point")
        for status in _batch.run(work, n, nthreads, report):
            check(status, name)
        bad = np.isnan(w)
        if bad.any():
            index = int(bad.argmax())
            raise error_for(int(lib.ISECT_E_NONFINITE), name, index=index, item="point",
                            arg="points", detail=point_problem(flat[index]))
        return float(w[0]) if shape == () else w.reshape(shape)

    # ------------------------------------------------------------ internals

    def _repr_fields(self) -> str:
        """A summary (the arrays are too long to print)."""
        return f"<{len(self._data)} vertices, {self.n_faces} faces>"

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as (vertices, faces as indices + offsets, matrix)."""
        return (_rebuild_mesh, (self._data, self._indices, self._offsets, self._matrix))


#: Mesh.contains rules: the values of isect_shape.flags for ISECT_MESH.
_RULES = {"evenodd": int(lib.ISECT_EVEN_ODD), "nonzero": int(lib.ISECT_NONZERO),
          "winding": int(lib.ISECT_WINDING)}


def _rebuild_mesh(
    vertices: npt.NDArray[np.float64],
    indices: npt.NDArray[np.int32],
    offsets: npt.NDArray[np.int64] | None,
    matrix: npt.NDArray[np.float64] | None,
) -> Mesh:
    """Unpickle a mesh."""
    if offsets is None:
        mesh = Mesh(vertices, indices.reshape(-1, 3))
    else:
        mesh = Mesh(vertices, np.split(indices, offsets[1:-1]))
    return mesh if matrix is None else mesh.transformed(matrix)
