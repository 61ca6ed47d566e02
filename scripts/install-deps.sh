#!/usr/bin/env bash
# Installs the Debian packages footprint builds and tests with; silent when all are present.
# Idempotent: called by every `make` target. Needs root (or sudo) only when something is missing.
set -euo pipefail

packages=(
    build-essential cmake ninja-build clang-format pkg-config
    libopenimageio-dev openimageio-tools libopencv-core-dev   # image I/O + benchmark peer
    libopenexr-dev                                            # multi-part MIP-mapped OpenEXR
    libtiff-dev                                               # which TIFF codecs libtiff has
    zlib1g-dev                                                # a PNG's compressed text chunks
    libtbb-dev                                                # parallelism
    libembree-dev libtinyobjloader-dev libtinygltf-dev libstb-dev
    nlohmann-json3-dev libcli11-dev
    libgtest-dev libgmock-dev libbenchmark-dev
    chromium                                                  # footprint eval's report check
    fonts-dejavu-core                                         # contact sheets' labels
    valgrind                                                  # bench/env-instructions.sh
    libepoxy-dev libegl-dev libgl1-mesa-dri libglfw3-dev      # the GPU path (OpenGL 4.5, EGL)
    xvfb xauth                                                # footprint view's test (a display)
    pybind11-dev python3-dev python3-numpy python3-pytest     # the Python module and its tests
    clang-14 libclang-rt-14-dev                               # make fuzz (libFuzzer)
    libfilament-dev libfilament-tools                         # examples/filament (matc, cmgen)
    slurm-wlm munge                                           # tests/farm: a one-node Slurm cluster
)

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
