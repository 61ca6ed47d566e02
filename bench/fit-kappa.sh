#!/usr/bin/env bash
# bench/fit-kappa.sh BUILD OUT [SCENE...] — fits κ, the scale of the environment footprint's
# roughness term (K = D Dᵀ + κ² K3, spec §2.6): fa-rough's interior RMSE against the 1024-spp
# reference for each κ, per scene (built-in demo names or scene files; default: the demos with a
# bump map or micro-roughness). The references are rendered once and cached in OUT/cache, so each
# further κ renders only the filter modes at 1 spp. Prints one row per scene and the κ of the
# smallest error; docs/performance.md has the figures.
set -euo pipefail
build=${1:?usage: bench/fit-kappa.sh BUILD OUT [SCENE...]}
out=${2:?usage: bench/fit-kappa.sh BUILD OUT [SCENE...]}
shift 2
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then scenes=(water bump_plate brushed_sphere); fi
kappas=(1 1.5 1.75 2 2.25 2.5 3)

printf '%-18s' scene
for k in "${kappas[@]}"; do printf ' %9s' "k=$k"; done
printf '  best\n'
for scene in "${scenes[@]}"; do
    printf '%-18s' "$(basename "$scene" .json)"
    best=""
    best_error=""
    for k in "${kappas[@]}"; do
        "$build/footprint" eval "$scene" --kappa "$k" --out "$out" --frames 0 --spp-list 1 \
            --filter-spp-list 1 --no-browser-check --quiet
        error=$(awk -F, '$2 == "fa-rough" { print $6 }' "$out/results.csv")
        printf ' %9.6f' "$error"
        if [ -z "$best" ] || awk -v a="$error" -v b="$best_error" 'BEGIN { exit !(a < b) }'; then
            best=$k
            best_error=$error
        fi
    done
    printf '  %s\n' "$best"
done
