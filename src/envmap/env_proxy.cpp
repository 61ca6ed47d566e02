// envmap/env_proxy.cpp — a ray's exit from a box or sphere proxy and the footprint's move onto the
// parallax-corrected direction (env_proxy.h).
#include <footprint/envmap/env_proxy.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace footprint {

namespace {

struct Exit {
    float t;
    Vec3 normal;
};

// The far crossing of the slabs (the box's exit), where the ray crosses the box forwards.
std::optional<Exit> box_exit(Vec3 lo, Vec3 hi, Vec3 p, Vec3 r) {
    const float o[3] = {p.x, p.y, p.z}, d[3] = {r.x, r.y, r.z};
    const float a[3] = {lo.x, lo.y, lo.z}, b[3] = {hi.x, hi.y, hi.z};
    float t_near = -INFINITY, t_far = INFINITY;
    int axis = -1;
    for (int k = 0; k < 3; ++k) {
        if (d[k] == 0) {
            if (o[k] < a[k] || o[k] > b[k]) return std::nullopt;
            continue;
        }
        const float t0 = (a[k] - o[k]) / d[k], t1 = (b[k] - o[k]) / d[k];
        t_near = std::max(t_near, std::min(t0, t1));
        if (std::max(t0, t1) < t_far) t_far = std::max(t0, t1), axis = k;
    }
    if (axis < 0 || !(t_far > 0) || t_near > t_far || !std::isfinite(t_far)) return std::nullopt;
    Vec3 normal{0, 0, 0};
    (axis == 0 ? normal.x : axis == 1 ? normal.y : normal.z) = 1;
    return Exit{t_far, normal};
}

std::optional<Exit> sphere_exit(Vec3 center, float radius, Vec3 p, Vec3 r) {
    const Vec3 o = p - center;
    const float b = dot(o, r), c = dot(o, o) - radius * radius;
    const float discriminant = b * b - c;
    if (!(discriminant >= 0)) return std::nullopt;
    const float t = -b + std::sqrt(discriminant);
    if (!(t > 0)) return std::nullopt;
    return Exit{t, (o + t * r) / radius};
}

}  // namespace

Vec3 ProxyStep::move(Vec3 dp, Vec3 dr) const {
    const Vec3 x = dp + along * dr;
    // P x = x − r̂ (m·x)/(m·r̂).
    return x - (dot(m, x) / dot(m, r_hat)) * r_hat;
}

std::optional<ProxyStep> proxy_step(const EnvProxy& proxy, Vec3 p, Vec3 r) {
    const float length_r = length(r);
    if (!(length_r > 0) || !std::isfinite(length_r) || !is_finite(p)) return std::nullopt;
    const Vec3 r_hat = r / length_r;
    const std::optional<Exit> exit = proxy.shape == EnvProxy::Shape::box
                                         ? box_exit(proxy.min, proxy.max, p, r_hat)
                                         : sphere_exit(proxy.center, proxy.radius, p, r_hat);
    // A ray grazing the exit surface (m·r̂ → 0) has no stable footprint there: the map at infinity.
    if (!exit || !(std::abs(dot(exit->normal, r_hat)) > 1e-4f)) return std::nullopt;
    ProxyStep step;
    step.direction = p + exit->t * r_hat - proxy.capture;
    step.r_hat = r_hat;
    step.m = exit->normal;
    step.along = exit->t / length_r;
    if (!is_finite(step.direction) || !(dot(step.direction, step.direction) > 0))
        return std::nullopt;
    return step;
}

bool proxy_contains(const EnvProxy& proxy, Vec3 p) {
    constexpr float kSurface = 1e-4f;  // of the box's largest extent or the sphere's radius
    if (proxy.shape == EnvProxy::Shape::sphere) {
        const Vec3 o = p - proxy.center;
        const float radius = proxy.radius * (1 + kSurface);
        return dot(o, o) <= radius * radius;
    }
    const Vec3 extent = proxy.max - proxy.min;
    const float tolerance = kSurface * std::max({extent.x, extent.y, extent.z});
    return p.x >= proxy.min.x - tolerance && p.x <= proxy.max.x + tolerance &&
           p.y >= proxy.min.y - tolerance && p.y <= proxy.max.y + tolerance &&
           p.z >= proxy.min.z - tolerance && p.z <= proxy.max.z + tolerance;
}

float proxy_volume(const EnvProxy& proxy) {
    if (proxy.shape == EnvProxy::Shape::sphere)
        return 4.0f / 3.0f * std::numbers::pi_v<float> * proxy.radius * proxy.radius * proxy.radius;
    const Vec3 extent = proxy.max - proxy.min;
    return extent.x * extent.y * extent.z;
}

}  // namespace footprint
