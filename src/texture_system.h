// texture_system.h — footprint::TextureSystem: filtered lookups of texture files by name, through
// a cache of bounded size, callable from many threads (the role of OpenImageIO's TextureSystem).
//
//   footprint::TextureSystemOptions options;
//   options.max_memory_mb = 512;
//   auto ts = footprint::TextureSystem::create(options);
//   float rgb[3];
//   footprint::Status s = ts->texture("albedo.tx", coords, footprint::LookupOptions{}, rgb);
//   if (!s) std::cerr << s.error().message << "\n";   // "cannot read 'albedo.tx': no such file"
//
// Files are opened on first use, by name (a path; relative names are relative to the process's
// working directory). What a texture() call returns is texture_lookup() (texture/texture_lookup.h)
// of the file's MIP pyramid, with every filter and LookupOptions of that call: coordinates,
// derivatives and results in its conventions.
//
// Where the texels come from
//   Stored levels. A tiled file that stores its MIP levels — OpenImageIO maketx's .tx, a tiled
//   MIP-mapped OpenEXR or TIFF, save_image_levels()' and `footprint maketx`'s output — is read
//   tile by tile, as lookups need its tiles, and its levels are used as stored (a box pyramid's
//   kernel is assumed, as MipPyramid::from_levels() assumes).
//   Built levels. Any other image is read whole once and its pyramid built (MipPyramid::build's
//   levels, with options.downsample), a level at a time, into the cache folder: options.cache_dir,
//   or by default default_texture_cache_dir() ($XDG_CACHE_HOME/footprint, else
//   $HOME/.cache/footprint). There it is a tiled MIP-mapped EXR, named by a hash of the source's
//   absolute path, size and modification time (and of the options that shape the pyramid), so
//   that a changed source is built again; it is then read tile by tile like a stored file, and
//   later runs open it without building. A build holds the image and two levels as floats (about
//   1.3 times the image as floats) until it is written; the file is written under a temporary name
//   and renamed, so that an interrupted build leaves no cache file and processes building the same
//   file at once each put a complete one in place. Lookups give the same bits as on the pyramid
//   built in memory: the file keeps the levels' prefilter variances. options.build_in_memory
//   keeps the pyramid in memory instead (stats().bytes_in_memory), outside max_memory_mb's bound.
//   Where the default folder cannot be made or a file cannot be written there, the pyramid is
//   held in memory and a warning says so (take_warnings(); once for the folder, once per file).
//   Colour: integer files are sRGB-decoded as load_image() decodes them (image/image_io.h), float
//   files are linear (options.color = ColorEncoding::linear: every file's values as stored, as
//   OpenImageIO's TextureSystem returns them); alpha is read as stored, straight or
//   premultiplied, as load_image() reads it. Wrap modes come from the file's "wrapmodes" attribute
//   (maketx's; "black" is read as clamp), else options.default_wrap.
//
// Bounded memory
//   Stored and cached files' texels live in tiles of options.tile_size² texels, per MIP level,
//   loaded on demand into one cache shared by all threads and evicted least-recently-used when the
//   texels of the cached tiles would exceed max_memory_mb. Each thread keeps the last tiles it used
//   (a micro-cache of kMicroCacheTiles tiles, without locks) and pins the tiles of the lookup it is
//   in until that lookup returns. So the texels resident at any time are at most max_memory_mb
//   plus, per thread, the micro-cache and the tiles of one lookup; plus about 150 bytes of
//   bookkeeping per cached tile; plus the maps held whole (below, and build_in_memory). stats()
//   reports all of them (bytes_resident, peak_bytes; bytes_in_memory: those held whole). The
//   threads' micro-caches belong to the system and are freed with it. Results do not depend on
//   what the cache holds: a lookup returns the same bits with any max_memory_mb.
//   Bump maps are read the same way: a bump pyramid file (`footprint maketx --bump`) is read tile
//   by tile as a texture of 5 moment channels, a normal map has its pyramid built into the cache
//   folder (as a texture's, build_in_memory and fallback alike) and then read tile by tile. So are
//   environment maps, per face (and per polar cap of a lat-long map), per MIP level: an
//   environment pyramid file (`footprint maketx --env`, envmap/env_pyramid_file.h) is read tile by
//   tile as stored; any other image, laid out as load_environment() detects, has its pyramids
//   built and held whole as an EnvironmentMap (stats().bytes_in_memory) or, with an explicit
//   cache_dir (not the default folder), written there as an environment pyramid file once and read
//   tile by tile (later runs open it without building). Not by default, because lookups through
//   tiles return the map's own results bit for bit with footprint assembly only; the other
//   filters, which read the centre face alone, may differ at a cube face's edge (a cube map in
//   memory keeps its neighbours' texels there).
//
// Maps made in memory
//   add_image(), add_bump() and add_environment() give a name to an image, a bump pyramid or an
//   environment map the caller made (a generated texture, a normal map at the scene's strength, an
//   environment assembled from six face files): lookups by that name then read it, held whole,
//   as they read a file. footprint's renderer registers its derived maps this way, so that every
//   lookup it makes goes through one TextureSystem. A name can be given once; a registered name
//   hides a file of that name.
//
// Whole maps, for a GPU
//   pyramid(), bump_pyramid() and environment_map() hand out a map whole, for uploading to a GPU:
//   a tiled file's levels are then read completely, outside the cache and its bound.
//
// UDIM
//   A name containing "<UDIM>" is a set of files: the lookup at (s, t) reads the one whose name has
//   1001 + ⌊s⌋ + 10·⌊t⌋ there, at (s − ⌊s⌋, t − ⌊t⌋), as other renderers resolve UDIMs (u tiles
//   0…9 per row). A position outside u ∈ [0, 10), t ≥ 0, or on a tile with no file, is missing.
//
// Errors
//   A file that cannot be read, or is not a texture footprint reads, gives every lookup on it an
//   Error naming the file ("cannot read 'a.png': no such file"), never a crash, and costs one
//   attempt to open: it is not retried. A lookup given a missing colour (missing_color, as
//   OpenImageIO's missingcolor) writes that colour instead and succeeds; the error is then
//   reported once per file through take_errors().
//
// Thread safety: every call may be made from any number of threads at once.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <footprint/bump/bump_pyramid.h>
#include <footprint/core/result.h>
#include <footprint/envmap/env_footprint.h>
#include <footprint/envmap/environment_map.h>
#include <footprint/image/image_io.h>
#include <footprint/texture/texture_lookup.h>
#include <footprint/texture/wrap.h>

namespace footprint {

struct TextureSystemOptions {
    std::size_t max_memory_mb = 1024;  // the cached tiles' texels, in MiB (≥ 1)
    int tile_size = 64;                // texels per tile side: a power of two, 8 to 1024
    // Where pyramids built for files without stored levels are written, then read tile by tile
    // (created if missing); empty: default_texture_cache_dir(). An environment map's are written
    // only to a cache_dir given here (see "Bounded memory").
    std::filesystem::path cache_dir;
    // Hold the pyramids built for files without stored levels whole in memory, as footprint did
    // before its default cache folder: nothing is written, but their texels are not bounded by
    // max_memory_mb (stats().bytes_in_memory). Not with a cache_dir.
    bool build_in_memory = false;
    DownsampleFilter downsample = DownsampleFilter::box;  // of pyramids built here
    WrapMode default_wrap = WrapMode::repeat;             // for files that do not say how they wrap
    // How integer files' colour channels are decoded (load_image()'s choice, image/image_io.h):
    // automatic decodes sRGB where load_image() would; linear returns values as stored.
    ColorEncoding color = ColorEncoding::automatic;
};

struct TextureSystemStats {
    std::size_t files = 0;         // names opened, those that failed too
    std::size_t tiles_loaded = 0;  // tiles read into the cache (again after an eviction)
    // Tiles asked of the shared cache: found there, or not (then loaded). A thread's micro-cache
    // answers most tile requests before they reach it; those are not counted.
    std::size_t tile_hits = 0, tile_misses = 0;
    // Texels held now: the tiles alive (cached, or pinned) and the maps held whole.
    std::size_t bytes_resident = 0;
    std::size_t peak_bytes = 0;       // the most bytes_resident has been
    std::size_t bytes_in_memory = 0;  // texels of the maps held whole (see "Where the texels…")
};

struct TextureInfo {
    int width = 0, height = 0;  // level 0
    int channels = 0;
    int levels = 0;
    bool tiled = false;  // read tile by tile through the cache (stored or cached levels)
    WrapMode wrap_s = WrapMode::repeat, wrap_t = WrapMode::repeat;
};

// A file's entry in a TextureSystem, for callers that look one file up many times: handle() once,
// then lookups by handle skip the name's lookup. Valid as long as the TextureSystem. Textures,
// bump maps and environment maps have a handle type each: one file may be read as more than one.
class TextureHandle;
class BumpHandle;
class EnvironmentHandle;

class TextureSystem {
  public:
    static constexpr int kMicroCacheTiles = 8;

    // Refuses options it cannot honour (max_memory_mb 0, a tile size that is not a power of two in
    // range, a cache_dir that cannot be created, a cache_dir with build_in_memory), naming them. A
    // default cache folder that cannot be created is a warning (take_warnings()), not a refusal:
    // pyramids are then built in memory.
    static Result<std::unique_ptr<TextureSystem>> create(const TextureSystemOptions& options = {});
    virtual ~TextureSystem() = default;

    // The handle of a texture file, opening it on first use (a file that fails to open has a handle
    // too: lookups on it give its error).
    virtual TextureHandle* handle(std::string_view name) = 0;
    // The file's size, channels and levels (a UDIM set: its first tile's), or its error.
    virtual Result<TextureInfo> info(TextureHandle* texture) = 0;
    Result<TextureInfo> info(std::string_view name) { return info(handle(name)); }

    // The texture filtered over the footprint of `coords`: out.size() floats, the file's first
    // channels, any beyond them 0 (3 of a 1-channel file: grey, 0, 0). On an error, the missing
    // colour (its first out.size() floats, 0 beyond) if one is given, else an Error.
    virtual Status texture(TextureHandle* texture, const TextureCoords& coords,
                           const LookupOptions& options, std::span<float> out,
                           std::span<const float> missing_color = {}) = 0;
    Status texture(std::string_view name, const TextureCoords& coords, const LookupOptions& options,
                   std::span<float> out, std::span<const float> missing_color = {}) {
        return texture(handle(name), coords, options, out, missing_color);
    }

    // environment_lookup() form (a) of the environment map in `name` (an environment pyramid
    // file, or a lat-long, cube cross or sphere/paraboloid image laid out as load_environment()
    // detects it): direction r and its ray differentials. out and missing_color as texture().
    virtual Status environment(EnvironmentHandle* map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                               const EnvLookupOptions& options, std::span<float> out,
                               std::span<const float> missing_color = {}) = 0;
    Status environment(std::string_view name, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                       const EnvLookupOptions& options, std::span<float> out,
                       std::span<const float> missing_color = {}) {
        return environment(environment_handle(name), r, dr_dx, dr_dy, options, out, missing_color);
    }
    // Schilling's form (b): a footprint computed for this map (environment_shape() gives its
    // layout and texel scale for compute_env_footprint()).
    virtual Status environment(EnvironmentHandle* map, const EnvFootprint& footprint,
                               const LookupOptions& options, std::span<float> out,
                               std::span<const float> missing_color = {}) = 0;
    Status environment(std::string_view name, const EnvFootprint& footprint,
                       const LookupOptions& options, std::span<float> out,
                       std::span<const float> missing_color = {}) {
        return environment(environment_handle(name), footprint, options, out, missing_color);
    }
    // Unfiltered: environment_bilinear() at the finest level in the map's direction r (a point
    // sample, as a supersampled reference takes them).
    virtual Status environment_sample(EnvironmentHandle* map, Vec3 r, std::span<float> out) = 0;
    struct EnvironmentShape {
        EnvLayout layout;
        Vec2 texel_scale;
        int channels;
        // The coarsest (1×1) level of each face, averaged: the map's mean colour, unweighted by
        // solid angle (an ambient term's level); channels floats, 0 beyond.
        std::array<float, MipPyramid::kMaxChannels> mean{};
    };
    virtual Result<EnvironmentShape> environment_shape(EnvironmentHandle* map) = 0;
    Result<EnvironmentShape> environment_shape(std::string_view name) {
        return environment_shape(environment_handle(name));
    }
    virtual EnvironmentHandle* environment_handle(std::string_view name) = 0;

    // bump_lookup() (bump/bump_pyramid.h) of the bump map in `name`: the mean slope and slope
    // covariance over the footprint, scaled as options.strength and options.micro_roughness say
    // (a LookupOptions converts: 1 and none). The map is a bump pyramid file (`footprint maketx
    // --bump`, bump/bump_pyramid_file.h), read tile by tile; a normal map (OpenGL convention,
    // decoded as load_slope_map() decodes it, at strength 1 without micro-roughness), whose
    // pyramid is built as a texture's is (in memory, or once into cache_dir and then read tile by
    // tile); or the pyramid add_bump() gave that name.
    virtual Status bump(BumpHandle* map, const TextureCoords& coords,
                        const BumpLookupOptions& options, SlopeStatistics* statistics) = 0;
    Status bump(std::string_view name, const TextureCoords& coords,
                const BumpLookupOptions& options, SlopeStatistics* statistics) {
        return bump(bump_handle(name), coords, options, statistics);
    }
    virtual BumpHandle* bump_handle(std::string_view name) = 0;
    // The size, levels and wraps of a bump map's moment pyramid (5 channels), or its error.
    virtual Result<TextureInfo> info(BumpHandle* map) = 0;

    // Maps made in memory (see above). Each returns the new entry's handle, or an Error where the
    // name is taken or the map is empty. add_image() builds the image's pyramid as for a file
    // without stored levels, wrapping as `wrap_s`, `wrap_t`; its channels are linear.
    virtual Result<TextureHandle*> add_image(std::string_view name, const Image& image,
                                             WrapMode wrap_s = WrapMode::repeat,
                                             WrapMode wrap_t = WrapMode::repeat) = 0;
    virtual Result<BumpHandle*> add_bump(std::string_view name, BumpPyramid pyramid) = 0;
    virtual Result<EnvironmentHandle*> add_environment(std::string_view name,
                                                       EnvironmentMap map) = 0;

    // Whole maps (see above), or the entry's error.
    virtual Result<std::shared_ptr<const MipPyramid>> pyramid(TextureHandle* texture) = 0;
    virtual Result<std::shared_ptr<const BumpPyramid>> bump_pyramid(BumpHandle* map) = 0;
    virtual Result<std::shared_ptr<const EnvironmentMap>> environment_map(
        EnvironmentHandle* map) = 0;

    virtual TextureSystemStats stats() const = 0;
    // The errors not yet taken, each file's once, in the order they happened.
    virtual std::vector<Error> take_errors() = 0;
    // The warnings not yet taken: things done otherwise than asked, lookups unaffected (a cache
    // folder that cannot be used: pyramids held in memory instead), each once.
    virtual std::vector<Error> take_warnings() { return {}; }
};

// The default cache folder of built pyramids (TextureSystemOptions::cache_dir):
// $XDG_CACHE_HOME/footprint where XDG_CACHE_HOME is an absolute path, else
// $HOME/.cache/footprint; empty where neither is set (pyramids are then built in memory).
std::filesystem::path default_texture_cache_dir();

}  // namespace footprint
