// Tests of the error budget (render/error_budget.h): its reference and filtered images are the
// renderer's, and each hybrid takes exactly its own term from the samples.
#include "render/error_budget.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "envmap/env_reference.h"
#include "render/render_scene.h"
#include "render/test_scene_parts.h"

namespace footprint {
namespace {

constexpr int kSpp = 16;

// Fine stripes, so that filtering matters: period 4 texels, 0.1 … 0.9, tinted.
std::shared_ptr<const Image> stripes(int w, int h) {
    auto image = std::make_shared<Image>(w, h, 3);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float v = ((x / 2 + y / 2) % 2) ? 0.9f : 0.1f;
            float* p = image->at(x, y);
            p[0] = v, p[1] = 0.5f * v + 0.2f, p[2] = 0.3f;
        }
    }
    return image;
}

// A flat plane y = 0 seen at an angle, filling the image.
SceneDesc plane_scene(const MaterialDesc& material) {
    SceneDesc scene;
    scene.width = 24, scene.height = 16;
    scene.camera.position = {0, 1.5, 3};
    scene.camera.look_at = {0, 0, -1};
    scene.camera.fov_y_deg = 40;
    PlaneShape plane;
    plane.infinite = true;
    plane.uv_scale = 3;
    scene.objects.push_back({"plane", plane, material});
    return scene;
}

ErrorBudgetImages budget_of(const SceneDesc& desc, RenderScene& scene) {
    Result<RenderScene> prepared = prepare_render_scene(desc);
    EXPECT_TRUE(prepared.ok()) << prepared.error().message;
    scene = std::move(*prepared);
    ErrorBudgetOptions options;
    options.spp = kSpp;
    options.seed = 5;
    return render_error_budget(scene, options);
}

const Image& term_image(const ErrorBudgetImages& budget, BudgetTerm term) {
    for (std::size_t i = 0; i < all_budget_terms().size(); ++i) {
        if (all_budget_terms()[i] == term) return budget.terms[i];
    }
    ADD_FAILURE() << "no term " << budget_term_name(term);
    return budget.filtered;
}

double max_difference(const Image& a, const Image& b, const Image* mask = nullptr) {
    double worst = 0;
    for (std::size_t p = 0; p < a.pixel_count(); ++p) {
        if (mask && mask->pixels[p] < 0.5f) continue;
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(double(a.pixels[p * 3 + c]) - b.pixels[p * 3 + c]));
        }
    }
    return worst;
}

TEST(ErrorBudget, ItsReferenceAndFilteredImagesAreTheRenderersOwn) {
    MaterialDesc material;
    material.base_color_map = ImageSource{{}, stripes(64, 64), "stripes"};
    SceneDesc desc = plane_scene(material);
    desc.lights.push_back({LightType::directional, {-1, -1, -0.5}, {}, {1, 1, 1}});
    RenderScene scene;
    const ErrorBudgetImages budget = budget_of(desc, scene);

    RenderOptions reference;
    reference.filter = FilterMode::reference;
    reference.spp = kSpp;
    reference.seed = 5;
    EXPECT_EQ(budget.reference.pixels, render(scene, reference).pixels);
    RenderOptions filtered;
    filtered.filter = FilterMode::fa_rough;
    EXPECT_EQ(budget.filtered.pixels, render(scene, filtered).pixels);
    ASSERT_EQ(budget.terms.size(), all_budget_terms().size());
}

// A textured plane under one directional light: every factor but the base colour is the same at
// every sample, so the texture hybrid is the reference and every other term leaves the pixel as
// filtered.
TEST(ErrorBudget, OnALitTexturedPlaneTheTextureCarriesAllTheError) {
    MaterialDesc material;
    material.base_color_map = ImageSource{{}, stripes(64, 64), "stripes"};
    SceneDesc desc = plane_scene(material);
    desc.lights.push_back({LightType::directional, {-1, -1, -0.5}, {}, {1, 1, 1}});
    RenderScene scene;
    const ErrorBudgetImages budget = budget_of(desc, scene);
    const Image mask = interior_mask(scene);

    constexpr double kRounding = 2e-6;  // float sums of 16 samples
    EXPECT_GT(max_difference(budget.filtered, budget.reference, &mask), 0.05);
    for (BudgetTerm term : {BudgetTerm::texture, BudgetTerm::lambert, BudgetTerm::factors}) {
        EXPECT_LT(max_difference(term_image(budget, term), budget.reference, &mask), kRounding)
            << budget_term_name(term);
    }
    for (BudgetTerm term :
         {BudgetTerm::bump, BudgetTerm::diffuse, BudgetTerm::highlight, BudgetTerm::fresnel,
          BudgetTerm::env_filter, BudgetTerm::env_footprint, BudgetTerm::env_two_lobes,
          BudgetTerm::reflection, BudgetTerm::mirror}) {
        EXPECT_LT(max_difference(term_image(budget, term), budget.filtered), kRounding)
            << budget_term_name(term);
    }
    // The exact Gaussian of the footprint is closer to the samples than footprint assembly is
    // (both measured on the interior).
    double filtered = 0, exact = 0;
    const Image& texture_filter = term_image(budget, BudgetTerm::texture_filter);
    for (std::size_t i = 0; i < mask.pixel_count(); ++i) {
        if (mask.pixels[i] < 0.5f) continue;
        for (int c = 0; c < 3; ++c) {
            const double r = budget.reference.pixels[i * 3 + c];
            filtered += std::pow(budget.filtered.pixels[i * 3 + c] - r, 2);
            exact += std::pow(texture_filter.pixels[i * 3 + c] - r, 2);
        }
    }
    EXPECT_LT(exact, filtered);
}

// A perfect flat mirror (F0 = 1) in a striped environment: only the reflection differs between
// the samples, so its hybrid is the reference; the exact Gaussian of the mode's own footprint is
// environment_reference() of that footprint.
TEST(ErrorBudget, OnAPerfectMirrorTheReflectionCarriesAllTheError) {
    SceneDesc desc = plane_scene(test::mirror_material(1));
    desc.environment = test::latlong_environment(stripes(128, 64), "striped sky");
    RenderScene scene;
    const ErrorBudgetImages budget = budget_of(desc, scene);
    const Image mask = interior_mask(scene);

    constexpr double kRounding = 2e-6;
    EXPECT_GT(max_difference(budget.filtered, budget.reference, &mask), 0.02);
    for (BudgetTerm term : {BudgetTerm::reflection, BudgetTerm::mirror, BudgetTerm::factors}) {
        EXPECT_LT(max_difference(term_image(budget, term), budget.reference, &mask), kRounding)
            << budget_term_name(term);
    }
    for (BudgetTerm term : {BudgetTerm::texture, BudgetTerm::texture_filter, BudgetTerm::diffuse,
                            BudgetTerm::lambert, BudgetTerm::highlight, BudgetTerm::fresnel}) {
        EXPECT_LT(max_difference(term_image(budget, term), budget.filtered), kRounding)
            << budget_term_name(term);
    }
    // The Gaussians differ from the filtered pixel (a different kernel) but not wildly.
    for (BudgetTerm term :
         {BudgetTerm::env_filter, BudgetTerm::env_footprint, BudgetTerm::env_two_lobes}) {
        const double d = max_difference(term_image(budget, term), budget.filtered, &mask);
        EXPECT_GT(d, 1e-4) << budget_term_name(term);
        EXPECT_LT(d, 0.5) << budget_term_name(term);
    }
}

// A local map around the mirror (scene/scene.h's local_environments): the exact Gaussians are
// taken over the map the pixel reflects, not the scene's. With uniform maps every Gaussian's
// integral is that map's colour, which the filtered pixel shows too.
TEST(ErrorBudget, TheExactReflectionReadsTheLocalMapThePixelReflects) {
    SceneDesc desc = plane_scene(test::mirror_material(1));
    auto uniform = [](float r, float g, float b) {
        auto image = std::make_shared<Image>(16, 8, 3);
        for (std::size_t i = 0; i < image->pixel_count(); ++i)
            image->pixels[3 * i] = r, image->pixels[3 * i + 1] = g, image->pixels[3 * i + 2] = b;
        return test::latlong_environment(image, "uniform");
    };
    desc.environment = uniform(0, 1, 0);
    desc.local_environments = {uniform(1, 0.5f, 0)};
    desc.local_environments[0].proxy =
        EnvProxy{EnvProxy::Shape::box, {-50, -1, -50}, {50, 20, 50}, {}, 1, {0, 1, 0}};
    RenderScene scene;
    const ErrorBudgetImages budget = budget_of(desc, scene);
    const Image mask = interior_mask(scene);
    for (BudgetTerm term :
         {BudgetTerm::env_filter, BudgetTerm::env_footprint, BudgetTerm::env_two_lobes}) {
        EXPECT_LT(max_difference(term_image(budget, term), budget.filtered, &mask), 1e-3)
            << budget_term_name(term);
        EXPECT_NEAR(term_image(budget, term).at(12, 12, 0), 1.0f, 1e-3) << budget_term_name(term);
    }
}

// sphere_gaussian_from_spread of the ray differentials is sphere_gaussian_from_ray_differentials,
// and more spread vectors add their covariances.
TEST(ErrorBudget, SpreadVectorsAddTheirCovariances) {
    const Vec3d r{0.2, 0.3, 1.5}, dx{0.01, 0, 0.002}, dy{0, 0.02, -0.001};
    const Vec3d both[2] = {dx, dy};
    const SphereGaussian a = sphere_gaussian_from_ray_differentials(r, dx, dy);
    const SphereGaussian b = sphere_gaussian_from_spread(r, both);
    EXPECT_NEAR(length(a.axis1 - b.axis1), 0, 1e-15);
    EXPECT_NEAR(length(a.axis2 - b.axis2), 0, 1e-15);
    // dx twice (√2·dx once) doubles its variance: the same as spreading by √2 dx.
    const Vec3d twice[3] = {dx, dx, dy};
    const SphereGaussian c = sphere_gaussian_from_spread(r, twice);
    const SphereGaussian d = sphere_gaussian_from_ray_differentials(r, std::sqrt(2.0) * dx, dy);
    EXPECT_NEAR(length(c.axis1 - d.axis1), 0, 1e-12);
    EXPECT_NEAR(length(c.axis2 - d.axis2), 0, 1e-12);
}

}  // namespace
}  // namespace footprint
