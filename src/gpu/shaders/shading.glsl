// gpu/shaders/shading.glsl — Fresnel over the slopes (shading/fresnel.h) and the shading of one hit
// (render/renderer.h's "Shading"), the same steps as the CPU renderer. The roughness-aware
// Blinn-Phong and microfacet highlights and Schlick's Fresnel are the library's
// (footprint/highlight.glsl, docs/method.md, "Shading").

#include "footprint/highlight.glsl"

// The channels' mean; exactly their value where they are equal (as the CPU's channel_mean()).
float channel_mean(vec3 c) {
    return c.x == c.y && c.y == c.z ? c.x : (c.x + c.y + c.z) / 3.0;
}

// ---- Fresnel over Gaussian slopes (shading/fresnel.h's fresnel_over_slopes()).

// Φ(z) by Abramowitz & Stegun 7.1.26 (|error| < 1.5e-7): GLSL has no erf.
float normal_cdf(float z) {
    float x = abs(z) / sqrt(2.0);
    float t = 1.0 / (1.0 + 0.3275911 * x);
    float poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 +
                 t * (-1.453152027 + t * 1.061405429))));
    float tail = 0.5 * poly * exp(-x * x);  // 1 − Φ(|z|)
    return z >= 0.0 ? 1.0 - tail : tail;
}

// The incomplete moments of the standard normal density from z0 on (shading/fresnel.cpp):
// to_z1[k] = ∫_{z0}^{z1} z^k φ (k ≤ 7), to_inf[k] = ∫_{z0}^{∞} z^k φ (k ≤ 2), below = Φ(z0); bounds
// beyond ±10 count as infinite (φ(10) ≈ 8e-23).
void normal_moments(float z0, float z1, out float to_z1[8], out float to_inf[3], out float below) {
    if (z0 <= -10.0 && z1 >= 10.0) {  // the whole line: E[z^k] = (k − 1)!!
        to_z1 = float[8](1.0, 0.0, 1.0, 0.0, 3.0, 0.0, 15.0, 0.0);
        to_inf = float[3](1.0, 0.0, 1.0);
        below = 0.0;
        return;
    }
    z0 = clamp(z0, -10.0, 10.0);
    z1 = clamp(z1, -10.0, 10.0);
    float phi0 = exp(-0.5 * z0 * z0) * 0.3989422804, phi1 = exp(-0.5 * z1 * z1) * 0.3989422804;
    float cdf0 = normal_cdf(z0), cdf1 = normal_cdf(z1);
    below = cdf0;
    to_z1[0] = cdf1 - cdf0;
    to_z1[1] = phi0 - phi1;
    to_inf[0] = 1.0 - cdf0;
    to_inf[1] = phi0;
    float edge0 = phi0, edge1 = phi1;  // z^{k−1} φ(z) at both bounds
    for (int k = 2; k < 8; ++k) {
        edge0 *= z0;
        edge1 *= z1;
        to_z1[k] = float(k - 1) * to_z1[k - 2] + edge0 - edge1;
        if (k < 3) to_inf[k] = float(k - 1) * to_inf[k - 2] + edge0;
    }
}

struct FresnelOverSlopes {
    float mean;         // E[F; c ≥ 0]
    float facing_away;  // P(c < 0)
    float schlick;      // E[(1 − c)⁵; 0 ≤ c ≤ 1]: any F0's mean is
                        // F0 (1 − facing_away) + (1 − F0) schlick
    vec2 shift;         // the F-weighted mean slope − b̄ (slopes facing the eye)
    vec3 k;             // their F-weighted covariance (xx, xy, yy)
};

FresnelOverSlopes fresnel_over_slopes(float f0, float cos_mean, vec2 u, vec3 k) {
    FresnelOverSlopes out_f = FresnelOverSlopes(fp_schlick_fresnel(f0, cos_mean), 0.0,
                                                fp_schlick_fresnel(0.0, cos_mean), vec2(0), k);
    float variance = k.x * u.x * u.x + 2.0 * k.y * u.x * u.y + k.z * u.y * u.y;
    if (!(variance > 1e-12)) return out_f;
    float sigma = sqrt(variance), a = 1.0 - cos_mean;
    float to_z1[8], to_inf[3], below;
    normal_moments(-cos_mean / sigma, (1.0 - cos_mean) / sigma, to_z1, to_inf, below);
    // (a − σz)⁵ = Σ_j c_j z^j, c_j = C(5, j) a^{5−j} (−σ)^j (GLSL's pow is undefined for a
    // negative base, so the powers are products).
    const float binomial[6] = float[6](1.0, 5.0, 10.0, 10.0, 5.0, 1.0);
    float c[6];
    float a_power = 1.0, s_power = 1.0;
    for (int j = 5; j >= 0; --j) {
        c[j] = a_power;  // a^{5−j}
        a_power *= a;
    }
    for (int j = 0; j <= 5; ++j) {
        c[j] *= binomial[j] * s_power;
        s_power *= -sigma;
    }
    float moments[3];
    for (int m = 0; m < 3; ++m) {
        float quintic = 0.0;
        for (int j = 0; j <= 5; ++j) quintic += c[j] * to_z1[m + j];
        moments[m] = f0 * to_inf[m] + (1.0 - f0) * quintic;
        if (m == 0) out_f.schlick = quintic;
    }
    out_f.facing_away = below;
    if (!(moments[0] > 0.0)) return out_f;
    vec2 ku = vec2(k.x * u.x + k.y * u.y, k.y * u.x + k.z * u.y);
    float mean_z = moments[1] / moments[0];
    float variance_z = max(0.0, moments[2] / moments[0] - mean_z * mean_z);
    float narrowing = (1.0 - variance_z) / variance;
    out_f.mean = moments[0];
    out_f.shift = (mean_z / sigma) * ku;
    out_f.k = k - narrowing * vec3(ku.x * ku.x, ku.x * ku.y, ku.y * ku.y);
    return out_f;
}

void tangent_basis(vec3 n, out vec3 u, out vec3 v) {
    u = normalize(cross(n, abs(n.x) < 0.6 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    v = cross(n, u);
}

// ---- Shadows (SampleShader::in_shadow()). The ray starts off the surface on the eye's side by
// the CPU's kShadowBias × (1 + the distances to the eye and to the world origin), beyond the
// rounding of a float hit point.
vec3 shadow_ray_origin(Hit hit, vec3 eye) {
    vec3 ng = dot(hit.ng, eye - hit.p) < 0.0 ? -hit.ng : hit.ng;
    return hit.p + 1e-4 * (1.0 + length(hit.p - eye) + length(hit.p + u_camera_position)) * ng;
}

bool in_shadow(Light light, vec3 origin) {
    if (light.color.w == 0.0) return false;
    if (light.direction.w == 0.0) return scene_occluded(Ray(origin, -light.direction.xyz), FLT_MAX);
    return scene_occluded(Ray(origin, light.position.xyz - origin), 1.0);  // the light at t = 1
}

// ---- One hit, shaded (render/renderer.cpp's shade_hit()).
vec3 shade_hit(Ray ray, vec3 dddx, vec3 dddy, Hit hit) {
    Material material = materials[hit.material];
    int mode = u_mode;
    bool filtered = mode != MODE_POINT;
    bool rough_mode = mode == MODE_FA_ROUGH;

    // Ray differentials → texture coordinates: (s, t) = (u, 1 − v) and their derivatives.
    Differentials diff;
    diff.valid = false;
    if (filtered) diff = surface_differentials(ray, dddx, dddy, hit);
    if (!diff.valid) {
        diff.dpdx = diff.dpdy = diff.dndx = diff.dndy = vec3(0);
        diff.duvdx = diff.duvdy = vec2(0);
    }
    vec2 st = fract(vec2(hit.uv.x, 1.0 - hit.uv.y));
    vec4 dst = vec4(diff.duvdx.x, -diff.duvdx.y, diff.duvdy.x, -diff.duvdy.y);
    if (material.parallax.x > 0.0) {  // (s, t) = (u, 1 − v): ∂p/∂t = −∂p/∂v
        parallax_march(material, parallax_direction(ray.origin - hit.p, hit.dpdu, -hit.dpdv, hit.n),
                       st, dst, mode);
        st = fract(st);
    }

    vec3 base = material.base_color.rgb;
    if (material.maps.x >= 0)
        base *= lookup_2d(material.maps.x, material.maps.y, 1, st, dst, mode).a.rgb;
    if (material.procedural.x > 0.0)  // band-limited where the derivatives are (diff.valid)
        base *= procedural_color(material, hit.p + u_camera_position, diff.dpdx, diff.dpdy);
    vec3 f0 = material.f0.rgb;
    float micro_variance = material.bump.w * material.bump.w;  // σ² of the micro-roughness
    if (material.f0_map.x >= 0) {
        vec4 texel = lookup_2d(material.f0_map.x, material.f0_map.y, 1, st, dst, mode).a;
        f0 = clamp(f0 * texel.rgb, 0.0, 1.0);
        micro_variance = max(0.0, texel.a);
    }

    bool bump_map = material.maps.z >= 0;
    bool procedural_bump = material.procedural_bump.x > 0.0;
    bool bumped = bump_map || procedural_bump || material.bump.w > 0.0;
    Frame frame = Frame(vec3(1, 0, 0), vec3(0, 1, 0), 1.0);
    if (bumped) frame = bump_frame(material, hit);

    // Bump: the mean slope b and roughness K_b of the filtered region (spec §5.4).
    vec2 slope = vec2(0);
    vec3 k_b = material.roughness.xyz;
    if (bump_map) {
        Texel moments = lookup_2d(material.maps.z, material.maps.w, 2, st, dst, mode);
        FpSlopeStats stats = fp_slope_stats(moments.a, moments.b.x,
                                            vec2(material.main_direction.w, material.roughness.w));
        slope = stats.mean;
        k_b = stats.k;
    } else if (procedural_bump) {  // h = strength·v: b = −∇h and K_b in the orthonormal frame
        ProceduralSlopes ps = procedural_slopes(material.procedural_bump, hit.p + u_camera_position,
                                                diff.dpdx, diff.dpdy);
        float a = material.procedural_bump.w;
        slope = -a * vec2(dot(ps.gradient, frame.t1), dot(ps.gradient, frame.t2));
        k_b += a * a * vec3(dot(frame.t1, ps.covariance * frame.t1),
                            dot(frame.t1, ps.covariance * frame.t2),
                            dot(frame.t2, ps.covariance * frame.t2));
    }
    if (!rough_mode) k_b = vec3(0);
    vec2 b_t = frame.slope_sign * slope;

    // Face the viewer (a surface seen from behind is shaded as its mirror image).
    vec3 n = hit.n, dndx = diff.dndx, dndy = diff.dndy;
    vec3 v = ray.origin - hit.p, v_hat = normalize(v);
    if (dot(hit.ng, v) < 0.0) {
        n = -n;
        dndx = -dndx;
        dndy = -dndy;
        frame.t1 = -frame.t1;
        frame.t2 = -frame.t2;
    }
    if (!fp_is_finite(b_t.x + b_t.y)) b_t = vec2(0);
    vec3 n_m = bumped ? n + length(n) * (b_t.x * frame.t1 + b_t.y * frame.t2) : n;
    vec3 n_hat = normalize(n_m);
    if (dot(n_hat, v_hat) <= 0.0) n_hat = n;  // a slope tilted past the viewer (spec §4)
    if (dot(n_hat, v_hat) <= 0.0) n_hat = v_hat;

    vec3 color = vec3(0);
    vec3 e1, e2;
    tangent_basis(n_hat, e1, e2);
    vec3 k_e = bumped && rough_mode ? covariance_in_frame(k_b, frame, e1, e2) : k_b;
    // A metallic-roughness material's α is in K_b; where the mode leaves K_b out, its texel's.
    float alpha = material.highlight.z > 0.0 ? (rough_mode ? 0.0 : sqrt(2.0 * micro_variance))
                                             : material.highlight.y;
    vec3 shadow_origin = shadow_ray_origin(hit, ray.origin);
    for (int i = 0; i < u_light_count; ++i) {
        Light light = lights[i];
        vec3 l;
        float scale = 1.0;
        if (light.direction.w == 0.0) {
            l = normalize(-light.direction.xyz);
        } else {
            vec3 d = light.position.xyz - hit.p;
            float d2 = dot(d, d);
            if (!(d2 > 0.0)) continue;
            l = d / sqrt(d2);
            scale = 1.0 / d2;
        }
        float cos_l = dot(n_hat, l);
        if (cos_l <= 0.0 || in_shadow(light, shadow_origin)) continue;
        vec3 h = normalize(l + v_hat);
        int highlight = int(material.highlight.x);
        vec3 spec = vec3(0);
        if (material.weights.y > 0.0 && highlight == FP_HIGHLIGHT_BLINN_PHONG) {
            spec = vec3(material.weights.y *
                        fp_specular_lobe(rough_mode, n_hat, e1, e2, h, k_e, material.weights.z));
        } else if (material.weights.y > 0.0) {  // f_r·cos_l, widened by K_b in the rough mode
            spec = material.weights.y * fp_microfacet_highlight(highlight, n_hat, e1, e2, l, v_hat,
                                                             rough_mode ? k_e : vec3(0),
                                                             alpha, f0);
        }
        color += scale * light.color.rgb * (material.weights.x * cos_l * base + spec);
    }

    vec3 p_world = hit.p + u_camera_position;
    use_environment_at(p_world);  // the innermost local map around the point, else the scene's
    if (env_layout != ENV_NONE && material.f0.w > 0.0) {
        // K_b's mean variance widens the diffuse light, less a metallic-roughness material's own.
        float variance = 0.5 * (k_b.x + k_b.z) - (material.highlight.z > 0.0 ? micro_variance : 0.0);
        color += material.f0.w * base * env_irradiance(n_hat, rough_mode ? max(0.0, variance) : 0.0) / PI;
    }
    int probe = material.probe.x;  // a dynamic environment map's slot, which the mirror reads
    if (probe >= 0) use_slot(probe);
    if (env_layout != ENV_NONE && material.weights.w > 0.0) {
        vec3 texel;
        vec3 fresnel = fp_schlick_fresnel3(f0, dot(n_hat, v_hat));
        float f0_mean = channel_mean(f0);  // steers the Fresnel-weighted slopes
        if (filtered) {
            // The rough mode averages Fresnel over the slopes and looks the reflection up under
            // the slopes weighted by it (in b_t's coordinates, where K_b is the same).
            vec2 b_env = b_t;
            vec3 k_env = k_b;
            float facing_away = 0.0;
            if (bumped && rough_mode) {
                vec3 tangential = v_hat - dot(n_hat, v_hat) * n_hat;
                vec2 u = length(n) / length(n_m) *
                         vec2(dot(frame.t1, tangential), dot(frame.t2, tangential));
                if (!fp_is_finite(u.x + u.y)) u = vec2(0);
                FresnelOverSlopes w = fresnel_over_slopes(f0_mean, dot(n_hat, v_hat), u, k_b);
                fresnel = f0 * (1.0 - w.facing_away) + (1.0 - f0) * w.schlick;
                facing_away = w.facing_away;
                b_env = b_t + w.shift;
                k_env = w.k;
            }
            Frame t = bumped ? frame : Frame(vec3(1, 0, 0), vec3(0, 1, 0), 1.0);
            EnvFootprint f = reflection_footprint(p_world, v, -diff.dpdx, -diff.dpdy, n, dndx, dndy,
                                                  bumped ? b_env : vec2(0), t,
                                                  bumped ? fp_roughness_factor(k_env) : vec3(0), k_env);
            texel = env_lookup(f, mode, f.k.x + f.k.z);
            // Slopes facing away from the eye are shaded with the surface's own normal (§4).
            float cos_surface = dot(normalize(n), v_hat);
            float f_away = facing_away * fp_schlick_fresnel(f0_mean, cos_surface);
            float f_mean = channel_mean(fresnel);
            if (facing_away > 1e-3 && f_mean + f_away > 0.0) {
                EnvFootprint unbumped = reflection_footprint(p_world, v, -diff.dpdx, -diff.dpdy, n, dndx,
                                                             dndy, vec2(0), t, vec3(0), vec3(0));
                vec3 away = env_lookup(unbumped, mode, unbumped.k.x + unbumped.k.z);
                texel = (f_mean * texel + f_away * away) / (f_mean + f_away);
                fresnel += facing_away * fp_schlick_fresnel3(f0, cos_surface);
            }
        } else {
            texel = env_point_sample(local_direction(p_world,
                                                     2.0 * dot(n_hat, v_hat) * n_hat - v_hat));
        }
        color += material.weights.w * fresnel * texel;
    }
    use_scene_environment();
    return color;
}

// A ray that escapes: the environment filtered over the camera ray's own differentials (form (a)),
// or the background colour.
vec3 background(Ray ray, vec3 dddx, vec3 dddy) {
    vec3 origin = ray.origin + u_camera_position;
    use_environment_at(origin);
    if (env_layout == ENV_NONE) return u_background;
    if (u_mode == MODE_POINT) return env_point_sample(local_direction(origin, ray.direction));
    return env_lookup(ray_footprint(origin, ray.direction, dddx, dddy), u_mode, 0.0);
}
