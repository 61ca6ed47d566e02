// docs/library.md's snippets of bump maps, environment maps, form (b) for a reflection and
// batched environment lookups, as written between their markers and run one after the other (the
// reflection uses the bump lookup's slopes), around them the declarations they take from the
// text: a surface point's geometry and ray differentials, files written here. Built and run
// against the installed package by cmake/test_snippets.cmake; check_snippets.py holds
// docs/library.md to these regions.
#include <footprint/footprint.h>

#include <cstdio>
#include <vector>

#include "support.h"

namespace {

using namespace footprint;
using snippets::check;

int bump_and_environment() {
    // A bump-mapped point seen from the eye: its texture coordinates, normal, frame and the view.
    const TextureCoords coords{0.3f, 0.6f, 0.02f, 0, 0.005f, 0.01f};
    const Vec3 eye{0, 1.5f, 3}, p{0.2f, 1.0f, -0.5f}, n{0, 1, 0}, dn_dx{0.01f, 0, 0},
        dn_dy{0, 0, 0.01f}, e1{1, 0, 0}, e2{0, 0, -1};
    const Vec3 r{0, 0.6f, -0.8f}, dr_dx{0.01f, 0, 0}, dr_dy{0, 0.006f, 0.008f};
    // A row of pixels' reflected rays, and their footprints, as a renderer makes them.
    auto pixel_rays = [&] {
        std::vector<EnvRayDifferential> rays(20, EnvRayDifferential{r, dr_dx, dr_dy});
        for (std::size_t i = 0; i < rays.size(); ++i)
            rays[i].direction.x = 0.1f * static_cast<float>(i);
        return rays;
    };
    // clang-format off
    // snippet begin: docs/library.md
    SlopeMapLoadOptions load;                                 // a normal map, OpenGL green, by default
    load.normal_map.invalid_normal_policy = InvalidNormalPolicy::error;
    Result<Image> slopes = load_slope_map("bricks_normal.png", load);   // loaded as data, not sRGB
    BumpPyramidOptions bump_options;
    bump_options.micro_roughness = {0.001f, 0, 0.001f};       // optional K_0 (slope units²)
    Result<BumpPyramid> bump = BumpPyramid::build(*slopes, bump_options);
    SlopeStatistics st = bump_lookup(*bump, coords, LookupOptions{});   // μ and K_b
    RoughnessFactor B = roughness_factor(st.covariance);                // d1, d2, d3
    float l1 = isotropic_roughness(st.covariance);
    // snippet end
    // clang-format on
    check(slopes.ok() && bump.ok() && l1 > 0, "docs/library.md: the bump pyramid and its lookup");

    // clang-format off
    // snippet begin: docs/library.md
    Result<EnvironmentMap> sky = load_environment({"sky.exr"}, {});    // layout from the aspect ratio
    float rgb[3];
    environment_lookup(*sky, r, dr_dx, dr_dy, LookupOptions{}, rgb);  // form (a), like OIIO
    EnvLookupOptions rotated{LookupOptions{}, rotation_xyz_degrees(0, 90, 0)};
    environment_lookup(*sky, r, dr_dx, dr_dy, rotated, rgb);          // with a rotation A
    IrradianceSH sh = project_radiance([&](Vec3 w, Vec3 d1, Vec3 d2) {
        environment_lookup(*sky, w, d1, d2, LookupOptions{}, rgb);
        return Vec3{rgb[0], rgb[1], rgb[2]};
    });
    Vec3 e = irradiance(sh, n);                                       // matte: albedo · e / π
    // snippet end
    // clang-format on
    check(sky.ok() && e.x > 0 && e.y > 0 && e.z > 0, "docs/library.md: environment lookups");

    // clang-format off
    // snippet begin: docs/library.md
    ReflectionGeometry g;
    g.v = eye - p;  g.n = n;  g.dn_dx = dn_dx;  g.dn_dy = dn_dy;     // dv_dx, dv_dy: −e_x, −e_y by default
    g.bump_slope = st.mean;  g.t1 = e1;  g.t2 = e2;                  // from bump_lookup and the frame
    g.roughness = roughness_factor(st.covariance);
    EnvFootprint f = compute_env_footprint(sky->layout(), sky->texel_scale(), g);
    environment_lookup(*sky, f, LookupOptions{}, rgb);
    // snippet end
    // clang-format on
    check(snippets::finite(rgb, 3), "docs/library.md: form (b)");
    auto pixel_footprints = [&] { return std::vector<EnvFootprint>(20, f); };

    // clang-format off
    // snippet begin: docs/library.md
    std::vector<EnvRayDifferential> rays = pixel_rays();     // {r, ∂r/∂x, ∂r/∂y} each
    std::vector<float> colours(rays.size() * sky->channels());
    environment_lookup_batch(*sky, rays, LookupOptions{}, colours.data());
    std::vector<EnvFootprint> footprints = pixel_footprints();  // form (b), one per pixel
    environment_lookup_batch(*sky, footprints, LookupOptions{}, colours.data());
    // snippet end
    // clang-format on
    check(std::equal(rgb, rgb + 3, colours.begin()),
          "docs/library.md: environment_lookup_batch = the single call");
    return 0;
}

}  // namespace

int main() {
    snippets::write_files();
    if (bump_and_environment() != 0) return 1;
    std::printf("docs/library.md's bump and environment snippets ran\n");
    return 0;
}
