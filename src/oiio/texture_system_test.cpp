// The OpenImageIO adapter against OpenImageIO's own TextureSystem, in one process, on the same
// files: where both define the same value they agree within the rounding of the files' texels.
#include "oiio/texture_system.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/test_temp_dir.h"
#include "texture/reference_filter.h"

namespace footprint {
namespace {

using OIIO::ImageBuf;
using OIIO::ImageSpec;
using OIIO::TextureOpt;
using OIIO::TypeDesc;
using OIIO::ustring;

// Agreement of two float lookups of the same texels: float rounding of a few blended taps.
constexpr float kSameValue = 2e-5f;
// Of derivatives, which scale a texel difference by the level's width (64 here).
constexpr float kSameDerivative = 2e-3f;

struct Systems {
    OIIO::TextureSystem* oiio = OIIO::TextureSystem::create(/*shared=*/false);
    OIIO::TextureSystem* ours = footprint::oiio::create_texture_system();
    Systems() {
        // The adapter MIP-maps unmipped files; OpenImageIO as a host would configure it to.
        oiio->attribute("automip", 1);
    }
    ~Systems() {
        OIIO::TextureSystem::destroy(oiio, /*teardown_imagecache=*/true);
        footprint::oiio::destroy_texture_system(ours);
    }
};

// A 64×64 texture of noise (`channels` channels), written by OpenImageIO's maketx as `format`.
std::string make_tx(const test::TempDir& dir, const std::string& name, TypeDesc format,
                    const std::string& wrap = "black", int channels = 3, int size = 64) {
    ImageBuf image(ImageSpec(size, size, channels, TypeDesc::FLOAT));
    std::mt19937 random(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            float v[4];
            for (int c = 0; c < channels; ++c) v[c] = u(random);
            image.setpixel(x, y, v, channels);
        }
    ImageSpec config;
    config.format = format;
    config.attribute("wrapmodes", wrap);
    const std::string file = (dir / name).string();
    EXPECT_TRUE(
        OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, image, file, config))
        << OIIO::geterror();
    return file;
}

float random_in(std::mt19937& random, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(random);
}

// The same texture() call on both systems; expects the results (and derivatives) to agree.
void expect_same_texture(Systems& systems, const std::string& file, TextureOpt options, float s,
                         float t, float dsdx, float dtdx, float dsdy, float dtdy, int nchannels,
                         bool derivatives, const std::string& what) {
    float expected[8], got[8], eds[8], edt[8], gds[8], gdt[8];
    TextureOpt o1 = options, o2 = options;
    const bool ok1 =
        systems.oiio->texture(ustring(file), o1, s, t, dsdx, dtdx, dsdy, dtdy, nchannels, expected,
                              derivatives ? eds : nullptr, derivatives ? edt : nullptr);
    const bool ok2 =
        systems.ours->texture(ustring(file), o2, s, t, dsdx, dtdx, dsdy, dtdy, nchannels, got,
                              derivatives ? gds : nullptr, derivatives ? gdt : nullptr);
    ASSERT_EQ(ok1, ok2) << what << ": " << systems.ours->geterror();
    for (int c = 0; c < nchannels; ++c) {
        EXPECT_NEAR(got[c], expected[c], kSameValue)
            << what << " channel " << c << " at (" << s << ", " << t << ")";
        if (derivatives) {
            EXPECT_NEAR(gds[c], eds[c], kSameDerivative) << what << " d/ds channel " << c;
            EXPECT_NEAR(gdt[c], edt[c], kSameDerivative) << what << " d/dt channel " << c;
        }
    }
}

// A texture of `width`×`height` texels whose texel (x, y) (row y from the top, OpenImageIO's
// t = 0) is value(x, y, channel), written by maketx as `kind` with `wrap` modes (none: maketx's).
template <class Value>
std::string make_tx_of(
    const test::TempDir& dir, const std::string& name, int width, int height, int channels,
    const Value& value, const std::string& wrap = "periodic",
    OIIO::ImageBufAlgo::MakeTextureMode kind = OIIO::ImageBufAlgo::MakeTxTexture) {
    ImageBuf image(ImageSpec(width, height, channels, TypeDesc::FLOAT));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float v[4];
            for (int c = 0; c < channels; ++c) v[c] = value(x, y, c);
            image.setpixel(x, y, v, channels);
        }
    ImageSpec config;
    if (!wrap.empty()) config.attribute("wrapmodes", wrap);
    const std::string file = (dir / name).string();
    EXPECT_TRUE(OIIO::ImageBufAlgo::make_texture(kind, image, file, config)) << OIIO::geterror();
    return file;
}

TEST(OiioAdapter, ClosestBilinearOneLevelAndTrilinearAgreeWithOpenImageIO) {
    test::TempDir dir;
    Systems systems;
    for (const TypeDesc format : {TypeDesc::FLOAT, TypeDesc::UINT8, TypeDesc::HALF}) {
        const std::string file =
            make_tx(dir, "noise-" + std::string(format.c_str()) + ".tx", format, "periodic,clamp");
        std::mt19937 random(1);
        for (const auto mip : {TextureOpt::MipModeNoMIP, TextureOpt::MipModeOneLevel,
                               TextureOpt::MipModeTrilinear}) {
            for (const auto interp : {TextureOpt::InterpClosest, TextureOpt::InterpBilinear,
                                      TextureOpt::InterpSmartBicubic}) {
                for (int k = 0; k < 200; ++k) {
                    TextureOpt options;
                    options.mipmode = mip;
                    options.interpmode = interp;
                    const float d = std::exp2(random_in(random, -9, 0));
                    const float aspect = random_in(random, 1, 3);
                    expect_same_texture(systems, file, options, random_in(random, -0.5f, 1.5f),
                                        random_in(random, -0.5f, 1.5f), d * aspect, 0, 0, d, 3,
                                        interp != TextureOpt::InterpClosest,
                                        "mipmode " + std::to_string(mip) + " interp " +
                                            std::to_string(interp) + " " + format.c_str());
                }
            }
        }
    }
}

TEST(OiioAdapter, EveryWrapModeAgreesWithOpenImageIO) {
    test::TempDir dir;
    Systems systems;
    const std::string file = make_tx(dir, "noise.tx", TypeDesc::FLOAT);
    std::mt19937 random(2);
    for (const auto wrap : {TextureOpt::WrapDefault, TextureOpt::WrapBlack, TextureOpt::WrapClamp,
                            TextureOpt::WrapPeriodic, TextureOpt::WrapMirror,
                            TextureOpt::WrapPeriodicPow2, TextureOpt::WrapPeriodicSharedBorder}) {
        for (int k = 0; k < 300; ++k) {
            TextureOpt options;
            options.mipmode = TextureOpt::MipModeNoMIP;
            options.interpmode = TextureOpt::InterpBilinear;
            options.swrap = wrap;
            options.twrap = k % 2 ? wrap : TextureOpt::WrapClamp;
            expect_same_texture(systems, file, options, random_in(random, -2.5f, 3.5f),
                                random_in(random, -2.5f, 3.5f), 0, 0, 0, 0, 3, true,
                                "wrap " + std::to_string(wrap));
        }
    }
}

TEST(OiioAdapter, FillFirstchannelAndGrayToRgbAgreeWithOpenImageIO) {
    test::TempDir dir;
    Systems systems;
    const std::string rgb = make_tx(dir, "rgb.tx", TypeDesc::FLOAT, "clamp");
    const std::string gray = make_tx(dir, "gray.tx", TypeDesc::UINT8, "clamp", 1);
    for (int gray_to_rgb = 0; gray_to_rgb < 2; ++gray_to_rgb) {
        systems.oiio->attribute("gray_to_rgb", gray_to_rgb);
        systems.ours->attribute("gray_to_rgb", gray_to_rgb);
        for (int first = 0; first < 4; ++first) {
            TextureOpt options;
            options.mipmode = TextureOpt::MipModeTrilinear;
            options.interpmode = TextureOpt::InterpBilinear;
            options.fill = 0.25f;
            options.firstchannel = first;
            for (const std::string& file : {rgb, gray})
                expect_same_texture(systems, file, options, 0.3f, 0.6f, 0.01f, 0, 0, 0.01f, 5,
                                    false, file + " firstchannel " + std::to_string(first));
        }
    }
}

TEST(OiioAdapter, ResultDerivativesOfARampAgreeWithOpenImageIO) {
    test::TempDir dir;
    ImageBuf ramp(ImageSpec(64, 64, 1, TypeDesc::FLOAT));
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float v = 0.5f * static_cast<float>(x) / 64 + 0.25f * static_cast<float>(y) / 64;
            ramp.setpixel(x, y, &v, 1);
        }
    ImageSpec config;
    config.attribute("wrapmodes", "clamp,clamp");
    const std::string file = (dir / "ramp.tx").string();
    ASSERT_TRUE(
        OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, ramp, file, config));
    Systems systems;
    for (const auto mip :
         {TextureOpt::MipModeNoMIP, TextureOpt::MipModeTrilinear, TextureOpt::MipModeDefault}) {
        TextureOpt options;
        options.mipmode = mip;
        options.interpmode = TextureOpt::InterpBilinear;
        float value, ds, dt;
        ASSERT_TRUE(systems.ours->texture(ustring(file), options, 0.5f, 0.5f, 0.02f, 0, 0, 0.02f, 1,
                                          &value, &ds, &dt));
        // The ramp's slope: 0.5 per unit of s, 0.25 per unit of t, whichever filter reads it.
        EXPECT_NEAR(ds, 0.5f, 0.01f) << "mipmode " << mip;
        EXPECT_NEAR(dt, 0.25f, 0.01f) << "mipmode " << mip;
        if (mip != TextureOpt::MipModeDefault)
            expect_same_texture(systems, file, options, 0.43f, 0.57f, 0.02f, 0, 0, 0.02f, 1, true,
                                "ramp mipmode " + std::to_string(mip));
    }
}

TEST(OiioAdapter, MissingFilesAndMissingColorAgreeWithOpenImageIO) {
    test::TempDir dir;
    Systems systems;
    const std::string missing = (dir / "no-such-file.tx").string();
    TextureOpt options;
    float got[3], expected[3];
    EXPECT_FALSE(systems.ours->texture(ustring(missing), options, 0.5f, 0.5f, 0, 0, 0, 0, 3, got));
    const std::string message = systems.ours->geterror();
    EXPECT_NE(message.find("no-such-file.tx"), std::string::npos) << message;
    const float red[3] = {1, 0, 0};
    options.missingcolor = red;
    TextureOpt o2 = options;
    EXPECT_TRUE(systems.ours->texture(ustring(missing), options, 0.5f, 0.5f, 0, 0, 0, 0, 3, got));
    EXPECT_TRUE(systems.oiio->texture(ustring(missing), o2, 0.5f, 0.5f, 0, 0, 0, 0, 3, expected));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(got[c], expected[c]);
}

TEST(OiioAdapter, LatLongEnvironmentComesOutInOpenImageIOsOrientation) {
    test::TempDir dir;
    // A lat-long map whose texels are their own positions, so that a wrong axis shows.
    ImageBuf image(ImageSpec(128, 64, 3, TypeDesc::FLOAT));
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 128; ++x) {
            const float v[3] = {static_cast<float>(x) / 128, static_cast<float>(y) / 64,
                                0.5f + 0.5f * std::sin(0.3f * static_cast<float>(x * y))};
            image.setpixel(x, y, v, 3);
        }
    const std::string file = (dir / "sky.tx").string();
    ImageSpec config;
    ASSERT_TRUE(
        OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxEnvLatl, image, file, config))
        << OIIO::geterror();
    Systems systems;
    std::mt19937 random(3);
    int compared = 0;
    for (int k = 0; k < 400; ++k) {
        const Imath::V3f R(random_in(random, -1, 1), random_in(random, -1, 1),
                           random_in(random, -1, 1));
        if (R.length() < 0.1f) continue;
        // Away from the poles and the seam, where the two differ by design: footprint reads the
        // 30° around each pole from its polar caps (docs/environment-maps.md), OpenImageIO
        // fades to a pole colour.
        const Imath::V3f n = R.normalized();
        if (std::fabs(n.y) > 0.85f || (n.z < 0 && std::fabs(n.x) < 0.05f)) continue;
        TextureOpt options;
        options.interpmode = TextureOpt::InterpBilinear;
        TextureOpt o2 = options;
        const Imath::V3f tiny(0, 0, 0);
        float expected[3], got[3];
        ASSERT_TRUE(systems.oiio->environment(ustring(file), options, R, tiny, tiny, 3, expected));
        ASSERT_TRUE(systems.ours->environment(ustring(file), o2, R, tiny, tiny, 3, got))
            << systems.ours->geterror();
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], expected[c], 1e-3f) << "R = " << R << " channel " << c;
        ++compared;
    }
    EXPECT_GT(compared, 200);
}

TEST(OiioAdapter, BatchesGiveTheirLanesSingleLookups) {
    test::TempDir dir;
    Systems systems;
    const std::string file = make_tx(dir, "noise.tx", TypeDesc::FLOAT, "periodic");
    constexpr int W = OIIO::Tex::BatchWidth;
    std::mt19937 random(4);
    float s[W], t[W], dsdx[W], dtdx[W], dsdy[W], dtdy[W];
    for (int i = 0; i < W; ++i) {
        s[i] = random_in(random, 0, 1), t[i] = random_in(random, 0, 1);
        dsdx[i] = random_in(random, 0.001f, 0.05f), dtdy[i] = random_in(random, 0.001f, 0.05f);
        dtdx[i] = dsdy[i] = 0;
    }
    OIIO::TextureOptBatch batch;
    for (int i = 0; i < W; ++i)
        batch.sblur[i] = batch.tblur[i] = 0, batch.swidth[i] = batch.twidth[i] = 1;
    const OIIO::Tex::RunMask mask = 0x5555 & ((OIIO::Tex::RunMask(1) << W) - 1);
    float result[3 * W] = {}, ds[3 * W] = {}, dt[3 * W] = {};
    ASSERT_TRUE(systems.ours->texture(ustring(file), batch, mask, s, t, dsdx, dtdx, dsdy, dtdy, 3,
                                      result, ds, dt));
    for (int i = 0; i < W; ++i) {
        if (!(mask & (OIIO::Tex::RunMask(1) << i))) continue;
        TextureOpt options;
        float one[3], one_ds[3], one_dt[3];
        ASSERT_TRUE(systems.ours->texture(ustring(file), options, s[i], t[i], dsdx[i], dtdx[i],
                                          dsdy[i], dtdy[i], 3, one, one_ds, one_dt));
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(result[c * W + i], one[c]) << "lane " << i;
            EXPECT_EQ(ds[c * W + i], one_ds[c]) << "lane " << i;
            EXPECT_EQ(dt[c * W + i], one_dt[c]) << "lane " << i;
        }
    }
}

TEST(OiioAdapter, HostileArgumentsReturnFalseWithAMessageNeverACrash) {
    test::TempDir dir;
    Systems systems;
    const std::string file = make_tx(dir, "noise.tx", TypeDesc::FLOAT);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    float result[8];
    const auto refused = [&](TextureOpt options, float s, float t, float d, int nchannels,
                             const std::string& word) {
        const bool ok =
            systems.ours->texture(ustring(file), options, s, t, d, 0, 0, d, nchannels, result);
        const std::string message = systems.ours->geterror();
        EXPECT_FALSE(ok) << word;
        EXPECT_NE(message.find(word), std::string::npos) << message;
        EXPECT_NE(message.find("noise.tx"), std::string::npos) << message;
    };
    TextureOpt options;
    refused(options, nan, 0.5f, 0.01f, 3, "s = nan");
    refused(options, 0.5f, inf, 0.01f, 3, "t = inf");
    refused(options, 0.5f, 0.5f, 1e30f, 3, "too large");
    refused(options, 0.5f, 0.5f, -inf, 3, "dsdx");
    refused(options, 0.5f, 0.5f, 0.01f, -1, "nchannels");
    TextureOpt bad = options;
    bad.subimage = 99;
    refused(bad, 0.5f, 0.5f, 0.01f, 3, "subimage 99");
    bad = options;
    bad.sblur = 1e9f * 1e9f;
    refused(bad, 0.5f, 0.5f, 0.01f, 3, "sblur");
    bad = options;
    bad.swidth = -1;
    refused(bad, 0.5f, 0.5f, 0.01f, 3, "swidth");
    bad = options;
    bad.anisotropic = 0;
    refused(bad, 0.5f, 0.5f, 0.01f, 3, "anisotropic");
    bad = options;
    bad.firstchannel = -2;
    refused(bad, 0.5f, 0.5f, 0.01f, 3, "firstchannel");
    // A handle that is not the adapter's.
    OIIO::TextureSystem::TextureHandle* foreign = systems.oiio->get_texture_handle(ustring(file));
    EXPECT_FALSE(
        systems.ours->texture(foreign, nullptr, options, 0.5f, 0.5f, 0, 0, 0, 0, 3, result));
    EXPECT_NE(systems.ours->geterror().find("handle"), std::string::npos);
    // Extreme but finite values are looked up.
    for (const float d : {0.0f, 1e-30f, 1e6f}) {
        TextureOpt any = options;
        EXPECT_TRUE(systems.ours->texture(ustring(file), any, 0.5f, 0.5f, d, d, d, d, 3, result));
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(result[c]));
    }
}

// ---- Footprint assembly against brute force.

// Strongly anisotropic footprints on a texture of fine oblique waves, against the brute-force
// reference filter (texture/reference_filter.h): level 0's bilinear reconstruction integrated
// against a Gaussian of covariance K/4, K = D Dᵀ with D the lookup's Jacobian in level-0 texels
// (its derivatives times the texture's size), i.e. the ellipse the two pixel steps span, filtered
// by a σ = ½-pixel Gaussian. RMSE over all lookups. Measured: the adapter 0.0070, OpenImageIO
// 0.0106. Of the references scaled by 0.4 to 1.45, OpenImageIO is closest to the unscaled one
// (0.0106; 0.0111 at 1.15): both aim at the same footprint, and the adapter's is the closer.
constexpr double kAnisoAdapterRmse = 0.010;
constexpr double kAnisoOpenImageIORmse = 0.02;  // bounded too: the comparison is set up right
constexpr double kAnisoAdvantage = 0.8;         // adapter RMSE ≤ this × OpenImageIO's
// The reference of a mirrored (t the wrong way) or transposed (s and t swapped) footprint is at
// least this many times farther from the adapter than the right one (measured: 8.7 and 8.1).
constexpr double kWrongAxisFactor = 4;

TEST(OiioAdapter, AnisotropicIsCloserToBruteForceThanOpenImageIO) {
    test::TempDir dir;
    constexpr int kSize = 256;
    // Two plane waves of periods 5.5 and 4.8 texels, whole numbers of cycles across the texture
    // (so that it tiles) and oblique, so that a footprint and its mirror image or its transpose
    // average them differently.
    const auto waves = [](int x, int y, int) {
        const double u = static_cast<double>(x) / kSize, v = static_cast<double>(y) / kSize;
        return static_cast<float>(0.5 + 0.25 * std::sin(2 * M_PI * (40 * u + 23 * v)) +
                                  0.2 * std::sin(2 * M_PI * (-17 * u + 51 * v) + 1.0));
    };
    // The reference reads the same texels, row 0 at the top as OpenImageIO's t = 0.
    Image level0(kSize, kSize, 1);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) level0.at(x, y, 0) = waves(x, y, 0);
    const std::string file = make_tx_of(dir, "waves.tx", kSize, kSize, 1, waves, "periodic");
    Systems systems;
    std::mt19937 random(5);
    double adapter_sq = 0, oiio_sq = 0, mirrored_sq = 0, transposed_sq = 0;
    int n = 0;
    // OpenImageIO's t runs down the rows; with flip_t it runs up them, at t' = 1 − t.
    for (const int flip_t : {0, 1}) {
        systems.oiio->attribute("flip_t", flip_t);
        systems.ours->attribute("flip_t", flip_t);
        for (int k = 0; k < 192; ++k) {
            // 16 orientations over half a turn, anisotropy 8, 12 and 16 (below the default
            // `anisotropic` 32, so that neither clamps it), minor semi-axis 0.6 to 2.5 texels.
            const float angle = static_cast<float>(M_PI) * static_cast<float>(k % 16) / 16 +
                                random_in(random, 0, 0.1f);
            const float ratio = 8.0f + 4.0f * static_cast<float>((k / 16) % 3);
            const float minor = random_in(random, 0.6f, 2.5f), major = ratio * minor;
            const float s = random_in(random, 0, 1), t = random_in(random, 0, 1);
            // The Jacobian's columns in texels, the images of one pixel step in x and in y: the
            // major axis in x for half the lookups, in y for the others.
            Vec2 dx{major * std::cos(angle), major * std::sin(angle)};
            Vec2 dy{-minor * std::sin(angle), minor * std::cos(angle)};
            if (k % 2) std::swap(dx, dy);
            const float dsdx = dx.x / kSize, dtdx = dx.y / kSize, dsdy = dy.x / kSize,
                        dtdy = dy.y / kSize;
            TextureOpt o1, o2;  // the default: mipmode aniso
            float adapter, oiio;
            ASSERT_TRUE(
                systems.ours->texture(ustring(file), o1, s, t, dsdx, dtdx, dsdy, dtdy, 1, &adapter))
                << systems.ours->geterror();
            ASSERT_TRUE(
                systems.oiio->texture(ustring(file), o2, s, t, dsdx, dtdx, dsdy, dtdy, 1, &oiio));
            // The footprint in the reference's rows: t's derivatives change sign with flip_t.
            const float row_t = flip_t ? 1 - t : t, sign = flip_t ? -1.0f : 1.0f;
            const auto reference = [&](Vec2 a, Vec2 b) {
                float value;
                reference_lookup(level0, s, row_t, make_footprint_ellipse(a, b), ReferenceOptions{},
                                 &value);
                return value;
            };
            const float want = reference({dx.x, sign * dx.y}, {dy.x, sign * dy.y});
            const float mirrored = reference({dx.x, -sign * dx.y}, {dy.x, -sign * dy.y});
            const float transposed = reference({dx.y, sign * dx.x}, {dy.y, sign * dy.x});
            adapter_sq += (adapter - want) * (adapter - want);
            oiio_sq += (oiio - want) * (oiio - want);
            mirrored_sq += (adapter - mirrored) * (adapter - mirrored);
            transposed_sq += (adapter - transposed) * (adapter - transposed);
            ++n;
        }
    }
    const double adapter_rmse = std::sqrt(adapter_sq / n), oiio_rmse = std::sqrt(oiio_sq / n);
    EXPECT_LT(adapter_rmse, kAnisoAdapterRmse);
    EXPECT_LT(oiio_rmse, kAnisoOpenImageIORmse);
    EXPECT_LT(adapter_rmse, kAnisoAdvantage * oiio_rmse)
        << "adapter " << adapter_rmse << ", OpenImageIO " << oiio_rmse;
    EXPECT_GT(std::sqrt(mirrored_sq / n), kWrongAxisFactor * adapter_rmse);
    EXPECT_GT(std::sqrt(transposed_sq / n), kWrongAxisFactor * adapter_rmse);
}

// A call with OpenImageIO's default options takes a shorter route through the adapter than one
// that names the file's own wrap modes or asks for derivatives; both must give the same bits, for
// every shape of footprint (magnified, isotropic, anisotropic) and for fewer channels than the
// file has. With flip_t, default options take the longer route too.
TEST(OiioAdapter, DefaultOptionsGiveTheBitsOfTheRoutedLookup) {
    test::TempDir dir;
    const std::string file = make_tx(dir, "periodic.tx", TypeDesc::HALF, "periodic", 4, 128);
    Systems systems;
    std::mt19937 random(11);
    int anisotropic = 0;
    for (const int flip_t : {0, 1}) {
        systems.ours->attribute("flip_t", flip_t);
        for (int k = 0; k < 300; ++k) {
            const float s = random_in(random, -1, 2), t = random_in(random, -1, 2);
            // Semi-axes from a tenth of a texel to 40 texels, at any angle and ratio.
            const float major = std::exp2(random_in(random, -3.3f, 5.3f)) / 128;
            const float minor = k % 5 == 0 ? major : major * random_in(random, 0.02f, 1.0f);
            const float angle = random_in(random, 0, static_cast<float>(M_PI));
            const float dsdx = major * std::cos(angle), dtdx = major * std::sin(angle);
            const float dsdy = -minor * std::sin(angle), dtdy = minor * std::cos(angle);
            anisotropic += major > 1.1f * minor && major * 128 > 1.5f;
            const int nchannels = 1 + k % 4;
            TextureOpt defaults, named, with_derivatives;
            named.swrap = named.twrap = TextureOpt::WrapPeriodic;
            float direct[4], routed[4], derived[4], ds[4], dt[4];
            ASSERT_TRUE(systems.ours->texture(ustring(file), defaults, s, t, dsdx, dtdx, dsdy, dtdy,
                                              nchannels, direct));
            ASSERT_TRUE(systems.ours->texture(ustring(file), named, s, t, dsdx, dtdx, dsdy, dtdy,
                                              nchannels, routed));
            ASSERT_TRUE(systems.ours->texture(ustring(file), with_derivatives, s, t, dsdx, dtdx,
                                              dsdy, dtdy, nchannels, derived, ds, dt));
            for (int c = 0; c < nchannels; ++c) {
                EXPECT_EQ(direct[c], routed[c]) << "lookup " << k << " channel " << c;
                EXPECT_EQ(direct[c], derived[c]) << "lookup " << k << " channel " << c;
            }
        }
    }
    EXPECT_GT(anisotropic, 200);  // most lookups are footprint assembly's
}

// ---- UDIM sets.

// The name of the file behind a handle, or "" for none.
std::string name_of(OIIO::TextureSystem* system, OIIO::TextureSystem::TextureHandle* handle) {
    return handle ? system->filename_from_handle(handle).string() : std::string();
}

TEST(OiioAdapter, UdimTilesResolveAsOpenImageIOResolvesThem) {
    test::TempDir dir;
    constexpr int kTile = 16;
    // Tiles 1001 (u 0, v 0), 1002 (u 1, v 0) and 1011 (u 0, v 1); 1012 (u 1, v 1) is missing.
    // Each tile has its own level, a ramp across s and a gentler one down t: a wrong tile, or
    // the right tile read at the wrong place or upside down, shows.
    const auto texel = [](int udim, int x, int y, int c) {
        const int u = (udim - 1001) % 10, v = (udim - 1001) / 10;
        return 0.25f * static_cast<float>(u + 2 * v) + 0.1f * static_cast<float>(x) / kTile +
               0.05f * static_cast<float>(y) / kTile + 0.01f * static_cast<float>(c);
    };
    std::map<int, std::string> tile_file;
    for (const int udim : {1001, 1002, 1011})
        tile_file[udim] = make_tx_of(
            dir, "tex." + std::to_string(udim) + ".tx", kTile, kTile, 3,
            [&](int x, int y, int c) { return texel(udim, x, y, c); }, "clamp");
    const ustring pattern((dir / "tex.<UDIM>.tx").string());
    Systems systems;
    OIIO::TextureSystem* ours = systems.ours;
    OIIO::TextureSystem* oiio = systems.oiio;

    EXPECT_TRUE(ours->is_udim(pattern));
    EXPECT_EQ(ours->is_udim(pattern), oiio->is_udim(pattern));
    EXPECT_FALSE(ours->is_udim(ustring(tile_file[1001])));
    EXPECT_TRUE(ours->is_udim(ours->get_texture_handle(pattern)));
    EXPECT_FALSE(ours->is_udim(ours->get_texture_handle(ustring(tile_file[1001]))));

    // resolve_udim: u tile from s, v tile from t, none for the missing tile or beyond the set.
    struct Where {
        float s, t;
        int udim;  // 0: no tile
    };
    for (const Where& at : {Where{0.5f, 0.5f, 1001}, Where{1.5f, 0.25f, 1002},
                            Where{0.25f, 1.5f, 1011}, Where{1.5f, 1.5f, 0}, Where{2.5f, 0.5f, 0},
                            Where{0.5f, 2.5f, 0}, Where{-0.5f, 0.5f, -1}}) {
        const std::string expected = name_of(oiio, oiio->resolve_udim(pattern, at.s, at.t));
        const std::string got = name_of(ours, ours->resolve_udim(pattern, at.s, at.t));
        const std::string by_handle =
            name_of(ours, ours->resolve_udim(ours->get_texture_handle(pattern),
                                             ours->get_perthread_info(), at.s, at.t));
        EXPECT_EQ(got, expected) << "at (" << at.s << ", " << at.t << ")";
        EXPECT_EQ(by_handle, expected) << "at (" << at.s << ", " << at.t << ")";
        if (at.udim >= 0) {  // -1: whatever OpenImageIO makes of a negative s
            EXPECT_EQ(got, at.udim ? tile_file[at.udim] : "") << at.s << ", " << at.t;
        }
    }
    // A file that is not a UDIM set resolves to itself.
    OIIO::TextureSystem::TextureHandle* plain = ours->get_texture_handle(ustring(tile_file[1002]));
    EXPECT_EQ(ours->resolve_udim(plain, nullptr, 0.5f, 0.5f), plain);

    // inventory_udim: 2 × 2 tiles, one of them empty.
    std::vector<ustring> expected_names, names, names_by_handle;
    int expected_nu = 0, expected_nv = 0, nu = 0, nv = 0, nu_h = 0, nv_h = 0;
    oiio->inventory_udim(pattern, expected_names, expected_nu, expected_nv);
    ours->inventory_udim(pattern, names, nu, nv);
    ours->inventory_udim(ours->get_texture_handle(pattern), nullptr, names_by_handle, nu_h, nv_h);
    EXPECT_EQ(names, expected_names);
    EXPECT_EQ(names_by_handle, expected_names);
    EXPECT_EQ(nu, expected_nu);
    EXPECT_EQ(nv, expected_nv);
    EXPECT_EQ(nu_h, expected_nu);
    EXPECT_EQ(nv_h, expected_nv);
    EXPECT_EQ(nu, 2);
    EXPECT_EQ(nv, 2);
    EXPECT_EQ(std::count_if(names.begin(), names.end(), [](ustring n) { return !n.empty(); }), 3);

    // Lookups through the pattern, the missing tile and beyond the set included: the same value
    // and return value as OpenImageIO's (float files: within float rounding).
    std::mt19937 random(6);
    for (const auto interp : {TextureOpt::InterpClosest, TextureOpt::InterpBilinear}) {
        for (const auto mip : {TextureOpt::MipModeNoMIP, TextureOpt::MipModeTrilinear}) {
            for (int k = 0; k < 100; ++k) {
                TextureOpt options;
                options.interpmode = interp;
                options.mipmode = mip;
                const float d = std::exp2(random_in(random, -8, -3));
                expect_same_texture(
                    systems, pattern.string(), options, random_in(random, -0.5f, 2.5f),
                    random_in(random, -0.5f, 2.5f), d, 0, 0, d, 3, false,
                    "UDIM interp " + std::to_string(interp) + " mipmode " + std::to_string(mip));
            }
        }
    }
    (void)ours->geterror();
    // Each tile's own texels, at the texel centres, channel by channel.
    for (const int udim : {1001, 1002, 1011}) {
        const int u = (udim - 1001) % 10, v = (udim - 1001) / 10;
        for (const auto& [x, y] : {std::pair{0, 0}, std::pair{13, 2}, std::pair{3, 11}}) {
            TextureOpt options;
            options.interpmode = TextureOpt::InterpClosest;
            options.mipmode = TextureOpt::MipModeNoMIP;
            float got[3];
            ASSERT_TRUE(ours->texture(pattern, options, u + (x + 0.5f) / kTile,
                                      v + (y + 0.5f) / kTile, 0, 0, 0, 0, 3, got))
                << ours->geterror();
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], texel(udim, x, y, c), kSameValue)
                    << "tile " << udim << " texel (" << x << ", " << y << ")";
        }
    }
    // The missing tile: false and the fill as OpenImageIO, or the missing colour (true).
    float got[3] = {9, 9, 9}, expected[3] = {9, 9, 9};
    TextureOpt o1, o2;
    EXPECT_EQ(ours->texture(pattern, o1, 1.5f, 1.5f, 0.01f, 0, 0, 0.01f, 3, got),
              oiio->texture(pattern, o2, 1.5f, 1.5f, 0.01f, 0, 0, 0.01f, 3, expected));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(got[c], expected[c]);
    (void)ours->geterror();
    (void)oiio->geterror();
    const float red[3] = {1, 0, 0};
    o1.missingcolor = o2.missingcolor = red;
    EXPECT_TRUE(ours->texture(pattern, o1, 1.5f, 1.5f, 0.01f, 0, 0, 0.01f, 3, got));
    EXPECT_TRUE(oiio->texture(pattern, o2, 1.5f, 1.5f, 0.01f, 0, 0, 0.01f, 3, expected));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(got[c], expected[c]);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(got[c], red[c]);

    // footprint assembly (the default mode) reads the resolved tile at the position within it:
    // the same as the tile's own lookup, bit for bit.
    for (int k = 0; k < 50; ++k) {
        const float s = random_in(random, 0, 2), t = random_in(random, 0, 1);
        const float d = std::exp2(random_in(random, -6, -3));
        const int udim = 1001 + static_cast<int>(s);
        TextureOpt a, b;
        float through_pattern[3], from_tile[3];
        ASSERT_TRUE(ours->texture(pattern, a, s, t, d, 0.3f * d, 0, d, 3, through_pattern));
        ASSERT_TRUE(ours->texture(ustring(tile_file[udim]), b, s - std::floor(s), t, d, 0.3f * d, 0,
                                  d, 3, from_tile));
        for (int c = 0; c < 3; ++c) EXPECT_EQ(through_pattern[c], from_tile[c]) << s << ", " << t;
    }
}

// ---- Batches and the deprecated multi-point forms.

// A lat-long map whose texels are their own positions (a wrong axis shows), 128 × 64.
std::string make_latlong(const test::TempDir& dir, const std::string& name) {
    return make_tx_of(
        dir, name, 128, 64, 3,
        [](int x, int y, int c) {
            return c == 0   ? static_cast<float>(x) / 128
                   : c == 1 ? static_cast<float>(y) / 64
                            : 0.5f + 0.5f * std::sin(0.3f * static_cast<float>(x * y));
        },
        "", OIIO::ImageBufAlgo::MakeTxEnvLatl);
}

// A direction away from the poles and the −z seam, where the adapter and OpenImageIO agree
// (LatLongEnvironmentComesOutInOpenImageIOsOrientation).
Imath::V3f random_direction(std::mt19937& random) {
    for (;;) {
        const Imath::V3f R(random_in(random, -1, 1), random_in(random, -1, 1),
                           random_in(random, -1, 1));
        if (R.length() < 0.1f) continue;
        const Imath::V3f n = R.normalized();
        if (std::fabs(n.y) > 0.85f || (n.z < 0 && std::fabs(n.x) < 0.05f)) continue;
        return R;
    }
}

// A small random vector: a ray differential.
Imath::V3f random_differential(std::mt19937& random, float size) {
    return Imath::V3f(random_in(random, -size, size), random_in(random, -size, size),
                      random_in(random, -size, size));
}

// Results' agreement where the adapter and OpenImageIO both read a lat-long map bilinearly.
constexpr float kSameEnvironment = 1e-3f;
// Untouched output: a value no lookup returns.
constexpr float kUntouched = -7.0f;

TEST(OiioAdapter, EnvironmentBatchesAndMultiPointFormsGiveTheirSingleLookups) {
    test::TempDir dir;
    const std::string sky = make_latlong(dir, "sky.tx");
    Systems systems;
    OIIO::TextureSystem* ours = systems.ours;
    constexpr int W = OIIO::Tex::BatchWidth;
    std::mt19937 random(8);
    Imath::V3f R[W], dRdx[W], dRdy[W];
    float R_soa[3 * W], dRdx_soa[3 * W], dRdy_soa[3 * W];  // x of every lane, then y, then z
    for (int i = 0; i < W; ++i) {
        R[i] = random_direction(random);
        // Some lanes magnified (the delegate's smart bicubic), most minified (footprint's).
        dRdx[i] = random_differential(random, i % 4 ? 0.08f : 0.002f);
        dRdy[i] = random_differential(random, i % 4 ? 0.08f : 0.002f);
        for (int a = 0; a < 3; ++a) {
            R_soa[a * W + i] = R[i][a];
            dRdx_soa[a * W + i] = dRdx[i][a];
            dRdy_soa[a * W + i] = dRdy[i][a];
        }
    }
    // Lanes 3 and 10 off; each lane its own width, so that a lane read with another's options
    // shows.
    const OIIO::Tex::RunMask mask =
        OIIO::Tex::RunMaskOn & ~(OIIO::Tex::RunMask(1) << 3 | OIIO::Tex::RunMask(1) << 10);
    OIIO::TextureOptBatch batch;
    for (int i = 0; i < W; ++i) {
        batch.sblur[i] = batch.tblur[i] = 0;
        batch.swidth[i] = 1 + 0.1f * static_cast<float>(i);
        batch.twidth[i] = 1 + 0.05f * static_cast<float>(i);
    }
    const auto single = [&](int i, float* out) {
        TextureOpt options;
        options.swidth = batch.swidth[i];
        options.twidth = batch.twidth[i];
        ASSERT_TRUE(ours->environment(ustring(sky), options, R[i], dRdx[i], dRdy[i], 3, out))
            << ours->geterror();
    };
    std::vector<float> by_name(3 * W, kUntouched), by_handle(3 * W, kUntouched);
    ASSERT_TRUE(
        ours->environment(ustring(sky), batch, mask, R_soa, dRdx_soa, dRdy_soa, 3, by_name.data()))
        << ours->geterror();
    ASSERT_TRUE(ours->environment(ours->get_texture_handle(ustring(sky)),
                                  ours->get_perthread_info(), batch, mask, R_soa, dRdx_soa,
                                  dRdy_soa, 3, by_handle.data()));
    for (int i = 0; i < W; ++i) {
        const bool on = mask & (OIIO::Tex::RunMask(1) << i);
        float one[3];
        single(i, one);
        for (int c = 0; c < 3; ++c) {
            // Channel c of lane i at c × W + i.
            EXPECT_EQ(by_name[c * W + i], on ? one[c] : kUntouched) << "lane " << i;
            EXPECT_EQ(by_handle[c * W + i], on ? one[c] : kUntouched) << "lane " << i;
        }
    }

    // The layout as OpenImageIO's own batch reads it: bilinear without derivatives, where the
    // two agree.
    {
        OIIO::TextureOptBatch bilinear = batch;
        bilinear.interpmode = OIIO::Tex::InterpMode::Bilinear;
        const float zero[3 * W] = {};
        std::vector<float> got(3 * W, kUntouched), expected(3 * W, kUntouched);
        ASSERT_TRUE(
            ours->environment(ustring(sky), bilinear, mask, R_soa, zero, zero, 3, got.data()));
        ASSERT_TRUE(systems.oiio->environment(ustring(sky), bilinear, mask, R_soa, zero, zero, 3,
                                              expected.data()));
        for (int k = 0; k < 3 * W; ++k) EXPECT_NEAR(got[k], expected[k], kSameEnvironment) << k;
    }

    // The deprecated multi-point form: points beginactive to endactive whose runflag is on, each
    // with its own widths, results point by point (3 floats each) from the start of `result`.
    OIIO_PRAGMA_WARNING_PUSH
    OIIO_GCC_PRAGMA(GCC diagnostic ignored "-Wdeprecated-declarations") {
        OIIO::Runflag runflags[W];
        for (int i = 0; i < W; ++i) runflags[i] = i % 5 == 2 ? OIIO::RunFlagOff : OIIO::RunFlagOn;
        const int begin = 1, end = W - 2;
        TextureOpt base;  // the TextureOptions refer to its fields
        OIIO::TextureOptions options(base);
        options.swidth.init(batch.swidth, sizeof(float));
        options.twidth.init(batch.twidth, sizeof(float));
        for (int by = 0; by < 2; ++by) {
            std::vector<float> got(3 * W, kUntouched);
            const bool ok =
                by == 0
                    ? ours->environment(ustring(sky), options, runflags, begin, end,
                                        OIIO::VaryingRef<Imath::V3f>(R, sizeof(Imath::V3f)),
                                        OIIO::VaryingRef<Imath::V3f>(dRdx, sizeof(Imath::V3f)),
                                        OIIO::VaryingRef<Imath::V3f>(dRdy, sizeof(Imath::V3f)), 3,
                                        got.data())
                    : ours->environment(
                          ours->get_texture_handle(ustring(sky)), nullptr, options, runflags, begin,
                          end, OIIO::VaryingRef<Imath::V3f>(R, sizeof(Imath::V3f)),
                          OIIO::VaryingRef<Imath::V3f>(dRdx, sizeof(Imath::V3f)),
                          OIIO::VaryingRef<Imath::V3f>(dRdy, sizeof(Imath::V3f)), 3, got.data());
            ASSERT_TRUE(ok) << ours->geterror();
            for (int i = 0; i < W; ++i) {
                const bool on = i >= begin && i < end && runflags[i];
                float one[3];
                single(i, one);
                for (int c = 0; c < 3; ++c)
                    EXPECT_EQ(got[3 * i + c], on ? one[c] : kUntouched) << "point " << i;
            }
        }
        // Against OpenImageIO's own multi-point form, bilinear without derivatives.
        TextureOpt bilinear_base;
        bilinear_base.interpmode = TextureOpt::InterpBilinear;
        OIIO::TextureOptions bilinear(bilinear_base);
        Imath::V3f zero(0, 0, 0);
        std::vector<float> got(3 * W, kUntouched), expected(3 * W, kUntouched);
        ASSERT_TRUE(ours->environment(ustring(sky), bilinear, runflags, begin, end,
                                      OIIO::VaryingRef<Imath::V3f>(R, sizeof(Imath::V3f)),
                                      OIIO::VaryingRef<Imath::V3f>(zero),
                                      OIIO::VaryingRef<Imath::V3f>(zero), 3, got.data()));
        ASSERT_TRUE(systems.oiio->environment(
            ustring(sky), bilinear, runflags, begin, end,
            OIIO::VaryingRef<Imath::V3f>(R, sizeof(Imath::V3f)), OIIO::VaryingRef<Imath::V3f>(zero),
            OIIO::VaryingRef<Imath::V3f>(zero), 3, expected.data()));
        for (int k = 0; k < 3 * W; ++k) EXPECT_NEAR(got[k], expected[k], kSameEnvironment) << k;
    }
    OIIO_PRAGMA_WARNING_POP
}

TEST(OiioAdapter, TextureMultiPointFormsGiveTheirSingleLookups) {
    test::TempDir dir;
    const std::string file = make_tx(dir, "noise.tx", TypeDesc::FLOAT, "periodic");
    Systems systems;
    OIIO::TextureSystem* ours = systems.ours;
    constexpr int N = 12;
    std::mt19937 random(9);
    float s[N], t[N], dsdx[N], dtdx[N], dsdy[N], dtdy[N], swidth[N], tblur[N];
    OIIO::Runflag runflags[N];
    for (int i = 0; i < N; ++i) {
        s[i] = random_in(random, 0, 1), t[i] = random_in(random, 0, 1);
        dsdx[i] = random_in(random, 0.002f, 0.08f), dtdx[i] = random_in(random, -0.01f, 0.01f);
        dsdy[i] = random_in(random, -0.01f, 0.01f), dtdy[i] = random_in(random, 0.002f, 0.03f);
        swidth[i] = 1 + 0.2f * static_cast<float>(i);  // per point: a lane mix-up shows
        tblur[i] = 0.002f * static_cast<float>(i % 3);
        runflags[i] = i % 4 == 1 ? OIIO::RunFlagOff : OIIO::RunFlagOn;
    }
    const int begin = 2, end = N - 1;
    OIIO_PRAGMA_WARNING_PUSH
    OIIO_GCC_PRAGMA(GCC diagnostic ignored "-Wdeprecated-declarations")
    // The default mode (footprint assembly) and trilinear (OpenImageIO's rule), each against the
    // single lookups bit for bit; trilinear against OpenImageIO's own multi-point form too.
    for (const auto mip : {TextureOpt::MipModeDefault, TextureOpt::MipModeTrilinear}) {
        TextureOpt base;
        base.mipmode = mip;
        base.interpmode = TextureOpt::InterpBilinear;
        OIIO::TextureOptions options(base);
        options.swidth.init(swidth, sizeof(float));
        options.tblur.init(tblur, sizeof(float));
        const auto varying = [](float* v) { return OIIO::VaryingRef<float>(v, sizeof(float)); };
        for (int by = 0; by < 2; ++by) {
            std::vector<float> got(3 * N, kUntouched), ds(3 * N, kUntouched), dt(3 * N, kUntouched);
            const bool ok =
                by == 0 ? ours->texture(ustring(file), options, runflags, begin, end, varying(s),
                                        varying(t), varying(dsdx), varying(dtdx), varying(dsdy),
                                        varying(dtdy), 3, got.data(), ds.data(), dt.data())
                        : ours->texture(ours->get_texture_handle(ustring(file)),
                                        ours->get_perthread_info(), options, runflags, begin, end,
                                        varying(s), varying(t), varying(dsdx), varying(dtdx),
                                        varying(dsdy), varying(dtdy), 3, got.data(), ds.data(),
                                        dt.data());
            ASSERT_TRUE(ok) << ours->geterror();
            for (int i = 0; i < N; ++i) {
                const bool on = i >= begin && i < end && runflags[i];
                TextureOpt one_options = base;
                one_options.swidth = swidth[i];
                one_options.tblur = tblur[i];
                float one[3], one_ds[3], one_dt[3];
                ASSERT_TRUE(ours->texture(ustring(file), one_options, s[i], t[i], dsdx[i], dtdx[i],
                                          dsdy[i], dtdy[i], 3, one, one_ds, one_dt));
                for (int c = 0; c < 3; ++c) {
                    EXPECT_EQ(got[3 * i + c], on ? one[c] : kUntouched) << "point " << i;
                    EXPECT_EQ(ds[3 * i + c], on ? one_ds[c] : kUntouched) << "point " << i;
                    EXPECT_EQ(dt[3 * i + c], on ? one_dt[c] : kUntouched) << "point " << i;
                }
            }
        }
        if (mip == TextureOpt::MipModeTrilinear) {
            std::vector<float> got(3 * N, kUntouched), expected(3 * N, kUntouched);
            ASSERT_TRUE(ours->texture(ustring(file), options, runflags, begin, end, varying(s),
                                      varying(t), varying(dsdx), varying(dtdx), varying(dsdy),
                                      varying(dtdy), 3, got.data()));
            ASSERT_TRUE(systems.oiio->texture(ustring(file), options, runflags, begin, end,
                                              varying(s), varying(t), varying(dsdx), varying(dtdx),
                                              varying(dsdy), varying(dtdy), 3, expected.data()));
            for (int k = 0; k < 3 * N; ++k) EXPECT_NEAR(got[k], expected[k], kSameValue) << k;
        }
    }
    OIIO_PRAGMA_WARNING_POP
}

// ---- Threads, per-thread info, statistics and metadata.

TEST(OiioAdapter, ThreadsWithTheirOwnInfoGetTheSingleThreadResults) {
    test::TempDir dir;
    const std::string file = make_tx(dir, "noise.tx", TypeDesc::FLOAT, "periodic", 3, 256);
    const std::string sky = make_latlong(dir, "sky.tx");
    // Texture lookups in every mode the adapter answers or delegates, and lat-long lookups.
    struct Lookup {
        TextureOpt::MipMode mip;
        TextureOpt::InterpMode interp;
        float s, t, dsdx, dtdx, dsdy, dtdy;
        Imath::V3f R, dRdx, dRdy;
    };
    constexpr int N = 240;
    std::vector<Lookup> lookups;
    std::mt19937 random(10);
    const TextureOpt::MipMode mips[] = {TextureOpt::MipModeDefault, TextureOpt::MipModeTrilinear,
                                        TextureOpt::MipModeNoMIP, TextureOpt::MipModeOneLevel};
    for (int k = 0; k < N; ++k) {
        const float d = std::exp2(random_in(random, -10, -1));
        lookups.push_back({mips[k % 4],
                           k % 3 ? TextureOpt::InterpSmartBicubic : TextureOpt::InterpBilinear,
                           random_in(random, -1, 2), random_in(random, -1, 2), d,
                           random_in(random, -0.5f, 0.5f) * d, random_in(random, -0.5f, 0.5f) * d,
                           random_in(random, 0.1f, 1) * d, random_direction(random),
                           random_differential(random, 0.05f), random_differential(random, 0.05f)});
    }
    // N texture results, then N environment results, 3 channels each.
    const auto run = [&](OIIO::TextureSystem* system, OIIO::TextureSystem::Perthread* info,
                         bool by_handle, std::vector<float>& out) {
        out.assign(6 * N, kUntouched);
        OIIO::TextureSystem::TextureHandle* texture =
            system->get_texture_handle(ustring(file), info);
        OIIO::TextureSystem::TextureHandle* environment =
            system->get_texture_handle(ustring(sky), info);
        for (int k = 0; k < N; ++k) {
            const Lookup& l = lookups[k];
            TextureOpt options;
            options.mipmode = l.mip;
            options.interpmode = l.interp;
            float* r = out.data() + 3 * k;
            if (by_handle)
                system->texture(texture, info, options, l.s, l.t, l.dsdx, l.dtdx, l.dsdy, l.dtdy, 3,
                                r);
            else
                system->texture(ustring(file), options, l.s, l.t, l.dsdx, l.dtdx, l.dsdy, l.dtdy, 3,
                                r);
            TextureOpt env_options;
            env_options.interpmode = TextureOpt::InterpBilinear;
            float* e = out.data() + 3 * (N + k);
            if (by_handle)
                system->environment(environment, info, env_options, l.R, l.dRdx, l.dRdy, 3, e);
            else
                system->environment(ustring(sky), env_options, l.R, l.dRdx, l.dRdy, 3, e);
        }
    };
    std::vector<float> reference;
    {
        OIIO::TextureSystem* alone = footprint::oiio::create_texture_system();
        run(alone, alone->get_perthread_info(), false, reference);
        footprint::oiio::destroy_texture_system(alone);
    }
    // A fresh system, so that the threads race to open the files and to read their tiles.
    OIIO::TextureSystem* shared = footprint::oiio::create_texture_system();
    constexpr int kThreads = 4;
    std::vector<std::vector<float>> results(kThreads);
    std::vector<std::thread> threads;
    for (int k = 0; k < kThreads; ++k)
        threads.emplace_back([&, k] {
            switch (k % 3) {
                case 0: {  // its own info, made and destroyed by the thread, lookups by handle
                    OIIO::TextureSystem::Perthread* info = shared->create_thread_info();
                    run(shared, info, true, results[k]);
                    shared->destroy_thread_info(info);
                    break;
                }
                case 1:  // the system's info for this thread, by handle
                    run(shared, shared->get_perthread_info(nullptr), true, results[k]);
                    break;
                default:  // by name
                    run(shared, nullptr, false, results[k]);
            }
        });
    for (std::thread& thread : threads) thread.join();
    for (int k = 0; k < kThreads; ++k) {
        int differ = 0;
        for (int i = 0; i < 6 * N; ++i) differ += results[k][i] != reference[i];
        EXPECT_EQ(differ, 0) << "thread " << k;
    }
    // getstats(): every call counted, from every thread, footprint's share and the delegate's
    // statistics; reset_stats() starts again.
    const std::string stats = shared->getstats();
    const std::string calls = std::to_string(kThreads * N);
    EXPECT_NE(stats.find("texture calls " + calls + ","), std::string::npos) << stats;
    EXPECT_NE(stats.find("environment calls " + calls + ","), std::string::npos) << stats;
    EXPECT_EQ(stats.find("answered by footprint 0\n"), std::string::npos) << stats;
    EXPECT_NE(stats.find("OpenImageIO"), std::string::npos) << stats;
    shared->reset_stats();
    EXPECT_NE(shared->getstats().find("texture calls 0,"), std::string::npos);
    footprint::oiio::destroy_texture_system(shared);
}

TEST(OiioAdapter, TextureInfoAgreesWithOpenImageIO) {
    test::TempDir dir;
    const std::string noise = make_tx(dir, "noise.tx", TypeDesc::FLOAT, "periodic,clamp");
    const std::string sky = make_latlong(dir, "sky.tx");
    // A constant image, which maketx detects and marks with its colour. OpenImageIO reports that
    // colour only from a file whose Software names maketx, as the maketx command writes it.
    std::string constant = (dir / "constant.tx").string();
    {
        ImageBuf image(ImageSpec(32, 32, 3, TypeDesc::FLOAT));
        OIIO::ImageBufAlgo::fill(image, {0.2f, 0.4f, 0.6f});
        ImageSpec config;
        config.attribute("maketx:constant_color_detect", 1);
        config.attribute("Software", "OpenImageIO maketx");
        ASSERT_TRUE(OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, image,
                                                     constant, config));
    }
    const std::string missing = (dir / "missing.tx").string();
    Systems systems;
    struct Query {
        const char* name;
        TypeDesc type;
    };
    const Query queries[] = {{"exists", TypeDesc::INT},
                             {"resolution", TypeDesc(TypeDesc::INT, 2)},
                             {"channels", TypeDesc::INT},
                             {"subimages", TypeDesc::INT},
                             {"miplevels", TypeDesc::INT},
                             {"datawindow", TypeDesc(TypeDesc::INT, 4)},
                             {"averagecolor", TypeDesc(TypeDesc::FLOAT, 3)},
                             {"constantcolor", TypeDesc(TypeDesc::FLOAT, 3)},
                             {"wrapmodes", TypeDesc::STRING},
                             {"textureformat", TypeDesc::STRING},
                             {"texturetype", TypeDesc::STRING}};
    for (const std::string& file : {noise, sky, constant, missing}) {
        for (const Query& q : queries) {
            for (int by = 0; by < 2; ++by) {
                // Room for 4 ints or floats, or a ustring; the same unwritten pattern on both.
                union Data {
                    int i[4];
                    float f[4];
                    const char* s;
                };
                Data got, expected;
                std::memset(&got, 0x5a, sizeof got);
                std::memset(&expected, 0x5a, sizeof expected);
                const bool ok_got = by == 0 ? systems.ours->get_texture_info(
                                                  ustring(file), 0, ustring(q.name), q.type, &got)
                                            : systems.ours->get_texture_info(
                                                  systems.ours->get_texture_handle(ustring(file)),
                                                  nullptr, 0, ustring(q.name), q.type, &got);
                const bool ok_expected =
                    by == 0 ? systems.oiio->get_texture_info(ustring(file), 0, ustring(q.name),
                                                             q.type, &expected)
                            : systems.oiio->get_texture_info(
                                  systems.oiio->get_texture_handle(ustring(file)), nullptr, 0,
                                  ustring(q.name), q.type, &expected);
                const std::string what = file + " " + q.name + (by ? " by handle" : "");
                EXPECT_EQ(ok_got, ok_expected) << what;
                if (!ok_expected) continue;
                if (q.type == TypeDesc::STRING)
                    EXPECT_STREQ(got.s, expected.s) << what;
                else
                    EXPECT_EQ(std::memcmp(&got, &expected, q.type.size()), 0) << what;
            }
        }
    }
    (void)systems.ours->geterror();
    (void)systems.oiio->geterror();
    // What they say: a 64 × 64 RGB texture, periodic in s, clamped in t; its average colour
    // that of uniform noise; the lat-long map is one; the constant file's colour; no file.
    int resolution[2] = {}, channels = 0, exists = -1;
    ustring wrapmodes, format;
    float average[3] = {}, colour[3] = {};
    OIIO::TextureSystem* ours = systems.ours;
    ASSERT_TRUE(ours->get_texture_info(ustring(noise), 0, ustring("resolution"),
                                       TypeDesc(TypeDesc::INT, 2), resolution));
    EXPECT_EQ(resolution[0], 64);
    EXPECT_EQ(resolution[1], 64);
    ASSERT_TRUE(
        ours->get_texture_info(ustring(noise), 0, ustring("channels"), TypeDesc::INT, &channels));
    EXPECT_EQ(channels, 3);
    ASSERT_TRUE(ours->get_texture_info(ustring(noise), 0, ustring("wrapmodes"), TypeDesc::STRING,
                                       &wrapmodes));
    EXPECT_EQ(wrapmodes, "periodic,clamp");
    ASSERT_TRUE(ours->get_texture_info(ustring(noise), 0, ustring("averagecolor"),
                                       TypeDesc(TypeDesc::FLOAT, 3), average));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(average[c], 0.5f, 0.05f);
    ASSERT_TRUE(ours->get_texture_info(ustring(noise), 0, ustring("textureformat"),
                                       TypeDesc::STRING, &format));
    EXPECT_EQ(format, "Plain Texture");
    ASSERT_TRUE(ours->get_texture_info(ustring(sky), 0, ustring("textureformat"), TypeDesc::STRING,
                                       &format));
    EXPECT_EQ(format, "LatLong Environment");
    ASSERT_TRUE(ours->get_texture_info(ustring(constant), 0, ustring("constantcolor"),
                                       TypeDesc(TypeDesc::FLOAT, 3), colour));
    EXPECT_NEAR(colour[0], 0.2f, kSameValue);
    EXPECT_NEAR(colour[1], 0.4f, kSameValue);
    EXPECT_NEAR(colour[2], 0.6f, kSameValue);
    ASSERT_TRUE(
        ours->get_texture_info(ustring(missing), 0, ustring("exists"), TypeDesc::INT, &exists));
    EXPECT_EQ(exists, 0);
    (void)ours->geterror();
}

// ---- Hostile arguments beyond texture()'s (HostileArgumentsReturnFalseWithAMessageNeverACrash).
// None of these is sent to OpenImageIO's own TextureSystem: 2.4.7 crashes on some
// (docs/library.md), and get_texels() runs a reversed range's memset past the buffer.

// Expects `ok` false and the thread's message to hold `word` and `file`'s name.
void expect_refused(OIIO::TextureSystem* system, bool ok, const std::string& word,
                    const std::string& file) {
    const std::string message = system->geterror();
    EXPECT_FALSE(ok) << word;
    EXPECT_NE(message.find(word), std::string::npos) << "'" << word << "' in: " << message;
    const std::string name = std::filesystem::path(file).filename().string();
    EXPECT_NE(message.find(name), std::string::npos) << "'" << name << "' in: " << message;
}

TEST(OiioAdapter, HostileEnvironmentArgumentsReturnFalseWithAMessage) {
    test::TempDir dir;
    const std::string sky = make_latlong(dir, "sky.tx");
    OIIO::TextureSystem* ours = footprint::oiio::create_texture_system();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const Imath::V3f R(0.3f, 0.2f, 1), d(0.01f, 0, 0), e(0, 0.01f, 0);
    float result[8], ds[8], dt[8];
    const auto lookup = [&](TextureOpt options, Imath::V3f r, Imath::V3f dx, Imath::V3f dy,
                            int nchannels = 3, float* out = nullptr) {
        return ours->environment(ustring(sky), options, r, dx, dy, nchannels, out ? out : result);
    };
    const TextureOpt plain;
    expect_refused(ours, lookup(plain, {nan, 0, 1}, d, e), "R.x = nan", sky);
    expect_refused(ours, lookup(plain, {0, inf, 1}, d, e), "R.y = inf", sky);
    expect_refused(ours, lookup(plain, {0, 0, 1e30f}, d, e), "R.z", sky);
    expect_refused(ours, lookup(plain, R, {0, nan, 0}, e), "dRdx.y = nan", sky);
    expect_refused(ours, lookup(plain, R, d, {0, 0, -inf}), "dRdy.z = -inf", sky);
    expect_refused(ours, lookup(plain, R, {1e30f, 0, 0}, e), "too large", sky);
    expect_refused(ours, lookup(plain, {0, 0, 0}, d, e), "zero", sky);
    TextureOpt bad = plain;
    bad.sblur = -0.5f;
    expect_refused(ours, lookup(bad, R, d, e), "sblur", sky);
    bad = plain;
    bad.twidth = -1;
    expect_refused(ours, lookup(bad, R, d, e), "twidth", sky);
    bad = plain;
    bad.anisotropic = 0;
    expect_refused(ours, lookup(bad, R, d, e), "anisotropic", sky);
    // The combinations that crash OpenImageIO 2.4.7: refused on the derivatives first.
    expect_refused(ours, lookup(bad, R, {1e30f, 1e30f, 0}, {0, 1e30f, 1e30f}), "dRdx", sky);
    bad = plain;
    bad.sblur = 1e9f;
    expect_refused(ours, lookup(bad, R, {inf, 0, 0}, {0, inf, 0}), "dRdx.x = inf", sky);
    bad = plain;
    bad.firstchannel = -1;
    expect_refused(ours, lookup(bad, R, d, e), "firstchannel", sky);
    bad = plain;
    bad.subimage = 99;
    expect_refused(ours, lookup(bad, R, d, e), "subimage 99", sky);
    bad = plain;
    // 7: within the enum's range (0 to 7), beyond OpenImageIO's modes (its table of lookup
    // functions has 7 entries).
    bad.mipmode = static_cast<TextureOpt::MipMode>(7);
    expect_refused(ours, lookup(bad, R, d, e), "mipmode 7", sky);
    expect_refused(ours, lookup(plain, R, d, e, -1), "nchannels", sky);
    expect_refused(ours, lookup(plain, R, d, e, 1 << 20), "nchannels", sky);
    {
        TextureOpt options;
        expect_refused(ours, ours->environment(ustring(sky), options, R, d, e, 3, nullptr),
                       "result", sky);
        expect_refused(ours, ours->environment(ustring(sky), options, R, d, e, 3, result, ds),
                       "together", sky);
    }
    // A first channel beyond the file's: every channel the fill, as OpenImageIO documents.
    TextureOpt beyond = plain;
    beyond.firstchannel = 99;
    beyond.fill = 0.25f;
    ASSERT_TRUE(lookup(beyond, R, d, e)) << ours->geterror();
    for (int c = 0; c < 3; ++c) EXPECT_EQ(result[c], 0.25f);
    // Extreme but finite values are looked up, and give finite values.
    for (const float size : {0.0f, 1e-30f, 1e6f}) {
        ASSERT_TRUE(lookup(plain, R, {size, 0, 0}, {0, size, size}, 3, result)) << ours->geterror();
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(result[c])) << size;
    }
    // With result derivatives (the delegate's).
    TextureOpt with_derivatives;
    ASSERT_TRUE(ours->environment(ustring(sky), with_derivatives, R, d, e, 3, result, ds, dt));
    footprint::oiio::destroy_texture_system(ours);
}

TEST(OiioAdapter, HostileTexelRequestsReturnFalseWithAMessage) {
    test::TempDir dir;
    const std::string file = make_tx(dir, "noise.tx", TypeDesc::FLOAT, "clamp");
    Systems systems;
    OIIO::TextureSystem* ours = systems.ours;
    std::vector<float> texels(64 * 64 * 4, kUntouched);
    const auto get = [&](int miplevel, int x0, int x1, int y0, int y1, int z0, int z1, int c0,
                         int c1, void* out, int subimage = 0) {
        TextureOpt options;
        options.subimage = subimage;
        return ours->get_texels(ustring(file), options, miplevel, x0, x1, y0, y1, z0, z1, c0, c1,
                                TypeDesc::FLOAT, out);
    };
    // A valid request: OpenImageIO's texels, row by row, and the checks refuse nothing of it.
    {
        std::vector<float> expected(4 * 4 * 3, kUntouched);
        TextureOpt options;
        ASSERT_TRUE(get(1, 2, 6, 3, 7, 0, 1, 0, 3, texels.data())) << ours->geterror();
        ASSERT_TRUE(systems.oiio->get_texels(ustring(file), options, 1, 2, 6, 3, 7, 0, 1, 0, 3,
                                             TypeDesc::FLOAT, expected.data()));
        for (int k = 0; k < 4 * 4 * 3; ++k) EXPECT_EQ(texels[k], expected[k]) << k;
        // An empty rectangle reads nothing, whatever `result` is.
        EXPECT_TRUE(get(0, 5, 5, 0, 4, 0, 1, 0, 3, nullptr)) << ours->geterror();
    }
    expect_refused(ours, get(99, 0, 4, 0, 4, 0, 1, 0, 3, texels.data()), "MIP level 99", file);
    expect_refused(ours, get(-1, 0, 4, 0, 4, 0, 1, 0, 3, texels.data()), "MIP level -1", file);
    expect_refused(ours, get(0, 4, 0, -2, 4, 0, 1, 0, 3, texels.data()), "xend", file);
    expect_refused(ours, get(0, 0, 4, 4, 0, 0, 1, 0, 3, texels.data()), "yend", file);
    expect_refused(ours, get(0, 0, 4, 0, 4, 1, 0, 0, 3, texels.data()), "zend", file);
    expect_refused(ours, get(0, 0, 4, 0, 4, 0, 1, -1, 3, texels.data()), "chbegin", file);
    expect_refused(ours, get(0, -1, 4, 0, 4, 0, 1, 3, 0, texels.data()), "chend", file);
    expect_refused(ours, get(0, 0, 4, 0, 4, 0, 1, 0, 3, nullptr), "result", file);
    expect_refused(ours, get(0, 0, 4, 0, 4, 0, 1, 0, 3, texels.data(), 99), "subimage 99", file);
    // Nothing was written by a refused request.
    for (std::size_t k = 4 * 4 * 3; k < texels.size(); ++k) ASSERT_EQ(texels[k], kUntouched) << k;
}

TEST(OiioAdapter, HostileBatchArgumentsReturnFalseWithAMessage) {
    test::TempDir dir;
    const std::string file = make_tx(dir, "noise.tx", TypeDesc::FLOAT, "periodic");
    const std::string sky = make_latlong(dir, "sky.tx");
    OIIO::TextureSystem* ours = footprint::oiio::create_texture_system();
    constexpr int W = OIIO::Tex::BatchWidth;
    constexpr OIIO::Tex::RunMask kAll = OIIO::Tex::RunMaskOn;  // every lane of the batch
    std::mt19937 random(11);
    float s[W], t[W], dsdx[W], dtdx[W], dsdy[W], dtdy[W], R[3 * W], dR[3 * W] = {};
    for (int i = 0; i < W; ++i) {
        s[i] = random_in(random, 0, 1), t[i] = random_in(random, 0, 1);
        dsdx[i] = dtdy[i] = random_in(random, 0.001f, 0.05f);
        dtdx[i] = dsdy[i] = 0;
        const Imath::V3f r = random_direction(random);
        for (int a = 0; a < 3; ++a) R[a * W + i] = r[a];
    }
    OIIO::TextureOptBatch batch;
    for (int i = 0; i < W; ++i)
        batch.sblur[i] = batch.tblur[i] = 0, batch.swidth[i] = batch.twidth[i] = 1;
    float result[3 * W];
    const auto texture = [&](OIIO::TextureOptBatch& options, OIIO::Tex::RunMask mask,
                             float* out = nullptr, int nchannels = 3) {
        std::fill(std::begin(result), std::end(result), kUntouched);
        return ours->texture(ustring(file), options, mask, s, t, dsdx, dtdx, dsdy, dtdy, nchannels,
                             out ? out : result);
    };
    const auto environment = [&](OIIO::TextureOptBatch& options, OIIO::Tex::RunMask mask) {
        std::fill(std::begin(result), std::end(result), kUntouched);
        return ours->environment(ustring(sky), options, mask, R, dR, dR, 3, result);
    };
    // The batch's good lanes, each its single lookup.
    const auto expect_lanes = [&](OIIO::Tex::RunMask mask, int bad_lane, bool env) {
        for (int i = 0; i < W; ++i) {
            if (!(mask & (OIIO::Tex::RunMask(1) << i)) || i == bad_lane) continue;
            TextureOpt options;
            float one[3];
            const Imath::V3f r(R[i], R[W + i], R[2 * W + i]), zero(0, 0, 0);
            ASSERT_TRUE(env ? ours->environment(ustring(sky), options, r, zero, zero, 3, one)
                            : ours->texture(ustring(file), options, s[i], t[i], dsdx[i], dtdx[i],
                                            dsdy[i], dtdy[i], 3, one));
            for (int c = 0; c < 3; ++c) EXPECT_EQ(result[c * W + i], one[c]) << "lane " << i;
        }
    };

    // NaN in one lane: that lane refused (false, a message naming the file, and its result the
    // missing-texture zero), the others looked up.
    s[5] = std::numeric_limits<float>::quiet_NaN();
    expect_refused(ours, texture(batch, kAll), "s = nan", file);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(result[c * W + 5], 0.0f);
    expect_lanes(kAll, 5, false);
    s[5] = 0.5f;
    R[W + 7] = std::numeric_limits<float>::infinity();
    expect_refused(ours, environment(batch, kAll), "R.y = inf", sky);
    expect_lanes(kAll, 7, true);
    R[W + 7] = 0.1f;
    // A lane's own hostile option.
    batch.swidth[2] = -1;
    expect_refused(ours, texture(batch, kAll), "swidth", file);
    expect_lanes(kAll, 2, false);
    batch.swidth[2] = 1;
    // Mask bits beyond the batch are ignored, as OpenImageIO's loop over its lanes ignores them;
    // an empty mask looks nothing up and writes nothing.
    ASSERT_TRUE(texture(batch, ~OIIO::Tex::RunMask(0))) << ours->geterror();
    expect_lanes(kAll, -1, false);
    ASSERT_TRUE(texture(batch, 0));
    for (const float v : result) EXPECT_EQ(v, kUntouched);
    // The batch's own arguments.
    expect_refused(ours, texture(batch, kAll, nullptr, 1000), "nchannels", file);
    expect_refused(ours, texture(batch, kAll, nullptr, -3), "nchannels", file);
    expect_refused(
        ours, ours->texture(ustring(file), batch, kAll, s, t, dsdx, dtdx, dsdy, dtdy, 3, nullptr),
        "result", file);
    expect_refused(
        ours,
        ours->texture(ustring(file), batch, kAll, s, t, dsdx, dtdx, dsdy, dtdy, 3, result, result),
        "together", file);
    expect_refused(
        ours,
        ours->texture(ustring(file), batch, kAll, nullptr, t, dsdx, dtdx, dsdy, dtdy, 3, result),
        "null", file);
    expect_refused(ours, ours->environment(ustring(sky), batch, kAll, R, nullptr, dR, 3, result),
                   "null", sky);
    OIIO::TextureOptBatch bad = batch;
    bad.subimage = 99;
    expect_refused(ours, texture(bad, kAll), "subimage 99", file);
    bad = batch;
    bad.anisotropic = 0;
    expect_refused(ours, environment(bad, kAll), "anisotropic", sky);
    footprint::oiio::destroy_texture_system(ours);
}

TEST(OiioAdapter, BadHandlesAndSubimagesAreRefusedNamingTheFile) {
    test::TempDir dir;
    const std::string file = make_tx(dir, "noise.tx", TypeDesc::FLOAT, "periodic");
    const std::string sky = make_latlong(dir, "sky.tx");
    Systems systems;
    OIIO::TextureSystem* ours = systems.ours;
    using Handle = OIIO::TextureSystem::TextureHandle;
    // A null handle, and one of OpenImageIO's own system (not the adapter's).
    Handle* foreign = systems.oiio->get_texture_handle(ustring(file));
    float result[3 * OIIO::Tex::BatchWidth] = {};
    const float zero[3 * OIIO::Tex::BatchWidth] = {};
    const Imath::V3f R(0, 0, 1), d(0.01f, 0, 0);
    for (Handle* bad : {static_cast<Handle*>(nullptr), foreign}) {
        const auto expect_handle_refused = [&](bool ok, const char* call) {
            const std::string message = ours->geterror();
            EXPECT_FALSE(ok) << call;
            EXPECT_NE(message.find(std::string(call) + "(): not a texture handle"),
                      std::string::npos)
                << message;
        };
        TextureOpt options;
        OIIO::TextureOptBatch batch;
        expect_handle_refused(
            ours->texture(bad, nullptr, options, 0.5f, 0.5f, 0, 0, 0, 0, 3, result), "texture");
        expect_handle_refused(ours->environment(bad, nullptr, options, R, d, d, 3, result),
                              "environment");
        expect_handle_refused(
            ours->texture(bad, nullptr, batch, 1, zero, zero, zero, zero, zero, zero, 3, result),
            "texture");
        expect_handle_refused(
            ours->environment(bad, nullptr, batch, 1, zero, zero, zero, 3, result), "environment");
        expect_handle_refused(ours->get_texels(bad, nullptr, options, 0, 0, 1, 0, 1, 0, 1, 0, 3,
                                               TypeDesc::FLOAT, result),
                              "get_texels");
        int channels = 0;
        expect_handle_refused(
            ours->get_texture_info(bad, nullptr, 0, ustring("channels"), TypeDesc::INT, &channels),
            "get_texture_info");
        ImageSpec spec;
        expect_handle_refused(ours->get_imagespec(bad, nullptr, 0, spec), "get_imagespec");
        expect_handle_refused(ours->imagespec(bad, nullptr, 0) != nullptr, "imagespec");
        EXPECT_FALSE(ours->good(bad));
        EXPECT_FALSE(ours->is_udim(bad));
        EXPECT_EQ(ours->resolve_udim(bad, nullptr, 0.5f, 0.5f), nullptr);
        EXPECT_TRUE(ours->filename_from_handle(bad).empty());
        std::vector<ustring> names{ustring("x")};
        int nu = 1, nv = 1;
        ours->inventory_udim(bad, nullptr, names, nu, nv);
        EXPECT_TRUE(names.empty());
        EXPECT_EQ(nu + nv, 0);
    }
    // A subimage the file does not have, in every call that takes one.
    TextureOpt options;
    options.subimage = 99;
    expect_refused(ours, ours->texture(ustring(file), options, 0.5f, 0.5f, 0, 0, 0, 0, 3, result),
                   "subimage 99", file);
    expect_refused(ours, ours->environment(ustring(sky), options, R, d, d, 3, result),
                   "subimage 99", sky);
    expect_refused(ours,
                   ours->get_texels(ustring(file), options, 0, 0, 1, 0, 1, 0, 1, 0, 3,
                                    TypeDesc::FLOAT, result),
                   "subimage 99", file);
    int channels = 0;
    ImageSpec spec;
    Handle* handle = ours->get_texture_handle(ustring(file));
    for (const int subimage : {99, -1}) {
        const std::string word = "subimage " + std::to_string(subimage);
        expect_refused(ours,
                       ours->get_texture_info(ustring(file), subimage, ustring("channels"),
                                              TypeDesc::INT, &channels),
                       word, file);
        expect_refused(ours,
                       ours->get_texture_info(handle, nullptr, subimage, ustring("channels"),
                                              TypeDesc::INT, &channels),
                       word, file);
        expect_refused(ours, ours->get_imagespec(ustring(file), subimage, spec), word, file);
        expect_refused(ours, ours->get_imagespec(handle, nullptr, subimage, spec), word, file);
        expect_refused(ours, ours->imagespec(ustring(file), subimage) != nullptr, word, file);
        expect_refused(ours, ours->imagespec(handle, nullptr, subimage) != nullptr, word, file);
    }
    // Subimage 0 is the file's.
    EXPECT_TRUE(
        ours->get_texture_info(handle, nullptr, 0, ustring("channels"), TypeDesc::INT, &channels));
    EXPECT_EQ(channels, 3);
}

}  // namespace
}  // namespace footprint
