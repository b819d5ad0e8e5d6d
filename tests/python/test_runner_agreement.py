# SPDX-License-Identifier: Apache-2.0
"""The two corpus runners agree on malformed files (issue 13, item 6).

The same files go to the C runner (build/tests/corpus_runner, built by
``make test-c``) and to ``python -m isect cases``: each must reject every
malformed one (exit status 1, a message naming the problem, and from Python
no traceback), and both must accept the well-formed control file, so a runner
that rejects everything cannot pass.
"""

from __future__ import annotations

import copy
import json
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
from conftest import ROOT

C_RUNNER = ROOT / "build" / "tests" / "corpus_runner"

needs_c_runner = pytest.mark.skipif(
    not C_RUNNER.exists(), reason="build/tests/corpus_runner not built (make test-c)"
)


def _control() -> dict[str, Any]:
    """A small well-formed file: two cases of the real corpus."""
    doc = json.loads((ROOT / "tests" / "cases" / "sphere.json").read_text(encoding="utf-8"))
    ok = [c for c in doc["cases"] if c.get("op", "intersect") == "intersect"
          and c["expect"]["status"] == "ok" and c["expect"].get("count")][:2]
    doc["cases"], doc["number_of_cases"] = ok, len(ok)
    return doc


def _with(change: Callable[[dict[str, Any]], None]) -> Callable[[], str]:
    def make() -> str:
        doc = copy.deepcopy(_control())
        change(doc)
        return json.dumps(doc)

    return make


def _set_id(value: Any) -> Callable[[dict[str, Any]], None]:
    def change(doc: dict[str, Any]) -> None:
        doc["cases"][1]["id"] = value

    return change


def _nested(depth: int, where: str) -> Callable[[], str]:
    """A file whose nesting is ``depth`` levels deep, inside a case's field
    (``where="case"``) or as the whole document (``"top"``)."""

    def make() -> str:
        deep = "[" * depth + "]" * depth
        if where == "top":
            return deep
        text = json.dumps(_control())
        return text.replace('"name": ', f'"deep": {deep}, "name": ', 1)

    return make


def _drop(key: str) -> Callable[[dict[str, Any]], None]:
    def change(doc: dict[str, Any]) -> None:
        del doc["cases"][1][key]

    return change


def _text(replace: str, by: str) -> Callable[[], str]:
    def make() -> str:
        text = json.dumps(_control())
        assert replace in text
        return text.replace(replace, by, 1)

    return make


MALFORMED: dict[str, Callable[[], str]] = {
    "id 1.5": _with(_set_id(1.5)),
    "id 1e300": _with(_set_id(1e300)),
    "id -1e300": _with(_set_id(-1e300)),
    "id 2**53 + 2": _with(_set_id(2**53 + 2)),
    "id a string": _with(_set_id("7")),
    "id true": _with(_set_id(True)),
    "id null": _with(_set_id(None)),
    "id missing": _with(_drop("id")),
    "id duplicate": _with(lambda d: d["cases"][1].__setitem__("id", d["cases"][0]["id"])),
    "number_of_cases wrong": _with(lambda d: d.__setitem__("number_of_cases", 3)),
    "number_of_cases 2.5": _with(lambda d: d.__setitem__("number_of_cases", 2.5)),
    "number_of_cases missing": _with(lambda d: d.pop("number_of_cases")),
    "schema wrong": _with(lambda d: d.__setitem__("schema", "isect-cases/0")),
    "cases not a list": _with(lambda d: d.__setitem__("cases", {"a": 1})),
    "case not an object": _with(lambda d: d["cases"].__setitem__(1, [1, 2])),
    "expect.count 1.5": _with(lambda d: d["cases"][1]["expect"].__setitem__("count", 1.5)),
    "ray.org of 2 numbers": _with(lambda d: d["cases"][1]["ray"].__setitem__("org", [0, 0])),
    "ray.org a string": _with(lambda d: d["cases"][1]["ray"].__setitem__("org", "origin")),
    "nested 5000 deep in a case": _nested(5000, "case"),
    "nested 1001 deep in a case": _nested(1001, "case"),
    "nested 100000 deep": _nested(100_000, "top"),
    "nested 3000 deep in ray.org": _text('"org": [', '"org": ' + "[" * 3000 + "]" * 3000
                                         + ', "x": ['),
    "NaN literal": _text('"radius": ', '"radius": NaN, "r": '),
    "Infinity literal": _text('"radius": ', '"radius": Infinity, "r": '),
    "not JSON": lambda: '{"schema": "isect-cases/1", "cases": [',
    "trailing text": lambda: json.dumps(_control()) + " x",
    "empty file": lambda: "",
    "top level a list": lambda: "[]",
}

ACCEPTED: dict[str, Callable[[], str]] = {
    "control": lambda: json.dumps(_control()),
    "id 2.0 (an integral number)": _with(_set_id(2.0)),
    "id -(2**53)": _with(_set_id(-(2**53))),
    "nested 900 deep in an unknown field": _nested(900, "case"),
}


def _run_c(path: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(C_RUNNER), str(path)], capture_output=True, text=True, timeout=60)


def _run_python(path: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "isect", "cases", str(path)],
        capture_output=True, text=True, timeout=60,
    )


@needs_c_runner
@pytest.mark.parametrize("make", list(MALFORMED.values()), ids=list(MALFORMED))
def test_both_runners_reject(tmp_path: Path, make: Callable[[], str]) -> None:
    path = tmp_path / "bad.json"
    path.write_text(make(), encoding="utf-8")
    c, py = _run_c(path), _run_python(path)
    assert c.returncode == 1, c.stdout + c.stderr
    assert "FAIL" in c.stdout and " 0 failed" not in c.stdout, c.stdout
    assert py.returncode == 1, py.stdout + py.stderr
    assert "Traceback" not in py.stdout + py.stderr, py.stderr
    assert "ERROR" in py.stdout or "FAIL" in py.stdout, py.stdout
    assert py.stdout.strip().splitlines()[-1].endswith(("failed", "failed, 0 skipped (c-only)"))
    assert " 0 failed" not in py.stdout.strip().splitlines()[-1]


@needs_c_runner
@pytest.mark.parametrize("make", list(ACCEPTED.values()), ids=list(ACCEPTED))
def test_both_runners_accept(tmp_path: Path, make: Callable[[], str]) -> None:
    path = tmp_path / "good.json"
    path.write_text(make(), encoding="utf-8")
    c, py = _run_c(path), _run_python(path)
    assert c.returncode == 0, c.stdout + c.stderr
    assert py.returncode == 0, py.stdout + py.stderr
    assert c.stdout.strip().splitlines()[-1] == py.stdout.strip().splitlines()[-1] == (
        "2 passed, 0 failed"
    )


def test_deep_nesting_is_a_clean_error_in_process(tmp_path: Path) -> None:
    """The runner's own entry point (no subprocess) reports the file, with no
    RecursionError escaping (works without the C runner)."""
    from isect._cases import run_files

    path = tmp_path / "deep.json"
    path.write_text(_nested(100_000, "top")(), encoding="utf-8")
    (result,) = run_files([path])
    assert result.status == "error" and "nested" in result.message
    path.write_text(_nested(5000, "case")(), encoding="utf-8")
    (result,) = run_files([path])
    assert result.status == "error" and "nested" in result.message
