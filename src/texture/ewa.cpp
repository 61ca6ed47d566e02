#include "texture/ewa.h"

#include <algorithm>
#include <cmath>

#include "math/fast_log2.h"

#include "texture/filters.h"
#include "texture/sampling.h"
#include "texture/tiled_texels.h"

namespace footprint {

Sym2 ewa_gaussian_covariance(const FootprintEllipse& footprint, float prefilter_variance,
                             float texel_size) {
    const float shrink = prefilter_variance + 1.0f / 12.0f;
    const float floor_variance = kEwaMinSigma * kEwaMinSigma * texel_size * texel_size;
    const float major =
        std::max(0.25f * footprint.major_radius * footprint.major_radius - shrink, floor_variance);
    const float minor =
        std::max(0.25f * footprint.minor_radius * footprint.minor_radius - shrink, floor_variance);
    return outer(footprint.major_axis, major) + outer(footprint.minor_axis(), minor);
}

Sym2 ewa_squeeze_thin_level(Sym2 sigma, int width, int height) {
    // Scaling one axis by k (ξ → diag(1, k)·ξ) scales the Gaussian's spread that way and keeps its
    // marginal along the other, which is all that a level one texel thick sees.
    const float cap = kEwaThinLevelSigma * kEwaThinLevelSigma;
    if (height == 1 && sigma.yy > cap)
        sigma = {sigma.xx, std::sqrt(cap / sigma.yy) * sigma.xy, cap};
    if (width == 1 && sigma.xx > cap) sigma = {cap, std::sqrt(cap / sigma.xx) * sigma.xy, sigma.yy};
    return sigma;
}

namespace detail {

namespace {

// Σ w(ξ)·texel over one level, added into acc[] (weighted by level_weight) and the weight sum.
template <int S, class Texels>
void accumulate_ewa_level(const Texels& pyramid, int l, float s, float t,
                          const FootprintEllipse& footprint, float level_weight, double* acc) {
    const MipPyramid::LevelView& level = pyramid.level(l);
    const float tx = static_cast<float>(pyramid.width(0)) / static_cast<float>(level.width);
    const float ty = static_cast<float>(pyramid.height(0)) / static_cast<float>(level.height);
    const Vec2 pv = pyramid.prefilter_variance(l);
    Sym2 sigma = ewa_gaussian_covariance(footprint, std::max(pv.x, pv.y), std::max(tx, ty));
    // To this level's texel units, enlarged so that the 3σ-truncated Gaussian keeps covariance Σ.
    const float enlarge = 1.0f / ewa_truncation_variance();
    sigma = ewa_squeeze_thin_level({enlarge * sigma.xx / (tx * tx), enlarge * sigma.xy / (tx * ty),
                                    enlarge * sigma.yy / (ty * ty)},
                                   level.width, level.height);
    const float det = sigma.determinant();
    const Sym2 q = {sigma.yy / det, -sigma.xy / det, sigma.xx / det};  // Σ'⁻¹
    const float cutoff = kEwaTruncationSigmas * kEwaTruncationSigmas;
    const float edge_weight = std::exp(-0.5f * cutoff);

    const float cx = s * static_cast<float>(level.width) - 0.5f;
    const float cy = t * static_cast<float>(level.height) - 0.5f;
    const float half_h = kEwaTruncationSigmas * std::sqrt(sigma.yy);
    const int y_begin = static_cast<int>(std::ceil(cy - half_h));
    const int y_end = static_cast<int>(std::floor(cy + half_h));
    double sum[S] = {};
    double weight_sum = 0;
    for (int y = y_begin; y <= y_end; ++y) {
        const float dy = static_cast<float>(y) - cy;
        // Span of q(dx, dy) < cutoff in this row: a dx² + 2 b dy dx + (c dy² − cutoff) < 0.
        const float b = q.xy * dy;
        const float disc = b * b - q.xx * (q.yy * dy * dy - cutoff);
        if (disc <= 0) continue;
        const float root = std::sqrt(disc);
        const int x_begin = static_cast<int>(std::ceil(cx + (-b - root) / q.xx));
        const int x_end = static_cast<int>(std::floor(cx + (-b + root) / q.xx));
        const int wy = wrap_index(y, level.height, pyramid.wrap_t());
        for (int x = x_begin; x <= x_end; ++x) {
            const float dx = static_cast<float>(x) - cx;
            const float r2 = q.xx * dx * dx + 2 * q.xy * dx * dy + q.yy * dy * dy;
            if (r2 >= cutoff) continue;
            const float w = std::exp(-0.5f * r2) - edge_weight;
            const int wx =
                x >= 0 && x < level.width ? x : wrap_index(x, level.width, pyramid.wrap_s());
            const float* texel = level_texel(pyramid, l, wx, wy);
            for (int k = 0; k < S; ++k) sum[k] += w * texel[k];
            weight_sum += w;
        }
    }
    if (weight_sum <= 0) {  // the ellipse missed every texel centre: fall back to bilinear
        const Texel<S> bilinear = sample_bilinear<S>(pyramid, l, s, t);
        for (int k = 0; k < S; ++k)
            acc[k] += level_weight * bilinear.v[k];  // (double accumulators)
        return;
    }
    for (int k = 0; k < S; ++k) acc[k] += level_weight * (sum[k] / weight_sum);
}

}  // namespace

template <class Texels>
void filter_ewa(const Texels& pyramid, float s, float t, const FootprintEllipse& footprint,
                const LookupOptions& options, float* out) {
    FootprintEllipse e = footprint;
    if (e.major_radius <= 1.0f) {  // magnification: reconstruct, don't blur
        lookup_level0_bilinear(pyramid, s, t, out);
        return;
    }
    // Clamp the anisotropy by growing the minor axis (pbrt-v4).
    const float max_aniso = std::max(1.0f, options.max_anisotropy);
    if (e.minor_radius * max_aniso < e.major_radius) {
        e.minor_radius = e.major_radius / max_aniso;
        e.matrix = e.from_axes();
    }
    const float lod =
        std::clamp(fast_log2(std::max(e.minor_radius, 1e-30f)) - 1.5f + options.lod_bias, 0.0f,
                   static_cast<float>(pyramid.max_level()));
    const int l0 = static_cast<int>(lod);
    const float w = l0 < pyramid.max_level() ? lod - static_cast<float>(l0) : 0.0f;
    dispatch_stride(pyramid.stride(), [&]<int S>() {
        double acc[S] = {};
        if (w < 1) accumulate_ewa_level<S>(pyramid, l0, s, t, e, 1 - w, acc);
        if (w > 0) accumulate_ewa_level<S>(pyramid, l0 + 1, s, t, e, w, acc);
        for (int k = 0; k < pyramid.channels(); ++k) out[k] = static_cast<float>(acc[k]);
    });
}

template void filter_ewa(const MipPyramid&, float, float, const FootprintEllipse&,
                         const LookupOptions&, float*);
template void filter_ewa(const TiledTexels&, float, float, const FootprintEllipse&,
                         const LookupOptions&, float*);

}  // namespace detail
}  // namespace footprint
