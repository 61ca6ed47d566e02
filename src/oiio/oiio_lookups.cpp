#include "oiio/oiio_lookups.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace footprint::oiio::detail {

namespace {

using footprint::detail::OpenAs;
using footprint::detail::TexelReader;
using OIIO::TextureOpt;

constexpr int kMaxChannels = MipPyramid::kMaxChannels;

// OpenImageIO's wrap modes that footprint has too (its periodic_pow2 is periodic).
std::optional<WrapMode> footprint_wrap(TextureOpt::Wrap wrap) {
    switch (wrap) {
        case TextureOpt::WrapClamp:
            return WrapMode::clamp;
        case TextureOpt::WrapPeriodic:
        case TextureOpt::WrapPeriodicPow2:
            return WrapMode::repeat;
        case TextureOpt::WrapMirror:
            return WrapMode::mirror;
        default:
            return std::nullopt;  // black, periodic with a shared border: not footprint's
    }
}

// OpenImageIO's wrap rules on a texel index (valid: false means a black texel). Clamp, periodic
// and mirror are footprint's own (texture/wrap.h); black and the shared border are OpenImageIO's.
bool wrap_index(TextureOpt::Wrap wrap, int& i, int n) {
    if (const std::optional<WrapMode> mode = footprint_wrap(wrap)) {
        i = footprint::wrap_index(i, n, *mode);
        return true;
    }
    if (wrap == TextureOpt::WrapPeriodicSharedBorder) {
        // As OpenImageIO 2.4 computes it, the first and last columns being one position.
        const int period = std::max(n, 2) - 1;
        i %= period;
        if (i < 0) i += std::max(n, 2);
        return true;
    }
    return i >= 0 && i < n;  // black
}

TextureOpt::Wrap oiio_wrap(WrapMode mode) {
    switch (mode) {
        case WrapMode::clamp:
            return TextureOpt::WrapClamp;
        case WrapMode::repeat:
            return TextureOpt::WrapPeriodic;
        case WrapMode::mirror:
            return TextureOpt::WrapMirror;
    }
    return TextureOpt::WrapDefault;
}

TextureOpt::Wrap resolved(TextureOpt::Wrap asked, TextureOpt::Wrap file) {
    const TextureOpt::Wrap w = asked == TextureOpt::WrapDefault ? file : asked;
    return w == TextureOpt::WrapPeriodicPow2 ? TextureOpt::WrapPeriodic : w;
}

// ---- OpenImageIO's rules for the mip modes whose value it fixes (texture_lookup_nomip and
// texture_lookup_trilinear_mipmap in its texturesys.cpp), on footprint's texels.

// One level's sample: the channels from `first`, the derivatives ∂/∂s, ∂/∂t, and the weight of
// the taps that fell inside (for the fill of channels the file lacks, as OpenImageIO weighs it).
struct LevelSample {
    std::array<float, kMaxChannels> value{}, ds{}, dt{};
    float coverage = 0;
};
// What write_result() writes: a LevelSample's arrays, or a filter's.
struct SampleView {
    const float* value;
    const float* ds;
    const float* dt;
    float coverage;
};
SampleView view_of(const LevelSample& v) {
    return {v.value.data(), v.ds.data(), v.dt.data(), v.coverage};
}

LevelSample sample_closest(const TexelReader& texels, int level, float s, float t,
                           TextureOpt::Wrap ws, TextureOpt::Wrap wt, int first, int count) {
    const int w = texels.width(level), h = texels.height(level);
    const float x = s * static_cast<float>(w) - 0.5f, y = t * static_cast<float>(h) - 0.5f;
    int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
    if (x - std::floor(x) > 0.5f) ++i;
    if (y - std::floor(y) > 0.5f) ++j;
    LevelSample out;
    if (!(wrap_index(ws, i, w) & wrap_index(wt, j, h))) return out;
    const float* texel = texels.texel(level, i, j);
    for (int c = 0; c < count; ++c) out.value[c] = texel[first + c];
    out.coverage = 1;
    return out;
}

LevelSample sample_bilinear(const TexelReader& texels, int level, float s, float t,
                            TextureOpt::Wrap ws, TextureOpt::Wrap wt, int first, int count) {
    const int w = texels.width(level), h = texels.height(level);
    const float x = s * static_cast<float>(w) - 0.5f, y = t * static_cast<float>(h) - 0.5f;
    const float fx = x - std::floor(x), fy = y - std::floor(y);
    int i[2] = {static_cast<int>(std::floor(x)), 0}, j[2] = {static_cast<int>(std::floor(y)), 0};
    i[1] = i[0] + 1;
    j[1] = j[0] + 1;
    bool valid_i[2], valid_j[2];
    for (int k = 0; k < 2; ++k) {
        valid_i[k] = wrap_index(ws, i[k], w);
        valid_j[k] = wrap_index(wt, j[k], h);
    }
    // The four taps, a b above, c d below; a black tap is 0.
    static const std::array<float, kMaxChannels> kBlack{};
    const float* tap[2][2];
    for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a)
            tap[b][a] =
                valid_i[a] && valid_j[b] ? texels.texel(level, i[a], j[b]) + first : kBlack.data();
    LevelSample out;
    for (int c = 0; c < count; ++c) {
        const float a = tap[0][0][c], b = tap[0][1][c], cc = tap[1][0][c], d = tap[1][1][c];
        const float upper = a + fx * (b - a), lower = cc + fx * (d - cc);
        out.value[c] = upper + fy * (lower - upper);
        out.ds[c] = static_cast<float>(w) * ((b - a) + fy * ((d - cc) - (b - a)));
        out.dt[c] = static_cast<float>(h) * ((cc - a) + fx * ((d - b) - (cc - a)));
    }
    const auto inside = [&](int a, int b) { return valid_i[a] && valid_j[b] ? 1.0f : 0.0f; };
    const float upper = inside(0, 0) + fx * (inside(1, 0) - inside(0, 0));
    const float lower = inside(0, 1) + fx * (inside(1, 1) - inside(0, 1));
    out.coverage = upper + fy * (lower - upper);
    return out;
}

// OpenImageIO's adjust_width: derivatives scaled by the widths, degenerate ones made tiny.
void adjust_width(TexCoords& c, float swidth, float twidth) {
    c.dsdx *= swidth;
    c.dtdx *= twidth;
    c.dsdy *= swidth;
    c.dtdy *= twidth;
    constexpr float eps = 1.0e-8f, eps2 = eps * eps;
    const float dx2 = c.dsdx * c.dsdx + c.dtdx * c.dtdx, dy2 = c.dsdy * c.dsdy + c.dtdy * c.dtdy;
    if (dx2 < eps2) {
        if (dy2 < eps2) {
            c.dsdx = eps, c.dtdx = 0, c.dsdy = 0, c.dtdy = eps;
        } else {
            const float scale = eps / std::sqrt(dy2);
            c.dsdx = c.dtdy * scale;
            c.dtdx = -c.dsdy * scale;
        }
    } else if (dy2 < eps2) {
        const float scale = eps / std::sqrt(dx2);
        c.dsdy = -c.dtdx * scale;
        c.dtdy = c.dsdx * scale;
    }
}

struct LevelChoice {
    int level[2] = {0, 0};
    float weight[2] = {1, 0};
};

// compute_miplevels: the level where the filter's width falls to a texel, blended with the one
// before it by 2·width − 1 (not the GL rule's fraction of the log).
LevelChoice oiio_levels(const TexelReader& texels, const TextureOpt& options, float filtwidth) {
    LevelChoice choice;
    const int levels = texels.level_count();
    int found = -1;
    float blend = 0;
    for (int m = 0; m < levels; ++m) {
        const float width =
            filtwidth * static_cast<float>(std::min(texels.width(m), texels.height(m)));
        if (width <= 1.0f) {
            found = m;
            blend = std::clamp(2.0f * width - 1.0f, 0.0f, 1.0f);
            break;
        }
    }
    if (found < 0) {  // wider than the coarsest level
        choice.level[0] = choice.level[1] = levels - 1;
    } else if (found == 0 || options.mipmode == TextureOpt::MipModeNoMIP) {
        choice.level[0] = choice.level[1] = 0;  // finer than level 0
    } else if (options.mipmode == TextureOpt::MipModeOneLevel) {
        choice.level[0] = choice.level[1] = found;
    } else {
        choice.level[0] = found - 1;
        choice.level[1] = found;
        choice.weight[0] = 1.0f - blend;
        choice.weight[1] = blend;
    }
    return choice;
}

// The samples of `choice`'s levels, closest or bilinear, blended by its weights.
LevelSample sample_levels(const TexelReader& texels, const LevelChoice& choice,
                          TextureOpt::InterpMode interp, const TexCoords& c, TextureOpt::Wrap ws,
                          TextureOpt::Wrap wt, int first, int count) {
    LevelSample sum;
    for (int k = 0; k < 2; ++k) {
        if (choice.weight[k] == 0) continue;
        const LevelSample one =
            interp == TextureOpt::InterpClosest
                ? sample_closest(texels, choice.level[k], c.s, c.t, ws, wt, first, count)
                : sample_bilinear(texels, choice.level[k], c.s, c.t, ws, wt, first, count);
        const float w = choice.weight[k];
        for (int ch = 0; ch < count; ++ch) {
            sum.value[ch] += w * one.value[ch];
            sum.ds[ch] += w * one.ds[ch];
            sum.dt[ch] += w * one.dt[ch];
        }
        sum.coverage += w * one.coverage;
    }
    return sum;
}

// The value of a no-MIP, one-level or trilinear lookup: OpenImageIO's levels and weights,
// closest or bilinear samples (its smart bicubic is bilinear in these modes).
LevelSample oiio_rule_lookup(const TexelReader& texels, const TextureOpt& options, TexCoords c,
                             TextureOpt::Wrap ws, TextureOpt::Wrap wt, int first, int count) {
    LevelChoice choice;
    if (options.mipmode != TextureOpt::MipModeNoMIP) {
        adjust_width(c, options.swidth, options.twidth);
        const float sfilt = std::max(std::fabs(c.dsdx), std::fabs(c.dsdy));
        const float tfilt = std::max(std::fabs(c.dtdx), std::fabs(c.dtdy));
        float filtwidth =
            options.conservative_filter ? std::max(sfilt, tfilt) : std::min(sfilt, tfilt);
        filtwidth += std::max(options.sblur, options.tblur);
        choice = oiio_levels(texels, options, filtwidth);
    }
    return sample_levels(texels, choice, options.interpmode, c, ws, wt, first, count);
}

// ---- footprint assembly for the anisotropic mode.

// The footprint in level-0 texels, K = D Dᵀ with D = diag(W, H)·∂(s,t)/∂(x,y) (docs/method.md,
// "Conventions").
struct Covariance {
    double a = 0, b = 0, c = 0;  // [[a b] [b c]]
};
Covariance footprint_covariance(const TexCoords& c, float w, float h) {
    const double xs = c.dsdx * w, xt = c.dtdx * h, ys = c.dsdy * w, yt = c.dtdy * h;
    return {xs * xs + ys * ys, xs * xt + ys * yt, xt * xt + yt * yt};
}
// K's eigenvalues are the ellipse's squared semi-axes λ1² ≥ λ2², in texels²: m ± d, with m the
// mean of K's diagonal and d = √(h² + b²), h half its difference (K's entries, finite floats
// squared, cannot overflow a double). The routing compares them without the square root.
struct Eigen {
    double m, d2;  // m and d²
    explicit Eigen(const Covariance& k)
        : m(0.5 * (k.a + k.c)), d2(0.25 * (k.a - k.c) * (k.a - k.c) + k.b * k.b) {}
    // λ1 ≤ limit: d ≤ limit² − m.
    bool major_within(double limit) const {
        const double room = limit * limit - m;
        return room >= 0 && d2 <= room * room;
    }
    // λ1 ≤ ratio·λ2: (1 + ratio²)·d ≤ (ratio² − 1)·m.
    bool ratio_within(double ratio) const {
        const double r2 = ratio * ratio;
        return (1 + r2) * (1 + r2) * d2 <= (r2 - 1) * (r2 - 1) * m * m;
    }
    double major() const { return std::sqrt(m + std::sqrt(d2)); }
    double minor() const { return std::sqrt(std::max(0.0, m - std::sqrt(d2))); }
};
// Where a footprint lies against the texture's edges: the wrap modes matter only for a footprint
// whose texels reach beyond them. Its reach: the ellipse's extent, a wide margin for the probes'
// spread along the major axis and their bilinear taps at a coarser level.
enum class Reach { inside, straddles, outside };
Reach reach(double centre, double extent, double margin, int size) {
    const double r = 4 * extent + 2 * margin + 2;
    if (centre - r >= 0 && centre + r <= size) return Reach::inside;
    if (centre + r < 0 || centre - r > size) return Reach::outside;
    return Reach::straddles;
}

// How footprint_texture() answers a footprint in the anisotropic modes. Magnified: a smart-bicubic
// lookup that OpenImageIO reads from level 0 bicubically (a footprint of at most one texel), the
// delegate's. Isotropic: one trilinear probe, whatever the level rule, so it takes OpenImageIO's
// (its compute_miplevels on the ellipse's minor axis, as its anisotropic mode does), so that a
// mapping of N texels to a pixel reads level log2 N alone, as OpenImageIO's does and its test
// suite expects, where footprint assembly's rule would blend in some of the next level for the
// reconstruction's share (docs/method.md). Anisotropic: footprint assembly.
enum class Shape { magnified, isotropic, anisotropic };
Shape shape_of(const Eigen& axes, TextureOpt::InterpMode interp) {
    constexpr double kOneTexel = 1.001;   // 1:1 mappings, over the derivatives' rounding
    constexpr double kIsotropic = 1.001;  // footprint assembly's own one-probe ratio
    if (interp == TextureOpt::InterpSmartBicubic && axes.major_within(kOneTexel))
        return Shape::magnified;
    return axes.ratio_within(kIsotropic) ? Shape::isotropic : Shape::anisotropic;
}
// Footprint assembly with OpenImageIO's `anisotropic` as its probe budget.
LookupOptions assembly_options(const TextureOpt& options) {
    LookupOptions lookup;
    lookup.filter = TextureFilter::footprint_assembly;
    lookup.max_probes = std::clamp(options.anisotropic, 1, 1024);
    return lookup;
}

void write_result(const SampleView& v, int actual, int nchannels, const TextureOpt& options,
                  const FileFacts& facts, const Settings& settings, float* result, float* dresultds,
                  float* dresultdt) {
    for (int c = 0; c < nchannels; ++c) {
        result[c] = c < actual ? v.value[c] : options.fill * v.coverage;
        if (dresultds) {
            dresultds[c] = c < actual ? v.ds[c] : 0.0f;
            dresultdt[c] = c < actual ? v.dt[c] * (settings.flip_t ? -1.0f : 1.0f) : 0.0f;
        }
    }
    // gray_to_rgb (OpenImageIO's fill_gray_channels): one channel to RGB, two (R, A) to RRRA.
    if (actual < nchannels && options.firstchannel == 0 && settings.gray_to_rgb) {
        const int channels = facts.nchannels;
        const auto shuffle = [&](float* v) {
            if (!v) return;
            if (channels == 1 && nchannels >= 3) {
                v[1] = v[2] = v[0];
            } else if (channels == 2 && nchannels == 4 && facts.alpha_channel == 1) {
                const float alpha = v[1];
                v[1] = v[2] = v[0];
                v[3] = alpha;
            }
        };
        shuffle(result);
        shuffle(dresultds);
        shuffle(dresultdt);
    }
}

}  // namespace

static_assert(static_cast<int>(WrapMode::mirror) + 1 == Entries::kWrapModes);

TextureHandle* Entries::texture(footprint::TextureSystem& system, const OpenAs& as) {
    // Most lookups read the file's own entry, opened by an earlier one.
    const bool own = as.subimage == 0 && !as.wrap_s && !as.wrap_t;
    if (own && texture_ready_.load(std::memory_order_acquire)) return texture_;
    const auto opened = [&] {
        TextureHandle* entry = footprint::detail::texture_handle(system, file_, as);
        return system.info(entry) ? entry : nullptr;
    };
    if (as.subimage == 0 && as.wrap_s && as.wrap_t) {
        std::atomic<TextureHandle*>& slot =
            wrapped_[static_cast<int>(*as.wrap_s) * kWrapModes + static_cast<int>(*as.wrap_t)];
        TextureHandle* entry = slot.load(std::memory_order_acquire);
        if (!entry) {  // two threads may both open it: texture_handle() gives both the same
            entry = opened();
            slot.store(entry, std::memory_order_release);
        }
        return entry;
    }
    if (!own) return opened();
    std::call_once(texture_opened_, [&] {
        texture_ = opened();
        if (texture_) {
            const Result<TextureInfo> info = system.info(texture_);
            own_wraps_ = {oiio_wrap(info->wrap_s), oiio_wrap(info->wrap_t)};
        }
    });
    texture_ready_.store(true, std::memory_order_release);
    return texture_;
}

EnvironmentHandle* Entries::latlong(footprint::TextureSystem& system) {
    std::call_once(latlong_opened_, [&] {
        EnvironmentHandle* entry = system.environment_handle(file_);
        const Result<TextureSystem::EnvironmentShape> shape = system.environment_shape(entry);
        if (shape && shape->layout == EnvLayout::latlong) latlong_ = entry;
    });
    return latlong_;
}

std::optional<bool> footprint_texture(footprint::TextureSystem& system, Entries& file,
                                      const FileFacts& facts, const Settings& settings,
                                      const TextureOpt& options, TexCoords c, int nchannels,
                                      float* result, float* dresultds, float* dresultdt,
                                      std::string& error) {
    // What footprint does not answer: files OpenImageIO cannot open (it reports them), named
    // subimages, cropped or overscanned files, bicubic and stochastic modes.
    if (!facts.good || !options.subimagename.empty() || !facts.full_pixel_range ||
        facts.sample_border || options.interpmode == TextureOpt::InterpBicubic ||
        options.mipmode == TextureOpt::MipModeStochasticTrilinear ||
        options.mipmode == TextureOpt::MipModeStochasticAniso)
        return std::nullopt;
    const int first = options.firstchannel;
    const int actual = std::clamp(facts.nchannels - first, 0, nchannels);
    if (first + actual > kMaxChannels) return std::nullopt;
    const TextureOpt::Wrap ws = resolved(options.swrap, facts.swrap);
    const TextureOpt::Wrap wt = resolved(options.twrap, facts.twrap);
    if (settings.flip_t) {
        c.t = 1.0f - c.t;
        c.dtdx = -c.dtdx;
        c.dtdy = -c.dtdy;
    }
    const OpenAs subimage{options.subimage, std::nullopt, std::nullopt};
    const float w = static_cast<float>(facts.width), h = static_cast<float>(facts.height);

    const bool aniso = options.mipmode == TextureOpt::MipModeDefault ||
                       options.mipmode == TextureOpt::MipModeAniso;
    // A lookup by OpenImageIO's own level rules, `sample(texels)`, on footprint's texels.
    const auto by_oiio_rules = [&](const auto& sample) -> std::optional<bool> {
        TextureHandle* entry = file.texture(system, subimage);
        if (!entry) return std::nullopt;
        LevelSample value;
        const Status read = footprint::detail::read_texels(
            system, entry, [&](const TexelReader& texels) { value = sample(texels); });
        if (!read) {
            error = read.error().message;
            return false;
        }
        write_result(view_of(value), actual, nchannels, options, facts, settings, result, dresultds,
                     dresultdt);
        return true;
    };
    if (!aniso)
        return by_oiio_rules([&](const TexelReader& texels) {
            return oiio_rule_lookup(texels, options, c, ws, wt, first, actual);
        });

    // Footprint assembly. What stays OpenImageIO's: closest probes; blur, which OpenImageIO adds
    // to the ellipse's axes (its adjust_blur), not as a kernel; smart-bicubic lookups that
    // OpenImageIO reads from level 0 bicubically (a footprint of at most one texel); and files
    // larger than OpenImageIO's max_mip_res, whose finest levels it hides.
    if (options.interpmode == TextureOpt::InterpClosest || options.sblur != 0 ||
        options.tblur != 0 || std::max(facts.width, facts.height) > settings.max_mip_res)
        return std::nullopt;
    const TexCoords scaled{c.s,
                           c.t,
                           c.dsdx * options.swidth,
                           c.dtdx * options.twidth,
                           c.dsdy * options.swidth,
                           c.dtdy * options.twidth};
    const Covariance k = footprint_covariance(scaled, w, h);
    const Eigen axes(k);
    const Shape shape = shape_of(axes, options.interpmode);
    if (shape == Shape::magnified) return std::nullopt;
    if (shape == Shape::isotropic) {
        const float minor_st =
            static_cast<float>(axes.minor()) / static_cast<float>(std::max(w, h));
        return by_oiio_rules([&](const TexelReader& texels) {
            return sample_levels(texels, oiio_levels(texels, options, minor_st),
                                 TextureOpt::InterpBilinear, c, ws, wt, first, actual);
        });
    }
    // The file's own entry wraps as the file says, which is what a lookup asks for unless it
    // names other modes; then those matter only where the footprint's texels reach an edge.
    TextureHandle* entry = file.texture(system, subimage);
    if (!entry) return std::nullopt;
    if (options.subimage != 0 || !file.wraps_as_own(ws, wt)) {
        const std::optional<WrapMode> wrap_s = footprint_wrap(ws), wrap_t = footprint_wrap(wt);
        const double major = axes.major();
        const Reach reach_s = reach(c.s * w, std::sqrt(k.a), major, facts.width);
        const Reach reach_t = reach(c.t * h, std::sqrt(k.c), major, facts.height);
        if (reach_s != Reach::inside || reach_t != Reach::inside) {
            const bool black_s = ws == TextureOpt::WrapBlack, black_t = wt == TextureOpt::WrapBlack;
            if ((black_s && reach_s == Reach::outside) || (black_t && reach_t == Reach::outside)) {
                // All black, as OpenImageIO's every tap is.
                write_result(view_of(LevelSample{}), actual, nchannels, options, facts, settings,
                             result, dresultds, dresultdt);
                return true;
            }
            if (!wrap_s || !wrap_t) return std::nullopt;
            entry = file.texture(system, {options.subimage, wrap_s, wrap_t});
            if (!entry) return std::nullopt;
        }
    }
    const LookupOptions lookup = assembly_options(options);
    // The lookup writes channels 0 to first + actual: the result is the last `actual` of them.
    const auto filtered = [&](float s, float t, std::array<float, kMaxChannels>& all) {
        return system.texture(entry, {s, t, scaled.dsdx, scaled.dtdx, scaled.dsdy, scaled.dtdy},
                              lookup, std::span<float>(all.data(), first + actual));
    };
    std::array<float, kMaxChannels> value, ds, dt;
    if (Status s = filtered(c.s, c.t, value); !s) {
        error = s.error().message;
        return false;
    }
    if (dresultds) {
        // The filtered result's derivatives by central differences over half the footprint
        // (at least half a texel): the slope of what the filter returns, as OpenImageIO's are
        // of what its probes return.
        const float hs = 0.5f * std::max(static_cast<float>(std::sqrt(k.a)), 1.0f) / w;
        const float ht = 0.5f * std::max(static_cast<float>(std::sqrt(k.c)), 1.0f) / h;
        std::array<float, kMaxChannels> lo{}, hi{};
        (void)filtered(c.s - hs, c.t, lo);
        (void)filtered(c.s + hs, c.t, hi);
        for (int ch = first; ch < first + actual; ++ch) ds[ch] = (hi[ch] - lo[ch]) / (2 * hs);
        (void)filtered(c.s, c.t - ht, lo);
        (void)filtered(c.s, c.t + ht, hi);
        for (int ch = first; ch < first + actual; ++ch) dt[ch] = (hi[ch] - lo[ch]) / (2 * ht);
    }
    write_result({value.data() + first, ds.data() + first, dt.data() + first, 1}, actual, nchannels,
                 options, facts, settings, result, dresultds, dresultdt);
    return true;
}

TextureHandle* direct_entry(footprint::TextureSystem& system, Entries& file,
                            const FileFacts& facts) {
    if (!facts.good || !facts.full_pixel_range || facts.sample_border ||
        facts.nchannels > kMaxChannels)
        return nullptr;
    TextureHandle* entry = file.texture(system, {});
    const TextureOpt::Wrap ws = resolved(TextureOpt::WrapDefault, facts.swrap);
    const TextureOpt::Wrap wt = resolved(TextureOpt::WrapDefault, facts.twrap);
    return entry && file.wraps_as_own(ws, wt) ? entry : nullptr;
}

std::optional<bool> direct_texture(footprint::TextureSystem& system, TextureHandle* entry,
                                   int width, int height, const TextureOpt& options,
                                   const TexCoords& c, int nchannels, float* result,
                                   std::string& error) {
    const Eigen axes(
        footprint_covariance(c, static_cast<float>(width), static_cast<float>(height)));
    if (shape_of(axes, options.interpmode) != Shape::anisotropic) return std::nullopt;
    const Status s = system.texture(entry, {c.s, c.t, c.dsdx, c.dtdx, c.dsdy, c.dtdy},
                                    assembly_options(options), std::span<float>(result, nchannels));
    if (!s) error = s.error().message;
    return static_cast<bool>(s);
}

std::optional<bool> footprint_environment(footprint::TextureSystem& system, Entries& file,
                                          const FileFacts& facts, const TextureOpt& options,
                                          Imath::V3f R, Imath::V3f dRdx, Imath::V3f dRdy,
                                          int nchannels, float* result, float* dresultds,
                                          float* dresultdt, std::string& error) {
    // footprint answers the anisotropic modes of plain lat-long maps (2:1, one subimage, no
    // sample border), without blur or result derivatives.
    const bool aniso = options.mipmode == TextureOpt::MipModeDefault ||
                       options.mipmode == TextureOpt::MipModeAniso;
    if (!facts.good || facts.cube || facts.sample_border || !facts.full_pixel_range || !aniso ||
        options.subimage != 0 || !options.subimagename.empty() || dresultds || dresultdt ||
        options.sblur != 0 || options.tblur != 0 ||
        options.interpmode == TextureOpt::InterpClosest ||
        options.interpmode == TextureOpt::InterpBicubic || facts.width != 2 * facts.height)
        return std::nullopt;
    const int first = options.firstchannel;
    const int actual = std::clamp(facts.nchannels - first, 0, nchannels);
    if (first + actual > kMaxChannels) return std::nullopt;
    // OpenImageIO's smart bicubic where the map is magnified (a pixel's angle below a texel's).
    const Imath::V3f unit = R.normalized();
    const float angle = std::min((R + dRdx).normalized().cross(unit).length(),
                                 (R + dRdy).normalized().cross(unit).length());
    if (options.interpmode == TextureOpt::InterpSmartBicubic &&
        angle * static_cast<float>(facts.height) < static_cast<float>(M_PI))
        return std::nullopt;
    // OpenImageIO's lat-long convention in footprint's (docs/library.md): y up, s = 0.5 at −z,
    // which is footprint's direction (−x, y, −z); z up turns (x, y, z) into y-up's (−y, z, x).
    const auto to_footprint = [&](const Imath::V3f& v) {
        const Imath::V3f up = facts.y_up ? v : Imath::V3f(-v.y, v.z, v.x);
        return Vec3{-up.x, up.y, -up.z};
    };
    EnvironmentHandle* entry = file.latlong(system);
    if (!entry) return std::nullopt;
    EnvLookupOptions lookup;
    lookup.filter = TextureFilter::footprint_assembly;
    lookup.max_probes = std::clamp(options.anisotropic, 1, 1024);
    std::array<float, kMaxChannels> all{};
    const Status status = system.environment(
        entry, to_footprint(R), to_footprint(dRdx * options.swidth),
        to_footprint(dRdy * options.twidth), lookup, std::span<float>(all.data(), first + actual));
    if (!status) {
        error = status.error().message;
        return false;
    }
    for (int c = 0; c < nchannels; ++c) result[c] = c < actual ? all[first + c] : options.fill;
    return true;
}

std::string check_options(const TextureOpt& options, int subimages) {
    static constexpr const char* names[] = {"sblur", "tblur", "swidth", "twidth", "fill"};
    const float values[] = {options.sblur, options.tblur, options.swidth, options.twidth,
                            options.fill};
    if (!values_in_range(values, 5)) return check_values(names, values, 5);
    for (int k = 0; k < 4; ++k)
        if (values[k] < 0)
            return std::string(names[k]) + " = " + std::to_string(values[k]) + " is negative";
    if (options.firstchannel < 0)
        return "firstchannel = " + std::to_string(options.firstchannel) + " is negative";
    if (options.subimagename.empty() && (options.subimage < 0 || options.subimage >= subimages))
        return "subimage " + std::to_string(options.subimage) + " is out of range (the file has " +
               std::to_string(subimages) + ")";
    if (options.anisotropic < 1)
        return "anisotropic = " + std::to_string(options.anisotropic) + " is below 1";
    const auto wrap_ok = [](int w) {
        return w >= TextureOpt::WrapDefault && w < TextureOpt::WrapLast;
    };
    if (!wrap_ok(options.swrap) || !wrap_ok(options.twrap))
        return "a wrap mode is not one of OpenImageIO's";
    if (options.mipmode < TextureOpt::MipModeDefault ||
        options.mipmode > TextureOpt::MipModeStochasticAniso)
        return "mipmode " + std::to_string(options.mipmode) + " is not one of OpenImageIO's";
    if (options.interpmode < TextureOpt::InterpClosest ||
        options.interpmode > TextureOpt::InterpSmartBicubic)
        return "interpmode " + std::to_string(options.interpmode) + " is not one of OpenImageIO's";
    return {};
}

std::string check_values(const char* const* names, const float* values, int count) {
    for (int k = 0; k < count; ++k) {
        if (!std::isfinite(values[k]))
            return std::string(names[k]) + " = " + std::to_string(values[k]) + " is not finite";
        if (std::fabs(values[k]) > 1e15f)
            return std::string(names[k]) + " = " + std::to_string(values[k]) + " is too large";
    }
    return {};
}

}  // namespace footprint::oiio::detail
