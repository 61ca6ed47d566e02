// bench/oiio_texture_file.h — the OpenImageIO peer's set-up, shared by the texture and environment
// benchmarks: an image written as a tiled, MIP-mapped .tx by ImageBufAlgo::make_texture (what
// `maketx` does), opened in a TextureSystem large enough to keep every tile resident (so that the
// benchmarks measure filtering, not I/O), and removed again on destruction.
#pragma once

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

#include "image/image.h"

namespace footprint::bench {

// What the batched TextureSystem calls take besides the lookups: options whose per-lane arrays are
// the single calls' defaults (TextureOptBatch leaves them uninitialised), and the mask of the first
// `count` lanes.
inline OIIO::TextureOptBatch default_batch_options() {
    OIIO::TextureOptBatch options;
    for (int i = 0; i < OIIO::Tex::BatchWidth; ++i) {
        options.sblur[i] = options.tblur[i] = options.rblur[i] = 0;
        options.swidth[i] = options.twidth[i] = options.rwidth[i] = 1;
    }
    return options;
}
inline OIIO::Tex::RunMask first_lanes(int count) {
    return count >= 32 ? ~OIIO::Tex::RunMask(0) : (OIIO::Tex::RunMask(1) << count) - 1;
}

class OiioTextureFile {
  public:
    // `mode`: MakeTxTexture or MakeTxEnvLatl; `config` carries maketx's options (e.g. wrapmodes).
    OiioTextureFile(const Image& image, const std::filesystem::path& tx_path,
                    OIIO::ImageBufAlgo::MakeTextureMode mode, const OIIO::ImageSpec& config = {})
        : path_(tx_path) {
        OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
        OIIO::ImageBuf source(spec, const_cast<float*>(image.pixels.data()));
        if (!OIIO::ImageBufAlgo::make_texture(mode, source, path_.string(), config))
            throw std::runtime_error("make_texture failed: " + OIIO::geterror());
        system_ = OIIO::TextureSystem::create(false);
        system_->attribute("max_memory_MB", 4096.0f);
        handle_ = system_->get_texture_handle(OIIO::ustring(path_.string()));
        if (!handle_) throw std::runtime_error("OIIO cannot open " + path_.string());
    }
    ~OiioTextureFile() {
        OIIO::TextureSystem::destroy(system_);
        std::error_code ec;
        std::filesystem::remove(path_, ec);
    }
    OiioTextureFile(const OiioTextureFile&) = delete;
    OiioTextureFile& operator=(const OiioTextureFile&) = delete;

    OIIO::TextureSystem& system() const { return *system_; }
    OIIO::TextureSystem::TextureHandle* handle() const { return handle_; }

  private:
    std::filesystem::path path_;
    OIIO::TextureSystem* system_ = nullptr;
    OIIO::TextureSystem::TextureHandle* handle_ = nullptr;
};

}  // namespace footprint::bench
