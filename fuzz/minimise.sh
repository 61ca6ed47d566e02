#!/usr/bin/env bash
# fuzz/minimise.sh BUILD TARGET KB DIR... — replaces the seed corpus fuzz/corpus/TARGET by a
# libFuzzer merge (-merge=1) of it and the inputs in DIR... (a campaign's): the inputs that add
# coverage, smallest first, up to KB kilobytes beside the seeds already there, which are kept (the
# repository keeps its corpora small). Run after a campaign; commit the result.
set -euo pipefail
cd "$(dirname "$0")/.."
build=$1 target=$2 kb=$3
shift 3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/merged" "$work/tmp"
TMPDIR=$work/tmp LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp "$build/fuzz/fuzz_$target" \
    -merge=1 -timeout=10 -rss_limit_mb=2048 "$work/merged" "fuzz/corpus/$target" "$@" \
    >"$work/merge.log" 2>&1 || { tail -20 "$work/merge.log"; exit 1; }
grep 'MERGE-OUTER: [0-9]* new files' "$work/merge.log"
# libFuzzer names a merged input by its SHA-1: the seeds' own copies are left out.
seeds=$(sha1sum "fuzz/corpus/$target"/* | cut -d' ' -f1)
total=0 kept=0
while read -r size file; do
    grep -qx "$file" <<<"$seeds" && continue
    total=$((total + size))
    [ $total -gt $((kb * 1024)) ] && break
    cp "$work/merged/$file" "fuzz/corpus/$target/"
    kept=$((kept + 1))
done < <(cd "$work/merged" && find . -type f -printf '%s %f\n' | sort -n)
echo "fuzz/corpus/$target: $kept files, $(du -sb "fuzz/corpus/$target" | cut -f1) bytes"
