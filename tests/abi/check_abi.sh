#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# ABI stability check of libisect.so (libabigail, Debian package abigail-tools).
#
#   sh tests/abi/check_abi.sh            check a fresh build against the baseline
#   sh tests/abi/check_abi.sh LIB        check that library instead
#   sh tests/abi/check_abi.sh --update   rewrite the baseline (`make abi-baseline`)
#
# The baseline libisect/abi/libisect.so.<ABI>.abi is `abidw` output: every
# exported function with its symbol version and the full layout of every type
# reachable from isect.h. The check fails when, compared with it, a function
# or variable was removed or changed (parameters, return type, any field,
# size or offset of a type it reaches, its symbol version), when a new symbol
# sits in a version node the baseline already has (each release adds its own
# node, ISECT_1.1 after ISECT_1.0, ...), or when the soname, ISECT_ABI_VERSION
# and isect_abi_version() disagree. Added functions are allowed and listed.
#
# abidw and abidiff read types from DWARF, which the default build (-O2, no
# -g) does not have, so with no LIB the library is built again with -g into
# build/abi (same sources, flags and version script, plus -g).
#
# abidiff's exit status is a bit set: 1 error, 2 usage error, 4 ABI change,
# 8 incompatible ABI change. Run with --no-added-syms, any change left (4 or
# 8) is a removal or a modification; the second run, with additions, only
# reports them.
set -u
cd "$(dirname "$0")/../.."
abi=$(sh scripts/version.sh abi)
baseline=libisect/abi/libisect.so.$abi.abi
headers=libisect/include
MAKE=${MAKE:-make}
CC=${CC:-cc}

for tool in abidw abidiff readelf nm; do
    if ! command -v $tool >/dev/null 2>&1; then
        echo "FAIL $tool not found (Debian: apt-get install abigail-tools binutils)"
        echo "0 passed, 1 failed"
        exit 1
    fi
done

update=0
if [ "${1:-}" = "--update" ]; then
    update=1
    shift
fi
if [ $# -ge 1 ]; then
    lib=$1
else
    if ! $MAKE -s --no-print-directory B=build/abi OPT="-O2 -g" lib >/dev/null; then
        echo "FAIL building build/abi/libisect.so.$abi with -g"
        echo "0 passed, 1 failed"
        exit 1
    fi
    lib=build/abi/libisect.so.$abi
fi

# Options that keep the baseline free of this machine's paths and limited to
# isect.h's types. Source locations stay in (as paths relative to the source
# root): abidiff's header filter (--hd2) decides by them which types are
# public, and without them every type change would be filtered out.
dump_opts="--headers-dir $headers --drop-private-types --no-corpus-path --no-comp-dir-path"

if [ $update -eq 1 ]; then
    mkdir -p "$(dirname "$baseline")"
    # shellcheck disable=SC2086
    abidw $dump_opts --out-file "$baseline" "$lib" || exit 1
    echo "wrote $baseline from $lib ($(grep -c '<elf-symbol ' "$baseline") symbols)"
    exit 0
fi

passed=0
failed=0
pass() { passed=$((passed + 1)); printf 'ok   %s\n' "$1"; }
fail() { failed=$((failed + 1)); printf 'FAIL %s\n' "$1"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

if [ ! -f "$baseline" ]; then
    fail "no baseline $baseline (make abi-baseline writes it)"
    echo "$passed passed, $failed failed"
    exit 1
fi

# 1. Nothing removed or changed.
changed=1
abidiff --no-added-syms --hd2 "$headers" --drop-private-types --no-show-locs \
    "$baseline" "$lib" >"$tmp/changes" 2>&1
rc=$?
if [ $((rc & 3)) -ne 0 ]; then
    cat "$tmp/changes"
    fail "abidiff could not compare $baseline with $lib (exit status $rc)"
elif [ $((rc & 12)) -ne 0 ]; then
    cat "$tmp/changes"
    fail "ABI of $lib: removed or changed functions or types against $baseline (above)"
else
    changed=0
    pass "no function or type of $baseline removed or changed"
fi

# 2. Additions: allowed, reported. (When nothing was removed or changed,
# whatever abidiff still finds is an addition.)
if [ $changed -eq 0 ]; then
    abidiff --hd2 "$headers" --drop-private-types --no-show-locs "$baseline" "$lib" \
        >"$tmp/all" 2>&1
    rc=$?
    if [ $((rc & 3)) -eq 0 ] && [ $((rc & 4)) -ne 0 ]; then
        echo "note: additions to the ABI (allowed; the baseline is regenerated at the release):"
        sed 's/^/    /' "$tmp/all"
    fi
fi

# 3. New symbols go into a new version node.
sed -n "s/.*<elf-symbol name='\([^']*\)' version='\([^']*\)'.*/\1 \2/p" "$baseline" \
    | sort -u >"$tmp/base_syms"
cut -d' ' -f2 "$tmp/base_syms" | sort -u >"$tmp/base_nodes"
nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBR]$/ {print $3}' | grep '^isect_' \
    | sed 's/@@*/ /' | sort -u >"$tmp/lib_syms"
bad_nodes=$(join -v 2 "$tmp/base_syms" "$tmp/lib_syms" | while read -r name node; do
    if grep -qx "$node" "$tmp/base_nodes"; then echo "$name@$node"; fi
done)
if [ -n "$bad_nodes" ]; then
    fail "symbols added to a version node of an earlier release (give the release its own node in libisect/isect.map): $bad_nodes"
else
    pass "new symbols, if any, are in a new version node"
fi

# 4. soname, ISECT_ABI_VERSION and isect_abi_version() agree.
soname=$(readelf -d "$lib" | sed -n 's/.*SONAME.*\[\(.*\)\].*/\1/p')
if [ "$soname" = "libisect.so.$abi" ]; then
    pass "soname $soname = libisect.so.ISECT_ABI_VERSION"
else
    fail "soname (expected libisect.so.$abi from ISECT_ABI_VERSION, got '$soname')"
fi
cat >"$tmp/abi_version.c" <<'EOF'
#include <isect.h>
#include <stdio.h>
int main(void)
{
    printf("%d %d\n", isect_abi_version(), ISECT_ABI_VERSION);
    return 0;
}
EOF
libdir=$(cd "$(dirname "$lib")" && pwd)
cp "$lib" "$tmp/libisect.so.$abi"
ln -sf "libisect.so.$abi" "$tmp/libisect.so"
if $CC -std=c99 -I"$headers" "$tmp/abi_version.c" -o "$tmp/abi_version" -L"$tmp" -lisect \
        >"$tmp/cc.log" 2>&1; then
    got=$(LD_LIBRARY_PATH="$tmp:$libdir" "$tmp/abi_version")
    if [ "$got" = "$abi $abi" ]; then
        pass "isect_abi_version() = ISECT_ABI_VERSION = $abi"
    else
        fail "isect_abi_version() and ISECT_ABI_VERSION (expected '$abi $abi', got '$got')"
    fi
else
    cat "$tmp/cc.log"
    fail "building the isect_abi_version() probe"
fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
