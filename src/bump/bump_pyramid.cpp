#include "bump/bump_pyramid.h"

#include <cmath>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "texture/downsample.h"

namespace footprint {

namespace {

constexpr int kMomentChannels = 5;  // μ'1, μ'2, M2'11, M2'12, M2'22

std::string texel_name(int x, int y) {
    return "(" + std::to_string(x) + ", " + std::to_string(y) + ")";
}

}  // namespace

Result<BumpPyramid> BumpPyramid::build(const Image& slopes, const BumpPyramidOptions& options) {
    if (slopes.empty() || slopes.width < 1 || slopes.height < 1) return Error{"slope map is empty"};
    if (slopes.channels != 2)
        return Error{"slope map has " + std::to_string(slopes.channels) +
                     " channels; expected 2 (b1, b2)"};
    const Sym2 k0 = options.micro_roughness;
    if (!k0.is_finite() || k0.xx < 0 || k0.yy < 0 || k0.determinant() < -1e-12f * (k0.xx + k0.yy))
        return Error{"micro-roughness [[" + std::to_string(k0.xx) + ", " + std::to_string(k0.xy) +
                     "], [" + std::to_string(k0.xy) + ", " + std::to_string(k0.yy) +
                     "]] is not a covariance (PSD)"};
    const Image& extra = options.micro_variance;
    if (!extra.empty()) {
        if (extra.channels != 1 || extra.width != slopes.width || extra.height != slopes.height)
            return Error{"micro-variance map is " + std::to_string(extra.width) + "×" +
                         std::to_string(extra.height) + "×" + std::to_string(extra.channels) +
                         "; expected 1 channel of the slope map's size " +
                         std::to_string(slopes.width) + "×" + std::to_string(slopes.height)};
        for (std::size_t i = 0; i < extra.pixels.size(); ++i)
            if (!(extra.pixels[i] >= 0) || !std::isfinite(extra.pixels[i]))
                return Error{"micro-variance texel " +
                             texel_name(static_cast<int>(i % extra.width),
                                        static_cast<int>(i / extra.width)) +
                             " is " + std::to_string(extra.pixels[i]) + "; expected finite ≥ 0"};
    }

    // The mean slope, in double (rows in parallel, combined in row order: deterministic).
    std::vector<double> row_sums(std::size_t(slopes.height) * 2, 0.0);
    parallel_for_each(0, slopes.height, [&](int y) {
        double s0 = 0, s1 = 0;
        for (int x = 0; x < slopes.width; ++x) {
            s0 += slopes.at(x, y, 0);
            s1 += slopes.at(x, y, 1);
        }
        row_sums[2 * y] = s0;
        row_sums[2 * y + 1] = s1;
    });
    double mean[2] = {0, 0};
    for (int y = 0; y < slopes.height; ++y) {
        mean[0] += row_sums[2 * y];
        mean[1] += row_sums[2 * y + 1];
    }
    mean[0] /= static_cast<double>(slopes.pixel_count());
    mean[1] /= static_cast<double>(slopes.pixel_count());
    if (!std::isfinite(mean[0]) || !std::isfinite(mean[1]))
        for (int y = 0; y < slopes.height; ++y)
            for (int x = 0; x < slopes.width; ++x)
                for (int c = 0; c < 2; ++c)
                    if (!std::isfinite(slopes.at(x, y, c)))
                        return Error{"slope map texel " + texel_name(x, y) +
                                     " has a non-finite slope (" +
                                     std::to_string(slopes.at(x, y, c)) + ")"};
    BumpPyramid p;
    p.options_ = options;
    p.options_.micro_variance = {};  // in level 0's moments now
    p.offset_ = {float(mean[0]), float(mean[1])};

    // Level 0: μ' and M2' = μ'μ'ᵀ + K_0, computed in double, stored as float.
    std::vector<Image> levels;
    levels.emplace_back(slopes.width, slopes.height, kMomentChannels);
    {
        Image& l0 = levels.back();
        parallel_for_each(std::size_t(0), slopes.pixel_count(), [&](std::size_t i) {
            const double m1 = slopes.pixels[2 * i] - double(p.offset_.x);
            const double m2 = slopes.pixels[2 * i + 1] - double(p.offset_.y);
            const double own = extra.empty() ? 0.0 : double(extra.pixels[i]);
            float* o = &l0.pixels[i * kMomentChannels];
            o[0] = float(m1);
            o[1] = float(m2);
            o[2] = float(m1 * m1 + k0.xx + own);
            o[3] = float(m1 * m2 + k0.xy);
            o[4] = float(m2 * m2 + k0.yy + own);
        });
    }

    // Coarser levels: the linear moment form of §5.3 in double, from the previous level.
    MipPyramidOptions po;
    po.wrap_s = options.wrap_s;
    po.wrap_t = options.wrap_t;
    po.downsample = options.downsample;
    std::vector<double> previous;  // level l−1 in double (empty for level 0: read the floats)
    int w = slopes.width, h = slopes.height;
    while (w > 1 || h > 1) {
        const int nw = std::max(1, w / 2), nh = std::max(1, h / 2);
        std::vector<double> next(std::size_t(nw) * nh * kMomentChannels);
        if (previous.empty())
            detail::downsample<float, double>(levels[0].pixels.data(), w, h, next.data(), nw, nh,
                                              kMomentChannels, po);
        else
            detail::downsample<double, double>(previous.data(), w, h, next.data(), nw, nh,
                                               kMomentChannels, po);
        Image level(nw, nh, kMomentChannels);
        parallel_for_each(std::size_t(0), next.size(),
                          [&](std::size_t i) { level.pixels[i] = float(next[i]); });
        levels.push_back(std::move(level));
        previous = std::move(next);
        w = nw;
        h = nh;
    }
    Result<MipPyramid> pyramid = MipPyramid::from_levels(levels, po);
    if (!pyramid) return pyramid.error();
    p.moments_ = std::move(*pyramid);
    return p;
}

Result<BumpPyramid> BumpPyramid::from_moment_levels(const std::vector<Image>& levels,
                                                    Vec2 slope_offset, WrapMode wrap_s,
                                                    WrapMode wrap_t) {
    if (levels.empty() || levels[0].channels != kMomentChannels)
        return Error{"a bump pyramid has 5 moment channels, not " +
                     std::to_string(levels.empty() ? 0 : levels[0].channels)};
    if (!std::isfinite(slope_offset.x) || !std::isfinite(slope_offset.y))
        return Error{"the slope offset is not finite"};
    BumpPyramid p;
    p.options_.wrap_s = wrap_s;
    p.options_.wrap_t = wrap_t;
    MipPyramidOptions po;
    po.wrap_s = wrap_s;
    po.wrap_t = wrap_t;
    Result<MipPyramid> moments = MipPyramid::from_levels(levels, po);
    if (!moments) return moments.error();
    p.moments_ = std::move(*moments);
    p.offset_ = slope_offset;
    return p;
}

SlopeStatistics slope_statistics(const float* m, Vec2 offset, const BumpLookupOptions& options) {
    // K = M2' − μ'μ'ᵀ (the offset cancels: K is invariant to a shift of the slopes).
    const double m1 = m[0], m2 = m[1];
    const Sym2 k{float(m[2] - m1 * m1), float(m[3] - m1 * m2), float(m[4] - m2 * m2)};
    SlopeStatistics st{Vec2{float(m1 + offset.x), float(m2 + offset.y)}, clamp_to_psd(k)};
    if (options.strength != 1) {
        st.mean = options.strength * st.mean;
        st.covariance = (options.strength * options.strength) * st.covariance;
    }
    st.covariance = st.covariance + options.micro_roughness;
    return st;
}

SlopeStatistics BumpPyramid::from_moments(const float* m) const {
    return slope_statistics(m, offset_, {});
}

SlopeStatistics BumpPyramid::statistics(int level, int x, int y) const {
    return from_moments(moments_.texel(level, x, y));
}

BumpPyramid BumpPyramid::scaled(float strength, Sym2 micro_roughness) const {
    // μ'' = s·μ', M2'' = s²·M2' + K_0 about the offset s·o: then μ'' + s·o = s·μ and
    // M2'' − μ''μ''ᵀ = s²·K + K_0.
    const double s = strength;
    const double added[3] = {micro_roughness.xx, micro_roughness.xy, micro_roughness.yy};
    std::vector<Image> levels;
    for (int l = 0; l < moments_.level_count(); ++l) {
        Image& level = levels.emplace_back(moments_.level_image(l));
        for (std::size_t i = 0; i < level.pixel_count(); ++i) {
            float* m = &level.pixels[i * kMomentChannels];
            for (int c = 0; c < 2; ++c) m[c] = float(s * m[c]);
            for (int c = 2; c < kMomentChannels; ++c) m[c] = float(s * s * m[c] + added[c - 2]);
        }
    }
    Result<BumpPyramid> p =
        from_moment_levels(levels, float(s) * offset_, options_.wrap_s, options_.wrap_t);
    p->options_ = options_;
    p->options_.micro_roughness = micro_roughness;
    return std::move(*p);
}

SlopeStatistics bump_lookup(const BumpPyramid& pyramid, const TextureCoords& coords,
                            const BumpLookupOptions& options) {
    float m[kMomentChannels];
    texture_lookup(pyramid.moments(), coords, options, m);
    return slope_statistics(m, pyramid.slope_offset(), options);
}

SlopeStatistics bump_lookup(const BumpPyramid& pyramid, float s, float t,
                            const FootprintEllipse& footprint, const BumpLookupOptions& options) {
    float m[kMomentChannels];
    texture_lookup(pyramid.moments(), s, t, footprint, options, m);
    return slope_statistics(m, pyramid.slope_offset(), options);
}

}  // namespace footprint
