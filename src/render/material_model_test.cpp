// Tests of the metallic-roughness model (render/material_model.h): its texels by hand, and the
// renderer's images against closed forms and the reference.
#include "render/material_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "metrics/test_rmse.h"
#include "render/camera.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render/test_scene_parts.h"

namespace footprint {
namespace {

using detail::metallic_roughness_texels;
using detail::resampled;
using test::rmse;

// Texel arithmetic in float: a few ulps.
constexpr float kTexel = 1e-6f;

TEST(MaterialModel, TexelsAreGltfsMixOfADielectricAndAMetal) {
    Image base(2, 1, 3), material(2, 1, 3);
    const float c[2][3] = {{1.0f, 0.78f, 0.34f}, {0.2f, 0.5f, 0.9f}};
    const float rough[2] = {0.5f, 1.0f}, metal[2] = {1.0f, 0.25f};
    for (int x = 0; x < 2; ++x) {
        for (int k = 0; k < 3; ++k) base.at(x, 0, k) = c[x][k];
        material.at(x, 0, 0) = 0.7f;  // occlusion: unused
        material.at(x, 0, 1) = rough[x];
        material.at(x, 0, 2) = metal[x];
    }
    const Vec3 factor{1, 0.5f, 1};
    const auto texels = metallic_roughness_texels(&base, factor, &material, 0.8f, 0.6f);
    ASSERT_EQ(texels.diffuse.width, 2);
    const float f[3] = {factor.x, factor.y, factor.z};
    for (int x = 0; x < 2; ++x) {
        const float m = 0.8f * metal[x], r = 0.6f * rough[x];
        for (int k = 0; k < 3; ++k) {
            const float colour = f[k] * c[x][k];
            EXPECT_NEAR(texels.diffuse.at(x, 0, k), colour * (1 - m), kTexel) << x << k;
            EXPECT_NEAR(texels.f0.at(x, 0, k), 0.04f * (1 - m) + colour * m, kTexel) << x << k;
        }
        EXPECT_NEAR(texels.variance.at(x, 0, 0), 0.5f * std::pow(r, 4.0f), kTexel) << x;
    }
    // Without a metallic-roughness texture: the factors throughout; a grey base texture.
    Image grey(1, 1, 1, 0.5f);
    const auto plain = metallic_roughness_texels(&grey, {1, 1, 1}, nullptr, 0, 1);
    EXPECT_NEAR(plain.diffuse.at(0, 0, 2), 0.5f, kTexel);
    EXPECT_NEAR(plain.f0.at(0, 0, 1), 0.04f, kTexel);
    EXPECT_NEAR(plain.variance.at(0, 0, 0), 0.5f, kTexel);
}

TEST(MaterialModel, ResamplingInterpolatesAtTheFinerTexelCentresAndWraps) {
    Image row(2, 1, 1);
    row.at(0, 0, 0) = 1, row.at(1, 0, 0) = 5;
    const Image four = resampled(row, 4, 1);
    // Centres at 0.125, 0.375, … of the period: −¼, ¼, ¾, 1¼ source texels from texel 0's centre.
    EXPECT_NEAR(four.at(0, 0, 0), 0.25f * 5 + 0.75f * 1, kTexel);  // wraps to texel 1
    EXPECT_NEAR(four.at(1, 0, 0), 0.75f * 1 + 0.25f * 5, kTexel);
    EXPECT_NEAR(four.at(2, 0, 0), 0.25f * 1 + 0.75f * 5, kTexel);
    EXPECT_NEAR(four.at(3, 0, 0), 0.75f * 5 + 0.25f * 1, kTexel);
    EXPECT_EQ(resampled(row, 2, 1).pixels, row.pixels);
    // Different sizes: the texels come at the larger.
    const Image material(4, 2, 3, 1.0f);
    const auto texels = metallic_roughness_texels(&row, {1, 1, 1}, &material, 0, 1);
    EXPECT_EQ(texels.f0.width, 4);
    EXPECT_EQ(texels.f0.height, 2);
}

// ---------------------------------------------------------------------------------------------
// Images

std::shared_ptr<const Image> constant_image(int w, int h, Vec3 c) {
    auto image = std::make_shared<Image>(w, h, 3);
    for (std::size_t i = 0; i < image->pixel_count(); ++i) {
        image->pixels[i * 3 + 0] = c.x, image->pixels[i * 3 + 1] = c.y;
        image->pixels[i * 3 + 2] = c.z;
    }
    return image;
}

MaterialDesc metallic_roughness(Vec3 base, float metallic, float roughness) {
    MaterialDesc m;
    m.model = MaterialDesc::Model::metallic_roughness;
    m.highlight = MaterialDesc::Highlight::ggx;
    m.base_color = base, m.metallic = metallic, m.roughness = roughness;
    return m;
}

// The plane y = 0 seen from above at an angle.
SceneDesc plane_scene(const MaterialDesc& material) {
    SceneDesc scene;
    scene.width = 48, scene.height = 32;
    scene.camera.position = {0, 2, 4};
    scene.camera.look_at = {0, 0, 0};
    scene.camera.fov_y_deg = 50;
    PlaneShape plane;
    plane.infinite = true;
    scene.objects.push_back({"plane", plane, material});
    return scene;
}

EnvironmentDesc constant_environment(Vec3 colour) {
    return test::latlong_environment(constant_image(64, 32, colour), "constant");
}

const FilterMode kModes[] = {FilterMode::bilinear,  FilterMode::trilinear, FilterMode::fa,
                             FilterMode::fa_rough,  FilterMode::ewa_rough, FilterMode::reference,
                             FilterMode::lean,      FilterMode::toksvig,   FilterMode::specular_aa,
                             FilterMode::stochastic};

// A smooth metal (r = 0) in a white sky mirrors it tinted by Fresnel per channel, F0 = its base
// colour; a smooth dielectric adds its diffuse colour × the sky to Fresnel of F0 = 0.04. In every
// mode, at every pixel that sees the plane.
TEST(MaterialModel, SmoothMetalAndDielectricInAWhiteSkyByHand) {
    const Vec3 gold{1.0f, 0.78f, 0.34f};
    for (const float metallic : {1.0f, 0.0f}) {
        SceneDesc desc = plane_scene(metallic_roughness(gold, metallic, 0));
        desc.environment = constant_environment({1, 1, 1});
        Result<RenderScene> scene = prepare_render_scene(desc);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        const PinholeCamera camera(desc.camera, desc.width, desc.height);
        for (FilterMode mode : kModes) {
            RenderOptions options;
            options.filter = mode;
            options.spp = mode == FilterMode::reference ? 16 : 1;
            const Image image = render(*scene, options);
            for (int y = 0; y < desc.height; y += 3)
                for (int x = 0; x < desc.width; x += 3) {
                    const Vec3d d = normalize(camera.ray(x + 0.5, y + 0.5).ray.direction);
                    if (d.y > -0.5) continue;  // steep enough that Fresnel is flat over a pixel
                    const double w = std::pow(1 + d.y, 5);  // (1 − cos θ)⁵
                    const float c[3] = {gold.x, gold.y, gold.z};
                    for (int k = 0; k < 3; ++k) {
                        const double f0 = metallic * c[k] + 0.04 * (1 - metallic);
                        const double want = (1 - metallic) * c[k] + f0 + (1 - f0) * w;
                        // The reference's samples spread over the pixel, where Fresnel varies.
                        const double tol = mode == FilterMode::reference ? 2e-3 : 1e-5;
                        EXPECT_NEAR(image.at(x, y, k), want, tol)
                            << filter_mode_name(mode) << " m " << metallic << " " << x << "," << y;
                    }
                }
        }
    }
}

// Lambert of BRDF c/π for the lights: two dielectrics differing only in base colour differ by
// (c1 − c2) E cos_l / π (their highlights are the same: F0 = 0.04 whatever the colour).
TEST(MaterialModel, DielectricLambertIsColourOverPi) {
    Image image[2];
    const Vec3 colours[2] = {{0.9f, 0.5f, 0.1f}, {0.1f, 0.2f, 0.3f}};
    for (int i = 0; i < 2; ++i) {
        SceneDesc desc = plane_scene(metallic_roughness(colours[i], 0, 0.5f));
        LightDesc sun;
        sun.type = LightType::directional;
        sun.direction = {0, -1, 0};
        sun.color = {2, 2, 2};
        desc.lights.push_back(sun);
        Result<RenderScene> scene = prepare_render_scene(desc);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        RenderOptions options;
        options.filter = FilterMode::fa_rough;
        image[i] = render(*scene, options);
    }
    const float c0[3] = {0.9f, 0.5f, 0.1f}, c1[3] = {0.1f, 0.2f, 0.3f};
    for (int y = 20; y < 32; y += 4)
        for (int x = 0; x < 48; x += 4)
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(image[0].at(x, y, k) - image[1].at(x, y, k), 2 * (c0[k] - c1[k]) / M_PI,
                            1e-5)
                    << x << "," << y;
}

// The modes that leave K_b out take the texel's own α for the highlight (no pinpoint highlight of
// α → 0): on a flat, constantly rough plane under a light, fa renders what fa-rough renders, and
// the reference converges to it.
TEST(MaterialModel, WithoutRoughnessModesTheHighlightKeepsTheMaterialsAlpha) {
    SceneDesc desc = plane_scene(metallic_roughness({0.9f, 0.6f, 0.3f}, 1, 0.5f));
    LightDesc lamp;
    lamp.type = LightType::point;
    lamp.position = {0, 1.2, 0.5};
    lamp.color = {2, 2, 2};
    desc.lights.push_back(lamp);
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    RenderOptions options;
    options.filter = FilterMode::fa_rough;
    const Image rough = render(*scene, options);
    float peak = 0;
    for (float v : rough.pixels) peak = std::max(peak, v);
    EXPECT_GT(peak, 0.1f);  // the highlight is in the image
    for (FilterMode mode : {FilterMode::fa, FilterMode::trilinear, FilterMode::bilinear}) {
        options.filter = mode;
        const Image plain = render(*scene, options);
        for (std::size_t i = 0; i < plain.pixels.size(); ++i)
            ASSERT_NEAR(plain.pixels[i], rough.pixels[i], 1e-4f * peak) << filter_mode_name(mode);
    }
}

// A lat-long sky with stripes, so that the mirror's roughness shows.
std::shared_ptr<const Image> striped_sky() {
    auto image = std::make_shared<Image>(256, 128, 3);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 256; ++x) {
            const float stripe = ((x / 4) % 2) ? 1.5f : 0.1f;
            float* p = image->at(x, y);
            p[0] = stripe, p[1] = 0.6f * stripe, p[2] = 0.3f + 0.002f * y;
        }
    return image;
}

// fa-rough's error against fa's where the roughness varies (docs/performance.md, accuracy bounds).
constexpr double kRoughnessGain = 0.25;

// A roughness texture (fine stripes of r = 0.4 and 0.6 on a metal) under a striped sky and a
// light: the pyramid filters its slope variance with the normals', so fa-rough lands close to the
// 256-spp reference, much closer than fa, which leaves roughness out. (Stripes of 0.15 and 0.75
// are a mixture of a sharp and a broad lobe that one Gaussian of slopes cannot hold: there the
// highlight's error stays at about half of fa's, docs/method.md.)
TEST(MaterialModel, PerTexelRoughnessIsFilteredTowardsTheReference) {
    auto texture = std::make_shared<Image>(64, 64, 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            texture->at(x, y, 1) = (x / 2) % 2 ? 0.6f : 0.4f;
            texture->at(x, y, 2) = 1;  // metallic
        }
    MaterialDesc material = metallic_roughness({0.95f, 0.64f, 0.54f}, 1, 1);
    material.metallic_roughness_map = ImageSource{{}, texture, "striped roughness"};
    SceneDesc desc = plane_scene(material);
    desc.environment = test::latlong_environment(striped_sky(), "striped sky");
    LightDesc lamp;
    lamp.type = LightType::point;
    lamp.position = {0.5, 1.5, -1};
    lamp.color = {3, 3, 3};
    desc.lights.push_back(lamp);
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    RenderOptions options;
    options.filter = FilterMode::reference;
    options.spp = 256;
    const Image reference = render(*scene, options);
    options.spp = 1;
    options.filter = FilterMode::fa;
    const double fa = rmse(render(*scene, options), reference);
    options.filter = FilterMode::fa_rough;
    const double fa_rough = rmse(render(*scene, options), reference);
    EXPECT_LT(fa_rough, kRoughnessGain * fa) << "fa-rough " << fa_rough << ", fa " << fa;
    // Stochastic filtering draws the texel's micro-slope for the mirror and takes its α for the
    // highlight, as the reference does: with 64 samples it converges there too.
    options.filter = FilterMode::stochastic;
    options.spp = 64;
    const double stochastic = rmse(render(*scene, options), reference);
    EXPECT_LT(stochastic, kRoughnessGain * fa) << "stochastic " << stochastic << ", fa " << fa;
}

}  // namespace
}  // namespace footprint
