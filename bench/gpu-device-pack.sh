#!/usr/bin/env bash
# bench/gpu-device-pack.sh — packs what bench/gpu-device.sh needs on a bare GPU machine that
# reaches no network (the device tool: /work/.library/device/README.md): footprint-bench and
# footprint-filament, the Debian libraries they load (their ELF closure, glibc's loader and libc
# included, so that nothing of the machine's own is mixed in but its GPU driver), Filament's
# compiled materials and the outputs of its tools (cmgen, roughness-prefilter) computed here, the
# showcase's files, and Xvfb for Filament's GLX. Run here, from the repository root, after `make`:
#
#   bench/gpu-device-pack.sh [BUILD_DIR] [PACK_DIR]        # defaults: build, .gpu-pack
#
# Writes PACK_DIR/pack.tar.xz and PACK_DIR/MANIFEST (PACK_DIR is ignored through
# .git/info/exclude); the device run names PACK_DIR in its `carry`. Everything that travels must fit
# in 64 MiB with the repository, so the libraries that no code path of these programs calls —
# OpenImageIO's plugins' dependencies (OpenVDB, FFmpeg, DCMTK, libheif, LibRaw, OpenCV,
# OpenColorIO, ...), and the LLVM behind Mesa's software driver for Xvfb's server-side GLX — are
# replaced by stubs (bench/gpu-device/make_stub.py): the same SONAME, version nodes and the symbols
# the carried files import, each function aborting with its name. A stub that is called after all
# says so on stderr ("<lib>: stub for <symbol> called"); add that library to `keep` below.
set -euo pipefail
build=${1:-build}
pack=${2:-.gpu-pack}
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/.." && pwd)
arch_dir=/lib/x86_64-linux-gnu

# Libraries replaced by stubs (SONAMEs). Whatever they alone need is then not carried either.
stubs=(
    libopenvdb.so.10.0 libavcodec.so.59 libavformat.so.59 libavutil.so.57 libswscale.so.6
    libopencv_core.so.406 libopencv_imgproc.so.406 libopencv_videoio.so.406
    libdcmimage.so.17 libdcmimgle.so.17 libdcmdata.so.17 liboflog.so.17 libofstd.so.17
    libheif.so.1 libraw_r.so.20 libOpenColorIO.so.2.1 libopenjp2.so.7
)
# Xvfb's alone, in x/lib: Mesa's software driver runs softpipe there (GALLIUM_DRIVER=softpipe),
# never LLVM. Apart from the rest, so that a client's Mesa (llvmpipe here) finds the real ones.
stubs_x=(libLLVM-15.so.1 libsensors.so.5 libelf.so.1 libz3.so.4 libxml2.so.2 libicuuc.so.72)
# Loaded with dlopen, so not in any file's NEEDED: glvnd's front ends (libepoxy and Filament load
# them; the vendor library, NVIDIA's or Mesa's, is the machine's), libXext (NVIDIA's
# libGLX_nvidia links it; the machine's is not on the library path), and glibc's compatibility
# libraries that a driver may still name.
dlopened=(libEGL.so.1 libGL.so.1 libOpenGL.so.0 libGLX.so.0 libGLdispatch.so.0 libXext.so.6 libdl.so.2
          libpthread.so.0 librt.so.1 libm.so.6)
# Benign stub functions (they return a pointer to zeros: "", or a non-zero number): what runs
# when the libraries are loaded — OpenImageIO's static DICOM registration object (DCMTK's
# DiRegister, made and destroyed), gallivm's LLVMIsMultithreaded check in Mesa's driver (Xvfb) —
# and version queries OpenImageIO may make while it lists its plugins.
benign=(_ZN10DiRegisterC1Ev _ZN10DiRegisterC2Ev _ZN10DiRegisterD1Ev _ZN10DiRegisterD2Ev
        LLVMIsMultithreaded
        av_version_info avformat_version avcodec_version libraw_version libraw_versionNumber
        opj_version heif_get_version heif_get_version_number heif_get_version_number_major
        heif_get_version_number_minor)

for program in footprint-bench footprint-filament; do
    [[ -x $build/$program ]] || { echo "gpu-device-pack: $build/$program is missing (make; Filament: libfilament-dev)" >&2; exit 1; }
done
[[ -d $build/filament-materials ]] || { echo "gpu-device-pack: $build/filament-materials is missing" >&2; exit 1; }

stage=$(mktemp -d /tmp/gpu-pack.XXXXXX)
trap 'rm -rf "$stage"' EXIT   # GPU_PACK_STAGE=DIR keeps a copy of the unpacked pack there
mkdir -p "$stage"/{bin,lib,stub,filament/materials,filament/cache,data,scenes,x/bin,x/lib,x/dri,x/xkb}

# --- the programs, stripped -------------------------------------------------------------------
strip -o "$stage/bin/footprint-bench" "$build/footprint-bench"
strip -o "$stage/bin/footprint-filament" "$build/footprint-filament"
cp /usr/bin/Xvfb "$stage/x/bin/Xvfb"
cp /usr/bin/xkbcomp "$stage/x/bin/xkbcomp"
cp /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so "$stage/x/dri/swrast_dri.so"
cp -r /usr/share/X11/xkb/. "$stage/x/xkb/"   # Xvfb compiles its keymap with xkbcomp at start

# --- the ELF closure, with the stubs cut in ---------------------------------------------------
declare -A where=() kept=() stubbed=()
while read -r name path; do where[$name]=$path; done < <(ldconfig -p | awk '/x86-64/ && $NF ~ /^\// {print $1, $NF}')
is_stub() { local s; for s in "${stubs[@]}" "${stubs_x[@]}"; do [[ $s == "$1" ]] && return 0; done; return 1; }
is_stub_x() { local s; for s in "${stubs_x[@]}"; do [[ $s == "$1" ]] && return 0; done; return 1; }
queue=("$stage/bin/footprint-bench" "$stage/bin/footprint-filament" "$stage/x/bin/Xvfb"
       "$stage/x/bin/xkbcomp" "$stage/x/dri/swrast_dri.so")
for name in "${dlopened[@]}"; do queue+=("${where[$name]:?$name not found}"); kept[$name]=1; done
while ((${#queue[@]})); do
    file=${queue[0]}; queue=("${queue[@]:1}")
    for need in $(readelf -d "$file" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p'); do
        [[ $need == ld-linux-x86-64.so.2 ]] && continue
        [[ -n ${kept[$need]:-} || -n ${stubbed[$need]:-} ]] && continue
        if is_stub "$need"; then stubbed[$need]=1; continue; fi
        path=${where[$need]:-}
        [[ -n $path ]] || { echo "gpu-device-pack: $file needs $need, which ldconfig does not know" >&2; exit 1; }
        kept[$need]=1
        queue+=("$path")
    done
done
for name in "${!kept[@]}"; do cp -L "${where[$name]}" "$stage/lib/$name"; done
cp -L /lib64/ld-linux-x86-64.so.2 "$stage/lib/ld-linux-x86-64.so.2"

# Every symbol a carried file imports: a stub exports only those (and keeps every version node).
for f in "$stage"/bin/* "$stage"/x/bin/* "$stage"/x/dri/* "$stage"/lib/*; do
    readelf -W --dyn-syms "$f" | awk '$7 == "UND" && $8 != "" {sub(/@.*/, "", $8); print $8}'
done | sort -u > "$stage/stub/needed.txt"
for name in "${!stubbed[@]}"; do
    dir=$stage/lib; is_stub_x "$name" && dir=$stage/x/lib
    python3 "$here/gpu-device/make_stub.py" "${where[$name]}" "$dir" \
        --needed "$stage/stub/needed.txt" --benign "${benign[@]}" > /dev/null
done
rm -rf "$stage/stub"

# --- Filament's materials and its tools' outputs ------------------------------------------------
cp "$build"/filament-materials/*.filamat "$stage/filament/materials/"
# The cache is keyed by a hash of the pixels, so what footprint-filament computes here is what it
# looks up there; one tiny comparison per scene fills it (cmgen and roughness-prefilter run here).
cache=$stage/filament/cache
runner=(); [[ -z ${DISPLAY:-} ]] && runner=(xvfb-run -a -s "-screen 0 64x64x24")
for scene in plate floor mirror; do
    "${runner[@]}" "$build/footprint-filament" "$scene" --compare --size 32x18 --supersample 1 \
        --frames 1 --cache "$cache" -o "$stage/tmp-compare" > /dev/null 2>&1 ||
        { echo "gpu-device-pack: footprint-filament $scene failed here (is Xvfb there?)" >&2; exit 1; }
done
rm -rf "$stage/tmp-compare"
# Only what the lookups read: the deployed KTX files and the roughness levels.
find "$cache" -type f ! -name '*.ktx' ! -name 'roughness_*.png' -delete

# --- the showcase: its files from the data set, the scene with paths into the pack --------------
data=$repo/../shared/data
showcase=$repo/examples/scenes/showcase.json
if [[ -d $data ]]; then
    grep -o '"\.\./\.\./\.\./shared/data/[^"]*"' "$showcase" | tr -d '"' | sort -u |
    while read -r rel; do
        file=${rel#../../../shared/data/}
        mkdir -p "$stage/data/$(dirname "$file")"
        if [[ $file == *.gltf ]]; then   # the glTF's buffers and images lie beside it
            cp -r "$data/$(dirname "$file")/." "$stage/data/$(dirname "$file")/"
        else
            cp "$data/$file" "$stage/data/$file"
        fi
    done
    sed 's#\.\./\.\./\.\./shared/data/#../data/#g' "$showcase" > "$stage/scenes/showcase.json"
else
    echo "gpu-device-pack: no data set at $data: the showcase is not packed" >&2
fi

# --- pack ----------------------------------------------------------------------------------------
mkdir -p "$pack"
pack=$(cd "$pack" && pwd)
if [[ $pack == "$repo"/* ]]; then   # ignored, so that only the device run's `carry` takes it along
    rel=/${pack#"$repo"/}/
    grep -qxF "$rel" "$repo/.git/info/exclude" 2>/dev/null || echo "$rel" >> "$repo/.git/info/exclude"
fi
{
    echo "# bench/gpu-device-pack.sh, $(date -u +%FT%TZ), $(git -C "$repo" rev-parse --short HEAD)"
    echo "# real libraries:"; printf '%s\n' "${!kept[@]}" | sort
    echo "# stubs:"; printf '%s\n' "${!stubbed[@]}" | sort
} > "$pack/MANIFEST"
cp "$pack/MANIFEST" "$stage/MANIFEST"
XZ_OPT="-9 -T${XZ_THREADS:-2}" tar -C "$stage" -cJf "$pack/pack.tar.xz.tmp" .
mv "$pack/pack.tar.xz.tmp" "$pack/pack.tar.xz"
[[ -n ${GPU_PACK_STAGE:-} ]] && { rm -rf "$GPU_PACK_STAGE"; cp -a "$stage" "$GPU_PACK_STAGE"; }
echo "gpu-device-pack: $pack/pack.tar.xz, $(du -b "$pack/pack.tar.xz" | cut -f1) bytes" \
     "($(du -sb "$stage" | cut -f1) unpacked; ${#kept[@]} libraries, ${#stubbed[@]} stubs)"
