// envmap/cube_edges.h — (private to envmap) the texel across a cube face's edge, by integers.
//
// A bilinear tap one texel beyond exactly one edge of a cube face (x ∈ {−1, w} or y ∈ {−1, w},
// the other coordinate on the face) is read from the neighbouring face (spec §3.1's seamless
// filtering). The texel there is the one that holds the direction of the tap's centre: the first
// row or column of the neighbour along the shared edge, at the same index k along it, or at
// w − 1 − k where the two faces run the edge the opposite way. (Why the same index: the centre of
// tap k lies at v = (2k + 1)/w − 1 along the edge and 1 + 1/w across it, so on the neighbour it
// lies at v·w/(w + 1), which is texel k's interval with at least 1/(w + 1) of a texel to spare.)
// That relation depends only on the cube's face orientations (env_layout.h), not on w: it is
// tabulated once, from the directions themselves, for each face's four edges, and the test checks
// it against the direction of every tap's centre for every edge of faces of many sizes.
//
//      −t (side 2)
//     +-----------+
//  −s |   face    | +s        tap (−1, k): side 0   tap (w, k): side 1
//  (0)|  w × w    | (1)       tap (k, −1): side 2   tap (k, w): side 3
//     +-----------+
//      +t (side 3)
// Taps beyond two edges at once (a face's corner, where three faces meet) keep the direction
// lookup (env_sampling.h).
#pragma once

#include "envmap/env_layout.h"

namespace footprint {

// The texel of the neighbour face that tap (x, y) of `face` (w × w texels) reads: (x, y) one
// texel beyond exactly one edge, the other coordinate in [0, w). The same as
// env_texel_of_direction(EnvLayout::cube, face, x, y, w, w), without the direction.
EnvTexel cube_texel_across_edge(int face, int x, int y, int w);

}  // namespace footprint
