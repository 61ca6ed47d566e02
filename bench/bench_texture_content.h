// bench/bench_texture_content.h — the benchmark's procedural texture.
//
// A deterministic linear-light RGB image with content at every scale, so that filter errors show:
// red: octaves of value noise (periods 256…4 texels) plus a checkerboard of 8-texel squares with
// hard edges; green: a grating of period 3.3 texels whose orientation turns across the image (near
// Nyquist: aliases at once when under-filtered); blue: fine value noise (period 2) over a gradient.
#pragma once

#include "image/image.h"

namespace footprint::bench {

Image make_benchmark_texture(int size);

}  // namespace footprint::bench
