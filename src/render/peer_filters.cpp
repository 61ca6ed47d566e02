#include "render/peer_filters.h"

#include <algorithm>
#include <cmath>

#include "bump/roughness.h"

namespace footprint::detail {

namespace {

// Below this |n̄| the normals cancel: σ² is capped there (a slope spread of 100).
constexpr float kMinNormalLength = 1e-4f;

}  // namespace

SlopeStatistics toksvig_slopes(Vec3 n) {
    const float length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!(length > kMinNormalLength) || !(n.z > 0)) {
        const float sigma2 = (1 - kMinNormalLength) / kMinNormalLength;
        return {Vec2{}, Sym2{sigma2, 0, sigma2}};
    }
    const float l = std::min(length, 1.0f);
    const float sigma2 = (1 - l) / l;
    return {Vec2{n.x / n.z, n.y / n.z}, Sym2{sigma2, 0, sigma2}};
}

Image unit_normals(const Image& slopes, float strength) {
    Image normals(slopes.width, slopes.height, 3);
    for (int y = 0; y < slopes.height; ++y) {
        for (int x = 0; x < slopes.width; ++x) {
            const float b1 = strength * slopes.at(x, y, 0), b2 = strength * slopes.at(x, y, 1);
            const float scale = 1 / std::sqrt(1 + b1 * b1 + b2 * b2);
            float* n = normals.at(x, y);
            n[0] = b1 * scale, n[1] = b2 * scale, n[2] = scale;
        }
    }
    return normals;
}

Sym2 screen_space_roughness(Vec2 dx, Vec2 dy) {
    constexpr float s = ScreenSpaceRoughness::kPixelFilterVariance;
    constexpr float limit = ScreenSpaceRoughness::kMaxVariance;
    const Sym2 k = s * footprint_matrix(dx, dy);
    if (!k.is_finite()) return Sym2{limit, 0, limit};
    const float xx = std::min(k.xx, limit), yy = std::min(k.yy, limit);
    // Scaling the covariance with the variances keeps its correlation, so K stays PSD.
    const float scale = k.xx > 0 && k.yy > 0 ? std::sqrt((xx / k.xx) * (yy / k.yy)) : 0.0f;
    return {xx, k.xy * scale, yy};
}

TextureCoords stochastic_probe(const TextureCoords& coords, int width, int height,
                               RandomStream& random) {
    const float w = static_cast<float>(width), h = static_cast<float>(height);
    // The pixel filter's Gaussian in level-0 texels: covariance K/4.
    const Sym2 k = 0.25f * footprint_matrix({w * coords.dsdx, h * coords.dtdx},
                                            {w * coords.dsdy, h * coords.dtdy});
    TextureCoords probe;
    probe.s = coords.s, probe.t = coords.t;
    const float minor = 0.5f * (k.trace() - std::hypot(k.xx - k.yy, 2 * k.xy));  // σ_min²
    if (!k.is_finite() || !(k.trace() > 0)) return probe;
    // The level whose kernel variance 4^L/4 is σ_min², its fraction drawn at random.
    const double lod = std::max(0.0, std::log2(2.0 * std::sqrt(std::max(minor, 0.0f))));
    int level = static_cast<int>(std::floor(lod));
    if (random.uniform() < lod - level) ++level;
    const float size = std::ldexp(1.0f, level);
    const float own = 0.25f * size * size;
    const RoughnessFactor b = roughness_factor(clamp_to_psd(k + Sym2{-own, 0, -own}));
    const Vec2 z = random.gaussian();
    // B Bᵀ = the residual covariance, so B z has it.
    const float ox = b.d1 * z.x + b.d2 * z.y, oy = b.d3 * z.y;
    probe.s = coords.s + ox / w, probe.t = coords.t + oy / h;
    probe.dsdx = size / w, probe.dtdy = size / h;
    return probe;
}

Vec2 sample_slope(const SlopeStatistics& slopes, Vec2 z) {
    const RoughnessFactor b = roughness_factor(slopes.covariance);
    return slopes.mean + Vec2{b.d1 * z.x + b.d2 * z.y, b.d3 * z.y};
}

}  // namespace footprint::detail
