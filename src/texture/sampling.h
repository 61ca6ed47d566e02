// texture/sampling.h — the inner loops every filter shares (private to texture/).
//
// All functions accumulate `weight × sample` into acc[0..S), S = the pyramid's texel stride, a
// compile-time constant so that the channel loops vectorise. Positions are normalised (s, t)
// already reduced by reduce_coordinate(); texel coordinates follow spec §1 (X = s·W − ½).
#pragma once

#include <cmath>

#include "texture/mip_pyramid.h"

namespace footprint::detail {

// Bilinear sample of one level at (s, t).
template <int S>
inline void accumulate_bilinear(const MipPyramid::LevelView& level, WrapMode wrap_s,
                                WrapMode wrap_t, float s, float t, float weight, float* acc) {
    const float x = s * static_cast<float>(level.width) - 0.5f;
    const float y = t * static_cast<float>(level.height) - 0.5f;
    const float xf = std::floor(x), yf = std::floor(y);
    const float fx = x - xf, fy = y - yf;
    int x0 = static_cast<int>(xf), y0 = static_cast<int>(yf);
    int x1 = x0 + 1, y1 = y0 + 1;
    if (x0 < 0 || x1 >= level.width) {
        x0 = wrap_index(x0, level.width, wrap_s);
        x1 = wrap_index(x1, level.width, wrap_s);
    }
    if (y0 < 0 || y1 >= level.height) {
        y0 = wrap_index(y0, level.height, wrap_t);
        y1 = wrap_index(y1, level.height, wrap_t);
    }
    const float* a = level.texel(x0, y0);
    const float* b = level.texel(x1, y0);
    const float* c = level.texel(x0, y1);
    const float* d = level.texel(x1, y1);
    const float wa = weight * (1 - fx) * (1 - fy), wb = weight * fx * (1 - fy);
    const float wc = weight * (1 - fx) * fy, wd = weight * fx * fy;
    for (int k = 0; k < S; ++k) acc[k] += wa * a[k] + wb * b[k] + wc * c[k] + wd * d[k];
}

// Blend weight of the finer level's successor at fractional lod L + w.
inline float lod_blend_weight(float w, LodBlend blend) {
    // Spec §2.8: linear blending gives variance 4^L(1+3w)/4; w' = (4^w − 1)/3 gives 4^{L+w}/4.
    return blend == LodBlend::linear ? w : (std::exp2(2.0f * w) - 1.0f) * (1.0f / 3.0f);
}

// Trilinear probe at a fractional level lod ∈ [0, max_level].
template <int S>
inline void accumulate_trilinear(const MipPyramid& pyramid, float s, float t, float lod,
                                 LodBlend blend, float weight, float* acc) {
    const int max_level = pyramid.max_level();
    const int l0 = std::min(static_cast<int>(lod), max_level);
    const float w = l0 < max_level ? lod_blend_weight(lod - static_cast<float>(l0), blend) : 0.0f;
    if (w < 1.0f)
        accumulate_bilinear<S>(pyramid.level(l0), pyramid.wrap_s(), pyramid.wrap_t(), s, t,
                               weight * (1 - w), acc);
    if (w > 0.0f)
        accumulate_bilinear<S>(pyramid.level(l0 + 1), pyramid.wrap_s(), pyramid.wrap_t(), s, t,
                               weight * w, acc);
}

// Calls f.template operator()<S>() with the pyramid's stride as a compile-time constant.
template <class F>
inline void dispatch_stride(int stride, F&& f) {
    switch (stride) {
        case 1:
            f.template operator()<1>();
            break;
        case 2:
            f.template operator()<2>();
            break;
        case 4:
            f.template operator()<4>();
            break;
        default:
            f.template operator()<8>();
            break;
    }
}

}  // namespace footprint::detail
