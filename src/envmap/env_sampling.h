// envmap/env_sampling.h — (private to envmap) reading an environment map's texels seamlessly:
// taps beyond a face's edge come from wherever the direction of their centre lies (spec §3.1's
// seamless cube filtering, the lat-long seam and poles, the sphere map's rim, the other paraboloid
// hemisphere). Used by environment_map.cpp and polar_caps.cpp; the public entry points are in
// environment_map.h.
#pragma once

#include <algorithm>

#include "envmap/environment_map.h"
#include "texture/sampling.h"

namespace footprint::detail {

// One texel of a level of `face`, where (x, y) may lie beyond the level's edge: such a tap is taken
// from wherever the direction of its centre lies — the neighbour cube face (seamless cube
// filtering, §3.1), across a lat-long pole (the seam wraps the same way), back through the sphere
// map's rim, or on the other paraboloid hemisphere.
inline const float* env_texel(const EnvironmentMap& map, int face, int level, int x, int y) {
    const MipPyramid::LevelView view = map.face(face).level(level);
    if (x >= 0 && y >= 0 && x < view.width && y < view.height) return view.texel(x, y);
    if (map.layout() == EnvLayout::latlong) {
        // Over a pole, row −1 − k is row k half a turn around; the seam wraps (exact for texel
        // centres, and no trigonometry).
        if (y < 0 || y >= view.height) {
            y = y < 0 ? -1 - y : 2 * view.height - 1 - y;
            x += view.width / 2;
        }
        x %= view.width;
        if (x < 0) x += view.width;
        return view.texel(x, std::clamp(y, 0, view.height - 1));
    }
    const float w = static_cast<float>(view.width), h = static_cast<float>(view.height);
    const EnvCoords c = env_coords(
        map.layout(), env_direction(map.layout(), face, (static_cast<float>(x) + 0.5f) / w,
                                    (static_cast<float>(y) + 0.5f) / h));
    const MipPyramid::LevelView other = map.face(c.face).level(level);
    return other.texel(std::clamp(static_cast<int>(c.s * w), 0, view.width - 1),
                       std::clamp(static_cast<int>(c.t * h), 0, view.height - 1));
}

// Bilinear on a level of `face`, with taps beyond its edges read by direction (env_texel).
template <int S>
[[gnu::always_inline]] inline Texel<S> env_bilinear(const EnvironmentMap& map, int face, int level,
                                                    float s, float t) {
    const MipPyramid& pyramid = map.face(face);
    const MipPyramid::LevelView view = pyramid.level(level);
    const float x = s * static_cast<float>(view.width) - 0.5f;
    const float y = t * static_cast<float>(view.height) - 0.5f;
    const int x0 = floor_to_int(x), y0 = floor_to_int(y);
    if (x0 >= 0 && y0 >= 0 && x0 + 1 < view.width && y0 + 1 < view.height)
        return sample_bilinear<S>(view, pyramid.wrap_s(), pyramid.wrap_t(), s, t);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    Texel<S> r{};
    add_scaled(r, (1 - fx) * (1 - fy), Texel<S>::load(env_texel(map, face, level, x0, y0)));
    add_scaled(r, fx * (1 - fy), Texel<S>::load(env_texel(map, face, level, x0 + 1, y0)));
    add_scaled(r, (1 - fx) * fy, Texel<S>::load(env_texel(map, face, level, x0, y0 + 1)));
    add_scaled(r, fx * fy, Texel<S>::load(env_texel(map, face, level, x0 + 1, y0 + 1)));
    return r;
}

// Where a footprint-assembly probe reads: EnvCoords without default values, so that an array of
// the most probes a plan can hold costs nothing to declare.
struct ProbeCentre {
    int face;
    float s, t;
};

// Requests the cache lines of a probe's bilinear taps at `level` (taps beyond a face's edge are
// left to env_texel).
inline void prefetch_probe(const EnvironmentMap& map, const ProbeCentre& probe, int level) {
    prefetch_bilinear(map.face(probe.face).level(level), probe.s, probe.t);
}

template <int S>
[[gnu::always_inline]] inline Texel<S> env_trilinear(const EnvironmentMap& map, const EnvCoords& c,
                                                     float lod, LodBlend blend) {
    const int max_level = map.face(c.face).max_level();
    const int l0 = std::min(static_cast<int>(lod), max_level);
    const float w = l0 < max_level ? lod_blend_weight(lod - static_cast<float>(l0), blend) : 0.0f;
    Texel<S> r = env_bilinear<S>(map, c.face, l0, c.s, c.t);
    if (w > 0.0f) {
        const Texel<S> coarse = env_bilinear<S>(map, c.face, l0 + 1, c.s, c.t);
        r.v += w * (coarse.v - r.v);
    }
    return r;
}

}  // namespace footprint::detail
