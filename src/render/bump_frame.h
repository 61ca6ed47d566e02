// render/bump_frame.h — the tangent frame T in which a material's bump slopes perturb the normal
// at a hit (spec §2.2: n_m = n + |n| T b), and the roughness expressed for the highlights.
//
// The slope maps hold b in bump/slope_map.h's convention: b = −∇h per unit of (u, v) in the
// frame (e_u, e_v) (render_scene.h). Per material frame (scene/scene.h's BumpFrame):
//   natural          spec §6.1: T = (s_u, s_v)/|n| with s_u = n̂ × p_v, s_v = p_u × n̂, and the
//                    height derivatives f = −b enter it: slope_sign = −1. Bumps scale with the
//                    parameterisation (exact for a height field on the surface).
//   normalized       T = (ŝ_u, ŝ_v), slope_sign = −1: the same directions, unit length.
//   main_direction   spec §6.2: T = (e1, e2) of make_orthonormal_frame(n, m), m = the material's
//                    main direction or, when that is zero, the surface's ∂p/∂v; slope_sign = +1.
// A mesh part with tangents (glTF TANGENT, SceneHit::tangent) overrides the frame, as its normal
// map was baked: e1 = the tangent made orthogonal to n, e2 = tangent_sign·(n × e1).
#pragma once

#include "bump/local_frame.h"
#include "math/footprint_ellipse.h"
#include "render/render_scene.h"

namespace footprint {

struct BumpFrameAtHit {
    TangentFrame frame;
    float slope_sign = 1;  // b_T = slope_sign · b
};

BumpFrameAtHit bump_frame(const BumpDesc& bump, const SceneHit& hit);

// K_b, given in T's coordinates, expressed in an orthonormal frame (e1, e2) of the shading
// normal: the 3-D covariance T K Tᵀ of the tangential normal offsets, projected onto e1, e2.
Sym2 covariance_in_frame(const Sym2& k, const TangentFrame& t, Vec3 e1, Vec3 e2);

}  // namespace footprint
