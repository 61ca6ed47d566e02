// scene/mesh_accel.cpp — Embree 3 BVH over triangle meshes; mesh hit differential geometry.
#include "scene/mesh_accel.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace footprint {
namespace {

void on_embree_error(void* user, RTCError code, const char* message) {
    auto* out = static_cast<std::string*>(user);
    if (out->empty())
        *out = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
               (message ? message : "(no message)");
}

struct Barycentric {
    double t, b1, b2;
};

// Möller–Trumbore in double precision, without range tests (the triangle is known to be hit).
std::optional<Barycentric> refine(const Vec3d& o, const Vec3d& d, const Vec3d& p0, const Vec3d& p1,
                                  const Vec3d& p2) {
    const Vec3d e1 = p1 - p0, e2 = p2 - p0;
    const Vec3d pvec = cross(d, e2);
    const double det = dot(e1, pvec);
    if (det == 0 || !std::isfinite(det)) return std::nullopt;
    const double inv = 1.0 / det;
    const Vec3d tvec = o - p0;
    const Vec3d qvec = cross(tvec, e1);
    Barycentric b{dot(e2, qvec) * inv, dot(tvec, pvec) * inv, dot(d, qvec) * inv};
    if (!std::isfinite(b.t) || !std::isfinite(b.b1) || !std::isfinite(b.b2)) return std::nullopt;
    return b;
}

// Keeps (b1, b2) inside the triangle: b1, b2 ≥ 0, b1 + b2 ≤ 1.
void clamp_to_triangle(double& b1, double& b2) {
    b1 = std::max(b1, 0.0);
    b2 = std::max(b2, 0.0);
    const double s = b1 + b2;
    if (s > 1) b1 /= s, b2 /= s;
}

// The ray in Embree's float form, t in [max(t_min, 0), t_max] (+∞ past float's range).
RTCRay embree_ray(const Ray& ray, double t_min, double t_max) {
    RTCRay r{};
    r.org_x = static_cast<float>(ray.origin.x);
    r.org_y = static_cast<float>(ray.origin.y);
    r.org_z = static_cast<float>(ray.origin.z);
    r.dir_x = static_cast<float>(ray.direction.x);
    r.dir_y = static_cast<float>(ray.direction.y);
    r.dir_z = static_cast<float>(ray.direction.z);
    r.tnear = static_cast<float>(std::max(t_min, 0.0));
    r.tfar = t_max >= static_cast<double>(std::numeric_limits<float>::max())
                 ? std::numeric_limits<float>::infinity()
                 : static_cast<float>(t_max);
    r.mask = 0xFFFFFFFFu;
    r.flags = 0;
    r.time = 0;
    return r;
}

// Whether Embree accepts `r`: every origin and direction component within ±1.844e18 (Embree's
// FLT_LARGE), not NaN. Embree asserts otherwise (Debian's build aborts), and a ray beyond that
// range meets no triangle in float precision: it misses.
bool embree_traces(const RTCRay& r) {
    constexpr float kLarge = 1.844e18f;
    for (const float v : {r.org_x, r.org_y, r.org_z, r.dir_x, r.dir_y, r.dir_z}) {
        if (!(std::abs(v) <= kLarge)) return false;
    }
    return !std::isnan(r.tnear) && !std::isnan(r.tfar);
}

}  // namespace

Result<MeshAccel> MeshAccel::build(std::vector<MeshInstance> instances) {
    for (std::size_t i = 0; i < instances.size(); ++i) {
        const TriangleMesh* m = instances[i].mesh;
        if (!m) continue;
        const std::size_t n = m->positions.size();
        for (const auto& tri : m->triangles)
            for (std::uint32_t k : tri)
                if (k >= n)
                    return Error{"mesh '" + m->name + "': index " + std::to_string(k) +
                                 " out of range (" + std::to_string(n) + " vertices)"};
        for (const Vec3d& p : m->positions)
            if (!is_finite(vec3_cast<float>(p)))
                return Error{"mesh '" + m->name + "': vertex position not finite in float"};
    }
    MeshAccel accel;
    accel.instances_ = std::move(instances);
    std::string error;
    accel.device_ = rtcNewDevice(nullptr);
    if (!accel.device_)
        return Error{"Embree: cannot create a device (error " +
                     std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")"};
    rtcSetDeviceErrorFunction(accel.device_, on_embree_error, &error);
    accel.scene_ = rtcNewScene(accel.device_);
    if (accel.scene_) {
        rtcSetSceneFlags(accel.scene_, RTC_SCENE_FLAG_ROBUST);
        for (std::size_t i = 0; i < accel.instances_.size() && error.empty(); ++i) {
            const TriangleMesh* m = accel.instances_[i].mesh;
            if (!m || m->triangles.empty()) continue;
            RTCGeometry geom = rtcNewGeometry(accel.device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            if (!geom) break;
            auto* vb = static_cast<float*>(
                rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), m->positions.size()));
            auto* ib = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(unsigned), m->triangles.size()));
            if (vb && ib) {
                for (std::size_t k = 0; k < m->positions.size(); ++k) {
                    vb[3 * k + 0] = static_cast<float>(m->positions[k].x);
                    vb[3 * k + 1] = static_cast<float>(m->positions[k].y);
                    vb[3 * k + 2] = static_cast<float>(m->positions[k].z);
                }
                for (std::size_t k = 0; k < m->triangles.size(); ++k)
                    for (int c = 0; c < 3; ++c) ib[3 * k + c] = m->triangles[k][c];
                rtcCommitGeometry(geom);
                rtcAttachGeometryByID(accel.scene_, geom, static_cast<unsigned>(i));
            }
            rtcReleaseGeometry(geom);
        }
        if (error.empty()) rtcCommitScene(accel.scene_);
    }
    if (error.empty() && !accel.scene_) error = "Embree: cannot create a scene";
    rtcSetDeviceErrorFunction(accel.device_, nullptr, nullptr);
    if (!error.empty()) return Error{error};
    return accel;
}

MeshAccel::MeshAccel(MeshAccel&& other) noexcept
    : device_(std::exchange(other.device_, nullptr)),
      scene_(std::exchange(other.scene_, nullptr)),
      instances_(std::move(other.instances_)) {
    other.instances_.clear();
}

MeshAccel& MeshAccel::operator=(MeshAccel&& other) noexcept {
    if (this != &other) {
        release();
        device_ = std::exchange(other.device_, nullptr);
        scene_ = std::exchange(other.scene_, nullptr);
        instances_ = std::move(other.instances_);
        other.instances_.clear();
    }
    return *this;
}

MeshAccel::~MeshAccel() {
    release();
}

void MeshAccel::release() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
    scene_ = nullptr;
    device_ = nullptr;
}

bool MeshAccel::occluded(const Ray& ray, double t_min, double t_max) const {
    if (!scene_ || !(t_max >= t_min)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = embree_ray(ray, t_min, t_max);
    if (!embree_traces(r)) return false;
    rtcOccluded1(scene_, &context, &r);
    return r.tfar < 0;  // Embree sets tfar to −∞ on a hit
}

std::optional<MeshHitRecord> MeshAccel::intersect(const Ray& ray, double t_min,
                                                  double t_max) const {
    if (!scene_ || !(t_max >= t_min)) return std::nullopt;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray = embree_ray(ray, t_min, t_max);
    if (!embree_traces(rh.ray)) return std::nullopt;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    MeshHitRecord hit;
    hit.mesh = static_cast<int>(rh.hit.geomID);
    hit.object = instances_[hit.mesh].object;
    hit.triangle = static_cast<int>(rh.hit.primID);
    hit.t = rh.ray.tfar;
    hit.b1 = rh.hit.u;
    hit.b2 = rh.hit.v;
    const TriangleMesh& m = *instances_[hit.mesh].mesh;
    const auto& tri = m.triangles[hit.triangle];
    if (auto r = refine(ray.origin, ray.direction, m.positions[tri[0]], m.positions[tri[1]],
                        m.positions[tri[2]])) {
        hit.t = r->t;
        hit.b1 = r->b1;
        hit.b2 = r->b2;
    }
    hit.t = std::clamp(hit.t, t_min, t_max);
    clamp_to_triangle(hit.b1, hit.b2);
    return hit;
}

SurfaceHit mesh_surface_hit(const TriangleMesh& mesh, int triangle, double b1, double b2,
                            const Ray& ray, double t) {
    const auto& tri = mesh.triangles[triangle];
    const double b0 = 1 - b1 - b2;
    const Vec3d p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]],
                p2 = mesh.positions[tri[2]];
    SurfaceHit h;
    h.t = t;
    h.primitive = triangle;
    h.p = b0 * p0 + b1 * p1 + b2 * p2;
    const Vec3d dp1 = p1 - p0, dp2 = p2 - p0;  // ∂p/∂b1, ∂p/∂b2
    Vec3d ng = normalize(cross(dp1, dp2));

    // (u, v) as a function of (b1, b2): uv = uv0 + b1·e1 + b2·e2. Its inverse Jacobian gives
    // ∂b/∂u and ∂b/∂v; identity when (u, v) = (b1, b2).
    double db1du = 1, db2du = 0, db1dv = 0, db2dv = 1;
    if (mesh.has_uvs()) {
        const Vec2d uv0 = mesh.uvs[tri[0]], uv1 = mesh.uvs[tri[1]], uv2 = mesh.uvs[tri[2]];
        h.uv = b0 * uv0 + b1 * uv1 + b2 * uv2;
        const Vec2d e1 = uv1 - uv0, e2 = uv2 - uv0;
        const double det = e1.x * e2.y - e1.y * e2.x;
        if (std::abs(det) > 1e-12 * (dot(e1, e1) + dot(e2, e2)) && std::isfinite(det)) {
            const double inv = 1.0 / det;
            db1du = e2.y * inv;
            db1dv = -e2.x * inv;
            db2du = -e1.y * inv;
            db2dv = e1.x * inv;
        }
    } else {
        h.uv = {b1, b2};
    }
    h.dpdu = db1du * dp1 + db2du * dp2;
    h.dpdv = db1dv * dp1 + db2dv * dp2;

    bool shading = false;
    if (mesh.has_normals()) {
        const Vec3d n0 = mesh.normals[tri[0]], n1 = mesh.normals[tri[1]], n2 = mesh.normals[tri[2]];
        const Vec3d nn = b0 * n0 + b1 * n1 + b2 * n2;
        const double len = length(nn);
        if (len > 0 && std::isfinite(len)) {
            shading = true;
            h.n = nn / len;
            const Vec3d dn1 = n1 - n0, dn2 = n2 - n0;  // ∂N/∂b1, ∂N/∂b2
            auto project = [&](Vec3d d) { return (d - dot(h.n, d) * h.n) / len; };
            h.dndu = project(db1du * dn1 + db2du * dn2);
            h.dndv = project(db1dv * dn1 + db2dv * dn2);
        }
    }
    if (ng.x == 0 && ng.y == 0 && ng.z == 0)  // degenerate triangle
        ng = shading ? h.n : -normalize(ray.direction);
    if (!shading) {
        h.n = ng;
        h.dndu = h.dndv = Vec3d{0, 0, 0};
    } else if (dot(ng, h.n) < 0) {
        ng = -ng;
    }
    h.geometric_normal = ng;
    return h;
}

std::optional<MeshTangentFrame> mesh_tangent_frame(const TriangleMesh& mesh, int triangle,
                                                   double b1, double b2) {
    if (!mesh.has_tangents()) return std::nullopt;
    const auto& tri = mesh.triangles[triangle];
    const double b0 = 1 - b1 - b2;
    const Vec3d t = normalize(b0 * mesh.tangents[tri[0]].xyz + b1 * mesh.tangents[tri[1]].xyz +
                              b2 * mesh.tangents[tri[2]].xyz);
    if (t.x == 0 && t.y == 0 && t.z == 0) return std::nullopt;
    return MeshTangentFrame{t, mesh.tangents[tri[0]].w < 0 ? -1.0 : 1.0};
}

}  // namespace footprint
