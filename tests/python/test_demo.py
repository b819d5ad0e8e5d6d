# SPDX-License-Identifier: Apache-2.0
"""The demo renderer (demo/render.py, run by ``make demo``) at a reduced size:
both pictures are written, non-empty, and every object of the scene shows in
its own colour."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
import time
from pathlib import Path
from types import ModuleType
from typing import Any

import isect
import numpy as np
import pytest
from conftest import ROOT
from PIL import Image

RENDER = ROOT / "demo" / "render.py"
WIDTH, HEIGHT = 240, 180


def _module() -> ModuleType:
    spec = importlib.util.spec_from_file_location("demo_render", RENDER)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def demo(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """Run the demo once, as ``make demo`` does but smaller, into a temp dir."""
    out = tmp_path_factory.mktemp("demo")
    start = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, str(RENDER), "--size", f"{WIDTH}x{HEIGHT}", "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    return {
        "out": out,
        "proc": proc,
        "seconds": time.perf_counter() - start,
        "module": _module(),
    }


def _pixels_of(rgb: np.ndarray, color: tuple[int, int, int]) -> int:
    """How many pixels are the colour shaded by some intensity >= 0.25 (the
    renderer multiplies each object's colour by a Lambert factor)."""
    b = np.asarray(color, float)
    p = rgb.reshape(-1, 3).astype(float)
    k = p @ b / (b @ b)
    residual = np.abs(p - k[:, None] * b).max(axis=1)
    return int(np.sum((k >= 0.25) & (residual <= 2.0)))


def test_demo_runs_and_reports(demo: dict[str, Any]) -> None:
    proc = demo["proc"]
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr
    assert f"wrote {demo['out'] / 'scene.png'}" in proc.stdout
    summary = [line for line in proc.stdout.splitlines() if line.startswith("summary:")]
    assert len(summary) == 1, proc.stdout
    assert demo["seconds"] < 60


def test_scene_shows_every_object(demo: dict[str, Any]) -> None:
    path = demo["out"] / "scene.png"
    assert path.stat().st_size > 0
    img = Image.open(path).convert("RGB")
    assert img.width == WIDTH and img.height > HEIGHT  # the caption strip is below
    rgb = np.asarray(img)[:HEIGHT]  # the rendering only, not the caption's legend
    assert len(np.unique(rgb.reshape(-1, 3), axis=0)) > 50
    objects = demo["module"].build_scene()
    names = [o.name for o in objects]
    for expected in ("sphere", "box", "concave polygon", "pentagram even-odd",
                     "pentagram non-zero", "convex polyhedron", "capped cylinder", "ellipsoid",
                     "hyperboloid (clipped quadric)", "rotated, sheared box"):  # fmt: skip
        assert expected in names
    if hasattr(isect, "Mesh"):
        assert any("mesh" in n for n in names)
    assert len({o.color for o in objects}) == len(objects)
    missing = [o.name for o in objects if _pixels_of(rgb, o.color) < 15]
    assert not missing, f"objects not visible in scene.png: {missing}"


def test_exactly_once(demo: dict[str, Any]) -> None:
    path = demo["out"] / "exactly_once.png"
    if not hasattr(isect, "Mesh"):
        assert not path.exists()
        assert "skipped" in demo["proc"].stdout
        pytest.skip("isect.Mesh is not available yet")
    assert path.stat().st_size > 0
    rgb = np.asarray(Image.open(path).convert("RGB"))
    assert rgb.shape[1] >= 2 * 240
    panel = rgb[:240, :240]  # libisect's half: every ray crosses once (green)
    assert _pixels_of(panel, (60, 210, 90)) > 100
    assert _pixels_of(panel, (255, 60, 60)) == 0  # no leak
    assert "exactly-once: libisect 0 leaks/0 double hits" in demo["proc"].stdout
