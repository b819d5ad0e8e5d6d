#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The kernel benchmarks' targets in one table (the last step of ``make bench``).

Reads bench/results/kernels.json (``build/bench/bench_kernels``) and
bench/results/python_kernels.json (``bench/python_kernels_bench.py``), prints
one table with every primitive's C ratio against the textbook loop, the 4M-ray
streaming ratio, the Python speed-up over numpy and the one-ray Python call
times, each with its target and PASS/FAIL, and writes the same as
bench/results/summary.json (one record per check) and bench/results/summary.md.
A missing results file leaves its columns empty ("-"). Standard library only.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

RESULTS = Path(__file__).resolve().parent / "results"


def load(name: str) -> dict[str, Any] | None:
    """A results file, or None if it is missing or unreadable."""
    try:
        return json.loads((RESULTS / name).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def verdict(ok: bool) -> str:
    """PASS or FAIL."""
    return "PASS" if ok else "FAIL"


def collect() -> list[dict[str, Any]]:
    """Every check as a record: kind, primitive, value, min, max, target, pass."""
    checks: list[dict[str, Any]] = []
    c = load("kernels.json")
    if c is not None:
        for r in c["kernels"]:
            checks.append(
                {
                    "check": "C libisect/textbook throughput, N = 4096",
                    "key": "c_ratio",
                    "primitive": r["primitive"],
                    "value": r["ratio"],
                    "min": r["ratio_min"],
                    "max": r["ratio_max"],
                    "target": f">= {c['ratio_target_min']:g}",
                    "pass": r["pass"],
                }
            )
        for r in c["stream"]["results"]:
            checks.append(
                {
                    "check": "C batch/streaming copy time, N = 4M",
                    "key": "stream",
                    "primitive": r["primitive"],
                    "value": r["ratio"],
                    "min": r["ratio_min"],
                    "max": r["ratio_max"],
                    "target": f"<= {c['stream']['ratio_target_max']:g}",
                    "pass": r["pass"],
                }
            )
    p = load("python_kernels.json")
    if p is not None:
        target = p["targets"]["speedup_min"]
        for r in p["kernels"]:
            for form in ("intersect", "intersect_rays"):
                checks.append(
                    {
                        "check": f"Python {form} speed-up over numpy, N = {p['n']:,}",
                        "key": f"py_{form}",
                        "primitive": r["primitive"],
                        "value": r[f"speedup_{form}"],
                        "min": r[f"speedup_{form}_range"][0],
                        "max": r[f"speedup_{form}_range"][1],
                        "target": f">= {target:g}x",
                        "pass": r[f"speedup_{form}"] >= target,
                    }
                )
        one = p["one_ray"]
        for call, name in (("intersect", "Sphere.intersect"), ("intersect_all", "intersect_all")):
            checks.append(
                {
                    "check": f"one-ray {name}, median us",
                    "key": f"one_{call}",
                    "primitive": "sphere",
                    "value": one[f"{call}_us"],
                    "min": one[f"{call}_us_range"][0],
                    "max": one[f"{call}_us_range"][1],
                    "target": f"<= {p['targets'][f'one_ray_{call}_us_max']:g} us",
                    "pass": one[f"{call}_pass"],
                }
            )
    return checks


def cell(check: dict[str, Any] | None, digits: int = 3, unit: str = "") -> str:
    """'value (min-max) VERDICT' or '-'."""
    if check is None:
        return "-"
    text = f"{check['value']:.{digits}f}{unit}"
    if "min" in check:
        text += f" ({check['min']:.{digits}f}-{check['max']:.{digits}f})"
    return f"{text} {verdict(check['pass'])}"


COLUMNS = [
    "primitive",
    "C libisect/textbook (N = 4096; >= 0.5)",
    "C batch/copy (N = 4M; <= 2.0)",
    "Python intersect vs numpy (>= 5x)",
    "Python intersect_rays vs numpy (>= 5x)",
]


def table(checks: list[dict[str, Any]]) -> list[list[str]]:
    """One row per primitive: C ratio, streaming ratio, the two Python speed-ups."""
    by = {(c["key"], c["primitive"]): c for c in checks}
    primitives = dict.fromkeys(c["primitive"] for c in checks if not c["key"].startswith("one_"))
    rows = []
    for prim in primitives:
        rows.append(
            [
                prim,
                cell(by.get(("c_ratio", prim))),
                cell(by.get(("stream", prim)), 2),
                cell(by.get(("py_intersect", prim)), 2, "x"),
                cell(by.get(("py_intersect_rays", prim)), 2, "x"),
            ]
        )
    return rows


def main() -> None:
    """Print the table and write summary.json and summary.md."""
    c, p = load("kernels.json"), load("python_kernels.json")
    checks = collect()
    rows = table(checks)
    one = [check for check in checks if check["key"].startswith("one_")]
    notes = [f"{o['check']}: {cell(o, 2, ' us')} (target {o['target']})" for o in one]
    missing = [name for name, doc in (("kernels.json", c), ("python_kernels.json", p)) if not doc]
    if missing:
        notes.append("missing: " + ", ".join(missing))
    passed = sum(check["pass"] for check in checks)
    notes.append(f"{passed} of {len(checks)} checks pass")

    widths = [max(len(r[i]) for r in [COLUMNS] + rows) for i in range(len(COLUMNS))]
    print("\nlibisect kernel targets (medians; ranges over blocks or pairs in parentheses)\n")
    for r in [COLUMNS] + rows:
        print("  ".join(f"{x:<{w}}" for x, w in zip(r, widths)).rstrip())
    print("\n".join([""] + notes))

    md = ["# libisect kernel targets", "", "Medians; ranges in parentheses.", ""]
    md += ["| " + " | ".join(r) + " |" for r in [COLUMNS, ["---"] * len(COLUMNS)] + rows]
    md += [""] + [f"- {note}" for note in notes] + [""]
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "summary.md").write_text("\n".join(md), encoding="utf-8")
    doc = {"passed": passed, "total": len(checks), "checks": checks}
    (RESULTS / "summary.json").write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(f"wrote {RESULTS / 'summary.md'} and {RESULTS / 'summary.json'}")


if __name__ == "__main__":
    main()
