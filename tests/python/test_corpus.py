"""The golden corpus (tests/cases/*.json) through the Python API.

Every case of every file is one test. An ``intersect`` case is run through
``intersect_all`` (every hit, compared with the expectation), ``intersect``
(the batch closest hit must equal the first hit bit for bit, or be a MISS) and
``intersect_all_batch`` (the same hits, bit for bit). Cases flagged ``c-only``
(raw integer shape types and the like) cannot be expressed through the Python
API and are skipped, as the schema allows.
"""

from __future__ import annotations

import math
import struct
from typing import Any

import isect
import numpy as np
import pytest
from corpus import (
    KINDS,
    SCHEMA,
    STATUS_ERRORS,
    case_shape,
    close,
    load_files,
    num,
    ray_args,
    tolerances,
)

FILES = load_files()


def _params() -> list[Any]:
    params = []
    for path, doc in FILES:
        for case in doc.get("cases", []):
            case_id = f"{path.stem}:{case.get('id')}:{case.get('name', '')}"
            params.append(pytest.param(doc, case, id=case_id))
    return params


def test_corpus_present() -> None:
    """The corpus exists and every file has the documented header."""
    assert FILES, "no tests/cases/*.json files"
    for path, doc in FILES:
        assert doc.get("schema") == SCHEMA, path.name
        assert doc["number_of_cases"] == len(doc["cases"]), path.name
        ids = [c["id"] for c in doc["cases"]]
        assert len(ids) == len(set(ids)), f"{path.name}: duplicate case ids"
        used = {flag for c in doc["cases"] for flag in c.get("flags", [])}
        missing = used - set(doc.get("notes", {}))
        assert not missing, f"{path.name}: flags without notes: {sorted(missing)}"


def _bits(x: float) -> bytes:
    return struct.pack("<d", x)


def _same_record(record: Any, hit: isect.Hit) -> bool:
    """A HIT_DTYPE record and a Hit hold the same bits."""
    ours = [
        float(record["t"]),
        *map(float, record["point"]),
        *map(float, record["normal"]),
        *map(float, record["uv"]),
    ]
    theirs = [hit.t, *hit.point, *hit.normal, *hit.uv]
    return (
        all(_bits(a) == _bits(b) for a, b in zip(ours, theirs))
        and int(record["prim"]) == hit.prim
        and int(record["kind"]) == int(hit.kind)
    )


def _check_hits(case: dict[str, Any], hits: list[isect.Hit]) -> None:
    expect = case["expect"]
    tol = tolerances(case)
    assert len(hits) == expect["count"], f"count {len(hits)} != {expect['count']}: {hits}"
    for i, (got, want) in enumerate(zip(hits, expect.get("hits", []))):
        where = f"hit {i}: {got}"
        assert close(got.t, num(want["t"]), tol["t"]), where
        for key, attr in (("point", got.point), ("normal", got.normal), ("uv", got.uv)):
            if key in want:
                assert all(close(a, e, tol[key]) for a, e in zip(attr, num(want[key]))), (
                    f"{where}: {key} != {want[key]}"
                )
        if "prim" in want:
            assert got.prim == want["prim"], where
        if "kind" in want:
            assert got.kind == KINDS[want["kind"]], where


def _run_intersect(case: dict[str, Any]) -> None:
    org, dirn, kwargs = ray_args(case)
    shape = case_shape(case)
    hits = shape.intersect_all(org, dirn, **kwargs)
    _check_hits(case, hits)

    closest = shape.intersect(org, dirn, **kwargs)
    if hits:
        assert _same_record(closest, hits[0]), f"batch {closest} != first hit {hits[0]}"
    else:
        assert closest["kind"] == isect.HitKind.MISS and closest["t"] == math.inf
        assert closest["prim"] == -1

    offsets, all_hits = shape.intersect_all_batch(org, dirn, **kwargs)
    assert offsets.tolist() == [0, len(hits)]
    assert all(_same_record(r, h) for r, h in zip(all_hits, hits))


def _ray_is_bad(case: dict[str, Any]) -> bool:
    org, dirn, kwargs = ray_args(case)
    values = [*org, *dirn]
    return (
        not all(math.isfinite(v) for v in values)
        or all(v == 0 for v in dirn)
        or math.isnan(kwargs["tmin"])
        or math.isnan(kwargs["tmax"])
    )


def _run_intersect_error(case: dict[str, Any], error: type[isect.IsectError]) -> None:
    org, dirn, kwargs = ray_args(case)
    with pytest.raises(error):
        case_shape(case).intersect_all(org, dirn, **kwargs)
    with pytest.raises(error):
        case_shape(case).intersect(org, dirn, **kwargs)
    if _ray_is_bad(case):
        # errors="mark": a bad ray is marked INVALID unless the shape or the
        # options are bad too, which raise whatever the ray.
        try:
            record = case_shape(case).intersect(org, dirn, errors="mark", **kwargs)
        except error:
            return
        assert record["kind"] == isect.HitKind.INVALID and math.isnan(record["t"])


def _contains(case: dict[str, Any]) -> bool:
    shape = case_shape(case)
    if not isinstance(shape, isect.Solid):
        # Thin surfaces have no contains() in Python; C answers E_ARG.
        raise isect.InvalidArgumentError("thin surfaces have no inside")
    return bool(shape.contains(num(case["point"])))


def _rule(case: dict[str, Any]) -> Any:
    return case.get("rule", "evenodd")


OPS = {
    "contains": lambda c: {"inside": int(_contains(c))},
    "point_in_polygon2": lambda c: {
        "inside": int(isect.point_in_polygon(num(c["polygon"]), num(c["point"]), rule=_rule(c)))
    },
    "winding_number2": lambda c: {
        "winding": int(isect.winding_number(num(c["polygon"]), num(c["point"])))
    },
    "polygon_normal": lambda c: {"normal": isect.polygon_normal(num(c["vertices"])).tolist()},
    "plane_from_points": lambda c: {"plane": isect.plane_from_points(num(c["vertices"])).tolist()},
}


@pytest.mark.parametrize(("doc", "case"), _params())
def test_case(doc: dict[str, Any], case: dict[str, Any]) -> None:
    """One corpus case through the Python API."""
    if "c-only" in case.get("flags", []):
        pytest.skip("c-only: not expressible through the Python API")
    op = case.get("op", "intersect")
    status = case["expect"]["status"]
    if op == "intersect":
        if status == "ok":
            _run_intersect(case)
        else:
            _run_intersect_error(case, STATUS_ERRORS[status])
        return
    run = OPS[op]
    if status != "ok":
        with pytest.raises(STATUS_ERRORS[status]):
            run(case)
        return
    got = run(case)
    expect = case["expect"]
    tol = tolerances(case)
    for key, value in got.items():
        if key not in expect:
            continue
        if isinstance(value, list):
            t = tol.get(key, tol["normal"])
            assert all(close(a, e, t) for a, e in zip(value, num(expect[key]))), (key, value)
            assert len(value) == len(expect[key])
        else:
            assert value == expect[key], (key, value, expect[key])


def test_every_op_known() -> None:
    """Every op in the corpus is one this runner knows."""
    ops = {c.get("op", "intersect") for _, doc in FILES for c in doc["cases"]}
    assert ops <= set(OPS) | {"intersect"}, ops


def test_shape_types_expressible() -> None:
    """Every string shape type in the corpus has a Python constructor."""
    types = {
        c["shape"]["type"]
        for _, doc in FILES
        for c in doc["cases"]
        if "shape" in c and isinstance(c["shape"]["type"], str)
    }
    known = {
        "plane",
        "sphere",
        "box",
        "triangle",
        "polygon",
        "convex",
        "cylinder",
        "infinite_cylinder",
        "ellipsoid",
        "quadric",
    }
    assert types <= known, types - known


def test_hit_dtype_record_fields() -> None:
    """The batch record's fields read as the documented numpy types."""
    rec = isect.Sphere([0, 0, 0], 1).intersect([0, 0, -5], [0, 0, 1])
    assert isinstance(rec, np.void) and rec.dtype == isect.HIT_DTYPE
