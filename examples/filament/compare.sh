#!/usr/bin/env bash
# examples/filament/compare.sh — the in-engine comparison table: every built-in scene (and the
# FlightHelmet glTF where the data set has it) rendered with footprint's material, Filament's best
# practice and the supersampled truth (footprint-filament --compare), interior RMSE and mean FLIP
# against the truth, frame time in ms; then the contact sheet OUT_DIR/contact_sheet.png (one row
# per scene: footprint | filament | truth; needs oiiotool).
#   examples/filament/compare.sh [BUILD_DIR] [SIZE] [SUPERSAMPLE] [OUT_DIR]
# Defaults: build, 640x360, 8, out/filament. Runs under xvfb-run when no X display is set.
# The FlightHelmet: $FOOTPRINT_DATA/meshes/FlightHelmet/FlightHelmet.gltf (default data set:
# ../shared/data beside the repository), lit by the Venice sky; skipped when it is not there.
# The README's picture: compare.sh build 240x135 8 out/filament-sheet, then
#   cp out/filament-sheet/contact_sheet.png docs/images/filament_compare.png
set -euo pipefail
build=${1:-build} size=${2:-640x360} n=${3:-8} out=${4:-out/filament}
repo=$(cd "$(dirname "$0")/../.." && pwd)
data=${FOOTPRINT_DATA:-$repo/../shared/data}
scenes=(plate floor mirror)
names=(plate floor mirror)  # each scene's name in the table and its files' names
helmet=$data/meshes/FlightHelmet/FlightHelmet.gltf
if [[ -f "$helmet" ]]; then
    scenes+=("$helmet")
    names+=(FlightHelmet)
else
    echo "(no $helmet: the FlightHelmet row is left out)" >&2
fi
runner=()
[[ -z "${DISPLAY:-}" ]] && runner=(xvfb-run -a -s "-screen 0 64x64x24")
printf '%-12s %-10s %10s %10s %10s\n' scene material rmse flip frame_ms
for scene in "${scenes[@]}"; do
    "${runner[@]}" "$build/footprint-filament" "$scene" --compare --size "$size" --supersample "$n" -o "$out" \
        2>&1 | grep -v -e FEngine -e CircularBuffer  # Filament's banner goes to stdout
done
if command -v oiiotool >/dev/null; then
    sheets=()
    for name in "${names[@]}"; do sheets+=("$out/${name}_sheet.png"); done
    oiiotool "${sheets[@]}" --mosaic:pad=4 1x${#names[@]} -o "$out/contact_sheet.png"
    echo "contact sheet (footprint | filament | truth): $out/contact_sheet.png"
fi
