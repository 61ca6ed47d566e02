// Ray differentials on triangle meshes (scene/ray_differentials.h with scene/mesh_accel.h's
// barycentric differential geometry): ∂p, ∂n and ∂(u, v) per pixel step against finite
// differences of re-intersected rays, on a smooth-shaded UV sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene/mesh.h"
#include "scene/mesh_accel.h"
#include "scene/ray_differentials.h"

namespace footprint {
namespace {

// A UV sphere of radius 1 at the origin: vertex normals = positions, uv = (φ/2π, 1 − θ/π).
TriangleMesh uv_sphere(int segments, int rings) {
    TriangleMesh mesh;
    for (int j = 0; j <= rings; ++j) {
        const double theta = std::numbers::pi * j / rings;
        for (int i = 0; i <= segments; ++i) {
            const double phi = 2 * std::numbers::pi * i / segments;
            const Vec3d p{std::sin(theta) * std::sin(phi), std::cos(theta),
                          std::sin(theta) * std::cos(phi)};
            mesh.positions.push_back(p);
            mesh.normals.push_back(p);
            mesh.uvs.push_back(
                {static_cast<double>(i) / segments, 1.0 - static_cast<double>(j) / rings});
        }
    }
    const auto index = [&](int i, int j) {
        return static_cast<std::uint32_t>(j * (segments + 1) + i);
    };
    for (int j = 0; j < rings; ++j) {
        for (int i = 0; i < segments; ++i) {
            mesh.triangles.push_back({index(i, j), index(i, j + 1), index(i + 1, j + 1)});
            mesh.triangles.push_back({index(i, j), index(i + 1, j + 1), index(i + 1, j)});
        }
    }
    return mesh;
}

TEST(MeshRayDifferentials, MatchFiniteDifferencesOfReintersectedRays) {
    const TriangleMesh mesh = uv_sphere(24, 16);
    Result<MeshAccel> accel = MeshAccel::build({{0, &mesh}});
    ASSERT_TRUE(accel.ok()) << accel.error().message;
    // Pinhole camera at (0.3, 0.8, 3.5) looking at the origin; 64 × 48 pixels, 40° vertical.
    const Vec3d eye{0.3, 0.8, 3.5};
    const Vec3d f = normalize(Vec3d{0, 0, 0} - eye);
    const Vec3d r = normalize(cross(f, Vec3d{0, 1, 0}));
    const Vec3d u = cross(r, f);
    const double a = 2 * std::tan(20 * std::numbers::pi / 180) / 48;
    const auto ray = [&](double x, double y) {
        return Ray{eye, f + (a * (x - 32)) * r - (a * (y - 24)) * u};
    };
    struct Sample {
        bool hit = false;
        int triangle = -1;
        SurfaceHit surface;
    };
    const auto trace = [&](double x, double y) {
        Sample s;
        const Ray q = ray(x, y);
        if (auto record = accel->intersect(q, 1e-9, 1e9)) {
            s.hit = true;
            s.triangle = record->triangle;
            s.surface =
                mesh_surface_hit(mesh, record->triangle, record->b1, record->b2, q, record->t);
        }
        return s;
    };
    constexpr double h = 1e-3;
    int checked = 0;
    for (int py = 1; py < 48; py += 3) {
        for (int px = 1; px < 64; px += 3) {
            const double x = px + 0.5, y = py + 0.5;
            const Sample centre = trace(x, y);
            if (!centre.hit) continue;
            const Sample xm = trace(x - h, y), xp = trace(x + h, y);
            const Sample ym = trace(x, y - h), yp = trace(x, y + h);
            // Inside one triangle only: across an edge the interpolated normal is not smooth.
            bool same = true;
            for (const Sample* s : {&xm, &xp, &ym, &yp})
                same = same && s->triangle == centre.triangle;
            if (!same) continue;
            RayDifferential rd{ray(x, y), {}, a * r, {}, -a * u};
            const SurfaceDifferentials d = surface_differentials(rd, centre.surface);
            ASSERT_TRUE(d.valid);
            const auto expect_near = [&](Vec3d analytic, Vec3d fd, const char* what) {
                const double tol = 1e-5 * std::max(length(analytic), length(fd)) + 1e-9;
                EXPECT_LE(length(analytic - fd), tol) << what << " at pixel " << px << "," << py;
            };
            const auto uv3 = [](Vec2d v) { return Vec3d{v.x, v.y, 0}; };
            expect_near(d.dpdx, (xp.surface.p - xm.surface.p) / (2 * h), "dp/dx");
            expect_near(d.dpdy, (yp.surface.p - ym.surface.p) / (2 * h), "dp/dy");
            expect_near(d.dndx, (xp.surface.n - xm.surface.n) / (2 * h), "dn/dx");
            expect_near(d.dndy, (yp.surface.n - ym.surface.n) / (2 * h), "dn/dy");
            expect_near(uv3(d.duvdx), uv3((xp.surface.uv - xm.surface.uv) / (2 * h)), "duv/dx");
            expect_near(uv3(d.duvdy), uv3((yp.surface.uv - ym.surface.uv) / (2 * h)), "duv/dy");
            ++checked;
        }
    }
    EXPECT_GT(checked, 60);
}

}  // namespace
}  // namespace footprint
