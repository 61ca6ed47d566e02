// bump/local_frame.cpp — natural and orthonormal tangent frames, spec §6 (see local_frame.h).
#include "bump/local_frame.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace footprint {
namespace {

constexpr float kMinSinAngleFloor = 1e-5f;  // below this, m × n̂ has too few correct digits
constexpr float kMaxSinAngle = 0.5f;        // keeps the automatic fallback axis usable (header)
// Relative size of n̂_s·(p_u × p_v) below which a shading normal lies in the tangent plane.
constexpr float kShadingNormalMinCos = 1e-6f;

bool is_zero(Vec3 a) {
    return a.x == 0.0f && a.y == 0.0f && a.z == 0.0f;
}

// The unit world axis with the smallest |v_i| (ties to the lower index); v must be a unit vector.
Vec3 least_aligned_axis(Vec3 v) {
    const float ax = std::abs(v.x), ay = std::abs(v.y), az = std::abs(v.z);
    if (ax <= ay && ax <= az) return {1.0f, 0.0f, 0.0f};
    if (ay <= az) return {0.0f, 1.0f, 0.0f};
    return {0.0f, 0.0f, 1.0f};
}

// e1 = (d × n̂)/|d × n̂|, e2 = n̂ × e1 (spec §6.2) if the sine of the angle between d and n̂ is at
// least min_sin. e1 is re-orthogonalised against n̂ so that the frame stays orthonormal to float
// precision even when d is nearly parallel to n̂.
std::optional<OrthonormalFrame> frame_from_direction(Vec3 n_hat, Vec3 d, float min_sin,
                                                     FrameOrigin origin) {
    const Vec3 d_hat = normalize(d);
    if (is_zero(d_hat)) return std::nullopt;
    Vec3 w = cross(d_hat, n_hat);
    w = w - dot(w, n_hat) * n_hat;
    const float sin_angle = length(w);
    if (!(sin_angle >= min_sin)) return std::nullopt;
    const Vec3 e1 = normalize(w);
    return OrthonormalFrame{e1, cross(n_hat, e1), n_hat, origin};
}

Vec2 finite_or_zero(Vec2 b) {
    return is_finite(b) ? b : Vec2{};
}

}  // namespace

Vec3 perturbed_normal(Vec3 n, const TangentFrame& frame, Vec2 b) {
    if (!is_finite(n)) return {};
    b = finite_or_zero(b);
    return n + length(n) * (b.x * frame.t1 + b.y * frame.t2);  // spec §2.2
}

NaturalFrame make_natural_frame(Vec3 p_u, Vec3 p_v) {
    if (!is_finite(p_u) || !is_finite(p_v)) return {};
    const Vec3 n = cross(p_u, p_v);
    const Vec3 n_hat = normalize(n);
    if (is_zero(n_hat)) return {};
    return {n, cross(n_hat, p_v), cross(p_u, n_hat)};  // spec §6.1
}

NaturalFrame make_natural_frame(Vec3 p_u, Vec3 p_v, Vec3 shading_normal) {
    const Vec3 ns = normalize(shading_normal);
    if (is_zero(ns)) return make_natural_frame(p_u, p_v);
    const NaturalFrame degenerate{ns, {}, {}};
    if (!is_finite(p_u) || !is_finite(p_v)) return degenerate;
    const Vec3 pn = cross(p_u, p_v);
    const float pn_length = length(pn);
    const float area = dot(ns, pn);  // n̂_s·(p_u × p_v)
    if (!std::isfinite(area) || !std::isfinite(pn_length) ||
        !(std::abs(area) > kShadingNormalMinCos * pn_length)) {
        return degenerate;
    }
    const float sigma = area > 0.0f ? 1.0f : -1.0f;  // −1: mirrored (left-handed) uv mapping
    return {std::abs(area) * ns, sigma * cross(ns, p_v), sigma * cross(p_u, ns)};
}

Vec3 perturbed_normal(const NaturalFrame& frame, Vec2 f) {
    f = finite_or_zero(f);
    return frame.n + f.x * frame.s_u + f.y * frame.s_v;  // n' = n + f_u s_u + f_v s_v (§6.1)
}

TangentFrame tangent_frame(const NaturalFrame& frame) {
    const float n_length = length(frame.n);
    if (!(n_length > 0.0f) || !std::isfinite(n_length)) return {};
    return {frame.s_u / n_length, frame.s_v / n_length};
}

OrthonormalFrame make_orthonormal_frame(Vec3 n, Vec3 m, const OrthonormalFrameOptions& options) {
    const Vec3 n_hat = normalize(n);
    if (is_zero(n_hat)) {
        return {{1.0f, 0.0f, 0.0f},
                {0.0f, 1.0f, 0.0f},
                {0.0f, 0.0f, 1.0f},
                FrameOrigin::degenerate_normal};
    }
    // NaN fails the comparison and takes the floor.
    const float min_sin = options.min_sin_angle > kMinSinAngleFloor
                              ? std::min(options.min_sin_angle, kMaxSinAngle)
                              : kMinSinAngleFloor;
    if (auto frame = frame_from_direction(n_hat, m, min_sin, FrameOrigin::main_direction)) {
        return *frame;
    }
    if (auto frame = frame_from_direction(n_hat, options.fallback_direction, min_sin,
                                          FrameOrigin::fallback_direction)) {
        return *frame;
    }
    const Vec3 m_hat = normalize(m);
    if (!is_zero(m_hat)) {
        if (auto frame = frame_from_direction(n_hat, least_aligned_axis(m_hat), min_sin,
                                              FrameOrigin::fallback_direction)) {
            return *frame;
        }
    }
    // Last resort: |axis·n̂| ≤ 1/√3, so |axis × n̂| ≥ √(2/3) > kMaxSinAngle: always succeeds.
    if (auto frame = frame_from_direction(n_hat, least_aligned_axis(n_hat), 0.0f,
                                          FrameOrigin::fallback_direction)) {
        return *frame;
    }
    return {{1.0f, 0.0f, 0.0f},
            {0.0f, 1.0f, 0.0f},
            {0.0f, 0.0f, 1.0f},
            FrameOrigin::degenerate_normal};  // unreachable
}

TangentFrame tangent_frame(const OrthonormalFrame& frame) {
    return {frame.e1, frame.e2};
}

Vec3 perturbed_normal(Vec3 n, const OrthonormalFrame& frame, Vec2 b) {
    return perturbed_normal(n, tangent_frame(frame), b);
}

Vec2 slopes_in_frame(Vec2 b, const TangentFrame& from, const OrthonormalFrame& to) {
    b = finite_or_zero(b);
    const Vec3 d = b.x * from.t1 + b.y * from.t2;
    return {dot(d, to.e1), dot(d, to.e2)};
}

}  // namespace footprint
