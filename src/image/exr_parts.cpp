#include "image/exr_parts.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFloatVectorAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledOutputPart.h>
#include <OpenEXR/ImfVecAttribute.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <string>

namespace footprint::detail {

namespace {

// An OpenEXR output stream into memory (the caller writes the file atomically).
class MemoryStream final : public Imf::OStream {
  public:
    MemoryStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        const auto end = static_cast<std::size_t>(position_) + static_cast<std::size_t>(n);
        if (bytes.size() < end) bytes.resize(end);
        std::memcpy(bytes.data() + position_, c, static_cast<std::size_t>(n));
        position_ = end;
    }
    std::uint64_t tellp() override { return position_; }
    void seekp(std::uint64_t position) override { position_ = position; }

    std::vector<unsigned char> bytes;

  private:
    std::uint64_t position_ = 0;
};

const std::vector<std::string>& channel_names(int channels, const LevelsSaveOptions& options) {
    static const std::vector<std::string> kNames[4] = {
        {"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
    return options.channel_names.empty() ? kNames[channels - 1] : options.channel_names;
}

// A float attribute as OpenImageIO writes one: 2 and 3 floats as v2f and v3f.
void insert_floats(Imf::Header& header, const LevelsSaveOptions::FloatAttribute& a) {
    const std::vector<float>& v = a.values;
    if (v.size() == 1) return header.insert(a.name, Imf::FloatAttribute(v[0]));
    if (v.size() == 2) return header.insert(a.name, Imf::V2fAttribute({v[0], v[1]}));
    if (v.size() == 3) return header.insert(a.name, Imf::V3fAttribute({v[0], v[1], v[2]}));
    header.insert(a.name, Imf::FloatVectorAttribute(v));
}

Imf::Header part_header(const LevelChain& part, const Imath::Box2i& display,
                        const LevelsSaveOptions& options) {
    const Image& base = part.levels[0];
    Imf::Header header(display, display);
    header.dataWindow() = Imath::Box2i({0, 0}, {base.width - 1, base.height - 1});
    header.setName(part.name);
    header.setType(Imf::TILEDIMAGE);
    header.setTileDescription(Imf::TileDescription(options.tile_size, options.tile_size,
                                                   Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const std::string& name : channel_names(base.channels, options))
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    header.insert("textureformat", Imf::StringAttribute("Plain Texture"));
    if (!options.wrap_modes.empty())
        header.insert("wrapmodes", Imf::StringAttribute(options.wrap_modes));
    for (const auto& [name, value] : options.string_attributes)
        header.insert(name, Imf::StringAttribute(value));
    for (const LevelsSaveOptions::FloatAttribute& a : options.float_attributes)
        insert_floats(header, a);
    return header;
}

void write_level(Imf::TiledOutputPart& out, const Image& level, int l,
                 const std::vector<std::string>& names) {
    Imf::FrameBuffer frame;
    const std::size_t x_stride = sizeof(float) * static_cast<std::size_t>(level.channels);
    for (int c = 0; c < level.channels; ++c)
        frame.insert(
            names[c],
            Imf::Slice(Imf::FLOAT,
                       const_cast<char*>(reinterpret_cast<const char*>(level.pixels.data() + c)),
                       x_stride, x_stride * static_cast<std::size_t>(level.width)));
    out.setFrameBuffer(frame);
    out.writeTiles(0, out.numXTiles(l) - 1, 0, out.numYTiles(l) - 1, l);
}

}  // namespace

Result<std::vector<unsigned char>> encode_exr_parts(const std::vector<LevelChain>& parts,
                                                    const LevelsSaveOptions& options) {
    int width = 0, height = 0;
    for (const LevelChain& part : parts) {
        width = std::max(width, part.levels[0].width);
        height = std::max(height, part.levels[0].height);
    }
    const Imath::Box2i display({0, 0}, {width - 1, height - 1});
    try {
        std::vector<Imf::Header> headers;
        for (const LevelChain& part : parts) headers.push_back(part_header(part, display, options));
        MemoryStream stream;
        {
            Imf::MultiPartOutputFile file(stream, headers.data(), static_cast<int>(headers.size()));
            for (std::size_t p = 0; p < parts.size(); ++p) {
                Imf::TiledOutputPart out(file, static_cast<int>(p));
                const std::vector<Image>& levels = parts[p].levels;
                for (std::size_t l = 0; l < levels.size(); ++l)
                    write_level(out, levels[l], static_cast<int>(l),
                                channel_names(levels[0].channels, options));
            }
        }
        return std::move(stream.bytes);
    } catch (const std::exception& e) {
        return Error{std::string("OpenEXR could not encode the parts: ") + e.what()};
    }
}

}  // namespace footprint::detail
