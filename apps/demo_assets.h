// apps/demo_assets.h — procedural assets for the built-in demo scenes, generated in code.
//
// Every function returns a linear-light float Image (image/image.h), deterministic (the same call
// always gives bit-identical texels: fixed-seed integer hashes, no rand(), no threads), finite, and
// fast (each well under 0.3 s at its default size on one core). They stand in for files, so the
// demo runs without ../shared/data, and they are made to provoke the aliasing the library filters:
//
//   environment maps (lat-long, envmap/env_layout.h §3.4: width × width/2, RGB, t = 0 the +Y row,
//   s = ½ + atan2(r_x, −r_z)/(2π), so the image centre s = ½, t = ½ looks along −Z):
//     make_night_sky_latlong      moon, stars, dark sea              (env paper Fig. 10/11 style)
//     make_zebra_latlong          black/white bands of latitude      (env paper Fig. 12/13)
//     make_sky_gradient_latlong   daylight sky with a sun            (fallback for the HDR files)
//   height maps (1 channel, size × size, tile the plane, mean ≈ 0, values in [−1, 1]):
//     make_water_height_map       ripples: sinusoids, several directions and octaves
//     make_brushed_metal_height_map   grooves along u plus a few scratches
//   textures (RGB, values in [0, 1]):
//     make_secret_writing_texture  stretched text, texture paper Fig. 1/2 ("secret writing")
//     make_topographic_texture     a terrain's heights as colours with contour lines
//
// Height units: a height map's values are dimensionless, in [−1, 1]; the surface height is
// value × HeightMapOptions::height_scale (bump/slope_map.h), the "strength" of the bumps, in the
// world units of texel_size_u/v. Sizes below each function's minimum are raised to it.
#pragma once

#include "image/image.h"
#include "math/vec3.h"
#include "scene/scene.h"

namespace footprint {

// ---- Environment maps (lat-long) ---------------------------------------------------------------

// Angular radius of the night sky's moon disk, and its elevation above the horizon and azimuth
// (from −Z towards +X), in degrees.
inline constexpr double kNightSkyMoonRadiusDeg = 1.5;
inline constexpr double kNightSkyMoonElevationDeg = 18.0;
inline constexpr double kNightSkyMoonAzimuthDeg = 20.0;

// A moonlit night, width × width/2 RGB HDR (width ≥ 16):
//   * sky: blue-black, ~0.002 at the zenith rising to ~0.015 at the horizon, with a faint glow
//     (≤ 0.1) within 40° of the moon;
//   * ~4000 stars at the default width (the count scales with the area): gaussian dots of
//     σ ≈ 0.45–0.8 texels, peak 0.05–5, white, bluish or orange, fading out near the horizon —
//     sub-texel detail that sparkles and vanishes when the map is point sampled;
//   * the moon: a disk of radius kNightSkyMoonRadiusDeg (8.5 texels tall at 2048), slightly warm
//     white of ~30 at its centre, a little limb darkening, darker maria (×0.55–0.65), an
//     antialiased limb; its direction is night_sky_moon_direction() (s ≈ 0.556, t = 0.4);
//   * below the horizon (t > ½, r_y < 0): a dark sea, ~0.01 at the horizon fading to ~0.003.
// The horizon row is box filtered.
Image make_night_sky_latlong(int width = 2048);

// Unit direction of the moon's centre: elevation 18°, azimuth 20° from −Z towards +X,
// (cos 18° sin 20°, sin 18°, −cos 18° cos 20°) ≈ (0.325, 0.309, −0.894).
Vec3 night_sky_moon_direction();

// Period of the zebra bands, in degrees of latitude (180° / 36).
inline constexpr double kZebraPeriodDeg = 5.0;

// The zebra environment (env paper Fig. 12/13), width × width/2 RGB (width ≥ 8): horizontal bands
// of constant latitude, white (1) then black (0), each kZebraPeriodDeg/2 wide, starting with white
// at the zenith: value(θ) = 1 where frac(θ / 5°) < ½, θ = πt the angle from +Y. 36 periods from
// pole to pole, 71 edges. Each row holds the exact box-filtered mean of the bands over its
// θ-interval, so the map itself does not alias (edges are grey, never a staircase); the mean over
// the image is ½. A flat mirror reflects the bands as straight lines that crowd together towards
// the horizon — the pattern that shows every error of an environment filter.
Image make_zebra_latlong(int width = 1024);

// Elevation and azimuth (from −Z towards +X, so −40° is towards −X) of the daylight sun, degrees.
inline constexpr double kSkyGradientSunElevationDeg = 35.0;
inline constexpr double kSkyGradientSunAzimuthDeg = -40.0;

// A plain daylight sky, width × width/2 RGB HDR (width ≥ 16): deep blue at the zenith, pale blue
// at the horizon, a brown-grey ground below it (darker further down), and a sun: a gaussian blob
// of σ = 1.2° and peak ~40 in a wide glow, in the direction sky_gradient_sun_direction(). The
// fallback when the HDR environments of ../shared/data are missing.
Image make_sky_gradient_latlong(int width = 512);

// Unit direction of the sun of make_sky_gradient_latlong().
Vec3 sky_gradient_sun_direction();

// ---- Height maps -------------------------------------------------------------------------------

// Water ripples, size × size, 1 channel (size ≥ 16), tiling the plane seamlessly: a sum of 15
// sinusoids, 3 per octave at 2, 4, 8, 16, 32 cycles per tile (those at or above the Nyquist limit
// of a small map are left out), their amplitude falling by ×0.55 per octave, directions spread
// ±50° about a wind direction of 30° (from +u towards +v). Each has an integer wave vector, so the
// sum is exactly periodic and has zero mean; it is scaled so that max |value| = 1. The steepest
// step of the map value between neighbouring texels is ~0.05 at 512 (it scales as 1/size): with
// height_scale = 1 and texel_size = 1/size (the map across one world unit) the slopes reach ~25;
// a height_scale of ~0.01 gives gentle ripples (slopes ≲ 0.25).
Image make_water_height_map(int size = 512);

// Brushed metal, size × size, 1 channel (size ≥ 16), tiling seamlessly: grooves brushed along u —
// periodic value noise whose cells are long along u (size/2 … size/16 texels) and short along v
// (1 … 8 texels), so the height varies quickly along v (rows) and slowly along u (columns) — plus
// 8 straight scratches in random directions (1.2–2 texels wide, deeper than the grooves), drawn
// wrapped around the borders. The mean is removed; values lie in [−1, 1] (grooves ~±0.3, scratch
// bottoms down to ~−1). Mean |∂h/∂v| is more than 10× mean |∂h/∂u|.
Image make_brushed_metal_height_map(int size = 512);

// ---- Textures ----------------------------------------------------------------------------------

// "Secret writing" (texture paper Fig. 1/2), size × size RGB (size ≥ 64): lines of real text in a
// 5 × 7 bitmap font, dark ink on light paper, stretched 6× along v. Viewed head-on it is a field
// of thin vertical strokes; seen at a grazing angle (foreshortening ~6×, the plane's v axis
// running away from the viewer, the top row t = 0 farthest) the letters get their proper shape and
// the text can be read — if the filter is anisotropic. Strokes are 1 texel wide along u at 1024
// (size/1024 texels, at least 1), one 6-texel-tall unit along v; glyphs advance 6 units, lines 9.
// Isotropic trilinear filtering picks the mip level from the long axis of the footprint and
// blurs the strokes into grey bars and moiré; footprint assembly keeps them. Paper ≈ (0.85, 0.82,
// 0.72) with faint blue ruled lines under each line of text, ink dark blue-black (one line in
// five red); mean luminance ≈ 0.67.
Image make_secret_writing_texture(int size = 1024);

// A topographic map of `terrain` (scene/terrain.h) for its uv: colour by height (green lowlands,
// brown slopes, grey rock, white peaks, over the terrain's own range) and a dark contour line every
// `contour` world units of height, about 1.5 texels wide at any slope — thin lines that crowd where
// the terrain is steep, the detail a filter must keep from aliasing towards the horizon.
// size × size RGB (size ≥ 16), rows along +z as the terrain's uv.
Image make_topographic_texture(const TerrainShape& terrain, double contour, int size = 1024);

}  // namespace footprint
