#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Write the golden corpus tests/cases/<family>.json from the mpmath reference.

    python3 tests/golden/generate.py            # (re)write every file
    python3 tests/golden/generate.py --check    # exit 1 if any byte would change
    python3 tests/golden/generate.py --selftest # also cross-check the reference

The output is deterministic: fixed case order, fixed key order, floats as
Python's shortest round-trip repr of the double (the correctly rounded value
of the exact answer), "inf" / "-inf" / "nan" strings for non-finite numbers.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.dont_write_bytecode = True          # keep tests/golden free of __pycache__

import bad_input  # noqa: E402
import box  # noqa: E402
import convex  # noqa: E402
import exact  # noqa: E402
import cylinder  # noqa: E402
import ellipsoid  # noqa: E402
import mesh  # noqa: E402
import plane  # noqa: E402
import polygon  # noqa: E402
import polygon2d  # noqa: E402
import quadric  # noqa: E402
import spawn  # noqa: E402
import sphere  # noqa: E402
import transformed  # noqa: E402
import triangle  # noqa: E402
import winding  # noqa: E402
from model import CASE_KEYS, Group, check_flags  # noqa: E402
from reference import evaluate  # noqa: E402

SCHEMA = "isect-cases/1"
GENERATOR = "tests/golden/generate.py (mpmath, 80 digits)"
CASES_DIR = HERE.parent / "cases"
FAMILIES = [plane, sphere, box, triangle, polygon, convex, cylinder, ellipsoid, quadric, transformed,
            polygon2d, mesh, bad_input, spawn, winding]
WIDTH = 150


# ------------------------------------------------------------------- JSON
def scalar(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return '"nan"'
        if math.isinf(v):
            return '"inf"' if v > 0 else '"-inf"'
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    raise TypeError(f"cannot write {type(v).__name__}")


def compact(v: Any) -> str:
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)}: {compact(x)}" for k, x in v.items()) + "}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(compact(x) for x in v) + "]"
    return scalar(v)


def has_dict(v: Any) -> bool:
    if isinstance(v, dict):
        return True
    return isinstance(v, (list, tuple)) and any(has_dict(x) for x in v)


def render(v: Any, indent: int, col: int, expand: bool = False) -> str:
    """v as JSON: on one line if it fits in WIDTH from column col, else expanded.

    A dict without nested dicts (a hit, a shape, a ray) always stays on one line.
    """
    text = compact(v)
    leaf_dict = isinstance(v, dict) and not any(has_dict(x) for x in v.values())
    if (not isinstance(v, (dict, list, tuple)) or not v
            or (not expand and (col + len(text) <= WIDTH or leaf_dict))):
        return text
    pad = " " * (indent + 2)
    if isinstance(v, dict):
        items = [f"{pad}{json.dumps(k)}: {render(x, indent + 2, indent + 4 + len(k) + 2)}"
                 for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"
    items = [pad + render(x, indent + 2, indent + 2) for x in v]
    return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"


def document(family: str, notes: dict, cases: list[dict]) -> str:
    head = {"schema": SCHEMA, "family": family, "generator": GENERATOR,
            "number_of_cases": len(cases), "notes": notes}
    lines = ["{"]
    for k, v in head.items():
        lines.append(f"  {json.dumps(k)}: {render(v, 2, 4 + len(k), expand=(k == 'notes'))},")
    lines.append('  "cases": [')
    lines.append(",\n".join("    " + render(c, 4, 4, expand=True) for c in cases))
    lines.append("  ]")
    lines.append("}")
    return "\n".join(lines) + "\n"


# ----------------------------------------------------------------- groups
def check_group(g: Group) -> None:
    exps = [m["expect"] for m in g.members]
    if g.kind == "one-inside":
        ok = sum(e["inside"] for e in exps) == 1
    else:
        counts = [e["count"] for e in exps]
        kinds = [h["kind"] for e in exps for h in e["hits"]]
        ok = {"one": sorted(counts) == [0] * (len(counts) - 1) + [1],
              "even": sum(counts) % 2 == 0,
              "enter-exit": sorted(kinds) == ["enter", "exit"]}[g.kind]
    if not ok:
        raise AssertionError(f"watertightness group '{g.name}' ({g.kind}) violated: {exps}")


# ------------------------------------------------------------------ build
def build(mod) -> tuple[str, str]:
    """(file name, text) of one family."""
    raw = mod.cases()
    groups: list[Group] = []
    cases = []
    for i, c in enumerate(raw):
        g = c.pop("_group", None)
        if g is not None and g not in groups:
            groups.append(g)
        tol_of = c.pop("_tol", None)
        # "_exact": a case whose ray passes within a rounding error of an edge on purpose (its
        # sheared projection is not exact in doubles; flag "rounded-frame"): decided exactly, as
        # the library's face tests decide, instead of refused as a design hazard.
        decide = exact.deciding_exactly() if c.pop("_exact", False) else contextlib.nullcontext()
        try:
            with decide:
                c["expect"] = evaluate(c)
            if tol_of is not None:
                c["tol"] = {**c.get("tol", {}), **tol_of(c["expect"])}
            if hasattr(mod, "check_case"):
                mod.check_case(c)
        except Exception as e:
            raise RuntimeError(f"{mod.FAMILY}: case {i} '{c['name']}': {e}") from e
        cases.append({"id": i + 1, **{k: c[k] for k in CASE_KEYS if k in c}})
    for g in groups:
        check_group(g)
    per_family_min = 20
    if len(cases) < per_family_min:
        raise AssertionError(f"{mod.FAMILY}: only {len(cases)} cases")
    return f"{mod.FAMILY}.json", document(mod.FAMILY, check_flags(cases), cases)


def first_difference(old: str, new: str) -> str:
    """Which case (or header line) differs between two versions of a file."""
    try:
        a, b = json.loads(old), json.loads(new)
    except json.JSONDecodeError:
        return "the existing file is not valid JSON"
    for k in ("schema", "family", "generator", "number_of_cases", "notes"):
        if a.get(k) != b.get(k):
            return f"header field '{k}'"
    for ca, cb in zip(a.get("cases", []), b.get("cases", [])):
        if ca != cb:
            keys = [k for k in set(ca) | set(cb) if ca.get(k) != cb.get(k)]
            return f"case id {cb.get('id')} '{cb.get('name')}' (keys {sorted(keys)})"
    return "formatting only (same JSON values, different bytes)"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="fail if regenerating would change tests/cases/*.json")
    ap.add_argument("--selftest", action="store_true", help="cross-check the reference solvers first")
    ap.add_argument("--out", type=Path, default=CASES_DIR, help="output directory (default tests/cases)")
    args = ap.parse_args(argv)

    if args.selftest:
        import selftest
        selftest.run()

    bad = 0
    total = 0
    for mod in FAMILIES:
        name, text = build(mod)
        total += text.count('"id": ')
        path = args.out / name
        if args.check:
            old = path.read_text() if path.exists() else None
            if old is None:
                print(f"{path}: missing")
                bad += 1
            elif old != text:
                print(f"{path}: differs at {first_difference(old, text)}")
                bad += 1
        else:
            args.out.mkdir(parents=True, exist_ok=True)
            if not path.exists() or path.read_text() != text:
                path.write_text(text)
    if args.check:
        print(f"golden corpus: {'OK' if not bad else 'STALE'} ({len(FAMILIES)} files, {total} cases"
              + (f", {bad} differ" if bad else "") + ")")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
