# SPDX-License-Identifier: Apache-2.0
"""The shape base classes: the ``isect_shape`` descriptor and every query.

A shape keeps its numbers in one read-only, contiguous float64 array; the C
descriptor (``isect_shape``) points into that array and, when the shape is
transformed, at an ``isect_xform`` the shape also owns. Both live as long as the
Python object, and neither ever changes after construction, so one shape may be
queried from many threads at once.

Every number a query returns is computed by libisect; this module only moves
bytes between numpy arrays and C buffers.
"""

from __future__ import annotations

import copy
import math
import struct
import threading
from collections.abc import Sequence
from typing import Any, ClassVar, TypeVar

import numpy as np
import numpy.typing as npt

from . import _batch, _progress
from ._args import (
    ArrayLike,
    Vector3,
    as_float_array,
    as_int32,
    as_matrix4,
    as_points,
    as_ray_array,
    as_records,
    as_scalar,
    as_threads,
    as_vector,
    make_opts,
    make_rays,
    ray_columns,
    ray_culprit,
    ray_problem,
    raise_on_bad,
)
from ._errors import IsectError, check, error_for, invalid, nonfinite_element, value_text
from ._isect import ffi, lib
from ._types import HIT_DTYPE, KIND_BY_VALUE, RAY_DTYPE, Hit

_KINDS = KIND_BY_VALUE

S = TypeVar("S", bound="Shape")
T = TypeVar("T", bound=np.generic)

_INVALID = int(lib.ISECT_INVALID)
_HIT_KINDS = (int(lib.ISECT_ENTER), int(lib.ISECT_EXIT), int(lib.ISECT_TOUCH))
# struct layouts of one isect_hit / isect_ray, for single-ray queries; they hold
# only if the C structs are packed in field order (checked below).
_HIT_STRUCT = struct.Struct("=9d2i")  # t, point[3], normal[3], uv[2], prim, kind
_RAY_STRUCT = struct.Struct("=8d")  # org[3], dir[3], tmin, tmax
_HIT_SIZE = _HIT_STRUCT.size
if (
    _HIT_SIZE != HIT_DTYPE.itemsize
    or _RAY_STRUCT.size != RAY_DTYPE.itemsize
    or [HIT_DTYPE.fields[k][1] for k in HIT_DTYPE.names] != [0, 8, 32, 56, 72, 76]  # type: ignore[index, union-attr]
    or [RAY_DTYPE.fields[k][1] for k in RAY_DTYPE.names] != [0, 24, 48, 56]  # type: ignore[index, union-attr]
):  # pragma: no cover
    raise ImportError("isect: isect_hit / isect_ray are not laid out as isect.h documents")

#: A valid ray used to let the C library validate a new shape's numbers.
_PROBE_RAY = ffi.new("isect_ray *", ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.0, math.inf))


class _Scratch(threading.local):
    """Per-thread C buffers for single-ray queries, so that intersect_all
    allocates nothing but its result. ``bufs`` is one tuple to keep the hot
    path to a single thread-local lookup: (ray cdata, ray bytes, hits cdata,
    hits bytes, capacity)."""

    bufs: tuple[Any, Any, Any, Any, int]

    def __init__(self) -> None:
        """Allocate this thread's buffers."""
        self.resize(8)

    def resize(self, cap: int) -> None:
        """Make room for ``cap`` hits (C-allocated, so properly aligned)."""
        ray = ffi.new("isect_ray *")
        hits = ffi.new("isect_hit[]", cap)
        self.bufs = (ray, ffi.buffer(ray), hits, ffi.buffer(hits), cap)


_scratch = _Scratch()
_NULL = ffi.NULL
_c_intersect = lib.isect_intersect
_c_intersect_batch = lib.isect_intersect_batch
_new = ffi.new
_from_buffer = ffi.from_buffer
_pack_ray = _RAY_STRUCT.pack_into
_unpack_hit = _HIT_STRUCT.unpack_from
_tuple_new = tuple.__new__

#: The number types that the one-ray fast path of Shape.intersect hands to cffi
#: itself: for these cffi's C double is the float64 that numpy makes of them
#: (the same value; for a large int, both the correctly rounded one). Lists and
#: tuples of them and float64 arrays of shape (3,) take the fast path; any
#: other input takes the general path.
_PLAIN_NUMBERS = frozenset((float, int, np.float64))
_F8 = np.dtype(np.float64)


def _all_plain(a: object, b: object, c: object, d: object, e: object, f: object, g: object,
               h: object) -> bool:
    """The 8 numbers of a ray are plain numbers (types of ``_PLAIN_NUMBERS``)."""
    p = _PLAIN_NUMBERS
    return (type(a) in p and type(b) in p and type(c) in p and type(d) in p and type(e) in p
            and type(f) in p and type(g) in p and type(h) in p)


def _plain_vector(v: object) -> Sequence[float] | None:
    """The 3 numbers of ``v`` if it is a list or tuple of 3 plain numbers or a
    native float64 array of shape (3,); None for anything else."""
    if type(v) is list or type(v) is tuple:
        if len(v) == 3 and (
            type(v[0]) in _PLAIN_NUMBERS
            and type(v[1]) in _PLAIN_NUMBERS
            and type(v[2]) in _PLAIN_NUMBERS
        ):
            return v
    elif type(v) is np.ndarray and v.shape == (3,) and v.dtype == _F8:
        return v.tolist()  # type: ignore[no-any-return]
    return None


def _closest_one(c: Any, origin: object, direction: object, tmin: object, tmax: object) -> Any:
    """The fast path of :meth:`Shape.intersect`: one valid ray, default options.

    The ray goes straight into an ``isect_ray`` and through the C call of the
    general path (``isect_intersect_batch``, n = 1), and its record is returned
    as the general path returns it: a ``HIT_DTYPE`` record viewing a fresh
    writable 0-d array. Returns None for any other input (a batch, another
    number type, a bad ray), which the general path then handles, errors
    included. Nothing is shared between calls, so it is reentrant.
    """
    if type(tmin) not in _PLAIN_NUMBERS or type(tmax) not in _PLAIN_NUMBERS:
        return None
    org = _plain_vector(origin)
    if org is None:
        return None
    dirn = _plain_vector(direction)
    if dirn is None:
        return None
    try:
        ray = _new("isect_ray *", (org, dirn, tmin, tmax))
    except OverflowError:  # an int beyond the float range
        return None
    out = bytearray(_HIT_SIZE)
    hit = _from_buffer("isect_hit *", out)
    if _c_intersect_batch(c, ray, 1, _NULL, hit) < 0 or hit.kind == _INVALID:
        return None
    return np.ndarray((), HIT_DTYPE, out)[()]



def _soa_columns(origins: ArrayLike, directions: ArrayLike, tmin: ArrayLike,
                 tmax: ArrayLike) -> tuple[Any, ...] | None:
    """The arguments of ``intersect`` as contiguous float64 columns with
    steps (0: one value for every ray) and the batch shape, when each is
    either one value or exactly the batch's shape; None otherwise (general
    broadcasting goes through ``make_rays``)."""
    org, dirs, lo, hi, shape = ray_columns(origins, directions, tmin, tmax)
    if shape == ():
        return None
    cols = []
    for a, point_shape, k in ((org, org.shape[:-1], 3), (dirs, dirs.shape[:-1], 3),
                              (lo, lo.shape, 1), (hi, hi.shape, 1)):
        if point_shape == ():
            cols.append((np.ascontiguousarray(a, dtype=np.float64).reshape(-1), 0))
        elif point_shape == shape:
            cols.append((np.ascontiguousarray(a, dtype=np.float64).reshape(-1), k))
        else:
            return None
    return (*cols, shape)

class Shape:
    """Base class of every shape: the queries shared by all primitives.

    Shapes are immutable. Construct one of the subclasses (:class:`Sphere`,
    :class:`Box`, ...); invalid numbers (NaN, a negative radius, ...) raise at
    construction, with the error libisect reports for them. Degenerate
    geometry (zero radius, zero-area triangle, ...) is valid and never hit.
    """

    __slots__ = ("_data", "_data_ptr", "_n", "_flags", "_matrix", "_xform", "_c", "__weakref__")

    #: The C shape type (``ISECT_SPHERE``, ...).
    _type: ClassVar[int] = 0

    _data: npt.NDArray[np.float64]
    _data_ptr: Any
    _n: int
    _flags: int
    _matrix: npt.NDArray[np.float64] | None
    _xform: Any
    _c: Any

    # ------------------------------------------------------------ building

    def _setup(self, data: npt.NDArray[np.float64], n: int = 0, flags: int = 0) -> None:
        """Adopt (a frozen copy of) ``data`` and build the descriptor."""
        self._data = frozen(data)
        self._n = n
        self._flags = flags
        self._matrix = None
        self._xform = ffi.NULL
        self._validate()
        self._describe()

    def _validate(self) -> None:
        """Raise for what the C check of the type refuses, in the order it
        checks, naming the element and its value (``radius = -1.0 is
        negative``, ``center[1] = nan is not finite``): the counts and flags
        (:meth:`_check_counts`), then NaN and infinity, then the type's rules
        for values (:meth:`_check_values`). The C library validates the
        numbers again (:meth:`_describe`); it is the judge, this only names."""
        context = type(self).__name__
        detail = self._check_counts()
        if detail is not None:
            raise error_for(int(lib.ISECT_E_ARG), context, detail=detail)
        for name, _ in self._layout:
            detail = nonfinite_element(self._part(name), name)
            if detail is not None:
                raise error_for(int(lib.ISECT_E_NONFINITE), context, detail=detail)
        detail = self._check_values()
        if detail is not None:
            raise error_for(int(lib.ISECT_E_ARG), context, detail=detail)

    def _check_counts(self) -> str | None:
        """What is wrong with the shape's counts or flags (a polygon of 2
        vertices, an unknown rule), or None."""
        return None

    def _check_values(self) -> str | None:
        """What is wrong with the shape's (finite) numbers (a negative
        radius, lo > hi), or None."""
        return None

    #: Numbers per row of a "the rest" part of ``_layout`` (count 0): 3 for
    #: vertices, 4 for planes.
    _row: ClassVar[int] = 3

    def _part(self, name: str) -> npt.NDArray[np.float64]:
        """The numbers of the constructor argument ``name`` (``_layout``): a
        0-d array for one number, (k,) for a vector, (rows, _row) for the rest."""
        flat = self._data.reshape(-1)
        at = 0
        for part, count in self._layout:
            if part == name:
                if count == 0:
                    return flat[at:].reshape(-1, self._row)
                return flat[at] if count == 1 else flat[at:at + count]
            at += count
        raise KeyError(name)  # pragma: no cover - a name of _layout

    def _describe(self) -> None:
        """(Re)build the C descriptor and let libisect validate it."""
        c = ffi.new("isect_shape *")
        c.type = self._type
        try:
            c.n = self._n
            c.flags = self._flags
        except OverflowError:
            raise invalid(f"{type(self).__name__}: count or flag out of the int32 range") from None
        c.reserved = 0
        self._data_ptr, c.mesh = self._geometry()
        c.data = self._data_ptr
        c.xform = ffi.NULL
        # Counting the hits of a valid ray with the untransformed shape reports
        # exactly the errors of the shape's own numbers, n and flags.
        status = lib.isect_intersect(c, _PROBE_RAY, ffi.NULL, ffi.NULL, 0)
        if status < 0:
            raise error_for(status, type(self).__name__, arg=self._blame(status))
        c.xform = self._xform
        self._c = c

    #: The constructor's numeric arguments in the order of the data array:
    #: (name, count of doubles; 0 for "all the rest").
    _layout: ClassVar[tuple[tuple[str, int], ...]] = ()

    def _blame(self, status: int) -> str | None:
        """The constructor argument that holds what libisect refused
        (``status``), for the message: the first with a NaN or infinity for
        ISECT_E_NONFINITE, :meth:`_blame_arg` for ISECT_E_ARG."""
        if status == lib.ISECT_E_NONFINITE:
            at = 0
            for name, count in self._layout:
                part = self._data[at:] if count == 0 else self._data[at:at + count]
                if not np.isfinite(part).all():
                    return name
                at += count
            return None
        if status == lib.ISECT_E_ARG:
            return self._blame_arg()
        return None

    def _blame_arg(self) -> str | None:
        """The argument an ISECT_E_ARG of the constructor is about (the rules
        of isect.h for the type: a negative radius, lo > hi, ...)."""
        return None

    def _geometry(self) -> tuple[Any, Any]:
        """The descriptor's ``data`` and ``mesh`` pointers: the shape's own
        numbers and NULL (:class:`~isect.Mesh` passes NULL and its handle)."""
        return ffi.from_buffer("double[]", self._data), ffi.NULL

    # ----------------------------------------------------------- properties

    @property
    def data(self) -> npt.NDArray[np.float64]:
        """The shape's numbers as the C library reads them (read-only), in the
        order of its scalar function's arguments."""
        return self._data

    @property
    def matrix(self) -> npt.NDArray[np.float64] | None:
        """The row-major 4x4 object-to-world matrix, or None if untransformed."""
        return self._matrix

    def bounds(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """A conservative world-space box ``(lo, hi)`` (``isect_shape_bounds``).

        Every point of the shape, and every hit reported for it, lies in
        ``lo <= x <= hi``: spheres, ellipsoids, boxes, finite cylinders,
        triangles, planar polygons and meshes get their extent (transformed
        shapes the image of it), widened by 2^-40 of its magnitude for the
        rounding of reported points; planes, infinite cylinders, quadrics,
        convex polyhedra and polygons whose vertices are not exactly
        coplanar are unbounded (``-inf`` / ``inf``). A mesh without vertices
        has the empty box (``lo = inf``, ``hi = -inf``).

        Returns:
            Two float64 arrays of shape (3,).
        """
        lo = ffi.new("double[3]")
        hi = ffi.new("double[3]")
        check(lib.isect_shape_bounds(self._c, lo, hi), f"{type(self).__name__}.bounds")
        return np.array(list(lo), dtype=np.float64), np.array(list(hi), dtype=np.float64)

    def transformed(self: S, matrix: ArrayLike) -> S:
        """The same shape placed by an affine object-to-world transform.

        Args:
            matrix: a row-major 4x4 matrix (or 16 numbers) whose last row is
                0 0 0 1. If the shape is already transformed, the result is
                placed by ``matrix @ self.matrix``.

        Returns:
            A new shape of the same class sharing this shape's data. Rays are
            taken to object space by the inverse (t is preserved), hits are
            returned in world space.

        Raises:
            InvalidArgumentError: wrong shape, or last row not 0 0 0 1.
            NonFiniteError: NaN or infinity in the matrix.
            DegenerateError: a singular linear part.
        """
        m = as_matrix4(matrix)
        context = f"{type(self).__name__}.transformed"
        # isect_xform_init's checks, in its order, naming the element.
        detail = nonfinite_element(m, "matrix")
        if detail is not None:
            raise error_for(int(lib.ISECT_E_NONFINITE), context, detail=detail)
        if m[3].tolist() != [0.0, 0.0, 0.0, 1.0]:
            raise error_for(int(lib.ISECT_E_ARG), context, detail=(
                f"matrix[3] = {value_text(m[3])} is not [0.0, 0.0, 0.0, 1.0] (the last row "
                "of an affine object-to-world matrix)"))
        if self._matrix is not None:
            m = m @ self._matrix
        xform = ffi.new("isect_xform *")
        status = lib.isect_xform_init(xform, ffi.from_buffer("double[]", m))
        if status == lib.ISECT_E_DEGENERATE:
            raise error_for(status, context, detail=(
                f"matrix: the linear part {value_text(m[:3, :3])} is singular (the determinant "
                "of its rows scaled to unit length is at most 2^-40 in magnitude)"))
        check(status, context, "matrix")
        new = copy.copy(self)
        new._matrix = frozen(m)
        new._xform = xform
        new._describe()
        return new

    # -------------------------------------------------------------- queries

    def intersect(
        self,
        origins: ArrayLike,
        directions: ArrayLike,
        *,
        tmin: ArrayLike = 0.0,
        tmax: ArrayLike = math.inf,
        eps: float | None = None,
        cull_back: bool = False,
        any_hit: bool = False,
        threads: int | None = None,
        errors: str = "raise",
        progress: bool = False,
    ) -> Any:
        """Closest hit of each ray (``isect_intersect_batch``).

        Args:
            origins: ray origins, shape (..., 3); a single (3,) origin is
                broadcast against many directions.
            directions: ray directions, shape (..., 3); need not be unit
                length, never renormalised. A single (3,) direction is
                broadcast against many origins.
            tmin, tmax: the hit interval [tmin, tmax], scalars or arrays that
                broadcast with the batch shape.
            eps: tolerance of the epsilon policy (default ``EPS_DEFAULT``).
            cull_back: drop EXIT hits of thin surfaces (``ISECT_CULL_BACK``).
            any_hit: accept any hit (``ISECT_ANY_HIT``; occlusion queries).
            threads: split the batch over this many threads (the GIL is
                released during the C calls); None (the default): every core
                this process may run on (:func:`isect.default_threads`); 1:
                on the calling thread. The result is byte-identical for every
                value.
            errors: ``"raise"`` raises for the first bad ray (NaN/Inf, zero
                direction, NaN tmin/tmax), naming its flat index;
                ``"mark"`` returns bad rays as kind INVALID with t = NaN.
            progress: show a progress bar (tqdm if installed, else a
                percentage on standard error) while the batch runs; the
                result is the same.

        Returns:
            A ``HIT_DTYPE`` array of the broadcast batch shape, or a single
            ``HIT_DTYPE`` record when origins and directions are both (3,).
            Rays that hit nothing have kind MISS, t = +inf, prim = -1.

        One ray given as plain numbers (lists or tuples of 3 floats or ints,
        or float64 arrays of shape (3,)), with the default options, goes
        straight to the C call; the result is the same.
        """
        if (
            eps is None
            and cull_back is False
            and any_hit is False
            and threads is None
            and type(errors) is str
            and errors == "raise"
            and progress is False
        ):
            record = _closest_one(self._c, origins, directions, tmin, tmax)
            if record is not None:
                return record
        soa = _soa_columns(origins, directions, tmin, tmax)
        if soa is not None:
            hits, shape = self._closest_soa(soa, eps, cull_back, any_hit, threads, errors,
                                            progress)
        else:
            rays, shape = make_rays(origins, directions, tmin, tmax)
            hits = self._closest(rays, eps, cull_back, any_hit, threads, errors, "intersect",
                                 progress)
        return hits.reshape(shape)[()] if shape == () else hits.reshape(shape)

    def intersect_rays(
        self,
        rays: ArrayLike,
        *,
        eps: float | None = None,
        cull_back: bool = False,
        any_hit: bool = False,
        threads: int | None = None,
        errors: str = "raise",
        progress: bool = False,
    ) -> npt.NDArray[np.void]:
        """Closest hit of each ray of a ``RAY_DTYPE`` array, without copying it.

        The zero-copy form of :meth:`intersect`: a C-contiguous ``RAY_DTYPE``
        array is handed to C as it is (others are converted once). Arguments
        and result as for :meth:`intersect`; the result has ``rays.shape``.
        """
        flat, shape = as_ray_array(rays)
        hits = self._closest(flat, eps, cull_back, any_hit, threads, errors, "intersect_rays",
                             progress)
        return hits.reshape(shape)

    def intersect_all(
        self,
        origin: Vector3,
        direction: Vector3,
        *,
        tmin: float = 0.0,
        tmax: float = math.inf,
        eps: float | None = None,
        cull_back: bool = False,
        any_hit: bool = False,
    ) -> list[Hit]:
        """Every hit of one ray in [tmin, tmax], sorted by t (``isect_intersect``).

        Args:
            origin: the ray origin, 3 numbers.
            direction: the ray direction, 3 numbers (not renormalised).
            tmin, tmax: the hit interval.
            eps, cull_back, any_hit: options, as for :meth:`intersect`.

        Returns:
            A list of :class:`Hit` (kinds ENTER, EXIT, TOUCH), empty for a miss.

        Raises:
            NonFiniteError: NaN/Inf in the ray, NaN tmin/tmax, bad eps.
            DegenerateError: a zero direction.
            InvalidArgumentError: not 3 numbers, negative eps.
        """
        ray, ray_bytes, hits, hit_bytes, cap = _scratch.bufs
        try:
            ox, oy, oz = origin
            dx, dy, dz = direction
            # Plain numbers only (floats first: the common case, and cheap).
            if not (
                type(ox) is float and type(oy) is float and type(oz) is float
                and type(dx) is float and type(dy) is float and type(dz) is float
                and type(tmin) is float and type(tmax) is float
            ) and not _all_plain(ox, oy, oz, dx, dy, dz, tmin, tmax):
                raise TypeError
            _pack_ray(ray_bytes, 0, ox, oy, oz, dx, dy, dz, tmin, tmax)
        except (TypeError, ValueError, OverflowError, struct.error):
            # Anything but plain numbers (or an int beyond the doubles): the
            # general conversion, which names the argument it refuses.
            _pack_ray(
                ray_bytes, 0, *as_vector(origin, 3, "origin").tolist(),
                *as_vector(direction, 3, "direction").tolist(),
                as_scalar(tmin, "tmin"), as_scalar(tmax, "tmax"),
            )
        if eps is None and cull_back is False and any_hit is False:
            opts = _NULL
        else:
            opts = make_opts(eps, cull_back, any_hit)
        n = _c_intersect(self._c, ray, opts, hits, cap)
        if n > cap:  # more hits than the scratch holds (meshes): grow it, ask again
            _scratch.resize(n)
            ray2, ray_bytes2, hits, hit_bytes, cap = _scratch.bufs
            ray_bytes2[:] = ray_bytes
            n = _c_intersect(self._c, ray2, opts, hits, cap)
        if n < 0:
            org, dirn, lo, hi = ray.org, ray.dir, ray.tmin, ray.tmax
            culprit = ray_culprit(org, dirn, lo, hi, ("origin", "direction", "tmin", "tmax"))
            detail = ray_problem(org, dirn, lo, hi)  # names the argument and its value
            raise error_for(n, f"{type(self).__name__}.intersect_all",
                            arg=None if detail else culprit, detail=detail)
        out = []
        for offset in range(0, _HIT_SIZE * n, _HIT_SIZE):
            t, px, py, pz, nx, ny, nz, u, v, prim, kind = _unpack_hit(hit_bytes, offset)
            out.append(_tuple_new(Hit, (t, (px, py, pz), (nx, ny, nz), (u, v), prim, _KINDS[kind])))
        return out

    def intersect_all_batch(
        self,
        origins: ArrayLike,
        directions: ArrayLike,
        *,
        tmin: ArrayLike = 0.0,
        tmax: ArrayLike = math.inf,
        eps: float | None = None,
        cull_back: bool = False,
        any_hit: bool = False,
        threads: int | None = None,
        errors: str = "raise",
        progress: bool = False,
    ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.void]]:
        """Every hit of every ray, CSR style (``isect_intersect_all_batch``).

        Arguments as for :meth:`intersect`; the batch is flattened to n rays.

        Returns:
            ``(offsets, hits)``: ``offsets`` int64 of length n + 1, and ray i's
            hits, sorted by t, are ``hits[offsets[i]:offsets[i+1]]``
            (``HIT_DTYPE``). With ``errors="mark"`` a bad ray has one INVALID
            record.
        """
        rays, _ = make_rays(origins, directions, tmin, tmax)
        name = f"{type(self).__name__}.intersect_all_batch"
        raising = raise_on_bad(errors)
        nthreads = as_threads(threads)
        opts = make_opts(eps, cull_back, any_hit)
        n = rays.shape[0]
        rp = ffi.from_buffer("isect_ray[]", rays)

        def work(lo: int, hi: int) -> tuple[int, npt.NDArray[np.int64], npt.NDArray[np.void]]:
            """All hits of rays[lo:hi] into chunk-local offsets and hits."""
            m = hi - lo
            offsets = np.empty(m + 1, dtype=np.int64)
            op = ffi.from_buffer("int64_t[]", offsets)
            cap = max(16, 2 * m)
            hits = np.empty(cap, dtype=HIT_DTYPE)
            total = lib.isect_intersect_all_batch(
                self._c, rp + lo, m, opts, op, ffi.from_buffer("isect_hit[]", hits), cap
            )
            if total > cap:
                cap = total
                hits = np.empty(cap, dtype=HIT_DTYPE)
                total = lib.isect_intersect_all_batch(
                    self._c, rp + lo, m, opts, op, ffi.from_buffer("isect_hit[]", hits), cap
                )
            return total, offsets, hits[: max(total, 0)]

        parts = _batch.run(work, n, nthreads, _progress.reporter(progress, name, n, "ray"))
        for total, _, _ in parts:
            check(total, name)
        if len(parts) == 1:
            _, offsets, hits = parts[0]
            if hits.base is not None and 2 * len(hits) < len(hits.base):
                hits = hits.copy()  # do not keep a mostly unused buffer alive
        else:
            offsets = np.empty(n + 1, dtype=np.int64)
            offsets[0] = 0
            base, lo = 0, 0
            for total, part_offsets, _ in parts:
                m = len(part_offsets) - 1
                offsets[lo + 1 : lo + m + 1] = part_offsets[1:] + base
                base += total
                lo += m
            hits = np.concatenate([h for _, _, h in parts])
        if raising:
            bad = hits["kind"] == _INVALID
            if bad.any():
                ray = int(np.searchsorted(offsets, int(bad.argmax()), side="right")) - 1
                self._raise_bad_ray(rp, ray, opts, name)
        return offsets, hits

    def spawn(
        self,
        hits: HitsLike,
        directions: ArrayLike,
        *,
        threads: int | None = None,
        progress: bool = False,
    ) -> Any:
        """Secondary rays leaving this shape's surface at hits (``isect_spawn_ray``).

        Each ray starts at its hit's point moved along the hit's normal by the
        fewest whole ulps (1, 2, 4, ...) that put it strictly on the side of the
        surface its direction points into, as the shape's exact side test
        decides it; so intersecting the ray with this shape never finds the
        surface it leaves at t ~ 0, and still finds any other surface more
        than a few ulps away (a reflection, a refraction, a shadow ray). The
        ray's direction is the given one, ``tmin`` 0 and ``tmax`` +inf.

        Args:
            hits: hits this shape reported (in world space): a ``HIT_DTYPE``
                array of shape (N,) (or any shape), a single ``HIT_DTYPE``
                record, or a :class:`Hit` (or a list of them).
            directions: the new directions, (N, 3) or (3,); they need not be
                unit length. Hits and directions broadcast against each other
                (one hit with many directions, or one direction for many hits).
            threads: split a large batch over this many threads (the GIL is
                released); None (the default): every core; the result is the
                same for every value.
            progress: show a progress bar while the batch runs (as for
                :meth:`intersect`).

        Returns:
            A ``RAY_DTYPE`` array of the broadcast shape, or a single
            ``RAY_DTYPE`` record for one hit and one (3,) direction. Pass it
            to :meth:`intersect_rays`, or its fields to :meth:`intersect`.

        Raises:
            InvalidArgumentError: a hit whose kind is not ENTER, EXIT or TOUCH
                (a MISS or INVALID record of a batch), a zero normal, a prim
                that is not one of this shape's (a mesh face index out of
                range), arrays of the wrong dtype or shape.
            NonFiniteError: NaN or infinity in a hit or a direction.
            DegenerateError: a zero direction, or a hit that is not near the
                surface (no offset leaves it).
            The error names the flat index of the first bad row (``index``).
        """
        name = f"{type(self).__name__}.spawn"
        harr = _as_hit_array(hits, name)
        dirs = as_points(directions, 3, "directions")
        try:
            shape = np.broadcast_shapes(harr.shape, dirs.shape[:-1])
        except ValueError:
            raise invalid(
                f"{name}: cannot broadcast hits {harr.shape} and directions {dirs.shape} together"
            ) from None
        n = math.prod(shape)
        if harr.size == 1 and n != 1:
            hflat, hit_step = np.ascontiguousarray(harr.reshape(1)), 0
        else:
            hflat, hit_step = _flat_contiguous(harr, shape), 1
        if dirs.shape[:-1] != shape and math.prod(dirs.shape[:-1]) == 1:
            dflat, dir_step = np.ascontiguousarray(dirs.reshape(3), dtype=np.float64), 0
        else:
            dflat = _flat_contiguous(np.asarray(dirs, dtype=np.float64), (*shape, 3))
            dir_step = 3
        out = np.empty(n, dtype=RAY_DTYPE)
        hp = ffi.from_buffer("isect_hit[]", hflat)
        dp = ffi.from_buffer("double[]", dflat)
        op = ffi.from_buffer("isect_ray[]", out)
        c = self._c

        def work(lo: int, hi: int) -> tuple[int, int]:
            """One chunk: (status, index of its first bad row or -1)."""
            bad = ffi.new("int64_t *")
            status = lib.pyisect_spawn_batch(
                c, hp + lo * hit_step, hit_step, dp + lo * dir_step, dir_step, hi - lo, op + lo, bad
            )
            return int(status), (lo + int(bad[0]) if status < 0 else -1)

        nthreads = as_threads(threads)
        report = _progress.reporter(progress, name, n, "ray")
        for status, index in _batch.run(work, n, nthreads, report):
            if status < 0:
                d = dflat[index * dir_step:index * dir_step + 3]
                arg, detail = self._spawn_problem(hflat[index * hit_step], d)
                raise error_for(status, name, index=index, item="hit", arg=arg, detail=detail)
        return out.reshape(shape)[()] if shape == () else out.reshape(shape)

    def _spawn_problem(self, hit: Any, d: npt.NDArray[np.float64]) -> tuple[str, str]:
        """The argument and what is wrong with a row that :meth:`spawn`
        refused, with its values, by the checks of ``isect_spawn_ray`` in
        their order."""
        kind, prim = int(hit["kind"]), int(hit["prim"])
        point, normal = hit["point"], hit["normal"]
        if kind not in _HIT_KINDS:
            what = _KINDS[kind].name if 0 <= kind < len(_KINDS) else "not a kind"
            return "hits", (f"kind = {kind} ({what}) is not a hit: ENTER, EXIT or TOUCH (a batch "
                            "writes MISS for a ray that hit nothing, INVALID for a bad ray)")
        faces = self._prim_count()
        if faces is not None and not 0 <= prim < faces:
            return "hits", f"prim = {prim} is outside [0, {faces}) (the mesh's faces)"
        for field, values in (("point", point), ("normal", normal)):
            if not np.isfinite(values).all():
                return "hits", f"{field} = {value_text(values)} is not finite"
        if not np.isfinite(d).all():
            return "directions", f"direction = {value_text(d)} is not finite"
        if not d.any():
            return "directions", f"direction = {value_text(d)} is zero"
        if not normal.any():
            return "hits", f"normal = {value_text(normal)} is zero (not the record of a hit)"
        return "hits", (f"no offset of point = {value_text(point)} along its normal leaves the "
                        f"surface in direction {value_text(d)} (a point not near the surface, a "
                        "degenerate shape, or a direction running inward along another face "
                        "through the edge or corner the hit lies on)")

    def _prim_count(self) -> int | None:
        """The number of valid hit prims (a mesh's faces), None if any is valid."""
        return None

    # ------------------------------------------------------------ internals

    def _closest(
        self,
        rays: np.ndarray,
        eps: float | None,
        cull_back: bool,
        any_hit: bool,
        threads: int | None,
        errors: str,
        method: str,
        progress: bool = False,
    ) -> npt.NDArray[np.void]:
        """Run ``isect_intersect_batch`` over a flat contiguous ray array."""
        name = f"{type(self).__name__}.{method}"
        raising = raise_on_bad(errors)
        nthreads = as_threads(threads)
        opts = make_opts(eps, cull_back, any_hit)
        n = rays.shape[0]
        hits = np.empty(n, dtype=HIT_DTYPE)
        rp = ffi.from_buffer("isect_ray[]", rays)
        hp = ffi.from_buffer("isect_hit[]", hits)
        c = self._c

        def work(lo: int, hi: int) -> tuple[int, int]:
            """One chunk [lo, hi): the C loop; its status and first bad ray."""
            bad = ffi.new("int64_t *")
            status = lib.pyisect_closest(c, rp + lo, hi - lo, opts, hp + lo, bad)
            return int(status), (lo + int(bad[0]) if bad[0] >= 0 else -1)

        results = _batch.run(work, n, nthreads, _progress.reporter(progress, name, n, "ray"))
        for status, _ in results:
            check(status, name)
        if raising:
            first = [b for _, b in results if b >= 0]
            if first:
                args = ("rays",) if method == "intersect_rays" else _RAY_ARGS
                self._raise_bad_ray(rp, first[0], opts, name, args)
        return hits

    def _closest_soa(
        self,
        soa: tuple[Any, ...],
        eps: float | None,
        cull_back: bool,
        any_hit: bool,
        threads: int | None,
        errors: str,
        progress: bool = False,
    ) -> tuple[npt.NDArray[np.void], tuple[int, ...]]:
        """``intersect`` over separate columns (``_soa_columns``), packed in C."""
        name = f"{type(self).__name__}.intersect"
        raising = raise_on_bad(errors)
        nthreads = as_threads(threads)
        opts = make_opts(eps, cull_back, any_hit)
        (org, org_step), (dirs, dir_step), (lo, lo_step), (hi, hi_step), shape = soa
        n = math.prod(shape)
        hits = np.empty(n, dtype=HIT_DTYPE)
        op, dp = ffi.from_buffer("double[]", org), ffi.from_buffer("double[]", dirs)
        lp, hp_ = ffi.from_buffer("double[]", lo), ffi.from_buffer("double[]", hi)
        out = ffi.from_buffer("isect_hit[]", hits)
        c = self._c

        def work(a: int, b: int) -> tuple[int, int]:
            """One chunk [a, b): the C loop; its status and first bad ray."""
            bad = ffi.new("int64_t *")
            status = lib.pyisect_closest_soa(
                c, op + a * org_step, org_step, dp + a * dir_step, dir_step, lp + a * lo_step,
                lo_step, hp_ + a * hi_step, hi_step, b - a, opts, out + a, bad)
            return int(status), (a + int(bad[0]) if bad[0] >= 0 else -1)

        results = _batch.run(work, n, nthreads, _progress.reporter(progress, name, n, "ray"))
        for status, _ in results:
            check(status, name)
        if raising:
            first = [b for _, b in results if b >= 0]
            if first:
                index = first[0]
                one, _ = make_rays(org[index * org_step:index * org_step + 3],
                                   dirs[index * dir_step:index * dir_step + 3],
                                   lo[index * lo_step], hi[index * hi_step])
                rp = ffi.from_buffer("isect_ray[]", one)
                status = lib.isect_intersect(c, rp, opts, ffi.NULL, 0)
                raise_bad_element(status, name, index, "ray", _ray_arg(rp[0], _RAY_ARGS),
                                  _ray_detail(rp[0]))
        return hits, shape

    def _raise_bad_ray(
        self, rp: Any, index: int, opts: Any, name: str, args: Sequence[str] = ()
    ) -> None:
        """Raise the error the scalar call reports for the batch's bad ray,
        naming which of ``args`` (origins, directions, tmin, tmax) holds it."""
        status = lib.isect_intersect(self._c, rp + index, opts, ffi.NULL, 0)
        raise_bad_element(status, name, index, "ray", _ray_arg(rp[index], args or _RAY_ARGS),
                          _ray_detail(rp[index]))

    def _repr_fields(self) -> str:
        """The constructor arguments, for repr()."""
        return f"data={self._data.tolist()}"

    def __repr__(self) -> str:
        """The constructor call that rebuilds the shape, and its transform."""
        text = f"{type(self).__name__}({self._repr_fields()})"
        if self._matrix is not None:
            text += f".transformed({self._matrix.tolist()})"
        return text

    def __copy__(self: S) -> S:
        """A shallow copy sharing every field (the data array, a mesh handle):
        what :meth:`transformed` starts from, without rebuilding the shape."""
        new = object.__new__(type(self))
        for cls in type(self).__mro__:
            for name in getattr(cls, "__slots__", ()):
                if name != "__weakref__" and hasattr(self, name):
                    setattr(new, name, getattr(self, name))
        return new

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as (class, data, n, flags, matrix)."""
        return (_rebuild, (type(self), self._data, self._n, self._flags, self._matrix))


class Solid(Shape):
    """A shape with an inside: :meth:`contains` applies."""

    __slots__ = ()

    def _contains_refusal(self) -> str | None:
        """Why this shape has no inside after all (an open cylinder), or None."""
        return None

    def contains(
        self, points: ArrayLike, *, threads: int | None = None, progress: bool = False
    ) -> Any:
        """Whether each point lies in the closed solid (``isect_contains_batch``).

        Args:
            points: shape (..., 3).
            threads: split the batch over this many threads; None (the
                default): every core; the result is the same for every value.
            progress: show a progress bar while the batch runs (as for
                :meth:`~Shape.intersect`).

        Returns:
            A bool array of shape (...), or a bool for a single (3,) point.

        Raises:
            NonFiniteError: a point with NaN/Inf (``index`` names the first).
            InvalidArgumentError: points not of shape (..., 3); an open
                (uncapped) cylinder, which is a thin surface.
        """
        return self._contains(self._c, points, threads, f"{type(self).__name__}.contains",
                              progress)

    def _contains(
        self, c: Any, points: ArrayLike, threads: int | None, name: str, progress: bool = False
    ) -> Any:
        """``isect_contains_batch`` with descriptor ``c`` (this shape's, or a
        mesh's with another containment rule)."""
        refusal = self._contains_refusal()
        if refusal is not None:
            raise error_for(int(lib.ISECT_E_ARG), name, detail=refusal)
        pts = as_points(points, 3, "points")
        shape = pts.shape[:-1]
        flat = np.ascontiguousarray(pts.reshape(-1, 3))
        n = flat.shape[0]
        inside = np.empty(n, dtype=np.uint8)
        pp = ffi.from_buffer("double[]", flat)
        ip = ffi.from_buffer("uint8_t[]", inside)

        def work(lo: int, hi: int) -> int:
            """One chunk of the batch: the C call over [lo, hi)."""
            return int(lib.isect_contains_batch(c, pp + 3 * lo, hi - lo, ip + lo))

        nthreads = as_threads(threads)
        report = _progress.reporter(progress, name, n, "point")
        for status in _batch.run(work, n, nthreads, report):
            check(status, name)
        bad = inside == _INVALID
        if bad.any():
            index = int(bad.argmax())
            raise_bad_element(lib.isect_contains(c, pp + 3 * index), name, index, "point",
                              "points", point_problem(flat[index]))
        result = inside.view(np.bool_).reshape(shape)
        return bool(result) if shape == () else result


#: What :meth:`Shape.spawn` takes as hits: ``HIT_DTYPE`` arrays or records, or
#: :class:`Hit` tuples.
HitsLike = ArrayLike | Hit | Sequence[Hit]


def _as_hit_array(hits: Any, name: str) -> np.ndarray:
    """``hits`` as a ``HIT_DTYPE`` array (no copy when it already is one)."""
    if isinstance(hits, Hit) or (
        isinstance(hits, (list, tuple)) and hits and all(isinstance(h, Hit) for h in hits)
    ):
        rows = [hits] if isinstance(hits, Hit) else list(hits)
        a = np.zeros(len(rows), dtype=HIT_DTYPE)
        for field, shape in (("t", ()), ("point", (3,)), ("normal", (3,)), ("uv", (2,))):
            column = as_float_array([getattr(h, field) for h in rows], f"hits.{field}")
            if column.shape != (len(rows), *shape):
                raise invalid(f"hits.{field}: expected {shape or 'a number'} per hit")
            a[field] = column
        for field in ("prim", "kind"):
            a[field] = [as_int32(getattr(h, field), f"hits.{field}") for h in rows]
        return a.reshape(()) if isinstance(hits, Hit) else a
    return as_records(hits, HIT_DTYPE, "hits", "HIT_DTYPE records or Hit tuples")


def _flat_contiguous(a: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    """``a`` broadcast to ``shape``, flattened and C-contiguous (a copy only when needed)."""
    if a.shape != shape:
        a = np.broadcast_to(a, shape)
    return np.ascontiguousarray(a).reshape(-1)


#: The arguments of a ray, as Shape.intersect names them.
_RAY_ARGS = ("origins", "directions", "tmin", "tmax")


def _ray_arg(ray: Any, args: Sequence[str]) -> str:
    """Which of ``args`` holds the problem of the bad ``isect_ray`` ``ray``
    (one name when ``args`` is a single name, as for ``intersect_rays``)."""
    if len(args) == 1:
        return args[0]
    return ray_culprit(ray.org, ray.dir, ray.tmin, ray.tmax, args)


def point_problem(point: npt.NDArray[np.float64]) -> str | None:
    """What is wrong with a point a batch refused: its value when not finite;
    None otherwise (finite, but its image under a transform is not)."""
    if np.isfinite(point).all():
        return None
    return f"{value_text(point)} is not finite"


def _ray_detail(ray: Any) -> str | None:
    """What is wrong with the bad ``isect_ray`` ``ray``, with its values."""
    return ray_problem(ray.org, ray.dir, ray.tmin, ray.tmax)


def raise_bad_element(
    status: int, name: str, index: int, item: str, arg: str | None = None,
    detail: str | None = None,
) -> None:
    """Raise for element ``index`` that a batch call marked INVALID, with the
    error the matching scalar call reports for it (``status``), naming the
    argument ``arg`` that holds it and, in ``detail``, the value."""
    if status >= 0:
        raise IsectError(
            f"{name}: {item} {index} was marked INVALID by the batch call, "
            "but the scalar call accepts it",
            index=index,
        )
    raise error_for(status, name, index=index, item=item, arg=arg, detail=detail)


def _rebuild(
    cls: type[Shape],
    data: npt.NDArray[np.float64],
    n: int,
    flags: int,
    matrix: npt.NDArray[np.float64] | None,
) -> Shape:
    """Unpickle a shape."""
    shape = cls.__new__(cls)
    shape._setup(np.array(data, dtype=np.float64, order="C", copy=True), n, flags)
    return shape if matrix is None else shape.transformed(matrix)


def frozen(a: npt.NDArray[T]) -> npt.NDArray[T]:
    """A read-only C-contiguous copy of ``a`` that can never be made writeable.

    Its memory is an immutable ``bytes`` object, so numpy refuses
    ``flags.writeable = True`` on it and on every view of it (ValueError:
    "cannot set WRITEABLE flag to True of this array"); an array that owns its
    memory would allow it. Shapes keep their numbers (and meshes their
    indices) in such arrays: what the C descriptor points at cannot change.
    """
    out = np.frombuffer(np.ascontiguousarray(a).tobytes(), dtype=a.dtype).reshape(a.shape)
    if not out.flags.aligned:  # pragma: no cover - bytes data is 8-byte aligned
        out = np.frombuffer(bytes(out.tobytes()), dtype=a.dtype).reshape(a.shape)
    return out


def readonly_view(a: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """A read-only view of (part of) a shape's data."""
    v = a.view()
    v.flags.writeable = False
    return v
