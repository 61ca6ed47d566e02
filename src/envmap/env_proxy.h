// envmap/env_proxy.h — local, parallax-corrected environment maps: the paper's "position-dependent
// environment maps".
//
// A map captured at a point c inside a room shows each wall point q in the direction q − c. A
// surface point p elsewhere in the room sees along its reflected direction r the wall point
// q = p + t r̂ where that ray leaves the room, and so must read the map in the direction
//
//     d = q − c,
//
// not r (which is right only for p = c or walls at infinity). The room is a proxy: a box or a
// sphere. Where the ray from p does not leave it forwards (p outside, the proxy behind or
// missed), d = r: the map at infinity.
//
// The footprint. d depends on p and r; to first order (r̂ = r/|r|, m the proxy's normal at q,
// P = I − r̂ mᵀ/(m·r̂) the projection onto the tangent plane at q along r̂):
//
//     ∂q = P (∂p + t ∂r̂),   ∂r̂ = (I − r̂ r̂ᵀ) ∂r/|r|,   so   ∂d = P ∂p + (t/|r|) P ∂r
//
// (P r̂ = 0 absorbs the radial part of ∂r, and the change of t moves q along r̂, which P removes).
// The distance term (t/|r|) P scales and shears every direction spread the footprint holds — the
// pixel's ∂r/∂x, ∂r/∂y and the roughness columns — and P ∂p adds the pixel's own motion across
// the surface, which a map at infinity does not see. ProxyStep applies both to an EnvFootprint's
// vectors (env_footprint.h), which then gives the footprint in d's texel space.
//
// Nested proxies. A scene may hold several local maps (a room, an alcove in it, a cabinet in
// that): each point reads the innermost one whose proxy contains it, the smallest by volume among
// those that do, and the scene's environment where none does.
#pragma once

#include <optional>

#include <footprint/math/vec3.h>

namespace footprint {

struct EnvProxy {
    enum class Shape { box, sphere };
    Shape shape = Shape::box;
    Vec3 min{-1, -1, -1}, max{1, 1, 1};  // box
    Vec3 center{0, 0, 0};                // sphere
    float radius = 1;                    // sphere
    Vec3 capture{0, 0, 0};               // c: where the map was captured (world space)
};

// Where a ray from p along r leaves the proxy, and the linear map of ∂p and ∂r onto ∂d there.
struct ProxyStep {
    Vec3 direction;   // d = q − c
    Vec3 r_hat, m;    // the ray's unit direction, the proxy's normal at q
    float along = 0;  // t/|r|
    // ∂d = P ∂p + (t/|r|) P ∂r.
    Vec3 move(Vec3 dp, Vec3 dr) const;
};

// The step for a ray from p along r (any nonzero length), or nullopt where the ray does not leave
// the proxy forwards (the map is then at infinity: d = r).
std::optional<ProxyStep> proxy_step(const EnvProxy& proxy, Vec3 p, Vec3 r);

// Whether p lies in the proxy, its surface included to within 1e-4 of its size: a room's floor
// that is the box's face belongs to the room wherever the hit point rounds.
bool proxy_contains(const EnvProxy& proxy, Vec3 p);
// The proxy's volume, which orders nested proxies (innermost first).
float proxy_volume(const EnvProxy& proxy);

}  // namespace footprint
