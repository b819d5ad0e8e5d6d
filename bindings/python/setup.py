# SPDX-License-Identifier: Apache-2.0
"""setuptools glue: the cffi extension, the version from isect.h, and an sdist
that carries the libisect sources along (see build_isect.py)."""

from __future__ import annotations

import re
import shutil
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.sdist import sdist

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from build_isect import find_libisect as libisect_root  # noqa: E402


def read_version() -> str:
    """ISECT_VERSION_STRING from isect.h, the one place the version is defined."""
    header = (libisect_root() / "include" / "isect.h").read_text(encoding="utf-8")
    match = re.search(r'#define\s+ISECT_VERSION_STRING\s+"([^"]+)"', header)
    if match is None:
        raise RuntimeError("ISECT_VERSION_STRING not found in isect.h")
    return match.group(1)


class SdistWithLibisect(sdist):
    """sdist that copies libisect/include and libisect/src into _libisect/."""

    def make_release_tree(self, base_dir: str, files: list[str]) -> None:
        """Build the release tree, then add the libisect sources."""
        super().make_release_tree(base_dir, files)
        src = libisect_root()
        dst = Path(base_dir) / "_libisect"
        for part in ("include", "src"):
            shutil.copytree(src / part, dst / part, dirs_exist_ok=True)


setup(
    version=read_version(),
    cffi_modules=["build_isect.py:ffibuilder"],
    cmdclass={"sdist": SdistWithLibisect},
)
