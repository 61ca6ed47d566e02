// envmap/tiled_environment.h — an environment map whose texels are read tile by tile (private to
// the library): the texture system's environment pyramid files (env_pyramid_file.h), filtered
// within its bounded cache.
//
// A TiledEnvironment has the layout, faces and polar caps of an EnvironmentMap, each face a
// TiledTexels (texture/tiled_texels.h) over the tiles of its part of the file. Its lookups are
// the EnvironmentMap's, step for step (env_lookup_general.h is written once over either map), and
// return bit for bit what the same lookups on the map the file holds return, for the filter
// footprint assembly. (The other filters read the centre face alone and wrap there as a texture
// does; a cube face in memory keeps its neighbours' texels in a border, which a tiled face does
// not, so at a cube face's edge they may differ.)
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include "core/result.h"
#include "envmap/environment_map.h"
#include "texture/tiled_texels.h"

namespace footprint::detail {

// The shape of an environment map's pyramids: its layout, and one TiledShape for each face (in
// face order), then, for a lat-long map with them, the two polar caps (+Y, −Y).
struct TiledEnvShape {
    EnvLayout layout = EnvLayout::latlong;
    std::vector<TiledShape> parts;
    bool polar_caps = false;

    int face_count() const { return static_cast<int>(parts.size()) - (polar_caps ? 2 : 0); }
    int channels() const { return parts[0].channels; }
    Vec2 texel_scale() const {  // S = (W0, H0) of a face's level 0
        return {static_cast<float>(parts[0].levels[0].width),
                static_cast<float>(parts[0].levels[0].height)};
    }
};

// The shape of `map`'s pyramids in tiles of 2^tile_log2 texels: its faces' level sizes and wrap
// modes, the box prefilter's variance as a stored chain's (MipPyramid::from_levels()).
TiledEnvShape tiled_env_shape(const EnvironmentMap& map, int tile_log2);

// The shape of the environment pyramid file `file` (env_pyramid_file.h), from its headers, in tiles
// of 2^tile_log2 texels: what the texture system reads it tile by tile with. An Error naming the
// file where it is not one, or its parts do not make its layout's map.
Result<TiledEnvShape> environment_pyramid_shape(const std::filesystem::path& file, int tile_log2);

// An environment map read through tiles: part i (a face, then the caps) from parts[i]. Its faces
// are TiledTexels made on first use, each with the part's tiles at hand (TiledTexels::Slots; none
// given: slots of its own), for one lookup at a time (one thread).
class TiledEnvironment {
  public:
    static constexpr int kMaxParts = 8;  // a cube's six faces; a lat-long map and two caps

    struct Part {
        const TileSource* source = nullptr;
        TiledTexels::Slots* slots = nullptr;
    };

    TiledEnvironment(const TiledEnvShape& shape, const std::array<Part, kMaxParts>& parts)
        : shape_(shape), parts_(parts) {}
    TiledEnvironment(const TiledEnvironment&) = delete;
    TiledEnvironment& operator=(const TiledEnvironment&) = delete;

    // What the environment lookups ask of a map (as EnvironmentMap's members of the same names).
    EnvLayout layout() const { return shape_.layout; }
    int face_count() const { return shape_.face_count(); }
    int channels() const { return shape_.channels(); }
    Vec2 texel_scale() const { return shape_.texel_scale(); }
    const TiledTexels& face(int i) const { return part(i); }
    const TiledTexels* polar_cap(int pole) const {
        return shape_.polar_caps ? &part(face_count() + pole) : nullptr;
    }

  private:
    const TiledTexels& part(int i) const {
        if (!texels_[i]) {
            if (parts_[i].slots)
                texels_[i].emplace(shape_.parts[i], *parts_[i].source, *parts_[i].slots);
            else
                texels_[i].emplace(shape_.parts[i], *parts_[i].source);
        }
        return *texels_[i];
    }

    const TiledEnvShape& shape_;
    std::array<Part, kMaxParts> parts_;
    mutable std::array<std::optional<TiledTexels>, kMaxParts> texels_;
};

// environment_lookup() and environment_bilinear() (environment_map.h) of a TiledEnvironment.
void environment_lookup(const TiledEnvironment& map, const EnvFootprint& footprint,
                        const LookupOptions& options, float* out);
void environment_lookup(const TiledEnvironment& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                        const EnvLookupOptions& options, float* out);
void environment_bilinear(const TiledEnvironment& map, Vec3 r, int level, float* out);

}  // namespace footprint::detail
