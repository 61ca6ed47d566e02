#!/usr/bin/env bash
# The renderer on textures that do not fit its cache: a grazing plane in four strips, each textured
# by one of footprint-bench texsys' 4096² float files (tiled, stored MIP levels: 4 × 341 MiB of
# texels), rendered by `footprint render --filter fa-rough` through the texture system with a
# small and a large --texture-memory-mb. Prints per run the wall time, the process's peak RSS, the
# texture system's peak resident texels and tiles loaded, and whether the two images are the same
# bytes.
#
#   bash bench/render-texture-memory.sh [BUILD_DIR] [FILES_DIR] [SMALL_MB] [LARGE_MB]
#   (defaults: build, bench-out/texsys-files, 64, 4096; the files are written by
#    `BUILD_DIR/footprint-bench texsys --dir FILES_DIR` when missing)
set -euo pipefail
build=${1:-build}
files=${2:-bench-out/texsys-files}
small=${3:-64}
large=${4:-4096}
[ -x "$build/footprint" ] || { echo "render-texture-memory: $build/footprint is missing (make build)" >&2; exit 1; }
if [ ! -f "$files/texsys-4096-3.exr" ]; then
    mkdir -p "$files"
    "$build/footprint-bench" texsys --dir "$files" --textures 4 --frames 2 --threads 1 --no-oiio \
        --frame 64x36 --quiet >/dev/null
fi
files=$(cd "$files" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

objects=""
for i in 0 1 2 3; do
    x=$(( 4 * i - 6 ))
    objects+="${objects:+,}{\"shape\": \"plane\", \"center\": [$x, 0, -30], \"size\": [4, 64], \"uv_scale\": 0.25,
      \"material\": {\"base_color\": \"$files/texsys-4096-$i.exr\", \"specular\": 0.2}}"
done
cat >"$out/scene.json" <<EOF
{"image": {"width": 1280, "height": 720},
 "camera": {"position": [0, 1, 2], "look_at": [0, 0.82, 0.98], "fov_y_deg": 40},
 "lights": [{"type": "directional", "direction": [0.3, -1, -0.5]}],
 "objects": [$objects]}
EOF

run() {  # cache_mb
    local json
    json=$( { /usr/bin/time -f '%M' "$build/footprint" render "$out/scene.json" -o "$out/$1.exr" \
        --texture-memory-mb "$1" --json --quiet 2>"$out/$1.rss"; } )
    python3 - "$1" "$json" "$(tail -1 "$out/$1.rss")" <<'PY'
import json, sys
mb, summary, rss_kb = sys.argv[1], json.loads(sys.argv[2]), int(sys.argv[3])
print(f"--texture-memory-mb {mb:>5}: {summary['seconds']:6.2f} s, peak RSS {rss_kb / 1024:7.1f} MiB, "
      f"peak texels {summary['texture_peak_bytes'] / 2**20:7.1f} MiB, "
      f"{summary['texture_tiles_loaded']} tiles loaded")
PY
}
run "$small"
run "$large"
if cmp -s "$out/$small.exr" "$out/$large.exr"; then
    echo "images: the same bytes"
else
    echo "images: DIFFERENT" && exit 1
fi
