// texture/parallax.cpp — the parallax-occlusion march and its derivatives (parallax.h).
#include <footprint/texture/parallax.h>

#include <algorithm>
#include <cmath>

namespace footprint {

namespace {

float dot2(Vec2 a, Vec2 b) {
    return a.x * b.x + a.y * b.y;
}

}  // namespace

Vec2 parallax_direction(Vec3 v, Vec3 dp_ds, Vec3 dp_dt, Vec3 n) {
    const Vec3 n_hat = normalize(n), v_hat = normalize(v);
    const float cos_v = dot(v_hat, n_hat);
    if (!(cos_v > 1e-4f)) return {0, 0};
    // The tangential part of v̂ as a ∂p/∂s + b ∂p/∂t: the 2×2 normal equations of the frame.
    const Vec3 tangential = v_hat - cos_v * n_hat;
    const float ss = dot(dp_ds, dp_ds), st = dot(dp_ds, dp_dt), tt = dot(dp_dt, dp_dt);
    const float det = ss * tt - st * st;
    if (!(std::abs(det) > 1e-20f) || !std::isfinite(det)) return {0, 0};
    const float rs = dot(tangential, dp_ds), rt = dot(tangential, dp_dt);
    const Vec2 ab{(tt * rs - st * rt) / det, (ss * rt - st * rs) / det};
    const Vec2 w = -(1 / cos_v) * ab;
    return std::isfinite(w.x) && std::isfinite(w.y) ? w : Vec2{0, 0};
}

ParallaxResult parallax_march(const std::function<float(Vec2)>& height,
                              const std::function<Vec2(Vec2)>& gradient, Vec2 st, Vec2 dst_dx,
                              Vec2 dst_dy, Vec2 w, const ParallaxOptions& options) {
    ParallaxResult out{st, dst_dx, dst_dy, 0};
    const int steps = std::clamp(options.steps, 1, kMaxParallaxSteps);
    Vec2 shift = options.depth * w;  // (s, t) travelled from the top to the bottom
    const float length = std::sqrt(dot2(shift, shift));
    if (!(length > 0) || !std::isfinite(length)) return out;
    if (length > options.max_shift) shift = (options.max_shift / length) * shift;

    // Step down until the ray is below the relief: f(z) = z − (1 − h) ≥ 0.
    float z_before = 0, f_before = -(1 - height(st));
    if (f_before >= 0) return out;  // the top of the relief: no shift
    float z = 0, f = f_before;
    for (int i = 1; i <= steps; ++i) {
        z = static_cast<float>(i) / static_cast<float>(steps);
        f = z - (1 - height(st + z * shift));
        if (f >= 0) break;
        z_before = z, f_before = f;
    }
    // The crossing of the two lines between the last step above and the first below.
    const float crossing =
        f > f_before ? z_before + (z - z_before) * (-f_before) / (f - f_before) : z;
    out.depth_fraction = std::clamp(crossing, 0.0f, 1.0f);
    out.st = st + out.depth_fraction * shift;

    // ∂s' = ∂s − depth·w (∇h·∂s)/(1 + depth ∇h·w), with the clamped shift as depth·w.
    const Vec2 g = gradient(out.st);
    const float denominator = 1 + dot2(g, shift);
    if (denominator > 0.25f && std::isfinite(denominator)) {
        out.dst_dx = dst_dx - (dot2(g, dst_dx) / denominator) * shift;
        out.dst_dy = dst_dy - (dot2(g, dst_dy) / denominator) * shift;
    }
    return out;
}

}  // namespace footprint
