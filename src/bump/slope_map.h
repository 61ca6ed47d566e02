// bump/slope_map.h — slope maps: precalculated bump derivatives (S97b "Bump mapping with
// precalculated derivatives"), made from height maps or normal maps.
//
// A slope map is an Image with 2 channels (b1, b2): the bump slope vector b of spec §1/§2.2 at
// each texel, in an orthonormal tangent frame T = (e1 e2). The renderer perturbs the normal as
//     n_m = n + |n| (b1 e1 + b2 e2)                                   (spec §2.2)
// so for a unit normal the perturbed normal is n̂ + b1 e1 + b2 e2 (not normalised).
//
// Sign convention (architecture.md: the slope and normal-map signs are defined here, once)
// ----------------------------------------------------------------------------------------
//
//        image / file layout              texture space            tangent frame
//      x → column 0 … W−1               v ↑                        e2 = e_v (up the image)
//   y  +-------------------+ t = 0        |                        ↑
//   ↓  | row 0 (top)       |              |                        |
//      |                   |              |                        ⊙──→ e1 = e_u
//      | row H−1 (bottom)  |              +──────→ u               n̂ out of the page,
//      +-------------------+ t = 1      (0, 0) = bottom-left      (e1, e2, n̂) right-handed
//
//   * u = s runs along the columns, left → right; v = 1 − t runs UP the image (t = 0 is the top
//     row, spec §1). This is the OpenGL convention of tangent-space normal maps ("green up").
//   * The surface height field is h(u, v) (world units). Its perturbed normal in the tangent frame
//     (e_u, e_v, n̂) is ∝ (−h_u, −h_v, 1), where h_u, h_v are derivatives per unit of WORLD length
//     along e_u, e_v.
//   * The stored slope is b = (b1, b2) = (−h_u, −h_v): height per unit length, so that
//     n_m = n̂ + b1 e1 + b2 e2 with e1 = e_u, e2 = e_v. A surface rising to the right (h_u > 0)
//     has b1 < 0: its normal leans left, away from the uphill direction.
//   * Which frame: b is meant for the orthonormal frame of local_frame.h built with the main
//     direction m = p_v = ∂p/∂v, the surface direction of increasing v, i.e. UP the image
//     (p_v = −∂p/∂t). Spec §6.2 [F3u] then gives e2 = p̂_v and e1 ⟂ p_v with e1·p_u > 0, so e1 = e_u
//     wherever the parameterisation is orthogonal.
//   * For a normal map texel (n_x, n_y, n_z) in the same frame, b = (n_x, n_y)/n_z.
//
// The natural frame's derivatives (spec §6.1)
// --------------------------------------------
// The natural frame stores the plain parametric derivatives f_u = ∂h/∂u, f_v = ∂h/∂v of the
// height (height per unit of PARAMETER u, v) and perturbs n' = n + f_u s_u + f_v s_v with
// s_u = n̂ × p_v, s_v = p_u × n̂. For an orthogonal parameterisation (p_u ⟂ p_v) with e_u = p̂_u,
// e_v = p̂_v: s_u = −|p_v| e_u, s_v = −|p_u| e_v, |n| = |p_u||p_v|, hence
//     n'/|n| = n̂ − (f_u/|p_u|) e_u − (f_v/|p_v|) e_v      ⇒    b1 = −f_u/|p_u|,   b2 = −f_v/|p_v|
// (slopes_from_natural_derivatives / natural_derivatives_from_slopes). In particular, a slope map
// made by slopes_from_height_map with height_scale = 1, texel_size_u = 1/W and texel_size_v = 1/H
// (u, v ∈ [0, 1] across the map) holds exactly −(f_u, f_v): negate it to get the natural-frame
// map. For a non-orthogonal parameterisation use local_frame.h's slopes_in_frame(), which
// re-expresses any tangent-frame slope in an orthonormal frame exactly.
//
// Errors (core/result.h): nothing prints or throws. Bad input (empty or malformed images, wrong
// channel counts, NaN/Inf values, normals at or below the tangent plane, bad options) returns an
// Error whose message names the offending texel "(x, y)" (x = column, y = row from the top) or
// option and the value; load_slope_map's messages also name the file.
#pragma once

#include <filesystem>

#include <footprint/core/result.h>
#include <footprint/image/image.h>
#include <footprint/math/vec.h>

namespace footprint {

// ---- Height maps -------------------------------------------------------------------------------

enum class HeightMapWrap {
    repeat,  // the map tiles the plane: neighbours wrap around (central differences everywhere)
    clamp,   // no neighbours outside: one-sided differences on the border texels
};

struct HeightMapOptions {
    float height_scale = 1.0f;  // world height per unit of map value (negative inverts the bumps)
    float texel_size_u = 1.0f;  // world length of one texel along u (one column step), > 0
    float texel_size_v = 1.0f;  // world length of one texel along v (one row step), > 0
    HeightMapWrap wrap_u = HeightMapWrap::repeat;
    HeightMapWrap wrap_v = HeightMapWrap::repeat;
};

// Slopes of the height map's channel 0 (any further channels are ignored: a grey map saved as RGB
// works), by central differences:
//   b1(x, y) = −(h(x+1, y) − h(x−1, y)) · height_scale / (2 · texel_size_u)
//   b2(x, y) = +(h(x, y+1) − h(x, y−1)) · height_scale / (2 · texel_size_v)
// The + in b2 is the sign flip of v = 1 − t: rows go down, v goes up. At clamp borders the
// difference is one-sided (h(1) − h(0) over one texel); a map 1 texel wide has b1 = 0 (likewise
// for v). With repeat the neighbours wrap. Returns a W×H 2-channel slope map.
// Errors: empty or malformed image, 0 channels, a non-finite height (names the texel and value),
// non-finite or non-positive options.
Result<Image> slopes_from_height_map(const Image& height, const HeightMapOptions& options = {});

// ---- Normal maps -------------------------------------------------------------------------------

enum class NormalMapGreen {
    opengl,   // +Y = up the image (+v): the convention above ("green up"; Blender, Maya, glTF)
    directx,  // +Y = down the image (−v): n_y is negated on input (3ds Max, Unreal, DirectX)
};

enum class InvalidNormalPolicy {
    error,  // return an Error naming the first invalid texel (x, y) and its value (default)
    clamp,  // replace it: slope of magnitude max_slope in the direction of (n_x, n_y), or b = 0
            // (flat) where that direction is undefined (n_x = n_y = 0, or a NaN/Inf component)
};

struct NormalMapOptions {
    NormalMapGreen green_convention = NormalMapGreen::opengl;
    float strength = 1.0f;  // multiplies every slope (0 flattens; negative inverts the bumps)
    // A texel is invalid if a component is NaN/Inf, n_z ≤ 0 (normal on or below the tangent plane),
    // or its slope |b| = |(n_x, n_y)|/n_z exceeds max_slope (within atan(1/max_slope) of the
    // plane). The default 1000 (89.94°) accepts every 8-bit normal with n_z > 0 (slope ≤ 361).
    float max_slope = 1000.0f;
    InvalidNormalPolicy invalid_normal_policy = InvalidNormalPolicy::error;
};

// Slopes of a tangent-space normal map. `normals` holds the DECODED DATA values c ∈ [0, 1]:
// callers must load normal map files with ColorEncoding::linear (load_image would otherwise
// sRGB-decode an 8-bit PNG and bend every normal); load_slope_map does this. The normal is
// n = 2c − 1 (any length: only its direction matters, so unnormalised maps are fine), then
// n_y ← −n_y for directx, then
//     b = strength · (n_x, n_y) / n_z                   (n ∝ (−h_u, −h_v, 1) ⇒ b = (n_x, n_y)/n_z)
// Channels: 3 = (x, y, z); 4 = (x, y, z, ignored alpha); 2 = (x, y) only, with
// z = sqrt(max(0, 1 − n_x² − n_y²)) reconstructed (x² + y² ≥ 1 gives z = 0: invalid). Other
// channel counts (1, 5+) are refused. Invalid texels are handled by options.invalid_normal_policy
// (the validity test uses the slope before `strength`). Returns a W×H 2-channel slope map.
Result<Image> slopes_from_normal_map(const Image& normals, const NormalMapOptions& options = {});

// The inverse, for round trips and for saving: a W×H 3-channel normal map in the OpenGL
// convention, c = (n + 1)/2 with n = (b1, b2, 1)/|(b1, b2, 1)|, values in [0, 1]. Reads channels 0
// and 1 (a missing channel 1 counts as 0); a non-finite slope gives the flat normal (0.5, 0.5, 1),
// as does every texel of a malformed image; a zero-size image gives an empty one.
// Save the result with ColorEncoding::linear.
Image normals_from_slopes(const Image& slopes);

// ---- Files -------------------------------------------------------------------------------------

enum class SlopeMapSource { height_map, normal_map };

struct SlopeMapLoadOptions {
    SlopeMapSource source = SlopeMapSource::normal_map;
    HeightMapOptions height_map;  // used when source == height_map
    NormalMapOptions normal_map;  // used when source == normal_map
};

// Loads `file` with load_image(…, ColorEncoding::linear) — file values are data, never sRGB — and
// converts it with slopes_from_height_map or slopes_from_normal_map (a normal map's NaN/Inf texels
// are loaded as they are, so its invalid_normal_policy decides for them). Errors name the file:
// "cannot read 'n.png': …" from the loader, or "cannot make a slope map from 'n.png': normal map
// texel (3, 1) …".
Result<Image> load_slope_map(const std::filesystem::path& file,
                             const SlopeMapLoadOptions& options = {});

// ---- Natural-frame derivatives (spec §6.1) ↔ slopes, orthogonal parameterisation ---------------

// b = (−f_u/|p_u|, −f_v/|p_v|) (derivation above). A length that is not finite and > 0 gives 0 for
// that component (a degenerate parameterisation carries no bump), as does a non-finite result.
Vec2 slopes_from_natural_derivatives(Vec2 f, float pu_length, float pv_length);
// f = (−b1·|p_u|, −b2·|p_v|), the inverse; a non-finite or negative length, or a non-finite
// result, gives 0 likewise.
Vec2 natural_derivatives_from_slopes(Vec2 b, float pu_length, float pv_length);

}  // namespace footprint
