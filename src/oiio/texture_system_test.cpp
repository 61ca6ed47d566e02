// The OpenImageIO adapter against OpenImageIO's own TextureSystem, in one process, on the same
// files: where both define the same value they agree within the rounding of the files' texels.
#include "oiio/texture_system.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/test_temp_dir.h"

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

}  // namespace
}  // namespace footprint
