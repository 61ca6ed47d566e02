#!/usr/bin/env bash
# tests/farm/slurm_array_test.sh FOOTPRINT — scripts/farm/slurm-array.sh end to end, on a fake
# Slurm (fake-sbatch) that runs each array task as its own process, side by side: a render split
# into bands by the job array and merged by the dependent job must be the whole render's file byte
# for byte, and a sequence split into runs of frames the whole sequence's files; a failing task
# must leave no output (the merge never runs); bad arguments are refused.
set -euo pipefail
footprint=$(realpath "$1")
here=$(dirname "$(realpath "$0")")
script=$here/../../scripts/farm/slurm-array.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
export FOOTPRINT=$footprint SBATCH=$here/fake-sbatch FAKE_SLURM_DIR=$work/slurm
fail() { echo "FAIL: $*" >&2; exit 1; }
options=(--size 64 --filter fa-rough --threads 1)

# Bands: three tasks and the merge, against one process rendering the whole image.
"$footprint" render water "${options[@]}" --quiet -o whole.png
ids=$("$script" --tiles 3 -o split.png water -- "${options[@]}")
[[ $(wc -l <<<"$ids") == 2 ]] || fail "expected two job ids, got: $ids"
cmp whole.png split.png || fail "the merged bands differ from the whole render"
[[ ! -e split.png.tiles ]] || fail "the merge job left its bands behind"
grep -q -- "--dependency=afterok:$(head -1 <<<"$ids")" slurm/jobs || fail "merge not after the array"

# Frames: five frames, two per task (the last task one), against one sequence render.
mkdir whole split
"$footprint" render water "${options[@]}" --frames 5 --quiet -o whole/seq.png
"$script" --frames 5 --per-task 2 -o split/seq.png water -- "${options[@]}" >/dev/null
grep -q -- "--array=0-2" slurm/jobs || fail "five frames two per task should be three tasks"
for frame in 0000 0001 0002 0003 0004; do
    cmp "whole/seq_$frame.png" "split/seq_$frame.png" || fail "frame $frame differs"
done

# A task that fails (an unknown filter) cancels the merge: no output, no error hidden.
"$script" --tiles 2 -o broken.png water -- --filter nonsense >/dev/null
[[ ! -e broken.png ]] || fail "a merge ran after failed tasks"
tail -1 slurm/jobs | grep -q CANCELLED || fail "the merge was not cancelled"

# Bad arguments: one line naming the argument, exit 1, nothing submitted.
before=$(wc -l <slurm/jobs)
expect_refusal() {
    local message=$1
    shift
    if "$script" "$@" 2>err.txt; then fail "accepted: $*"; fi
    grep -qF -- "$message" err.txt || fail "'$*' said: $(cat err.txt), not: $message"
}
expect_refusal "--tiles 0: expected a whole number" --tiles 0 -o a.png water
expect_refusal "give one" --tiles 2 --frames 2 -o a.png water
expect_refusal "-o OUT is required" --tiles 2 water
expect_refusal "unknown option '--tile'" --tile 2 -o a.png water
[[ $(wc -l <slurm/jobs) == "$before" ]] || fail "a refused call submitted a job"
echo "slurm-array.sh: bands and frame runs match the whole render"
