// README.md's snippets of the bump lookup, the environment lookup and the diffuse light and local
// maps, as written between their markers and run one after the other as the README tells them
// (the environment lookup uses the bump lookup's slopes), around them the declarations they take
// from the text: a surface point's geometry and ray differentials, files written here. Built and
// run against the installed package by cmake/test_snippets.cmake; check_snippets.py holds the
// README to these regions.
#include <footprint/footprint.h>

#include <cstdio>
#include <vector>

#include "support.h"

// The snippets' own #include lines stand inside the function below: the headers were included
// above, so there they add nothing (#pragma once).

namespace {

using namespace footprint;
using snippets::check;

int bump_and_environment() {
    // A bump-mapped point seen from the eye: its texture coordinates, normal, frame and the view.
    const TextureCoords c{0.3f, 0.6f, 0.02f, 0, 0.005f, 0.01f};
    const float cos_a = 0.95f, shininess = 40;
    const Vec2 d{0.1f, -0.2f};
    Vec3 p{0.2f, 1.0f, -0.5f}, n{0, 1, 0}, dn_dx{0.01f, 0, 0}, dn_dy{0, 0, 0.01f};
    const Vec3 to_eye{0, 1, 2}, e1{1, 0, 0}, e2{0, 0, -1};
    Vec3 r{0, 0.6f, -0.8f};
    const Vec3 dr_dx{0.01f, 0, 0}, dr_dy{0, 0.006f, 0.008f};
    const float slope_variance = 0.02f;
    std::vector<EnvRayDifferential> rays(20, EnvRayDifferential{r, dr_dx, dr_dy});
    for (std::size_t i = 0; i < rays.size(); ++i)
        rays[i].direction.x = 0.1f * static_cast<float>(i);
    std::vector<float> storage(rays.size() * 3);
    float* out = storage.data();
    // clang-format off
    // snippet begin: README.md
    #include <footprint/bump/bump_pyramid.h>
    #include <footprint/bump/slope_map.h>
    #include <footprint/shading/blinn_phong.h>

    Result<Image> slopes = load_slope_map("bricks_normal.png");   // normal map, OpenGL green, read as data
    Result<BumpPyramid> bump = BumpPyramid::build(*slopes);       // moments μ and M2 = K_b + μμᵀ
    SlopeStatistics st = bump_lookup(*bump, c, LookupOptions{});  // mean slope μ, covariance K_b
    RoughnessFactor B = roughness_factor(st.covariance);          // B Bᵀ = K_b, for the environment
    float highlight = rough_blinn_phong(cos_a, d, st.covariance, shininess);  // Blinn-Phong ⊛ N(0, K_b)
    // snippet end
    // clang-format on
    check(slopes.ok() && bump.ok(), "README: the bump pyramid");
    check(st.covariance.trace() > 0 && highlight > 0, "README: bump_lookup and the highlight");

    // clang-format off
    // snippet begin: README.md
    #include <footprint/envmap/env_image_io.h>       // load_environment: any layout and arrangement
    #include <footprint/envmap/environment_map.h>    // EnvironmentMap, environment_lookup

    Result<EnvironmentMap> sky = load_environment({"sky.exr"});       // layout from the aspect ratio
    float rgb[3];                                                      // sky->channels() floats
    environment_lookup(*sky, r, dr_dx, dr_dy, LookupOptions{}, rgb);   // direction + ray differentials

    ReflectionGeometry g;                        // Schilling's footprint K = D Dᵀ + κ² K3:
    g.v = to_eye;  g.n = n;  g.dn_dx = dn_dx;  g.dn_dy = dn_dy;       // view vector, normal and its derivatives
    g.bump_slope = st.mean;  g.t1 = e1;  g.t2 = e2;  g.roughness = B; // the bump lookup above, its frame
    EnvFootprint f = compute_env_footprint(sky->layout(), sky->texel_scale(), g);
    environment_lookup(*sky, f, LookupOptions{}, rgb);
    environment_lookup_batch(*sky, rays, LookupOptions{}, out);        // many rays: the same results, faster
    EnvLookupOptions rotated{LookupOptions{}, rotation_xyz_degrees(0, 90, 0)};  // an environment rotation
    environment_lookup(*sky, r, dr_dx, dr_dy, rotated, rgb);
    // snippet end
    // clang-format on
    check(sky.ok() && snippets::finite(rgb, 3), "README: environment_lookup");
    float first[3];
    environment_lookup(*sky, rays[0].direction, rays[0].d_dx, rays[0].d_dy, LookupOptions{}, first);
    check(std::equal(first, first + 3, out), "README: environment_lookup_batch = the single call");

    // clang-format off
    // snippet begin: README.md
    #include <footprint/envmap/env_proxy.h>
    #include <footprint/envmap/irradiance.h>

    IrradianceSH sh = project_radiance([&](Vec3 w, Vec3 d1, Vec3 d2) {
        environment_lookup(*sky, w, d1, d2, LookupOptions{}, rgb);
        return Vec3{rgb[0], rgb[1], rgb[2]};
    });
    Vec3 e = irradiance(sh, n, slope_variance);  // a matte surface reflects albedo·e/π
    EnvProxy room{EnvProxy::Shape::box, {-4, 0, -5}, {4, 3, 3}, {}, 1, /*capture*/ {0, 1.5f, -1}};
    if (auto step = proxy_step(room, p, r)) r = step->direction;  // step->move(∂p, ∂r): the footprint
    bool mine = proxy_contains(room, p);  // nested rooms: the smallest proxy_volume() containing p wins
    // snippet end
    // clang-format on
    check(e.x > 0 && e.y > 0 && e.z > 0, "README: irradiance");
    check(mine, "README: proxy_contains");
    return 0;
}

}  // namespace

int main() {
    snippets::write_files();
    if (bump_and_environment() != 0) return 1;
    std::printf("README.md's bump and environment snippets ran\n");
    return 0;
}
