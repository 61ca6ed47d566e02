#include "texture/texture_lookup.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "image/test_images.h"
#include "texture/ewa.h"

namespace footprint {
namespace {

constexpr TextureFilter kAllFilters[] = {
    TextureFilter::nearest,    TextureFilter::bilinear,           TextureFilter::trilinear,
    TextureFilter::brilinear,  TextureFilter::footprint_assembly, TextureFilter::ewa,
    TextureFilter::summed_area};

// A linear ramp is reproduced exactly by every filter whose kernel is symmetric about the centre;
// what remains is float rounding of values up to ~10 and of offsets up to ~100 texels.
constexpr float kRampTolerance = 2e-4f;
// EWA sums a sampled Gaussian, whose centroid is off by its aliasing term ≤ 4πσ²e^{−2π²σ²} ≈ 4e−3
// texel at its smallest σ (kEwaMinSigma); times the ramp's gradient (0.011 per texel) that is 5e−5.
constexpr float kEwaRampTolerance = kRampTolerance + 4e-3f * 0.011f;
// Values from pyramids of constant levels: blends of small integers in float.
constexpr float kLevelTolerance = 1e-5f;

Image ramp_image(int size) {
    Image image(size, size, 1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            image.at(x, y, 0) = 0.3f + 0.01f * float(x) + 0.005f * float(y);
    return image;
}

TEST(TextureLookup, LinearRampIsReproducedAwayFromBorders) {
    const int size = 512;
    MipPyramidOptions po;
    po.wrap_s = po.wrap_t = WrapMode::clamp;
    const MipPyramid pyramid = MipPyramid::build(ramp_image(size), po);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0, 1);
    for (TextureFilter filter : {TextureFilter::bilinear, TextureFilter::trilinear,
                                 TextureFilter::footprint_assembly, TextureFilter::ewa}) {
        LookupOptions options;
        options.filter = filter;
        for (int i = 0; i < 300; ++i) {
            const float s = 0.3f + 0.4f * u(rng), t = 0.3f + 0.4f * u(rng);
            const float major =
                0.2f * std::pow(200.0f, u(rng));  // up to 40 texels: kernels stay inside
            const FootprintEllipse e =
                make_footprint_ellipse(major, major / std::pow(32.0f, u(rng)), u(rng) * 3.2f);
            float got;
            texture_lookup(pyramid, s, t, e, options, &got);
            const float x = s * size - 0.5f, y = t * size - 0.5f;
            const float want = 0.3f + 0.01f * x + 0.005f * y;
            EXPECT_NEAR(got, want,
                        filter == TextureFilter::ewa ? kEwaRampTolerance : kRampTolerance)
                << to_string(filter) << " footprint " << i << " λ = " << e.major_radius << ","
                << e.minor_radius;
        }
    }
}

// A pyramid whose level l holds the constant l: a lookup returns the level it read.
MipPyramid level_index_pyramid(int size) {
    std::vector<Image> levels;
    for (int l = 0, w = size;; ++l, w = std::max(1, w / 2)) {
        levels.emplace_back(w, w, 1, float(l));
        if (w == 1) break;
    }
    return std::move(MipPyramid::from_levels(levels).value());
}

float lookup_value(const MipPyramid& p, const FootprintEllipse& e, const LookupOptions& options) {
    float v;
    texture_lookup(p, 0.37f, 0.61f, e, options, &v);
    return v;
}

TEST(TextureLookup, LevelSelection) {
    const MipPyramid p = level_index_pyramid(256);  // levels 0..8
    LookupOptions tri, fa, ewa;
    tri.filter = TextureFilter::trilinear;
    ewa.filter = TextureFilter::ewa;
    for (int k = 0; k <= 8; ++k) {
        const FootprintEllipse iso =
            make_footprint_ellipse(std::exp2(float(k)), std::exp2(float(k)), 0.2f);
        EXPECT_NEAR(lookup_value(p, iso, tri), k, kLevelTolerance);
        // Footprint assembly plans Λ = √(λ² + 1) from tr K = 2 on (footprint_assembly.h): one
        // probe at log2 Λ, half a level above level 0 for a one-texel footprint, converging on k.
        EXPECT_NEAR(lookup_value(p, iso, fa),
                    std::min(8.0f, 0.5f * std::log2(std::exp2(2.0f * k) + 1)), kLevelTolerance)
            << k;
        // EWA reads one and a half levels finer than the minor axis (ewa.h).
        EXPECT_NEAR(lookup_value(p, iso, ewa), std::max(0.0f, k - 1.5f), kLevelTolerance) << k;
    }
    // Half-way between levels 3 and 4: GL blends linearly, the remap by variance ((4^w − 1)/3 =
    // 1/3 at w = ½; footprint assembly's lod is log2 Λ = 3.5056).
    const FootprintEllipse half = make_footprint_ellipse(std::exp2(3.5f), std::exp2(3.5f), 1.0f);
    EXPECT_NEAR(lookup_value(p, half, tri), 3.5f, kLevelTolerance);
    const float half_lod = 0.5f * std::log2(128.0f + 1);
    EXPECT_NEAR(lookup_value(p, half, fa), half_lod, kLevelTolerance);
    fa.lod_blend = LodBlend::variance_matched;
    EXPECT_NEAR(lookup_value(p, half, fa), 3.0f + (std::exp2(2 * (half_lod - 3)) - 1) / 3,
                kLevelTolerance);
    fa.lod_blend = LodBlend::linear;

    // Spec Rule B with its own budget for the anisotropic cases below.
    fa.probe_rule = ProbeRule::moment_matched;
    fa.max_probes = 16;
    fa.lod_blend = LodBlend::linear;
    // Anisotropic: footprint assembly reads the minor axis' level (log2 Λ2 = log2 √17),
    // trilinear the major one's.
    const FootprintEllipse aniso = make_footprint_ellipse(16, 4, 0.7f);
    const float aniso_lod = 0.5f * std::log2(17.0f);
    EXPECT_NEAR(lookup_value(p, aniso, fa), aniso_lod, kLevelTolerance);
    EXPECT_NEAR(lookup_value(p, aniso, tri), 4.0f, kLevelTolerance);
    // Beyond the probe budget the level rises: λ = (64, 4), N_max = 16 → T_p = Λ1·√(3/258).
    const float tp = std::sqrt(64.0f * 64 + 1) * std::sqrt(3.0f / 258);
    EXPECT_NEAR(lookup_value(p, make_footprint_ellipse(64, 4, 0.7f), fa), std::log2(tp), 1e-4f);
    // lod_bias shifts every filter's level.
    fa.lod_bias = 1;
    EXPECT_NEAR(lookup_value(p, aniso, fa), aniso_lod + 1, kLevelTolerance);
    // Footprints larger than the texture read the coarsest level; magnification reads level 0.
    fa.lod_bias = 0;
    EXPECT_NEAR(lookup_value(p, make_footprint_ellipse(1e6f, 1e6f, 0), fa), 8.0f, kLevelTolerance);
    EXPECT_NEAR(lookup_value(p, make_footprint_ellipse(0.2f, 0.1f, 0), fa), 0.0f, kLevelTolerance);
    // From tr K = 1 to 2 the reconstruction's share ρ rises from 0 to 1 (footprint_assembly.h):
    // λ = 0.8 isotropic, ρ = 0.28, one probe at ½ log2(0.64 + 0.28) < 0, level 0; λ = 0.9,
    // ρ = 0.62, ½ log2(0.81 + 0.62) = 0.258.
    EXPECT_NEAR(lookup_value(p, make_footprint_ellipse(0.8f, 0.8f, 0), fa), 0.0f, kLevelTolerance);
    EXPECT_NEAR(lookup_value(p, make_footprint_ellipse(0.9f, 0.9f, 0), fa),
                0.5f * std::log2(0.81f + 0.62f), 1e-5f);
}

TEST(TextureLookup, TrilinearUsesTheGlRuleOnDerivatives) {
    const MipPyramid p = level_index_pyramid(256);
    LookupOptions tri;
    tri.filter = TextureFilter::trilinear;
    // ρ = max(|∂(X,Y)/∂x|, |∂(X,Y)/∂y|) = max(|(8, 6)|, |(0, 4)|) = 10 → lod log2(10).
    TextureCoords c{0.4f, 0.4f, 8.0f / 256, 6.0f / 256, 0, 4.0f / 256};
    float v;
    texture_lookup(p, c, tri, &v);
    EXPECT_NEAR(v, std::log2(10.0f), kLevelTolerance);
    // footprint_of: K = D Dᵀ with D = S·∂(s,t)/∂(x,y).
    const FootprintEllipse e = footprint_of(p, c);
    EXPECT_NEAR(e.matrix.xx, 64.0f, 1e-3f);
    EXPECT_NEAR(e.matrix.xy, 48.0f, 1e-3f);
    EXPECT_NEAR(e.matrix.yy, 36.0f + 16.0f, 1e-3f);
}

// Brilinear blends two levels only within brilinear_band of a transition (lod L + ½): at lod L + f
// it reads level L + clamp((f − ½)/band + ½, 0, 1). Band 1 is trilinear, band 0 the nearer level.
TEST(TextureLookup, BrilinearBlendsOnlyNearLevelTransitions) {
    const MipPyramid p = level_index_pyramid(256);
    auto at_lod = [&](float lod, float band, TextureFilter filter) {
        LookupOptions options;
        options.filter = filter;
        options.brilinear_band = band;
        const float d = std::exp2(lod) / 256;  // ρ = 2^lod level-0 texels per pixel
        float v;
        texture_lookup(p, TextureCoords{0.4f, 0.6f, d, 0, 0, d}, options, &v);
        return v;
    };
    for (float f : {0.0f, 0.1f, 0.3f, 0.4f, 0.5f, 0.55f, 0.6f, 0.7f, 0.9f}) {
        const float want = 3 + std::clamp((f - 0.5f) / 0.25f + 0.5f, 0.0f, 1.0f);
        EXPECT_NEAR(at_lod(3 + f, 0.25f, TextureFilter::brilinear), want, 1e-4f) << f;
        EXPECT_NEAR(at_lod(3 + f, 1.0f, TextureFilter::brilinear),
                    at_lod(3 + f, 1.0f, TextureFilter::trilinear), 1e-6f)
            << f;
        EXPECT_NEAR(at_lod(3 + f, 0.0f, TextureFilter::brilinear), f < 0.5f ? 3.0f : 4.0f, 1e-4f);
    }
    // Away from a transition it is one level's bilinear probe, bit for bit: a lookup at lod 3.1
    // equals trilinear's at exactly lod 3 on a random texture.
    const MipPyramid noise = MipPyramid::build(random_image(256, 256, 3, 5u));
    LookupOptions brilinear, trilinear;
    brilinear.filter = TextureFilter::brilinear;
    trilinear.filter = TextureFilter::trilinear;
    for (float s : {0.13f, 0.5f, 0.77f}) {
        float a[3], b[3];
        const float d31 = std::exp2(3.1f) / 256, d3 = 8.0f / 256;
        texture_lookup(noise, TextureCoords{s, 0.3f, d31, 0, 0, d31}, brilinear, a);
        texture_lookup(noise, TextureCoords{s, 0.3f, d3, 0, 0, d3}, trilinear, b);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(a[c], b[c]) << s;
    }
}

// Bilinear lookups near and across the edges equal bilinear interpolation of an explicitly
// wrap-extended copy of the image (built here independently of wrap_index).
TEST(TextureLookup, WrapModesAtTheEdges) {
    const int w = 5, h = 4;
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(0, 1);
    const Image image = random_image(w, h, 1, 1234u);
    for (WrapMode ws : {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror})
        for (WrapMode wt : {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror}) {
            // 5×5 copies of the texture around the original, mirrored or clamped as the modes say.
            const int ew = 5 * w, eh = 5 * h;
            auto source = [&](int i, int n, int copy, WrapMode mode) {
                if (mode == WrapMode::repeat) return i;
                if (mode == WrapMode::clamp) return copy < 2 ? 0 : copy > 2 ? n - 1 : i;
                return (copy % 2 == 0) ? i : n - 1 - i;  // mirror: odd copies reversed
            };
            Image extended(ew, eh, 1);
            for (int y = 0; y < eh; ++y)
                for (int x = 0; x < ew; ++x)
                    extended.at(x, y, 0) =
                        image.at(source(x % w, w, x / w, ws), source(y % h, h, y / h, wt), 0);
            MipPyramidOptions po;
            po.wrap_s = ws;
            po.wrap_t = wt;
            const MipPyramid p = MipPyramid::build(image, po);
            LookupOptions bilinear;
            bilinear.filter = TextureFilter::bilinear;
            for (int i = 0; i < 200; ++i) {
                const float s = -1.0f + 3.0f * u(rng), t = -1.0f + 3.0f * u(rng);
                float got;
                texture_lookup(p, s, t, FootprintEllipse{}, bilinear, &got);
                const float x = (s + 2) * w - 0.5f,
                            y = (t + 2) * h - 0.5f;  // in the extended image
                const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
                const float fx = x - x0, fy = y - y0;
                const float want = (1 - fx) * (1 - fy) * extended.at(x0, y0, 0) +
                                   fx * (1 - fy) * extended.at(x0 + 1, y0, 0) +
                                   (1 - fx) * fy * extended.at(x0, y0 + 1, 0) +
                                   fx * fy * extended.at(x0 + 1, y0 + 1, 0);
                EXPECT_NEAR(got, want, 1e-5f)
                    << to_string(ws) << "/" << to_string(wt) << " at " << s << "," << t;
            }
        }
}

TEST(TextureLookup, NearestAndBilinearAtTexelCentres) {
    Image image(4, 2, 2);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i);
    const MipPyramid p = MipPyramid::build(image);
    for (TextureFilter f : {TextureFilter::nearest, TextureFilter::bilinear}) {
        LookupOptions o;
        o.filter = f;
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 4; ++x) {
                float v[2];
                // Texel (x, y) has its centre at s = (x + ½)/W (spec §1).
                texture_lookup(p, (x + 0.5f) / 4, (y + 0.5f) / 2, FootprintEllipse{}, o, v);
                EXPECT_EQ(v[0], image.at(x, y, 0));
                EXPECT_EQ(v[1], image.at(x, y, 1));
            }
    }
}

TEST(TextureLookup, DegenerateInputsGiveFiniteValues) {
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0, 1);
    const Image image = random_image(33, 17, 3, 1234u);
    const float inf = std::numeric_limits<float>::infinity(),
                nan = std::numeric_limits<float>::quiet_NaN();
    const float values[] = {0.0f, -0.0f, 1e-30f, -3.0f, 1e30f, -1e30f, inf, -inf, nan};
    for (WrapMode wrap : {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror}) {
        MipPyramidOptions po;
        po.wrap_s = po.wrap_t = wrap;
        po.summed_area_table = true;
        const MipPyramid p = MipPyramid::build(image, po);
        for (TextureFilter filter : kAllFilters) {
            LookupOptions options;
            options.filter = filter;
            for (float position : values)
                for (float derivative : values)
                    for (int pattern = 0; pattern < 4; ++pattern) {
                        TextureCoords c{0.5f, 0.25f, 0.01f, 0.0f, 0.0f, 0.01f};
                        if (pattern & 1) c.s = position;
                        if (pattern & 2) c.t = position;
                        c.dsdx = derivative;
                        c.dtdy = pattern == 3 ? derivative : 0.02f;
                        float v[3];
                        texture_lookup(p, c, options, v);
                        for (float x : v) {
                            ASSERT_TRUE(std::isfinite(x)) << to_string(filter) << " s=" << c.s
                                                          << " t=" << c.t << " d=" << derivative;
                            ASSERT_GE(x, -1e-5f);
                            ASSERT_LE(x, 1 + 1e-5f);
                        }
                    }
        }
    }
}

TEST(TextureLookup, BatchedLookupsEqualSingleLookups) {
    // texture_lookup_batch requests the texels of a group's probes and lines before reading any:
    // its results must be bit-identical to one call per lookup, for every filter and probe rule,
    // every wrap mode, row-major and tiled levels, 1 to 8 floats per texel, footprints from
    // magnification to 64:1 (one probe, short lines inside the level and across its edges, long
    // lines), degenerate input, and batch sizes that leave a partial last group.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0, 1);
    const float nan = std::numeric_limits<float>::quiet_NaN(),
                inf = std::numeric_limits<float>::infinity();
    std::vector<TextureCoords> coords(147);
    for (std::size_t i = 0; i < coords.size(); ++i) {
        TextureCoords& c = coords[i];
        const float size = std::exp2(-6 + 9 * u(rng));  // 1/64 … 8 texels of the 64² level 0
        const float anisotropy = i % 3 == 0 ? 1 : std::exp2(6 * u(rng));
        const float angle = 6.2831853f * u(rng);
        const float major = size * anisotropy / 64, minor = size / 64;
        c = {2 * u(rng) - 0.5f,       -0.5f + 2 * u(rng),       major * std::cos(angle),
             major * std::sin(angle), -minor * std::sin(angle), minor * std::cos(angle)};
        if (i % 17 == 3) c.dsdx = nan;
        if (i % 19 == 5) c.t = inf;
        if (i % 23 == 7) c.dsdx = c.dtdx = c.dsdy = c.dtdy = 0;
        if (i % 29 == 9) c.dtdy = 1e30f;
    }
    LookupOptions rule_b, gaussian, rule_a, texram, linear_blend;
    rule_b.probe_rule = ProbeRule::moment_matched;
    gaussian.probe_rule = ProbeRule::gaussian;
    rule_a.probe_rule = ProbeRule::ext;
    texram.probe_rule = ProbeRule::texram;
    linear_blend.lod_blend = LodBlend::linear;
    std::vector<LookupOptions> all_options = {rule_b, gaussian, rule_a, texram, linear_blend};
    for (TextureFilter filter : kAllFilters) {
        LookupOptions o;
        o.filter = filter;
        all_options.push_back(o);
    }
    for (int channels : {1, 2, 3, 4, 5})
        for (WrapMode wrap : {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror})
            for (int tile_log2 : {0, 2}) {
                MipPyramidOptions po;
                po.wrap_s = po.wrap_t = wrap;
                po.tile_log2 = tile_log2;
                po.summed_area_table = true;
                const MipPyramid p = MipPyramid::build(random_image(64, 64, channels, 99u), po);
                for (const LookupOptions& options : all_options)
                    for (std::size_t count : {std::size_t(1), std::size_t(16), coords.size()}) {
                        const std::span<const TextureCoords> batch(coords.data(), count);
                        std::vector<float> single(count * channels), batched(count * channels);
                        for (std::size_t i = 0; i < count; ++i)
                            texture_lookup(p, coords[i], options, &single[i * channels]);
                        texture_lookup_batch(p, batch, options, batched.data());
                        for (std::size_t i = 0; i < single.size(); ++i)
                            ASSERT_EQ(std::bit_cast<std::uint32_t>(single[i]),
                                      std::bit_cast<std::uint32_t>(batched[i]))
                                << to_string(options.filter) << " channels " << channels << " wrap "
                                << to_string(wrap) << " tiles " << tile_log2 << " rule "
                                << int(options.probe_rule) << " lookup " << i / channels;
                    }
            }
}

TEST(TextureLookup, FilterNamesRoundTrip) {
    for (TextureFilter f : kAllFilters) EXPECT_EQ(parse_texture_filter(to_string(f)), f);
    EXPECT_FALSE(parse_texture_filter("anisotropic").has_value());
}

}  // namespace
}  // namespace footprint
