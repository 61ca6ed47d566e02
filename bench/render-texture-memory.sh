#!/usr/bin/env bash
# The renderer on maps that do not fit its cache: a grazing plane in four strips, each textured by
# one of footprint-bench texsys' 4096² float files (tiled, stored MIP levels: 4 × 341 MiB of
# texels), and three mirror spheres reflecting a 4096×2048 lat-long environment pyramid file
# (`footprint maketx --env`: its levels and polar caps, 470 MiB of texels), rendered by
# `footprint render --filter fa-rough` through the texture system with a small and a large
# --texture-memory-mb, and once more with the environment's source image instead, whose pyramids
# are then built and held whole. Prints per run the wall time, the process's peak RSS, the texture
# system's peak resident texels and tiles loaded, and whether the images are the same bytes. The
# render's time includes the tiles it reads; the whole run's, the loading (and building) before.
#
#   bash bench/render-texture-memory.sh [BUILD_DIR] [FILES_DIR] [SMALL_MB] [LARGE_MB]
#   (defaults: build, bench-out/texsys-files, 64, 4096; the textures are written by
#    `BUILD_DIR/footprint-bench texsys --dir FILES_DIR` when missing, the environment from
#    $ENV_SOURCE — any lat-long image, resized to 4096×2048 by oiiotool — or, without it, from
#    oiiotool's noise pattern)
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
if [ ! -f "$files/env-4096-env.exr" ]; then
    command -v oiiotool >/dev/null ||
        { echo "render-texture-memory: oiiotool is missing (scripts/install-deps.sh)" >&2; exit 1; }
    if [ -n "${ENV_SOURCE:-}" ]; then
        oiiotool "$ENV_SOURCE" --ch R,G,B --resize 4096x2048 -d float -o "$files/env-4096.exr"
    else
        oiiotool --pattern noise:type=uniform:min=0:max=4 4096x2048 3 -d float -o "$files/env-4096.exr"
    fi
    "$build/footprint" maketx "$files/env-4096.exr" --env latlong -o "$files/env-4096-env.exr" >/dev/null
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
for x in -2.5 0 2.5; do
    objects+=",{\"shape\": \"sphere\", \"center\": [$x, 1.2, -8], \"radius\": 1,
      \"material\": {\"base_color\": [1, 1, 1], \"diffuse\": 0, \"mirror\": 1}}"
done
for env in env-4096-env env-4096; do
    cat >"$out/$env.json" <<EOF
{"image": {"width": 1280, "height": 720},
 "camera": {"position": [0, 1, 2], "look_at": [0, 0.82, 0.98], "fov_y_deg": 40},
 "environment": {"file": "$files/$env.exr", "layout": "latlong"},
 "lights": [{"type": "directional", "direction": [0.3, -1, -0.5]}],
 "objects": [$objects]}
EOF
done

run() {  # cache_mb environment
    local json
    json=$( { /usr/bin/time -f '%e %M' "$build/footprint" render "$out/$2.json" -o "$out/$1-$2.exr" \
        --texture-memory-mb "$1" --json --quiet 2>"$out/$1-$2.rss"; } )
    python3 - "$1" "$2" "$json" "$(tail -1 "$out/$1-$2.rss")" <<'PY'
import json, sys
mb, env, summary = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
wall, rss_kb = float(sys.argv[4].split()[0]), int(sys.argv[4].split()[1])
print(f"--texture-memory-mb {mb:>5}, {env + '.exr':18}: render {summary['seconds']:5.2f} s, "
      f"whole run {wall:5.2f} s, "
      f"peak RSS {rss_kb / 1024:7.1f} MiB, peak texels {summary['texture_peak_bytes'] / 2**20:7.1f} MiB, "
      f"{summary['texture_tiles_loaded']} tiles loaded")
PY
}
run "$small" env-4096-env
run "$large" env-4096-env
run "$small" env-4096
if cmp -s "$out/$small-env-4096-env.exr" "$out/$large-env-4096-env.exr" &&
    cmp -s "$out/$small-env-4096-env.exr" "$out/$small-env-4096.exr"; then
    echo "images: the same bytes"
else
    echo "images: DIFFERENT" && exit 1
fi
