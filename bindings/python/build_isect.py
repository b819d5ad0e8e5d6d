"""cffi build script (API, out-of-line mode) for the extension ``isect._isect``.

The C sources of libisect are compiled *into* the extension module, so the
installed package needs no shared library at run time. setup.py names this file
in ``cffi_modules``; running it directly (``python build_isect.py``) builds the
extension in place next to the package sources, for quick experiments.

The sources are looked up in two places, first match wins:

1. ``_libisect/`` next to this file: the copy that ``setup.py sdist`` puts into
   a source distribution, so an sdist builds on its own;
2. ``../../libisect/``: the library in the repository (``pip install
   ./bindings/python`` from a clone).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from cffi import FFI

HERE = Path(os.path.abspath(os.path.dirname(__file__)))


def find_libisect() -> Path:
    """Return the directory that holds ``include/isect.h`` and ``src/*.c``."""
    for candidate in (HERE / "_libisect", HERE.parent.parent / "libisect"):
        if (candidate / "include" / "isect.h").is_file() and (candidate / "src").is_dir():
            return candidate
    raise RuntimeError(
        "libisect sources not found: expected bindings/python/_libisect/ (sdist) "
        "or libisect/ two levels above bindings/python/ (repository checkout)"
    )


def compile_args() -> list[str]:
    """Flags that keep the arithmetic identical to the C build of libisect.

    No fused multiply-add contraction (it would change results on targets with
    FMA), no fast-math, hidden visibility so only the module init is exported.
    """
    if sys.platform == "win32":
        return ["/fp:precise"]
    return ["-ffp-contract=off", "-fvisibility=hidden", "-fno-fast-math"]


def make_ffibuilder() -> FFI:
    """Create the FFI builder: cdef from isect_cdef.h, sources from libisect."""
    root = find_libisect()
    sources = sorted(str(p) for p in (root / "src").glob("*.c"))
    builder = FFI()
    builder.cdef((HERE / "isect_cdef.h").read_text(encoding="utf-8"))
    builder.set_source(
        "isect._isect",
        '#include "isect.h"\n',
        sources=sources,
        include_dirs=[str(root / "include"), str(root / "src")],
        define_macros=[("ISECT_STATIC", None)],
        extra_compile_args=compile_args(),
        libraries=[] if sys.platform == "win32" else ["m"],
    )
    return builder


ffibuilder = make_ffibuilder()

if __name__ == "__main__":
    ffibuilder.compile(tmpdir=str(HERE / "src"), verbose=True)
