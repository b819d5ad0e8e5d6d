# SPDX-License-Identifier: Apache-2.0
"""The exception hierarchy and the one table that maps C status codes to it.

Every error the package raises for a bad argument is an :class:`IsectError`
whose class is chosen by :data:`STATUS_ERRORS` from the libisect status code
(``ISECT_E_*``) — whether the C library reported it or the Python layer found
it first (for example an array of the wrong shape, which is ``ISECT_E_ARG``).
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from ._isect import ffi, lib


class IsectError(Exception):
    """Base class of every error reported by libisect.

    Attributes:
        status: the libisect status code (``ISECT_E_*``, negative).
        index: in a batch call, the flat index of the first offending ray or
            point; ``None`` otherwise.
    """

    status: ClassVar[int] = 0

    def __init__(self, message: str, *, index: int | None = None) -> None:
        """Create the error with its message and, for a batch, the element index."""
        super().__init__(message)
        self.index = index


class InvalidArgumentError(IsectError, ValueError):
    """``ISECT_E_ARG``: a missing or malformed argument — wrong array shape,
    bad count, negative radius, negative eps, unknown rule, flag or option."""

    status = lib.ISECT_E_ARG


class NonFiniteError(IsectError, ValueError):
    """``ISECT_E_NONFINITE``: NaN or infinity where a finite number is required
    (ray origin or direction, NaN tmin/tmax, shape data, eps, a point)."""

    status = lib.ISECT_E_NONFINITE


class DegenerateError(IsectError, ValueError):
    """``ISECT_E_DEGENERATE``: a zero ray direction, a singular transform, or
    the normal of a polygon of zero area."""

    status = lib.ISECT_E_DEGENERATE


class OutOfMemoryError(IsectError, MemoryError):
    """``ISECT_E_NOMEM``: the C library could not allocate memory."""

    status = lib.ISECT_E_NOMEM


#: The one mapping from C status codes to exception classes.
STATUS_ERRORS: dict[int, type[IsectError]] = {
    cls.status: cls
    for cls in (InvalidArgumentError, NonFiniteError, DegenerateError, OutOfMemoryError)
}


def strerror(status: int) -> str:
    """The C library's description of a status code (``isect_strerror``)."""
    return str(ffi.string(lib.isect_strerror(status)).decode("utf-8", "replace"))


def error_for(
    status: int,
    context: str,
    *,
    index: int | None = None,
    item: str = "element",
    arg: str | None = None,
    detail: str | None = None,
) -> IsectError:
    """Build the exception for a negative status code.

    Args:
        status: the C status code.
        context: what was being done, e.g. ``"Sphere.intersect"``.
        index: the flat index of the offending element of a batch, if any.
        item: what the batch holds ("ray", "point"), for the message.
        arg: the argument that holds the offending value, e.g. ``"radius"``.
        detail: what exactly is wrong, naming the element and its value
            (``"radius = -1.0 is negative"``), where Python can tell; the
            C library's description of the status (``isect_strerror``)
            otherwise.

    The message reads "context: arg: item index: detail".
    """
    cls = STATUS_ERRORS.get(status, IsectError)
    where = f"{context}: " if context else ""
    named = f"{arg}: " if arg else ""
    which = f"{item} {index}: " if index is not None else ""
    return cls(f"{where}{named}{which}{detail or strerror(status)}", index=index)


def value_text(x: object) -> str:
    """A value for an error message: a number as Python prints it (``nan``,
    ``-1.0``, ``99``), an array or sequence as a list of such numbers."""
    if isinstance(x, np.ndarray) and x.ndim > 0:
        x = x.tolist()
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(value_text(v) for v in x) + "]"
    if isinstance(x, np.generic):
        x = x.item()
    return repr(x)


def too_few(n: int, least: int, name: str, what: str) -> str | None:
    """``"vertices: 2 given (a polygon needs at least 3)"`` if n < least,
    else None."""
    if n >= least:
        return None
    return f"{name}: {n} given ({what} needs at least {least})"


def nonfinite_element(values: object, name: str) -> str | None:
    """``"name[i][j] = nan is not finite"`` for the first NaN or infinity of
    the array ``values`` (indexed as the array is shaped; ``name`` alone for
    a scalar), or None when every value is finite."""
    a = np.asarray(values, dtype=np.float64)
    bad = ~np.isfinite(a)
    if not bad.any():
        return None
    at = np.unravel_index(int(bad.argmax()), a.shape) if a.ndim else ()
    element = name + "".join(f"[{int(i)}]" for i in at)
    return f"{element} = {value_text(a[at])} is not finite"


def check(status: int, context: str, arg: str | None = None) -> int:
    """Return a non-negative status unchanged; raise the mapped error otherwise."""
    if status < 0:
        raise error_for(int(status), context, arg=arg)
    return int(status)


def nonfinite(message: str) -> NonFiniteError:
    """A :class:`NonFiniteError` for a problem found in Python."""
    return NonFiniteError(message)


def invalid(message: str) -> InvalidArgumentError:
    """An :class:`InvalidArgumentError` for a problem found in Python."""
    return InvalidArgumentError(message)
