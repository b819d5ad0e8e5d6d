# SPDX-License-Identifier: Apache-2.0
"""The user case runner, ``python -m isect cases FILE.json... [--json]``."""

from __future__ import annotations

import copy
import json
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from conftest import ROOT
from isect.__main__ import main

CASES = sorted((ROOT / "tests" / "cases").glob("*.json"))


def _doc(name: str) -> dict[str, Any]:
    return json.loads((ROOT / "tests" / "cases" / name).read_text(encoding="utf-8"))


def _write(tmp_path: Path, name: str, doc: Any) -> Path:
    """Write a file; a document without ``number_of_cases`` (required, as in
    the C runner) gets the count of its cases."""
    if isinstance(doc, dict) and isinstance(doc.get("cases"), list):
        doc = {"number_of_cases": len(doc["cases"]), **doc}
    path = tmp_path / name
    path.write_text(doc if isinstance(doc, str) else json.dumps(doc), encoding="utf-8")
    return path


def _run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str]:
    rc = main(["cases", *args])
    out = capsys.readouterr()
    return rc, out.out + out.err


def test_real_corpus_passes() -> None:
    """The project's corpus passes through the command, as a user runs it."""
    proc = subprocess.run(
        [sys.executable, "-m", "isect", "cases", *map(str, CASES)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    last = proc.stdout.strip().splitlines()[-1]
    m = re.fullmatch(r"(\d+) passed, 0 failed(, (\d+) skipped \(c-only\))?", last)
    assert m, last
    total = sum(len(_doc(p.name)["cases"]) for p in CASES)
    assert int(m.group(1)) + int(m.group(3) or 0) == total
    assert "FAIL" not in proc.stdout


def test_wrong_expectation_fails_and_names_the_case(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    doc = _doc("sphere.json")
    case = next(c for c in doc["cases"] if c["expect"]["status"] == "ok" and c["expect"]["count"])
    bad = copy.deepcopy(case)
    bad["id"], bad["name"] = 9001, "deliberately wrong t"
    bad["expect"]["hits"][0]["t"] = 123.5
    doc["cases"] = [case, bad]
    doc["number_of_cases"] = 2
    path = _write(tmp_path, "mine.json", doc)
    rc, out = _run(capsys, str(path))
    assert rc == 1
    assert "FAIL" in out and "mine.json" in out and "case 9001" in out
    assert "deliberately wrong t" in out
    assert "expected 123.5" in out and "expected:" in out and "actual:" in out
    assert out.strip().splitlines()[-1] == "1 passed, 1 failed"


def test_wrong_count_and_kind_fail(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    doc = _doc("sphere.json")
    case = next(c for c in doc["cases"] if c["expect"]["status"] == "ok" and c["expect"]["count"])
    a, b = copy.deepcopy(case), copy.deepcopy(case)
    a["id"], b["id"] = 1, 2
    a["expect"]["count"] += 1
    b["expect"]["status"] = "E_DEGENERATE"
    doc["cases"], doc["number_of_cases"] = [a, b], 2
    rc, out = _run(capsys, str(_write(tmp_path, "two.json", doc)))
    assert rc == 1
    assert "case 1" in out and "count: expected" in out
    assert "case 2" in out and "expected E_DEGENERATE, actual ok" in out
    assert out.strip().splitlines()[-1] == "0 passed, 2 failed"


def _one_case(**changes: Any) -> dict[str, Any]:
    case = {
        "id": 7,
        "name": "my case",
        "shape": {"type": "sphere", "center": [0, 0, 0], "radius": 1},
        "ray": {"org": [0, 0, -5], "dir": [0, 0, 1]},
        "expect": {"status": "ok", "count": 2, "hits": [{"t": 4}, {"t": 6}]},
    }
    for key, value in changes.items():
        if value is None:
            del case[key]
        else:
            case[key] = value
    return {"schema": "isect-cases/1", "cases": [case]}


def test_a_good_user_file_passes(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rc, out = _run(capsys, str(_write(tmp_path, "ok.json", _one_case())))
    assert rc == 0 and out.strip() == "1 passed, 0 failed"


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"expect": None}, "'expect'"),
        ({"shape": {"type": "sphere", "center": [0, 0, 0], "radius": "big"}}, "shape.radius"),
        ({"shape": {"type": "sphere", "center": [0, 0, 0]}}, "shape.radius"),
        ({"shape": {"type": "donut", "radius": 1}}, "shape.type"),
        ({"ray": {"org": [0, 0, -5]}}, "ray.dir"),
        ({"op": "teleport"}, "'op'"),
        ({"expect": {"status": "E_WHATEVER"}}, "expect.status"),
        ({"expect": {"status": "ok", "count": 2, "hits": [{"t": 4, "kind": "in"}]}}, "kind"),
        ({"opts": {"flags": ["fast"]}}, "opts.flags"),
    ],
)
def test_malformed_case_is_named(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], changes: dict[str, Any], field: str
) -> None:
    """A bad case: file, case and field named, no traceback, exit 1."""
    rc, out = _run(capsys, str(_write(tmp_path, "bad.json", _one_case(**changes))))
    assert rc == 1
    assert "Traceback" not in out
    line = next(x for x in out.splitlines() if x.startswith("ERROR"))
    assert "bad.json" in line and "case 7 (my case)" in line and field in line, line
    assert out.strip().splitlines()[-1] == "0 passed, 1 failed"


# A unit cube of quads (outward normals): its report is known by hand.
CUBE = {
    "type": "mesh",
    "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                 [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
    "faces": [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [0, 4, 7, 3], [1, 2, 6, 5]],
}  # fmt: skip
CUBE_REPORT = {
    "vertices": 8, "edges": 12, "faces": 6, "boundary_edges": 0, "nonmanifold_edges": 0,
    "misoriented_edges": 0, "degenerate_faces": 0, "components": 1, "euler_characteristic": 2,
    "genus": 0, "closed": 1, "oriented": 1, "volume": 1.0, "area": 6.0,
}  # fmt: skip


def _mesh_cases(**changes: Any) -> dict[str, Any]:
    """A cube pierced (intersect), probed (contains) and checked (mesh_check,
    id 7, the case ``changes`` apply to, as in :func:`_one_case`)."""
    mesh_check = {
        "op": "mesh_check",
        "shape": CUBE,
        "ray": None,
        "expect": {"status": "ok", "report": dict(CUBE_REPORT)},
    }
    doc = _one_case(**{**mesh_check, **changes})
    doc["cases"] += [
        {
            "id": 1,
            "shape": CUBE,
            "ray": {"org": [0.5, 0.25, -1], "dir": [0, 0, 1]},
            "expect": {"status": "ok", "count": 2, "hits": [
                {"t": 1, "normal": [0, 0, -1], "prim": 0, "kind": "enter"},
                {"t": 2, "normal": [0, 0, 1], "prim": 1, "kind": "exit"}]},
        },
        {"id": 2, "op": "contains", "shape": CUBE, "point": [0.5, 0.5, 0.5],
         "expect": {"status": "ok", "inside": 1}},
        {"id": 3, "op": "contains", "shape": CUBE, "point": [0.5, 0.5, 1.5],
         "expect": {"status": "ok", "inside": 0}},
    ]  # fmt: skip
    return doc


def test_mesh_cases_pass(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rc, out = _run(capsys, "-v", str(_write(tmp_path, "mesh.json", _mesh_cases())))
    assert rc == 0 and out.strip().splitlines()[-1] == "4 passed, 0 failed", out
    assert "PASS" in out and "case 7 (my case)" in out


@pytest.mark.parametrize(
    ("shape", "status"),
    [
        ({**CUBE, "faces": [[0, 1, 8]]}, "E_ARG"),  # index out of range
        ({**CUBE, "faces": [[0, -1, 2]]}, "E_ARG"),
        ({**CUBE, "faces": [[0, 1, 2], [0, 1]]}, "E_ARG"),  # a face of 2 indices
        ({**CUBE, "faces": [[0, 1, 2, 3], []]}, "E_ARG"),
        ({**CUBE, "vertices": [[0, 0, "nan"], *CUBE["vertices"][1:]]}, "E_NONFINITE"),
        ({**CUBE, "vertices": [[0, 0], *CUBE["vertices"][1:]]}, "E_ARG"),  # a vertex of 2
    ],
)
def test_mesh_creation_error_is_the_status_whatever_the_op(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], shape: dict[str, Any], status: str
) -> None:
    cases = [
        {"id": 1, "shape": shape, "ray": {"org": [0.5, 0.5, -1], "dir": [0, 0, 1]}},
        {"id": 2, "shape": shape, "ray": {"org": [0.5, 0.5, -1], "dir": [0, 0, 0]}},
        {"id": 3, "op": "contains", "shape": shape, "point": [0.5, 0.5, 0.5]},
        {"id": 4, "op": "mesh_check", "shape": shape},
    ]
    for case in cases:
        case["expect"] = {"status": status}
    doc = {"schema": "isect-cases/1", "cases": cases}
    rc, out = _run(capsys, str(_write(tmp_path, "mesh.json", doc)))
    assert rc == 0 and out.strip() == "4 passed, 0 failed", out


def test_open_mesh_contains_is_an_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    box = {**CUBE, "faces": CUBE["faces"][1:]}  # no bottom
    doc = _one_case(op="contains", shape=box, ray=None, point=[0.5, 0.5, 0.5],
                    expect={"status": "ok", "inside": 1})  # fmt: skip
    rc, out = _run(capsys, str(_write(tmp_path, "open.json", doc)))
    assert rc == 1 and "expected ok, actual E_ARG" in out, out
    assert '"status": "E_ARG"' in out
    doc["cases"][0]["expect"] = {"status": "E_ARG"}
    rc, out = _run(capsys, str(_write(tmp_path, "open.json", doc)))
    assert rc == 0, out


def test_wrong_report_fails_and_names_the_fields(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    doc = _mesh_cases()
    report = doc["cases"][0]["expect"]["report"]
    report.update(genus=1, closed=0, volume=1.5)
    report["area"] = 6 * (1 + 1e-13)  # within the default tolerance
    rc, out = _run(capsys, "--json", str(_write(tmp_path, "mesh.json", doc)))
    assert rc == 1
    result = json.loads(out)
    assert (result["passed"], result["failed"], result["malformed"]) == (3, 1, 0)
    (fail,) = (r for r in result["results"] if r["status"] == "fail")
    assert fail["id"] == 7
    assert "report.genus: expected 1, actual 0" in fail["message"]
    assert "report.closed: expected 0, actual 1" in fail["message"]
    assert "report.volume: expected 1.5, actual 1.0" in fail["message"]
    assert "area" not in fail["message"] and "vertices" not in fail["message"]
    assert fail["actual"]["report"] == CUBE_REPORT
    report.update(genus=0, closed=1, volume=1.0, area=6.01)
    doc["cases"][0]["tol"] = {"area": 1e-2}  # tol.area applies to area
    rc, out = _run(capsys, str(_write(tmp_path, "mesh.json", doc)))
    assert rc == 0, out


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"shape": {**CUBE, "faces": [0, 1, 2]}}, "shape.faces[0]"),  # not a list of lists
        ({"shape": {**CUBE, "faces": "0 1 2"}}, "shape.faces"),
        ({"shape": {**CUBE, "faces": [[0, 1, 2.5]]}}, "shape.faces[0][2]"),
        ({"shape": {**CUBE, "faces": [[0, 1, True]]}}, "shape.faces[0][2]"),
        ({"shape": {"type": "mesh", "faces": [[0, 1, 2]]}}, "shape.vertices"),
        ({"shape": {**CUBE, "vertices": [[0, 0, "zero"]]}}, "shape.vertices[0][2]"),
        ({"shape": {"type": "mesh", "vertices": [[0, 0, 0]]}}, "shape.faces"),
        ({"shape": {"type": "sphere", "center": [0, 0, 0], "radius": 1}}, "shape.type"),
        ({"expect": {"status": "ok"}}, "expect.report"),
        ({"expect": {"status": "ok", "report": [8, 12]}}, "expect.report"),
        ({"expect": {"status": "ok", "report": {**CUBE_REPORT, "colour": 1}}},
         "expect.report.colour"),
        ({"expect": {"status": "ok", "report": {**CUBE_REPORT, "genus": None}}},
         "expect.report.genus"),
        ({"expect": {"status": "ok", "report": {**CUBE_REPORT, "edges": 12.0}}},
         "expect.report.edges"),
        ({"expect": {"status": "ok", "report": {**CUBE_REPORT, "closed": 2}}},
         "expect.report.closed"),
        ({"expect": {"status": "ok", "report": {**CUBE_REPORT, "area": "big"}}},
         "expect.report.area"),
        ({"expect": {"status": "ok", "report": {
            k: v for k, v in CUBE_REPORT.items() if k != "components"}}},
         "expect.report.components"),
    ],
)  # fmt: skip
def test_malformed_mesh_case_is_named(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], changes: dict[str, Any], field: str
) -> None:
    """A bad mesh case: file, case and field named, the other cases still run."""
    rc, out = _run(capsys, str(_write(tmp_path, "badmesh.json", _mesh_cases(**changes))))
    assert rc == 1 and "Traceback" not in out
    (line,) = (x for x in out.splitlines() if x.startswith("ERROR"))
    assert "badmesh.json" in line and "case 7 (my case)" in line, line
    assert f"field {field!r}" in line, line
    assert out.strip().splitlines()[-1] == "3 passed, 1 failed"


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("{not json", "not valid JSON"),
        ("[1, 2]", "one JSON object"),
        (json.dumps({"schema": "other/2", "cases": []}), "'schema'"),
        (json.dumps({"schema": "isect-cases/1"}), "'cases'"),
        (json.dumps({"schema": "isect-cases/1", "number_of_cases": 3, "cases": []}),
         "'number_of_cases'"),
    ],
)  # fmt: skip
def test_malformed_file_is_named(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str, words: str
) -> None:
    path = _write(tmp_path, "broken.json", text)
    good = _write(tmp_path, "good.json", _one_case())
    rc, out = _run(capsys, str(path), str(good))
    assert rc == 1 and "Traceback" not in out
    line = next(x for x in out.splitlines() if x.startswith("ERROR"))
    assert "broken.json" in line and words in line, line
    assert out.strip().splitlines()[-1] == "1 passed, 1 failed"  # the good file still ran


def test_missing_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rc, out = _run(capsys, str(tmp_path / "nope.json"))
    assert rc == 1 and "nope.json" in out and "cannot read" in out


def test_json_output_parses(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    doc = _one_case()
    wrong = copy.deepcopy(doc["cases"][0])
    wrong["id"], wrong["expect"]["hits"][0]["t"] = 8, 4.5
    doc["cases"].append(wrong)
    bad = _write(tmp_path, "bad.json", _one_case(shape={"type": "donut"}))
    rc, out = _run(capsys, "--json", str(_write(tmp_path, "mine.json", doc)), str(bad))
    assert rc == 1
    result = json.loads(out)
    assert result["schema"] == "isect-cases/1"
    assert (result["passed"], result["failed"], result["malformed"]) == (1, 2, 1)
    by_id = {(Path(r["file"]).name, r["id"]): r for r in result["results"]}
    assert by_id[("mine.json", 7)]["status"] == "pass"
    fail = by_id[("mine.json", 8)]
    assert fail["status"] == "fail" and fail["expected"]["hits"][0]["t"] == 4.5
    assert fail["actual"]["hits"][0]["t"] == 4.0 and fail["actual"]["count"] == 2
    assert by_id[("bad.json", 7)]["status"] == "error"
    assert "shape.type" in by_id[("bad.json", 7)]["message"]


def test_json_output_of_real_corpus_is_strict_json() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "isect", "cases", "--json", str(ROOT / "tests/cases/bad_input.json")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout, parse_constant=lambda c: pytest.fail(f"non-JSON {c}"))
    assert doc["failed"] == 0 and doc["passed"] > 0


def test_usage(capsys: pytest.CaptureFixture[str]) -> None:
    assert main([]) == 2
    assert "usage: python -m isect cases" in capsys.readouterr().err
    assert main(["--help"]) == 0
