#!/usr/bin/env bash
# bench/oiio-testtex.sh — OpenImageIO's own texture tests judge footprint's OIIO::TextureSystem
# adapter (docs/oiio-testtex.md). From an OpenImageIO source checkout at tag v2.4.7.1 it extracts
# src/testtex/testtex.cpp and the testsuite's texture-* tests (nothing of OpenImageIO's is kept in
# this repository), builds testtex twice — as is against OpenImageIO, and with the lines that create
# and destroy the texture system switched to footprint::oiio::create_texture_system() and
# destroy_texture_system() against footprint's installed CMake package — and runs every 2D
# texture-filtering test with each, through the testsuite's own runtest.py and its idiff
# thresholds. Prints a markdown table and writes it to --output (default $OUT_DIR/testtex.md,
# OUT_DIR defaulting to the repository's bench-out/):
#   group A, tests whose values OpenImageIO's semantics fix: does each binary pass the suite's
#            idiff comparison against OpenImageIO's reference image (max error, RMS, PSNR);
#   group B, tests where footprint filters differently by design: RMS error and PSNR of each
#            binary's image against two supersampled references (stock testtex, the test's own
#            arguments, --supersample N (8) times the resolution, one bilinear point sample of
#            MIP level 0 per pixel, filtered back down by a box — oiiotool — and by a Gaussian of
#            σ = ½ pixel — gaussian_downsample.cpp), and the suite's verdict.
#
#   bench/oiio-testtex.sh [options] OIIO_CHECKOUT
#     OIIO_CHECKOUT      an OpenImageIO clone: a work tree or a (bare) git directory with the tag
#     --images DIR       an OpenImageIO-images clone (work tree, git directory, or a folder holding
#                        miplevels.tx), for texture-res, -filtersize and -maxres; without it those
#                        are listed as "input missing"
#     --output FILE      where the markdown goes (default: $OUT_DIR/testtex.md, or bench-out/)
#     --build DIR        footprint's build folder, installed into the work folder (default: build)
#     --prefix DIR       an installed footprint package to use instead of --build
#     --work DIR         keep the work folder (sources, binaries, every image) in DIR; a later run
#                        with the same DIR rebuilds testtex incrementally (default: a temporary
#                        folder, removed at exit)
#     --tests "A B ..."  only these tests (names without "texture-")
#     --supersample N    the reference's samples per pixel along each axis (default 8)
#     --jobs N           compile jobs (default 2)
#
# Needs what `make build` installs on Debian 12 (scripts/install-deps.sh): a C++20 compiler,
# cmake, ninja, libopenimageio-dev 2.4.7 and openimageio-tools (oiiotool, maketx, idiff), python3
# (runtest.py) and git; and footprint built (`make build`, or --prefix to an installed package).
# Runs in about 10–15 minutes on two cores, most of it building testtex and the references.
set -euo pipefail

readonly TAG=v2.4.7.1
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/.." && pwd)

# Which tests are run, and how they are judged.
readonly GROUP_A="fill missing udim udim2 gray flipt derivs pointsample res width0blur mip-nomip"
readonly GROUP_B="wrapfill mip-trilinear mip-onelevel interp-closest interp-bilinear \
interp-bicubic filtersize skinny fat blurtube uint8 half uint16 overscan crop cropover maxres"
declare -A SKIPPED=(
    [texture3d]="3D volume lookups (an OpenVDB file): delegated to OpenImageIO, not 2D filtering"
    [icwrite]="tests ImageCache::add_tile() on generated tiles: the image cache, not filtering"
    [gettexels]="get_texels() returns raw texels: delegated to OpenImageIO, not filtering"
    [stats]="prints OpenImageIO's cache statistics (text): not filtering"
    [filtersize-stochastic]="stochastic mip mode: delegated to OpenImageIO"
    [levels-stochaniso]="stochastic mip mode: delegated to OpenImageIO"
    [levels-stochmip]="stochastic mip mode: delegated to OpenImageIO"
    [mip-stochasticaniso]="stochastic mip mode: delegated to OpenImageIO"
    [mip-stochastictrilinear]="stochastic mip mode: delegated to OpenImageIO"
)
readonly PYTHON_TEXTURESYS_REASON="not a texture-* test: OpenImageIO's Python binding creates its \
own TextureSystem, with no hook to put footprint behind it"
# Group-B tests without a fair supersampled reference, and why.
declare -A NO_REFERENCE=(
    [filtersize]="none: miplevels.tx's levels are different images on purpose (the test checks which level is read)"
    [maxres]="none: miplevels.tx's levels are different images on purpose, and max_mip_res drops the finer ones"
)
readonly BLUR_REASON="none: blur > 0 (its kernel is each implementation's own)"

say() { printf '[oiio-testtex] %s\n' "$*" >&2; }
die() {
    printf 'oiio-testtex: %s\n' "$*" >&2
    exit 1
}
usage() {
    sed -n '/^#   bench\/oiio-testtex.sh/,/^#     --jobs/p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

# ---- Arguments.
oiio=""
images=""
output="${OUT_DIR:-$repo/bench-out}/testtex.md"
build_dir="$repo/build"
prefix=""
work=""
only=""
supersample=8
jobs=2
while [ $# -gt 0 ]; do
    case "$1" in
        --images) images=${2:?--images needs a folder}; shift 2 ;;
        --output) output=${2:?--output needs a file}; shift 2 ;;
        --build) build_dir=${2:?--build needs a folder}; shift 2 ;;
        --prefix) prefix=${2:?--prefix needs a folder}; shift 2 ;;
        --work) work=${2:?--work needs a folder}; shift 2 ;;
        --tests) only=${2:?--tests needs a list}; shift 2 ;;
        --supersample) supersample=${2:?--supersample needs a number}; shift 2 ;;
        --jobs | -j) jobs=${2:?--jobs needs a number}; shift 2 ;;
        -h | --help) usage ;;
        -*) die "unknown option '$1' (--help lists them)" ;;
        *)
            [ -z "$oiio" ] || die "one OpenImageIO checkout only ('$oiio', then '$1')"
            oiio=$1
            shift
            ;;
    esac
done
[ -n "$oiio" ] || { echo "oiio-testtex: the OpenImageIO checkout is missing" >&2; usage; }
[[ "$supersample" =~ ^[1-9][0-9]?$ ]] || die "--supersample '$supersample' is not a number from 1 to 99"
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "--jobs '$jobs' is not a positive number"

for tool in git cmake python3 oiiotool maketx idiff; do
    command -v "$tool" >/dev/null || die "$tool is missing (scripts/install-deps.sh installs it)"
done
[ -d "$oiio" ] || die "'$oiio' is not a folder (an OpenImageIO work tree or git directory)"
git -C "$oiio" rev-parse --git-dir >/dev/null 2>&1 ||
    die "'$oiio' is not a git repository (an OpenImageIO clone is needed)"
git -C "$oiio" rev-parse -q --verify "refs/tags/$TAG^{commit}" >/dev/null ||
    die "'$oiio' has no tag $TAG (git -C '$oiio' fetch --tags; the installed OpenImageIO is 2.4.7)"
for file in src/testtex/testtex.cpp testsuite/runtest.py; do
    git -C "$oiio" cat-file -e "$TAG:$file" 2>/dev/null ||
        die "'$oiio' at $TAG has no $file: not OpenImageIO?"
done
installed=$(oiiotool --version 2>/dev/null | head -n 1 || true)
case "$installed" in
    *2.4.7*) ;;
    *) say "warning: oiiotool reports '$installed', not OpenImageIO 2.4.7: the tag's tests may not fit" ;;
esac
if [ -z "$prefix" ]; then
    [ -f "$build_dir/cmake_install.cmake" ] ||
        die "'$build_dir' is not a footprint build folder (run make build, or give --prefix)"
else
    [ -f "$prefix/lib/cmake/footprint/footprintConfig.cmake" ] ||
        die "'$prefix' holds no footprint package (lib/cmake/footprint/footprintConfig.cmake)"
fi

# ---- The work folder: a temporary one, or --work (ours: empty, or marked by an earlier run).
temporary=""
partial=""
cleanup() {
    [ -z "$partial" ] || rm -f "$partial"
    if [ -n "$temporary" ]; then rm -rf "$work"; fi
}
trap cleanup EXIT
if [ -z "$work" ]; then
    work=$(mktemp -d "${TMPDIR:-/tmp}/oiio-testtex.XXXXXX")
    temporary=1
else
    mkdir -p "$work"
    if [ -n "$(ls -A "$work")" ] && [ ! -f "$work/.oiio-testtex" ]; then
        die "--work '$work' is not empty and not an earlier run's work folder"
    fi
    work=$(cd "$work" && pwd)
    rm -rf "$work/oiio" "$work/testtex" "$work/images" "$work/stock" "$work/footprint" \
        "$work/reference" "$work/prefix" "$work/rows"
fi
touch "$work/.oiio-testtex"
mkdir -p "$(dirname "$output")"
output=$(cd "$(dirname "$output")" && pwd)/$(basename "$output")
partial="$output.partial.$$"

# ---- OpenImageIO's files at the tag: testtex.cpp, runtest.py, the texture tests and their inputs.
say "extracting $TAG's testtex.cpp and testsuite/texture-* from $oiio"
mapfile -t all_tests < <(git -C "$oiio" ls-tree --name-only "$TAG" testsuite/ |
    sed -n 's|^testsuite/texture-||p')
[ ${#all_tests[@]} -gt 0 ] || die "'$oiio' at $TAG has no testsuite/texture-* tests"
for t in $only; do
    [[ " ${all_tests[*]} " == *" $t "* ]] || die "--tests: $TAG has no testsuite/texture-$t"
done
mkdir -p "$work/oiio"
wanted=(src/testtex/testtex.cpp testsuite/runtest.py testsuite/common/grid.tif
    testsuite/common/textures testsuite/common/OpenColorIO src/fonts/Droid_Sans
    "${all_tests[@]/#/testsuite/texture-}")
if ! git -C "$oiio" archive "$TAG" "${wanted[@]}" 2>"$work/archive.log" | tar -x -C "$work/oiio"; then
    cat "$work/archive.log" >&2
    die "could not extract $TAG's files from '$oiio'"
fi

mkdir -p "$work/images"
if [ -n "$images" ]; then
    [ -d "$images" ] || die "--images '$images' is not a folder"
    if [ -f "$images/miplevels.tx" ]; then
        cp "$images/miplevels.tx" "$work/images/"
    elif git -C "$images" rev-parse --git-dir >/dev/null 2>&1 &&
        git -C "$images" cat-file -e HEAD:miplevels.tx 2>/dev/null; then
        git -C "$images" archive HEAD miplevels.tx 2>>"$work/archive.log" | tar -x -C "$work/images" ||
            die "could not extract miplevels.tx from '$images'"
    else
        die "--images '$images' has no miplevels.tx (an OpenImageIO-images clone is needed)"
    fi
fi

# ---- testtex.cpp, patched with sed: built outside OpenImageIO's tree, then switched to footprint.
# Each edit must match exactly once, or the tag's file is not the one this script knows.
src="$work/testtex"
mkdir -p "$src"
orig="$work/oiio/src/testtex/testtex.cpp"
expect_once() { # FILE REGEX WHAT
    local n
    n=$(grep -c -- "$2" "$1" || true)
    [ "$n" = 1 ] || die "testtex.cpp at $TAG: expected one $3, found $n (the script knows $TAG's file)"
}
expect_once "$orig" '^#include "../libtexture/imagecache_pvt.h"$' 'OpenImageIO-internal include'
expect_once "$orig" '^test_hash()$' 'test_hash() definition'
expect_once "$orig" '^    texsys = TextureSystem::create();$' 'TextureSystem::create() line'
expect_once "$orig" '^    TextureSystem::destroy(texsys);$' 'TextureSystem::destroy() line'
# 1. Outside OpenImageIO's tree: its private imagecache_pvt.h is not installed. testtex uses it for
#    --testhash alone (ImageCacheFile, TileID), whose body becomes a message; bjhash, which the
#    stochastic modes use, comes from the public OpenImageIO/hash.h.
sed -e 's|^#include "../libtexture/imagecache_pvt.h"$|#include <OpenImageIO/hash.h>  // footprint harness: was "../libtexture/imagecache_pvt.h"|' \
    -e '/^test_hash()$/,/^}$/c\
test_hash()\
{\
    // footprint harness: the tile-hash test needs OpenImageIO-internal headers\
    Strutil::print(std::cerr, "testtex: --testhash is not built outside OpenImageIO\\n");\
}' "$orig" >"$src/testtex.cpp"
# 2. footprint: the texture system is created and destroyed by footprint::oiio, nothing else.
sed -e 's|^\(#include <OpenImageIO/hash.h>.*\)$|\1\n#include <footprint/oiio/texture_system.h>  // footprint harness|' \
    -e 's|^    texsys = TextureSystem::create();$|    texsys = footprint::oiio::create_texture_system();  // footprint harness|' \
    -e 's|^    TextureSystem::destroy(texsys);$|    footprint::oiio::destroy_texture_system(texsys);  // footprint harness|' \
    "$src/testtex.cpp" >"$src/testtex-footprint.cpp"
diff "$orig" "$src/testtex.cpp" >"$src/build-changes.diff" || true
diff "$src/testtex.cpp" "$src/testtex-footprint.cpp" >"$src/footprint-changes.diff" || true
[ "$(grep -c '^>' "$src/footprint-changes.diff")" = 3 ] || die "the footprint edits did not apply"

# ---- footprint's package and the two binaries.
if [ -z "$prefix" ]; then
    prefix="$work/prefix"
    say "installing footprint from $build_dir into $prefix"
    for attempt in 1 2 3; do
        if cmake --install "$build_dir" --prefix "$prefix" >"$work/install.log" 2>&1; then break; fi
        if [ "$attempt" = 3 ]; then
            cat "$work/install.log" >&2
            die "cmake --install '$build_dir' failed"
        fi
        say "install failed (is the build being rebuilt?); retrying in 30 s"
        sleep 30
    done
fi
prefix=$(cd "$prefix" && pwd)
say "building testtex and testtex-footprint (a few minutes)"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if ! cmake -S "$here/oiio-testtex" -B "$work/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
    -DTESTTEX_SOURCE_DIR="$src" -DCMAKE_PREFIX_PATH="$prefix" >"$work/configure.log" 2>&1; then
    cat "$work/configure.log" >&2
    die "configuring bench/oiio-testtex failed"
fi
if ! cmake --build "$work/build" -j "$jobs" >"$work/build.log" 2>&1; then
    tail -n 40 "$work/build.log" >&2
    die "building testtex failed ($work/build.log)"
fi

# ---- Running the tests: one tree per binary, laid out as OpenImageIO's build/testsuite, with
# bin/ holding testtex (a wrapper that records its arguments) and the installed tools. oiiotool's
# -text (the UDIM tests) looks for OpenImageIO's default font, DroidSans, which Debian's package
# leaves out: OPENIMAGEIO_FONTS points at the tag's src/fonts.
setup_tree() { # FLAVOUR BINARY
    local root="$work/$1"
    mkdir -p "$root/bin" "$root/testsuite"
    cat >"$root/bin/testtex" <<EOF
#!/usr/bin/env bash
printf '%q ' "\$@" >>.testtex-calls
printf '\n' >>.testtex-calls
exec "$2" "\$@"
EOF
    chmod +x "$root/bin/testtex"
    for tool in oiiotool maketx idiff; do ln -s "$(command -v "$tool")" "$root/bin/$tool"; done
    ln -s "$work/oiio/testsuite/common" "$root/testsuite/common"
    ln -s "$work/images" "$root/testsuite/oiio-images"
}
setup_tree stock "$work/build/testtex"
setup_tree footprint "$work/build/testtex-footprint"

run_suite_test() { # FLAVOUR TEST: runtest.py as OpenImageIO's ctest runs it; its exit status
    local dir="$work/$1/testsuite/texture-$2"
    mkdir -p "$dir"
    (
        cd "$dir"
        env -u CI -u DEBUG -u OIIO_TESTSUITE_CUR \
            OIIO_TESTSUITE_ROOT="$work/oiio/testsuite" \
            OIIO_TESTSUITE_SRC="$work/oiio/testsuite/texture-$2" \
            OIIO_TESTSUITE_IMAGEDIR="$work/$1/testsuite/oiio-images" \
            OCIO=../common/OpenColorIO/nuke-default/config.ocio \
            OIIO_TESTSUITE_OCIOCONFIG=../common/OpenColorIO/nuke-default/config.ocio \
            OPENIMAGEIO_FONTS="$work/oiio/src/fonts" \
            timeout 1200 python3 "$work/oiio/testsuite/runtest.py" "$dir" >runtest.log 2>&1
    )
}

# idiff's report for IMAGE, the last one in FILE (runtest.py appends the suite's comparisons to
# out.txt): "reference<TAB>verdict<TAB>max<TAB>rms<TAB>psnr"; identical images print no figures.
idiff_report() { # FILE [IMAGE]
    awk -v want="${2:-}" '
        /^Comparing "/ {
            split($0, q, "\"")
            inside = (want == "" || q[2] == want)
            if (inside) { ref = q[4]; max = "0"; rms = "0"; psnr = "inf" }
            next
        }
        inside && /^ *RMS error =/ { rms = $4 }
        inside && /^ *Peak SNR =/ { psnr = $4 }
        inside && /^ *Max error/ { max = $4 }
        inside && /^(PASS|FAILURE|WARNING)/ {
            found = ref "\t" $1 "\t" max "\t" rms "\t" psnr
            inside = 0
        }
        END { if (found != "") print found }' "$1"
}
# The images the suite compared, in order (from out.txt's idiff reports).
compared_images() { # OUT_TXT
    awk '/^Comparing "/ { split($0, q, "\""); if (!seen[q[2]]++) print q[2] }' "$1"
}
# Two images' figures: "max<TAB>rms<TAB>psnr".
compare() { # A B
    local report
    report=$( (idiff -a "$1" "$2" || true) 2>&1)
    printf '%s\n' "$report" | idiff_report /dev/stdin | cut -f 3-5
}
fmt_num() { # VALUE: 4 significant digits
    case "$1" in "" | inf | nan | -*) printf '%s' "${1:-?}" ;; *) printf '%.4g' "$1" ;; esac
}
verdict_word() { # idiff's verdict → runtest.py's: a warning fails the test too
    case "$1" in
        PASS) printf 'PASS' ;;
        WARNING) printf 'FAIL (warning)' ;;
        FAILURE) printf 'FAIL' ;;
        *) printf '%s' "${1:-no image}" ;;
    esac
}
# The suite's thresholds for TEST: runtest.py's defaults, those run.py sets, and the --fail of an
# idiff run.py calls itself (texture-res).
thresholds() { # TEST
    local run="$work/oiio/testsuite/texture-$1/run.py" fail=0.004 percent=0.02 hard=0.012 name value
    while read -r name value; do
        case "$name" in
            failthresh) fail=$value ;;
            failpercent) percent=$value ;;
            hardfail) hard=$value ;;
        esac
    done < <(sed -n 's/^\(failthresh\|failpercent\|hardfail\) *= *\([0-9.e-]*\).*/\1 \2/p' "$run")
    value=$(grep -v '^ *#' "$run" | grep -o -- '--fail [0-9.]*' | tail -n 1 | cut -d' ' -f2 || true)
    [ -z "$value" ] || fail=$value
    printf '%s / %s%% / %s' "$fail" "$percent" "$hard"
}

# A test's testtex call that wrote IMAGE, from the wrapper's record: prints the arguments
# (shell-quoted, as recorded), or nothing.
call_for() { # DIR IMAGE
    local line out i
    [ -f "$1/.testtex-calls" ] || return 0
    while IFS= read -r line; do
        local -a args
        eval "args=($line)"
        out=out.exr
        for ((i = 0; i < ${#args[@]}; i++)); do
            [ "${args[i]}" = -o ] && out=${args[i + 1]:-}
        done
        [ "$out" = "$2" ] && { printf '%s\n' "$line"; return 0; }
    done <"$1/.testtex-calls"
}
# The supersampled references for IMAGE of TEST: the recorded call re-run by stock testtex in the
# test's folder (its inputs), at N× the resolution, MIP level 0 only (--mipmode 1), one bilinear
# point sample per pixel (--interpmode 1; width and blur 0), then filtered back to one pixel in N×N
# two ways: the box (the mean of the pixel's N×N samples: oiiotool) into IMAGE.box.exr, and a
# Gaussian of σ = ½ pixel cut at 4σ (gaussian_downsample) into IMAGE.gaussian.exr.
make_references() { # TEST IMAGE
    local dir="$work/stock/testsuite/texture-$1" line xres=512 yres=512 i
    line=$(call_for "$dir" "$2")
    [ -n "$line" ] || return 1
    local -a args
    eval "args=($line)"
    for ((i = 0; i < ${#args[@]}; i++)); do
        case "${args[i]}" in -res | --res) xres=${args[i + 1]}; yres=${args[i + 2]} ;; esac
    done
    local ref="$work/reference/texture-$1"
    mkdir -p "$ref"
    (cd "$dir" && "$work/build/testtex" "${args[@]}" --res $((xres * supersample)) \
        $((yres * supersample)) --mipmode 1 --interpmode 1 --width 0 --blur 0 -d float \
        -o "$ref/$2.supersampled.exr" >"$ref/$2.log" 2>&1) || return 1
    oiiotool "$ref/$2.supersampled.exr" --resize:filter=box "${xres}x${yres}" -d float \
        -o "$ref/$2.box.exr" >>"$ref/$2.log" 2>&1 || return 1
    "$work/build/gaussian_downsample" "$supersample" "$ref/$2.supersampled.exr" \
        "$ref/$2.gaussian.exr" >>"$ref/$2.log" 2>&1 || return 1
    rm -f "$ref/$2.supersampled.exr"
}
# "RMS / PSNR dB" of IMAGE against REFERENCE.
error_cell() { # IMAGE REFERENCE
    local rms psnr
    IFS=$'\t' read -r _ rms psnr < <(compare "$1" "$2") || true
    printf '%s / %s dB' "$(fmt_num "${rms:-}")" "$(fmt_num "${psnr:-}")"
}

# ---- Which tests run.
selected() { [ -z "$only" ] || [[ " $only " == *" $1 "* ]]; }
needs_images() { grep -q 'OIIO_TESTSUITE_IMAGEDIR\|oiio-images' "$work/oiio/testsuite/texture-$1/run.py"; }

rows="$work/rows"
mkdir -p "$rows"
: >"$rows/a"
: >"$rows/b"
: >"$rows/skipped"
for t in "${all_tests[@]}"; do
    selected "$t" || continue
    group=""
    [[ " $GROUP_A " == *" $t "* ]] && group=a
    [[ " $GROUP_B " == *" $t "* ]] && group=b
    if [ -z "$group" ]; then
        printf '| texture-%s | %s |\n' "$t" "${SKIPPED[$t]:-not classified by this script: not run}" >>"$rows/skipped"
        continue
    fi
    if needs_images "$t" && [ ! -f "$work/images/miplevels.tx" ]; then
        if [ $group = a ]; then
            printf '| texture-%s | — | %s | input missing: miplevels.tx (--images) | — | input missing | — |\n' \
                "$t" "$(thresholds "$t")" >>"$rows/a"
        else
            printf '| texture-%s | — | input missing: miplevels.tx (--images) | — | — | — | — | — |\n' "$t" >>"$rows/b"
        fi
        continue
    fi
    say "texture-$t"
    status_stock=0 status_fp=0
    run_suite_test stock "$t" || status_stock=$?
    run_suite_test footprint "$t" || status_fp=$?
    ds="$work/stock/testsuite/texture-$t" dfp="$work/footprint/testsuite/texture-$t"
    mapfile -t imgs < <(compared_images "$ds/out.txt")
    for img in "${imgs[@]}"; do
        IFS=$'\t' read -r _ v_s max_s rms_s psnr_s < <(idiff_report "$ds/out.txt" "$img") || true
        IFS=$'\t' read -r _ v_f max_f rms_f psnr_f < <(idiff_report "$dfp/out.txt" "$img") || true
        same=""
        if [ -f "$ds/$img" ] && [ -f "$dfp/$img" ]; then
            IFS=$'\t' read -r max_sf _ < <(compare "$ds/$img" "$dfp/$img") || true
            [ "${max_sf:-}" = 0 ] && same=" (= stock)"
        fi
        if [ $group = a ]; then
            printf '| texture-%s | %s | %s | %s | %s / %s / %s | %s%s | %s / %s / %s |\n' "$t" "$img" \
                "$(thresholds "$t")" "$(verdict_word "${v_s:-}")" "$(fmt_num "${max_s:-}")" \
                "$(fmt_num "${rms_s:-}")" "$(fmt_num "${psnr_s:-}")" "$(verdict_word "${v_f:-}")" \
                "$same" "$(fmt_num "${max_f:-}")" "$(fmt_num "${rms_f:-}")" "$(fmt_num "${psnr_f:-}")" \
                >>"$rows/a"
            continue
        fi
        reason=${NO_REFERENCE[$t]:-}
        [ "$t" = blurtube ] && [[ "$img" != *-0.00.tif ]] && reason=$BLUR_REASON
        suite="$(verdict_word "${v_s:-}") / $(verdict_word "${v_f:-}")$same"
        if [ -n "$reason" ]; then
            printf '| texture-%s | %s | %s | — | — | — | — | %s |\n' "$t" "$img" "$reason" "$suite" >>"$rows/b"
            continue
        fi
        if ! make_references "$t" "$img"; then
            printf '| texture-%s | %s | failed (%s) | — | — | — | — | %s |\n' "$t" "$img" \
                "reference/texture-$t/$img.log in the work folder" "$suite" >>"$rows/b"
            continue
        fi
        box="$work/reference/texture-$t/$img.box.exr" gauss="$work/reference/texture-$t/$img.gaussian.exr"
        printf '| texture-%s | %s | %d×%d point samples | %s | %s | %s | %s | %s |\n' "$t" "$img" \
            "$supersample" "$supersample" "$(error_cell "$ds/$img" "$box")" \
            "$(error_cell "$dfp/$img" "$box")" "$(error_cell "$ds/$img" "$gauss")" \
            "$(error_cell "$dfp/$img" "$gauss")" "$suite" >>"$rows/b"
    done
    # What the image rows do not show: a text output, or a command that failed.
    for flavour in stock footprint; do
        log="$work/$flavour/testsuite/texture-$t/runtest.log"
        while read -r word name _; do
            [[ "$name" == *.txt ]] || continue
            printf '%s %s\n' "$flavour" "$word" >>"$rows/text-$t-$name"
        done < <(grep -E '^(PASS:|FAIL) ' "$log" | sed 's/^PASS:/PASS/')
        if grep -q '^#### Error: this command failed' "$log"; then
            printf '%s\n' "$flavour" >>"$rows/cmdfail-$t"
        fi
    done
    for f in "$rows"/text-"$t"-*; do
        [ -f "$f" ] || continue
        name=${f#"$rows/text-$t-"}
        vs=$(awk '$1 == "stock" { print $2 }' "$f") vf=$(awk '$1 == "footprint" { print $2 }' "$f")
        if [ $group = a ]; then
            printf '| texture-%s | %s (text) | identical text | %s | — | %s | — |\n' "$t" "$name" \
                "${vs:-?}" "${vf:-?}" >>"$rows/a"
        else
            printf '| texture-%s | %s (text) | — | — | — | — | — | %s / %s |\n' "$t" "$name" \
                "${vs:-?}" "${vf:-?}" >>"$rows/b"
        fi
    done
    if [ -f "$rows/cmdfail-$t" ]; then
        printf -- '- texture-%s: a command of run.py exited non-zero with %s (runtest.py fails the test).\n' \
            "$t" "$(paste -sd' ' "$rows/cmdfail-$t" | sed 's/ / and /')" >>"$rows/notes"
    fi
    printf '%s %s %s\n' "$t" "$status_stock" "$status_fp" >>"$rows/status"
done
printf '| python-texturesys | %s |\n' "$PYTHON_TEXTURESYS_REASON" >>"$rows/skipped"

# ---- The table.
{
    cat <<EOF
# OpenImageIO $TAG texture tests: stock testtex and footprint behind OIIO::TextureSystem

Made by \`bench/oiio-testtex.sh\` (docs/oiio-testtex.md explains every column); references
supersampled ${supersample}×${supersample}. "stock" is testtex built against OpenImageIO; "footprint"
is the same testtex with the texture system made by \`footprint::oiio::create_texture_system()\`.
"(= stock)": the two images are identical.

## Group A: fixed by OpenImageIO's semantics (the suite's idiff against its reference image)

| test | image | fail / failpercent / hardfail | stock | stock max / RMS / PSNR | footprint | footprint max / RMS / PSNR |
|---|---|---|---|---|---|---|
EOF
    cat "$rows/a"
    cat <<EOF

## Group B: different by design (RMS error / PSNR against supersampled references)

| test | image | reference | stock vs box | footprint vs box | stock vs Gaussian | footprint vs Gaussian | suite idiff vs OIIO ref (stock / footprint) |
|---|---|---|---|---|---|---|---|
EOF
    cat "$rows/b"
    printf '\n## Not run\n\n| test | why |\n|---|---|\n'
    cat "$rows/skipped"
    if [ -f "$rows/notes" ]; then
        printf '\n## Notes\n\n'
        cat "$rows/notes"
    fi
    if [ -f "$rows/status" ]; then
        printf '\n## Whole tests, as runtest.py (ctest) judges them\n\n'
        awk '{ n++; s += ($2 == 0); f += ($3 == 0); if ($2 != 0) sf = sf " texture-" $1; if ($3 != 0) ff = ff " texture-" $1 }
            END {
                printf "- stock testtex passes %d of %d%s\n", s, n, sf == "" ? "." : "; fails:" sf
                printf "- footprint testtex passes %d of %d%s\n", f, n, ff == "" ? "." : "; fails:" ff
            }' "$rows/status"
    fi
    printf '\n## The footprint edit of testtex.cpp (after the build edits)\n\n```diff\n'
    cat "$src/footprint-changes.diff"
    printf '```\n'
} >"$partial"
mv "$partial" "$output"
cat "$output"
say "table written to $output"
