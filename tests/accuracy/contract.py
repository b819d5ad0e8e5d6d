# SPDX-License-Identifier: Apache-2.0
"""The accuracy contract (SPEC, revision 2) as numbers, in one place.

``T_ULPS`` and ``NORM_ULPS`` are the SPEC's; the point and normal-angle
thresholds are "a few ulps" in the SPEC and are set here per primitive
(PROVISIONAL: chosen after the first measurements, see README.md).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable

from .metrics import Summary
from .primitives import PRIMITIVES

#: every reported t within this many ulps of the exact t
T_ULPS = 4.0
#: | |n| - 1 | in ulps of 1.0
NORM_ULPS = 1.0
#: distance of the reported point to the surface, ulps of max_k |P_k| (provisional)
POINT_ULPS: dict[str, float] = {name: 4.0 for name in PRIMITIVES}
#: angle to the exact normal at the exact point, units of 2^-53 rad (provisional)
ANGLE_UNITS: dict[str, float] = {name: 8.0 for name in PRIMITIVES}

#: the checked metrics, in test order
METRICS = ("t", "decisions", "point", "norm", "angle")


@dataclass(frozen=True)
class Verdict:
    """Worst value of one metric over a primitive's classes, and its limit."""
    metric: str
    worst: float
    limit: float
    where: str

    @property
    def ok(self) -> bool:
        return self.worst <= self.limit


def _worst(summaries: Iterable[tuple[str, Summary]], measure: str) -> tuple[float, str]:
    best = (0.0, "")
    for cls, s in summaries:
        v = s.max(measure)
        if v > best[0]:
            best = (v, f"{cls}: {s.worst.get(measure, (0, ''))[1]}")
    return best


def verdicts(primitive: str, summaries: list[tuple[str, Summary]]) -> dict[str, Verdict]:
    """The contract's verdict per metric for one primitive (all its classes).

    t covers both queries (every hit and the closest hit); a hit whose exact
    t is 0 but is reported at t != 0 counts as an infinite t error.
    """
    def verdict(metric: str, measure: str, limit: float) -> Verdict:
        worst, where = _worst(summaries, measure)
        return Verdict(metric, worst, limit, where)

    t = max(verdict("t", "t", T_ULPS), verdict("t", "t_closest", T_ULPS), key=lambda v: v.worst)
    t0 = sum(s.t0_bad for _, s in summaries)
    if t0:
        t = Verdict("t", float("inf"), T_ULPS, f"{t0} hit(s) with exact t = 0 reported at t != 0")
    dec = sum(s.decision_errors for _, s in summaries)
    dec_where = "; ".join(f"{cls}: {dict((k, v) for k, v in s.decisions.items() if v)} e.g. "
                          f"{next(iter(s.worst.get(k, (0, '')) for k in s.decisions if s.decisions[k]))[1]}"
                          for cls, s in summaries if s.decision_errors)
    return {"t": t,
            "decisions": Verdict("decisions", float(dec), 0.0, dec_where),
            "point": verdict("point", "point", POINT_ULPS[primitive]),
            "norm": verdict("norm", "norm", NORM_ULPS),
            "angle": verdict("angle", "angle", ANGLE_UNITS[primitive])}
