# SPDX-License-Identifier: Apache-2.0
"""The golden corpus (tests/cases/*.json) through the Python API.

Every case of every file is one test. An ``intersect`` case is run through
``intersect_all`` (every hit, compared with the expectation), ``intersect``
(the batch closest hit must equal the first hit bit for bit, or be a MISS) and
``intersect_all_batch`` (the same hits, bit for bit). Cases flagged ``c-only``
(raw integer shape types and the like) cannot be expressed through the Python
API and are skipped, as the schema allows.
"""

from __future__ import annotations

from typing import Any

import isect
import numpy as np
import pytest
from corpus import SCHEMA, CaseFailure, check_case, load_files
from isect._cases import OPS, SHAPE_TYPES

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


@pytest.mark.parametrize(("doc", "case"), _params())
def test_case(doc: dict[str, Any], case: dict[str, Any]) -> None:
    """One corpus case through the Python API (the checks of isect._cases,
    which ``python -m isect cases`` runs too)."""
    try:
        actual = check_case(case)
    except CaseFailure as failure:
        pytest.fail(
            f"{failure}\nexpected: {case.get('expect')}\n"
            f"actual: {getattr(failure, 'actual', None)}"
        )
    if actual is None:
        pytest.skip("c-only: not expressible through the Python API")


def test_every_op_known() -> None:
    """Every op in the corpus is one this runner knows."""
    ops = {c.get("op", "intersect") for _, doc in FILES for c in doc["cases"]}
    assert ops <= set(OPS), ops


def test_shape_types_expressible() -> None:
    """Every string shape type in the corpus has a Python constructor."""
    types = {
        c["shape"]["type"]
        for _, doc in FILES
        for c in doc["cases"]
        if "shape" in c and isinstance(c["shape"]["type"], str)
    }
    known = set(SHAPE_TYPES)
    assert types <= known, types - known


def test_hit_dtype_record_fields() -> None:
    """The batch record's fields read as the documented numpy types."""
    rec = isect.Sphere([0, 0, 0], 1).intersect([0, 0, -5], [0, 0, 1])
    assert isinstance(rec, np.void) and rec.dtype == isect.HIT_DTYPE
