#!/usr/bin/env bash
# fuzz/run.sh BUILD TARGET... — runs each fuzz target (BUILD/fuzz/fuzz_TARGET) for FUZZ_SECONDS
# (default 60) over its seed corpus fuzz/corpus/TARGET, FUZZ_JOBS (default 1) targets at a time.
# `make fuzz` calls it. The repository is never written: new inputs go to
# BUILD/fuzz-out/TARGET/corpus (kept for the next run), crash files to BUILD/fuzz-out/TARGET/
# (crash-*, leak-*, timeout-*, oom-*), the log to BUILD/fuzz-out/TARGET.log, the targets' scratch
# files under BUILD/fuzz-out/tmp. Exits non-zero if any target found a crash, naming its files.
set -uo pipefail
cd "$(dirname "$0")/.."
build=$1
shift
seconds=${FUZZ_SECONDS:-60}
jobs=${FUZZ_JOBS:-1}
out=$build/fuzz-out
mkdir -p "$out/tmp"

run_one() {
    local target=$1 dir=$out/$1
    # Kept from run to run: the inputs found (a head start) and earlier crash files.
    mkdir -p "$dir/corpus"
    touch "$dir/.started"
    local dict=()
    [ -f "fuzz/$target.dict" ] && dict=(-dict="fuzz/$target.dict")
    # -timeout: one input may take 10 s (a sanitised build); -rss_limit_mb / -malloc_limit_mb: a
    # file that claims a huge image must be refused, not allocated.
    TMPDIR=$out/tmp LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 \
        -rss_limit_mb=2048 -malloc_limit_mb=2048 -print_final_stats=1 "${dict[@]}" \
        -artifact_prefix="$dir/" "$dir/corpus" "fuzz/corpus/$target" >"$out/$target.log" 2>&1
    local rc=$?
    local execs cov
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$out/$target.log" | grep -o '[0-9]*$')
    cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$out/$target.log" | tail -1)
    if [ $rc -eq 0 ]; then
        echo "fuzz_$target: ${execs:-?} runs in ${seconds} s, $cov, no crash"
    else
        echo "fuzz_$target: FAILED (exit $rc) after ${execs:-?} runs; log $out/$target.log; crash file(s):"
        find "$dir" -maxdepth 1 -newer "$dir/.started" \( -name 'crash-*' -o -name 'leak-*' \
            -o -name 'timeout-*' -o -name 'oom-*' \) | sed 's/^/    /'
        echo "    reproduce: $build/fuzz/fuzz_$target FILE; then copy FILE to tests/data/bad/fuzz/$target/"
    fi
    return $rc
}
export -f run_one
export build out seconds

printf '%s\n' "$@" | xargs -P "$jobs" -I{} bash -c 'run_one {}'
