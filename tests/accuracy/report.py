# SPDX-License-Identifier: Apache-2.0
"""The results table: one row per (primitive, class), plain text or Markdown."""
from __future__ import annotations

import math
from typing import Sequence

from . import contract
from .harness import Cell
from .metrics import Summary

DEC_SHORT = {"outside": "o", "missing": "m", "kind": "k", "count": "c", "prim": "p", "closest": "cl"}

HEADER = ["primitive", "class", "rays", "hits",
          "t max", "t p99.9", "t closest max", "point max", "point p99.9", "point/obj max",
          "norm-1 max", "angle max", "angle p99.9", "decisions", "self-hit",
          "TB t max", "TB t p99.9", "TB point max", "TB angle max", "TB decisions", "TB self-hit", "undecided"]


def num(x: float | None) -> str:
    """Compact: 0, 0.97, 12, 3.4e+05, inf."""
    if x is None:
        return "-"
    if math.isinf(x):
        return "inf"
    if x == 0:
        return "0"
    if x < 100:
        return f"{x:.3g}"
    return f"{x:.2g}" if x >= 1e4 else f"{x:.0f}"


def _stat(s: Summary, m: str, i: int, limit: float | None = None) -> str:
    st = s.stats.get(m)
    if not st:
        return "-"
    v = st[i]
    return num(v) + ("*" if limit is not None and v > limit else "")


def decisions(s: Summary) -> str:
    if not s.decision_errors:
        return "0"
    return " ".join(f"{DEC_SHORT[k]}{v}" for k, v in s.decisions.items() if v)


def row(c: Cell) -> list[str]:
    lib, tb = c.lib, c.textbook
    t0 = f" (t0:{lib.t0_bad})" if lib.t0_bad else ""
    sec = c.cls == "secondary"
    point_lim = contract.POINT_ULPS[c.primitive]
    angle_lim = contract.ANGLE_UNITS[c.primitive]
    return [c.primitive, c.cls, str(lib.rays), str(lib.hits),
            _stat(lib, "t", 0, contract.T_ULPS) + t0, _stat(lib, "t", 1),
            _stat(lib, "t_closest", 0, contract.T_ULPS),
            _stat(lib, "point", 0, point_lim), _stat(lib, "point", 1), _stat(lib, "point_obj", 0),
            _stat(lib, "norm", 0, contract.NORM_ULPS), _stat(lib, "angle", 0, angle_lim),
            _stat(lib, "angle", 1), decisions(lib),
            f"{lib.self_hits}/{lib.exact_self_hits}" if sec else "",
            _stat(tb, "t", 0), _stat(tb, "t", 1), _stat(tb, "point", 0), _stat(tb, "angle", 0),
            decisions(tb), f"{tb.self_hits}" if sec else "", str(lib.undecided)]


def table(cells: Sequence[Cell], markdown: bool = False) -> str:
    rows = [HEADER] + [row(c) for c in cells]
    if markdown:
        lines = ["| " + " | ".join(rows[0]) + " |", "|" + "---|" * len(rows[0])]
        lines += ["| " + " | ".join(r) + " |" for r in rows[1:]]
        return "\n".join(lines)
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    return "\n".join("  ".join(x.ljust(w) if i < 2 else x.rjust(w) for i, (x, w) in enumerate(zip(r, widths)))
                     for r in rows)


LEGEND = """\
t: |t_lib - t_exact| / ulp(t_exact) over every hit both report (intersect_all_batch); "t closest": the
closest-hit batch call.  point: exact distance of the reported point to the exact surface in ulps of
max_k|P_k|; point/obj: in ulps of the object's own scale.  norm-1: | |n| - 1 | in ulps of 1.0; angle: angle to the exact
normal at the exact point, units of 2^-53 rad.  decisions: o = reported outside [tmin, tmax], m = missing,
k = kind, c = count, p = prim, cl = closest-hit call.  self-hit (secondary rays): library re-hits at
t|d| < 1e-9 size / of them real in exact geometry.  TB: the textbook double-precision code on the same
rays.  * = over the contract (t > 4 ulp, |n|-1 > 1 ulp, point / angle over contract.py's table);
t0:k = k hits with exact t = 0 reported at t != 0.  undecided: rays the contract leaves undefined."""
