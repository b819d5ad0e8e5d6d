# SPDX-License-Identifier: Apache-2.0
"""Splitting a batch over threads, optionally with a progress display.

libisect's batch functions are reentrant and cffi releases the GIL around every
C call, so chunks of one batch run truly in parallel. Each ray's result depends
on that ray alone, so any split gives the same bytes as one call. (The one
batch whose per-element evaluation depends on the batch size, the generalized
winding number, switches method below 8 points; chunks are never smaller than
``MIN_CHUNK`` unless the whole batch is, so no split changes a result.)

``threads=None`` means every core this process may run on
(:func:`default_threads`). With a progress display the batch is cut into
more, smaller chunks (still at least ``MIN_CHUNK`` elements) that ``threads``
workers take in turn, and the calling thread reports each finished chunk.
"""

from __future__ import annotations

import itertools
import os
import queue
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Protocol, TypeVar

T = TypeVar("T")

#: Batches are not split into chunks smaller than this many elements.
MIN_CHUNK = 4096

#: With a progress display, a batch is cut into about this many chunks (fewer
#: when it is small: chunks stay >= MIN_CHUNK), so the display moves in steps
#: of about 1%.
PROGRESS_STEPS = 100

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


class Progress(Protocol):
    """What :func:`run` reports to: a tqdm bar or the plain fallback."""

    def update(self, n: int) -> Any:
        """``n`` more elements are done."""

    def close(self) -> Any:
        """The batch is over (finished or failed)."""


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


def _split(n: int, parts: int) -> list[tuple[int, int]]:
    """range(n) as ``parts`` contiguous [lo, hi) ranges of near-equal size."""
    step, extra = divmod(n, parts)
    ranges = []
    lo = 0
    for i in range(parts):
        hi = lo + step + (1 if i < extra else 0)
        ranges.append((lo, hi))
        lo = hi
    return ranges


def chunks(n: int, threads: int) -> list[tuple[int, int]]:
    """Split range(n) into at most ``threads`` contiguous [lo, hi) ranges of
    at least MIN_CHUNK elements (one range when n is small)."""
    return _split(n, max(1, min(threads, n // MIN_CHUNK)))


def progress_chunks(n: int, threads: int) -> list[tuple[int, int]]:
    """Split range(n) for a batch with a progress display: about
    PROGRESS_STEPS ranges (at least ``threads``), none smaller than MIN_CHUNK
    (one range when n is small)."""
    return _split(n, max(1, min(max(PROGRESS_STEPS, threads), n // MIN_CHUNK)))


def run(
    work: Callable[[int, int], T], n: int, threads: int, progress: Progress | None = None
) -> list[T]:
    """Call ``work(lo, hi)`` for each chunk of range(n), in parallel when more
    than one chunk and thread; results in chunk order.

    With ``progress``, the chunks are those of :func:`progress_chunks`, at
    most ``threads`` of them run at once, and ``progress.update`` is called
    from the calling thread as each one finishes; ``progress.close`` at the
    end, also when ``work`` raises (the first exception is re-raised once
    every running chunk has finished; the chunks not yet started are not).
    """
    if progress is None:
        ranges = chunks(n, threads)
        if len(ranges) == 1:
            return [work(0, n)]
        pool = _executor(len(ranges))
        futures = [pool.submit(work, lo, hi) for lo, hi in ranges]
        return [f.result() for f in futures]
    try:
        return _run_reporting(work, n, threads, progress)
    finally:
        progress.close()


def _run_reporting(
    work: Callable[[int, int], T], n: int, threads: int, progress: Progress
) -> list[T]:
    """:func:`run` with a progress display (see there)."""
    ranges = progress_chunks(n, threads)
    workers = min(threads, len(ranges))
    if workers == 1:
        out = []
        for lo, hi in ranges:
            out.append(work(lo, hi))
            progress.update(hi - lo)
        return out
    results: list[Any] = [None] * len(ranges)
    done: queue.SimpleQueue[int | BaseException] = queue.SimpleQueue()
    order = itertools.count()  # next() on it is atomic under the GIL
    stop = threading.Event()

    def drain() -> None:
        """Take the next chunk until none is left (or a chunk failed)."""
        while not stop.is_set():
            i = next(order)
            if i >= len(ranges):
                return
            lo, hi = ranges[i]
            try:
                results[i] = work(lo, hi)
            except BaseException as exc:  # noqa: BLE001 - handed to the caller's thread
                done.put(exc)
                return
            done.put(hi - lo)

    pool = _executor(workers)
    futures = [pool.submit(drain) for _ in range(workers)]
    try:
        for _ in range(len(ranges)):
            item = done.get()
            if isinstance(item, BaseException):
                raise item
            progress.update(item)
    finally:
        stop.set()
        for f in futures:
            f.result()
    return results
