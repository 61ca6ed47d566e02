// envmap/env_layout.h — environment-map parameterisations P(r), their Jacobians J_P(r) = ∂(s,t)/∂r
// and their inverses (spec §3: cube §3.1, sphere §3.2, dual paraboloid §3.3, lat-long §3.4).
//
// Every layout maps a direction r (any nonzero length: P is homogeneous of degree 0) to a face and
// normalised coordinates (s, t), t = 0 the top row of the face image (spec §1, docs/method.md),
// and back.
// The Jacobian (2×3, rows ∂s/∂r and ∂t/∂r) satisfies
//     J_P(r) r = 0          (a lookup depends on the direction only, [P4])
//     J_P(λr) = J_P(r)/λ    (λ > 0; P is homogeneous of degree 0, so J_P is of degree −1)
// The footprint code (env_footprint.h) multiplies it by S = diag(W0, H0) to get level-0 texels.
// The spec wins over the paper: the cube uses the OpenGL face table (not the paper's eq. 6, which
// is transposed/mirrored on some faces, erratum [E6o]), the sphere map uses the homogeneous form
// r_z + |r| (the lecture's r_z + 1 is valid only for unit r, [P1L]).
//
// ---- Cube (§3.1, OpenGL). Faces +X −X +Y −Y +Z −Z = 0…5; major axis a = argmax|r_i|, ties to the
// lowest index; ma = r_a, σ = sgn(ma), sc = g_s·r, tc = g_t·r, s = ½(sc/|ma| + 1), t = ½(tc/|ma| +
// 1). The unfolded cube seen from inside, each face drawn as its image (s → right, t ↓ down), with
// the world axis each coordinate grows towards ("s→ −z": s grows towards −z):
//
//                 +----------+                        face  ma   g_s    g_t
//                 |  +Y (2)  |                         +X   r_x  −e_z   −e_y
//                 | s→ +x    |                         −X   r_x  +e_z   −e_y
//                 | t↓ +z    |                         +Y   r_y  +e_x   +e_z
//      +----------+----------+----------+----------+   −Y   r_y  +e_x   −e_z
//      |  −X (1)  |  +Z (4)  |  +X (0)  |  −Z (5)  |   +Z   r_z  +e_x   −e_y
//      | s→ +z    | s→ +x    | s→ −z    | s→ −x    |   −Z   r_z  −e_x   −e_y
//      | t↓ −y    | t↓ −y    | t↓ −y    | t↓ −y    |
//      +----------+----------+----------+----------+   (neighbouring edges in this drawing are
//                 |  −Y (3)  |                          shared edges of the cube; the −Z face's
//                 | s→ +x    |                          right edge meets −X's left edge)
//                 | t↓ −z    |
//                 +----------+
//   ∂s/∂r = (g_s − s' σ e_a)/(2|ma|),  ∂t/∂r = (g_t − t' σ e_a)/(2|ma|),  s' = sc/|ma|, t' =
//   tc/|ma|. Inverse r = σ e_a + (2s − 1) g_s + (2t − 1) g_t, valid beyond [0,1]² on the extended
//   face plane: cube_reproject() sends a probe centre that left its face through it onto the face
//   owning it.
//
// ---- Lat-long (§3.4): s = ½ + atan2(r_x, −r_z)/(2π), t = arccos(r_y/|r|)/π  (y up, t = 0 at +y):
//
//      s = 0          ¼            ½            ¾            1
//   t=0  +------------+------------+------------+------------+   whole top row:    +Y
//        |                                                   |
//   t=½  +Z          −X           −Z           +X           +Z   (+Z on the seam s = 0 ≡ s = 1)
//        |                                                   |
//   t=1  +------------+------------+------------+------------+   whole bottom row: −Y
//   ρ = √(r_x² + r_z²):  ∂s/∂r = (−r_z, 0, r_x)/(2πρ²),  ∂t/∂r = −(e_y − r_y r/|r|²)/(πρ).
//   s ∈ [0,1] is periodic (wrap offsets mod 1); +Z itself gives s = 1 (s = 0 when r_x = −0).
//   Inverse (φ = 2π(s − ½), θ = πt): r = (sin θ sin φ, cos θ, −sin θ cos φ); t outside [0,1]
//   continues over the pole along the great circle.
//
// ---- Sphere map (§3.2, OpenGL SPHERE_MAP, eye space, homogeneous form):
//   p = |r|, w = r_z + p, m = √(r_x² + r_y² + w²) = √(2pw), s = ½(r_x/m + 1), t = ½(1 − r_y/m).
//   (The spec's t = ½(r_y/m + 1) is OpenGL's, whose row 0 is the image's BOTTOM row; here t = 0 is
//   the top row, as in every layout of this library, so +Y is up in the image file — the way a
//   mirror-ball photograph or any sphere map on disk is drawn. Only the sign of ∂t/∂r changes.)
//
//        s=0            s=½            s=1
//   t=0   +-----------------------------+        a disk of radius ½ about (½, ½):
//         |         .--''''''--.        |          centre  +Z
//         |      .'      +Y      '.     |          +Y at (½, ½ − √2/4), −Y at (½, ½ + √2/4)
//         |     /                  \    |          −X at (½ − √2/4, ½), +X at (½ + √2/4, ½)
//   t=½   |    |  −X     +Z     +X  |   |          the rim circle: −Z (singular)
//         |     \                  /    |
//         |      '.      −Y      .'     |
//         |         '--......--'        |
//   t=1   +-----------------------------+
//   ∇m = (r_x e_x + r_y e_y + w(e_z + r/p))/m, ∂s/∂r = ½(e_x/m − r_x ∇m/m²),
//   ∂t/∂r = −½(e_y/m − r_y ∇m/m²).
//   Equal-area (Lambert azimuthal): |det J_tangent| = 1/16 per steradian ([P1a]); the anisotropy
//   grows without bound towards the rim r̂ → −e_z. Inverse: (a, b) = (2s − 1, 1 − 2t), k = a² + b²,
//   n_z = √(1 − k), r = (2a n_z, 2b n_z, 1 − 2k); points with 1 < √k < 2 are folded back into the
//   disk through the rim (√k → 2 − √k, azimuth + π, so a probe path crosses −Z continuously);
//   √k ≥ 2 gives −e_z.
//
// ---- Dual paraboloid (§3.3, Heidrich–Seidel 1998): face 0 = front (r_z ≥ 0, δ = |r| + r_z),
//   face 1 = back (r_z < 0, δ = |r| − r_z); (x, y) = (r_x, r_y)/δ, s = ½(x + 1), t = ½(1 − y)
//   (+Y up in the image, as for the sphere map).
//
//        front (face 0)                 back (face 1)           each face a disk of radius ½:
//   t=0  +---------------+         +---------------+            centre +Z (front), −Z (back);
//        |    .-'+Y'-.   |         |    .-'+Y'-.   |            the rim circle = the equator
//        |  /         \  |         |  /         \  |            r_z = 0 (shared by both faces);
//   t=½  | −X   +Z    +X |         | −X   −Z    +X |            ±X at s = ½ ± ½, ±Y at t = ½ ∓ ½
//        |  \         /  |         |  \         /  |            on both faces (the back face is
//        |    '-.−Y.-'   |         |    '-.−Y.-'   |            NOT mirrored in x).
//   t=1  +---------------+         +---------------+
//   ∂x/∂r = e_x/δ − r_x (r/|r| ± e_z)/δ², ∂y/∂r likewise (+ front, − back); ∂s = ½∂x, ∂t = −½∂y.
//   Conformal (stereographic): J_t J_tᵀ = c² I, c = 1/(2(1 + |r̂_z|)) ([P2c]).
//   Inverse r = (2x, 2y, ±(1 − x² − y²))/(1 + x² + y²) (+ front, − back), y = 1 − 2t; x² + y² > 1
//   continues into the other hemisphere (spec §3.3).
//
// ---- Degenerate input. Nothing here returns NaN or ±Inf:
//   * r = 0 or with a NaN component: the direction is taken as the fallback +e_z
//     (kEnvFallbackDirection) for the coordinates, and the Jacobian is 0.
//   * r with infinite components: the direction is the signs of the infinite components (finite
//     ones dropped, e.g. (Inf, 5, 0) → +e_x); the Jacobian is 0 (its limit, J ~ 1/|r|).
//   * tiny or huge finite r: r is pre-scaled by a power of two (exact), so the coordinates never
//     under/overflow; Jacobian entries that would overflow (|r| ≲ 1e-38 in float) are clamped to
//     ±max finite.
//   * lat-long poles (r_x = r_z = 0 exactly): s = ½, t = 0 (+Y) or 1 (−Y), and BOTH Jacobian rows
//     are 0 (the s row is ~1/ρ, the t row's direction depends on the azimuth of approach): a zero
//     Jacobian means "undefined here", and the caller takes the spec's isotropic fallback
//     T_p = (H0/π)·θ_fp (§3.4). Near (not at) the pole J is exact and large.
//   * sphere-map rim (r_x = r_y = 0, r_z < 0, i.e. r̂ = −e_z): (s, t) = (1, ½) (a point of the rim
//     circle, all of which is −Z) and a zero Jacobian; near it J is exact and large (∝ 1/m); the
//     caller clamps λ1 ≤ W/2 (§3.2).
//   * non-finite (s, t) or an invalid face in the inverse maps: the fallback direction +e_z.
//     Finite (s, t) of any size give a finite direction.
//
// The functions are templates on the scalar (float for rendering, double for references and
// tests), explicitly instantiated for float and double in env_layout.cpp.
#pragma once

#include <optional>
#include <string_view>

#include <footprint/math/vec.h>
#include <footprint/math/vec3.h>

namespace footprint {

enum class EnvLayout { cube, latlong, sphere, paraboloid };

// The direction used for r = 0 or NaN input and for invalid inverse-map input.
template <class T>
constexpr Vec3T<T> kEnvFallbackDirection{0, 0, 1};

template <class T>
struct EnvCoordsT {
    int face = 0;  // cube 0…5 (+X −X +Y −Y +Z −Z), paraboloid 0 front / 1 back, otherwise 0
    T s = T(0.5), t = T(0.5);
};
using EnvCoords = EnvCoordsT<float>;
using EnvCoordsd = EnvCoordsT<double>;
template <class T>
using CubeCoordsT = EnvCoordsT<T>;
using CubeCoords = CubeCoordsT<float>;

// J_P = ∂(s,t)/∂r: its rows ∂s/∂r and ∂t/∂r (2×3).
template <class T>
struct Jacobian23T {
    Vec3T<T> ds, dt;
};
using Jacobian23 = Jacobian23T<float>;
using Jacobian23d = Jacobian23T<double>;

// Number of faces: 6 (cube), 2 (paraboloid), 1 (lat-long, sphere).
int face_count(EnvLayout layout);

// "cube", "latlong", "sphere", "paraboloid" (the command line's and the scene files' names), and
// back; nullopt for any other name.
const char* env_layout_name(EnvLayout layout);
std::optional<EnvLayout> parse_env_layout(std::string_view name);

// ---- Cube (§3.1).
template <class T>
CubeCoordsT<T> cube_coords(Vec3T<T> r);
template <class T>
Jacobian23T<T> cube_jacobian(Vec3T<T> r);
// σ e_a + (2s − 1) g_s + (2t − 1) g_t of `face`, for any finite (s, t) (extended face plane; if
// that overflows, the same direction at half the scale).
template <class T>
Vec3T<T> cube_direction(int face, T s, T t);
// (face, s, t) with (s, t) possibly outside [0,1]² → the face that owns its direction, and (s, t)
// there: cube_coords(cube_direction(face, s, t)). Inside [0,1]² it returns (face, s, t) (up to
// rounding, and up to the tie rule on the face's edges).
template <class T>
CubeCoordsT<T> cube_reproject(int face, T s, T t);

// ---- Lat-long (§3.4); (s, t) as a Vec2 {s, t}.
template <class T>
Vec2T<T> latlong_coords(Vec3T<T> r);
template <class T>
Jacobian23T<T> latlong_jacobian(Vec3T<T> r);
template <class T>
Vec3T<T> latlong_direction(T s, T t);

// ---- Sphere map (§3.2); (s, t) as a Vec2 {s, t}.
template <class T>
Vec2T<T> sphere_coords(Vec3T<T> r);
template <class T>
Jacobian23T<T> sphere_jacobian(Vec3T<T> r);
template <class T>
Vec3T<T> sphere_direction(T s, T t);

// ---- Dual paraboloid (§3.3); face 0 front (r_z ≥ 0), 1 back.
template <class T>
EnvCoordsT<T> paraboloid_coords(Vec3T<T> r);
template <class T>
Jacobian23T<T> paraboloid_jacobian(Vec3T<T> r);
template <class T>
Vec3T<T> paraboloid_direction(int face, T s, T t);

// ---- Any layout, so that later code is written once. `face` is ignored by lat-long and sphere.
template <class T>
EnvCoordsT<T> env_coords(EnvLayout layout, Vec3T<T> r);
template <class T>
Jacobian23T<T> env_jacobian(EnvLayout layout, Vec3T<T> r);
// Both at once, bit-identical to env_coords and env_jacobian but sharing their work (the
// direction's rescaling, the cube face, the lat-long ρ): what every footprint needs.
template <class T>
struct EnvCoordsJacobianT {
    EnvCoordsT<T> coords;
    Jacobian23T<T> jacobian;
};
template <class T>
EnvCoordsJacobianT<T> env_coords_and_jacobian(EnvLayout layout, Vec3T<T> r);
using EnvCoordsJacobian = EnvCoordsJacobianT<float>;
// The (unnormalised, finite, nonzero) direction of (face, s, t).
template <class T>
Vec3T<T> env_direction(EnvLayout layout, int face, T s, T t);

// ---- Texels of a level w × h.
struct EnvTexel {
    int face, x, y;
};
// The texel holding the direction of the centre of texel (x, y) of `face`, which may lie beyond
// the level: on the neighbouring cube face, over a lat-long pole, back through the sphere map's
// rim, on the other paraboloid hemisphere (the seamless taps of envmap/env_sampling.h).
EnvTexel env_texel_of_direction(EnvLayout layout, int face, int x, int y, int w, int h);

}  // namespace footprint
