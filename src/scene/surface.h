// scene/surface.h — rays and the local differential geometry of a surface hit: what every shape
// (analytic or mesh) hands to the renderer, and all the renderer needs to compute ray
// differentials (scene/ray_differentials.h).
//
// Geometry is in double precision: ray differentials are differences of nearby hit points, and at
// a grazing angle far from the origin float loses them.
#pragma once

#include <footprint/math/vec.h>
#include <footprint/math/vec3.h>

namespace footprint {

struct Ray {
    Vec3d origin;
    Vec3d direction;  // any nonzero length; a hit's t is in units of |direction|
};

// The surface at a hit point p(u, v) of a parametric patch, with
//   n      the unit shading normal, on the side the shape's orientation says (outward for closed
//          shapes, the `normal` key for planes, towards the focus for the paraboloid mirror; for
//          meshes the interpolated vertex normal, or the geometric one without vertex normals).
//          The renderer flips it towards the viewer where needed; shapes never do.
//   ∂p/∂u, ∂p/∂v   the partial derivatives of the position with respect to the texture
//          coordinates (u, v) (uv = (u, v), as the shape's uv_scale or the mesh's UVs define them;
//          for a mesh without UVs, the barycentric coordinates (b1, b2))
//   ∂n/∂u, ∂n/∂v   the partial derivatives of that same unit n (Weingarten equations for analytic
//          shapes; the interpolated, normalised vertex normal's derivatives for meshes)
// Texture convention: (s, t) = (u, 1 − v) for image lookups (texture/texture_lookup.h: t grows
// down the image, v grows up it, bump/slope_map.h).
struct SurfaceHit {
    double t = 0;  // ray parameter: p = origin + t·direction
    Vec3d p;
    Vec3d n;
    Vec3d dpdu, dpdv;
    Vec3d dndu, dndv;
    Vec2d uv;
    Vec3d geometric_normal;  // unit, same side as n (for offsetting secondary rays)
    int object = -1;         // index into Scene::objects (set by the scene's intersector)
    int primitive = -1;      // triangle index for meshes, −1 for analytic shapes
};

}  // namespace footprint
