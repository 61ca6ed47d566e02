#include "filament_ktx_reader.h"

#include <image/KtxBundle.h>

namespace footprint::test {

FilamentKtx read_with_filament(const std::string& bytes) {
    const image::KtxBundle bundle(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                  static_cast<std::uint32_t>(bytes.size()));
    FilamentKtx ktx;
    const image::KtxInfo& info = bundle.getInfo();
    ktx.gl_type = info.glType;
    ktx.gl_format = info.glFormat;
    ktx.gl_internal_format = info.glInternalFormat;
    ktx.width = info.pixelWidth;
    ktx.height = info.pixelHeight;
    ktx.levels = bundle.getNumMipLevels();
    ktx.array_length = bundle.getArrayLength();
    ktx.cubemap = bundle.isCubemap();
    if (const char* v = bundle.getMetadata("KTXorientation")) ktx.orientation = v;
    if (const char* v = bundle.getMetadata("footprint:slope_offset")) ktx.slope_offset = v;
    for (std::uint32_t l = 0; l < ktx.levels; ++l) {
        auto& level = ktx.blobs.emplace_back();
        for (std::uint32_t f = 0; f < (ktx.cubemap ? 6u : 1u); ++f) {
            std::uint8_t* data = nullptr;
            std::uint32_t size = 0;
            if (bundle.getBlob({l, 0, f}, &data, &size))
                level.emplace_back(data, data + size);
            else
                level.emplace_back();
        }
    }
    return ktx;
}

}  // namespace footprint::test
