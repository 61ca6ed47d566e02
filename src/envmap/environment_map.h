// envmap/environment_map.h — environment maps as MIP pyramids, and filtered lookups over a
// footprint.
//
// A lat-long map is one pyramid with s repeating (the seam s = 0 ≡ 1 is continuous) and t clamped.
// A cube map is six square pyramids, +X −X +Y −Y +Z −Z (env_layout.h's face table and orientation),
// each clamped to its edges. Lookups take the footprint of env_footprint.h (K in level-0 texels of
// the face the direction lands on) and filter with footprint assembly (spec §2.8–2.9): the probes
// are placed on the centre face's plane along r1, and a probe centre that leaves the face is
// re-projected onto the face that owns its direction (spec §3.1 [E6s]); every probe reads the
// centre face's lod.
//
// Not yet (issue 4): bilinear taps that cross a cube-face edge read the edge texel of their own
// face (clamp-to-edge) rather than the neighbour's texels; the lat-long poles use the plain
// footprint (no spec §3.4 isotropic pole fallback); sphere and paraboloid maps; filters other than
// footprint assembly fall back to texture_lookup() on the centre face.
#pragma once

#include <array>

#include "core/result.h"
#include "envmap/env_footprint.h"
#include "envmap/env_layout.h"
#include "image/image.h"
#include "texture/mip_pyramid.h"
#include "texture/texture_lookup.h"

namespace footprint {

class EnvironmentMap {
  public:
    // A lat-long image (any size ≥ 1×1, 1–8 channels).
    static Result<EnvironmentMap> from_latlong(const Image& image);
    // Six square faces of one size and channel count, in the order +X −X +Y −Y +Z −Z.
    static Result<EnvironmentMap> from_cube_faces(const std::array<Image, 6>& faces);

    EnvLayout layout() const { return layout_; }
    int face_count() const { return static_cast<int>(faces_.size()); }
    int channels() const { return faces_.empty() ? 0 : faces_[0].channels(); }
    Vec2 texel_scale() const;  // S = (W0, H0) of a face's level 0
    const MipPyramid& face(int i) const { return faces_[i]; }

  private:
    EnvLayout layout_ = EnvLayout::latlong;
    std::vector<MipPyramid> faces_;
};

// The map filtered over `footprint` (from compute_env_footprint with this map's layout and
// texel_scale()): channels() floats to out.
void environment_lookup(const EnvironmentMap& map, const EnvFootprint& footprint,
                        const LookupOptions& options, float* out);

}  // namespace footprint
