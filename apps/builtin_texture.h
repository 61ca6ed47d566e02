// apps/builtin_texture.h — the demo's procedural test texture, generated in code.
//
// A size × size RGB image in linear light, values in [0, 1], made to show every kind of aliasing
// on a plane seen at a grazing angle (all feature sizes scale with `size`; at 1024):
//   * an 8 × 8 checkerboard (128-texel squares): warm light squares, dark blue squares;
//   * the light squares carry "text": lines of 5 × 7-texel pseudo-glyphs (random bitmaps, 1-texel
//     strokes, word gaps), dark or red ink — the highest frequencies, at the texel scale;
//   * the dark squares show a colour zone plate centred on the texture, cos(π r² / (2R)) with
//     R = size/2, a 120° phase shift per channel: its frequency rises linearly from 0 at the
//     centre to the Nyquist limit (½ cycle per texel) at r = R; beyond R the squares are plain;
//   * thin lines on top: 1-texel red lines every 32 texels, white ones on the checker edges.
// The image tiles seamlessly except for the zone plate's outer ring (plain beyond R anyway).
// Deterministic: the same size always gives bit-identical texels.
#pragma once

#include "image/image.h"

namespace footprint {

// size ≥ 16 (the feature sizes assume a multiple of 32; other sizes work, less tidily).
Image make_builtin_texture(int size = 1024);

}  // namespace footprint
