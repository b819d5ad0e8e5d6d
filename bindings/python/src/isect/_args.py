# SPDX-License-Identifier: Apache-2.0
"""Argument coercion: Python and numpy inputs to the contiguous float64 arrays
and C structs that libisect reads. Only marshalling happens here, no geometry.
"""

from __future__ import annotations

import math
import numbers
import operator
from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from ._batch import default_threads
from ._errors import invalid, nonfinite, value_text
from ._isect import ffi, lib
from ._types import RAY_DTYPE

ArrayLike = npt.ArrayLike
#: One 3-vector: a sequence of 3 numbers or a (3,) array.
Vector3 = Sequence[float] | npt.NDArray[Any]
#: A polygon fill rule: "evenodd", "nonzero", or the C value (passed through).
Rule = str | int

_RULES = {"evenodd": lib.ISECT_EVEN_ODD, "nonzero": lib.ISECT_NONZERO}
_OPTS_SIZE = ffi.sizeof("isect_opts")


#: numpy dtype kinds that are real numbers: bool, signed and unsigned
#: integers, floating point. Complex (the imaginary part would be lost),
#: datetime64 / timedelta64, strings, bytes, structured and object arrays
#: of anything but real numbers are refused, not converted.
_REAL_KINDS = frozenset("biuf")
_KIND_NAMES = {
    "c": "complex numbers",
    "m": "timedelta64 values",
    "M": "datetime64 values",
    "U": "strings",
    "S": "bytes",
    "V": "structured or raw records",
}


def as_float_array(x: ArrayLike, name: str) -> npt.NDArray[np.float64]:
    """``x`` as a float64 array (no copy if it already is one).

    Accepts real numbers only: arrays of bool, integer or floating dtype, and
    Python numbers or sequences of them (ints beyond int64, which numpy keeps
    as objects, become the nearest double). Anything else — complex,
    datetime64, timedelta64, strings, bytes, ``None``, other objects — and an
    integer beyond the range of doubles is an :class:`InvalidArgumentError`
    naming ``name``.
    """
    if type(x) is np.ndarray and x.dtype == np.float64:
        return x
    try:
        a = np.asarray(x)
    except (TypeError, ValueError, OverflowError) as exc:
        raise invalid(f"{name}: not an array of numbers ({exc})") from None
    kind = a.dtype.kind
    if kind == "O":
        for v in a.flat:
            if not isinstance(v, numbers.Real):
                raise invalid(f"{name}: expected real numbers, got {type(v).__name__} {v!r:.40}")
        try:
            return a.astype(np.float64)
        except OverflowError:
            raise invalid(f"{name}: a number too large for a double") from None
        except (TypeError, ValueError) as exc:  # pragma: no cover - a Real without __float__
            raise invalid(f"{name}: not an array of numbers ({exc})") from None
    if kind not in _REAL_KINDS:
        what = _KIND_NAMES.get(kind, f"dtype {a.dtype}")
        raise invalid(f"{name}: expected real numbers, got {what} (dtype {a.dtype})")
    return a.astype(np.float64, copy=False)


def as_vector(x: ArrayLike, k: int, name: str) -> npt.NDArray[np.float64]:
    """A fresh contiguous float64 array of shape (k,)."""
    a = as_float_array(x, name)
    if a.shape != (k,):
        raise invalid(f"{name}: expected {k} numbers, got an array of shape {a.shape}")
    return np.array(a, dtype=np.float64, order="C", copy=True)


def as_rows(x: ArrayLike, k: int, name: str) -> npt.NDArray[np.float64]:
    """A fresh contiguous float64 array of shape (n, k); n may be anything >= 0."""
    a = as_float_array(x, name)
    if a.ndim != 2 or a.shape[1] != k:
        if a.size == 0:
            return np.zeros((0, k), dtype=np.float64)
        raise invalid(f"{name}: expected an array of shape (n, {k}), got {a.shape}")
    return np.array(a, dtype=np.float64, order="C", copy=True)


def as_points(x: ArrayLike, k: int, name: str) -> npt.NDArray[np.float64]:
    """A float64 array of shape (..., k): one or many k-vectors (no copy if possible)."""
    a = as_float_array(x, name)
    if a.ndim == 0 or a.shape[-1] != k:
        raise invalid(f"{name}: expected an array of shape (..., {k}), got {a.shape}")
    return a


def as_scalar(x: Any, name: str) -> float:
    """A Python float from a number or 0-d array."""
    a = as_float_array(x, name)
    if a.shape != ():
        raise invalid(f"{name}: expected a number, got an array of shape {a.shape}")
    return float(a)


def as_int(x: Any, name: str) -> int:
    """A Python int from an integer (bool excluded)."""
    if isinstance(x, (bool, np.bool_)):
        raise invalid(f"{name}: expected an integer, got a bool")
    try:
        return operator.index(x)
    except TypeError:
        raise invalid(f"{name}: expected an integer, got {type(x).__name__}") from None


_INT32_MIN, _INT32_MAX = -(2**31), 2**31 - 1


def as_int32(x: Any, name: str) -> int:
    """An integer that a C ``int`` / ``int32_t`` argument holds (a flag, a
    rule); beyond that range an :class:`InvalidArgumentError` naming ``name``
    (the C library would reject any such value as unknown anyway)."""
    n = as_int(x, name)
    if not _INT32_MIN <= n <= _INT32_MAX:
        raise invalid(f"{name}: {n} is out of the range of a C int")
    return n


def as_flag(x: Any, name: str) -> bool:
    """A yes/no option: a bool (or numpy bool); anything else is an
    :class:`InvalidArgumentError` naming ``name``."""
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    raise invalid(f"{name}: expected True or False, got {type(x).__name__} {x!r:.40}")


def as_matrix4(m: ArrayLike) -> npt.NDArray[np.float64]:
    """A fresh row-major (4, 4) float64 matrix from a 4x4 array or 16 numbers."""
    a = as_float_array(m, "matrix")
    if a.shape not in ((4, 4), (16,)):
        raise invalid(f"matrix: expected a 4x4 matrix or 16 numbers, got shape {a.shape}")
    return np.array(a.reshape(4, 4), dtype=np.float64, order="C", copy=True)


def as_rule(rule: Rule) -> int:
    """The C fill rule for "evenodd" / "nonzero"; integers pass through to C."""
    if isinstance(rule, str):
        try:
            return int(_RULES[rule])
        except KeyError:
            raise invalid(f"rule: expected 'evenodd' or 'nonzero', got {rule!r}") from None
    return as_int32(rule, "rule")


def as_threads(threads: Any) -> int:
    """Number of threads for a batch: None means every core this process may
    run on (:func:`isect.default_threads`); 1 keeps the batch on the calling
    thread."""
    if threads is None:
        return default_threads()
    n = as_int(threads, "threads")
    if n < 1:
        raise invalid(f"threads: expected None or an integer >= 1, got {n}")
    return n


def raise_on_bad(errors: str) -> bool:
    """True for errors="raise", False for errors="mark"."""
    if errors == "raise":
        return True
    if errors == "mark":
        return False
    raise invalid(f"errors: expected 'raise' or 'mark', got {errors!r}")


def make_opts(eps: Any, cull_back: bool, any_hit: bool) -> Any:
    """An ``isect_opts *`` for the options, or NULL when all are defaults."""
    flags = (lib.ISECT_CULL_BACK if as_flag(cull_back, "cull_back") else 0) | (
        lib.ISECT_ANY_HIT if as_flag(any_hit, "any_hit") else 0
    )
    if eps is None and not flags:
        return ffi.NULL
    value = float(lib.ISECT_EPS_DEFAULT) if eps is None else as_scalar(eps, "eps")
    # The C library's own rules (isect_opts), checked here to name eps.
    if not math.isfinite(value):
        raise nonfinite(f"eps: expected a finite number, got {value}")
    if value < 0:
        raise invalid(f"eps: expected a number >= 0, got {value}")
    return ffi.new("isect_opts *", (_OPTS_SIZE, flags, value))


def ray_culprit(org: Any, dirn: Any, tmin: float, tmax: float, names: Sequence[str]) -> str:
    """Which of a bad ray's arguments (``names``: origin, direction, tmin,
    tmax) holds the problem the C library reports for it (its ray check:
    NaN or infinity first, then a zero direction)."""
    if not all(math.isfinite(v) for v in org):
        return names[0]
    if not all(math.isfinite(v) for v in dirn):
        return names[1]
    if math.isnan(tmin):
        return names[2]
    if math.isnan(tmax):
        return names[3]
    if not any(dirn):
        return names[1]
    return ", ".join(names)  # not one of the documented problems: all of them


def ray_problem(org: Any, dirn: Any, tmin: float, tmax: float) -> str | None:
    """What is wrong with a bad ray, naming the field and its value, in the
    order of the C library's ray check (``origin = [nan, 0.0, -5.0] is not
    finite``, ``direction = [0.0, 0.0, 0.0] is zero``); None for a ray with
    none of those problems."""
    org, dirn = [float(v) for v in org], [float(v) for v in dirn]
    if not all(math.isfinite(v) for v in org):
        return f"origin = {value_text(org)} is not finite"
    if not all(math.isfinite(v) for v in dirn):
        return f"direction = {value_text(dirn)} is not finite"
    if math.isnan(tmin):
        return "tmin = nan is not a number"
    if math.isnan(tmax):
        return "tmax = nan is not a number"
    if not any(dirn):
        return f"direction = {value_text(dirn)} is zero (a ray needs a direction)"
    return None


def ray_columns(
    origins: ArrayLike, directions: ArrayLike, tmin: ArrayLike, tmax: ArrayLike
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, tuple[int, ...]]:
    """Origins (..., 3), directions (..., 3), tmin and tmax (...) as float64
    arrays, and the batch shape they broadcast to (InvalidArgumentError if
    they do not)."""
    org = as_points(origins, 3, "origins")
    dirs = as_points(directions, 3, "directions")
    lo = as_float_array(tmin, "tmin")
    hi = as_float_array(tmax, "tmax")
    try:
        shape = np.broadcast_shapes(org.shape[:-1], dirs.shape[:-1], lo.shape, hi.shape)
    except ValueError:
        raise invalid(
            f"cannot broadcast origins {org.shape}, directions {dirs.shape}, "
            f"tmin {lo.shape} and tmax {hi.shape} together"
        ) from None
    return org, dirs, lo, hi, shape


def make_rays(
    origins: ArrayLike, directions: ArrayLike, tmin: ArrayLike, tmax: ArrayLike
) -> tuple[np.ndarray, tuple[int, ...]]:
    """Broadcast origins (..., 3), directions (..., 3), tmin and tmax (...) into
    one contiguous ``RAY_DTYPE`` array.

    Returns the flat (n,) ray array and the broadcast batch shape.
    """
    org, dirs, lo, hi, shape = ray_columns(origins, directions, tmin, tmax)
    rays = np.empty(shape, dtype=RAY_DTYPE)
    rays["org"] = org
    rays["dir"] = dirs
    rays["tmin"] = lo
    rays["tmax"] = hi
    return rays.reshape(-1), shape


def as_ray_array(rays: ArrayLike) -> tuple[np.ndarray, tuple[int, ...]]:
    """A contiguous flat ``RAY_DTYPE`` view (or copy) of ``rays`` and its shape."""
    a = as_records(rays, RAY_DTYPE, "rays", "RAY_DTYPE")
    a = np.ascontiguousarray(a)
    return a.reshape(-1), a.shape


def as_records(x: ArrayLike, dtype: np.dtype, name: str, dtype_name: str) -> np.ndarray:
    """``x`` as an array of the structured ``dtype`` (no copy when it is one).

    Another structured dtype with the same field names is converted, provided
    every field holds real numbers of the same shape; anything else is an
    :class:`InvalidArgumentError` naming ``name``.
    """
    try:
        a = np.asarray(x)
    except (TypeError, ValueError) as exc:
        raise invalid(f"{name}: expected an array of {dtype_name} ({exc})") from None
    if a.dtype == dtype:
        return a
    fields = a.dtype.fields
    if fields is None or set(fields) != set(dtype.fields or ()):
        raise invalid(f"{name}: expected an array of {dtype_name}, got dtype {a.dtype}")
    for field, (ftype, *_) in fields.items():
        want = dtype.fields[field][0]  # type: ignore[index]
        if ftype.base.kind not in _REAL_KINDS or ftype.shape != want.shape:
            raise invalid(
                f"{name}: field {field!r} must hold real numbers of shape {want.shape}, "
                f"got {ftype}"
            )
    try:
        return a.astype(dtype)
    except (TypeError, ValueError, OverflowError) as exc:  # pragma: no cover - kinds checked
        raise invalid(f"{name}: cannot convert to {dtype_name} ({exc})") from None
