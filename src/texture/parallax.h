// texture/parallax.h — parallax-occlusion mapping: the texture coordinates where the view ray
// meets a height field below the surface (the lectures' "parallax mapping").
//
// The height map h(s, t) ∈ [0, 1] describes a relief whose top (h = 1) is the geometric surface
// and whose bottom (h = 0) lies `depth` world units below it. A view ray entering the surface at
// (s, t) travels down and sideways; per world unit of depth it moves w = −(a, b)/(v̂·n̂) in (s, t),
// where a ∂p/∂s + b ∂p/∂t is the tangential part of the unit view vector v̂ (surface → eye). At
// depth fraction z ∈ [0, 1] it is at (s, t) + z·depth·w, and it meets the relief where
// z = 1 − h there.
//
// The march takes `steps` equal steps of z from the top, reading h at each (filtered at the level
// the pixel's footprint selects: a coarser relief for a larger footprint), stops at the first step
// below the relief, and refines linearly between the last two steps (the crossing of the lines
// z and 1 − h). At grazing angles |w| grows without bound; the march is then clamped to a shift of
// max_shift in (s, t).
//
// Derivatives. The displaced coordinates s' satisfy s' = s + (1 − h(s'))·depth·w; differentiating
// with w held (it varies slowly across a pixel),
//
//     ∂s' = ∂s − depth·w (∇h·∂s') = ∂s − depth·w (∇h·∂s)/(1 + depth ∇h·w)
//
// (Sherman–Morrison): a pixel on a relief that faces the viewer (∇h·w < 0) covers more of the map
// than the flat surface would, one that faces away less. Where 1 + depth ∇h·w ≤ ¼ (the view ray
// runs along the relief) ∂s is kept.
//
// Silhouettes are not changed: the geometry's outline stays where it is, and a relief at the edge
// of an object is cut by it.
#pragma once

#include <functional>

#include <footprint/math/vec.h>
#include <footprint/math/vec3.h>

namespace footprint {

struct ParallaxOptions {
    float depth = 0.05f;     // world units from h = 1 to h = 0
    int steps = 16;          // 1 … kMaxParallaxSteps
    float max_shift = 0.5f;  // the largest (s, t) shift taken, at grazing angles
};

inline constexpr int kMaxParallaxSteps = 256;

struct ParallaxResult {
    Vec2 st;                   // where the ray meets the relief
    Vec2 dst_dx, dst_dy;       // ∂(s, t)/∂x and ∂(s, t)/∂y there
    float depth_fraction = 0;  // z = 1 − h at the crossing
};

// w = −(a, b)/(v̂·n̂) per world unit of depth (see above) from the view vector and the surface's
// ∂p/∂s, ∂p/∂t and normal (any lengths); zero where the view is edge-on or the frame degenerate.
Vec2 parallax_direction(Vec3 v, Vec3 dp_ds, Vec3 dp_dt, Vec3 n);

// The march. height(st) reads the height map, filtered as the caller wants; gradient(st) its
// gradient ∇h per unit of (s, t) at the crossing.
ParallaxResult parallax_march(const std::function<float(Vec2)>& height,
                              const std::function<Vec2(Vec2)>& gradient, Vec2 st, Vec2 dst_dx,
                              Vec2 dst_dy, Vec2 w, const ParallaxOptions& options);

}  // namespace footprint
