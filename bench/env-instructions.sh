#!/usr/bin/env bash
# Instructions per environment lookup, counted by callgrind (exact and repeatable, unlike
# wall-clock rates on a shared machine): every layout × regime × form of footprint-bench env, on
# the smaller map of footprint-env-instructions (bench/env_instructions_main.cpp).
#
#   bash bench/env-instructions.sh [BUILD_DIR]     (default build/; needs valgrind)
#
# Prints one line per case: instructions per lookup (only the lookups are counted) and a hash of
# the results' bits (equal hashes: the same results, bit for bit).
set -euo pipefail
build=${1:-build}
driver=$build/footprint-env-instructions
command -v valgrind >/dev/null || { echo "env-instructions: valgrind is not installed" >&2; exit 1; }
[ -x "$driver" ] || { echo "env-instructions: $driver is missing (make build)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# OpenImageIO loads libhwy, whose initialiser reads the clock with rdtscp, which valgrind cannot
# run: its TimerResolution() is replaced by a stub (nothing measured calls it).
if ldd "$driver" | grep libhwy >/dev/null; then  # (not grep -q: pipefail, SIGPIPE)
    printf '#include <cstdint>\nnamespace hwy::platform { uint64_t TimerResolution() { return 1; } }\n' |
        c++ -x c++ -shared -fPIC -O2 -o "$out/hwy-timer-stub.so" - ||
        { echo "env-instructions: cannot build the libhwy timer stub" >&2; exit 1; }
    export LD_PRELOAD="$out/hwy-timer-stub.so${LD_PRELOAD:+:$LD_PRELOAD}"
fi
count_one() {  # layout regime form
    local lookups=20000
    [ "$2" = aniso32 ] && lookups=2000  # a long probe line each
    local log=$out/$1.$2.$3.log
    valgrind --tool=callgrind --callgrind-out-file="$out/$1.$2.$3.cg" \
        --toggle-collect='footprint::bench::run_*' "$driver" "$1" "$2" "$3" "$lookups" >"$log" 2>&1 ||
        { echo "env-instructions: $1 $2 $3 failed:" >&2; cat "$log" >&2; return 1; }
    local collected results
    collected=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$log")
    results=$(sed -n 's/.*results \([0-9a-f]*\).*/\1/p' "$log")
    printf '%-8s %-10s %-7s %8d  %s\n' "$1" "$2" "$3" $((collected / lookups)) "$results"
}
export -f count_one
export driver out
printf '%-8s %-10s %-7s %8s  %s\n' layout regime form instr/lookup results
for layout in latlong cube; do
    for regime in tiny moderate aniso32 pole_band; do
        for form in single batch; do echo "$layout $regime $form"; done
    done
done | xargs -P "$(nproc)" -L 1 bash -c 'count_one "$@"' _ | sort -k1,1r -k2,2 -k3,3r
