#include "bump/slope_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "core/test_temp_dir.h"
#include "image/image_io.h"
#include "math/vec3.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

// Central differences of a linear function are exact; what is left is float rounding of heights
// up to ~100 (ulp 7.6e-6) divided by 2·texel_size, in double, then one float rounding of b.
constexpr float kRampTolerance = 1e-4f;
// Float round trip slopes → normals → slopes for |b| ≤ 2: c = (n+1)/2 and n = 2c − 1 each carry
// ~1 ulp (6e-8) of rounding; b = n_xy/n_z amplifies an error δ in n by (1 + |b|)/n_z ≤ 3·√5 ≈ 6.7,
// so |Δb| ≲ 6.7 · 2 · 1.2e-7 ≈ 1.6e-6 (measured 3.6e-7 over 131 072 slopes); 4e-6 leaves a margin.
constexpr float kFloatRoundTripTolerance = 4e-6f;
// 8-bit linear PNG: each code is off by at most half a step, |Δc| ≤ 0.5/255, so |Δn_i| ≤ 1/255.
// To first order Δb_i = (Δn_i − b_i Δn_z)/n_z, so |Δb_i| ≤ (1/255)(1 + |b_i|)/n_z with
// 1/n_z = √(1 + |b|²) (computed per texel below); the margin covers the second-order term.
constexpr double kEightBitNormalStep = 1.0 / 255.0;
constexpr double kEightBitSecondOrderMargin = 1.1;
// Slopes of a normal map made from analytic normals in double are exact to float rounding of
// c (6e-8) amplified by ≤ 6.7 as above.
constexpr float kAnalyticNormalTolerance = 2e-6f;

// Texel (x, y) of a W×H map sits at u = (x + ½)·Δu, v = (H − y − ½)·Δv: v points up (slope_map.h).
double texel_u(int x, double du) {
    return (x + 0.5) * du;
}
double texel_v(int y, int height, double dv) {
    return (height - y - 0.5) * dv;
}

// A fresh directory under the system temp dir, removed when the test ends.
using test::TempDir;

// A height map holding h = a·x + c·y in map units (x = column, y = row from the top).
Image ramp(int w, int h, float a, float c, float offset = 3.0f) {
    Image image(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) image.at(x, y, 0) = offset + a * x + c * y;
    }
    return image;
}

TEST(SlopeMap, RampGivesConstantSlopesWithTheRightSigns) {
    // h rises to the right (a > 0) and DOWN the image (c > 0), i.e. it falls along v (up).
    const float a = 0.75f, c = 1.5f;
    HeightMapOptions options;
    options.height_scale = 2.0f;
    options.texel_size_u = 0.5f;
    options.texel_size_v = 0.25f;
    options.wrap_u = options.wrap_v = HeightMapWrap::clamp;  // one-sided borders: exact on a ramp
    const Result<Image> slopes = slopes_from_height_map(ramp(9, 7, a, c), options);
    ASSERT_TRUE(slopes.ok()) << slopes.error().message;
    ASSERT_EQ(slopes->channels, 2);
    // World: h_u = a·2/0.5 = 3 > 0 ⇒ b1 = −3 (normal leans left, away from the uphill side);
    // h_v = −c·2/0.25 = −12 (falls going up) ⇒ b2 = +12 (normal leans up).
    const float expected_b1 = -a * 2.0f / 0.5f, expected_b2 = c * 2.0f / 0.25f;
    EXPECT_FLOAT_EQ(expected_b1, -3.0f);
    EXPECT_FLOAT_EQ(expected_b2, 12.0f);
    for (int y = 0; y < 7; ++y) {
        for (int x = 0; x < 9; ++x) {
            EXPECT_NEAR(slopes->at(x, y, 0), expected_b1, kRampTolerance) << x << "," << y;
            EXPECT_NEAR(slopes->at(x, y, 1), expected_b2, kRampTolerance) << x << "," << y;
        }
    }
}

TEST(SlopeMap, RampSlopesGiveTheTrueNormalOfTheWorldSurface) {
    // Brute force, independent of the formulas: build the world surface with e_u = X, e_v = Y
    // (up the image), n̂ = Z: P(x, y) = (x·Δu, −y·Δv, height_scale·h). Its normal P_u × P_v must be
    // parallel to n̂ + b1 e1 + b2 e2 = (b1, b2, 1).
    const float a = -0.4f, c = 0.9f, du = 0.3f, dv = 0.7f, scale = 1.7f;
    HeightMapOptions options;
    options.height_scale = scale;
    options.texel_size_u = du;
    options.texel_size_v = dv;
    const Result<Image> slopes = slopes_from_height_map(ramp(5, 5, a, c), options);
    ASSERT_TRUE(slopes.ok());
    // Interior texel (repeat wrap would see the ramp's jump at the borders).
    const Vec3d p_u{du, 0.0, scale * a};   // ∂P/∂(x step)
    const Vec3d p_v{0.0, dv, -scale * c};  // ∂P/∂(one texel up) = −∂P/∂(y step)
    const Vec3d n = normalize(cross(p_u, p_v));
    const Vec3d m = normalize(Vec3d{slopes->at(2, 2, 0), slopes->at(2, 2, 1), 1.0});
    EXPECT_NEAR(n.x, m.x, kRampTolerance);
    EXPECT_NEAR(n.y, m.y, kRampTolerance);
    EXPECT_NEAR(n.z, m.z, kRampTolerance);
}

TEST(SlopeMap, SineMatchesTheAnalyticDerivativeWithinTheCentralDifferenceBound) {
    // h(x, y) = A sin(ω x + φ) + B cos(κ y) with periods dividing the map (repeat wrap exact).
    // For a sinusoid the central difference is exact up to one factor:
    //   (h(x+1) − h(x−1))/2 = h'(x) · sin(ω)/ω,
    // so |error| ≤ A ω (1 − sin ω/ω) ≤ A ω³/6 (Taylor) in map units per texel.
    const int w = 64, h = 48;
    const double A = 0.8, B = 0.5, omega = 2 * std::numbers::pi / 16,
                 kappa = 2 * std::numbers::pi / 12;
    const double phi = 0.3, du = 0.05, dv = 0.02, scale = 0.1;
    Image height(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            height.at(x, y, 0) =
                static_cast<float>(A * std::sin(omega * x + phi) + B * std::cos(kappa * y));
        }
    }
    HeightMapOptions options;
    options.height_scale = static_cast<float>(scale);
    options.texel_size_u = static_cast<float>(du);
    options.texel_size_v = static_cast<float>(dv);
    const Result<Image> slopes = slopes_from_height_map(height, options);
    ASSERT_TRUE(slopes.ok());
    const double bound_u = scale / du * A * omega * (1 - std::sin(omega) / omega);
    const double bound_v = scale / dv * B * kappa * (1 - std::sin(kappa) / kappa);
    EXPECT_LE(bound_u, scale / du * A * std::pow(omega, 3) / 6);
    // Float storage of h (≤ 6e-8 per value) enters as 6e-8·scale/texel_size.
    const double float_u = 1e-7 * scale / du, float_v = 1e-7 * scale / dv;
    double worst_u = 0, worst_v = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            // Analytic: b1 = −∂h/∂u_world = −(scale/du) ∂h/∂x; b2 = −∂h/∂v_world = +(scale/dv)
            // ∂h/∂y.
            const double b1 = -scale / du * A * omega * std::cos(omega * x + phi);
            const double b2 = scale / dv * (-B * kappa * std::sin(kappa * y));
            EXPECT_NEAR(slopes->at(x, y, 0), b1, bound_u + float_u);
            EXPECT_NEAR(slopes->at(x, y, 1), b2, bound_v + float_v);
            // And the exact sin(ω)/ω shrink, to float precision.
            EXPECT_NEAR(slopes->at(x, y, 0), b1 * std::sin(omega) / omega, float_u + 1e-6);
            worst_u = std::max(worst_u, std::abs(slopes->at(x, y, 0) - b1));
            worst_v = std::max(worst_v, std::abs(slopes->at(x, y, 1) - b2));
        }
    }
    // The bound is tight: the worst texel reaches it (cos = ±1 somewhere on a 16-texel period).
    EXPECT_GT(worst_u, 0.9 * bound_u);
    EXPECT_GT(worst_v, 0.9 * bound_v);
}

TEST(SlopeMap, WrapModesAtTheBorder) {
    // h = x² along a row of 4: repeat wraps (x = 0 sees x = 3), clamp is one-sided.
    Image height(4, 1, 1);
    for (int x = 0; x < 4; ++x) height.at(x, 0, 0) = static_cast<float>(x * x);
    HeightMapOptions options;
    options.wrap_u = HeightMapWrap::repeat;
    Result<Image> repeat = slopes_from_height_map(height, options);
    ASSERT_TRUE(repeat.ok());
    EXPECT_FLOAT_EQ(repeat->at(0, 0, 0), -(1.0f - 9.0f) / 2);
    EXPECT_FLOAT_EQ(repeat->at(3, 0, 0), -(0.0f - 4.0f) / 2);
    EXPECT_FLOAT_EQ(repeat->at(1, 0, 1), 0.0f);  // height 1 in v: no slope
    options.wrap_u = HeightMapWrap::clamp;
    Result<Image> clamp = slopes_from_height_map(height, options);
    ASSERT_TRUE(clamp.ok());
    EXPECT_FLOAT_EQ(clamp->at(0, 0, 0), -(1.0f - 0.0f));
    EXPECT_FLOAT_EQ(clamp->at(3, 0, 0), -(9.0f - 4.0f));
    EXPECT_FLOAT_EQ(clamp->at(1, 0, 0), -(4.0f - 0.0f) / 2);
}

TEST(SlopeMap, OneByOneMapsAreFlatOrPassThrough) {
    Image height(1, 1, 1, 5.0f);
    for (HeightMapWrap wrap : {HeightMapWrap::repeat, HeightMapWrap::clamp}) {
        HeightMapOptions options;
        options.wrap_u = options.wrap_v = wrap;
        const Result<Image> slopes = slopes_from_height_map(height, options);
        ASSERT_TRUE(slopes.ok());
        EXPECT_EQ(slopes->at(0, 0, 0), 0.0f);
        EXPECT_EQ(slopes->at(0, 0, 1), 0.0f);
    }
    Image normal(1, 1, 3);
    normal.at(0, 0, 0) = 0.75f;  // n = (0.5, 0, 1) ⇒ b = (0.5, 0)
    normal.at(0, 0, 1) = 0.5f;
    normal.at(0, 0, 2) = 1.0f;
    const Result<Image> slopes = slopes_from_normal_map(normal);
    ASSERT_TRUE(slopes.ok());
    EXPECT_FLOAT_EQ(slopes->at(0, 0, 0), 0.5f);
    EXPECT_FLOAT_EQ(slopes->at(0, 0, 1), 0.0f);
}

// Random slopes with |b_i| ≤ limit.
Image random_slopes(int w, int h, float limit, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-limit, limit);
    Image slopes(w, h, 2);
    for (float& v : slopes.pixels) v = u(rng);
    return slopes;
}

TEST(SlopeMap, NormalMapRoundTripInFloat) {
    const float limit = 2.0f / std::numbers::sqrt2_v<float>;  // |b| ≤ 2
    const Image slopes = random_slopes(32, 16, limit, 7);
    const Image normals = normals_from_slopes(slopes);
    ASSERT_EQ(normals.channels, 3);
    for (float v : normals.pixels) {
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f);
    }
    const Result<Image> back = slopes_from_normal_map(normals);
    ASSERT_TRUE(back.ok()) << back.error().message;
    for (std::size_t i = 0; i < slopes.pixels.size(); ++i) {
        EXPECT_NEAR(back->pixels[i], slopes.pixels[i], kFloatRoundTripTolerance) << i;
    }
}

TEST(SlopeMap, NormalMapRoundTripThroughAnEightBitPng) {
    const TempDir dir;
    ASSERT_TRUE(fs::is_directory(dir.path()));
    const Image slopes = random_slopes(24, 20, 1.0f, 11);
    const fs::path file = dir.path() / "normals.png";
    ImageSaveOptions save;
    save.encoding = ColorEncoding::linear;
    ASSERT_TRUE(save_image(normals_from_slopes(slopes), file, save).ok());
    const Result<Image> back = load_slope_map(file);  // loads as linear data
    ASSERT_TRUE(back.ok()) << back.error().message;
    ASSERT_EQ(back->width, 24);
    ASSERT_EQ(back->height, 20);
    for (int y = 0; y < 20; ++y) {
        for (int x = 0; x < 24; ++x) {
            const double b1 = slopes.at(x, y, 0), b2 = slopes.at(x, y, 1);
            const double inv_nz = std::sqrt(1 + b1 * b1 + b2 * b2);
            for (int c = 0; c < 2; ++c) {
                const double b = c == 0 ? b1 : b2;
                const double bound =
                    kEightBitSecondOrderMargin * kEightBitNormalStep * (1 + std::abs(b)) * inv_nz;
                EXPECT_NEAR(back->at(x, y, c), b, bound) << x << "," << y << "," << c;
            }
        }
    }
    // sRGB decoding would have bent the normals far beyond that bound: the loader must use linear.
    ImageLoadOptions srgb_options;
    srgb_options.encoding = ColorEncoding::srgb;
    const Result<Image> srgb = load_image(file, srgb_options);
    ASSERT_TRUE(srgb.ok());
    const Result<Image> wrong = slopes_from_normal_map(*srgb, {});
    if (wrong.ok()) {
        double worst = 0;
        for (std::size_t i = 0; i < slopes.pixels.size(); ++i) {
            worst = std::max(worst, std::abs(double(wrong->pixels[i]) - slopes.pixels[i]));
        }
        EXPECT_GT(worst, 0.1);
    }
}

TEST(SlopeMap, OpenGlAndDirectXDifferExactlyInTheSignOfB2) {
    const Image normals = normals_from_slopes(random_slopes(16, 16, 1.5f, 3));
    NormalMapOptions gl, dx;
    dx.green_convention = NormalMapGreen::directx;
    const Result<Image> a = slopes_from_normal_map(normals, gl);
    const Result<Image> b = slopes_from_normal_map(normals, dx);
    ASSERT_TRUE(a.ok() && b.ok());
    for (std::size_t i = 0; i < normals.pixel_count(); ++i) {
        EXPECT_EQ(a->pixels[2 * i], b->pixels[2 * i]);
        EXPECT_EQ(a->pixels[2 * i + 1], -b->pixels[2 * i + 1]);
    }
}

TEST(SlopeMap, StrengthScalesAndAlphaIsIgnored) {
    const Image slopes = random_slopes(8, 8, 1.0f, 5);
    const Image normals3 = normals_from_slopes(slopes);
    Image normals4(8, 8, 4);
    for (std::size_t i = 0; i < normals3.pixel_count(); ++i) {
        for (int c = 0; c < 3; ++c) normals4.pixels[4 * i + c] = normals3.pixels[3 * i + c];
        normals4.pixels[4 * i + 3] = 0.25f;  // alpha: must not matter
    }
    NormalMapOptions options;
    options.strength = -2.5f;
    const Result<Image> base = slopes_from_normal_map(normals3);
    const Result<Image> scaled = slopes_from_normal_map(normals4, options);
    ASSERT_TRUE(base.ok() && scaled.ok());
    for (std::size_t i = 0; i < base->pixels.size(); ++i) {
        EXPECT_FLOAT_EQ(scaled->pixels[i], -2.5f * base->pixels[i]);
    }
}

TEST(SlopeMap, TwoChannelNormalMapsReconstructZ) {
    const Image slopes = random_slopes(8, 8, 1.0f, 9);
    const Image normals3 = normals_from_slopes(slopes);
    Image normals2(8, 8, 2);
    for (std::size_t i = 0; i < normals3.pixel_count(); ++i) {
        normals2.pixels[2 * i] = normals3.pixels[3 * i];
        normals2.pixels[2 * i + 1] = normals3.pixels[3 * i + 1];
    }
    const Result<Image> back = slopes_from_normal_map(normals2);
    ASSERT_TRUE(back.ok()) << back.error().message;
    for (std::size_t i = 0; i < slopes.pixels.size(); ++i) {
        // z = √(1 − x² − y²) from rounded x, y: δz ≤ |n_xy| δn/n_z ≈ 3.4e-7 for |b| ≤ √2, so
        // |Δb| ≲ 1.2e-6: inside the same float round-trip bound.
        EXPECT_NEAR(back->pixels[i], slopes.pixels[i], kFloatRoundTripTolerance) << i;
    }
}

TEST(SlopeMap, HeightMapAndNormalMapOfTheSameSurfaceAgree) {
    // One analytic surface h(u, v) = A sin(α u) cos(β v) in world units, sampled two ways at the
    // texel centres (v pointing up): as a height map, and as an OpenGL normal map of its exact
    // normal (−h_u, −h_v, 1). Both must give the same slopes, within the central-difference
    // bound of the height map (per axis, as in the sine test: amplitude·(1 − sin θ/θ) with
    // θ = frequency·texel size) — this catches any disagreement in the sign of v.
    const int w = 40, h = 30;
    const double du = 0.1, dv = 0.1, A = 0.2;
    const double alpha = 2 * std::numbers::pi / (20 * du), beta = 2 * std::numbers::pi / (15 * dv);
    Image height(w, h, 1), normals(w, h, 3);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double u = texel_u(x, du), v = texel_v(y, h, dv);
            height.at(x, y, 0) = static_cast<float>(A * std::sin(alpha * u) * std::cos(beta * v));
            const double h_u = A * alpha * std::cos(alpha * u) * std::cos(beta * v);
            const double h_v = -A * beta * std::sin(alpha * u) * std::sin(beta * v);
            const Vec3d n = normalize(Vec3d{-h_u, -h_v, 1.0});
            normals.at(x, y, 0) = static_cast<float>(0.5 * (n.x + 1));
            normals.at(x, y, 1) = static_cast<float>(0.5 * (n.y + 1));
            normals.at(x, y, 2) = static_cast<float>(0.5 * (n.z + 1));
        }
    }
    HeightMapOptions ho;
    ho.texel_size_u = static_cast<float>(du);
    ho.texel_size_v = static_cast<float>(dv);
    const Result<Image> from_height = slopes_from_height_map(height, ho);
    const Result<Image> from_normals = slopes_from_normal_map(normals);
    ASSERT_TRUE(from_height.ok() && from_normals.ok());
    const double bound_u = A * alpha * (1 - std::sin(alpha * du) / (alpha * du)) + 1e-5;
    const double bound_v = A * beta * (1 - std::sin(beta * dv) / (beta * dv)) + 1e-5;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double u = texel_u(x, du), v = texel_v(y, h, dv);
            const double b1 = -A * alpha * std::cos(alpha * u) * std::cos(beta * v);
            const double b2 = A * beta * std::sin(alpha * u) * std::sin(beta * v);
            EXPECT_NEAR(from_normals->at(x, y, 0), b1,
                        kAnalyticNormalTolerance * (1 + std::abs(b1)));
            EXPECT_NEAR(from_normals->at(x, y, 1), b2,
                        kAnalyticNormalTolerance * (1 + std::abs(b2)));
            EXPECT_NEAR(from_height->at(x, y, 0), from_normals->at(x, y, 0), bound_u);
            EXPECT_NEAR(from_height->at(x, y, 1), from_normals->at(x, y, 1), bound_v);
        }
    }
}

TEST(SlopeMap, NaturalDerivativeConversion) {
    // Orthogonal parameterisation with |p_u| = 3, |p_v| = 0.5: b = (−f_u/3, −f_v/0.5) and back.
    const Vec2 f{1.2f, -0.4f};
    const Vec2 b = slopes_from_natural_derivatives(f, 3.0f, 0.5f);
    EXPECT_FLOAT_EQ(b.x, -0.4f);
    EXPECT_FLOAT_EQ(b.y, 0.8f);
    const Vec2 g = natural_derivatives_from_slopes(b, 3.0f, 0.5f);
    EXPECT_FLOAT_EQ(g.x, f.x);
    EXPECT_FLOAT_EQ(g.y, f.y);
    // Degenerate lengths carry no bump, never NaN.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Vec2 z = slopes_from_natural_derivatives(f, 0.0f, nan);
    EXPECT_EQ(z.x, 0.0f);
    EXPECT_EQ(z.y, 0.0f);
    const Vec2 z2 = natural_derivatives_from_slopes(Vec2{nan, 1.0f}, 1.0f, -1.0f);
    EXPECT_EQ(z2.x, 0.0f);
    EXPECT_EQ(z2.y, 0.0f);
    // A unit-parameter height slope map holds −(f_u, f_v) (slope_map.h): h = 2u − 3v on [0,1]².
    const int n = 8;
    Image height(n, n, 1);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            height.at(x, y, 0) =
                static_cast<float>(2 * texel_u(x, 1.0 / n) - 3 * texel_v(y, n, 1.0 / n));
        }
    }
    HeightMapOptions options;
    options.texel_size_u = options.texel_size_v = 1.0f / n;
    options.wrap_u = options.wrap_v = HeightMapWrap::clamp;
    const Result<Image> slopes = slopes_from_height_map(height, options);
    ASSERT_TRUE(slopes.ok());
    EXPECT_NEAR(slopes->at(3, 3, 0), -2.0f, kRampTolerance);
    EXPECT_NEAR(slopes->at(3, 3, 1), 3.0f, kRampTolerance);
}

// ---- Bad input -------------------------------------------------------------------------------

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

TEST(SlopeMap, NormalBelowTheTangentPlaneIsANamedError) {
    Image normals(4, 3, 3);
    for (std::size_t i = 0; i < normals.pixel_count(); ++i) {
        normals.pixels[3 * i] = normals.pixels[3 * i + 1] = 0.5f;
        normals.pixels[3 * i + 2] = 1.0f;
    }
    normals.at(2, 1, 0) = 0.8f;
    normals.at(2, 1, 2) = 0.25f;  // n_z = −0.5
    const Result<Image> slopes = slopes_from_normal_map(normals);
    ASSERT_FALSE(slopes.ok());
    const std::string& message = slopes.error().message;
    EXPECT_TRUE(contains(message, "texel (2, 1)")) << message;
    EXPECT_TRUE(contains(message, "-0.5")) << message;
    EXPECT_TRUE(contains(message, "n_z ≤ 0")) << message;

    // z exactly 0 (c = 0.5) is invalid too.
    normals.at(2, 1, 2) = 0.5f;
    EXPECT_FALSE(slopes_from_normal_map(normals).ok());

    // The clamp policy: slope of magnitude max_slope along (n_x, n_y) = (0.6, 0).
    NormalMapOptions options;
    options.invalid_normal_policy = InvalidNormalPolicy::clamp;
    options.max_slope = 50.0f;
    options.strength = 0.5f;
    const Result<Image> clamped = slopes_from_normal_map(normals, options);
    ASSERT_TRUE(clamped.ok());
    EXPECT_NEAR(clamped->at(2, 1, 0), 0.5f * 50.0f, 1e-4f);
    EXPECT_EQ(clamped->at(2, 1, 1), 0.0f);
    EXPECT_EQ(clamped->at(0, 0, 0), 0.0f);  // valid texels are untouched
}

TEST(SlopeMap, TooSteepNormalsFollowMaxSlope) {
    Image normals(1, 1, 3);
    normals.at(0, 0, 0) = 1.0f;  // n = (1, 0, 0.02): slope 50
    normals.at(0, 0, 1) = 0.5f;
    normals.at(0, 0, 2) = 0.51f;
    NormalMapOptions options;
    options.max_slope = 10.0f;
    const Result<Image> error = slopes_from_normal_map(normals, options);
    ASSERT_FALSE(error.ok());
    EXPECT_TRUE(contains(error.error().message, "exceeds max_slope = 10")) << error.error().message;
    options.max_slope = 100.0f;
    const Result<Image> ok = slopes_from_normal_map(normals, options);
    ASSERT_TRUE(ok.ok());
    EXPECT_NEAR(ok->at(0, 0, 0), 50.0f, 1e-3f);  // c = 0.51 is not exact in float: 1/0.02 · ~5e-6
    EXPECT_EQ(slopes_from_normal_map(normals).ok(), true);  // default max_slope 1000
}

TEST(SlopeMap, NanInputsAreNamedErrorsOrFlatUnderClamp) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Image height(3, 3, 1, 1.0f);
    height.at(1, 2, 0) = nan;
    const Result<Image> h = slopes_from_height_map(height);
    ASSERT_FALSE(h.ok());
    EXPECT_TRUE(contains(h.error().message, "texel (1, 2)")) << h.error().message;
    EXPECT_TRUE(contains(h.error().message, "nan")) << h.error().message;
    height.at(1, 2, 0) = std::numeric_limits<float>::infinity();
    EXPECT_FALSE(slopes_from_height_map(height).ok());

    Image normals(2, 2, 3, 0.5f);
    for (std::size_t i = 0; i < 4; ++i) normals.pixels[3 * i + 2] = 1.0f;
    normals.at(1, 0, 1) = nan;
    const Result<Image> n = slopes_from_normal_map(normals);
    ASSERT_FALSE(n.ok());
    EXPECT_TRUE(contains(n.error().message, "texel (1, 0)")) << n.error().message;
    EXPECT_TRUE(contains(n.error().message, "nan")) << n.error().message;
    NormalMapOptions options;
    options.invalid_normal_policy = InvalidNormalPolicy::clamp;
    const Result<Image> flat = slopes_from_normal_map(normals, options);
    ASSERT_TRUE(flat.ok());
    EXPECT_EQ(flat->at(1, 0, 0), 0.0f);
    EXPECT_EQ(flat->at(1, 0, 1), 0.0f);

    // 2-channel: x² + y² > 1 leaves no z.
    Image xy(1, 1, 2);
    xy.at(0, 0, 0) = 1.0f;
    xy.at(0, 0, 1) = 1.0f;
    const Result<Image> rim = slopes_from_normal_map(xy);
    ASSERT_FALSE(rim.ok());
    EXPECT_TRUE(contains(rim.error().message, "texel (0, 0)")) << rim.error().message;

    // normals_from_slopes never produces NaN: a non-finite slope is flat.
    Image slopes(1, 2, 2);
    slopes.at(0, 0, 0) = nan;
    slopes.at(0, 1, 0) = 1e30f;  // huge but finite: almost horizontal, still in [0, 1]
    const Image back = normals_from_slopes(slopes);
    EXPECT_EQ(back.at(0, 0, 0), 0.5f);
    EXPECT_EQ(back.at(0, 0, 1), 0.5f);
    EXPECT_EQ(back.at(0, 0, 2), 1.0f);
    EXPECT_FLOAT_EQ(back.at(0, 1, 0), 1.0f);
    EXPECT_FLOAT_EQ(back.at(0, 1, 2), 0.5f);
}

TEST(SlopeMap, WrongShapesAndOptionsAreNamedErrors) {
    const Result<Image> empty = slopes_from_height_map(Image{});
    ASSERT_FALSE(empty.ok());
    EXPECT_TRUE(contains(empty.error().message, "zero size")) << empty.error().message;
    const Result<Image> no_channels = slopes_from_height_map(Image(2, 2, 0));
    ASSERT_FALSE(no_channels.ok());
    EXPECT_TRUE(contains(no_channels.error().message, "0 channels")) << no_channels.error().message;
    const Result<Image> grey = slopes_from_normal_map(Image(2, 2, 1, 0.5f));
    ASSERT_FALSE(grey.ok());
    EXPECT_TRUE(contains(grey.error().message, "1 channels")) << grey.error().message;
    EXPECT_FALSE(slopes_from_normal_map(Image(2, 2, 5, 0.5f)).ok());
    Image malformed(2, 2, 3, 0.5f);
    malformed.pixels.pop_back();
    const Result<Image> bad = slopes_from_normal_map(malformed);
    ASSERT_FALSE(bad.ok());
    EXPECT_TRUE(contains(bad.error().message, "malformed")) << bad.error().message;

    HeightMapOptions ho;
    ho.texel_size_v = 0.0f;
    const Result<Image> size = slopes_from_height_map(Image(2, 2, 1), ho);
    ASSERT_FALSE(size.ok());
    EXPECT_TRUE(contains(size.error().message, "texel_size_v = 0")) << size.error().message;
    ho = {};
    ho.height_scale = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(slopes_from_height_map(Image(2, 2, 1), ho).ok());
    ho = {};
    ho.height_scale = 1e30f;
    ho.texel_size_u = 1e-30f;
    Image steep(3, 1, 1);
    steep.at(2, 0, 0) = 1e10f;
    const Result<Image> overflow = slopes_from_height_map(steep, ho);
    ASSERT_FALSE(overflow.ok());
    EXPECT_TRUE(contains(overflow.error().message, "overflows")) << overflow.error().message;

    NormalMapOptions no;
    no.max_slope = -1.0f;
    EXPECT_FALSE(slopes_from_normal_map(Image(1, 1, 3, 0.75f), no).ok());
    no = {};
    no.strength = std::numeric_limits<float>::infinity();
    EXPECT_FALSE(slopes_from_normal_map(Image(1, 1, 3, 0.75f), no).ok());
}

TEST(SlopeMap, LoadErrorsNameTheFile) {
    const TempDir dir;
    ASSERT_TRUE(fs::is_directory(dir.path()));
    const fs::path missing = dir.path() / "missing.png";
    const Result<Image> a = load_slope_map(missing);
    ASSERT_FALSE(a.ok());
    EXPECT_TRUE(contains(a.error().message, missing.string())) << a.error().message;

    // A grey PNG is not a normal map …
    const fs::path grey = dir.path() / "grey.png";
    ImageSaveOptions save;
    save.encoding = ColorEncoding::linear;
    ASSERT_TRUE(save_image(Image(4, 4, 1, 0.5f), grey, save).ok());
    const Result<Image> b = load_slope_map(grey);
    ASSERT_FALSE(b.ok());
    EXPECT_TRUE(contains(b.error().message, "cannot make a slope map from '" + grey.string()))
        << b.error().message;
    EXPECT_TRUE(contains(b.error().message, "1 channels")) << b.error().message;

    // … but a fine height map, read as linear data: 8-bit codes of a ramp, exact slopes.
    Image ramp_image(8, 2, 1);
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 8; ++x) ramp_image.at(x, y, 0) = static_cast<float>(x * 10) / 255.0f;
    }
    ASSERT_TRUE(save_image(ramp_image, grey, save).ok());
    SlopeMapLoadOptions options;
    options.source = SlopeMapSource::height_map;
    options.height_map.height_scale = 255.0f;
    options.height_map.wrap_u = HeightMapWrap::clamp;
    const Result<Image> c = load_slope_map(grey, options);
    ASSERT_TRUE(c.ok()) << c.error().message;
    EXPECT_NEAR(c->at(4, 1, 0), -10.0f, kRampTolerance);  // sRGB decoding would bend the ramp
    EXPECT_NEAR(c->at(4, 1, 1), 0.0f, kRampTolerance);

    // A normal map file with a texel below the tangent plane names the file and the texel.
    Image normals(3, 2, 3, 0.5f);
    for (std::size_t i = 0; i < normals.pixel_count(); ++i) normals.pixels[3 * i + 2] = 1.0f;
    normals.at(1, 1, 2) = 0.0f;
    const fs::path bad = dir.path() / "bad_normals.png";
    ASSERT_TRUE(save_image(normals, bad, save).ok());
    const Result<Image> d = load_slope_map(bad);
    ASSERT_FALSE(d.ok());
    EXPECT_TRUE(contains(d.error().message, bad.string())) << d.error().message;
    EXPECT_TRUE(contains(d.error().message, "texel (1, 1)")) << d.error().message;
}

TEST(SlopeMap, LoadedNanNormalsAreLeftToThePolicy) {
    const TempDir dir;
    const fs::path file = dir.path() / "n.exr";
    Image normals(3, 2, 3, 0.5f);
    for (std::size_t i = 0; i < normals.pixel_count(); ++i) normals.pixels[3 * i + 2] = 1.0f;
    normals.at(1, 0, 2) = std::numeric_limits<float>::quiet_NaN();
    ASSERT_TRUE(save_image(normals, file).ok());
    const Result<Image> refused = load_slope_map(file);
    ASSERT_FALSE(refused.ok());
    const std::string& message = refused.error().message;
    EXPECT_TRUE(contains(message, "'" + file.string() + "'")) << message;
    EXPECT_TRUE(contains(message, "normal map texel (1, 0)")) << message;
    EXPECT_TRUE(contains(message, "nan")) << message;
    SlopeMapLoadOptions options;
    options.normal_map.invalid_normal_policy = InvalidNormalPolicy::clamp;
    const Result<Image> flat = load_slope_map(file, options);
    ASSERT_TRUE(flat.ok()) << flat.error().message;
    EXPECT_EQ(flat->at(1, 0, 0), 0.0f);
    EXPECT_EQ(flat->at(1, 0, 1), 0.0f);
}

}  // namespace
}  // namespace footprint
