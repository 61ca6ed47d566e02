// scene/terrain.h — fractal terrain: a midpoint-displacement (diamond–square) height field as a
// triangle mesh, the `"shape": "terrain"` of a scene file (scene/scene.h's TerrainShape).
//
// The height field has n = 2^L + 1 samples per side over the rectangle `size` (x by z) centred on
// `center`, y up. Diamond–square fills it coarse to fine: each square's centre, then each edge's
// midpoint, is the mean of its 2 to 4 neighbours plus a Gaussian displacement whose standard
// deviation is A·d^H, d the distance to those neighbours on the sample lattice taken as a unit
// square (A the `height`, H the `roughness`): the increments of fractional Brownian motion with
// Hurst exponent H, so that a profile's power spectrum falls as f^−(2H+1) (H near 0: jagged; near
// 1: smooth hills). The four corners are displaced with d = 1.
//
// Each sample's displacement is a hash of (seed, its position on the finest lattice any L can
// reach): a terrain of L + 1 subdivisions refines the one of L, keeping its hills.
//
// The mesh: n² vertices, 2(n − 1)² triangles counter-clockwise seen from +y; smooth normals from
// the height field's central differences (one-sided at the border); uv = (i/(n − 1),
// 1 − j/(n − 1)) for sample (i along x, j along z), so a texture covers the terrain once, its rows
// running along +z. No tangents: bump maps take their frame from ∂p/∂u, ∂p/∂v.
#pragma once

#include <vector>

#include <footprint/scene/mesh.h>
#include <footprint/scene/scene.h>

namespace footprint {

// The heights, row-major: heights[j·n + i] for sample (i, j), n = 2^subdivisions + 1, relative to
// center.y. Subdivisions outside [1, kMaxTerrainSubdivisions] are clamped.
std::vector<double> terrain_heights(const TerrainShape& shape);

// The height field as a triangle mesh in world space, named `name`, with a default material.
TriangleMesh make_terrain_mesh(const TerrainShape& shape, const std::string& name = "terrain");

}  // namespace footprint
