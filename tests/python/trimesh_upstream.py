# SPDX-License-Identifier: Apache-2.0
"""trimesh's own ray tests, fetched from the sdist of the installed trimesh,
for test_trimesh_ray.py to run with isect's intersector swapped in.

The tests are not in trimesh's wheel, and not in this repository: the source
distribution of the installed version carries them (``tests/test_ray.py``,
``tests/test_ray_upstream.py``). :func:`find_tests` finds them, in order:

1. the directory or ``.tar.gz`` sdist named by ``ISECT_TRIMESH_TESTS``;
2. the cache ``build/trimesh-tests/<version>/`` of an earlier run;
3. ``pip download --no-deps --no-binary :all: trimesh==<version>`` (the
   package registry, through pip), extracted into that cache.

They import a helper module ``generic`` that trimesh keeps in its repository
but not in the sdist, together with the model files it loads; :func:`load`
gives them :data:`generic`, a stand-in written here: numpy and trimesh, a
seeded ``random``, a logger, and ``get_mesh`` which builds two of the models
with ``trimesh.creation`` (a unit cube and a unit sphere centred at the
origin, as their names say) and skips a test that needs any other model file.
"""

from __future__ import annotations

import importlib.util
import io
import logging
import os
import subprocess
import sys
import tarfile
import tempfile
import time
import types
from pathlib import Path
from typing import Any

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
FILES = ("test_ray.py", "test_ray_upstream.py")


def trimesh_version() -> str | None:
    """The installed trimesh's version, or None."""
    try:
        import trimesh
    except ImportError:
        return None
    return str(trimesh.__version__)


def _extract(sdist: Path, into: Path) -> None:
    """Copy FILES out of an sdist's ``*/tests/`` into ``into``."""
    into.mkdir(parents=True, exist_ok=True)
    with tarfile.open(sdist) as tar:
        for member in tar.getmembers():
            parts = Path(member.name).parts
            if len(parts) == 3 and parts[1] == "tests" and parts[2] in FILES and member.isfile():
                data = tar.extractfile(member)
                assert data is not None
                (into / parts[2]).write_bytes(data.read())


def find_tests() -> tuple[Path | None, str]:
    """The directory holding FILES, or None and the reason they are missing."""
    version = trimesh_version()
    if version is None:
        return None, "trimesh is not installed"
    override = os.environ.get("ISECT_TRIMESH_TESTS")
    if override:
        path = Path(override)
        if path.is_file():
            cache = ROOT / "build" / "trimesh-tests" / f"{version}-local"
            _extract(path, cache)
            path = cache
        return (path, "") if all((path / f).is_file() for f in FILES) else (
            None, f"ISECT_TRIMESH_TESTS={override} has no {' and '.join(FILES)}")
    cache = ROOT / "build" / "trimesh-tests" / version
    if all((cache / f).is_file() for f in FILES):
        return cache, ""
    with tempfile.TemporaryDirectory() as tmp:
        try:
            run = subprocess.run(
                [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps",
                 "--no-binary", ":all:", "--dest", tmp, f"trimesh=={version}"],
                capture_output=True, text=True, timeout=300, check=False,
            )
        except (OSError, subprocess.TimeoutExpired) as exc:
            return None, f"pip download of the trimesh {version} sdist failed: {exc}"
        sdists = sorted(Path(tmp).glob("trimesh-*.tar.gz"))
        if run.returncode != 0 or not sdists:
            last = (run.stderr.strip().splitlines() or ["no sdist"])[-1]
            return None, f"pip download of the trimesh {version} sdist failed: {last}"
        _extract(sdists[0], cache)
    if not all((cache / f).is_file() for f in FILES):
        return None, f"the trimesh {version} sdist has no tests/{' or tests/'.join(FILES)}"
    return cache, ""


# ------------------------------------------------------ the generic stand-in


def _get_mesh(name: str, **kwargs: Any) -> Any:
    """The models the ray tests load that trimesh.creation can make as their
    names describe; a test needing another model file is skipped."""
    import trimesh

    if name == "unit_cube.STL":
        return trimesh.creation.box(extents=(1.0, 1.0, 1.0), **kwargs)
    if name == "unit_sphere.STL":
        return trimesh.creation.icosphere(subdivisions=3, radius=1.0, **kwargs)
    pytest.skip(f"model file {name} is not in trimesh's sdist (trimesh keeps its models "
                "in its repository)")


def _random(*shape: Any) -> Any:
    """Uniform numbers in [0, 1) of the shape (like numpy.random.random),
    from a seeded generator, so runs repeat."""
    size = shape[0] if len(shape) == 1 else (shape or None)
    return _rng.random(size)


_rng = np.random.default_rng(20240917)


class _NoData(dict):  # type: ignore[type-arg]
    """trimesh's test data files (``g.data[...]``) are not in the sdist: a
    test that reads one is skipped."""

    def __missing__(self, key: str) -> Any:
        pytest.skip(f"trimesh's test data {key!r} is not in its sdist")


def make_generic() -> types.ModuleType:
    """A fresh ``generic`` stand-in module."""
    import trimesh

    g = types.ModuleType("generic")
    g.np = np  # type: ignore[attr-defined]
    g.trimesh = trimesh  # type: ignore[attr-defined]
    g.time = time  # type: ignore[attr-defined]
    g.io = io  # type: ignore[attr-defined]
    g.log = logging.getLogger("trimesh.tests")  # type: ignore[attr-defined]
    g.random = _random  # type: ignore[attr-defined]
    g.get_mesh = _get_mesh  # type: ignore[attr-defined]
    g.data = _NoData()  # type: ignore[attr-defined]
    return g


def load(path: Path) -> types.ModuleType:
    """Import one of trimesh's test files with the stand-in ``generic``."""
    saved = sys.modules.get("generic")
    sys.modules["generic"] = make_generic()
    try:
        spec = importlib.util.spec_from_file_location(f"trimesh_upstream_{path.stem}", path)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
    finally:
        if saved is None:
            sys.modules.pop("generic", None)
        else:
            sys.modules["generic"] = saved
    return module
