// scene/mesh_accel.h — ray intersection with triangle meshes (an Embree 3 BVH), and the
// differential geometry of a mesh hit for ray differentials.
//
// MeshAccel holds an Embree device and scene built over a list of meshes, each tagged with the
// scene object it belongs to. intersect() returns the nearest hit as (object, mesh, triangle, t,
// barycentrics); mesh_surface_hit() turns that into a SurfaceHit (scene/surface.h).
//
// Precision: Embree works in single precision. The vertices are copied to a float buffer and the
// BVH traversal is in float; intersect() then recomputes t and the barycentrics of the triangle
// Embree found in double precision (one Möller–Trumbore test against the double vertices), so a
// hit's t, b1, b2 are as accurate as the double geometry allows. Which triangle is hit is decided
// in float: within about 1e-7 relative of an edge, the neighbour may be reported, and a ray
// grazing a silhouette within that distance may hit or miss. The scene is built with Embree's
// robust flag (watertight: no ray passes between two triangles sharing an edge).
//
// Lifetime: MeshAccel keeps pointers to the meshes it was built from (for the refinement and
// mesh()); they must outlive it and not change.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "math/vec.h"
#include "math/vec3.h"
#include "scene/mesh.h"
#include "scene/surface.h"

struct RTCDeviceTy;
struct RTCSceneTy;

namespace footprint {

struct MeshInstance {
    int object = -1;                     // index into the scene's objects, reported back on a hit
    const TriangleMesh* mesh = nullptr;  // null or without triangles: skipped
};

struct MeshHitRecord {
    int object = -1;        // MeshInstance::object
    int mesh = -1;          // index of the instance in the list MeshAccel was built from
    int triangle = -1;      // index into the mesh's triangles
    double t = 0;           // ray parameter, in units of |direction|
    double b1 = 0, b2 = 0;  // barycentrics: p = (1 − b1 − b2)·p0 + b1·p1 + b2·p2
};

class MeshAccel {
  public:
    // An empty accelerator: intersect() always misses.
    MeshAccel() = default;
    // Builds the BVH over `instances` (any number, empty included). Fails only if Embree does
    // (unsupported CPU, out of memory), with Embree's message.
    static Result<MeshAccel> build(std::vector<MeshInstance> instances);

    MeshAccel(MeshAccel&& other) noexcept;
    MeshAccel& operator=(MeshAccel&& other) noexcept;
    MeshAccel(const MeshAccel&) = delete;
    MeshAccel& operator=(const MeshAccel&) = delete;
    ~MeshAccel();  // releases the Embree scene and device

    // The nearest hit with t in [t_min, t_max] (t_max may be +∞), or none. Thread-safe: any
    // number of threads may call it at once. The ray's direction need not be unit length.
    std::optional<MeshHitRecord> intersect(const Ray& ray, double t_min, double t_max) const;
    // Whether any triangle is hit with t in [t_min, t_max] (a shadow ray): Embree's any-hit
    // query, which stops at the first hit it finds. Thread-safe as intersect().
    bool occluded(const Ray& ray, double t_min, double t_max) const;

    std::size_t size() const { return instances_.size(); }
    const MeshInstance& instance(int mesh) const { return instances_[mesh]; }

  private:
    void release();

    RTCDeviceTy* device_ = nullptr;
    RTCSceneTy* scene_ = nullptr;
    std::vector<MeshInstance> instances_;
};

// The surface at barycentrics (b1, b2) of triangle `triangle` of `mesh`, hit by `ray` at `t`:
//   p      (1 − b1 − b2)·p0 + b1·p1 + b2·p2 (not origin + t·direction: it lies on the triangle)
//   geometric_normal   unit (p1 − p0) × (p2 − p0), flipped to the side of n when they disagree
//   n      the interpolated vertex normal, normalised, facing as stored; the geometric normal
//          (counter-clockwise side) without vertex normals or where the interpolation vanishes
//   uv     the interpolated UVs; (b1, b2) for a mesh without UVs
//   ∂p/∂u, ∂p/∂v   from the triangle's UVs (pbrt's method: invert the 2×2 matrix of UV edges).
//          Without UVs, or where that matrix is singular (|det| ≤ 1e-12·(|Δuv₁|² + |Δuv₂|²)),
//          the derivatives are taken with respect to (b1, b2) instead: ∂p/∂u = p1 − p0,
//          ∂p/∂v = p2 − p0 (uv still holds the interpolated UVs if there are any).
//   ∂n/∂u, ∂n/∂v   derivatives of the normalised interpolated normal N/|N| with respect to the
//          same (u, v): (I − n·nᵀ)·(∂N/∂u)/|N|, with ∂N/∂b1 = n1 − n0, ∂N/∂b2 = n2 − n0 and the
//          chain rule through the barycentrics; zero without vertex normals (flat triangle).
// `object` is left at −1 (the scene sets it), `primitive` = triangle. `ray` is not used beyond t;
// it is taken for symmetry with the analytic shapes.
SurfaceHit mesh_surface_hit(const TriangleMesh& mesh, int triangle, double b1, double b2,
                            const Ray& ray, double t);

// The interpolated tangent frame of a mesh with tangents (glTF TANGENT), for normal mapping.
struct MeshTangentFrame {
    Vec3d tangent;  // unit (1 − b1 − b2)·t0 + b1·t1 + b2·t2, not orthogonalised against n
    double tangent_sign;  // ±1: the bitangent is tangent_sign·(n × tangent) (v up); vertex 0's
};

// None if the mesh has no tangents or the interpolated tangent vanishes.
std::optional<MeshTangentFrame> mesh_tangent_frame(const TriangleMesh& mesh, int triangle,
                                                   double b1, double b2);

}  // namespace footprint
