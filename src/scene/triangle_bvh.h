// scene/triangle_bvh.h — (internal) a flat binary BVH over triangles for traversals that are not
// Embree's own: the GPU's shadow rays (gpu/shaders/geometry.glsl's mesh_occluded()).
//
// Embree's BVH builder (rtcBuildBVH, binned SAH) chooses the splits; this file only lays its tree
// out depth-first in 32-byte nodes that a shader reads from a storage buffer:
//
//   node i, inner   its box (lo, hi); its first child is node i + 1, its second node `next`
//   node i, leaf    its box; its triangles are triangles[next … next + count − 1]
//
// The boxes are the exact float bounds of the float corners, so a float ray test against the
// box never misses a triangle the float triangle test would hit.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/result.h"
#include "math/vec3.h"

namespace footprint {

struct TriangleBvhNode {  // geometry.glsl's BvhNode (std430: vec3, int, vec3, int)
    float lo[3];
    std::int32_t next;  // inner: the second child; leaf: the first entry of TriangleBvh::triangles
    float hi[3];
    std::int32_t count;  // 0 for an inner node; a leaf's triangle count (≥ 1)
};
static_assert(sizeof(TriangleBvhNode) == 32);

struct TriangleBvh {
    std::vector<TriangleBvhNode> nodes;    // node 0 is the root; none without triangles
    std::vector<std::uint32_t> triangles;  // indices into the builder's input, leaf by leaf
    int depth = 0;                         // the longest root-to-leaf path, in nodes
};

// A leaf holds at most this many triangles, and no path is longer than kTriangleBvhMaxDepth nodes
// (a traversal's stack needs no more entries than that).
constexpr int kTriangleBvhMaxLeaf = 4;
constexpr int kTriangleBvhMaxDepth = 48;

// The BVH over `triangles` (three corners each). Fails only if Embree does, with its message.
Result<TriangleBvh> build_triangle_bvh(std::span<const std::array<Vec3, 3>> triangles);

}  // namespace footprint
