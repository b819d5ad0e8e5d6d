# SPDX-License-Identifier: Apache-2.0
"""The progress display of ``progress=True`` batch calls.

A tqdm bar (``tqdm.auto``: a widget in Jupyter, text elsewhere) when tqdm can
be imported; tqdm is imported only when a display is asked for, so the package
neither needs nor loads it otherwise. Without tqdm, a plain percentage on
standard error, rewritten in place (``\\r``) at each whole percent and ended
with a newline.
"""

from __future__ import annotations

import importlib
import sys
from typing import Any, TextIO

from ._args import as_flag
from ._batch import Progress


class PlainProgress:
    """The display without tqdm: ``"{desc}: 42% (420000/1000000 rays)"`` on
    standard error (the stream at the time of the call)."""

    def __init__(self, desc: str, total: int, unit: str, file: TextIO | None = None) -> None:
        """Start at 0%."""
        self._desc = desc
        self._total = total
        self._unit = unit
        self._file = sys.stderr if file is None else file
        self._done = 0
        self._shown = -1
        self._show()

    def _show(self) -> None:
        """Rewrite the line if the whole percentage changed."""
        percent = 100 if self._total == 0 else (100 * self._done) // self._total
        if percent != self._shown:
            self._shown = percent
            self._file.write(f"\r{self._desc}: {percent:3d}% ({self._done}/{self._total} "
                             f"{self._unit}s)")
            self._file.flush()

    def update(self, n: int) -> None:
        """``n`` more elements are done."""
        self._done += n
        self._show()

    def close(self) -> None:
        """End the line."""
        self._file.write("\n")
        self._file.flush()


def _tqdm() -> Any:
    """tqdm's bar class (``tqdm.auto.tqdm``), or None when tqdm is not installed."""
    try:
        return importlib.import_module("tqdm.auto").tqdm
    except ImportError:
        return None


def reporter(progress: Any, desc: str, total: int, unit: str) -> Progress | None:
    """The display for a batch of ``total`` elements if ``progress`` is True,
    None if it is False; anything else is an InvalidArgumentError naming
    ``progress``."""
    if not as_flag(progress, "progress"):
        return None
    bar = _tqdm()
    if bar is None:
        return PlainProgress(desc, total, unit)
    shown: Progress = bar(total=total, desc=desc, unit=unit, unit_scale=True, leave=True)
    return shown
