// gpu/shaders/environment.glsl — environment maps filtered per pixel (envmap/, spec §2–3): the
// layouts' coordinates and Jacobians, the footprint K = D Dᵀ + κ² K3 and its anisotropic lookup.
//
// Layouts: a cube map (a samplerCube with seamless filtering, the hardware's own re-projection of
// a probe onto the face that owns its direction, spec §3.1); or map MAP_ENV, its faces as layers:
// a lat-long map (s repeating, t clamped) with its two polar caps (map MAP_CAPS, layer 0 = +Y,
// 1 = −Y), a sphere map, or a dual paraboloid (layer 0 the front, 1 the back). Taps of those that
// fall beyond a level's edge are read where their direction lies (envmap/env_sampling.h), where
// the hardware would clamp.
//
// The footprint K = D Dᵀ + κ² K3, the reflected direction's spreads (form (b)), the cube's face
// table and the cube's probes are the library's (footprint/environment.glsl, docs/method.md,
// "The environment footprint"); this file adds the other layouts, local maps' proxies, polar caps
// and EWA, and reads the scene's maps.

#include "footprint/environment.glsl"

const int ENV_NONE = -1;
const int ENV_CUBE = 0;  // envmap/env_layout.h's EnvLayout order
const int ENV_LATLONG = 1;
const int ENV_SPHERE = 2;
const int ENV_PARABOLOID = 3;

uniform int u_env_layout;
uniform mat3 u_env_rotation;   // A: world → map
uniform vec2 u_env_texel_scale;  // S = (W0, H0) of level 0 (a cube face's size for both)
uniform int u_env_caps;        // 1: the lat-long map has polar caps
uniform int u_env_proxy;       // a local map's proxy: 0 none (at infinity), 1 a box, 2 a sphere
uniform vec3 u_env_proxy_min, u_env_proxy_max;  // the box; a sphere: its centre, (radius, 0, 0)
uniform vec3 u_env_proxy_capture;               // c (world space)
uniform vec3 u_env_sh[9];      // the radiance's nine SH coefficients, world space (irradiance)
const int kMaxEnvLevels = 16;
uniform float u_env_prefilter[kMaxEnvLevels];  // each level's prefilter variance (level-0 texels²)
uniform ivec2 u_env_wrap;  // the map's wrap in s and t: 1 repeat, 0 clamp
uniform samplerCube u_env_cube;  // the lat-long map and its caps are u_maps[MAP_ENV], [MAP_CAPS]

// Cube maps besides the scene's, each on a unit of its own with its own rotation, size, proxy and
// irradiance (gpu_scene.h's CubeSlot): the local maps (local_environments, converted to cube maps
// where they are not), innermost first, then the dynamic environment maps
// (material.environment_probe, render/environment_probe.h) that the CPU rendered.
const int MAX_CUBE_SLOTS = 4;  // gpu_scene.h's kMaxCubeSlots
uniform samplerCube u_slot_cubes[MAX_CUBE_SLOTS];
uniform float u_slot_size[MAX_CUBE_SLOTS];  // texels along a face's edge
uniform mat3 u_slot_rotation[MAX_CUBE_SLOTS];
uniform int u_slot_proxy[MAX_CUBE_SLOTS];  // as u_env_proxy
uniform vec3 u_slot_proxy_min[MAX_CUBE_SLOTS], u_slot_proxy_max[MAX_CUBE_SLOTS];
uniform vec3 u_slot_proxy_capture[MAX_CUBE_SLOTS];
uniform vec3 u_slot_sh[9 * MAX_CUBE_SLOTS];
uniform int u_local_count;  // slots 0 … u_local_count − 1 hold the local maps

// The environment the lookups below read: the scene's or a slot's. The shading switches between
// them per point and per lookup.
int env_layout;
mat3 env_rotation;
vec2 env_texel_scale;
int env_caps;
int env_proxy;
vec3 env_proxy_min, env_proxy_max, env_proxy_capture;
int env_slot;  // −1: the scene's

void use_scene_environment() {
    env_layout = u_env_layout;
    env_rotation = u_env_rotation;
    env_texel_scale = u_env_texel_scale;
    env_caps = u_env_caps;
    env_proxy = u_env_proxy;
    env_proxy_min = u_env_proxy_min;
    env_proxy_max = u_env_proxy_max;
    env_proxy_capture = u_env_proxy_capture;
    env_slot = -1;
}

void use_slot(int k) {
    env_layout = ENV_CUBE;
    env_rotation = u_slot_rotation[k];
    env_texel_scale = vec2(u_slot_size[k]);
    env_caps = 0;
    env_proxy = u_slot_proxy[k];
    env_proxy_min = u_slot_proxy_min[k];
    env_proxy_max = u_slot_proxy_max[k];
    env_proxy_capture = u_slot_proxy_capture[k];
    env_slot = k;
}

// Whether p lies in slot k's proxy, its surface included (envmap/env_proxy.h's proxy_contains).
bool slot_contains(int k, vec3 p) {
    const float surface = 1e-4;
    vec3 lo = u_slot_proxy_min[k], hi = u_slot_proxy_max[k];
    if (u_slot_proxy[k] == 2) {
        float radius = hi.x * (1.0 + surface);
        return dot(p - lo, p - lo) <= radius * radius;
    }
    vec3 extent = hi - lo;
    float tolerance = surface * max(extent.x, max(extent.y, extent.z));
    return all(greaterThanEqual(p, lo - tolerance)) && all(lessThanEqual(p, hi + tolerance));
}

// The map that p sees: the innermost local map whose proxy contains it (the first: they are
// ordered), else the scene's (RenderScene::environment_at).
void use_environment_at(vec3 p) {
    for (int k = 0; k < u_local_count; ++k) {
        if (slot_contains(k, p)) {
            use_slot(k);
            return;
        }
    }
    use_scene_environment();
}

// The slot's cube: an array of samplers takes constant indices only, where pixels may differ.
#define SLOT_CASES(CALL) \
    switch (env_slot) {  \
        case 0: CALL(0);  \
        case 1: CALL(1);  \
        case 2: CALL(2);  \
        default: CALL(3); \
    }

vec4 env_cube_lod(vec3 direction, float lod) {
    if (env_slot < 0) return textureLod(u_env_cube, direction, lod);
#define SLOT_LOD(i) return textureLod(u_slot_cubes[i], direction, lod)
    SLOT_CASES(SLOT_LOD)
#undef SLOT_LOD
}

vec4 env_cube_grad(vec3 direction, vec3 d_dx, vec3 d_dy) {
    if (env_slot < 0) return textureGrad(u_env_cube, direction, d_dx, d_dy);
#define SLOT_GRAD(i) return textureGrad(u_slot_cubes[i], direction, d_dx, d_dy)
    SLOT_CASES(SLOT_GRAD)
#undef SLOT_GRAD
}

int env_cube_levels() {
    if (env_slot < 0) return textureQueryLevels(u_env_cube);
#define SLOT_LEVELS(i) return textureQueryLevels(u_slot_cubes[i])
    SLOT_CASES(SLOT_LEVELS)
#undef SLOT_LEVELS
}

// ---- Lat-long (§3.4): s = ½ + atan2(r_x, −r_z)/(2π), t = θ/π (y up).
FpMapPoint latlong_point(vec3 r) {
    float rho = length(r.xz), len = length(r);
    if (rho == 0.0) return FpMapPoint(0, vec2(0.5, r.y > 0.0 ? 0.0 : 1.0), vec3(0), vec3(0));
    vec2 st = vec2(0.5 + atan(r.x, -r.z) / TWO_PI, atan(rho, r.y) / PI);
    vec3 ds = vec3(-r.z, 0, r.x) / (TWO_PI * rho * rho);
    vec3 dt = -(vec3(0, 1, 0) - (r.y / (len * len)) * r) / (PI * rho);
    return FpMapPoint(0, st, ds, dt);
}

vec3 latlong_direction(vec2 st) {
    float phi = TWO_PI * (st.x - 0.5), theta = PI * st.y;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

// ---- Sphere map (§3.2), +Y up the image: (s, t) = ½(a + 1, 1 − b), (a, b) = (r_x, r_y)/m,
// m = √(2|r|(r_z + |r|)), written without cancellation on the far side; the rim direction −Z is
// singular (a zero Jacobian).
FpMapPoint sphere_point(vec3 r) {
    float p = length(r), h = length(r.xy), m, c;
    if (r.z >= 0.0) {
        float w = r.z + p;
        m = sqrt(2.0 * p * w);
        c = sqrt(w / (2.0 * p));
    } else {
        m = h * sqrt(2.0 * p / (p - r.z));
        c = h / sqrt(2.0 * p * (p - r.z));
    }
    if (m == 0.0) return FpMapPoint(0, vec2(1.0, 0.5), vec3(0), vec3(0));
    float a = clamp(r.x / m, -1.0, 1.0), b = clamp(r.y / m, -1.0, 1.0);
    vec3 grad_m = vec3(a, b, c) + (c / p) * r;
    float k = 0.5 / m;
    return FpMapPoint(0, 0.5 * vec2(a + 1.0, 1.0 - b), k * (vec3(1, 0, 0) - a * grad_m),
                    -k * (vec3(0, 1, 0) - b * grad_m));
}

// Beyond the rim (ρ > 1) the map folds back through it: ρ → 2 − ρ, the azimuth + π.
vec3 sphere_direction(vec2 st) {
    float a = 2.0 * st.x - 1.0, b = 1.0 - 2.0 * st.y;
    float rho = length(vec2(a, b));
    if (!(rho < 2.0)) return vec3(0, 0, -1);
    if (rho > 1.0) {
        float k = -(2.0 - rho) / rho;
        a *= k;
        b *= k;
        rho = 2.0 - rho;
    }
    float nz = sqrt(max(0.0, (1.0 - rho) * (1.0 + rho)));
    return vec3(2.0 * a * nz, 2.0 * b * nz, 1.0 - 2.0 * rho * rho);
}

// ---- Dual paraboloid (§3.3): face 0 for r_z ≥ 0, (x, y) = (r_x, r_y)/(|r| + |r_z|).
FpMapPoint paraboloid_point(vec3 r) {
    float pr = length(r), sign = r.z >= 0.0 ? 1.0 : -1.0;
    float delta = pr + abs(r.z);
    float x = r.x / delta, y = r.y / delta;
    vec3 g = r / pr + vec3(0, 0, sign);
    float k = 0.5 / delta;
    return FpMapPoint(r.z >= 0.0 ? 0 : 1, 0.5 * vec2(x + 1.0, 1.0 - y),
                    k * (vec3(1, 0, 0) - x * g), -k * (vec3(0, 1, 0) - y * g));
}

// Beyond the disk (x² + y² > 1): the other hemisphere.
vec3 paraboloid_direction(int face, vec2 st) {
    float x = 2.0 * st.x - 1.0, y = 1.0 - 2.0 * st.y, sign = face == 0 ? 1.0 : -1.0;
    float k = x * x + y * y;
    if (isinf(k)) return vec3(0, 0, -sign);
    return vec3(2.0 * x, 2.0 * y, sign * (1.0 - k)) / (1.0 + k);
}

FpMapPoint env_point(vec3 r) {
    switch (env_layout) {
        case ENV_CUBE: return fp_cube_point(r);
        case ENV_SPHERE: return sphere_point(r);
        case ENV_PARABOLOID: return paraboloid_point(r);
        default: return latlong_point(r);
    }
}

vec3 env_direction(int face, vec2 st) {
    switch (env_layout) {
        case ENV_CUBE: return fp_cube_direction(face, st);
        case ENV_SPHERE: return sphere_direction(st);
        case ENV_PARABOLOID: return paraboloid_direction(face, st);
        default: return latlong_direction(st);
    }
}

// G x = S J_P x: the map motion, in level-0 texels, of a change x of the (map-space) direction.
vec2 map_motion(FpMapPoint p, vec3 x) {
    return fp_map_motion(p, env_texel_scale, x);
}

// ---- A local map's proxy (envmap/env_proxy.h): the direction from the capture point to where
// a ray leaves the box or sphere, and the footprint's spreads moved with it.

struct ProxyStep {
    vec3 direction;  // d = q − c
    vec3 r_hat, m;   // the ray's unit direction, the proxy's normal at q
    float along;     // t/|r|
};

bool proxy_step(vec3 p, vec3 r, out ProxyStep s) {
    float length_r = length(r);
    if (env_proxy == 0 || !(length_r > 0.0) || !fp_is_finite(length_r)) return false;
    vec3 r_hat = r / length_r;
    float t;
    vec3 m = vec3(0);
    if (env_proxy == 1) {  // the slabs' far crossing
        float t_near = -1e30, t_far = 1e30;
        int axis = -1;
        for (int k = 0; k < 3; ++k) {
            if (r_hat[k] == 0.0) {
                if (p[k] < env_proxy_min[k] || p[k] > env_proxy_max[k]) return false;
                continue;
            }
            float t0 = (env_proxy_min[k] - p[k]) / r_hat[k];
            float t1 = (env_proxy_max[k] - p[k]) / r_hat[k];
            t_near = max(t_near, min(t0, t1));
            if (max(t0, t1) < t_far) {
                t_far = max(t0, t1);
                axis = k;
            }
        }
        if (axis < 0 || !(t_far > 0.0) || t_near > t_far) return false;
        t = t_far;
        m[axis] = 1.0;
    } else {
        vec3 o = p - env_proxy_min;
        float radius = env_proxy_max.x;
        float b = dot(o, r_hat), disc = b * b - (dot(o, o) - radius * radius);
        if (!(disc >= 0.0)) return false;
        t = -b + sqrt(disc);
        if (!(t > 0.0)) return false;
        m = (o + t * r_hat) / radius;
    }
    if (!(abs(dot(m, r_hat)) > 1e-4)) return false;
    s = ProxyStep(p + t * r_hat - env_proxy_capture, r_hat, m, t / length_r);
    return dot(s.direction, s.direction) > 0.0;
}

// ∂d = P ∂p + (t/|r|) P ∂r, P = I − r̂ mᵀ/(m·r̂).
vec3 proxy_move(ProxyStep s, vec3 dp, vec3 dr) {
    vec3 x = dp + s.along * dr;
    return x - (dot(s.m, x) / dot(s.m, s.r_hat)) * s.r_hat;
}

vec3 local_direction(vec3 p, vec3 r) {
    ProxyStep s;
    return proxy_step(p, r, s) ? s.direction : r;
}

// ---- The footprint (envmap/env_footprint.h).
struct EnvFootprint {
    vec3 map_direction;  // A v_r
    FpMapPoint point;
    vec2 d_dx, d_dy;  // D's columns (curvature and aperture), level-0 texels per pixel
    vec3 k;           // K = D Dᵀ + κ² K3
    vec3 map_dr_dx, map_dr_dy, map_rough1, map_rough2;  // A ∂v_r/∂x, A ∂v_r/∂y, κ A (A_n E B)
    bool fallback;    // isotropic (a pole, non-finite input)
};

// The largest singular value of [a b] with both columns projected onto the plane ⟂ r̂.
float largest_tangent_singular_value(vec3 r, vec3 a, vec3 b) {
    vec3 r_hat = normalize(r);
    a -= dot(a, r_hat) * r_hat;
    b -= dot(b, r_hat) * r_hat;
    return fp_ellipse_of(vec3(dot(a, a), dot(a, b), dot(b, b))).l1;
}

void set_isotropic(inout EnvFootprint f, float tp) {
    if (!fp_is_finite(tp)) tp = 0.0;
    f.d_dx = vec2(tp, 0);
    f.d_dy = vec2(0, tp);
    f.k = vec3(tp * tp, 0, tp * tp);
    f.fallback = true;
}

// K for a direction r with spread ∂r/∂x, ∂r/∂y and the roughness columns rough1, rough2 (zero for
// form (a)): D = G [∂r/∂x, ∂r/∂y], K3 = (G rough1)(G rough1)ᵀ + (G rough2)(G rough2)ᵀ. Towards a
// lat-long pole (where the footprint, to 2σ, reaches it) the footprint is isotropic with
// T_p = (H0/π)·θ_fp (§3.4); at the sphere map's singular rim direction, T_p = (W0/4)·θ_fp (§3.2).
EnvFootprint footprint_of_spread(vec3 r, vec3 dr_dx, vec3 dr_dy, vec3 rough1, vec3 rough2) {
    EnvFootprint f;
    f.fallback = false;
    f.map_direction = env_rotation * r;
    f.point = env_point(f.map_direction);
    f.map_dr_dx = env_rotation * dr_dx;
    f.map_dr_dy = env_rotation * dr_dy;
    f.map_rough1 = u_kappa * (env_rotation * rough1);
    f.map_rough2 = u_kappa * (env_rotation * rough2);
    if (env_layout == ENV_SPHERE && f.point.ds == vec3(0) && f.point.dt == vec3(0)) {
        float theta = (largest_tangent_singular_value(r, dr_dx, dr_dy) +
                       u_kappa * largest_tangent_singular_value(r, rough1, rough2)) / length(r);
        set_isotropic(f, 0.25 * env_texel_scale.x * theta);
        return f;
    }
    if (env_layout == ENV_LATLONG) {
        vec3 m = f.map_direction;
        float spread = sqrt(dot(dr_dx, dr_dx) + dot(dr_dy, dr_dy)) +
                       abs(u_kappa) * sqrt(dot(rough1, rough1) + dot(rough2, rough2));
        float rho = length(m.xz);
        if (rho == 0.0 || rho < spread) {
            float theta = (largest_tangent_singular_value(r, dr_dx, dr_dy) +
                           u_kappa * largest_tangent_singular_value(r, rough1, rough2)) / length(r);
            if (rho == 0.0 || rho < sin(min(theta, 0.5 * PI)) * length(m)) {
                set_isotropic(f, env_texel_scale.y / PI * theta);
                return f;
            }
        }
    }
    f.d_dx = map_motion(f.point, f.map_dr_dx);
    f.d_dy = map_motion(f.point, f.map_dr_dy);
    f.k = fp_environment_footprint(f.d_dx, f.d_dy, map_motion(f.point, env_rotation * rough1),
                                   map_motion(f.point, env_rotation * rough2), u_kappa);
    return f;
}

// Form (a), for rays that escape from p: the direction r and its ray differentials (a local
// map's moved onto its direction; the pinhole's origin does not move).
EnvFootprint ray_footprint(vec3 p, vec3 r, vec3 dr_dx, vec3 dr_dy) {
    ProxyStep s;
    if (proxy_step(p, r, s)) {
        r = s.direction;
        dr_dx = proxy_move(s, vec3(0), dr_dx);
        dr_dy = proxy_move(s, vec3(0), dr_dy);
    }
    EnvFootprint f = footprint_of_spread(r, dr_dx, dr_dy, vec3(0), vec3(0));
    if (!fp_is_finite(f.k.x + f.k.y + f.k.z)) {
        f.d_dx = f.d_dy = vec2(0);
        f.k = vec3(0);
        f.map_dr_dx = f.map_dr_dy = vec3(0);
    }
    return f;
}

// Form (b), Schilling's (spec §2.2–2.6): v surface → eye, n the facing normal and its
// derivatives, b the mean slope in the frame T = (t1, t2), B = (d1, d2, d3) the roughness factor,
// K_b its covariance; p the surface point (world space), for a local map's proxy.
EnvFootprint reflection_footprint(vec3 p, vec3 v, vec3 dv_dx, vec3 dv_dy, vec3 n, vec3 dn_dx,
                                  vec3 dn_dy, vec2 b, Frame t, vec3 rough, vec3 k_b) {
    FpReflection r = fp_reflection(v, dv_dx, dv_dy, n, dn_dx, dn_dy, b, t.t1, t.t2, rough);
    vec3 reflected = r.r, dvr_dx = r.dr_dx, dvr_dy = r.dr_dy, rough1 = r.rough1, rough2 = r.rough2;
    ProxyStep s;
    if (proxy_step(p, reflected, s)) {  // a local map: ∂d = P ∂p + (t/|r|) P ∂r, ∂p = −∂v
        reflected = s.direction;
        dvr_dx = proxy_move(s, -dv_dx, dvr_dx);
        dvr_dy = proxy_move(s, -dv_dy, dvr_dy);
        rough1 = proxy_move(s, vec3(0), rough1);
        rough2 = proxy_move(s, vec3(0), rough2);
    }
    EnvFootprint f = footprint_of_spread(reflected, dvr_dx, dvr_dy, rough1, rough2);
    if (!f.fallback && !fp_is_finite(f.k.x + f.k.y + f.k.z + f.d_dx.x + f.d_dx.y + f.d_dy.x + f.d_dy.y)) {
        // Non-finite D or K (docs/method.md, "Degenerate cases"): isotropic from the roughness
        // alone, T_p = max(1, κ·‖G A_n E‖·l1).
        float n_len = length(n);
        FpEllipse gae = fp_ellipse_of(fp_footprint_matrix(
            map_motion(f.point, env_rotation * fp_reflection_normal_spread(r, n_len * t.t1)),
            map_motion(f.point, env_rotation * fp_reflection_normal_spread(r, n_len * t.t2))));
        float tp = u_kappa * gae.l1 * fp_ellipse_of(k_b).l1;  // l1 = √λ_max(K_b)
        set_isotropic(f, fp_is_finite(tp) ? max(1.0, tp) : 1.0);
        f.map_dr_dx = f.map_dr_dy = f.map_rough1 = f.map_rough2 = vec3(0);
    }
    return f;
}

// ---- Lookups.

// One trilinear probe of the cube map at a map-space direction.
vec4 env_probe_direction(vec3 direction, float lod) {
    return env_cube_lod(direction, lod);
}

ivec2 env_level_size(int level) {
    return max(ivec2(map_size(MAP_ENV)) >> level, ivec2(1));
}

// Texel i of a level of face `face` of MAP_ENV, where i may lie beyond the level's edge
// (envmap/env_sampling.h's env_texel): over a lat-long pole, row −1 − k is row k half a turn
// around (x + W/2) and the seam wraps; beyond a sphere or paraboloid image's edge, the texel its
// centre's direction lands in.
vec4 env_texel(int face, ivec2 i, int level) {
    ivec2 size = env_level_size(level);
    if (env_layout == ENV_LATLONG) {
        if (i.y < 0 || i.y >= size.y) {
            i.y = i.y < 0 ? -1 - i.y : 2 * size.y - 1 - i.y;
            i.x += size.x / 2;
        }
        i.x = ((i.x % size.x) + size.x) % size.x;
    } else if (any(lessThan(i, ivec2(0))) || any(greaterThanEqual(i, size))) {
        FpMapPoint p = env_point(env_direction(face, (vec2(i) + 0.5) / vec2(size)));
        face = p.face;
        i = ivec2(p.st * vec2(size));
    }
    return texelFetch(u_maps[MAP_ENV], ivec3(clamp(i, ivec2(0), size - 1), face), level);
}

// A bilinear sample of one level, its taps read by env_texel().
vec4 env_level_beyond_edge(int face, vec2 st, int level) {
    vec2 x = st * vec2(env_level_size(level)) - 0.5;
    ivec2 i0 = ivec2(floor(x));
    vec2 f = x - vec2(i0);
    vec4 taps[4];
    for (int k = 0; k < 4; ++k) taps[k] = env_texel(face, i0 + ivec2(k & 1, k >> 1), level);
    return mix(mix(taps[0], taps[1], f.x), mix(taps[2], taps[3], f.x), f.y);
}

// Whether a bilinear sample at st on a level has taps beyond its edges (the lat-long map's s
// wraps in the sampler: only t counts there).
bool taps_beyond_edge(vec2 st, int level) {
    ivec2 size = env_level_size(level);
    vec2 x = st * vec2(size) - 0.5;
    bool t_out = x.y < 0.0 || x.y > float(size.y - 1);
    return env_layout == ENV_LATLONG ? t_out : t_out || x.x < 0.0 || x.x > float(size.x - 1);
}

// One trilinear probe of MAP_ENV: the hardware's, or, where its taps reach beyond an edge, the
// same two levels read by env_level_beyond_edge().
vec4 env_probe_2d(int face, vec2 st, float lod) {
    int max_level = map_max_level(MAP_ENV);
    int l0 = min(int(lod), max_level);
    float w = l0 < max_level ? lod - float(l0) : 0.0;
    if (!taps_beyond_edge(st, l0) && !(w > 0.0 && taps_beyond_edge(st, l0 + 1)))
        return sample_lod(MAP_ENV, vec3(st, face), lod);
    vec4 fine = env_level_beyond_edge(face, st, l0);
    return w > 0.0 ? mix(fine, env_level_beyond_edge(face, st, l0 + 1), w) : fine;
}

// A point sample (level-0 bilinear) in world direction r: the `point` mode.
vec3 env_point_sample(vec3 r) {
    vec3 m = env_rotation * r;
    if (env_layout == ENV_CUBE) return env_probe_direction(m, 0.0).rgb;
    FpMapPoint p = env_point(m);
    return env_probe_2d(p.face, p.st, 0.0).rgb;
}

// The GPU's own anisotropic filter over the footprint's curvature term (no roughness).
vec3 env_hardware(EnvFootprint f) {
    if (env_layout == ENV_CUBE)  // trilinear: cube maps get no anisotropy on most hardware
        return env_cube_grad(f.map_direction, f.map_dr_dx, f.map_dr_dy).rgb;
    return hardware_lookup(MAP_ENV, f.point.face, 1, f.point.st, f.d_dx, f.d_dy).a.rgb;
}

// ---- Polar caps (envmap/polar_caps.h): a footprint centred within 30° of a pole whose probes
// stay on the cap's face is filtered on the cap, K from the map-space direction spreads.
struct CapFootprint {
    bool valid;
    int layer;  // 0: +Y, 1: −Y
    vec2 st;
    vec3 k;
};

CapFootprint cap_footprint(EnvFootprint f, float latlong_trace) {
    CapFootprint c;
    vec3 r = f.map_direction;
    c.valid = false;
    if (env_caps == 0 || !(abs(r.y) >= 0.8660254 * length(r))) return c;
    c.layer = r.y > 0.0 ? 0 : 1;
    FpMapPoint p = fp_cube_point_on(2 + c.layer, r);
    float n = map_size(MAP_CAPS).x;
    vec2 a = n * vec2(dot(p.ds, f.map_dr_dx), dot(p.dt, f.map_dr_dx));
    vec2 b = n * vec2(dot(p.ds, f.map_dr_dy), dot(p.dt, f.map_dr_dy));
    vec2 c1 = n * vec2(dot(p.ds, f.map_rough1), dot(p.dt, f.map_rough1));
    vec2 c2 = n * vec2(dot(p.ds, f.map_rough2), dot(p.dt, f.map_rough2));
    c.k = fp_footprint_matrix(a, b) + fp_footprint_matrix(c1, c2);
    c.st = p.st;
    float reach = (2.0 * sqrt(c.k.x + c.k.z) + 1.0) / n;
    bool on_face = p.st.x - reach >= 0.0 && p.st.x + reach <= 1.0 && p.st.y - reach >= 0.0 &&
                   p.st.y + reach <= 1.0;
    c.valid = fp_is_finite(c.k.x + c.k.y + c.k.z) && on_face &&
              !(c.k.x + c.k.z == 0.0 && latlong_trace > 0.0);
    return c;
}

vec3 cap_lookup(CapFootprint c, int mode) {
    int max_level = map_max_level(MAP_CAPS);
    FpEllipse e = fp_ellipse_of(c.k);
    if (mode == MODE_TRILINEAR)
        return probe(MAP_CAPS, c.layer, 1, c.st, clamp(log2(max(e.l1, 1e-30)), 0.0, float(max_level)))
            .a.rgb;
    return assemble(MAP_CAPS, c.layer, 1, c.st, fp_plan_probes(e, u_max_probes, max_level)).a.rgb;
}

// Probe placement on the sphere for the curved layouts (environment_map.cpp's TangentProbes): an
// offset o in level-0 texels is taken back to the tangent plane at r̂ through J_t⁻¹ and placed at
// the direction r̂ + J_t⁻¹ o, so that the probes follow the great circle through r̂.
struct TangentProbes {
    bool valid;
    vec3 centre, e1, e2;
    mat2 inv;  // J_t⁻¹, radians per texel
};

TangentProbes tangent_probes(vec3 direction) {
    TangentProbes t;
    t.centre = normalize(direction);
    t.e1 = normalize(cross(t.centre, abs(t.centre.x) < 0.6 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    t.e2 = cross(t.centre, t.e1);
    FpMapPoint p = env_point(t.centre);
    float j11 = env_texel_scale.x * dot(p.ds, t.e1), j12 = env_texel_scale.x * dot(p.ds, t.e2);
    float j21 = env_texel_scale.y * dot(p.dt, t.e1), j22 = env_texel_scale.y * dot(p.dt, t.e2);
    float det = j11 * j22 - j12 * j21;
    t.valid = abs(det) > 1e-12 * (j11 * j11 + j12 * j12 + j21 * j21 + j22 * j22) && fp_is_finite(det);
    t.inv = t.valid ? mat2(j22, -j21, -j12, j11) / det : mat2(0);  // column-major
    return t;
}

FpMapPoint tangent_place(TangentProbes t, vec2 offset) {
    vec2 ab = t.inv * offset;
    return env_point(t.centre + ab.x * t.e1 + ab.y * t.e2);
}

// How much the layout stretches a round footprint at the probes' centre: the anisotropy (≥ 1) of
// the ellipse of J_t⁻¹'s columns (TangentProbes::distortion()).
float tangent_distortion(TangentProbes t) {
    FpEllipse e = fp_ellipse_of(fp_footprint_matrix(t.inv[0], t.inv[1]));
    float ratio = e.l1 / e.l2;
    return fp_is_finite(ratio) ? max(ratio, 1.0) : 1.0;
}

// Where a probe centre (s, t) of `face` lands that was not placed on the sphere: itself on the
// face's valid region, else the face and (s, t) of its direction (environment_map.cpp's
// place_probe): over a lat-long pole, back through the sphere map's rim, onto the other
// paraboloid hemisphere.
FpMapPoint place_probe(int face, vec2 st) {
    vec2 ab = 2.0 * st - 1.0;
    bool outside = env_layout == ENV_LATLONG ? st.y < 0.0 || st.y > 1.0 : dot(ab, ab) > 1.0;
    return outside ? env_point(env_direction(face, st)) : FpMapPoint(face, st, vec3(0), vec3(0));
}

// How the probes of a line are placed. Cube: on the centre face's plane along r1, each handed to
// the hardware as a direction, which puts it on the face that owns it. The curved layouts
// (lat-long, sphere, paraboloid): on the sphere (tangent_place()), and on the lat-long map its ends
// placed exactly and the probes between on the quadratic through them and the centre
// (envmap/latlong_path.h), any that would cross a pole exactly.
struct ProbeLine {
    TangentProbes tangent;
    bool path;  // the lat-long quadratic c + u (h + u q), u = −1 … 1
    vec2 h, q;
};

ProbeLine probe_line(EnvFootprint f, FpPlan plan) {
    ProbeLine line;
    line.tangent.valid = false;
    line.path = false;
    line.h = line.q = vec2(0);
    if (env_layout == ENV_CUBE) return line;
    line.tangent = tangent_probes(f.map_direction);
    line.path = env_layout == ENV_LATLONG && line.tangent.valid && plan.count > 2;
    if (line.path) {
        vec2 c = f.point.st;
        vec2 a = tangent_place(line.tangent, fp_probe_offset(plan, plan.count - 1)).st - c;
        vec2 b = tangent_place(line.tangent, -fp_probe_offset(plan, plan.count - 1)).st - c;
        a.x -= round(a.x);  // unwrapped across the seam
        b.x -= round(b.x);
        line.h = 0.5 * (a - b);
        line.q = 0.5 * (a + b);
    }
    return line;
}

// Probe i of a line, its centre on_plane = c + o_i / S on the centre face's plane, at the plan's
// lod (the centre face's).
vec4 line_probe(EnvFootprint f, FpPlan plan, ProbeLine line, int i, vec2 on_plane) {
    if (env_layout == ENV_CUBE)
        return env_probe_direction(fp_cube_direction(f.point.face, on_plane), plan.lod);
    float half_count = 0.5 * float(plan.count - 1), u = (float(i) - half_count) / half_count;
    vec2 on_path = f.point.st + u * (line.h + u * line.q);
    FpMapPoint p;
    if (line.path && on_path.y >= 0.0 && on_path.y <= 1.0)
        p = FpMapPoint(0, on_path, vec3(0), vec3(0));
    else if (line.tangent.valid)
        p = tangent_place(line.tangent, fp_probe_offset(plan, i));
    else
        p = place_probe(f.point.face, on_plane);
    return env_probe_2d(p.face, p.st, plan.lod);
}

// C = Σ w_i probe_i / Σ w_i over the line (footprint/texture.glsl's FP_ASSEMBLE).
vec3 env_line(EnvFootprint f, FpPlan plan) {
    ProbeLine line = probe_line(f, plan);
    vec3 sum;
#define LINE_PROBE(i, on_plane, lod) line_probe(f, plan, line, i, on_plane).rgb
    FP_ASSEMBLE(vec3, sum, plan, f.point.st, env_texel_scale, LINE_PROBE)
#undef LINE_PROBE
    return sum;
}

// ---- EWA on the lat-long map (texture/ewa.h's filter_ewa()): where footprint assembly would need
// more probes than its budget. A truncated Gaussian of covariance K/4 less the level's prefilter,
// summed texel by texel over the exact span of the truncation ellipse, on the two levels around
// log2(λ2) − 1.5, the anisotropy clamped to 64 by growing the minor axis
// (env_lookup_general.h's kEwaBeyondProbesAnisotropy).
const float kEwaBeyondProbesAnisotropy = 64.0;

int ewa_wrap(int i, int n, int repeat) {
    if (i >= 0 && i < n) return i;
    return repeat == 1 ? ((i % n) + n) % n : clamp(i, 0, n - 1);
}

vec3 env_ewa_level(int face, int level, vec2 st, FpEllipse e) {
    // The level's size as the CPU's pyramid halves it (textureSize() on this array gave level 0's).
    vec2 level0 = map_size(MAP_ENV);
    ivec2 size = max(ivec2(1), ivec2(level0) >> level);
    float tx = level0.x / float(size.x), ty = level0.y / float(size.y);
    float shrink = u_env_prefilter[min(level, kMaxEnvLevels - 1)] + 1.0 / 12.0;
    float floor_variance = 0.36 * max(tx, ty) * max(tx, ty);  // (kEwaMinSigma·T)²
    float major = max(0.25 * e.l1 * e.l1 - shrink, floor_variance);
    float minor = max(0.25 * e.l2 * e.l2 - shrink, floor_variance);
    vec2 a = e.r1, b = vec2(-e.r1.y, e.r1.x);
    vec3 sigma = vec3(major * a.x * a.x + minor * b.x * b.x, major * a.x * a.y + minor * b.x * b.y,
                      major * a.y * a.y + minor * b.y * b.y);
    // In this level's texels, enlarged so that the truncated Gaussian keeps covariance Σ.
    float c = exp(-4.5);
    float keep = (2.0 - 11.0 * c - c * 81.0 / 4.0) / (2.0 * ((1.0 - c) - 4.5 * c));
    sigma = vec3(sigma.x / (tx * tx), sigma.y / (tx * ty), sigma.z / (ty * ty)) / keep;
    float det = sigma.x * sigma.z - sigma.y * sigma.y;
    vec3 q = vec3(sigma.z, -sigma.y, sigma.x) / det;  // Σ'⁻¹
    float cx = st.x * float(size.x) - 0.5, cy = st.y * float(size.y) - 0.5;
    float half_h = 3.0 * sqrt(sigma.z);
    vec3 sum = vec3(0);
    float weights = 0.0;
    for (int y = int(ceil(cy - half_h)); y <= int(floor(cy + half_h)); ++y) {
        float dy = float(y) - cy;
        float by = q.y * dy;
        float disc = by * by - q.x * (q.z * dy * dy - 9.0);
        if (disc <= 0.0) continue;
        float root = sqrt(disc);
        int wy = ewa_wrap(y, size.y, u_env_wrap.y);
        for (int x = int(ceil(cx + (-by - root) / q.x)); x <= int(floor(cx + (-by + root) / q.x));
             ++x) {
            float dx = float(x) - cx;
            float r2 = q.x * dx * dx + 2.0 * q.y * dx * dy + q.z * dy * dy;
            if (r2 >= 9.0) continue;
            float w = exp(-0.5 * r2) - c;
            sum += w * texelFetch(u_maps[MAP_ENV], ivec3(ewa_wrap(x, size.x, u_env_wrap.x), wy, face),
                                  level).rgb;
            weights += w;
        }
    }
    if (!(weights > 0.0)) return sample_lod(MAP_ENV, vec3(st, face), float(level)).rgb;
    return sum / weights;
}

vec3 env_ewa(int face, vec2 st, FpEllipse e, int max_level) {
    if (e.l1 <= 1.0) return sample_lod(MAP_ENV, vec3(st, face), 0.0).rgb;
    if (e.l2 * kEwaBeyondProbesAnisotropy < e.l1) e.l2 = e.l1 / kEwaBeyondProbesAnisotropy;
    float lod = clamp(log2(max(e.l2, 1e-30)) - 1.5, 0.0, float(max_level));
    int l0 = int(lod);
    float w = l0 < max_level ? lod - float(l0) : 0.0;
    vec3 out_c = vec3(0);
    if (w < 1.0) out_c += (1.0 - w) * env_ewa_level(face, l0, st, e);
    if (w > 0.0) out_c += w * env_ewa_level(face, l0 + 1, st, e);
    return out_c;
}

// The environment filtered over footprint f in `mode` (trilinear, fa, fa-rough, hw-aniso);
// latlong_trace: tr K of a form (b) footprint (0 for form (a)), which decides whether a cap takes a
// fallback footprint.
vec3 env_lookup(EnvFootprint f, int mode, float latlong_trace) {
    if (mode == MODE_HW_ANISO) return env_hardware(f);
    if (env_layout == ENV_LATLONG) {
        CapFootprint cap = cap_footprint(f, latlong_trace);
        if (cap.valid) return cap_lookup(cap, mode);
    }
    int max_level = env_layout == ENV_CUBE ? env_cube_levels() - 1
                                             : map_max_level(MAP_ENV);
    FpEllipse e = fp_is_finite(f.k.x + f.k.y + f.k.z) ? fp_ellipse_of(f.k) : FpEllipse(0.0, 0.0, vec2(1, 0));
    if (env_layout == ENV_SPHERE) {
        // §3.2: towards the singular rim the anisotropy grows without bound; λ1 ≤ W/2.
        e.l1 = min(e.l1, 0.5 * env_texel_scale.x);
        e.l2 = min(e.l2, e.l1);
    }
    float limit = 4.0 * max(env_texel_scale.x, env_texel_scale.y);
    e.l1 = min(e.l1, limit);
    e.l2 = min(e.l2, limit);
    FpPlan plan;
    if (mode == MODE_TRILINEAR) {
        plan = FpPlan(1, vec2(0), clamp(log2(max(e.l1, 1e-30)), 0.0, float(max_level)), 0.0, e.l1);
    } else {
        // Towards the sphere map's rim the map adds up to 67:1 of its own anisotropy: a line
        // there may take N_max × its distortion (environment_map.cpp's sphere_probe_limit).
        int max_probes = u_max_probes;
        if (env_layout == ENV_SPHERE) {
            TangentProbes t = tangent_probes(f.map_direction);
            if (t.valid)
                max_probes = int(min(ceil(float(max(max_probes, 1)) * tangent_distortion(t)),
                                     float(FP_MAX_PROBE_COUNT)));
        }
        plan = fp_plan_probes(e, max_probes, max_level);
        // Beyond the probe budget on a lat-long map: EWA (LookupOptions::ewa_beyond_probes, the
        // fa modes' setting); the other layouts keep the raised level.
        if (env_layout == ENV_LATLONG && fp_exceeds_probe_budget(plan, e))
            return env_ewa(f.point.face, f.point.st, e, max_level);
    }
    // Trilinear filters the centre face alone, its taps wrapped or clamped as the pyramid's
    // (environment_map.cpp's general_lookup() → texture_lookup()).
    if (mode == MODE_TRILINEAR && env_layout != ENV_CUBE)
        return sample_lod(MAP_ENV, vec3(f.point.st, f.point.face), plan.lod).rgb;
    if (plan.count == 1)
        return env_layout == ENV_CUBE ? env_probe_direction(f.map_direction, plan.lod).rgb
                                        : env_probe_2d(f.point.face, f.point.st, plan.lod).rgb;
    return env_line(f, plan);
}

// ---- Irradiance (envmap/irradiance.h): E(n) from the radiance's nine SH coefficients, its bands
// scaled by the clamped cosine's Â_l and by g_1, g_2 of slopes of mean variance σ² about n.

// √π z e^{z²} erfc(z): Abramowitz & Stegun 7.1.26 up to z = 2, Laplace's continued fraction beyond.
float root_pi_z_erfcx(float z) {
    if (z <= 2.0) {
        float t = 1.0 / (1.0 + 0.3275911 * z);
        float p = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 +
                                                               t * (-1.453152027 + t * 1.061405429))));
        return sqrt(PI) * z * p;
    }
    float d = z;
    for (int k = 8; k >= 1; --k) d = z + 0.5 * float(k) / d;
    return z / d;
}

// x e^x E₁(x): Abramowitz & Stegun 5.1.53 (x ≤ 1) and 5.1.56.
float x_ex_e1(float x) {
    if (x <= 1.0) {
        float e1 = -log(x) - 0.57721566 +
                   x * (0.99999193 + x * (-0.24991055 + x * (0.05519968 +
                                                             x * (-0.00976004 + x * 0.00107857))));
        return x * exp(x) * e1;
    }
    return (x * x + 2.334733 * x + 0.250621) / (x * x + 3.330657 * x + 1.681534);
}

vec3 env_irradiance(vec3 n, float slope_variance) {
    float g1 = 1.0, g2 = 1.0;
    if (slope_variance > 0.0) {
        float x = 1.0 / (2.0 * slope_variance);
        g1 = root_pi_z_erfcx(sqrt(x));
        g2 = (3.0 * x_ex_e1(x) - 1.0) / 2.0;
    }
    float a0 = PI, a1 = 2.0 * PI / 3.0 * g1, a2 = PI / 4.0 * g2;
    vec3 sh[9];
    for (int i = 0; i < 9; ++i) sh[i] = env_slot < 0 ? u_env_sh[i] : u_slot_sh[9 * env_slot + i];
    vec3 e = a0 * 0.282095 * sh[0] +
             a1 * 0.488603 * (n.y * sh[1] + n.z * sh[2] + n.x * sh[3]) +
             a2 * (1.092548 * (n.x * n.y * sh[4] + n.y * n.z * sh[5] + n.x * n.z * sh[7]) +
                   0.315392 * (3.0 * n.z * n.z - 1.0) * sh[6] +
                   0.546274 * (n.x * n.x - n.y * n.y) * sh[8]);
    return max(e, vec3(0));
}
