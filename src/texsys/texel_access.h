// texsys/texel_access.h — what the OpenImageIO adapter (oiio/) asks of a TextureSystem beyond its
// public API (private to the library).
//
// OpenImageIO's TextureSystem chooses a subimage and the wrap modes per call, and defines its own
// closest, bilinear and trilinear lookups (their levels and weights are OpenImageIO's, not the
// GL rule texture_lookup() follows). So the adapter opens a file once per subimage and pair of
// wrap modes it is asked for, and reads texels itself for the lookups whose value OpenImageIO
// fixes; footprint's filters run on the same entries through TextureSystem::texture().
#pragma once

#include <functional>
#include <optional>
#include <string_view>

#include "core/result.h"
#include "texture/wrap.h"
#include "texture_system.h"

namespace footprint::detail {

// How an entry reads its file: the subimage (a tiled MIP-mapped file's; other files have one),
// and wrap modes that replace the file's own.
struct OpenAs {
    int subimage = 0;
    std::optional<WrapMode> wrap_s, wrap_t;
    bool operator==(const OpenAs&) const = default;
};

// The entry of file `name` read as `as`: TextureSystem::handle(name) when `as` is the default,
// else an entry of its own (its tiles are cached apart from the default entry's).
TextureHandle* texture_handle(TextureSystem& system, std::string_view name, const OpenAs& as);

// The texels of an entry's levels, for lookups that address texels themselves.
class TexelReader {
  public:
    virtual int level_count() const = 0;
    virtual int width(int level) const = 0;
    virtual int height(int level) const = 0;
    virtual int channels() const = 0;
    // Texel (x, y) of `level`, x ∈ [0, width), y ∈ [0, height): channels() floats.
    virtual const float* texel(int level, int x, int y) const = 0;

  protected:
    ~TexelReader() = default;
};

// Calls read() with the entry's texels (through the cache, its tiles pinned until read()
// returns); the entry's error, or a read's that failed meanwhile, instead.
Status read_texels(TextureSystem& system, TextureHandle* file,
                   const std::function<void(const TexelReader&)>& read);

}  // namespace footprint::detail
