#!/usr/bin/env bash
# scripts/farm/slurm-array.sh — one footprint render split across a Slurm cluster: a job array with
# one task per band of rows (--tiles N) or per run of frames (--frames N), and, for bands, a merge
# job that starts once every task has succeeded (afterok). footprint schedules nothing itself.
#
#   scripts/farm/slurm-array.sh --tiles N  [--tile-dir DIR]    -o OUT.png SCENE [-- RENDER-OPTION...]
#   scripts/farm/slurm-array.sh --frames N [--per-task K]      -o OUT.png SCENE [-- RENDER-OPTION...]
#
# --tiles N: task I (1 … N) runs `footprint render SCENE --tile I/N -o DIR/tile-I.exr`; the merge
#   job runs `footprint merge DIR/tile-*.exr -o OUT` and then removes DIR (default OUT.tiles). OUT
#   is bit for bit the whole render (docs/farm.md).
# --frames N: task T renders frames T·K … T·K+K−1 of the N (`--frames A-B/N`, K = --per-task,
#   default 1), into the files a single `--frames N` run writes (OUT_0000.png, …).
# RENDER-OPTIONs (--filter, --spp, --size, --seed, --device …) go to every task unchanged.
#
# Environment: FOOTPRINT, the footprint binary as the compute nodes see it (default: `footprint`
# on their PATH); SBATCH, the submit command (default `sbatch`; tests use a fake). Every other
# sbatch setting comes from Slurm's own input variables (SBATCH_PARTITION, SBATCH_TIMELIMIT,
# SBATCH_ACCOUNT …) or #SBATCH-free flags in SBATCH_FLAGS, which is word-split. Prints the job ids
# (the array's, then the merge's) on stdout; exits 1 naming the argument at fault, or 1 if sbatch
# fails (nothing is left queued then).
set -euo pipefail

die() { echo "slurm-array.sh: $*" >&2; exit 1; }
usage() { sed -n '4,5p' "$0" | sed 's/^# *//' >&2; exit 2; }
positive() { [[ $2 =~ ^[1-9][0-9]*$ ]] || die "$1 $2: expected a whole number ≥ 1"; }

tiles="" frames="" per_task=1 tile_dir="" out="" scene=""
while (($#)); do
    case $1 in
    --tiles) positive "$1" "${2-}"; tiles=$2; shift 2 ;;
    --frames) positive "$1" "${2-}"; frames=$2; shift 2 ;;
    --per-task) positive "$1" "${2-}"; per_task=$2; shift 2 ;;
    --tile-dir) [[ -n ${2-} ]] || die "--tile-dir: expected a folder"; tile_dir=$2; shift 2 ;;
    -o | --out) [[ -n ${2-} ]] || die "$1: expected an output file"; out=$2; shift 2 ;;
    -h | --help) usage ;;
    --) shift; break ;;
    -*) die "unknown option '$1'" ;;
    *) [[ -z $scene ]] || die "a second scene '$1' (render options go after --)"; scene=$1; shift ;;
    esac
done
render_options=("$@")
[[ -n $scene ]] || usage
[[ -n $out ]] || die "-o OUT is required"
[[ -n $tiles || -n $frames ]] || die "give --tiles N or --frames N"
[[ -z $tiles || -z $frames ]] || die "--tiles and --frames are two ways to split: give one"
[[ -z $tile_dir || -n $tiles ]] || die "--tile-dir applies to --tiles only"
# The tasks run elsewhere, later, in the submit folder: absolute paths name the same files there.
out=$(realpath -m -- "$out")
[[ $scene == */* || $scene == *.json ]] && scene=$(realpath -m -- "$scene")
footprint=${FOOTPRINT:-footprint}
sbatch_cmd=${SBATCH:-sbatch}
read -r -a sbatch_flags <<<"${SBATCH_FLAGS:-}"

# Words quoted for the job's /bin/sh (sbatch --wrap), which knows no $'…' quoting.
quoted() {
    local words=() word
    for word; do words+=("'${word//\'/\'\\\'\'}'"); done
    echo "${words[*]}"
}
submit() {  # submit SBATCH-OPTION... -- COMMAND: prints the job id
    local options=() id
    while [[ $1 != -- ]]; do options+=("$1"); shift; done
    shift
    id=$("$sbatch_cmd" --parsable "${sbatch_flags[@]}" "${options[@]}" --wrap "$*") ||
        die "$sbatch_cmd failed (${options[*]})"
    echo "${id%%;*}"  # --parsable prints "id" or "id;cluster"
}

name=footprint-$(basename -- "${out%.*}")
if [[ -n $tiles ]]; then
    tile_dir=$(realpath -m -- "${tile_dir:-$out.tiles}")
    mkdir -p -- "$tile_dir"
    render=$(quoted "$footprint" render "$scene" "${render_options[@]}" --quiet)
    array=$(submit --job-name="$name" --array="1-$tiles" -- \
        "$render --tile \"\$SLURM_ARRAY_TASK_ID/$tiles\"" \
        "-o $(quoted "$tile_dir")/tile-\$SLURM_ARRAY_TASK_ID.exr")
    merge=$(quoted "$footprint" merge)
    merge_id=$(submit --job-name="$name-merge" --dependency="afterok:$array" --kill-on-invalid-dep=yes -- \
        "$merge $(quoted "$tile_dir")/tile-*.exr -o $(quoted "$out") --quiet &&" \
        "rm -r -- $(quoted "$tile_dir")") || {
        scancel "$array" 2>/dev/null || true
        exit 1
    }
    echo "$array"
    echo "$merge_id"
else
    tasks=$(((frames + per_task - 1) / per_task))
    render=$(quoted "$footprint" render "$scene" "${render_options[@]}" --quiet -o "$out")
    # Task T's frames; the last task may hold fewer.
    range="first=\$((SLURM_ARRAY_TASK_ID * $per_task));"
    range+=" last=\$((first + $per_task - 1 < $frames ? first + $per_task - 1 : $frames - 1));"
    submit --job-name="$name" --array="0-$((tasks - 1))" -- \
        "$range $render --frames \"\$first-\$last/$frames\""
fi
