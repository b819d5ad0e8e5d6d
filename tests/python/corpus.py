# SPDX-License-Identifier: Apache-2.0
"""Reading the golden corpus (tests/cases/*.json, schema ``isect-cases/1``).

The reading and checking of cases lives in the package (``isect._cases``, the
engine of ``python -m isect cases``); this module only adds where the
project's own corpus is. See tests/cases/README.md.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from isect._cases import (  # noqa: F401  (re-exported for the tests)
    DEFAULT_TOL,
    KINDS,
    SCHEMA,
    STATUS_ERRORS,
    CaseFailure,
    build_shape,
    case_shape,
    check_case,
    close,
    num,
    ray_args,
    tolerances,
)

CASES_DIR = Path(__file__).resolve().parents[1] / "cases"


def load_files() -> list[tuple[Path, dict[str, Any]]]:
    """Every corpus file with its parsed document, sorted by name."""
    return [
        (path, json.loads(path.read_text(encoding="utf-8")))
        for path in sorted(CASES_DIR.glob("*.json"))
    ]
