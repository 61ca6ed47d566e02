#include "scene/mesh_accel.h"
#include "core/test_shared_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <thread>
#include <vector>

namespace footprint {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

using test::shared_data_dir;

void expect_near(Vec3d a, Vec3d b, double tol, const char* what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

// A UV sphere (outward normals, uv = (longitude, latitude) / (2π, π)), slightly bumpy so that
// the normals differ from the faceted geometry.
TriangleMesh uv_sphere(Vec3d center, double radius, int nu, int nv) {
    TriangleMesh m;
    m.name = "sphere";
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            const double phi = 2 * kPi * i / nu, theta = kPi * j / nv;
            const Vec3d d{std::sin(theta) * std::cos(phi), std::cos(theta),
                          std::sin(theta) * std::sin(phi)};
            m.positions.push_back(center + radius * (1 + 0.05 * std::sin(3 * phi)) * d);
            m.normals.push_back(d);
            m.uvs.push_back({static_cast<double>(i) / nu, 1 - static_cast<double>(j) / nv});
        }
    auto id = [nu](int i, int j) { return static_cast<std::uint32_t>(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
            m.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
        }
    return m;
}

TriangleMesh quad(double z) {
    TriangleMesh m;
    m.name = "quad";
    m.positions = {{-3, -3, z}, {3, -3, z}, {3, 3, z}, {-3, 3, z}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

struct Brute {
    int mesh = -1, triangle = -1;
    double t = 0, b1 = 0, b2 = 0;
};

// Reference: Möller–Trumbore over every triangle, in double precision.
Brute brute_force(const std::vector<const TriangleMesh*>& meshes, const Ray& r, double t_min,
                  double t_max) {
    Brute best;
    double t_best = t_max;
    for (std::size_t k = 0; k < meshes.size(); ++k) {
        const TriangleMesh& m = *meshes[k];
        for (std::size_t i = 0; i < m.triangles.size(); ++i) {
            const auto& tri = m.triangles[i];
            const Vec3d p0 = m.positions[tri[0]], e1 = m.positions[tri[1]] - p0,
                        e2 = m.positions[tri[2]] - p0;
            const Vec3d pv = cross(r.direction, e2);
            const double det = dot(e1, pv);
            if (det == 0) continue;
            const Vec3d tv = r.origin - p0;
            const double u = dot(tv, pv) / det;
            if (u < 0 || u > 1) continue;
            const Vec3d qv = cross(tv, e1);
            const double v = dot(r.direction, qv) / det;
            if (v < 0 || u + v > 1) continue;
            const double t = dot(e2, qv) / det;
            if (t < t_min || t > t_best) continue;
            t_best = t;
            best = {static_cast<int>(k), static_cast<int>(i), t, u, v};
        }
    }
    return best;
}

double edge_distance(double b1, double b2) {
    return std::min({b1, b2, 1 - b1 - b2});
}

TEST(MeshAccel, MatchesBruteForce) {
    const TriangleMesh sphere = uv_sphere({0.2, -0.1, 0.3}, 1.0, 24, 12);
    const TriangleMesh floor = quad(-1.5);
    Result<MeshAccel> accel = MeshAccel::build({{7, &sphere}, {3, &floor}});
    ASSERT_TRUE(accel.ok()) << accel.error().message;
    ASSERT_EQ(accel->size(), 2u);
    const std::vector<const TriangleMesh*> meshes = {&sphere, &floor};

    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> u(-1, 1);
    int hits = 0, ambiguous = 0;
    for (int i = 0; i < 400; ++i) {
        Ray ray;
        ray.origin = 4.0 * normalize(Vec3d{u(rng), u(rng), u(rng)});
        const Vec3d target{1.5 * u(rng), 1.5 * u(rng), 1.5 * u(rng)};
        ray.direction = (target - ray.origin) * (0.5 + 0.5 * (u(rng) + 1));  // not unit length
        const double t_max = i % 5 == 0 ? 0.5 : std::numeric_limits<double>::infinity();
        const auto got = accel->intersect(ray, 1e-6, t_max);
        const Brute want = brute_force(meshes, ray, 1e-6, t_max);
        if (!got || want.mesh < 0) {
            if (got.has_value() != (want.mesh >= 0)) {
                // A silhouette graze: only allowed right at an edge.
                const double e =
                    got ? edge_distance(got->b1, got->b2) : edge_distance(want.b1, want.b2);
                EXPECT_LT(e, 1e-5) << "ray " << i;
                ++ambiguous;
            }
            continue;
        }
        ++hits;
        EXPECT_NEAR(got->t, want.t, 1e-4 * want.t) << "ray " << i;
        EXPECT_EQ(got->object, want.mesh == 0 ? 7 : 3);
        if (got->mesh != want.mesh || got->triangle != want.triangle) {
            EXPECT_LT(edge_distance(want.b1, want.b2), 1e-5) << "ray " << i;
            ++ambiguous;
            continue;
        }
        EXPECT_NEAR(got->b1, want.b1, 1e-9) << "ray " << i;
        EXPECT_NEAR(got->b2, want.b2, 1e-9) << "ray " << i;
        EXPECT_NEAR(got->t, want.t, 1e-9 * want.t) << "ray " << i;  // refined in double
    }
    EXPECT_GT(hits, 200);
    EXPECT_LE(ambiguous, 4);
}

TEST(MeshAccel, RespectsTheRayInterval) {
    const TriangleMesh floor = quad(0);
    Result<MeshAccel> accel = MeshAccel::build({{0, &floor}});
    ASSERT_TRUE(accel.ok());
    const Ray ray{{0.1, 0.2, 2}, {0, 0, -2}};  // hits at t = 1
    ASSERT_TRUE(accel->intersect(ray, 0, 10).has_value());
    EXPECT_NEAR(accel->intersect(ray, 0, 10)->t, 1, 1e-12);
    EXPECT_FALSE(accel->intersect(ray, 0, 0.99).has_value());
    EXPECT_FALSE(accel->intersect(ray, 1.01, 10).has_value());
    EXPECT_FALSE(accel->intersect(Ray{{0.1, 0.2, 2}, {0, 0, 1}}, 0, 10).has_value());
}

// fuzz_scene_json: a camera at 1.1e31 gave Embree a ray it asserts on (Debian's Embree aborts).
// Rays beyond Embree's range miss, and no ray aborts.
TEST(MeshAccel, RaysBeyondEmbreesRangeMiss) {
    const TriangleMesh floor = quad(0);
    Result<MeshAccel> accel = MeshAccel::build({{0, &floor}});
    ASSERT_TRUE(accel.ok());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const Ray& ray : {Ray{{0.1, 1.1e31, 2}, {0, -1, -1}}, Ray{{0.1, 0.2, 2}, {0, 0, -1e30}},
                           Ray{{0.1, nan, 2}, {0, 0, -1}}}) {
        EXPECT_FALSE(accel->intersect(ray, 0, 1e300).has_value());
        EXPECT_FALSE(accel->occluded(ray, 0, 1e300));
    }
    EXPECT_TRUE(accel->intersect(Ray{{0.1, 0.2, 1e18}, {0, 0, -1}}, 0, 2e18).has_value());
}

TEST(MeshAccel, EmptyAndMoved) {
    const Ray ray{{0, 0, 2}, {0, 0, -1}};
    MeshAccel none;
    EXPECT_FALSE(none.intersect(ray, 0, 10).has_value());
    Result<MeshAccel> empty = MeshAccel::build({});
    ASSERT_TRUE(empty.ok());
    EXPECT_FALSE(empty->intersect(ray, 0, 10).has_value());
    TriangleMesh no_triangles;
    Result<MeshAccel> skipped = MeshAccel::build({{0, nullptr}, {1, &no_triangles}});
    ASSERT_TRUE(skipped.ok());
    EXPECT_FALSE(skipped->intersect(ray, 0, 10).has_value());

    const TriangleMesh floor = quad(0);
    Result<MeshAccel> built = MeshAccel::build({{0, nullptr}, {5, &floor}});
    ASSERT_TRUE(built.ok());
    MeshAccel a = std::move(built).value();
    MeshAccel b(std::move(a));
    EXPECT_FALSE(a.intersect(ray, 0, 10).has_value());  // NOLINT: moved-from is empty
    auto hit = b.intersect(ray, 0, 10);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->object, 5);
    EXPECT_EQ(hit->mesh, 1);
    a = std::move(b);
    EXPECT_TRUE(a.intersect(ray, 0, 10).has_value());
}

TEST(MeshAccel, RejectsBadIndices) {
    TriangleMesh bad = quad(0);
    bad.triangles.push_back({0, 1, 9});
    Result<MeshAccel> accel = MeshAccel::build({{0, &bad}});
    ASSERT_FALSE(accel.ok());
    EXPECT_NE(accel.error().message.find("out of range"), std::string::npos);
}

TEST(MeshAccel, ThreadSafe) {
    const TriangleMesh sphere = uv_sphere({0, 0, 0}, 1.0, 32, 16);
    Result<MeshAccel> accel = MeshAccel::build({{0, &sphere}});
    ASSERT_TRUE(accel.ok());
    std::vector<Ray> rays;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 2000; ++i)
        rays.push_back({{u(rng), u(rng), 5}, {0.1 * u(rng), 0.1 * u(rng), -1}});
    std::vector<double> serial(rays.size(), -1), parallel(rays.size(), -1);
    for (std::size_t i = 0; i < rays.size(); ++i)
        if (auto h = accel->intersect(rays[i], 0, 100)) serial[i] = h->t;
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k)
        threads.emplace_back([&, k] {
            for (std::size_t i = k; i < rays.size(); i += 4)
                if (auto h = accel->intersect(rays[i], 0, 100)) parallel[i] = h->t;
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(serial, parallel);
}

// ---------------------------------------------------------------------------------------------
// mesh_surface_hit

TriangleMesh curved_triangle() {
    TriangleMesh m;
    m.positions = {{0.1, 0.2, 0.3}, {1.3, 0.1, -0.2}, {0.2, 1.1, 0.4}};
    m.normals = {normalize(Vec3d{0.1, -0.2, 1}), normalize(Vec3d{0.5, 0.1, 1}),
                 normalize(Vec3d{-0.3, 0.4, 0.8})};
    m.uvs = {{0.2, 0.1}, {0.7, 0.3}, {0.1, 0.8}};
    m.triangles = {{0, 1, 2}};
    return m;
}

// Position and unit interpolated normal at barycentrics (b1, b2).
void interpolate(const TriangleMesh& m, double b1, double b2, Vec3d& p, Vec3d& n) {
    const double b0 = 1 - b1 - b2;
    p = b0 * m.positions[0] + b1 * m.positions[1] + b2 * m.positions[2];
    n = m.has_normals() ? normalize(b0 * m.normals[0] + b1 * m.normals[1] + b2 * m.normals[2])
                        : Vec3d{};
}

// Barycentrics at (u, v) for a mesh with UVs (solving uv = uv0 + b1·e1 + b2·e2).
void barycentrics_at(const TriangleMesh& m, double u, double v, double& b1, double& b2) {
    const Vec2d e1 = m.uvs[1] - m.uvs[0], e2 = m.uvs[2] - m.uvs[0];
    const Vec2d d = Vec2d{u, v} - m.uvs[0];
    const double det = e1.x * e2.y - e1.y * e2.x;
    b1 = (d.x * e2.y - d.y * e2.x) / det;
    b2 = (e1.x * d.y - e1.y * d.x) / det;
}

TEST(MeshSurfaceHit, DerivativesMatchFiniteDifferences) {
    const TriangleMesh m = curved_triangle();
    const double b1 = 0.3, b2 = 0.25;
    const Ray ray{{0, 0, 5}, {0, 0, -1}};
    const SurfaceHit h = mesh_surface_hit(m, 0, b1, b2, ray, 4.7);
    EXPECT_EQ(h.primitive, 0);
    EXPECT_EQ(h.t, 4.7);
    Vec3d p, n;
    interpolate(m, b1, b2, p, n);
    expect_near(h.p, p, 1e-14, "p");
    expect_near(h.n, n, 1e-14, "n");
    const Vec2d uv = 0.45 * m.uvs[0] + b1 * m.uvs[1] + b2 * m.uvs[2];
    EXPECT_NEAR(h.uv.x, uv.x, 1e-14);
    EXPECT_NEAR(h.uv.y, uv.y, 1e-14);
    EXPECT_GT(dot(h.geometric_normal, h.n), 0);
    EXPECT_NEAR(length(h.geometric_normal), 1, 1e-14);

    const double eps = 1e-6;
    Vec3d pu[2], nu[2], pv[2], nv[2];
    for (int s = 0; s < 2; ++s) {
        const double d = s ? eps : -eps;
        double c1, c2;
        barycentrics_at(m, uv.x + d, uv.y, c1, c2);
        interpolate(m, c1, c2, pu[s], nu[s]);
        barycentrics_at(m, uv.x, uv.y + d, c1, c2);
        interpolate(m, c1, c2, pv[s], nv[s]);
    }
    expect_near(h.dpdu, (pu[1] - pu[0]) / (2 * eps), 1e-7, "dpdu");
    expect_near(h.dpdv, (pv[1] - pv[0]) / (2 * eps), 1e-7, "dpdv");
    expect_near(h.dndu, (nu[1] - nu[0]) / (2 * eps), 1e-7, "dndu");
    expect_near(h.dndv, (nv[1] - nv[0]) / (2 * eps), 1e-7, "dndv");
    EXPECT_GT(length(h.dndu), 0.1);  // a real test: the normal does vary
    EXPECT_NEAR(dot(h.dndu, h.n), 0, 1e-12);
}

TEST(MeshSurfaceHit, WithoutUvsUsesBarycentrics) {
    TriangleMesh m = curved_triangle();
    m.uvs.clear();
    const double b1 = 0.2, b2 = 0.5;
    const SurfaceHit h = mesh_surface_hit(m, 0, b1, b2, Ray{{0, 0, 5}, {0, 0, -1}}, 1);
    EXPECT_EQ(h.uv.x, b1);
    EXPECT_EQ(h.uv.y, b2);
    expect_near(h.dpdu, m.positions[1] - m.positions[0], 1e-15, "dpdu");
    expect_near(h.dpdv, m.positions[2] - m.positions[0], 1e-15, "dpdv");
    const double eps = 1e-6;
    Vec3d p, na, nb;
    interpolate(m, b1 + eps, b2, p, na);
    interpolate(m, b1 - eps, b2, p, nb);
    expect_near(h.dndu, (na - nb) / (2 * eps), 1e-7, "dndu");
    interpolate(m, b1, b2 + eps, p, na);
    interpolate(m, b1, b2 - eps, p, nb);
    expect_near(h.dndv, (na - nb) / (2 * eps), 1e-7, "dndv");

    // Degenerate UVs (all equal) take the same fallback, but keep the interpolated uv.
    m.uvs = {{0.5, 0.5}, {0.5, 0.5}, {0.5, 0.5}};
    const SurfaceHit d = mesh_surface_hit(m, 0, b1, b2, Ray{{0, 0, 5}, {0, 0, -1}}, 1);
    EXPECT_NEAR(d.uv.x, 0.5, 1e-15);
    expect_near(d.dpdu, h.dpdu, 1e-15, "dpdu");
    expect_near(d.dndv, h.dndv, 1e-15, "dndv");
}

TEST(MeshSurfaceHit, FlatWithoutNormalsAndGeometricNormalSide) {
    TriangleMesh m = curved_triangle();
    m.normals.clear();
    const SurfaceHit h = mesh_surface_hit(m, 0, 0.2, 0.2, Ray{{0, 0, 5}, {0, 0, -1}}, 1);
    const Vec3d ng =
        normalize(cross(m.positions[1] - m.positions[0], m.positions[2] - m.positions[0]));
    expect_near(h.n, ng, 1e-15, "n");
    expect_near(h.geometric_normal, ng, 1e-15, "ng");
    expect_near(h.dndu, {0, 0, 0}, 0, "dndu");
    expect_near(h.dndv, {0, 0, 0}, 0, "dndv");

    // Vertex normals against the winding: n as stored, the geometric normal follows it.
    m.normals = {-ng, -ng, -ng};
    const SurfaceHit f = mesh_surface_hit(m, 0, 0.2, 0.2, Ray{{0, 0, 5}, {0, 0, -1}}, 1);
    expect_near(f.n, -ng, 1e-15, "n");
    expect_near(f.geometric_normal, -ng, 1e-15, "ng");
}

TEST(MeshSurfaceHit, TangentFrame) {
    TriangleMesh m = curved_triangle();
    EXPECT_FALSE(mesh_tangent_frame(m, 0, 0.2, 0.2).has_value());
    m.tangents = {{{1, 0, 0}, -1}, {{0, 1, 0}, -1}, {{1, 0, 0}, -1}};
    const auto f = mesh_tangent_frame(m, 0, 0.5, 0.0);
    ASSERT_TRUE(f.has_value());
    expect_near(f->tangent, normalize(Vec3d{1, 1, 0}), 1e-15, "tangent");
    EXPECT_EQ(f->tangent_sign, -1);
}

// The hits on a loaded asset go through both halves: intersect, then mesh_surface_hit.
TEST(MeshAccelSharedData, FlightHelmet) {
    const fs::path file = shared_data_dir() / "meshes" / "FlightHelmet" / "FlightHelmet.gltf";
    if (!fs::exists(file)) GTEST_SKIP() << test::missing_shared_data(file);
    Result<MeshAsset> asset = load_mesh(file);
    ASSERT_TRUE(asset.ok()) << asset.error().message;
    std::vector<MeshInstance> list;
    for (const TriangleMesh& m : asset->meshes) list.push_back({0, &m});
    Result<MeshAccel> accel = MeshAccel::build(list);
    ASSERT_TRUE(accel.ok()) << accel.error().message;
    int hits = 0;
    for (int i = 0; i < 21; ++i) {
        const Ray ray{{0, 0.05 + 0.03 * i, 2}, {0, 0, -1}};
        const auto h = accel->intersect(ray, 0, 100);
        if (!h) continue;
        ++hits;
        const TriangleMesh& m = *accel->instance(h->mesh).mesh;
        const SurfaceHit s = mesh_surface_hit(m, h->triangle, h->b1, h->b2, ray, h->t);
        expect_near(s.p, ray.origin + h->t * ray.direction, 1e-9, "p");
        EXPECT_NEAR(length(s.n), 1, 1e-12);
        EXPECT_TRUE(is_finite(s.dpdu) && is_finite(s.dpdv) && is_finite(s.dndu) &&
                    is_finite(s.dndv));
        EXPECT_TRUE(mesh_tangent_frame(m, h->triangle, h->b1, h->b2).has_value());
    }
    EXPECT_GE(hits, 15);  // the helmet covers most of its height seen from the front
}

}  // namespace
}  // namespace footprint
