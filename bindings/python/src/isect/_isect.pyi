# SPDX-License-Identifier: Apache-2.0
"""Type stub of the compiled cffi extension ``isect._isect``.

``ffi`` is the cffi FFI instance; ``lib`` exposes the C functions and
constants of ``isect.h`` (the cdef is made from the header by build_isect.py)
and the extension's own loop ``pyisect_spawn_batch`` (``Shape.spawn``'s batch:
isect_spawn_ray over n hits with the GIL released). Only the package's own
modules use them; they are not public API.
"""

from typing import Any

ffi: Any
lib: Any
