#!/usr/bin/env bash
# bench/gpu-device.sh — the GPU benchmarks on a bare machine with an NVIDIA GPU that reaches no
# network (the device tool), from what bench/gpu-device-pack.sh packed here:
#   footprint-bench gpu at 1920x1080 on every demo scene  -> $OUT/gpu-demos.json
#   footprint-bench gpu at 1920x1080 on the showcase      -> $OUT/gpu-showcase.json
#   the Filament comparison (plate, floor, mirror)        -> $OUT/filament.json
# and $OUT/log.txt (everything printed) and $OUT/machine.txt (GPU, driver, glibc). Bounded to
# GPU_DEVICE_BUDGET_S seconds in all (default 450, under 8 minutes). Run from the repository root:
#
#   here:  bench/gpu-device-pack.sh                      # once; writes .gpu-pack/ (~40 MB)
#   there: bench/gpu-device.sh                           # the device run, carry: [".gpu-pack"]
#
# Every program runs under the pack's own glibc loader with --inhibit-cache and the pack's
# libraries first, so nothing of the machine's is used but its GPU driver (NVIDIA's EGL and GLX
# vendor libraries, found below). Settings (environment):
#   GPU_DEVICE_SIZE      frame size (1920x1080); GPU_DEVICE_FRAMES timed frames per mode (20),
#                        GPU_DEVICE_WARMUP untimed ones first (3)
#   GPU_DEVICE_SCENES    demo scenes, space-separated (every demo scene)
#   GPU_DEVICE_FILAMENT_SIZE / _SUPERSAMPLE   Filament's comparison (GPU_DEVICE_SIZE, 8)
#   GPU_DEVICE_PARTS     which parts to run ("demos showcase filament")
#   GPU_DEVICE_PACK      the pack (.gpu-pack/pack.tar.xz); GPU_DEVICE_ROOT where it is unpacked
#   GPU_DEVICE_EGL_JSON, GPU_DEVICE_DRIVER_DIR, GPU_DEVICE_GLX_VENDOR   the driver, where the
#                        search below does not find NVIDIA's (llvmpipe here: 50_mesa.json,
#                        /usr/lib/x86_64-linux-gnu, mesa)
set -uo pipefail
size=${GPU_DEVICE_SIZE:-1920x1080}
frames=${GPU_DEVICE_FRAMES:-20}
warmup=${GPU_DEVICE_WARMUP:-3}
fsize=${GPU_DEVICE_FILAMENT_SIZE:-$size}
fsuper=${GPU_DEVICE_FILAMENT_SUPERSAMPLE:-8}
parts=${GPU_DEVICE_PARTS:-demos showcase filament}
budget=${GPU_DEVICE_BUDGET_S:-450}
pack=${GPU_DEVICE_PACK:-.gpu-pack/pack.tar.xz}
root=${GPU_DEVICE_ROOT:-/tmp/footprint-gpu-pack}
out=${OUT:-out/gpu-device}
repo=$PWD
mkdir -p "$out"
out=$(cd "$out" && pwd)
exec > >(tee "$out/log.txt") 2>&1
tee_pid=$!
say() { echo "gpu-device: $*"; }
left() { echo $((budget - SECONDS)); }

[[ -f $pack ]] || { say "no pack at $pack: run bench/gpu-device-pack.sh here and carry .gpu-pack"; exit 1; }
rm -rf "$root" && mkdir -p "$root" && tar -C "$root" -xJf "$pack" ||
    { say "cannot unpack $pack into $root"; exit 1; }
say "unpacked $pack into $root in ${SECONDS}s"
ld=$root/lib/ld-linux-x86-64.so.2

# --- the driver: NVIDIA's EGL vendor library and the folder of its libraries -------------------
egl_json=${GPU_DEVICE_EGL_JSON:-}
if [[ -z $egl_json ]]; then
    for c in ${__EGL_VENDOR_LIBRARY_FILENAMES//:/ } \
        /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json \
        /usr/share/glvnd/egl_vendor.d/10_nvidia.json /etc/glvnd/egl_vendor.d/10_nvidia.json; do
        [[ -f $c ]] && { egl_json=$c; break; }
    done
fi
[[ -n $egl_json ]] || egl_json=$(timeout 30 find / -xdev -path '*egl_vendor.d/*nvidia*.json' 2>/dev/null | head -1)
driver_dir=${GPU_DEVICE_DRIVER_DIR:-}
if [[ -z $driver_dir ]]; then
    egl_lib=libEGL_nvidia.so.0
    [[ -n $egl_json ]] && egl_lib=$(sed -n 's/.*"library_path" *: *"\([^"]*\)".*/\1/p' "$egl_json")
    if [[ $egl_lib == /* ]]; then
        found=$egl_lib
    else
        found=$(ls /usr/local/nvidia/lib64/"$egl_lib" /usr/local/nvidia/lib/"$egl_lib" \
                   /usr/lib/x86_64-linux-gnu/"$egl_lib" /usr/lib64/"$egl_lib" 2>/dev/null | head -1)
        [[ -n $found ]] || found=$(ldconfig -p 2>/dev/null | awk -v l="$egl_lib" '$1 == l && /x86-64/ {print $NF; exit}')
    fi
    [[ -n $found ]] || { say "no NVIDIA EGL driver ($egl_lib) found; set GPU_DEVICE_EGL_JSON and GPU_DEVICE_DRIVER_DIR"; exit 1; }
    # Only NVIDIA's own libraries, linked into a folder of their own: the machine's others stay out.
    driver_dir=$root/driver
    mkdir -p "$driver_dir"
    for f in "$(dirname "$(readlink -f "$found")")"/lib{EGL_nvidia,GLX_nvidia,nvidia-}*.so* \
             "$(dirname "$found")"/lib{EGL_nvidia,GLX_nvidia,nvidia-}*.so*; do
        [[ -e $f && ! -e $driver_dir/$(basename "$f") ]] && ln -s "$f" "$driver_dir/"
    done
    if [[ -z $egl_json ]]; then
        egl_json=$root/10_nvidia.json
        echo '{"file_format_version": "1.0.0", "ICD": {"library_path": "libEGL_nvidia.so.0"}}' > "$egl_json"
    fi
fi
glx_vendor=${GPU_DEVICE_GLX_VENDOR:-nvidia}
say "EGL vendor $egl_json; driver libraries from $driver_dir; GLX vendor $glx_vendor"

{
    echo "pack: $(head -1 "$root/MANIFEST")"
    echo "host glibc: $(ldd --version 2>/dev/null | head -1)"
    command -v nvidia-smi > /dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv
    echo "EGL vendor: $egl_json"; cat "$egl_json"
    echo "driver libraries:"; ls -l "$driver_dir" 2>/dev/null | head -40
} > "$out/machine.txt" 2>&1

# Runs a packed program: the pack's loader and libraries, then the driver's; a clean environment.
run() {
    local limit=$1; shift
    local program=$1; shift
    timeout -k 5 "$limit" env -i PATH=/usr/bin:/bin HOME="$root/home" XDG_CACHE_HOME="$root/cache" \
        __EGL_VENDOR_LIBRARY_FILENAMES="$egl_json" __GLX_VENDOR_LIBRARY_NAME="$glx_vendor" \
        FOOTPRINT_DATA="$repo/assets" ${DISPLAY:+DISPLAY=$DISPLAY} \
        "$ld" --inhibit-cache --library-path "$root/lib:$driver_dir" "$program" "$@"
}
status=0

# --- footprint-bench gpu: every demo scene, then the showcase --------------------------------
# The demos read the HDR sky and the brick normal map from the repository's assets/ (the same
# files as the data set's); the showcase its own files from the pack (pack's scenes/, data/).
# One process per scene, so that a scene that fails or runs out of time loses only itself; the
# scenes' JSON files are then gathered into one, {"runs": [...]}.
merge() {  # merge OUT_FILE FILE...: the files' JSON documents as one array
    local target=$1; shift
    { echo '{"size": "'"$size"'", "frames": '"$frames"', "runs": ['
      local first=1 f
      for f in "$@"; do [[ -s $f ]] || continue; ((first)) || echo ','; first=0; cat "$f"; done
      echo ']}'; } > "$target"
}
if [[ $parts == *demos* ]]; then
    scenes=${GPU_DEVICE_SCENES:-}
    # The demo scenes' names, from footprint-bench's own message for a name it does not know.
    [[ -n $scenes ]] || scenes=$(run 60 "$root/bin/footprint-bench" gpu --size 8x8 --scenes '?' 2>&1 |
        sed -n 's/.*not a built-in demo (\(.*\)).*/\1/p' | tr -d ,)
    [[ -n $scenes ]] || { say "cannot list the demo scenes (see above)"; status=1; }
    set -- $scenes
    n=$#
    say "footprint-bench gpu, $n demo scenes ($scenes), $size, $frames frames ($(left)s left)"
    files=()
    for scene in $scenes; do
        # What is left, less the showcase's and Filament's share, spread over the scenes to come.
        limit=$(( ($(left) - 150) / n )); n=$((n - 1))
        ((limit >= 10)) || { say "no time left for $scene: skipped"; status=1; continue; }
        run $limit "$root/bin/footprint-bench" gpu --size "$size" --frames "$frames" --warmup "$warmup" \
            --scenes "$scene" --json "$root/gpu-$scene.json" ||
            { say "demo scene $scene FAILED (status $?; 124: over its ${limit}s)"; status=1; }
        files+=("$root/gpu-$scene.json")
    done
    merge "$out/gpu-demos.json" "${files[@]}"
fi
if [[ $parts == *showcase* ]]; then
    if [[ -f $root/scenes/showcase.json ]]; then
        say "footprint-bench gpu, the showcase, $size ($(left)s left)"
        run $(($(left) - 90)) "$root/bin/footprint-bench" gpu --size "$size" --frames "$frames" --warmup "$warmup" \
            --scenes "$root/scenes/showcase.json" --json "$out/gpu-showcase.json" ||
            { say "the showcase FAILED (status $?)"; status=1; }
    else
        say "the showcase is not in the pack (no ../shared/data where it was packed): skipped"
    fi
fi

# --- the Filament comparison, under the pack's Xvfb (GLX: NVIDIA's client library) -----------
if [[ $parts == *filament* ]]; then
    say "Filament comparison, $fsize, truth ${fsuper}x ($(left)s left)"
    # Xvfb runs xkbcomp from /usr/bin (compiled in); a bare machine has none, so a wrapper that
    # runs the packed one goes there (only where there is none).
    if [[ ! -x /usr/bin/xkbcomp ]]; then
        printf '#!/bin/sh\nexec "%s" --inhibit-cache --library-path "%s" "%s" "$@"\n' \
            "$ld" "$root/lib" "$root/x/bin/xkbcomp" > /usr/bin/xkbcomp && chmod +x /usr/bin/xkbcomp ||
            say "cannot write /usr/bin/xkbcomp: Xvfb may fail to start"
    fi
    display=:77
    # Xvfb's own GLX (the server side) runs Mesa's softpipe; the rendering is the client's.
    env -i PATH=/usr/bin:/bin LIBGL_DRIVERS_PATH="$root/x/dri" GALLIUM_DRIVER=softpipe \
        DRAW_USE_LLVM=0 "$ld" --inhibit-cache --library-path "$root/x/lib:$root/lib" "$root/x/bin/Xvfb" \
        $display -screen 0 64x64x24 -nolisten tcp -xkbdir "$root/x/xkb" > "$root/xvfb.log" 2>&1 &
    xvfb=$!
    for _ in $(seq 50); do [[ -e /tmp/.X11-unix/X${display#:} ]] && break; sleep 0.2; done
    if ! kill -0 $xvfb 2>/dev/null; then
        say "Xvfb did not start: the Filament comparison is not run"; cat "$root/xvfb.log"; status=1
    else
        DISPLAY=$display
        rows=()
        for scene in plate floor mirror; do
            limit=$(($(left) - 10))
            ((limit > 20)) || { say "no time left for Filament's $scene"; status=1; break; }
            run $limit "$root/bin/footprint-filament" "$scene" --compare --size "$fsize" \
                --supersample "$fsuper" --materials "$root/filament/materials" \
                --cache "$root/filament/cache" --assets "$repo/assets" -o "$root/filament-out" \
                > "$root/filament-$scene.txt" 2>&1
            rc=$?
            grep -v -e FEngine -e CircularBuffer "$root/filament-$scene.txt"
            ((rc == 0)) || { say "Filament's $scene FAILED (status $rc)"; status=1; }
            # "scene material rmse flip frame_ms" rows (the truth: "-" for rmse and flip).
            while read -r s m r f t _; do
                [[ $s == "$scene" && $t =~ ^[0-9.]+$ ]] || continue
                [[ $r =~ ^[0-9.]+$ ]] || r=null
                [[ $f =~ ^[0-9.]+$ ]] || f=null
                rows+=("{\"scene\": \"$s\", \"material\": \"$m\", \"rmse\": $r, \"flip\": $f, \"frame_ms\": $t}")
            done < "$root/filament-$scene.txt"
        done
        unset DISPLAY
        {
            echo "{\"size\": \"$fsize\", \"supersample\": $fsuper, \"glx_vendor\": \"$glx_vendor\","
            echo " \"rows\": ["
            (IFS=$'\n'; echo "${rows[*]}" | sed '$!s/$/,/')
            echo "]}"
        } > "$out/filament.json"
        kill $xvfb 2>/dev/null; wait $xvfb 2>/dev/null
    fi
fi
say "done in ${SECONDS}s (budget ${budget}s); files in $out: $(cd "$out" && ls | tr '\n' ' ')"
exec >&- 2>&-
wait $tee_pid 2>/dev/null   # log.txt complete before the files are collected
exit $status
