// Tests of the plane view renderer (plane_view.h) and the built-in texture.
#include "plane_view.h"

#include "math/sample_patterns.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "builtin_texture.h"
#include "texture/mip_pyramid.h"

namespace footprint {
namespace {

PlaneViewOptions small_view(int width) {
    PlaneViewOptions view;
    view.width = width;
    view.height = plane_view_height(width);
    return view;
}

MipPyramid pyramid_of(const Image& image) {
    MipPyramidOptions options;
    options.summed_area_table = true;
    return MipPyramid::build(image, options);
}

constexpr TextureFilter kFilters[] = {TextureFilter::nearest,   TextureFilter::bilinear,
                                      TextureFilter::trilinear, TextureFilter::footprint_assembly,
                                      TextureFilter::ewa,       TextureFilter::summed_area};

TEST(PlaneView, HeightIsNineSixteenths) {
    EXPECT_EQ(plane_view_height(480), 270);
    EXPECT_EQ(plane_view_height(1920), 1080);
    EXPECT_EQ(plane_view_height(1), 1);
}

TEST(PlaneView, HorizonSplitsHitsAndMisses) {
    const PlaneView view(small_view(480));
    const double h = view.horizon_row();
    EXPECT_GT(h, 0.0);
    EXPECT_LT(h, 270.0);
    EXPECT_TRUE(view.hits_row(h + 0.01));
    EXPECT_FALSE(view.hits_row(h - 0.01));
    EXPECT_FALSE(view.sample(240.5, 0.5).hit);
    EXPECT_TRUE(view.sample(240.5, 269.5).hit);
}

// (a) The analytic ray-differential derivatives against central differences of (s, t) over pixel
// offsets ±δ, δ = 1e-3 px, in double. Near a row p pixels below the horizon, (s, t) ∝ 1/p, whose
// central difference has a relative truncation error ≈ (δ/p)² ≤ 1e-6 for p ≥ ½, and the rounding
// error is ≈ 1e-16·|s|/δ relative to |s|·δ/p, about 1e-10; 1e-3 is therefore a loose bound that any
// wrong factor, sign or missing term (e.g. forgetting ∂τ) exceeds by orders of magnitude.
TEST(PlaneView, DerivativesMatchCentralDifferences) {
    for (double yaw : {0.0, 25.0, -70.0}) {
        PlaneViewOptions options = small_view(480);
        options.yaw_degrees = yaw;
        const PlaneView view(options);
        const double delta = 1e-3;
        int checked = 0;
        for (int j = 0; j < options.height; j += 3) {
            const double y = j + 0.5;
            if (!view.hits_row(y - 1.0)) continue;  // keep p ≥ ½ px for the difference stencil
            for (int i = 0; i < options.width; i += 17) {
                const double x = i + 0.5;
                const PlaneSample p = view.sample(x, y);
                ASSERT_TRUE(p.hit);
                double s1, t1, s0, t0;
                ASSERT_TRUE(view.hit(x + delta, y, s1, t1));
                ASSERT_TRUE(view.hit(x - delta, y, s0, t0));
                const double fd_sx = (s1 - s0) / (2 * delta), fd_tx = (t1 - t0) / (2 * delta);
                ASSERT_TRUE(view.hit(x, y + delta, s1, t1));
                ASSERT_TRUE(view.hit(x, y - delta, s0, t0));
                const double fd_sy = (s1 - s0) / (2 * delta), fd_ty = (t1 - t0) / (2 * delta);
                // Relative to the size of the Jacobian (a component can be exactly 0).
                const double scale = std::max(
                    {std::abs(p.dsdx), std::abs(p.dtdx), std::abs(p.dsdy), std::abs(p.dtdy)});
                ASSERT_GT(scale, 0.0);
                EXPECT_NEAR(p.dsdx, fd_sx, 1e-3 * scale) << "pixel " << i << "," << j;
                EXPECT_NEAR(p.dtdx, fd_tx, 1e-3 * scale) << "pixel " << i << "," << j;
                EXPECT_NEAR(p.dsdy, fd_sy, 1e-3 * scale) << "pixel " << i << "," << j;
                EXPECT_NEAR(p.dtdy, fd_ty, 1e-3 * scale) << "pixel " << i << "," << j;
                ++checked;
            }
        }
        EXPECT_GT(checked, 1000);
    }
}

TEST(PlaneView, FootprintGrowsTowardsTheHorizon) {
    const PlaneViewOptions options = small_view(480);
    const PlaneView view(options);
    const PlaneSample near = view.sample(240.5, 269.5);
    const PlaneSample far = view.sample(240.5, std::ceil(view.horizon_row()) + 2.5);
    const double near_y = std::hypot(near.dsdy, near.dtdy), far_y = std::hypot(far.dsdy, far.dtdy);
    const double far_x = std::hypot(far.dsdx, far.dtdx);
    EXPECT_GT(far_y, 100 * near_y);
    EXPECT_GT(far_y, 10 * far_x);  // strongly anisotropic near the horizon
}

// (b) Rows are independent: the images are bit-identical for 1 and 2 threads.
TEST(PlaneView, ThreadCountDoesNotChangeTheImage) {
    const MipPyramid pyramid = pyramid_of(make_builtin_texture(256));
    const PlaneViewOptions view = small_view(96);
    PlaneReferenceOptions reference;
    reference.samples_per_axis = 4;
    auto render_all = [&] {
        std::vector<Image> images;
        for (TextureFilter f : kFilters) {
            LookupOptions lookup;
            lookup.filter = f;
            images.push_back(render_plane_view(pyramid, view, lookup));
        }
        images.push_back(render_plane_reference(pyramid, view, reference));
        return images;
    };
    std::vector<Image> one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = render_all();
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = render_all();
    }
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t i = 0; i < one.size(); ++i)
        EXPECT_TRUE(one[i].pixels == two[i].pixels) << "image " << i;
}

// (c) On a constant texture every filter, and the reference, returns the constant on the plane and
// the sky elsewhere.
TEST(PlaneView, ConstantTextureGivesTheConstant) {
    const float value[3] = {0.25f, 0.5f, 0.75f};
    Image texture(37, 20, 3);  // odd, non-square: every pyramid level and the SAT are exercised
    for (std::size_t p = 0; p < texture.pixel_count(); ++p)
        for (int c = 0; c < 3; ++c) texture.pixels[p * 3 + c] = value[c];
    const MipPyramid pyramid = pyramid_of(texture);
    const PlaneViewOptions options = small_view(128);
    const PlaneView view(options);
    std::vector<Image> images;
    for (TextureFilter f : kFilters) {
        LookupOptions lookup;
        lookup.filter = f;
        images.push_back(render_plane_view(pyramid, options, lookup));
    }
    PlaneReferenceOptions reference;
    reference.samples_per_axis = 3;
    images.push_back(render_plane_reference(pyramid, options, reference));
    for (std::size_t i = 0; i < images.size(); ++i) {
        const Image& image = images[i];
        ASSERT_EQ(image.channels, 3);
        int plane_pixels = 0;
        for (int y = 0; y < image.height; ++y) {
            const bool reference_image = i + 1 == images.size();
            const bool on_plane = reference_image ? view.covers_row(y) : view.hits_row(y + 0.5);
            const bool sky = !view.hits_row(y + 0.5 + 1.5);
            for (int x = 0; x < image.width; ++x) {
                for (int c = 0; c < 3; ++c) {
                    if (on_plane) {
                        ASSERT_NEAR(image.at(x, y, c), value[c], 1e-5f)
                            << "image " << i << " pixel " << x << "," << y;
                    } else if (sky) {
                        ASSERT_EQ(image.at(x, y, c), options.sky[c]) << "image " << i;
                    }
                }
                plane_pixels += on_plane;
            }
        }
        EXPECT_GT(plane_pixels, image.width * image.height / 2);
    }
}

// (d) A real measurement on the built-in texture: the anisotropic filters are much closer to the
// supersampled ground truth than nearest-texel sampling (96 × 54 pixels).
TEST(PlaneView, AnisotropicFiltersBeatNearestOnTheBuiltinTexture) {
    const MipPyramid pyramid = pyramid_of(make_builtin_texture(512));
    const PlaneViewOptions view = small_view(96);
    PlaneReferenceOptions reference_options;
    reference_options.samples_per_axis = 8;
    const Image reference = render_plane_reference(pyramid, view, reference_options);
    auto rmse = [&](TextureFilter f) {
        LookupOptions lookup;
        lookup.filter = f;
        std::size_t pixels = 0;
        const double e =
            plane_rmse(render_plane_view(pyramid, view, lookup), reference, view, &pixels);
        EXPECT_GT(pixels, 2000u);
        return e;
    };
    const double nearest = rmse(TextureFilter::nearest);
    const double fa = rmse(TextureFilter::footprint_assembly);
    const double ewa = rmse(TextureFilter::ewa);
    EXPECT_LT(fa, 0.75 * nearest) << "fa " << fa << " nearest " << nearest;
    EXPECT_LT(ewa, 0.75 * nearest) << "ewa " << ewa << " nearest " << nearest;
    EXPECT_GT(fa, 0.0);
}

TEST(PlaneView, RmseOfAnImageWithItselfIsZero) {
    const PlaneViewOptions view = small_view(64);
    Image a(view.width, view.height, 3, 0.5f);
    Image b = a;
    EXPECT_EQ(plane_rmse(a, b, view), 0.0);
    for (float& v : b.pixels) v += 0.25f;
    EXPECT_NEAR(plane_rmse(a, b, view), 0.25, 1e-6);
}

TEST(PlaneView, InverseNormalCdf) {
    for (double x : {-5.0, -3.0, -2.0, -1.0, -0.3, 0.0, 0.7, 1.5, 2.5, 4.0}) {
        const double p = 0.5 * std::erfc(-x / std::sqrt(2.0));
        EXPECT_NEAR(inverse_normal_cdf(p), x, 1e-7 * std::max(1.0, std::abs(x))) << x;
    }
}

TEST(BuiltinTexture, IsDeterministicLinearRgbInUnitRange) {
    const Image a = make_builtin_texture(256), b = make_builtin_texture(256);
    EXPECT_EQ(a.width, 256);
    EXPECT_EQ(a.height, 256);
    EXPECT_EQ(a.channels, 3);
    EXPECT_TRUE(a.pixels == b.pixels);
    float lo = 1, hi = 0;
    for (float v : a.pixels) lo = std::min(lo, v), hi = std::max(hi, v);
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_LT(lo, 0.05f);  // has contrast
    EXPECT_GT(hi, 0.8f);
}

}  // namespace
}  // namespace footprint
