// footprint/environment.glsl — the environment footprint K = D Dᵀ + κ² K3 and the cube-map lookup
// by probes (docs/method.md, "The environment footprint", "Environment layouts" and "Filtering on
// the sphere"; envmap/env_footprint.h, envmap/environment_map.h).
//
// A reflecting point seen through a pixel reads the environment in the reflected direction v_r.
// D Dᵀ is how the pixel's aperture and the surface's curvature move v_r per pixel step, K3 how far
// the sub-pixel bump slopes (K_b = B Bᵀ) scatter it, both as a footprint on the map in level-0
// texels: G = S·J_P(v_r), S the texels per unit of (s, t), J_P = ∂(s, t)/∂r the layout's Jacobian.
// Directions are in the map's space (an environment rotation applied), of any nonzero length, and
// their derivatives those of the same vectors.
#ifndef FOOTPRINT_GLSL_ENVIRONMENT
#define FOOTPRINT_GLSL_ENVIRONMENT

#include "footprint/common.glsl"
#include "footprint/texture.glsl"

// Where a direction lands on a map: its face, (s, t) there and the Jacobian J_P = ∂(s,t)/∂r as its
// rows ds = ∂s/∂r, dt = ∂t/∂r.
struct FpMapPoint {
    int face;
    vec2 st;
    vec3 ds, dt;
};

// ---- The cube (docs/method.md, "Environment layouts": OpenGL's face table, +X −X +Y −Y +Z −Z):
// s = ½(sc/|ma| + 1), t = ½(tc/|ma| + 1), t = 0 the face image's top row, as samplerCube reads it.

// Face f's major axis and the directions of increasing s and t on it.
void fp_cube_face_axes(int face, out vec3 major, out vec3 gs, out vec3 gt) {
    if (face == 0) {
        major = vec3(1, 0, 0); gs = vec3(0, 0, -1); gt = vec3(0, -1, 0);
    } else if (face == 1) {
        major = vec3(-1, 0, 0); gs = vec3(0, 0, 1); gt = vec3(0, -1, 0);
    } else if (face == 2) {
        major = vec3(0, 1, 0); gs = vec3(1, 0, 0); gt = vec3(0, 0, 1);
    } else if (face == 3) {
        major = vec3(0, -1, 0); gs = vec3(1, 0, 0); gt = vec3(0, 0, -1);
    } else if (face == 4) {
        major = vec3(0, 0, 1); gs = vec3(1, 0, 0); gt = vec3(0, -1, 0);
    } else {
        major = vec3(0, 0, -1); gs = vec3(-1, 0, 0); gt = vec3(0, -1, 0);
    }
}

// The face of r: its largest component's axis, ties to the lowest index.
int fp_cube_face(vec3 r) {
    vec3 a = abs(r);
    if (a.x >= a.y && a.x >= a.z) return r.x < 0.0 ? 1 : 0;
    if (a.y >= a.z) return r.y < 0.0 ? 3 : 2;
    return r.z < 0.0 ? 5 : 4;
}

// r on a given face's plane (its major axis need not be r's largest), with J_P there.
FpMapPoint fp_cube_point_on(int face, vec3 r) {
    vec3 major, gs, gt;
    fp_cube_face_axes(face, major, gs, gt);
    float ma = dot(major, r);  // |ma|, positive on its own face
    float sp = dot(gs, r) / ma, tp = dot(gt, r) / ma;
    return FpMapPoint(face, 0.5 * (vec2(sp, tp) + 1.0), (gs - sp * major) * (0.5 / ma),
                      (gt - tp * major) * (0.5 / ma));
}

FpMapPoint fp_cube_point(vec3 r) {
    return fp_cube_point_on(fp_cube_face(r), r);
}

// The direction of (s, t) on face f's plane, valid beyond the face: r = e_a + (2s − 1) g_s +
// (2t − 1) g_t. A probe placed off the face is handed to the sampler as this direction, which
// reads it on the face that owns it (docs/method.md, "Filtering on the sphere": Cube).
vec3 fp_cube_direction(int face, vec2 st) {
    vec3 major, gs, gt;
    fp_cube_face_axes(face, major, gs, gt);
    return major + (2.0 * st.x - 1.0) * gs + (2.0 * st.y - 1.0) * gt;
}

// ---- The footprint.

// G x = S J_P x: the map motion, in level-0 texels, of a change x of the direction at p, S =
// texel_scale = (W0, H0) (a cube face's size for both).
vec2 fp_map_motion(FpMapPoint p, vec2 texel_scale, vec3 x) {
    return texel_scale * vec2(dot(p.ds, x), dot(p.dt, x));
}

// K = D Dᵀ + κ² K3 (docs/method.md, "The environment footprint", eq. 13): D = (d_dx, d_dy) = G
// [∂r/∂x, ∂r/∂y] the curvature and aperture term, K3 = (G rough1)(G rough1)ᵀ + (G rough2)(G
// rough2)ᵀ the roughness term, given as its columns g_rough1 = G rough1, g_rough2 = G rough2; all
// in level-0 texels. κ = 2 (footprint's default) makes the roughness part of the probes' kernel,
// (κ²/4) K3, the slopes' own spread.
vec3 fp_environment_footprint(vec2 d_dx, vec2 d_dy, vec2 g_rough1, vec2 g_rough2, float kappa) {
    return fp_footprint_matrix(d_dx, d_dy) + (kappa * kappa) * fp_footprint_matrix(g_rough1, g_rough2);
}

// The reflected direction and its spreads, Schilling's form (b) (docs/method.md, "The environment
// footprint"): what fp_environment_footprint() needs, before the map's Jacobian.
struct FpReflection {
    vec3 r;               // v_r = 2 n_m (n_m·v) − v (n_m·n_m) (eq. 4), unnormalised: |v||n_m|²
    vec3 dr_dx, dr_dy;    // ∂v_r/∂x = A_v ∂v/∂x + A_n ∂n/∂x, and in y (eq. 5)
    vec3 rough1, rough2;  // A_n |n| T B's columns (eqs. 10–12), before κ
    vec3 nm, v;           // the perturbed normal n_m used, and v
};

// A_n x = ∂v_r/∂n_m x = 2 (n_m·v) x + 2 (v·x) n_m − 2 (n_m·x) v.
vec3 fp_reflection_normal_spread(FpReflection f, vec3 x) {
    return 2.0 * dot(f.nm, f.v) * x + 2.0 * dot(f.v, x) * f.nm - 2.0 * dot(f.nm, x) * f.v;
}

//   v, dv_dx, dv_dy: surface → eye, and its derivatives per pixel step (a pinhole's ∂v = −∂p: the
//                    sign matters, docs/method.md, "The sign of ∂v/∂x")
//   n, dn_dx, dn_dy: the surface normal (any nonzero scale, facing v) and the derivatives of that
//                    same vector per pixel step
//   b, t1, t2:       the mean bump slope in the frame T = (t1, t2): n_m = n + |n| T b
//   rough:           B = (d1, d2, d3), B Bᵀ = K_b (fp_roughness_factor()), zero for none
// A bump whose n_m faces away from v is dropped; a normal facing away (a silhouette) is clamped
// towards v until n̂·v̂ = 1e-3 (docs/method.md, "Degenerate cases").
FpReflection fp_reflection(vec3 v, vec3 dv_dx, vec3 dv_dy, vec3 n, vec3 dn_dx, vec3 dn_dy, vec2 b,
                           vec3 t1, vec3 t2, vec3 rough) {
    float n_len = length(n);
    vec3 nm = n + n_len * (b.x * t1 + b.y * t2);
    if (!fp_is_finite(nm.x + nm.y + nm.z) || !(dot(nm, v) > 0.0)) nm = n;  // the bump faces away
    if (!(dot(n, v) > 0.0)) {  // a silhouette: n clamped towards v
        vec3 v_hat = normalize(v);
        n -= (dot(n, v_hat) - 1e-3 * n_len) * v_hat;
        nm = n;
    }
    FpReflection f;
    f.nm = nm;
    f.v = v;
    float nm_nm = dot(nm, nm);
    f.r = 2.0 * dot(nm, v) * nm - nm_nm * v;
    // A_v x = ∂v_r/∂v x = 2 n_m (n_m·x) − (n_m·n_m) x, with n_m (the papers' eq. 8 has n).
    f.dr_dx = 2.0 * dot(nm, dv_dx) * nm - nm_nm * dv_dx + fp_reflection_normal_spread(f, dn_dx);
    f.dr_dy = 2.0 * dot(nm, dv_dy) * nm - nm_nm * dv_dy + fp_reflection_normal_spread(f, dn_dy);
    f.rough1 = fp_reflection_normal_spread(f, n_len * rough.x * t1);
    f.rough2 = fp_reflection_normal_spread(f, n_len * (rough.y * t1 + rough.z * t2));
    return f;
}

// ---- The cube-map lookup by probes (docs/method.md, "Filtering on the sphere": Cube;
// environment_lookup() on a cube map): footprint assembly on the centre face, the probes placed
// on its plane along the footprint's major axis, each handed to the sampler as the direction of
// that point (fp_cube_direction()), read at the centre face's planned lod. The cube must be
// sampled seamlessly (GL_TEXTURE_CUBE_MAP_SEAMLESS, always on in GLES 3 and Vulkan), so that
// bilinear taps cross the faces' edges as the CPU's do, and hold its whole chain of levels.

// With the footprint K (xx, xy, yy) already known, in level-0 texels of dir's face (the face
// fp_cube_point(dir) names), e.g. from fp_environment_footprint().
vec4 fp_environment_cube_k(samplerCube cube, vec3 dir, vec3 k, int max_probes) {
    int face_size = textureSize(cube, 0).x;
    FpMapPoint p = fp_cube_point(dir);
    FpPlan plan = fp_plan_probes(fp_planned_ellipse(k, vec2(float(face_size))), max_probes,
                                 fp_full_chain_max_level(ivec2(face_size)));
    if (plan.count == 1) return textureLod(cube, dir, plan.lod);
    vec4 result;
#define FP_SAMPLE_CUBE(i, at, lod) textureLod(cube, fp_cube_direction(p.face, at), lod)
    FP_ASSEMBLE(vec4, result, plan, p.st, float(face_size), FP_SAMPLE_CUBE)
#undef FP_SAMPLE_CUBE
    return result;
}

// The cube map filtered over the footprint of direction dir (environment_lookup() form (a), with
// roughness):
//   cube:             the environment, seamless, trilinear, its whole chain of levels
//   dir:              the lookup direction in the cube's space (any nonzero length), e.g.
//                     FpReflection's r
//   ddir_dx, ddir_dy: its derivatives per pixel step (a camera ray's differentials, or
//                     FpReflection's dr_dx, dr_dy)
//   rough1, rough2:   the roughness columns (FpReflection's), zero for none
//   kappa:            κ of eq. 13 (footprint's default 2)
//   max_probes:       N_max ≥ 1 (footprint's default 30)
// A non-finite footprint reads as a point lookup (one probe of level 0) in the direction dir.
vec4 fp_environment_cube(samplerCube cube, vec3 dir, vec3 ddir_dx, vec3 ddir_dy, vec3 rough1,
                         vec3 rough2, float kappa, int max_probes) {
    vec2 size = vec2(float(textureSize(cube, 0).x));
    FpMapPoint p = fp_cube_point(dir);
    vec3 k = fp_environment_footprint(fp_map_motion(p, size, ddir_dx), fp_map_motion(p, size, ddir_dy),
                                      fp_map_motion(p, size, rough1), fp_map_motion(p, size, rough2),
                                      kappa);
    if (!fp_is_finite(k.x + k.y + k.z)) k = vec3(0.0);
    return fp_environment_cube_k(cube, dir, k, max_probes);
}

#endif  // FOOTPRINT_GLSL_ENVIRONMENT
