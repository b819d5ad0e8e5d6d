# SPDX-License-Identifier: Apache-2.0
"""Splitting a batch over threads.

libisect's batch functions are reentrant and cffi releases the GIL around every
C call, so chunks of one batch run truly in parallel. Each ray's result depends
on that ray alone, so any split gives the same bytes as one call. (The one
batch whose per-element evaluation depends on the batch size, the generalized
winding number, switches method below 8 points; chunks are never smaller than
``MIN_CHUNK`` unless the whole batch is, so no split changes a result.)

``threads=None`` means every core this process may run on
(:func:`default_threads`).
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import TypeVar

T = TypeVar("T")

#: Batches are not split into chunks smaller than this many elements.
MIN_CHUNK = 4096

_pool: ThreadPoolExecutor | None = None
_pool_size = 0
_pool_lock = threading.Lock()


def default_threads() -> int:
    """The number of threads a batch call uses when ``threads=None``: the
    cores this process may run on (``len(os.sched_getaffinity(0))`` where the
    platform has it, so a CPU mask or a container's cpuset is respected;
    ``os.cpu_count()`` elsewhere), at least 1."""
    getaffinity = getattr(os, "sched_getaffinity", None)
    if getaffinity is not None:
        try:
            return max(1, len(getaffinity(0)))
        except OSError:  # pragma: no cover - a platform that has it but refuses
            pass
    return max(1, os.cpu_count() or 1)


def _executor(workers: int) -> ThreadPoolExecutor:
    """The shared pool, grown to at least ``workers`` threads.

    A smaller pool it replaces is not shut down (another thread may still be
    submitting to it); its idle threads exit once it is garbage-collected.
    """
    global _pool, _pool_size
    with _pool_lock:
        if _pool is None or _pool_size < workers:
            _pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="isect")
            _pool_size = workers
        return _pool


def chunks(n: int, threads: int) -> list[tuple[int, int]]:
    """Split range(n) into at most ``threads`` contiguous [lo, hi) ranges of
    at least MIN_CHUNK elements (one range when n is small)."""
    parts = max(1, min(threads, n // MIN_CHUNK))
    step, extra = divmod(n, parts)
    ranges = []
    lo = 0
    for i in range(parts):
        hi = lo + step + (1 if i < extra else 0)
        ranges.append((lo, hi))
        lo = hi
    return ranges


def run(work: Callable[[int, int], T], n: int, threads: int) -> list[T]:
    """Call ``work(lo, hi)`` for each chunk of range(n), in parallel when more
    than one chunk; results in chunk order."""
    ranges = chunks(n, threads)
    if len(ranges) == 1:
        return [work(0, n)]
    pool = _executor(len(ranges))
    futures = [pool.submit(work, lo, hi) for lo, hi in ranges]
    return [f.result() for f in futures]
