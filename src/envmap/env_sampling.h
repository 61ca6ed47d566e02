// envmap/env_sampling.h — (private to envmap) reading an environment map's texels seamlessly:
// taps beyond a face's edge come from wherever the direction of their centre lies (spec §3.1's
// seamless cube filtering, the lat-long seam and poles, the sphere map's rim, the other paraboloid
// hemisphere). Used by environment_map.cpp and polar_caps.cpp; the public entry points are in
// environment_map.h.
//
// Each function reads an EnvironmentMap, whose faces are MipPyramids in memory, or a
// TiledEnvironment (tiled_environment.h), whose faces are TiledTexels, `Map`, alike: the faces'
// texels are read through face_texel() and face_taps_inside(). A tiled face stores no border, so
// its taps beyond an edge are read by direction, from the texels a cube face's border holds.
#pragma once

#include <algorithm>
#include <type_traits>

#include "envmap/cube_edges.h"
#include "envmap/environment_map.h"
#include "texture/sampling.h"
#include "texture/tiled_texels.h"

namespace footprint::detail {

// Texel (x, y) of level l of a face, (x, y) on the level or its border (MipPyramidOptions::border).
inline const float* face_texel(const MipPyramid& face, int l, int x, int y) {
    return face.level(l).texel(x, y);
}
inline const float* face_texel(const TiledTexels& face, int l, int x, int y) {
    return face.texel(l, x, y);
}
// The taps at position p of level l (`view`) of a face, p inside the level or its border.
inline BilinearTaps face_taps_inside(const MipPyramid&, const MipPyramid::LevelView& view, int,
                                     const BilinearPosition& p) {
    return taps_at(view, p.x0, p.x0 + 1, p.y0, p.y0 + 1, p.fx, p.fy);
}
inline BilinearTaps face_taps_inside(const TiledTexels& face, const MipPyramid::LevelView&, int l,
                                     const BilinearPosition& p) {
    return face.taps(l, p);
}

// The texel (x, y) of a level of `face` that lies beyond the level's edge, taken from wherever the
// direction of its centre lies — the neighbour cube face (seamless cube filtering, §3.1; by
// integers beyond one edge, cube_edges.h), across a lat-long pole (the seam wraps the same way),
// back through the sphere map's rim, or on the other paraboloid hemisphere. A texel of the level
// itself, never of its border: it is what a cube face's border is filled with.
template <class Map>
inline const float* env_texel_beyond_edge(const Map& map, int face, int level, int x, int y) {
    const MipPyramid::LevelView& view = map.face(face).level(level);
    if (map.layout() == EnvLayout::latlong) {
        // Over a pole, row −1 − k is row k half a turn around; the seam wraps (exact for texel
        // centres, and no trigonometry).
        if (y < 0 || y >= view.height) {
            y = y < 0 ? -1 - y : 2 * view.height - 1 - y;
            x += view.width / 2;
        }
        x %= view.width;
        if (x < 0) x += view.width;
        return face_texel(map.face(face), level, x, std::clamp(y, 0, view.height - 1));
    }
    if (map.layout() == EnvLayout::cube &&
        (x < 0 || x >= view.width) != (y < 0 || y >= view.height)) {
        // Beyond one edge: the neighbour face's texel by integers (cube_edges.h), the one the
        // direction below finds.
        const EnvTexel across = cube_texel_across_edge(face, x, y, view.width);
        return face_texel(map.face(across.face), level, across.x, across.y);
    }
    const EnvTexel t = env_texel_of_direction(map.layout(), face, x, y, view.width, view.height);
    return face_texel(map.face(t.face), level, t.x, t.y);
}

// One texel of a level of `face`, where (x, y) may lie beyond the level's edge: a texel of the
// level or of its border (a cube face's neighbours' texels, stored with it), or one read by
// direction (env_texel_beyond_edge()).
template <class Map>
inline const float* env_texel(const Map& map, int face, int level, int x, int y) {
    const MipPyramid::LevelView& view = map.face(face).level(level);
    const int b = view.border;
    if (x >= -b && y >= -b && x < view.width + b && y < view.height + b)
        return face_texel(map.face(face), level, x, y);
    return env_texel_beyond_edge(map, face, level, x, y);
}

// The taps of a bilinear sample at position p on level `level` of `face`, some beyond its edges:
// those are read by direction (env_texel). Out of line: the rare case.
template <class Map>
[[gnu::noinline]] inline BilinearTaps env_taps_beyond_edge(const Map& map, int face, int level,
                                                           const BilinearPosition& p) {
    return {env_texel(map, face, level, p.x0, p.y0),
            env_texel(map, face, level, p.x0 + 1, p.y0),
            env_texel(map, face, level, p.x0, p.y0 + 1),
            env_texel(map, face, level, p.x0 + 1, p.y0 + 1),
            p.fx,
            p.fy};
}

// The taps of a bilinear sample at position p on `view`, level `level` of `face`; taps beyond its
// edges are read by direction (env_texel).
template <class Map>
inline BilinearTaps env_taps(const Map& map, int face, int level, const MipPyramid::LevelView& view,
                             const BilinearPosition& p) {
    if (p.inside) return face_taps_inside(map.face(face), view, level, p);
    return env_taps_beyond_edge(map, face, level, p);
}

// Bilinear on a level of `face`, with taps beyond its edges read by direction.
template <int S, class Map>
inline Texel<S> env_bilinear(const Map& map, int face, int level, float s, float t) {
    const MipPyramid::LevelView& view = map.face(face).level(level);
    return blend_taps<S>(env_taps(map, face, level, view, bilinear_position(view, s, t)));
}

// The taps of a trilinear probe at (face, s, t) (ProbeTaps), read seamlessly (env_taps).
template <class Map>
inline ProbeTaps probe_taps(const Map& map, int face, float s, float t, TrilinearLevels levels) {
    return trilinear_taps(
        map.face(face), s, t, levels,
        [&](const MipPyramid::LevelView& view, int level, const BilinearPosition& p) {
            return env_taps(map, face, level, view, p);
        });
}

// The same where it is cheapest to ask for: a probe whose taps all lie on its face's row-major
// levels in memory (most) is addressed inline, without the edge handling.
template <class Map>
inline ProbeTaps probe_taps_on_face(const Map& map, int face, float s, float t,
                                    TrilinearLevels levels) {
    if constexpr (!std::is_same_v<Map, EnvironmentMap>) {
        return probe_taps(map, face, s, t, levels);
    } else {
        const LineLevels on(map.face(face), levels);
        const BilinearPositionPair p = bilinear_positions(on.fine, on.coarse, s, t);
        if (!(p.fine.inside && p.coarse.inside && on.row_major()))
            return probe_taps(map, face, s, t, levels);
        auto taps = [](const MipPyramid::LevelView& view, const BilinearPosition& q) {
            return row_major_taps(view.base + q.y0 * view.row_floats + q.x0 * view.stride,
                                  view.row_floats, view.stride, q.fx, q.fy);
        };
        return {taps(on.fine, p.fine),
                levels.w > 0.0f ? taps(on.coarse, p.coarse) : BilinearTaps{}};
    }
}
}  // namespace footprint::detail
