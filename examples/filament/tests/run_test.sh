#!/usr/bin/env bash
# examples/filament/tests/run_test.sh — footprint-filament's tests (examples/filament/CMakeLists.txt).
#
#   run_test.sh skip REASON                      Filament is missing: skip (77) naming why
#   run_test.sh CASE BINARY MATERIALS_DIR WORK   one case under xvfb-run
#
# Where Filament or an X server cannot be had the test skips with the reason (exit 77), unless
# FOOTPRINT_REQUIRE_FILAMENT or FOOTPRINT_REQUIRE_GPU is set (CI), where that is a failure.
set -uo pipefail

required() {
    for v in "${FOOTPRINT_REQUIRE_FILAMENT:-}" "${FOOTPRINT_REQUIRE_GPU:-}"; do
        [[ -n "$v" && "$v" != 0 ]] && return 0
    done
    return 1
}
skip() {
    if required; then
        echo "FAIL (FOOTPRINT_REQUIRE_FILAMENT/FOOTPRINT_REQUIRE_GPU is set): $1" >&2
        exit 1
    fi
    echo "SKIP: $1" >&2
    exit 77
}
fail() { echo "FAIL: $1" >&2; exit 1; }

case_name=$1
[[ "$case_name" == skip ]] && skip "$2"
binary=$2 materials=$3 work=$4/$case_name
gltf=$(cd "$(dirname "$0")" && pwd)/gltf  # the glTF test scenes (gltf/make_quad.py writes them)
rm -rf "$work" && mkdir -p "$work"

command -v xvfb-run >/dev/null || skip "xvfb-run (package xvfb) is not installed: no X server for Filament's OpenGL backend"
# xvfb-run -a picks a free display; the screen is unused (rendering goes to an offscreen target).
run() { xvfb-run -a -s "-screen 0 64x64x24" "$binary" "$@"; }
# Whether an X server starts at all (Xvfb can be installed yet fail in a sandbox).
xvfb-run -a -s "-screen 0 64x64x24" true 2>"$work/xvfb.log" || skip "xvfb-run cannot start an X server: $(tail -1 "$work/xvfb.log")"

# Runs the program expecting failure; its stderr must contain $1.
expect_error() {
    local needle=$1; shift
    if run "$@" >"$work/out.log" 2>"$work/err.log"; then fail "exit 0 for: $*"; fi
    grep -qF -- "$needle" "$work/err.log" || fail "stderr does not name '$needle': $(cat "$work/err.log")"
    grep -q "^footprint-filament: " "$work/err.log" || fail "no message, perhaps an abort: $(cat "$work/err.log")"
}

# A value of the --compare table: scene, material, column (3 RMSE, 4 FLIP).
table_value() { awk -v m="$2" -v c="$3" '$2 == m { print $c }' "$1"; }

case "$case_name" in
same-pixels-twice)
    # Two processes, the same arguments: the same pixels, bit for bit (the EXR files' bytes).
    for material in filament footprint; do
        [[ $material == footprint && ! -f "$materials/footprint.filamat" ]] && continue
        for i in 1 2; do
            run plate --material $material --size 96x54 --frames 2 -o "$work/$material-$i.exr" >/dev/null \
                || fail "render $material $i failed"
        done
        cmp "$work/$material-1.exr" "$work/$material-2.exr" || fail "$material: two renders differ"
    done
    for i in 1 2; do
        run plate --supersample 2 --size 48x27 -o "$work/truth-$i.exr" >/dev/null || fail "truth $i failed"
    done
    cmp "$work/truth-1.exr" "$work/truth-2.exr" || fail "truth: two renders differ"
    ;;
materials-compile)
    # The build compiled them with matc; each must also load into Filament and render a frame.
    for f in filament_best truth object_id; do
        [[ -s "$materials/$f.filamat" ]] || fail "$materials/$f.filamat was not built"
    done
    run mirror --material filament --size 32x18 --frames 1 -o "$work/mirror.png" >/dev/null || fail "filament material"
    run mirror --supersample 1 --size 32x18 -o "$work/mirror-truth.png" >/dev/null || fail "truth material"
    if [[ -f "$materials/footprint.filamat" ]]; then
        run mirror --material footprint --size 32x18 --frames 1 -o "$work/mirror-fp.png" >/dev/null \
            || fail "footprint material"
    fi
    ;;
missing-asset)
    expect_error "$work/nothere.hdr" plate --environment "$work/nothere.hdr" --material filament --size 32x18 -o "$work/x.png"
    mkdir -p "$work/assets"
    expect_error "$work/assets/normals/polyhaven_metal_plate_02_nor_gl_1k.jpg" \
        plate --assets "$work/assets" --material filament --size 32x18 -o "$work/x.png"
    expect_error "$work/nothere.gltf" "$work/nothere.gltf" --material filament --size 32x18 -o "$work/x.png"
    expect_error "unknown scene 'teapot'" teapot --material filament --size 32x18 -o "$work/x.png"
    ;;
bad-material)
    # A corrupt package, a truncated one and a missing one: each named, none reaches Filament.
    mkdir -p "$work/mats"
    cp "$materials"/*.filamat "$work/mats/"
    echo "not a material" >"$work/mats/filament_best.filamat"
    expect_error "$work/mats/filament_best.filamat" plate --materials "$work/mats" --material filament --size 32x18 -o "$work/x.png"
    head -c 5000 "$materials/truth.filamat" >"$work/mats/truth.filamat"
    cp "$materials/filament_best.filamat" "$work/mats/"
    expect_error "$work/mats/truth.filamat" plate --materials "$work/mats" --material filament --size 32x18 -o "$work/x.png"
    rm "$work/mats/truth.filamat"
    expect_error "$work/mats/truth.filamat" plate --materials "$work/mats" --material filament --size 32x18 -o "$work/x.png"
    ;;
orientation)
    # The environment in footprint's orientation: a sky coloured by direction (0.5 + 0.5·d by
    # docs/method.md's lat-long addressing) over a flat mirror; every material and the truth must
    # show, per pixel, the colour of the view ray's direction (sky) or of its reflection (mirror).
    run sky --check-orientation --size 96x54 -o "$work" | tee "$work/table.txt" || fail "orientation (see the table)"
    ;;
closer-plate|closer-floor)
    # footprint's material is closer to the in-engine truth than Filament's best practice, by
    # interior RMSE and by mean FLIP.
    scene=${case_name#closer-}
    run "$scene" --compare --size 320x180 --supersample 6 --frames 2 >"$work/table.txt" || fail "--compare failed"
    cat "$work/table.txt"
    fp_rmse=$(table_value "$work/table.txt" footprint 3) fi_rmse=$(table_value "$work/table.txt" filament 3)
    fp_flip=$(table_value "$work/table.txt" footprint 4) fi_flip=$(table_value "$work/table.txt" filament 4)
    # Where it fails on the floor, see examples/filament/README.md ("Why footprint loses the floor
    # on llvmpipe"): llvmpipe's 16x anisotropic sampler is an EWA filter, not a GPU's probe rule.
    awk -v a="$fp_rmse" -v b="$fi_rmse" 'BEGIN { exit !(a < b) }' || fail "RMSE: footprint $fp_rmse, filament $fi_rmse"
    awk -v a="$fp_flip" -v b="$fi_flip" 'BEGIN { exit !(a < b) }' || fail "FLIP: footprint $fp_flip, filament $fi_flip"
    ;;
gltf-same-pixels-twice)
    # A glTF scene (tests/gltf/quad.gltf: base colour, normal and metallic-roughness maps, a
    # camera) with each material: two processes, the same EXR bytes. (The truth goes through the
    # same scene code; same-pixels-twice checks its determinism on the plate.)
    for material in filament footprint; do
        [[ $material == footprint && ! -f "$materials/footprint.filamat" ]] && continue
        for i in 1 2; do
            run "$gltf/quad.gltf" --material $material --size 96x54 --frames 2 -o "$work/$material-$i.exr" \
                >/dev/null || fail "render $material $i failed"
        done
        cmp "$work/$material-1.exr" "$work/$material-2.exr" || fail "$material: two renders differ"
    done
    ;;
gltf-missing-texture)
    # The scene without its texture files: the first one named, exit 1, no abort; a file that is
    # not glTF is named too.
    cp "$gltf/quad.gltf" "$work/"
    expect_error "$work/quad_basecolor.png" "$work/quad.gltf" --material footprint --size 32x18 -o "$work/x.png"
    cp "$gltf"/quad_basecolor.png "$work/"
    expect_error "$work/quad_normal.png" "$work/quad.gltf" --material filament --size 32x18 -o "$work/x.png"
    echo "not json" >"$work/broken.gltf"
    expect_error "$work/broken.gltf" "$work/broken.gltf" --material filament --size 32x18 -o "$work/x.png"
    ;;
gltf-camera-and-framing)
    # quad.gltf's camera looks straight down at the quad from 1 unit: the quad fills the view, so
    # every pixel is interior. quad_nocamera.gltf has no camera: the framing view must show the quad
    # (a part of the pixels interior) and the sky around it (not all of them).
    interior() { sed -n 's/^# .*: interior \([0-9.]*\) % of the pixels$/\1/p' "$1"; }
    run "$gltf/quad.gltf" --compare --size 64x36 --supersample 2 --frames 1 >"$work/camera.txt" \
        || fail "--compare with the camera failed"
    cat "$work/camera.txt"
    camera=$(interior "$work/camera.txt")
    awk -v a="$camera" 'BEGIN { exit !(a == 100) }' || fail "the glTF's camera: interior $camera %, not 100 %"
    run "$gltf/quad_nocamera.gltf" --compare --size 64x36 --supersample 2 --frames 1 >"$work/framing.txt" \
        || fail "--compare without a camera failed"
    cat "$work/framing.txt"
    framed=$(interior "$work/framing.txt")
    awk -v a="$framed" 'BEGIN { exit !(a > 2 && a < 100) }' || fail "the framing view: interior $framed %"
    ;;
*) fail "unknown case '$case_name'" ;;
esac
echo "PASS: $case_name"
