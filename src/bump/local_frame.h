// bump/local_frame.h — the local tangent frames in which bump slopes are stored and applied:
// spec §6 (S97b "local coordinate systems"; the spec corrects the papers' frame text) and the
// perturbed normal n_m = n + |n| T b of spec §2.2.
//
//   natural frame (§6.1)      s_u = n̂ × p_v,  s_v = p_u × n̂,  n = p_u × p_v = s_u × s_v   [F1]
//                             n' = n + f_u s_u + f_v s_v, f_u, f_v = parametric derivatives of the
//                             height. Dual basis: s_u·p_u = −|n|, s_u·p_v = 0 (s_u = −|n|∇u), so
//                             n' = |n|(n̂ − ∇_S f): exact where f = 0 (or the base surface is
//                             flat), first order in f·curvature otherwise [F2]. T = (s_u s_v)/|n|.
//   orthonormal frame (§6.2)  e1 = (m × n̂)/|m × n̂|,  e2 = n̂ × e1.
//                             e1 ⟂ plane(n, m); e2 ∈ plane(n, m) is the normalised tangent
//                             projection of m; (e1, e2, n̂) is right-handed [F3c]. Earth (n̂ on a
//                             sphere, m = its axis): e1 = east, e2 = north [F3e]. m = p_v: e2 =
//                             p̂_v, e1·p_u > 0 [F3u] — the frame the slope maps of slope_map.h
//                             assume. (Not the papers' prose "e2 ⟂ m, e1 in the plane": spec
//                             erratum 10.)
//
//     side view, plane(n, m) = the page             top view, n̂ out of the page
//
//              n̂    m                                       e2 (along m's tangent part)
//              ↑   ↗                                        ↑
//              |  /                                         |
//              | /                                          ⊙──→ e1
//     ─────────⊙──────→ e2   tangent plane                 n̂
//              e1 out of the page (e1 ⟂ m, e1 ⟂ n)
//
// Degenerate input never produces NaN (every fallback below is tested):
//   * make_orthonormal_frame: where |m̂ × n̂| < min_sin_angle (m ∥ n: the poles of the earth
//     example) no continuous frame exists (hairy ball). The frame then uses, in order, the first of
//     these that is not itself ∥ n̂: options.fallback_direction (if non-zero); the world axis
//     least aligned with m̂ (smallest |m̂_i|, ties to the lower index: x for m = z). That axis is
//     fixed for a fixed m and at least 54.7° away from it, so inside the fallback cap the frame is
//     continuous in n, and it is only discontinuous across the cap's rim. A zero or non-finite m
//     skips to the last resort: the world axis least aligned with n̂. A zero or non-finite n gives
//     the world frame (e1, e2, n̂) = (x, y, z) with origin = degenerate_normal.
//   * make_natural_frame: a degenerate parameterisation (p_u × p_v zero or non-finite) gives the
//     zero frame (n = s_u = s_v = 0) — or, with a usable shading normal, n = n̂_s, s_u = s_v = 0
//     (the bump is dropped, the normal kept).
//   * tangent_frame(NaturalFrame) with n = 0 gives T = 0; perturbed_normal with a non-finite slope
//     uses b = 0, with a non-finite n returns the zero vector.
#pragma once

#include <footprint/math/vec.h>
#include <footprint/math/vec3.h>

namespace footprint {

// T = (t1 t2), the 3×2 tangent frame of spec §1: ∂n̂_m/∂b.
struct TangentFrame {
    Vec3 t1, t2;
};

// n_m = n + |n| (b1 t1 + b2 t2)   (spec §2.2). n may be unnormalised (the perturbation scales with
// it, so n_m/|n| does not depend on |n|); b = 0 for a non-finite b; {0,0,0} for a non-finite n.
Vec3 perturbed_normal(Vec3 n, const TangentFrame& frame, Vec2 b);

// ---- Natural frame (spec §6.1) -----------------------------------------------------------------

struct NaturalFrame {
    Vec3 n;    // p_u × p_v (its length is the area element |p_u × p_v|)
    Vec3 s_u;  // n̂ × p_v
    Vec3 s_v;  // p_u × n̂
};

// From the surface partial derivatives p_u = ∂p/∂u, p_v = ∂p/∂v: n = p_u × p_v, n̂ = n/|n|.
NaturalFrame make_natural_frame(Vec3 p_u, Vec3 p_v);

// With an interpolated shading normal: n̂ = n̂_s (its length is ignored) and, with
// σ = sign(n̂_s·(p_u × p_v)) (−1 for a mirrored, left-handed uv mapping),
//   n = |n̂_s·(p_u × p_v)| n̂_s,   s_u = σ n̂_s × p_v,   s_v = σ p_u × n̂_s.
// The dual basis s_u·p_u = s_v·p_v = −|n|, s_u·p_v = s_v·p_u = 0 holds for either σ, so n' keeps
// the shading normal's side and the bumps their sign under mirrored uvs; [F1] reads
// n = σ s_u × s_v. Where n̂_s·(p_u × p_v) is 0 (or below 1e-6·|n̂_s||p_u × p_v|), the frame is
// degenerate: n = n̂_s, s_u = s_v = 0. A zero or non-finite shading normal is ignored (the
// two-argument form).
NaturalFrame make_natural_frame(Vec3 p_u, Vec3 p_v, Vec3 shading_normal);

// n' = n + f_u s_u + f_v s_v   (spec §6.1), f = (f_u, f_v) the parametric height derivatives.
// A non-finite f gives n.
Vec3 perturbed_normal(const NaturalFrame& frame, Vec2 f);

// T = (s_u s_v)/|n|, so perturbed_normal(n, tangent_frame(frame), f) = n + f_u s_u + f_v s_v.
TangentFrame tangent_frame(const NaturalFrame& frame);

// ---- Orthonormal frame from a main direction (spec §6.2) ---------------------------------------

enum class FrameOrigin {
    main_direction,      // built from m
    fallback_direction,  // m ∥ n̂ (or m unusable): built from a fallback direction (above)
    degenerate_normal,   // n zero or non-finite: the world frame x, y, z
};

struct OrthonormalFrameOptions {
    // Below this |m̂ × n̂| (the sine of the angle between m and n) the fallback is used. Clamped to
    // [1e-5, 0.5] (NaN → 1e-5). The default 1e-3 is a cap of 0.057° around ±m.
    float min_sin_angle = 1e-3f;
    // Secondary main direction; zero = automatic (the world axis least aligned with m̂).
    Vec3 fallback_direction{};
};

struct OrthonormalFrame {
    Vec3 e1, e2;  // unit tangents, e1 × e2 = normal
    Vec3 normal;  // n̂
    FrameOrigin origin = FrameOrigin::main_direction;
};

// e1 = (m × n̂)/|m × n̂|, e2 = n̂ × e1 (spec §6.2), with the fallbacks above. n and m may have any
// positive length. Always finite, orthonormal and right-handed to float precision.
OrthonormalFrame make_orthonormal_frame(Vec3 n, Vec3 m,
                                        const OrthonormalFrameOptions& options = {});

// T = (e1 e2).
TangentFrame tangent_frame(const OrthonormalFrame& frame);

// n + |n| (b1 e1 + b2 e2)   (spec §2.2), with n the (unnormalised) normal the frame was built from.
Vec3 perturbed_normal(Vec3 n, const OrthonormalFrame& frame, Vec2 b);

// The slope b given in the tangent frame `from` re-expressed in the orthonormal frame `to`:
// b' = (e1·T b, e2·T b). Exact whenever T b lies in to's tangent plane (both frames belong to the
// same n̂), so n + |n| T b = n + |n| (b'1 e1 + b'2 e2). E.g. natural-frame derivatives f of a
// non-orthogonal parameterisation: slopes_in_frame(f, tangent_frame(natural), orthonormal).
// A non-finite b gives 0.
Vec2 slopes_in_frame(Vec2 b, const TangentFrame& from, const OrthonormalFrame& to);

}  // namespace footprint
