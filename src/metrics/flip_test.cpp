// Tests of metrics/flip.h: LDR- and HDR-FLIP against the authors' reference implementation
// (NVlabs/flip v1.6, its C++ FLIP.h run on the synthetic images below), against a brute-force
// double-precision evaluation of the FLIP paper's formulas with direct 2-D filters, against the
// colour error computed by hand for uniform patches, and the properties the papers state.
//
// The published example (NVlabs/flip images/reference.png, test.png, .exr; mean LDR-FLIP
// 0.159691, HDR-FLIP 0.283478) is not used: only reference.png was available to this repository
// (test.png and the EXR pair were not), and reference.png alone is 4 MB. Instead the reference
// implementation was compiled and run on the deterministic synthetic pairs built here (same code,
// same float inputs), and its means, exposures and a few pixels are the expected values below.
#include "metrics/flip.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace footprint {
namespace {

// ---- synthetic images (the reference implementation's values below were computed on these) ----

// A small LCG giving values in [0, 1).
struct Lcg {
    std::uint32_t state;
    float next() {
        state = state * 1664525u + 1013904223u;
        return static_cast<float>((state >> 8) & 0xffffu) / 65536.0f;
    }
};

// A scene-like LDR reference: colour gradients, a checkerboard texture, a yellow disc.
Image ldr_reference(int w, int h) {
    Image image(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float u = (x + 0.5f) / w, v = (y + 0.5f) / h;
            const bool dark = ((x / 6) + (y / 6)) % 2 == 0;
            const float t = dark ? 0.25f : 0.9f;
            float r = t * (0.2f + 0.7f * u), g = t * (0.3f + 0.5f * v),
                  b = t * (0.8f - 0.6f * u * v);
            const float dx = x - 0.7f * w, dy = y - 0.35f * h;
            if (dx * dx + dy * dy < 0.02f * w * w) {
                r = 1.0f;
                g = 0.85f;
                b = 0.2f;
            }
            image.at(x, y, 0) = r;
            image.at(x, y, 1) = g;
            image.at(x, y, 2) = b;
        }
    return image;
}

// The test: the left third with noise (as Monte Carlo leaves), the middle third with the texture
// moved one pixel right, the right third with a colour shift (more red, less blue).
Image ldr_test(const Image& reference) {
    Image image = reference;
    Lcg lcg{12345u};
    for (int y = 0; y < reference.height; ++y)
        for (int x = 0; x < reference.width; ++x)
            for (int c = 0; c < 3; ++c) {
                float v = reference.at(x, y, c);
                if (x < reference.width / 3)
                    v += 0.3f * (lcg.next() - 0.5f);
                else if (x < 2 * reference.width / 3)
                    v = reference.at(x - 1, y, c);
                else
                    v *= (c == 0 ? 1.15f : c == 2 ? 0.8f : 1.0f);
                image.at(x, y, c) = v < 0 ? 0 : v > 1 ? 1 : v;
            }
    return image;
}

// HDR: the LDR reference under light growing from 2^−3 to 2^4 in steps across, plus five small
// very bright spots.
Image hdr_reference(int w, int h) {
    Image image = ldr_reference(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float light = 0.125f;
            for (int k = 0; k < (8 * x) / w; ++k) light *= 2.0f;
            for (int c = 0; c < 3; ++c) image.at(x, y, c) *= light;
        }
    for (int i = 0; i < 5; ++i)
        for (int c = 0; c < 3; ++c)
            image.at((7 + 17 * i) % w, (5 + 11 * i) % h, c) = 40.0f + 30.0f * i + 10.0f * c;
    return image;
}

// Its test: noisier, 10% dimmer in the bottom quarter, the spots moved one pixel and five more.
Image hdr_test(const Image& reference) {
    Image image = reference;
    Lcg lcg{777u};
    for (int y = 0; y < reference.height; ++y)
        for (int x = 0; x < reference.width; ++x)
            for (int c = 0; c < 3; ++c) {
                float v = reference.at(x, y, c);
                if (v > 30.0f) v = reference.at((x + 1) % reference.width, y, c);
                v *= 1.0f + 0.4f * (lcg.next() - 0.5f);
                if (y > 3 * reference.height / 4) v *= 0.9f;
                image.at(x, y, c) = v;
            }
    for (int i = 0; i < 5; ++i)
        for (int c = 0; c < 3; ++c)
            image.at((9 + 13 * i) % reference.width, (40 - 7 * i) % reference.height, c) = 60.0f;
    return image;
}

// ---- end of the synthetic images ---------------------------------------------------------------

// The reference implementation computes in 32-bit float, as flip.cpp does, but in another order
// (its filter sums, powf for the cube root, the white point as a reciprocal, derivative filters
// summed plainly where flip.cpp makes them exactly 0 on flat regions). Measured: pixels differ by
// up to 5e-5 (ΔE_f = √· magnifies tiny differences of nearly equal edge strengths), means by up to
// 6e-7, exposures by 5e-7.
constexpr double kReferenceMeanTolerance = 3e-6;
constexpr double kReferencePixelTolerance = 2e-4;
constexpr double kReferenceExposureTolerance = 5e-6;

// The float pipeline against double arithmetic on the same formulas. Single-precision rounding
// in the colour transforms (L* ~ 100) leaves ~1e-5 of colour error ΔE_c where the true one is ~0,
// and FLIP = ΔE_c^(1 − ΔE_f) raises it, up to (1e-5)^0.65 ≈ 6e-4 beside an edge (ΔE_f ≈ 0.35).
// Measured: 1.2e-4 beside the moved edge below, 4e-6 elsewhere.
constexpr double kDoubleTolerance = 1e-3;
// A uniform patch has no feature error, so only the colour transforms' rounding is left.
constexpr double kUniformTolerance = 5e-6;

FlipOptions ldr_options() {
    FlipOptions options;
    options.range = FlipRange::ldr;
    options.error_map = true;
    return options;
}

FlipOptions hdr_options() {
    FlipOptions options;
    options.range = FlipRange::hdr;
    options.error_map = true;
    return options;
}

// ---- an independent evaluation of the FLIP paper's formulas in double ---------------------------

constexpr double kPi = std::numbers::pi;
constexpr double kRgbToXyz[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};

using D3 = std::array<double, 3>;

D3 times(const double (&m)[3][3], const D3& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
            m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

D3 white() {
    return times(kRgbToXyz, {1, 1, 1});
}

// Solves M x = v by Cramer's rule (the test's own XYZ → RGB).
D3 solve(const double (&m)[3][3], const D3& v) {
    auto det = [](const double(&a)[3][3]) {
        return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
               a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    };
    D3 x{};
    for (int j = 0; j < 3; ++j) {
        double replaced[3][3];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) replaced[r][c] = c == j ? v[r] : m[r][c];
        x[j] = det(replaced) / det(m);
    }
    return x;
}

D3 rgb_to_ycxcz(const D3& rgb) {
    const D3 xyz = times(kRgbToXyz, rgb), w = white();
    const double x = xyz[0] / w[0], y = xyz[1] / w[1], z = xyz[2] / w[2];
    return {116 * y - 16, 500 * (x - y), 200 * (y - z)};
}

D3 ycxcz_to_rgb(const D3& v) {
    const D3 w = white();
    const double y = (v[0] + 16) / 116;
    return solve(kRgbToXyz, {(y + v[1] / 500) * w[0], y * w[1], (y - v[2] / 200) * w[2]});
}

// CIELAB of linear RGB with the Hunt adjustment (a, b scaled by 0.01 L).
D3 hunt_lab(const D3& rgb) {
    const D3 xyz = times(kRgbToXyz, rgb), w = white();
    const double delta = 6.0 / 29.0;
    auto f = [&](double t) {
        return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29.0;
    };
    const double fx = f(xyz[0] / w[0]), fy = f(xyz[1] / w[1]), fz = f(xyz[2] / w[2]);
    const double l = 116 * fy - 16;
    return {l, 0.01 * l * 500 * (fx - fy), 0.01 * l * 200 * (fy - fz)};
}

double hyab(const D3& p, const D3& q) {
    return std::abs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

// The colour error of two linear RGB colours in [0, 1] (the FLIP paper's colour pipeline).
double colour_error_by_hand(const D3& a, const D3& b) {
    const double c_max = std::pow(hyab(hunt_lab({0, 1, 0}), hunt_lab({0, 0, 1})), 0.7);
    const double e = std::pow(hyab(hunt_lab(a), hunt_lab(b)), 0.7);
    const double knee = 0.4 * c_max;
    return e < knee ? e * 0.95 / knee : 0.95 + (e - knee) / (c_max - knee) * 0.05;
}

struct BruteForce {
    std::vector<double> colour, feature, flip;  // ΔE_c, ΔE_f and FLIP per pixel
};

// LDR-FLIP of a against b (3 channels, values in [0, 1]) with the 2-D filters built and
// normalised directly in 2-D, applied by direct summation, the border extended by its edge
// pixels.
BruteForce brute_force_ldr_flip(const Image& a, const Image& b, double ppd) {
    const int w = a.width, h = a.height;
    auto clamped = [&](int x, int y) {
        return static_cast<std::size_t>(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1);
    };
    // The CSFs: {a1, b1, a2, b2} for Y, Cx, Cz.
    const double csf[3][4] = {
        {1, 0.0047, 0, 1e-5}, {1, 0.0053, 0, 1e-5}, {34.1, 0.04, 13.5, 0.025}};
    const int r = static_cast<int>(std::ceil(3 * std::sqrt(0.04 / (2 * kPi * kPi)) * ppd));
    std::vector<std::vector<double>> kernels(3);
    for (int ch = 0; ch < 3; ++ch) {
        double sum = 0;
        for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx) {
                const double d2 = (dx * dx + dy * dy) / (ppd * ppd);
                double k = 0;
                for (int i = 0; i < 2; ++i) {
                    const double ai = csf[ch][2 * i], bi = csf[ch][2 * i + 1];
                    k += ai * std::sqrt(kPi / bi) * std::exp(-kPi * kPi * d2 / bi);
                }
                kernels[ch].push_back(k);
                sum += k;
            }
        for (double& k : kernels[ch]) k /= sum;
    }
    // Feature filters: ∂G/∂x, ∂²G/∂x² of a 2-D Gaussian (σ = 0.041 ppd), each with positive
    // weights normalised to 1 and negative ones to −1; the y versions are their transposes.
    const double sigma = 0.5 * 0.082 * ppd;
    const int fr = static_cast<int>(std::ceil(3 * sigma));
    std::vector<double> edge_x, point_x;
    for (int dy = -fr; dy <= fr; ++dy)
        for (int dx = -fr; dx <= fr; ++dx) {
            const double g = std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
            edge_x.push_back(-dx * g);
            point_x.push_back((dx * dx / (sigma * sigma) - 1) * g);
        }
    for (std::vector<double>* k : {&edge_x, &point_x}) {
        double positive = 0, negative = 0;
        for (double v : *k) (v > 0 ? positive : negative) += std::abs(v);
        for (double& v : *k) v /= v > 0 ? positive : negative;
    }
    auto perceive = [&](const Image& image, std::vector<D3>& filtered, std::vector<double>& edge,
                        std::vector<double>& point) {
        std::vector<D3> ycxcz(image.pixel_count());
        for (std::size_t p = 0; p < ycxcz.size(); ++p)
            ycxcz[p] = rgb_to_ycxcz(
                {image.pixels[3 * p], image.pixels[3 * p + 1], image.pixels[3 * p + 2]});
        filtered.assign(ycxcz.size(), D3{});
        edge.assign(ycxcz.size(), 0);
        point.assign(ycxcz.size(), 0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t p = static_cast<std::size_t>(y) * w + x;
                for (int ch = 0; ch < 3; ++ch) {
                    std::size_t i = 0;
                    for (int dy = -r; dy <= r; ++dy)
                        for (int dx = -r; dx <= r; ++dx)
                            filtered[p][ch] +=
                                kernels[ch][i++] * ycxcz[clamped(x + dx, y + dy)][ch];
                }
                double ex = 0, ey = 0, px = 0, py = 0;
                const int n = 2 * fr + 1;
                for (int dy = -fr; dy <= fr; ++dy)
                    for (int dx = -fr; dx <= fr; ++dx) {
                        const std::size_t i = static_cast<std::size_t>(dy + fr) * n + (dx + fr);
                        const std::size_t t = static_cast<std::size_t>(dx + fr) * n + (dy + fr);
                        const double value = (ycxcz[clamped(x + dx, y + dy)][0] + 16) / 116;
                        ex += edge_x[i] * value;
                        px += point_x[i] * value;
                        ey += edge_x[t] * value;  // the transpose: ∂/∂y
                        py += point_x[t] * value;
                    }
                edge[p] = std::hypot(ex, ey);
                point[p] = std::hypot(px, py);
            }
    };
    std::vector<D3> fa, fb;
    std::vector<double> ea, eb, pa, pb;
    perceive(a, fa, ea, pa);
    perceive(b, fb, eb, pb);
    BruteForce result;
    for (std::size_t p = 0; p < fa.size(); ++p) {
        auto clamp01 = [](D3 c) {
            for (double& v : c) v = std::clamp(v, 0.0, 1.0);
            return c;
        };
        const double colour =
            colour_error_by_hand(clamp01(ycxcz_to_rgb(fa[p])), clamp01(ycxcz_to_rgb(fb[p])));
        const double feature =
            std::sqrt(std::max(std::abs(ea[p] - eb[p]), std::abs(pa[p] - pb[p])) / std::sqrt(2.0));
        result.colour.push_back(colour);
        result.feature.push_back(feature);
        result.flip.push_back(std::pow(colour, 1 - feature));
    }
    return result;
}

// ---- the reference implementation --------------------------------------------------------------

TEST(Flip, LdrMatchesTheReferenceImplementation) {
    const Image reference = ldr_reference(96, 64), test = ldr_test(reference);
    const Result<FlipResult> r = flip(test, reference, ldr_options());
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_FALSE(r->hdr);
    EXPECT_EQ(r->pixels, 96u * 64u);
    EXPECT_NEAR(r->mean, 0.209438369, kReferenceMeanTolerance);
    ASSERT_EQ(r->error_map.channels, 1);
    // A noisy pixel, one at the moved texture, one at the colour shift and one on the disc.
    EXPECT_NEAR(r->error_map.at(10, 20, 0), 0.320758283, kReferencePixelTolerance);
    EXPECT_NEAR(r->error_map.at(42, 30, 0), 0.214462131, kReferencePixelTolerance);
    EXPECT_NEAR(r->error_map.at(80, 50, 0), 0.244962946, kReferencePixelTolerance);
    EXPECT_NEAR(r->error_map.at(67, 22, 0), 0.177206561, kReferencePixelTolerance);

    FlipOptions coarse = ldr_options();
    coarse.pixels_per_degree = 20;
    const Result<FlipResult> at_20 = flip(test, reference, coarse);
    ASSERT_TRUE(at_20.ok()) << at_20.error().message;
    EXPECT_NEAR(at_20->mean, 0.289436311, kReferenceMeanTolerance);
}

TEST(Flip, HdrMatchesTheReferenceImplementation) {
    const Image reference = hdr_reference(96, 64), test = hdr_test(reference);
    const Result<FlipResult> r = flip(test, reference, hdr_options());
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_TRUE(r->hdr);
    EXPECT_NEAR(r->start_exposure, -6.31412935, kReferenceExposureTolerance);
    EXPECT_NEAR(r->stop_exposure, 2.49583912, kReferenceExposureTolerance);
    EXPECT_EQ(r->exposures, 9);
    EXPECT_NEAR(r->mean, 0.114361994, kReferenceMeanTolerance);
    EXPECT_NEAR(r->error_map.at(10, 20, 0), 0.0277596749, kReferencePixelTolerance);
    EXPECT_NEAR(r->error_map.at(42, 30, 0), 0.111077458, kReferencePixelTolerance);
    EXPECT_NEAR(r->error_map.at(80, 50, 0), 0.172828197, kReferencePixelTolerance);
    EXPECT_NEAR(r->error_map.at(24, 16, 0), 0.849805892, kReferencePixelTolerance);
}

// ---- the papers' formulas and properties -------------------------------------------------------

TEST(Flip, SeparableFiltersMatchBruteForceTwoDimensionalFlip) {
    const Image reference = ldr_reference(30, 22), test = ldr_test(reference);
    for (const double ppd : {kFlipDefaultPixelsPerDegree, 25.0}) {
        FlipOptions options = ldr_options();
        options.pixels_per_degree = ppd;
        const Result<FlipResult> r = flip(test, reference, options);
        ASSERT_TRUE(r.ok()) << r.error().message;
        const BruteForce expected = brute_force_ldr_flip(test, reference, ppd);
        double sum = 0;
        for (std::size_t p = 0; p < expected.flip.size(); ++p) {
            EXPECT_NEAR(r->error_map.pixels[p], expected.flip[p], kDoubleTolerance)
                << "pixel " << p << " ppd " << ppd;
            sum += expected.flip[p];
        }
        EXPECT_NEAR(r->mean, sum / static_cast<double>(expected.flip.size()), kDoubleTolerance);
    }
}

TEST(Flip, IdenticalImagesHaveZeroError) {
    const Image ldr = ldr_reference(40, 30), hdr = hdr_reference(40, 30);
    for (const auto& [image, options] :
         {std::pair{&ldr, ldr_options()}, std::pair{&hdr, hdr_options()}}) {
        const Result<FlipResult> r = flip(*image, *image, options);
        ASSERT_TRUE(r.ok()) << r.error().message;
        EXPECT_EQ(r->mean, 0.0);
        for (float v : r->error_map.pixels) ASSERT_EQ(v, 0.0f);
    }
}

// A uniform patch has no edges or points, so FLIP is the colour error alone, and the CSF filters
// (normalised to 1) leave its colour unchanged: the HyAB formula computed by hand.
TEST(Flip, UniformPatchesGiveTheHyabColourError) {
    const std::vector<std::pair<D3, D3>> pairs = {
        {{0.5, 0.5, 0.5}, {0.7, 0.5, 0.5}},     // below the knee p_c c_max
        {{0.2, 0.4, 0.6}, {0.25, 0.38, 0.5}},   // small
        {{0.9, 0.1, 0.1}, {0.1, 0.1, 0.9}},     // above the knee
        {{0.0, 0.0, 0.0}, {0.001, 0.002, 0.0}}  // dark: the linear part of L*
    };
    for (const auto& [a_colour, b_colour] : pairs) {
        Image a(12, 9, 3), b(12, 9, 3);
        for (std::size_t p = 0; p < a.pixel_count(); ++p)
            for (int c = 0; c < 3; ++c) {
                a.pixels[3 * p + c] = static_cast<float>(a_colour[c]);
                b.pixels[3 * p + c] = static_cast<float>(b_colour[c]);
            }
        D3 af{}, bf{};
        for (int c = 0; c < 3; ++c) {
            af[c] = a.pixels[c];  // the float inputs, exactly
            bf[c] = b.pixels[c];
        }
        const double expected = colour_error_by_hand(af, bf);
        const Result<FlipResult> r = flip(a, b, ldr_options());
        ASSERT_TRUE(r.ok()) << r.error().message;
        EXPECT_NEAR(r->mean, expected, kUniformTolerance);
        for (float v : r->error_map.pixels) EXPECT_NEAR(v, expected, kUniformTolerance);
    }
    // The largest difference, pure green against pure blue, is c_max itself: an error of 1.
    Image green(5, 4, 3), blue(5, 4, 3);
    for (std::size_t p = 0; p < green.pixel_count(); ++p) {
        green.pixels[3 * p + 1] = 1;
        blue.pixels[3 * p + 2] = 1;
    }
    const Result<FlipResult> extreme = flip(green, blue, ldr_options());
    ASSERT_TRUE(extreme.ok()) << extreme.error().message;
    EXPECT_NEAR(extreme->mean, 1.0, kUniformTolerance);
}

// An edge moved by one pixel: beside it the feature error ΔE_f raises FLIP above the colour error
// (ΔE_c^(1 − ΔE_f) > ΔE_c for ΔE_c < 1); far from it (beyond the filters) FLIP is 0.
TEST(Flip, MovedEdgeGivesFeatureError) {
    Image a(48, 8, 3, 0.1f), b(48, 8, 3, 0.1f);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 48; ++x)
            for (int c = 0; c < 3; ++c) {
                if (x >= 24) a.at(x, y, c) = 0.8f;
                if (x >= 25) b.at(x, y, c) = 0.8f;
            }
    const Result<FlipResult> r = flip(a, b, ldr_options());
    ASSERT_TRUE(r.ok()) << r.error().message;
    const BruteForce brute = brute_force_ldr_flip(a, b, kFlipDefaultPixelsPerDegree);
    for (std::size_t p = 0; p < brute.flip.size(); ++p)
        EXPECT_NEAR(r->error_map.pixels[p], brute.flip[p], kDoubleTolerance) << p;
    // Column 23, left of both edges: A steps up one pixel nearer than B.
    const std::size_t beside = 3 * 48 + 23;
    EXPECT_GT(brute.feature[beside], 0.3);
    EXPECT_GT(r->error_map.pixels[beside], brute.colour[beside] + 0.1);
    // Spatial filter radius 10 and feature radius 9 at 67 ppd: columns 0–13 and 35–47 see no
    // difference at all.
    for (int y = 0; y < 8; ++y) {
        for (int x : {0, 13, 35, 47}) EXPECT_EQ(r->error_map.at(x, y, 0), 0.0f) << x << ", " << y;
        for (int x = 21; x <= 27; ++x) EXPECT_GT(r->error_map.at(x, y, 0), 0.05f) << x;
    }
}

TEST(Flip, ErrorsLieInZeroToOneAndLdrFlipIsSymmetric) {
    Image a(33, 27, 3), b(33, 27, 3);
    Lcg lcg{99u};
    for (float& v : a.pixels) v = lcg.next() < 0.5f ? 0.0f : 1.0f;  // the harshest LDR inputs
    for (float& v : b.pixels) v = lcg.next();
    const Result<FlipResult> ab = flip(a, b, ldr_options()), ba = flip(b, a, ldr_options());
    ASSERT_TRUE(ab.ok() && ba.ok());
    EXPECT_GT(ab->mean, 0.3);
    for (std::size_t p = 0; p < ab->error_map.pixels.size(); ++p) {
        const float v = ab->error_map.pixels[p];
        ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << v;
        // Every step is a function of |difference| of the two images' values.
        ASSERT_EQ(v, ba->error_map.pixels[p]) << p;
    }
    // HDR input far outside [0, 1], negative values included.
    for (float& v : a.pixels) v = 1000.0f * (lcg.next() - 0.1f);
    const Result<FlipResult> hdr = flip(a, b, hdr_options());
    ASSERT_TRUE(hdr.ok()) << hdr.error().message;
    for (float v : hdr->error_map.pixels) ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << v;
}

// ---- HDR-FLIP ------------------------------------------------------------------------------

// Narkowicz's ACES fit, in double: T(c) = y (2.51 y + 0.03) / (y (2.43 y + 0.59) + 0.14), y = 0.6
// c.
double aces(double c) {
    const double y = 0.6 * c;
    return y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14);
}

TEST(Flip, AutomaticExposuresComeFromTheReferenceLuminance) {
    // x_max, the input ACES maps to 0.85, by bisection (T is increasing on [0, 10]).
    double lo = 0, hi = 10;
    for (int i = 0; i < 200; ++i) (aces(0.5 * (lo + hi)) < 0.85 ? lo : hi) = 0.5 * (lo + hi);
    const double x_max = 0.5 * (lo + hi);

    // Grey pixels: luminance = value. Sorted: 0.5 ×4, 2 ×3, 8 ×1, 64 ×1 → median (index 4) 2.
    const std::vector<float> greys = {2, 0.5f, 64, 0.5f, 2, 8, 0.5f, 2, 0.5f};
    Image reference(3, 3, 3), test(3, 3, 3);
    for (std::size_t p = 0; p < greys.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            reference.pixels[3 * p + c] = greys[p];
            test.pixels[3 * p + c] = 1.1f * greys[p];
        }
    Result<FlipResult> r = flip(test, reference, hdr_options());
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_NEAR(r->start_exposure, std::log2(x_max / 64), kReferenceExposureTolerance);
    EXPECT_NEAR(r->stop_exposure, std::log2(x_max / 2), kReferenceExposureTolerance);
    EXPECT_EQ(r->exposures, 5);  // ⌈log2(64 / 2)⌉ = 5

    // Coloured: Y = 0.2126 R + 0.7152 G + 0.0722 B.
    Image coloured = reference;
    coloured.at(2, 0, 0) = 100;  // (100, 64, 64): Y = 21.26 + 45.7728 + 4.6208 = 71.6536
    r = flip(test, coloured, hdr_options());
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_NEAR(r->start_exposure, std::log2(x_max / 71.6536), kReferenceExposureTolerance);

    // More than half black: the median of the positive luminances (0.5, 0.5, 2, 8 → index 2: 2).
    Image dark(3, 3, 3, 0.0f);
    for (int i : {0, 1, 2, 3}) {
        const float v = std::array{0.5f, 0.5f, 2.0f, 8.0f}[i];
        for (int c = 0; c < 3; ++c) dark.pixels[3 * i + c] = v;
    }
    r = flip(test, dark, hdr_options());
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_NEAR(r->stop_exposure, std::log2(x_max / 2), kReferenceExposureTolerance);

    // Given exposures are used as they are; the count is ⌈stop − start⌉, at least 2.
    FlipOptions given = hdr_options();
    given.start_exposure = -1.5;
    given.stop_exposure = -1.0;
    r = flip(test, reference, given);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->start_exposure, -1.5);
    EXPECT_EQ(r->stop_exposure, -1.0);
    EXPECT_EQ(r->exposures, 2);
    given.stop_exposure.reset();  // only the stop from the reference
    r = flip(test, reference, given);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->start_exposure, -1.5);
    EXPECT_NEAR(r->stop_exposure, std::log2(x_max / 2), kReferenceExposureTolerance);
}

// HDR-FLIP is, per pixel, the largest LDR-FLIP over the tone-mapped exposures.
TEST(Flip, HdrFlipIsTheLargestLdrFlipOverTheExposures) {
    const Image reference = hdr_reference(40, 28), test = hdr_test(reference);
    auto at_exposure = [&](double e) {
        FlipOptions options = hdr_options();
        options.start_exposure = e;
        options.stop_exposure = e;
        options.exposures = 1;
        Result<FlipResult> r = flip(test, reference, options);
        EXPECT_TRUE(r.ok()) << r.error().message;
        return r->error_map;
    };
    const Image low = at_exposure(-3.0), high = at_exposure(1.5);
    FlipOptions both = hdr_options();
    both.start_exposure = -3.0;
    both.stop_exposure = 1.5;
    both.exposures = 2;
    const Result<FlipResult> r = flip(test, reference, both);
    ASSERT_TRUE(r.ok()) << r.error().message;
    double sum = 0;
    for (std::size_t p = 0; p < low.pixels.size(); ++p) {
        ASSERT_EQ(r->error_map.pixels[p], std::max(low.pixels[p], high.pixels[p])) << p;
        sum += r->error_map.pixels[p];
    }
    EXPECT_NEAR(r->mean, sum / static_cast<double>(low.pixels.size()), 1e-12);

    // One exposure is LDR-FLIP of the images exposed and tone mapped by hand.
    Image mapped_test = test, mapped_reference = reference;
    for (Image* image : {&mapped_test, &mapped_reference})
        for (float& v : image->pixels)
            v = static_cast<float>(std::clamp(aces(std::exp2(1.5) * v), 0.0, 1.0));
    const Result<FlipResult> ldr = flip(mapped_test, mapped_reference, ldr_options());
    ASSERT_TRUE(ldr.ok()) << ldr.error().message;
    for (std::size_t p = 0; p < high.pixels.size(); ++p)
        EXPECT_NEAR(high.pixels[p], ldr->error_map.pixels[p], kDoubleTolerance) << p;
}

TEST(Flip, AutomaticRangeLooksAtTheColourChannels) {
    Image a(8, 8, 4, 0.5f), b(8, 8, 4, 0.5f);
    for (std::size_t p = 0; p < a.pixel_count(); ++p) a.pixels[4 * p + 3] = 2.0f;  // alpha only
    a.at(3, 3, 1) = 0.9f;
    Result<FlipResult> r = flip(a, b);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_FALSE(r->hdr);
    EXPECT_GT(r->mean, 0.0);
    b.at(5, 2, 0) = 1.5f;  // the reference's colour above 1
    r = flip(a, b);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_TRUE(r->hdr);
    EXPECT_EQ(r->exposures, 2);  // ⌈log2(0.7126 / 0.5)⌉ = 1 is raised to the minimum, 2
    // Automatic is then exactly FlipRange::hdr.
    FlipOptions hdr;
    hdr.range = FlipRange::hdr;
    const Result<FlipResult> forced = flip(a, b, hdr);
    ASSERT_TRUE(forced.ok()) << forced.error().message;
    EXPECT_EQ(forced->mean, r->mean);
    b.at(5, 2, 0) = 0.5f;
    a.at(0, 0, 2) = 1.0001f;  // the test's colour above 1
    r = flip(a, b);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_TRUE(r->hdr);
}

TEST(Flip, ChannelsAlphaAndGrey) {
    const Image rgb_a = ldr_test(ldr_reference(20, 14)), rgb_b = ldr_reference(20, 14);
    // RGBA: alpha ignored.
    Image rgba_a(20, 14, 4, 0.25f), rgba_b(20, 14, 4, 1.0f);
    for (std::size_t p = 0; p < rgb_a.pixel_count(); ++p)
        for (int c = 0; c < 3; ++c) {
            rgba_a.pixels[4 * p + c] = rgb_a.pixels[3 * p + c];
            rgba_b.pixels[4 * p + c] = rgb_b.pixels[3 * p + c];
        }
    const Result<FlipResult> rgb = flip(rgb_a, rgb_b, ldr_options());
    const Result<FlipResult> rgba = flip(rgba_a, rgba_b, ldr_options());
    ASSERT_TRUE(rgb.ok() && rgba.ok());
    EXPECT_EQ(rgb->mean, rgba->mean);
    // Grey (1 channel) is R = G = B; grey + alpha (2 channels) likewise.
    Image grey_a(20, 14, 1), grey_b(20, 14, 1), grey3_a(20, 14, 3), grey3_b(20, 14, 3);
    Image ga_a(20, 14, 2, 0.0f), ga_b(20, 14, 2, 1.0f);
    for (std::size_t p = 0; p < grey_a.pixel_count(); ++p) {
        grey_a.pixels[p] = ga_a.pixels[2 * p] = rgb_a.pixels[3 * p + 1];
        grey_b.pixels[p] = ga_b.pixels[2 * p] = rgb_b.pixels[3 * p + 1];
        for (int c = 0; c < 3; ++c) {
            grey3_a.pixels[3 * p + c] = grey_a.pixels[p];
            grey3_b.pixels[3 * p + c] = grey_b.pixels[p];
        }
    }
    const Result<FlipResult> grey = flip(grey_a, grey_b, ldr_options());
    const Result<FlipResult> grey3 = flip(grey3_a, grey3_b, ldr_options());
    const Result<FlipResult> grey_alpha = flip(ga_a, ga_b, ldr_options());
    ASSERT_TRUE(grey.ok() && grey3.ok() && grey_alpha.ok());
    EXPECT_GT(grey->mean, 0.0);
    EXPECT_EQ(grey->mean, grey3->mean);
    EXPECT_EQ(grey->mean, grey_alpha->mean);
}

TEST(Flip, MaskAveragesTheSelectedPixels) {
    const Image reference = ldr_reference(24, 16), test = ldr_test(reference);
    Image mask(24, 16, 1, 0.0f);
    mask.at(3, 4, 0) = 1.0f;
    mask.at(20, 10, 0) = 0.75f;
    mask.at(12, 12, 0) = 0.5f;  // not > 0.5
    FlipOptions options = ldr_options();
    const Result<FlipResult> all = flip(test, reference, options);
    options.mask = &mask;
    const Result<FlipResult> masked = flip(test, reference, options);
    ASSERT_TRUE(all.ok() && masked.ok());
    EXPECT_EQ(masked->pixels, 2u);
    // The filters see every pixel: the map is the same; only the average changes.
    EXPECT_EQ(masked->error_map.pixels, all->error_map.pixels);
    const double expected =
        (static_cast<double>(all->error_map.at(3, 4, 0)) + all->error_map.at(20, 10, 0)) / 2;
    EXPECT_NEAR(masked->mean, expected, 1e-12);
    EXPECT_GT(masked->mean, 0.0);

    Image wrong(23, 16, 1, 1.0f);
    options.mask = &wrong;
    Result<FlipResult> r = flip(test, reference, options);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "mask is 23x16 but the images are 24x16");
    Image none(24, 16, 3, 0.5f);
    options.mask = &none;
    r = flip(test, reference, options);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "mask selects no pixel (no value of channel 0 is > 0.5)");
    Image nan_mask(24, 16, 1, 1.0f);
    nan_mask.at(2, 1, 0) = std::numeric_limits<float>::quiet_NaN();
    options.mask = &nan_mask;
    r = flip(test, reference, options);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message,
              "mask has 1 non-finite pixel, the first at (2, 1) channel 0 = nan");
}

TEST(Flip, BadInputIsAnError) {
    const Image a(4, 4, 3, 0.5f), b(4, 4, 3, 0.25f);
    auto message = [](const Result<FlipResult>& r) {
        return r.ok() ? std::string("(no error)") : r.error().message;
    };
    EXPECT_EQ(message(flip(a, Image(3, 4, 3))), "images differ in size: A is 4x4, B is 3x4");
    EXPECT_EQ(message(flip(a, Image(4, 4, 1))), "images differ in channels: A has 3, B has 1");
    EXPECT_EQ(message(flip(Image(), b)), "A is empty");
    EXPECT_EQ(message(flip(a, Image())), "B is empty");
    Image nan = a;
    nan.at(1, 2, 0) = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(message(flip(nan, b)),
              "A has 1 non-finite pixel, the first at (1, 2) channel 0 = nan; B has 0 "
              "non-finite pixels");
    Image inf = b;
    inf.at(3, 3, 2) = std::numeric_limits<float>::infinity();
    EXPECT_EQ(message(flip(a, inf)),
              "A has 0 non-finite pixels; B has 1 non-finite pixel, the first at (3, 3) channel 2 "
              "= inf");

    FlipOptions options;
    for (const double ppd : {0.0, -5.0, 1001.0, std::numeric_limits<double>::quiet_NaN()}) {
        options.pixels_per_degree = ppd;
        EXPECT_EQ(message(flip(a, b, options))
                      .rfind("pixels per degree must be finite, > 0 and <= 1000 (got ", 0),
                  0u)
            << ppd;
    }
    options.pixels_per_degree = 0.001;  // tiny but valid: filters of one pixel
    const Result<FlipResult> tiny = flip(a, b, options);
    ASSERT_TRUE(tiny.ok()) << tiny.error().message;
    EXPECT_TRUE(std::isfinite(tiny->mean));

    options = hdr_options();
    options.start_exposure = 2;
    options.stop_exposure = 1;
    EXPECT_EQ(message(flip(a, b, options)), "start exposure 2 is above stop exposure 1");
    options.stop_exposure = std::numeric_limits<double>::infinity();
    EXPECT_EQ(message(flip(a, b, options)), "stop exposure must be finite (got inf)");
    options.stop_exposure.reset();
    options.start_exposure = 4;  // above the stop from the reference, log2(2.119 / 0.25) = 3.08
    EXPECT_EQ(message(flip(a, b, options)).rfind("start exposure 4 is above stop exposure 3.08", 0),
              0u)
        << message(flip(a, b, options));
    options = hdr_options();
    options.exposures = -1;
    EXPECT_EQ(message(flip(a, b, options)),
              "the number of exposures must be >= 0, 0 for automatic (got -1)");
    EXPECT_EQ(message(flip(a, Image(4, 4, 3, 0.0f), hdr_options())),
              "B has no pixel of positive luminance: HDR-FLIP's automatic exposures are "
              "undefined; give the start and stop exposures");
}

TEST(Flip, PixelsPerDegreeOfThePaper) {
    EXPECT_NEAR(flip_pixels_per_degree(0.7, 3840, 0.7), 67.02064327658225, 1e-12);
    EXPECT_EQ(kFlipDefaultPixelsPerDegree, flip_pixels_per_degree(0.7, 3840, 0.7));
    EXPECT_EQ(FlipOptions{}.pixels_per_degree, kFlipDefaultPixelsPerDegree);
}

TEST(Flip, SameMapOnOneThreadAsOnMany) {
    const Image reference = hdr_reference(40, 30), test = hdr_test(reference);
    const Result<FlipResult> many = flip(test, reference, hdr_options());
    Result<FlipResult> one = Error{""};
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = flip(test, reference, hdr_options());
    }
    ASSERT_TRUE(many.ok() && one.ok());
    EXPECT_EQ(many->error_map.pixels, one->error_map.pixels);
    EXPECT_EQ(many->mean, one->mean);
}

}  // namespace
}  // namespace footprint
