// bench/bench_lookups.h — the footprint regimes and random lookups every texture benchmark uses.
//
// A regime is the pair of texel-space lengths of the pixel-step images (the columns of D): tiny
// 0.25 × 0.25 texels (magnification), moderate 4 × 4, aniso32 1 × 32. A lookup puts such a
// footprint at a random position with a random orientation θ and scales it by 2^u, u ∈ [−½, ½] (±½
// octave): D = R(θ)·diag(major, minor)·2^u, in normalised units for a size × size texture.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "texture/texture_lookup.h"

namespace footprint::bench {

struct Regime {
    const char* name;
    float major, minor;  // texel lengths of the pixel-step images
};
inline constexpr Regime kRegimes[] = {
    {"tiny", 0.25f, 0.25f}, {"moderate", 4, 4}, {"aniso32", 32, 1}};

inline std::vector<TextureCoords> make_lookups(const Regime& regime, std::size_t n, int size,
                                               unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0, 1);
    std::vector<TextureCoords> lookups(n);
    const float inv = 1.0f / float(size);
    for (TextureCoords& c : lookups) {
        const float angle = 6.2831853f * unit(rng);
        const float scale = std::exp2(unit(rng) - 0.5f) * inv;
        const float ca = std::cos(angle), sa = std::sin(angle);
        c.s = unit(rng);
        c.t = unit(rng);
        c.dsdx = regime.major * scale * ca;
        c.dtdx = regime.major * scale * sa;
        c.dsdy = -regime.minor * scale * sa;
        c.dtdy = regime.minor * scale * ca;
    }
    return lookups;
}

}  // namespace footprint::bench
