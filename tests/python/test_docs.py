# SPDX-License-Identifier: Apache-2.0
"""The Python examples of the documentation run as written."""

from __future__ import annotations

import re

import pytest
from conftest import ROOT


def python_blocks() -> list[tuple[str, str]]:
    """```python blocks of README.md's Python section."""
    blocks = []
    for path in (ROOT / "README.md",):
        if not path.is_file():
            continue
        text = path.read_text(encoding="utf-8")
        if path.name == "README.md":
            match = re.search(r"^## Python\b.*?(?=^## |\Z)", text, re.M | re.S)
            text = match.group(0) if match else ""
        for i, code in enumerate(re.findall(r"^```python\n(.*?)^```", text, re.M | re.S)):
            blocks.append((f"{path.name}:{i}", code))
    return blocks


BLOCKS = python_blocks()


@pytest.mark.skipif(not BLOCKS, reason="no Python examples in README.md")
@pytest.mark.parametrize("code", [c for _, c in BLOCKS], ids=[n for n, _ in BLOCKS])
def test_example_runs(code: str, capsys: pytest.CaptureFixture[str]) -> None:
    """Each example executes without error and prints something."""
    exec(compile(code, "<example>", "exec"), {"__name__": "__example__"})
    assert capsys.readouterr().out.strip()
