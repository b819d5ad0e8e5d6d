#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Runs one libFuzzer harness for a fixed time (make fuzz, make test).
#
#     sh scripts/run_fuzz.sh BUILD_FUZZ_DIR NAME SECONDS
#
# The harness BUILD_FUZZ_DIR/fuzz_NAME grows its corpus in
# BUILD_FUZZ_DIR/corpus/NAME (kept between runs) from the seeds in
# BUILD_FUZZ_DIR/seeds/NAME; a crashing input is saved as
# BUILD_FUZZ_DIR/artifacts/NAME-crash-<sha1> (replay: fuzz_NAME FILE;
# FUZZ_VERBOSE=1 prints the decoded call). The full log is
# BUILD_FUZZ_DIR/logs/NAME.log; this prints the summary line, and on failure
# the report (invariant message, sanitizer trace, reproducer path).
set -u
fz=$1 name=$2 seconds=$3
bin=$fz/fuzz_$name
log=$fz/logs/$name.log
mkdir -p "$fz/corpus/$name" "$fz/seeds/$name" "$fz/artifacts" "$fz/logs"
# -timeout: an input that takes 20 s is a hang; -rss_limit_mb: a leak or a
# runaway allocation; -max_len: the seeds are below 3 KB.
# FUZZ_SEED (make test: 1) fixes libFuzzer's mutation sequence, so a run
# explores the same inputs wherever it runs (0: a random seed).
# Inputs that once failed (tests/fuzz/regressions/NAME/, each file named
# for what it caught) are read as seeds on every run.
regressions=$(dirname "$0")/../tests/fuzz/regressions/$name
[ -d "$regressions" ] || regressions=
"$bin" "$fz/corpus/$name" "$fz/seeds/$name" $regressions -max_total_time="$seconds" -timeout=20 \
    -seed="${FUZZ_SEED:-0}" \
    -rss_limit_mb=2048 -max_len=8192 -artifact_prefix="$fz/artifacts/$name-" \
    -print_final_stats=1 >"$log" 2>&1
rc=$?
runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
done_line=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -n 1)
if [ $rc -eq 0 ]; then
    echo "fuzz_$name: ${runs:-?} executions in $seconds s (${rate:-?} exec/s), no failure"
    [ -n "$done_line" ] && echo "$done_line"
    exit 0
fi
echo "fuzz_$name FAILED (status $rc) after ${runs:-?} executions; log: $log"
# The report: from the first error line, without libFuzzer's own frames.
awk '/invariant violated|ERROR: |runtime error/ { on = 1 } on && !/fuzzer::|__libc_start|_start |libc.so/' \
    "$log" | head -n 40
exit 1
