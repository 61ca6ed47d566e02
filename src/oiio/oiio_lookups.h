// oiio/oiio_lookups.h — which lookups of OpenImageIO's interface footprint answers, and how
// (private to oiio/).
//
// A texture() call keeps OpenImageIO's meaning: its (s, t) and derivatives, wrap modes, fill,
// firstchannel and gray_to_rgb rules, and — for the mip modes whose value OpenImageIO fixes
// (none, one level, trilinear) — its own choice of levels and weights, read from footprint's
// texels. The default (anisotropic) mode is footprint assembly (docs/method.md §2.8 in place of
// OpenImageIO's probes along the major axis). Anything else is routed to the delegate.
#pragma once

#include <Imath/ImathVec.h>  // before texture.h
#include <OpenImageIO/texture.h>

#include <array>
#include <atomic>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "texsys/texel_access.h"
#include "texture_system.h"

namespace footprint::oiio::detail {

// OpenImageIO's view of one file, read once through the delegate (so both read it alike): what
// every lookup reads, so in a cache line or two.
struct FileFacts {
    bool good = false;  // opened by OpenImageIO
    int subimages = 1;
    int width = 0, height = 0, nchannels = 0, alpha_channel = -1;  // subimage 0, level 0
    bool full_pixel_range = true;  // data window = display window (no crop, no overscan)
    OIIO::TextureOpt::Wrap swrap = OIIO::TextureOpt::WrapBlack;  // "wrapmodes", else black
    OIIO::TextureOpt::Wrap twrap = OIIO::TextureOpt::WrapBlack;
    bool latlong = false;        // textureformat "LatLong Environment"
    bool cube = false;           // textureformat "CubeFace Environment"
    bool y_up = true;            // a lat-long map's up axis ("oiio:updirection", else latlong_up)
    bool sample_border = false;  // "oiio:sampleborder": maketx's OpenEXR lat-long maps
};

// The system-wide settings that shape results (OpenImageIO attributes of the same names).
struct Settings {
    bool gray_to_rgb = false;
    bool flip_t = false;
    int max_mip_res = 1 << 30;  // OpenImageIO's: a file larger than this is the delegate's
};

struct TexCoords {
    float s, t, dsdx, dtdx, dsdy, dtdy;
};

// footprint's entries of one file, opened on first use and kept, so that a lookup by handle makes
// no lookup by name for the file's own entry. Null where footprint does not read the file (it is
// then the delegate's).
class Entries {
  public:
    explicit Entries(std::string file) : file_(std::move(file)) {}
    // The texture entry read as `as`: the file's own, kept, for the default `as`.
    TextureHandle* texture(footprint::TextureSystem& system, const footprint::detail::OpenAs& as);
    // Whether a lookup of subimage 0 wrapping as (s, t) reads the file as its own entry does,
    // so that the own entry, and its cached tiles, serve it. After texture(system, {}).
    bool wraps_as_own(OIIO::TextureOpt::Wrap s, OIIO::TextureOpt::Wrap t) const {
        return own_wraps_ == std::pair(s, t);
    }
    // The environment entry, where footprint reads the file as a lat-long map.
    EnvironmentHandle* latlong(footprint::TextureSystem& system);

  private:
    const std::string file_;
    std::once_flag texture_opened_, latlong_opened_;
    TextureHandle* texture_ = nullptr;
    std::atomic<bool> texture_ready_{false};  // texture_ is set: no std::call_once on lookups
    // texture_'s wrap modes, as OpenImageIO names them (none: not opened)
    std::pair<OIIO::TextureOpt::Wrap, OIIO::TextureOpt::Wrap> own_wraps_{
        OIIO::TextureOpt::WrapDefault, OIIO::TextureOpt::WrapDefault};
    EnvironmentHandle* latlong_ = nullptr;
    // Subimage 0 read with given wrap modes, by (wrap_s, wrap_t): a footprint near an edge of a
    // periodic, clamped or mirrored texture opens one, and such footprints are common (a long
    // line of probes reaches an edge from far inside), so it is kept rather than looked up by
    // name each time.
  public:
    static constexpr int kWrapModes = 3;  // footprint's WrapMode values

  private:
    std::array<std::atomic<TextureHandle*>, kWrapModes * kWrapModes> wrapped_{};
};

// A lookup footprint answers, or nullopt: the delegate's. Writes nchannels results (and the
// derivatives, where given) as OpenImageIO's texture() writes them. `error` receives why a
// lookup footprint took failed (a tile that cannot be read), and the call returns false then.
std::optional<bool> footprint_texture(footprint::TextureSystem& system, Entries& file,
                                      const FileFacts& facts, const Settings& settings,
                                      const OIIO::TextureOpt& options, TexCoords c, int nchannels,
                                      float* result, float* dresultds, float* dresultdt,
                                      std::string& error);

// The common call answered without footprint_texture()'s routing: OpenImageIO's default
// TextureOpt (as direct_options() checks it) on a file footprint reads as its own entry `entry`
// (width × height texels, at least nchannels channels), without result derivatives or flip_t.
// Gives the answer footprint_texture() gives for it, or nullopt where the footprint is one that
// footprint_texture() routes elsewhere (magnified or isotropic): then take footprint_texture().
inline bool direct_options(const OIIO::TextureOpt& o) {
    using T = OIIO::TextureOpt;
    return o.firstchannel == 0 && o.subimage == 0 && o.swrap == T::WrapDefault &&
           o.twrap == T::WrapDefault &&
           (o.mipmode == T::MipModeDefault || o.mipmode == T::MipModeAniso) &&
           (o.interpmode == T::InterpSmartBicubic || o.interpmode == T::InterpBilinear) &&
           o.sblur == 0 && o.tblur == 0 && o.swidth == 1 && o.twidth == 1 && o.anisotropic >= 1 &&
           o.subimagename.empty();
}
// The entry direct_texture() reads for a file, or null where its calls take footprint_texture():
// a file OpenImageIO reads otherwise than as a plain texture (cropped, with a sample border) or
// whose own entry wraps otherwise than the file says.
TextureHandle* direct_entry(footprint::TextureSystem& system, Entries& file,
                            const FileFacts& facts);
std::optional<bool> direct_texture(footprint::TextureSystem& system, TextureHandle* entry,
                                   int width, int height, const OIIO::TextureOpt& options,
                                   const TexCoords& c, int nchannels, float* result,
                                   std::string& error);

// The same for environment(): lat-long maps (OpenImageIO 2.4 reads every environment map as
// lat-long), direction R with ray differentials dRdx, dRdy in OpenImageIO's convention.
std::optional<bool> footprint_environment(footprint::TextureSystem& system, Entries& file,
                                          const FileFacts& facts, const OIIO::TextureOpt& options,
                                          Imath::V3f R, Imath::V3f dRdx, Imath::V3f dRdy,
                                          int nchannels, float* result, float* dresultds,
                                          float* dresultdt, std::string& error);

// Why a call's arguments cannot be looked up ("sblur = nan is not finite"), or empty.
std::string check_options(const OIIO::TextureOpt& options, int subimages);
std::string check_values(const char* const* names, const float* values, int count);
// Whether every value is finite and within ±1e15, as check_values() asks: every lookup's are,
// so the check is inline and the messages are not.
inline bool values_in_range(const float* values, int count) {
    bool in_range = true;
    for (int k = 0; k < count; ++k) in_range &= values[k] <= 1e15f && values[k] >= -1e15f;
    return in_range;  // NaN fails both comparisons
}

}  // namespace footprint::oiio::detail
