# SPDX-License-Identifier: Apache-2.0
"""cffi build script (API, out-of-line mode) for the extension ``isect._isect``.

The C sources of libisect are compiled *into* the extension module, so the
installed package needs no shared library at run time. setup.py names this file
in ``cffi_modules``. Besides the API of isect.h the extension holds one loop of
its own, ``pyisect_spawn_batch`` (``EXTENSION_SOURCE``), so that
``Shape.spawn`` runs a large batch in C.

The sources are looked up in these places, first match wins:

0. the directory named by the environment variable ``ISECT_LIBISECT_DIR``
   (it must hold ``include/isect.h`` and ``src/*/*.c``), to build against
   another copy of the library;
1. ``_libisect/`` next to this file: the copy that ``setup.py sdist`` puts into
   a source distribution, so an sdist builds on its own;
2. ``../../libisect/``: the library in the repository (``pip install
   ./bindings/python`` from a clone).
"""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

from cffi import FFI

HERE = Path(os.path.abspath(os.path.dirname(__file__)))


def find_libisect() -> Path:
    """Return the directory that holds ``include/isect.h`` and ``src/*/*.c``."""
    override = os.environ.get("ISECT_LIBISECT_DIR")
    if override:
        candidates = [Path(override).resolve()]
    else:
        candidates = [HERE / "_libisect", HERE.parent.parent / "libisect"]
    for candidate in candidates:
        if (candidate / "include" / "isect.h").is_file() and (candidate / "src").is_dir():
            return candidate
    raise RuntimeError(
        "libisect sources not found: looked for include/isect.h and src/ in "
        + ", ".join(str(c) for c in candidates)
    )


def compile_args() -> list[str]:
    """Flags that keep the arithmetic identical to the C build of libisect.

    No fused multiply-add contraction (it would change results on targets with
    FMA), no fast-math, hidden visibility so only the module init is exported.
    """
    if sys.platform == "win32":
        return ["/fp:precise"]
    return ["-ffp-contract=off", "-fvisibility=hidden", "-fno-fast-math"]


#: macros of isect.h that are not constants of the API (include guard,
#: visibility, a string, an initializer)
_NOT_CONSTANTS = {"ISECT_H", "ISECT_API", "ISECT_VERSION_STRING", "ISECT_OPTS_INIT"}


def cdef_from_header(header: str) -> str:
    """isect.h in the dialect cffi's ``cdef()`` parses.

    The header stays the one source of truth: comments and line continuations
    go, integer macros become ``#define NAME ...`` (the C compiler supplies the
    value), the floating-point ISECT_EPS_DEFAULT a ``static const double``,
    preprocessor-conditional code (the ISECT_API selection, ``extern "C"``) is
    dropped except inside the include guard, and ISECT_API is erased. Struct
    fields are kept exactly, so cffi checks every offset and size against the
    compiler's layout.
    """
    text = re.sub(r"/\*.*?\*/", " ", header, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text).replace("\\\n", " ")
    out: list[str] = []
    depth = 0                       # open #if blocks; the include guard is depth 1
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith("#"):
            words = stripped[1:].split(None, 2)
            directive = words[0] if words else ""
            if directive in ("if", "ifdef", "ifndef"):
                depth += 1
            elif directive == "endif":
                depth -= 1
            elif directive == "define" and depth == 1 and words[1] not in _NOT_CONSTANTS:
                value = words[2] if len(words) > 2 else ""
                if re.fullmatch(r"[0-9.]+[eE][-+]?[0-9]+|[0-9]*\.[0-9]+", value.strip()):
                    out.append(f"static const double {words[1]};")
                else:
                    out.append(f"#define {words[1]} ...")
            continue
        if depth <= 1:
            out.append(re.sub(r"\bISECT_API\s+", "", line))
    return "\n".join(out) + "\n"


#: C helpers of the extension itself (not part of libisect's API): loops over
#: one libisect call so that a large batch runs in C with the GIL released
#: (cffi releases it around every call). Thin over the C API: no geometry.
EXTENSION_CDEF = """
int64_t pyisect_closest_soa(const isect_shape *shape, const double *org, int64_t org_step,
                            const double *dir, int64_t dir_step, const double *tmin,
                            int64_t tmin_step, const double *tmax, int64_t tmax_step, int64_t n,
                            const isect_opts *opts, isect_hit *out, int64_t *bad);
int64_t pyisect_closest(const isect_shape *shape, const isect_ray *rays, int64_t n,
                        const isect_opts *opts, isect_hit *out, int64_t *bad);
int pyisect_spawn_batch(const isect_shape *shape, const isect_hit *hits, int64_t hit_step,
                        const double *dirs, int64_t dir_step, int64_t n, isect_ray *out,
                        int64_t *bad);
"""

EXTENSION_SOURCE = r"""
/* isect_intersect_batch over rays[0 .. m) into out, and *bad = base + the
 * index of the first INVALID record if *bad < 0 still: the records are
 * scanned while they are in cache (a scan of the whole result from numpy
 * afterwards reads every record's cache line again: 5 ms at 10^6 rays). */
static int64_t pyisect_closest_chunk(const isect_shape *shape, const isect_ray *rays, int64_t m,
                                     const isect_opts *opts, isect_hit *out, int64_t base,
                                     int64_t *bad)
{
    int64_t found = isect_intersect_batch(shape, rays, m, opts, out);
    if (found >= 0 && *bad < 0)
        for (int64_t j = 0; j < m; j++)
            if (out[j].kind == ISECT_INVALID) {
                *bad = base + j;
                break;
            }
    return found;
}

/* Rays, records and the cache-sized chunks the two loops below share. */
#define PYISECT_CHUNK 256

/* isect_intersect_batch over a ray array, PYISECT_CHUNK rays per call;
 * returns the number hit or the batch's negative status, *bad as below. */
static int64_t pyisect_closest(const isect_shape *shape, const isect_ray *rays, int64_t n,
                               const isect_opts *opts, isect_hit *out, int64_t *bad)
{
    int64_t hits = 0;
    *bad = -1;
    for (int64_t base = 0; base < n; base += PYISECT_CHUNK) {
        int64_t m = n - base < PYISECT_CHUNK ? n - base : PYISECT_CHUNK;
        int64_t found = pyisect_closest_chunk(shape, rays + base, m, opts, out + base, base, bad);
        if (found < 0)
            return found;
        hits += found;
    }
    return hits;
}

/* isect_intersect_batch over rays given as separate arrays: ray i is
 * org[i * org_step .. + 3], dir[i * dir_step .. + 3], tmin[i * tmin_step],
 * tmax[i * tmax_step] (a step of 0 repeats one value). The rays are packed
 * PYISECT_CHUNK at a time on the stack, so the batch never materialises an
 * n-ray array (at 10^6 rays, packing one took as long as the kernel).
 * Returns the number of rays hit or the batch's negative status; *bad is
 * the index of the first INVALID record (-1: none). */
static int64_t pyisect_closest_soa(const isect_shape *shape, const double *org, int64_t org_step,
                                   const double *dir, int64_t dir_step, const double *tmin,
                                   int64_t tmin_step, const double *tmax, int64_t tmax_step,
                                   int64_t n, const isect_opts *opts, isect_hit *out, int64_t *bad)
{
    isect_ray buf[PYISECT_CHUNK];
    int64_t hits = 0;
    *bad = -1;
    for (int64_t base = 0; base < n; base += PYISECT_CHUNK) {
        int64_t m = n - base < PYISECT_CHUNK ? n - base : PYISECT_CHUNK;
        for (int64_t j = 0; j < m; j++) {
            int64_t i = base + j;
            const double *o = org + i * org_step, *d = dir + i * dir_step;
            buf[j].org[0] = o[0];
            buf[j].org[1] = o[1];
            buf[j].org[2] = o[2];
            buf[j].dir[0] = d[0];
            buf[j].dir[1] = d[1];
            buf[j].dir[2] = d[2];
            buf[j].tmin = tmin[i * tmin_step];
            buf[j].tmax = tmax[i * tmax_step];
        }
        int64_t found = pyisect_closest_chunk(shape, buf, m, opts, out + base, base, bad);
        if (found < 0)
            return found;
        hits += found;
    }
    return hits;
}

/* isect_spawn_ray for i = 0 .. n-1 on hits[i * hit_step] and dirs[i * dir_step ..
 * + 3] (a step of 0 repeats one hit or one direction), into out[i]. Stops at
 * the first error: returns its status and sets *bad to its index (-1 when all
 * succeed); out[bad ..] is then not written. */
static int pyisect_spawn_batch(const isect_shape *shape, const isect_hit *hits, int64_t hit_step,
                               const double *dirs, int64_t dir_step, int64_t n, isect_ray *out,
                               int64_t *bad)
{
    int64_t i;
    for (i = 0; i < n; i++) {
        int status = isect_spawn_ray(shape, hits + i * hit_step, dirs + i * dir_step, out + i);
        if (status != ISECT_OK) {
            *bad = i;
            return status;
        }
    }
    *bad = -1;
    return ISECT_OK;
}
"""


def make_ffibuilder() -> FFI:
    """Create the FFI builder: cdef from isect.h, sources from libisect."""
    root = find_libisect()
    sources = sorted(str(p) for p in (root / "src").rglob("*.c"))
    # Headers are listed so that a rebuild in a used tree (bindings/python/build
    # left by an earlier pip install) is triggered by a header change too.
    headers = [root / "include" / "isect.h", *(root / "src").rglob("*.h")]
    builder = FFI()
    builder.cdef(cdef_from_header((root / "include" / "isect.h").read_text(encoding="utf-8")))
    builder.cdef(EXTENSION_CDEF)
    builder.set_source(
        "isect._isect",
        '#include "isect.h"\n' + EXTENSION_SOURCE,
        sources=sources,
        include_dirs=[str(root / "include"), str(root / "src")],
        define_macros=[("ISECT_STATIC", None)],
        extra_compile_args=compile_args(),
        libraries=[] if sys.platform == "win32" else ["m"],
        depends=sorted(str(p) for p in headers),
    )
    return builder


ffibuilder = make_ffibuilder()
