// scene/triangle_bvh.cpp — Embree's BVH builder into the flat layout of triangle_bvh.h.
#include "scene/triangle_bvh.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <new>
#include <string>

namespace footprint {
namespace {

// The builder's tree, in memory Embree's thread-local allocator owns (freed with the RTCBVH).
struct BuildNode {
    int count;  // 0: inner
};
struct InnerNode : BuildNode {
    RTCBounds bounds[2];
    BuildNode* children[2];
};
struct LeafNode : BuildNode {
    std::uint32_t ids[kTriangleBvhMaxLeaf];
};

void* create_inner(RTCThreadLocalAllocator alloc, unsigned int, void*) {
    void* memory = rtcThreadLocalAlloc(alloc, sizeof(InnerNode), alignof(InnerNode));
    return new (memory) InnerNode{{0}, {}, {nullptr, nullptr}};
}

void set_children(void* node, void** children, unsigned int count, void*) {
    for (unsigned int i = 0; i < count; ++i)
        static_cast<InnerNode*>(node)->children[i] = static_cast<BuildNode*>(children[i]);
}

void set_bounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
    for (unsigned int i = 0; i < count; ++i) static_cast<InnerNode*>(node)->bounds[i] = *bounds[i];
}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* primitives,
                  std::size_t count, void*) {
    void* memory = rtcThreadLocalAlloc(alloc, sizeof(LeafNode), alignof(LeafNode));
    auto* leaf = new (memory) LeafNode{{static_cast<int>(count)}, {}};
    for (std::size_t i = 0; i < count; ++i) leaf->ids[i] = primitives[i].primID;
    return leaf;
}

void on_error(void* user, RTCError code, const char* message) {
    auto* out = static_cast<std::string*>(user);
    if (out->empty())
        *out = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
               (message ? message : "(no message)");
}

// Depth-first: the node, then its first subtree, then its second (whose index goes in `next`).
void flatten(const BuildNode* node, const RTCBounds& box, int depth, TriangleBvh& out) {
    const auto index = out.nodes.size();
    out.nodes.push_back({{box.lower_x, box.lower_y, box.lower_z},
                         0,
                         {box.upper_x, box.upper_y, box.upper_z},
                         node->count});
    out.depth = std::max(out.depth, depth);
    if (node->count > 0) {
        const auto* leaf = static_cast<const LeafNode*>(node);
        out.nodes[index].next = static_cast<std::int32_t>(out.triangles.size());
        out.triangles.insert(out.triangles.end(), leaf->ids, leaf->ids + leaf->count);
        return;
    }
    const auto* inner = static_cast<const InnerNode*>(node);
    flatten(inner->children[0], inner->bounds[0], depth + 1, out);
    out.nodes[index].next = static_cast<std::int32_t>(out.nodes.size());
    flatten(inner->children[1], inner->bounds[1], depth + 1, out);
}

RTCBuildPrimitive primitive(const std::array<Vec3, 3>& t, std::uint32_t id) {
    RTCBuildPrimitive p{};
    p.lower_x = std::min({t[0].x, t[1].x, t[2].x});
    p.lower_y = std::min({t[0].y, t[1].y, t[2].y});
    p.lower_z = std::min({t[0].z, t[1].z, t[2].z});
    p.upper_x = std::max({t[0].x, t[1].x, t[2].x});
    p.upper_y = std::max({t[0].y, t[1].y, t[2].y});
    p.upper_z = std::max({t[0].z, t[1].z, t[2].z});
    p.geomID = 0;
    p.primID = id;
    return p;
}

RTCBounds bounds_of(std::span<const RTCBuildPrimitive> primitives) {
    const float inf = std::numeric_limits<float>::infinity();
    RTCBounds b{inf, inf, inf, 0, -inf, -inf, -inf, 0};
    for (const RTCBuildPrimitive& p : primitives) {
        b.lower_x = std::min(b.lower_x, p.lower_x), b.upper_x = std::max(b.upper_x, p.upper_x);
        b.lower_y = std::min(b.lower_y, p.lower_y), b.upper_y = std::max(b.upper_y, p.upper_y);
        b.lower_z = std::min(b.lower_z, p.lower_z), b.upper_z = std::max(b.upper_z, p.upper_z);
    }
    return b;
}

}  // namespace

Result<TriangleBvh> build_triangle_bvh(std::span<const std::array<Vec3, 3>> triangles) {
    TriangleBvh out;
    if (triangles.empty()) return out;
    std::vector<RTCBuildPrimitive> primitives;
    primitives.reserve(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i)
        primitives.push_back(primitive(triangles[i], static_cast<std::uint32_t>(i)));
    const RTCBounds root_box = bounds_of(primitives);

    std::string error;
    const std::unique_ptr<RTCDeviceTy, void (*)(RTCDevice)> device(rtcNewDevice(nullptr),
                                                                   rtcReleaseDevice);
    if (!device) return Error{"Embree: cannot create a device for the GPU's mesh BVH"};
    rtcSetDeviceErrorFunction(device.get(), on_error, &error);
    const std::unique_ptr<RTCBVHTy, void (*)(RTCBVH)> bvh(rtcNewBVH(device.get()), rtcReleaseBVH);
    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    args.maxBranchingFactor = 2;
    args.maxDepth = kTriangleBvhMaxDepth - 1;  // Embree counts edges, the layout nodes
    args.maxLeafSize = kTriangleBvhMaxLeaf;
    args.bvh = bvh.get();
    args.primitives = primitives.data();
    args.primitiveCount = primitives.size();
    args.primitiveArrayCapacity = primitives.size();
    args.createNode = create_inner;
    args.setNodeChildren = set_children;
    args.setNodeBounds = set_bounds;
    args.createLeaf = create_leaf;
    const auto* root = bvh ? static_cast<const BuildNode*>(rtcBuildBVH(&args)) : nullptr;
    if (!root || !error.empty())
        return Error{"the GPU's mesh BVH: " + (error.empty() ? "Embree built none" : error)};
    flatten(root, root_box, 1, out);
    return out;
}

}  // namespace footprint
