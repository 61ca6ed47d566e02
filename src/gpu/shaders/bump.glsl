// gpu/shaders/bump.glsl — bump maps' frames at a hit, and parallax-occlusion mapping
// (bump/local_frame.h, render/bump_frame.cpp, texture/parallax.h). The moments → slopes step and
// the roughness factor are the library's (footprint/bump.glsl, docs/method.md, "The moment
// pyramid").
//
// A bump map is its moment pyramid as two layers: (μ'1, μ'2, M2'11, M2'12) and (M2'22): every
// filter blends the moments with its weights, and fp_slope_stats() gives K_b = M2 − μμᵀ, the
// covariance of all the finest-level slopes in the filtered region.

#include "footprint/bump.glsl"

// ---- Frames (spec §6). T = (t1 t2) = ∂n̂_m/∂b; slope_sign as render/bump_frame.h.
struct Frame {
    vec3 t1, t2;
    float slope_sign;
};

// The unit world axis least aligned with unit v (ties to the lower index).
vec3 least_aligned_axis(vec3 v) {
    vec3 a = abs(v);
    if (a.x <= a.y && a.x <= a.z) return vec3(1, 0, 0);
    if (a.y <= a.z) return vec3(0, 1, 0);
    return vec3(0, 0, 1);
}

// e1 = (d × n̂)/|d × n̂| re-orthogonalised against n̂, if |d̂ × n̂| ≥ min_sin.
bool frame_from_direction(vec3 n_hat, vec3 d, float min_sin, out Frame frame) {
    float len = length(d);
    frame = Frame(vec3(0), vec3(0), 1.0);
    if (!(len > 0.0)) return false;
    vec3 w = cross(d / len, n_hat);
    w -= dot(w, n_hat) * n_hat;
    if (!(length(w) >= min_sin)) return false;
    vec3 e1 = normalize(w);
    frame = Frame(e1, cross(n_hat, e1), 1.0);
    return true;
}

// Spec §6.2: e1 = (m × n̂)/|m × n̂|, e2 = n̂ × e1, with local_frame.h's fallbacks.
Frame orthonormal_frame(vec3 n, vec3 m) {
    vec3 n_hat = normalize(n);
    Frame f;
    if (frame_from_direction(n_hat, m, 1e-3, f)) return f;
    if (length(m) > 0.0 && frame_from_direction(n_hat, least_aligned_axis(normalize(m)), 1e-3, f))
        return f;
    frame_from_direction(n_hat, least_aligned_axis(n_hat), 0.0, f);
    return f;
}

// Spec §6.1 with a shading normal: s_u = σ n̂ × p_v, s_v = σ p_u × n̂, T = (s_u s_v)/|n|.
Frame natural_frame(vec3 pu, vec3 pv, vec3 n, bool normalized) {
    vec3 ns = normalize(n);
    vec3 pn = cross(pu, pv);
    float area = dot(ns, pn);
    if (!(abs(area) > 1e-6 * length(pn))) return Frame(vec3(0), vec3(0), -1.0);
    float sigma = area > 0.0 ? 1.0 : -1.0;
    vec3 su = sigma * cross(ns, pv), sv = sigma * cross(pu, ns);
    if (normalized) return Frame(normalize(su), normalize(sv), -1.0);
    return Frame(su / abs(area), sv / abs(area), -1.0);
}

// The frame of a material's bump map at a hit (render/bump_frame.cpp).
Frame bump_frame(Material m, Hit hit) {
    if (m.base_color.w > 0.0 && hit.tangent.w != 0.0) {
        // glTF: e1 = the tangent made orthogonal to n, e2 = sign·(n × e1) (up the image).
        vec3 t = hit.tangent.xyz, e1 = t - dot(t, hit.n) * hit.n;
        if (dot(e1, e1) > 0.0) {
            e1 = normalize(e1);
            return Frame(e1, hit.tangent.w * cross(hit.n, e1), 1.0);
        }
    }
    int kind = int(m.bump.z);
    if (kind == 0) return natural_frame(hit.dpdu, hit.dpdv, hit.n, false);
    if (kind == 1) return natural_frame(hit.dpdu, hit.dpdv, hit.n, true);
    vec3 main_direction = m.main_direction.xyz;
    return orthonormal_frame(hit.n, dot(main_direction, main_direction) == 0.0 ? hit.dpdv
                                                                                : main_direction);
}

// K_b in the orthonormal basis (e1, e2) (render/bump_frame.h's covariance_in_frame).
vec3 covariance_in_frame(vec3 k, Frame t, vec3 e1, vec3 e2) {
    float a1 = dot(e1, t.t1), a2 = dot(e1, t.t2), b1 = dot(e2, t.t1), b2 = dot(e2, t.t2);
    mat2 kk = mat2(k.x, k.y, k.y, k.z);
    vec2 a = vec2(a1, a2), b = vec2(b1, b2);
    return vec3(dot(a, kk * a), dot(a, kk * b), dot(b, kk * b));
}

// ---- Parallax-occlusion mapping (texture/parallax.h): (s, t) and their derivatives moved to where
// the view ray meets the height map's relief.

// w = −(a, b)/(v̂·n̂) per world unit of depth, a ∂p/∂s + b ∂p/∂t the tangential part of v̂.
vec2 parallax_direction(vec3 v, vec3 dp_ds, vec3 dp_dt, vec3 n) {
    vec3 n_hat = normalize(n), v_hat = normalize(v);
    float cos_v = dot(v_hat, n_hat);
    if (!(cos_v > 1e-4)) return vec2(0);
    vec3 tangential = v_hat - cos_v * n_hat;
    float ss = dot(dp_ds, dp_ds), st = dot(dp_ds, dp_dt), tt = dot(dp_dt, dp_dt);
    float det = ss * tt - st * st;
    if (!(abs(det) > 1e-20) || !fp_is_finite(det)) return vec2(0);
    float rs = dot(tangential, dp_ds), rt = dot(tangential, dp_dt);
    vec2 w = -vec2(tt * rs - st * rt, ss * rt - st * rs) / (det * cos_v);
    return fp_is_finite(w.x + w.y) ? w : vec2(0);
}

// hw-aniso marches over trilinear heights, as engines do: ~30 anisotropic reads per pixel would
// cost more than the shading they serve, and the heights only place the crossing.
float parallax_height(Material m, vec2 st, vec4 dst, int mode) {
    int height_mode = mode == MODE_HW_ANISO ? MODE_TRILINEAR : mode;
    return lookup_2d(m.height_map.x, m.height_map.y, 1, st, dst, height_mode).a.r;
}

// The march (parallax_march()): material.parallax = (depth, steps, max_shift); st and dst updated.
void parallax_march(Material m, vec2 w, inout vec2 st, inout vec4 dst, int mode) {
    int steps = clamp(int(m.parallax.y), 1, 256);
    vec2 shift = m.parallax.x * w;
    float len = length(shift);
    if (!(len > 0.0) || !fp_is_finite(len)) return;
    if (len > m.parallax.z) shift *= m.parallax.z / len;
    float z_before = 0.0, f_before = -(1.0 - parallax_height(m, st, dst, mode));
    if (f_before >= 0.0) return;
    float z = 0.0, f = f_before;
    for (int i = 1; i <= steps; ++i) {
        z = float(i) / float(steps);
        f = z - (1.0 - parallax_height(m, st + z * shift, dst, mode));
        if (f >= 0.0) break;
        z_before = z;
        f_before = f;
    }
    float crossing = f > f_before ? z_before + (z - z_before) * (-f_before) / (f - f_before) : z;
    vec2 at = st + clamp(crossing, 0.0, 1.0) * shift;
    // ∂s' = ∂s − shift (∇h·∂s)/(1 + ∇h·shift), ∇h by central differences.
    vec2 size = map_size(m.height_map.x);
    vec2 h = 0.5 * max(abs(dst.xy) + abs(dst.zw), 1.0 / size);
    vec2 g = vec2(parallax_height(m, at + vec2(h.x, 0), dst, mode) -
                      parallax_height(m, at - vec2(h.x, 0), dst, mode),
                  parallax_height(m, at + vec2(0, h.y), dst, mode) -
                      parallax_height(m, at - vec2(0, h.y), dst, mode)) / (2.0 * h);
    float denominator = 1.0 + dot(g, shift);
    if (denominator > 0.25 && fp_is_finite(denominator)) {
        dst.xy -= (dot(g, dst.xy) / denominator) * shift;
        dst.zw -= (dot(g, dst.zw) / denominator) * shift;
    }
    st = at;
}
