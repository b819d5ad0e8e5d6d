#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# The library exports exactly the functions isect.h declares with ISECT_API:
# nothing else (no helper leaks out of -fvisibility=hidden and the version
# script) and nothing missing. Usage: check_exports.sh path/to/libisect.so.1
set -eu
lib=$1
header="$(dirname "$0")/../libisect/include/isect.h"
exported=$(mktemp); declared=$(mktemp)
trap 'rm -f "$exported" "$declared"' EXIT
nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBR]$/ {print $3}' | sed 's/@.*//' \
    | grep -v '^ISECT_[0-9_.]*$' | sort -u >"$exported"
grep -v '^ *#' "$header" | tr '\n' ' ' | grep -Eo 'ISECT_API[^;(]*\(' \
    | sed -E 's/.*[^A-Za-z0-9_](isect_[A-Za-z0-9_]+) *\($/\1/' | sort -u >"$declared"
status=0
if grep -v '^isect_' "$exported"; then
    echo "FAIL: symbols above are exported but not named isect_*"; status=1
fi
if ! diff -u "$declared" "$exported"; then
    echo "FAIL: exported symbols differ from the ISECT_API declarations of isect.h"; status=1
fi
# Every export carries the version node of the release that added it.
if nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBR]$/ {print $3}' | grep '^isect_' | grep -qv '@@ISECT_'; then
    echo "FAIL: an isect_ symbol has no ISECT_ version node"; status=1
fi
n=$(wc -l <"$exported")
[ $status -eq 0 ] && echo "exports OK: $n isect_* functions, all declared, all versioned"
exit $status
