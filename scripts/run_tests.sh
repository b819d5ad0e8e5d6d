#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Runs every test of the project (the Makefile's `make test` builds them
# first) and ends with one line "N passed, N failed" summed over all of them.
# Each step prints its own closing line; a step without counts (a check
# script) counts as one test by its exit status. Exits non-zero on any failure.
set -u
cd "$(dirname "$0")/.."
B=build
PY=.venv/bin/python
total_pass=0
total_fail=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT

step() {
    name=$1; shift
    printf '== %s\n' "$name"
    "$@" >"$log" 2>&1
    rc=$?
    cat "$log"
    # The last "N passed" / "N failed" figures the step printed (C runners:
    # "N passed, N failed"; pytest: "N passed, M skipped in 3.2s").
    p=$(grep -Eo '[0-9]+ passed' "$log" | tail -n 1 | grep -Eo '[0-9]+')
    f=$(grep -Eo '[0-9]+ failed' "$log" | tail -n 1 | grep -Eo '[0-9]+')
    if [ -z "$p$f" ]; then
        if [ $rc -eq 0 ]; then p=1; f=0; else p=0; f=1; fi
    fi
    p=${p:-0}; f=${f:-0}
    if [ $rc -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi  # crashed after counting
    total_pass=$((total_pass + p))
    total_fail=$((total_fail + f))
    [ $rc -eq 0 ] || printf '!! %s exited with status %d\n' "$name" $rc
}

for t in $B/tests/test_*; do
    [ -x "$t" ] && step "$(basename "$t")" "$t"
done
for t in $B/san/tests/test_*; do
    [ -x "$t" ] && step "$(basename "$t") [asan+ubsan]" "$t"
done
# The portable code that SSE replaces on x86-64 (BVH build and node test),
# built with ISECT_NO_SIMD and held to the same mesh tests.
step "mesh tests build without SIMD" make --no-print-directory -s B=$B/nosimd \
    OPT="-O2 -DISECT_NO_SIMD" $B/nosimd/tests/test_mesh $B/nosimd/tests/test_mesh_exactly_once \
    $B/nosimd/tests/test_lanes
for t in test_mesh test_mesh_exactly_once; do
    [ -x $B/nosimd/tests/$t ] && step "$t [no SIMD]" $B/nosimd/tests/$t
done
# Batch records bit-identical to the scalar call at every SIMD level the
# CPU has (test_lanes: 350,000 random and adversarial rays per test shape,
# 3 to 12 shapes per primitive: over 10^6 rays per primitive), and the
# same records from the portable build without intrinsics (equal digests).
step "test_lanes 350,000 rays per shape" sh -c \
    "$B/tests/test_lanes 350000 >$B/lanes.out 2>&1; rc=\$?; cat $B/lanes.out; exit \$rc"
step "test_lanes [no SIMD]: the same digest" sh -c \
    "a=\$(grep digest $B/lanes.out); b=\$($B/nosimd/tests/test_lanes 350000 | grep digest); echo \"SIMD \$a, portable \$b\"; [ -n \"\$a\" ] && [ \"\$a\" = \"\$b\" ]"
# Exactly-once on closed meshes with injected degeneracies (zero-area and
# collinear faces, coincident vertices, repeated indices, slivers of
# rounding, ~1e+-150 coordinates): 10^6 rays, parity against an exact
# containment reference (the long run is the same with 100000000).
step "test_degenerate_mesh 10^6 rays" $B/tests/test_degenerate_mesh 1000000
# Secondary rays: 10^6 spawned rays per shape (reflected, refracted-like and
# random directions) never re-hit the surface they leave, never skip a close
# second surface.
step "test_spawn 10^6 rays per shape" $B/tests/test_spawn 1000000
# ThreadSanitizer (mk/tsan.mk): 8 threads on shared shapes and meshes, every
# batch kind, results equal to the single-threaded ones; any sanitizer report
# fails the step (scripts/run_tsan.sh, which first checks with a deliberate
# race that the sanitizer is live). Then the Python batch with threads= and
# concurrent Python threads, on the package built with -fsanitize=thread.
step "test_threads [tsan] 8 threads, 2000 rays per shape" sh scripts/run_tsan.sh c 2000 8
step "python batch build under tsan" make --no-print-directory -s tsan-py
step "python batch threads [tsan]" sh scripts/run_tsan.sh python
# The SSE2-only traversal that the AVX2 copy replaces on CPUs that have it.
step "mesh tests build without AVX2" make --no-print-directory -s B=$B/noavx2 \
    OPT="-O2 -DISECT_NO_AVX2" $B/noavx2/tests/test_mesh $B/noavx2/tests/test_mesh_exactly_once
for t in test_mesh test_mesh_exactly_once; do
    [ -x $B/noavx2/tests/$t ] && step "$t [SSE2 only]" $B/noavx2/tests/$t
done
# The batch's fallback when its lanes cannot be allocated (every ray traced
# at once), forced by a test build.
step "mesh tests build without batch lanes" make --no-print-directory -s B=$B/nolanes \
    OPT="-O2 -DISECT_TEST_NO_LANES" $B/nolanes/tests/test_mesh
[ -x $B/nolanes/tests/test_mesh ] && step "test_mesh [no batch lanes]" $B/nolanes/tests/test_mesh
if [ -x $B/tests/corpus_runner ]; then
    step "golden corpus (C)" $B/tests/corpus_runner tests/cases/*.json
    step "golden corpus (C) [asan+ubsan]" $B/san/tests/corpus_runner tests/cases/*.json
fi
# libFuzzer harnesses (tests/fuzz/, ASan+UBSan, invariants asserted), 60 s
# each: every shape query, spawned rays, mesh arrays, exactly-once parity on
# fuzzed closed meshes, the 2D polygon helpers, the corpus reader, winding
# numbers and mesh containment rules.
for h in shape spawn mesh mesh_parity polygon2 corpus winding; do
    [ -x $B/fuzz/fuzz_$h ] && step "fuzz_$h 60 s [libFuzzer asan+ubsan]" \
        env FUZZ_SEED=1 sh scripts/run_fuzz.sh $B/fuzz $h 60
done
step "fortran layout and constants" $B/fortran/test_layout libisect/include/isect.h
step "fortran module forms" $B/fortran/test_forms
step "golden corpus (Fortran)" $B/fortran/corpus_runner tests/cases/flat/*.txt
step "flat corpus export check" $PY tests/golden/export_flat.py --check
step "installed C and Fortran examples" sh tests/install/test_installed.sh
step "consumers: pkg-config, CMake find_package and FetchContent, meson subproject, fpm" \
    sh tests/install/consumers.sh
step "ABI check (abidiff)" sh tests/abi/check_abi.sh
step "exported symbols" sh scripts/check_exports.sh $B/libisect.so.1
step "clang -Werror build" make --no-print-directory -s CC=clang B=$B/clang lib
step "meson build and tests" sh scripts/meson_check.sh
step "SPDX licence headers" sh scripts/spdx_headers.sh --check
if [ -f tests/golden/generate.py ]; then
    step "corpus regeneration check" $PY tests/golden/generate.py --check
fi
if [ -d tests/python ]; then
    step "pytest" $PY -m pytest -q tests/python
fi

echo
echo "TOTAL: $total_pass passed, $total_fail failed"
[ "$total_fail" -eq 0 ]
