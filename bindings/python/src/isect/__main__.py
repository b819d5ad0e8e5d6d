# SPDX-License-Identifier: Apache-2.0
"""Command line: ``python -m isect cases FILE.json... [--json]``.

Runs golden-case files in the corpus schema (``isect-cases/1``, documented in
the project's tests/cases/README.md) against libisect through this package.
Prints each failing case with expected vs actual and ends with
``N passed, N failed`` (and ``N skipped`` for c-only cases). ``--json`` prints
one JSON document instead. A file or case that does not follow the schema is
reported by file, case and field, and counts as failed.

Exit status: 0 when every case passed (or was skipped), 1 when any case failed
or any file or case was malformed, 2 for a usage error.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence

from ._cases import SCHEMA, Result, jsonable, run_files


def _label(r: Result) -> str:
    """file, case id and name, for a message."""
    if r.id is None:
        return r.file
    name = f" ({r.name})" if r.name else ""
    return f"{r.file}: case {r.id}{name}"


def _text(results: list[Result], verbose: bool) -> str:
    lines = []
    for r in results:
        if r.status == "fail":
            lines.append(f"FAIL {_label(r)}: {r.message}")
            lines.append(f"  expected: {json.dumps(jsonable(r.expected))}")
            lines.append(f"  actual:   {json.dumps(jsonable(r.actual))}")
        elif r.status == "error":
            lines.append(f"ERROR {_label(r)}: {r.message}")
        elif verbose:
            lines.append(f"{r.status.upper()} {_label(r)}")
    return "\n".join(lines)


def _summary(results: list[Result]) -> dict[str, int]:
    count = {s: sum(r.status == s for r in results) for s in ("pass", "fail", "skip", "error")}
    return {
        "passed": count["pass"],
        "failed": count["fail"] + count["error"],
        "skipped": count["skip"],
        "malformed": count["error"],
    }


def cases_main(argv: Sequence[str]) -> int:
    """The ``cases`` subcommand."""
    parser = argparse.ArgumentParser(
        prog="python -m isect cases",
        description=f"Run golden-case files (schema {SCHEMA}) against libisect.",
    )
    parser.add_argument("files", nargs="+", metavar="FILE.json", help="case files to run")
    parser.add_argument("--json", action="store_true", help="print machine-readable results")
    parser.add_argument("-v", "--verbose", action="store_true", help="list passing cases too")
    args = parser.parse_args(argv)
    results = run_files(args.files)
    summary = _summary(results)
    if args.json:
        doc = {
            "schema": SCHEMA,
            "files": list(args.files),
            **summary,
            "results": [r.as_json() for r in results],
        }
        print(json.dumps(doc, indent=1))
    else:
        text = _text(results, args.verbose)
        if text:
            print(text)
        line = f"{summary['passed']} passed, {summary['failed']} failed"
        if summary["skipped"]:
            line += f", {summary['skipped']} skipped (c-only)"
        print(line)
    return 1 if summary["failed"] else 0


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m isect COMMAND ...``."""
    argv = list(sys.argv[1:] if argv is None else argv)
    commands = {"cases": cases_main}
    if not argv or argv[0] in ("-h", "--help") or argv[0] not in commands:
        out = sys.stdout if argv and argv[0] in ("-h", "--help") else sys.stderr
        print(
            "usage: python -m isect cases FILE.json... [--json] [-v]\n\n"
            "  cases   run golden-case files (schema isect-cases/1) against libisect",
            file=out,
        )
        return 0 if out is sys.stdout else 2
    return commands[argv[0]](argv[1:])


if __name__ == "__main__":
    sys.exit(main())
