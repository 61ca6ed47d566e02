// texture/downsample.h — one MIP level from the previous one (private to texture/ and bump/).
//
// The downsampling filters of mip_pyramid.h (box, tent), integrated exactly over the source texels
// for any size ratio, applied separably and fused per output row. Buffers are row-major,
// `stride` values per texel. float builds colour pyramids; double builds the bump pyramid's moments
// (bump/bump_pyramid.h), where the second moments must survive the subtraction K = M2 − μμᵀ.
#pragma once

#include "texture/mip_pyramid.h"

namespace footprint::detail {

// Reads In, accumulates and writes T (float → float, float → double, double → double).
// src_pitch and dst_pitch: values from one row to the next (0: packed rows, sw·stride and
// dw·stride), so that a level can be made in place among bordered ones.
template <class In, class T>
void downsample(const In* src, int sw, int sh, T* dst, int dw, int dh, int stride,
                const MipPyramidOptions& options, std::ptrdiff_t src_pitch = 0,
                std::ptrdiff_t dst_pitch = 0);

// Variance of one destination texel's taps about its centre, in source texels² (what one
// downsampling step adds: ¼ for the box with ratio 2, ¾ for the tent).
double tap_variance(int src, int dst, DownsampleFilter filter);

}  // namespace footprint::detail
