#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Prints the version defined in libisect/include/isect.h — the one place it is
# defined — for the Makefile and meson.build.  `version.sh` → 1.0.0,
# `version.sh abi` → 1 (the soname number).
set -eu
header="$(dirname "$0")/../libisect/include/isect.h"
field() { sed -n "s/^#define ISECT_$1 *\([0-9][0-9]*\).*/\1/p" "$header"; }
if [ "${1:-}" = abi ]; then
    field ABI_VERSION
else
    printf '%s.%s.%s\n' "$(field VERSION_MAJOR)" "$(field VERSION_MINOR)" "$(field VERSION_PATCH)"
fi
