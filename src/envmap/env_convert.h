// envmap/env_convert.h — resampling an environment map into another layout (or size), filtered.
//
// Every output texel is the source map filtered over that texel's footprint, never a point
// sample: for the texel centre (s, t) = ((x + ½)/W, (y + ½)/H) of face f of the output layout,
//   r       = n̂(env_direction(to, f, s, t))                         (unit direction)
//   ∂r/∂x   = n̂(env_direction(to, f, s + ½/W, t)) − n̂(env_direction(to, f, s − ½/W, t))
//   ∂r/∂y   = the same in t with ½/H                                  (n̂: normalised)
// i.e. the ray differentials per output-texel step, as central differences of the unit direction
// in double precision; then environment_lookup(source, r, ∂r/∂x, ∂r/∂y) (form (a), spec §2.4 with
// J_P of the source layout, §3), whose footprint ellipse is the image of the output texel on the
// source and whose filter (footprint assembly by default) has the covariance K/4 (spec §2.6).
// Minification (a smaller output) is therefore antialiased, magnification is bilinear.
//
// Texels outside the valid domain of the output layout are written with the layout's continuation
// (env_layout.h's inverse maps): outside the sphere map's disk the direction folded back through
// the rim, outside a paraboloid face's disk the other hemisphere. A renderer that filters near the
// rim then reads sensible values instead of black.
//
// Output sizes (`size`; 0 = default_env_size): cube: the face edge N (6 faces N × N);
// lat-long: the width N, height N/2 (N even); sphere: N × N; paraboloid: two faces N × N.
// The default keeps the source's angular resolution where each layout is sampled most coarsely:
// with ρ = texels per radian there,
//   lat-long W × H: ρ = min(W/(2π), H/π)  (the equator)     cube N: ρ = N/2 (a face centre)
//   sphere N:       ρ = N/4 (the centre, = the mean over the sphere: every texel is 16/N² sr)
//   paraboloid N:   ρ = N/4 (a face centre)
// the output gets the smallest size whose ρ is at least the source's (a lat-long width rounded
// up to even): lat-long 1024 × 512 → cube 326, sphere 652; cube 256 → lat-long 806 × 403; a
// conversion to the same layout keeps the size. Defaults are clamped to [1, 16384] (lat-long
// width [2, 16384]); an explicit size outside that range, or an odd lat-long width, is an error.
//
// Thread-safety: convert_environment runs the rows in parallel (oneTBB) and calls
// EnvConvertOptions::on_row from any thread, once per finished output row.
#pragma once

#include <functional>

#include <footprint/core/result.h>
#include <footprint/envmap/env_image_io.h>
#include <footprint/envmap/env_layout.h>
#include <footprint/envmap/environment_map.h>
#include <footprint/texture/texture_lookup.h>

namespace footprint {

struct EnvConvertOptions {
    int size = 0;          // 0: default_env_size(); otherwise as described above
    LookupOptions lookup;  // the filter (footprint assembly by default) and its options
    // Called after each output row (any thread, concurrently); may be empty.
    std::function<void()> on_row;
};

// Output size for converting `source` to `to` that keeps its angular resolution (rule above).
int default_env_size(const EnvironmentMap& source, EnvLayout to);
// Source angular resolution ρ, texels per radian where the layout is sampled most coarsely.
double env_texels_per_radian(EnvLayout layout, Vec2 texel_scale);
// Width and height of each output face for `size` (lat-long: {size, size/2}, others square).
std::array<int, 2> env_face_size(EnvLayout to, int size);
// Total number of output rows (faces × rows per face): the number of on_row calls.
int env_output_rows(EnvLayout to, int size);

// The source resampled into layout `to`. Errors: `size` out of range (names the value).
Result<EnvImages> convert_environment(const EnvironmentMap& source, EnvLayout to,
                                      const EnvConvertOptions& options = {});

}  // namespace footprint
