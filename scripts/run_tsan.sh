#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# ThreadSanitizer runs (mk/tsan.mk builds what they run):
#
#   run_tsan.sh c [rays [threads]]   build/tsan/tests/test_threads (default
#                                    2000 rays, 8 threads)
#   run_tsan.sh python               tests/python/tsan_threads.py on the
#                                    package in build/tsan/py, libtsan preloaded
#   run_tsan.sh                      both
#
# Each run is preceded by a deliberate race (--race), which the sanitizer must
# report: that shows it is live in that process. The run itself fails on any
# "WARNING: ThreadSanitizer" report, whatever the exit status, and on any
# failed comparison. Prints the run's output and a closing "N passed, N failed".
set -u
cd "$(dirname "$0")/.."
B=${B:-build}
what=${1:-all}
[ $# -gt 0 ] && shift
# exitcode=66: a report also makes the exit status non-zero; history_size:
# full stacks for the (hopefully never seen) second access of a report.
TSAN_OPTIONS="halt_on_error=0 exitcode=66 history_size=4 ${TSAN_OPTIONS:-}"
export TSAN_OPTIONS
log=$(mktemp)
trap 'rm -f "$log"' EXIT
fail=0

# live NAME CMD...: the deliberate race must be reported.
live() {
    name=$1; shift
    "$@" >"$log" 2>&1
    if grep -q "WARNING: ThreadSanitizer: data race" "$log"; then
        echo "$name: the sanitizer is live (the deliberate race of --race was reported)"
    else
        cat "$log"
        echo "FAILED: $name: the deliberate race of --race was not reported"
        fail=1
    fi
}

# clean NAME CMD...: the run must pass and report nothing.
clean() {
    name=$1; shift
    "$@" >"$log" 2>&1
    rc=$?
    cat "$log"
    reports=$(grep -c "WARNING: ThreadSanitizer" "$log")
    echo "$name: exit status $rc, ThreadSanitizer reports: $reports"
    if [ "$rc" -ne 0 ] || [ "$reports" -ne 0 ]; then
        echo "FAILED: $name"
        fail=1
    fi
}

if [ "$what" = c ] || [ "$what" = all ]; then
    bin=$B/tsan/tests/test_threads
    live "test_threads [tsan]" "$bin" --race 20 4
    clean "test_threads [tsan]" "$bin" "${1:-2000}" "${2:-8}"
fi
if [ "$what" = python ] || [ "$what" = all ]; then
    libtsan=$(${CC:-cc} -print-file-name=libtsan.so)
    py() {
        LD_PRELOAD=$libtsan PYTHONPATH=$B/tsan/py .venv/bin/python tests/python/tsan_threads.py "$@"
    }
    live "python batch [tsan]" py --race
    clean "python batch [tsan]" py
fi
# The counts of the last run, for scripts/run_tests.sh (a failure of the
# checks above adds one failure).
p=$(grep -Eo '[0-9]+ passed' "$log" | tail -n 1 | grep -Eo '[0-9]+')
f=$(grep -Eo '[0-9]+ failed' "$log" | tail -n 1 | grep -Eo '[0-9]+')
p=${p:-0}; f=${f:-0}
[ "$fail" -eq 0 ] || [ "$f" -ne 0 ] || f=1
echo "$p passed, $f failed"
[ "$fail" -eq 0 ]
