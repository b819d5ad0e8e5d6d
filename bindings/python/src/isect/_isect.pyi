"""Type stub of the compiled cffi extension ``isect._isect``.

``ffi`` is the cffi FFI instance; ``lib`` exposes the C functions and
constants declared in ``bindings/python/isect_cdef.h`` (see ``isect.h``).
Only the package's own modules use them; they are not public API.
"""

from typing import Any

ffi: Any
lib: Any
