# SPDX-License-Identifier: Apache-2.0
"""numpy dtypes that mirror the C structs, the hit kinds, and the Hit tuple.

``RAY_DTYPE`` and ``HIT_DTYPE`` are built from ``ffi.offsetof`` / ``ffi.sizeof``
of the compiled structs, so they match the C layout byte for byte by
construction; the import additionally checks the documented sizes (64 and 80
bytes), and cffi itself verified the field layout when the extension was built.
"""

from __future__ import annotations

import enum
from typing import NamedTuple

import numpy as np

from ._isect import ffi, lib

_F8 = np.dtype(np.float64)
_I4 = np.dtype(np.int32)


def _struct_dtype(ctype: str, fields: list[tuple[str, np.dtype, tuple[int, ...]]]) -> np.dtype:
    """A structured dtype with the C struct's field offsets and size."""
    return np.dtype(
        {
            "names": [name for name, _, _ in fields],
            "formats": [(base, shape) if shape else base for _, base, shape in fields],
            "offsets": [ffi.offsetof(ctype, name) for name, _, _ in fields],
            "itemsize": ffi.sizeof(ctype),
        }
    )


#: One ray, ``isect_ray``: ``org`` (3,), ``dir`` (3,), ``tmin``, ``tmax``; 64 bytes.
RAY_DTYPE: np.dtype = _struct_dtype(
    "isect_ray",
    [("org", _F8, (3,)), ("dir", _F8, (3,)), ("tmin", _F8, ()), ("tmax", _F8, ())],
)

#: One hit, ``isect_hit``: ``t``, ``point`` (3,), ``normal`` (3,), ``uv`` (2,),
#: ``prim`` (int32), ``kind`` (int32, a :class:`HitKind` value); 80 bytes.
HIT_DTYPE: np.dtype = _struct_dtype(
    "isect_hit",
    [
        ("t", _F8, ()),
        ("point", _F8, (3,)),
        ("normal", _F8, (3,)),
        ("uv", _F8, (2,)),
        ("prim", _I4, ()),
        ("kind", _I4, ()),
    ],
)

if RAY_DTYPE.itemsize != 64 or HIT_DTYPE.itemsize != 80:  # pragma: no cover
    raise ImportError(
        f"isect: unexpected C struct sizes (isect_ray {RAY_DTYPE.itemsize}, "
        f"isect_hit {HIT_DTYPE.itemsize}); the extension does not match isect.h"
    )

#: The default tolerance of the epsilon policy (``ISECT_EPS_DEFAULT``).
EPS_DEFAULT: float = float(lib.ISECT_EPS_DEFAULT)


class HitKind(enum.IntEnum):
    """What a hit is, with the values of the C constants ``ISECT_*``."""

    #: Batch output only: the ray hit nothing in [tmin, tmax] (t = +inf).
    MISS = lib.ISECT_MISS
    #: dir·normal < 0: entering a solid, or the front side of a thin surface.
    ENTER = lib.ISECT_ENTER
    #: dir·normal > 0: leaving a solid, or the back side of a thin surface.
    EXIT = lib.ISECT_EXIT
    #: Tangent contact, reported once.
    TOUCH = lib.ISECT_TOUCH
    #: Batch output only: that ray was bad (NaN/Inf, zero direction); t = NaN.
    INVALID = lib.ISECT_INVALID


#: HitKind members indexed by their value, for fast conversion of C ints.
KIND_BY_VALUE: tuple[HitKind, ...] = tuple(sorted(HitKind, key=int))
if [int(k) for k in KIND_BY_VALUE] != list(range(len(KIND_BY_VALUE))):  # pragma: no cover
    raise ImportError("isect: the ISECT_* hit kinds are not 0..4")


class Hit(NamedTuple):
    """One intersection, as returned by ``Shape.intersect_all``.

    Attributes:
        t: the ray parameter of the hit (P = org + t*dir).
        point: the hit point (x, y, z).
        normal: the unit normal there: outward for solids, the surface's own
            normal for thin surfaces.
        uv: triangle: barycentric weights of vertices b and c; else (0, 0).
        prim: the sub-part hit (box face 0..5 = -x,+x,-y,+y,-z,+z, convex
            plane index, cylinder 0 side / 1 cap at p0 / 2 cap at p1), or -1.
        kind: ENTER, EXIT or TOUCH.
    """

    t: float
    point: tuple[float, float, float]
    normal: tuple[float, float, float]
    uv: tuple[float, float]
    prim: int
    kind: HitKind
