# SPDX-License-Identifier: Apache-2.0
"""Command line: measure libisect against the exact reference and print the table.

    python tests/accuracy/run.py [--short | --full] [--rays N] [--primitive NAME ...]
                                 [--class NAME ...] [--markdown] [--jobs N] [--seed S] [--worst]
    python -m tests.accuracy ...            (the same, from the repository root)

--short (default): 50 rays per (primitive, class), 10-50 s on one core.
--full: 2000 rays per (primitive, class), 8-20 min of CPU, run over --jobs processes.
Exit status 0; the table marks values over the contract with *.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

if __package__ in (None, ""):                     # run as a script: import the package
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
    __package__ = "tests.accuracy"

from tests.accuracy import contract, harness, report  # noqa: E402

SHORT_RAYS = 50
FULL_RAYS = 2000


def commit() -> str:
    """The checked-out commit (and + when the work tree differs), for the header."""
    root = Path(__file__).resolve().parents[2]
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=root, capture_output=True,
                              text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=root,
                               capture_output=True, text=True, check=True).stdout.strip()
        return head + ("+" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="tests/accuracy/run.py", description=__doc__.split("\n")[0])
    size = ap.add_mutually_exclusive_group()
    size.add_argument("--short", action="store_true", help=f"{SHORT_RAYS} rays per cell (default)")
    size.add_argument("--full", action="store_true", help=f"{FULL_RAYS} rays per cell")
    ap.add_argument("--rays", type=int, help="rays per (primitive, class) cell")
    ap.add_argument("--primitive", action="append", choices=harness.PRIMITIVES, metavar="NAME",
                    help=f"only these (repeatable): {', '.join(harness.PRIMITIVES)}")
    ap.add_argument("--class", dest="classes", action="append", choices=harness.CLASSES, metavar="NAME",
                    help=f"only these classes (repeatable): {', '.join(harness.CLASSES)}")
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    ap.add_argument("--jobs", type=int, help="processes (default: 1 for --short, all CPUs for --full)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--worst", action="store_true", help="print the worst ray of every metric over the contract")
    args = ap.parse_args(argv)

    n = args.rays or (FULL_RAYS if args.full else SHORT_RAYS)
    jobs = args.jobs or ((os.cpu_count() or 1) if args.full else 1)
    prims = args.primitive or list(harness.PRIMITIVES)
    classes = args.classes or list(harness.CLASSES)
    import isect
    start = time.perf_counter()
    done = []

    def progress(cell: harness.Cell) -> None:
        done.append(cell)
        print(f"  [{len(done)}] {cell.primitive}/{cell.cls}: {cell.seconds:.1f} s", file=sys.stderr, flush=True)
    cells = harness.run(prims, classes, n, args.seed, jobs, progress)
    wall = time.perf_counter() - start
    cpu = sum(c.seconds for c in cells)
    print(f"libisect {isect.version()} (commit {commit()}), {n} rays per cell, seed {args.seed}, "
          f"{wall:.0f} s wall, {cpu:.0f} s in the cells, {jobs} process(es)\n")
    print(report.table(cells, args.markdown))
    print()
    print(report.LEGEND)
    if args.worst:
        print()
        for p in prims:
            mine = [(c.cls, c.lib) for c in cells if c.primitive == p]
            for v in contract.verdicts(p, mine).values():
                if not v.ok:
                    print(f"{p} {v.metric}: {report.num(v.worst)} > {v.limit}: {v.where[:2000]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
