#include "scene/triangle_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace footprint {
namespace {

using Triangle = std::array<Vec3, 3>;

// Möller–Trumbore, t in (0, t_max): the test geometry.glsl's mesh_occluded() makes per triangle.
bool hits(const Triangle& tri, Vec3 o, Vec3 d, float t_max) {
    const Vec3 e1 = tri[1] - tri[0], e2 = tri[2] - tri[0];
    const Vec3 pv = cross(d, e2);
    const float det = dot(e1, pv);
    if (det == 0) return false;
    const Vec3 tv = o - tri[0], qv = cross(tv, e1);
    const float u = dot(tv, pv) / det, v = dot(d, qv) / det, t = dot(e2, qv) / det;
    return u >= 0 && v >= 0 && u + v <= 1 && t > 0 && t < t_max;
}

// The slab test against a node's box, as the shader makes it.
bool box_hit(const TriangleBvhNode& n, Vec3 o, Vec3 inv, float t_max) {
    float t0 = 0, t1 = t_max;
    const float lo[3] = {n.lo[0], n.lo[1], n.lo[2]}, hi[3] = {n.hi[0], n.hi[1], n.hi[2]};
    const float oo[3] = {o.x, o.y, o.z}, ii[3] = {inv.x, inv.y, inv.z};
    for (int a = 0; a < 3; ++a) {
        float near = (lo[a] - oo[a]) * ii[a], far = (hi[a] - oo[a]) * ii[a];
        if (near > far) std::swap(near, far);
        t0 = std::max(t0, near), t1 = std::min(t1, far);
    }
    return t0 <= t1;
}

// The layout's traversal (geometry.glsl's mesh_occluded() in C++), counting the nodes it visits.
bool occluded(const TriangleBvh& bvh, const std::vector<Triangle>& tris, Vec3 o, Vec3 d,
              float t_max, int* visited = nullptr) {
    if (bvh.nodes.empty()) return false;
    const Vec3 inv{1 / d.x, 1 / d.y, 1 / d.z};
    std::vector<int> stack{0};
    while (!stack.empty()) {
        const TriangleBvhNode& n = bvh.nodes[static_cast<std::size_t>(stack.back())];
        const int index = stack.back();
        stack.pop_back();
        if (visited) ++*visited;
        if (!box_hit(n, o, inv, t_max)) continue;
        if (n.count > 0) {
            for (int k = 0; k < n.count; ++k)
                if (hits(tris[bvh.triangles[static_cast<std::size_t>(n.next + k)]], o, d, t_max))
                    return true;
        } else {
            stack.push_back(n.next);
            stack.push_back(index + 1);
        }
        EXPECT_LE(static_cast<int>(stack.size()), kTriangleBvhMaxDepth);
    }
    return false;
}

std::vector<Triangle> random_triangles(int count, std::mt19937& rng) {
    std::uniform_real_distribution<float> centre(-10, 10), edge(-0.6f, 0.6f);
    std::vector<Triangle> tris;
    for (int i = 0; i < count; ++i) {
        const Vec3 c{centre(rng), centre(rng), centre(rng)};
        tris.push_back({c + Vec3{edge(rng), edge(rng), edge(rng)},
                        c + Vec3{edge(rng), edge(rng), edge(rng)},
                        c + Vec3{edge(rng), edge(rng), edge(rng)}});
    }
    return tris;
}

TEST(TriangleBvh, HoldsEveryTriangleOnceInsideItsNodesBoxes) {
    std::mt19937 rng(3);
    const std::vector<Triangle> tris = random_triangles(5000, rng);
    Result<TriangleBvh> bvh = build_triangle_bvh(tris);
    ASSERT_TRUE(bvh) << bvh.error().message;
    std::vector<int> seen(tris.size(), 0);
    for (const TriangleBvhNode& n : bvh->nodes) {
        if (n.count == 0) continue;
        EXPECT_LE(n.count, kTriangleBvhMaxLeaf);
        for (int k = 0; k < n.count; ++k) {
            const std::uint32_t id = bvh->triangles[static_cast<std::size_t>(n.next + k)];
            ++seen[id];
            for (const Vec3& p : tris[id]) {  // exact float bounds: no tolerance
                EXPECT_TRUE(p.x >= n.lo[0] && p.y >= n.lo[1] && p.z >= n.lo[2]);
                EXPECT_TRUE(p.x <= n.hi[0] && p.y <= n.hi[1] && p.z <= n.hi[2]);
            }
        }
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(tris.size()));
    EXPECT_LE(bvh->depth, kTriangleBvhMaxDepth);
    EXPECT_GT(bvh->depth, 1);
}

// Every shadow ray gets the brute-force answer, and the tree prunes: a BVH whose traversal visits
// every node would pass the first test and fail the second.
TEST(TriangleBvh, ShadowRaysMatchBruteForceAndVisitFewNodes) {
    std::mt19937 rng(11);
    const std::vector<Triangle> tris = random_triangles(2000, rng);
    Result<TriangleBvh> bvh = build_triangle_bvh(tris);
    ASSERT_TRUE(bvh) << bvh.error().message;
    std::uniform_real_distribution<float> position(-12, 12), length(0.5f, 30);
    int blocked = 0, visited = 0;
    constexpr int kRays = 4000;
    for (int i = 0; i < kRays; ++i) {
        const Vec3 o{position(rng), position(rng), position(rng)};
        const Vec3 d = normalize(Vec3{position(rng), position(rng), position(rng)});
        const float t_max = length(rng);
        bool brute = false;
        for (const Triangle& t : tris) brute = brute || hits(t, o, d, t_max);
        ASSERT_EQ(occluded(*bvh, tris, o, d, t_max, &visited), brute) << "ray " << i;
        blocked += brute;
    }
    EXPECT_GT(blocked, kRays / 10);  // both answers occur often
    EXPECT_LT(blocked, kRays * 9 / 10);
    EXPECT_LT(visited / kRays, static_cast<int>(bvh->nodes.size()) / 10);
}

TEST(TriangleBvh, ASingleTriangleIsALeafAndNoneIsEmpty) {
    const std::vector<Triangle> one{{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}}};
    Result<TriangleBvh> bvh = build_triangle_bvh(one);
    ASSERT_TRUE(bvh) << bvh.error().message;
    ASSERT_EQ(bvh->nodes.size(), 1u);
    EXPECT_EQ(bvh->nodes[0].count, 1);
    EXPECT_TRUE(occluded(*bvh, one, {0.2f, 0.2f, 1}, {0, 0, -1}, 2));
    EXPECT_FALSE(occluded(*bvh, one, {0.2f, 0.2f, 1}, {0, 0, -1}, 0.5f));
    Result<TriangleBvh> none = build_triangle_bvh({});
    ASSERT_TRUE(none);
    EXPECT_TRUE(none->nodes.empty());
}

// Many copies of one triangle cannot be split by their boxes: the tree still ends in small leaves
// within the depth the shader's stack holds.
TEST(TriangleBvh, CoincidentTrianglesStayWithinTheDepthLimit) {
    const std::vector<Triangle> same(3000, {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}});
    Result<TriangleBvh> bvh = build_triangle_bvh(same);
    ASSERT_TRUE(bvh) << bvh.error().message;
    EXPECT_LE(bvh->depth, kTriangleBvhMaxDepth);
    EXPECT_EQ(bvh->triangles.size(), same.size());
}

}  // namespace
}  // namespace footprint
