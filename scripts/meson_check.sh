#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Builds and tests with meson in build/meson (the second build system must
# build the same library and pass the same tests as the Makefile).
set -eu
cd "$(dirname "$0")/.."
if [ -f build/meson/build.ninja ]; then
    meson setup --reconfigure build/meson >/dev/null
else
    meson setup build/meson >/dev/null
fi
ninja -C build/meson >/dev/null
meson test -C build/meson --print-errorlogs
