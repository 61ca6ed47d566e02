#include "image/image_io.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <tiffio.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "image/color.h"
#include "image/image_io_detail.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

// 8-bit sRGB: a value is off by at most half a code (0.5/255) in the encoded domain; the decode
// slope d(linear)/d(srgb) is largest at 1, where it is 2.4/1.055 ≈ 2.27. So the linear error is
// at most 2.27 × 0.5/255 ≈ 0.0045 (+ float rounding), well inside the required 0.02.
constexpr float kSrgb8RoundTripTolerance = 2.4f / 1.055f * (0.5f / 255.0f) + 1e-5f;
static_assert(kSrgb8RoundTripTolerance <= 0.02f);
// 16-bit sRGB: the same derivation with half a 16-bit code, 2.27 × 0.5/65535 ≈ 1.7e-5, plus a few
// float ulps from pow() in encode and decode.
constexpr float kSrgb16RoundTripTolerance = 2.4f / 1.055f * (0.5f / 65535.0f) + 3e-6f;
// Linear (un-encoded) 8-bit values and alpha: half a code.
constexpr float kLinear8Tolerance = 0.5f / 255.0f + 1e-6f;
// EXR half: 11 significant bits, round to nearest → relative error ≤ 2^-11.
constexpr float kHalfRelativeTolerance = 1.0f / 2048.0f;
// RGBE (.hdr): the three colours share one exponent e with max component m ≥ 2^(e−1), each has
// an 8-bit mantissa that is truncated, so the error is below one step 2^(e−8) ≤ m/128.
constexpr float kRgbeTolerancePerMax = 1.0f / 128.0f;
// JPEG (OpenImageIO's default quality 98, 4:2:0 chroma subsampling), compared in sRGB codes on
// the smooth test gradient, whose colour changes by 0.8/31 × 255 ≈ 6.6 codes per pixel: the
// 2×2 chroma averaging alone moves a pixel by up to about half of that (≈ 3.3 codes) and DCT
// quantisation adds one or two. Measured 4.5 codes max; the bound allows 8 codes (3 %). The mean
// error must stay near one code.
constexpr float kJpegMaxTolerance = 8.0f / 255.0f;
constexpr float kJpegMeanTolerance = 1.5f / 255.0f;
// sRGB decode of one 8-bit code: exact function of the code, float rounding only.
constexpr float kDecodeTolerance = 1e-6f;

// A fresh directory under the system temp dir, removed at the end of each test.
class ImageIo : public ::testing::Test {
  protected:
    void SetUp() override {
        std::random_device rd;
        dir_ = fs::temp_directory_path() /
               ("footprint-image-io-" + std::to_string(rd()) + "-" + std::to_string(rd()));
        ASSERT_TRUE(fs::create_directory(dir_));
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    fs::path path(const std::string& name) const { return dir_ / name; }
    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir_)) {
            names.push_back(e.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path dir_;
};

// Deterministic pixels in [lo, hi].
Image make_image(int width, int height, int channels, float lo, float hi, unsigned seed = 1) {
    Image image(width, height, channels);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    for (float& v : image.pixels) v = u(rng);
    return image;
}

void write_bytes(const fs::path& file, const std::string& bytes) {
    std::ofstream out(file, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string read_bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void truncate_to_half(const fs::path& file) {
    const std::string bytes = read_bytes(file);
    write_bytes(file, bytes.substr(0, bytes.size() / 2));
}

// Writes a file directly with OpenImageIO (no footprint code involved).
void write_with_oiio(const fs::path& file, int width, int height, int channels,
                     OIIO::TypeDesc format, const std::vector<float>& pixels) {
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(width, height, channels, format);
    ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << out->geterror();
    ASSERT_TRUE(out->close()) << out->geterror();
}

// The file name as error messages quote it. Built with += : GCC 12 gives a false -Wrestrict
// for "'" + std::string at -O3.
std::string quoted(const fs::path& file) {
    const std::string name = file.string();
    std::string s(name.size() + 2, '\'');
    name.copy(s.data() + 1, name.size());
    return s;
}

float max_abs_diff(const Image& a, const Image& b) {
    float m = 0.0f;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        m = std::max(m, std::fabs(a.pixels[i] - b.pixels[i]));
    }
    return m;
}

void expect_same_shape(const Image& a, const Image& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.channels, b.channels);
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
}

// ---- round trips -------------------------------------------------------------------------------

TEST_F(ImageIo, ExrFloatRoundTripIsBitExact) {
    for (int channels = 1; channels <= 4; ++channels) {
        Image image = make_image(7, 5, channels, -3.0f, 40.0f, static_cast<unsigned>(channels));
        image.pixels[0] = 1e30f;
        image.pixels[1 % image.pixels.size()] = -1e-30f;
        const fs::path file = path("float" + std::to_string(channels) + ".exr");
        ASSERT_TRUE(save_image(image, file).ok());
        const Result<Image> loaded = load_image(file);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        expect_same_shape(*loaded, image);
        EXPECT_EQ(loaded->pixels, image.pixels) << channels << " channels";
    }
}

// A band of rows is an EXR data window: its pixels as saved, its place read back, and what
// OpenImageIO itself sees (the display window the full image's); other files are whole images.
TEST_F(ImageIo, AnExrBandKeepsItsPlaceInTheFullImage) {
    const Image band = make_image(9, 4, 3, 0.0f, 2.0f, 3);
    const fs::path file = path("band.exr");
    ImageSaveOptions options;
    options.band = ImageBand{5, 9, 12};
    ASSERT_TRUE(save_image(band, file, options).ok());
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_EQ(loaded->pixels, band.pixels);
    const Result<ImageBand> place = load_image_band(file);
    ASSERT_TRUE(place.ok()) << place.error().message;
    EXPECT_EQ(place->y, 5);
    EXPECT_EQ(place->full_width, 9);
    EXPECT_EQ(place->full_height, 12);
    auto in = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().y, 5);
    EXPECT_EQ(in->spec().full_height, 12);
    const fs::path whole = path("whole.png");
    ASSERT_TRUE(save_image(band, whole).ok());
    const Result<ImageBand> own = load_image_band(whole);
    ASSERT_TRUE(own.ok()) << own.error().message;
    EXPECT_EQ(own->y, 0);
    EXPECT_EQ(own->full_height, 4);
    // Not an EXR, or not inside the full image: refused, nothing written.
    const Status png = save_image(band, path("band.png"), options);
    ASSERT_FALSE(png.ok());
    EXPECT_NE(png.error().message.find("must be .exr"), std::string::npos) << png.error().message;
    options.band = ImageBand{10, 9, 12};
    const Status outside = save_image(band, path("outside.exr"), options);
    ASSERT_FALSE(outside.ok());
    EXPECT_NE(outside.error().message.find("rows 10 to 14"), std::string::npos)
        << outside.error().message;
    EXPECT_FALSE(fs::exists(path("band.png")));
    EXPECT_FALSE(fs::exists(path("outside.exr")));
}

// ---- MIP levels --------------------------------------------------------------------------------

// Random levels of OpenEXR's round-down chain from width × height to 1 × 1.
std::vector<Image> mip_chain(int width, int height, int channels) {
    std::vector<Image> levels;
    for (int w = width, h = height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        levels.push_back(
            make_image(w, h, channels, -2.0f, 30.0f, static_cast<unsigned>(levels.size() + 10)));
        if (w == 1 && h == 1) return levels;
    }
}

TEST_F(ImageIo, MipLevelsRoundTripBitExactAsOneTiledExr) {
    for (int channels : {1, 2, 3, 4}) {
        const std::vector<Image> levels = mip_chain(37, 20, channels);
        ASSERT_EQ(levels.size(), 6u);  // 37×20, 18×10, 9×5, 4×2, 2×1, 1×1
        const fs::path file = path("levels" + std::to_string(channels) + ".exr");
        LevelsSaveOptions options;
        options.wrap_modes = "periodic,clamp";
        options.tile_size = 16;
        ASSERT_TRUE(save_image_levels(levels, file, options).ok());
        const Result<std::vector<Image>> loaded = load_image_levels(file);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        ASSERT_EQ(loaded->size(), levels.size());
        for (std::size_t l = 0; l < levels.size(); ++l) {
            expect_same_shape((*loaded)[l], levels[l]);
            EXPECT_EQ((*loaded)[l].pixels, levels[l].pixels)
                << channels << " channels, level " << l;
        }
        // What a texture system reads: 16 × 16 tiles, MIP-mapped, the wrap modes.
        auto in = OIIO::ImageInput::open(file.string());
        ASSERT_TRUE(in);
        EXPECT_EQ(in->spec().tile_width, 16);
        EXPECT_EQ(in->spec().get_string_attribute("wrapmodes"), "periodic,clamp");
        in->close();
    }
}

TEST_F(ImageIo, AFileWithoutMipLevelsIsItsOneLevel) {
    const Image image = make_image(9, 4, 3, 0.0f, 1.0f);
    ASSERT_TRUE(save_image(image, path("plain.png")).ok());
    const Result<std::vector<Image>> levels = load_image_levels(path("plain.png"));
    ASSERT_TRUE(levels.ok()) << levels.error().message;
    ASSERT_EQ(levels->size(), 1u);
    EXPECT_EQ((*levels)[0].pixels, load_image(path("plain.png"))->pixels);
}

TEST_F(ImageIo, WrongMipChainsAreRefusedNamingTheLevelAndLeaveNothing) {
    const fs::path file = path("bad.exr");
    std::vector<Image> levels = mip_chain(37, 20, 3);
    levels[2] = make_image(5, 5, 3, 0.0f, 1.0f);
    Status s = save_image_levels(levels, file);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message,
              "cannot write " + quoted(file) + ": MIP level 2: it is 5 x 5, not 9 x 5");
    levels = mip_chain(37, 20, 3);
    levels.pop_back();
    s = save_image_levels(levels, file);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message,
              "cannot write " + quoted(file) + ": the levels stop at 2 x 1, not 1 x 1");
    levels = mip_chain(37, 20, 3);
    levels[1] = make_image(18, 10, 4, 0.0f, 1.0f);
    s = save_image_levels(levels, file);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message,
              "cannot write " + quoted(file) + ": MIP level 1: it has 4 channels, level 0 has 3");
    s = save_image_levels(mip_chain(4, 4, 3), path("levels.png"));
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "cannot write " + quoted(path("levels.png")) +
                                     ": MIP levels are written as OpenEXR; name the file .exr");
    EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIo, ExrHalfRoundTripWithinHalfPrecision) {
    const Image image = make_image(6, 4, 4, -8.0f, 1000.0f);
    const fs::path file = path("half.exr");
    ImageSaveOptions options;
    options.exr_half = true;
    ASSERT_TRUE(save_image(image, file, options).ok());
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    expect_same_shape(*loaded, image);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        EXPECT_NEAR(loaded->pixels[i], image.pixels[i],
                    kHalfRelativeTolerance * std::fabs(image.pixels[i]));
    }
}

// load_image reads the file's own texels and converts them to float itself, in bands of rows
// (OpenImageIO 2.4's conversion goes through 64 MiB of scanlines); the floats must be the ones
// OpenImageIO's read_image gives, bit for bit, for every texel type, tiled or not, in one band or
// several (a band is 4 MiB: 341 rows of 2048 RGB 16-bit texels, 384 when tiles are 64 high), and
// for channels of several types (which OpenImageIO still converts).
TEST_F(ImageIo, EveryTexelTypeReadsAsOpenImageIOConvertsIt) {
    struct Case {
        const char* name;
        OIIO::TypeDesc format;
        int tile = 0;
        std::vector<OIIO::TypeDesc> channel_formats = {};
        int width = 37, height = 23;
    };
    using T = OIIO::TypeDesc;
    const std::vector<Case> cases = {
        {"u8.png", T::UINT8},
        {"u16.png", T::UINT16},
        {"i8.tif", T::INT8},
        {"i16.tif", T::INT16},
        {"u32.tif", T::UINT32},
        {"f64.tif", T::DOUBLE},
        {"u8_tiled.tif", T::UINT8, 16},
        {"half.exr", T::HALF},
        {"float.exr", T::FLOAT},
        {"half_tiled.exr", T::HALF, 16},
        {"mixed.exr", T::FLOAT, 0, {T::HALF, T::FLOAT, T::HALF}},
        {"mixed_uint.exr", T::FLOAT, 0, {T::UINT32, T::HALF, T::FLOAT}},
        {"mixed_tiled.exr", T::FLOAT, 16, {T::FLOAT, T::HALF, T::HALF}},
        {"mixed_bands.exr", T::FLOAT, 0, {T::HALF, T::FLOAT, T::HALF}, 2048, 700},
        {"u16_bands.tif", T::UINT16, 0, {}, 2048, 700},
        {"u16_tiled_bands.tif", T::UINT16, 64, {}, 2048, 700},
    };
    const int channels = 3;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        std::vector<float> written(std::size_t(c.width) * c.height * channels);
        for (std::size_t i = 0; i < written.size(); ++i)
            written[i] = 1.5f * std::sin(0.37f * static_cast<float>(i));  // also < 0 and > 1
        const fs::path file = path(c.name);
        auto out = OIIO::ImageOutput::create(file.string());
        ASSERT_TRUE(out) << OIIO::geterror();
        OIIO::ImageSpec spec(c.width, c.height, channels, c.format);
        spec.tile_width = spec.tile_height = c.tile;
        spec.channelformats = c.channel_formats;
        spec.attribute("compression", "none");
        ASSERT_TRUE(out->open(file.string(), spec) && out->write_image(T::FLOAT, written.data()) &&
                    out->close())
            << out->geterror();

        auto in = OIIO::ImageInput::open(file.string());
        ASSERT_TRUE(in) << OIIO::geterror();
        ASSERT_EQ(in->spec().tile_width, c.tile);
        ASSERT_EQ(in->spec().channelformats.empty(), c.channel_formats.empty());
        std::vector<float> expected(written.size());
        ASSERT_TRUE(in->read_image(0, 0, 0, channels, T::FLOAT, expected.data()));

        const Result<Image> loaded = load_image(file, {ColorEncoding::linear});
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        EXPECT_TRUE(loaded->pixels == expected);  // not EXPECT_EQ: millions of values
    }
}

TEST_F(ImageIo, Srgb8PngRoundTrip) {
    for (int channels = 1; channels <= 4; ++channels) {
        const Image image = make_image(16, 9, channels, 0.0f, 1.0f, 10u + channels);
        const fs::path file = path("srgb8_" + std::to_string(channels) + ".png");
        ASSERT_TRUE(save_image(image, file).ok());
        const Result<Image> loaded = load_image(file);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        expect_same_shape(*loaded, image);
        EXPECT_LE(max_abs_diff(*loaded, image), kSrgb8RoundTripTolerance) << channels;
    }
}

// is_srgb_encoded() answers what load_image's automatic encoding does: decode an sRGB PNG, leave
// a linear-tagged PNG and a float EXR alone; a file it cannot open is not sRGB.
TEST_F(ImageIo, IsSrgbEncodedFollowsTheAutomaticRule) {
    const Image image = make_image(8, 4, 3, 0.0f, 1.0f, 7u);
    ImageSaveOptions linear;
    linear.encoding = ColorEncoding::linear;
    ASSERT_TRUE(save_image(image, path("srgb.png")).ok());
    ASSERT_TRUE(save_image(image, path("linear.png"), linear).ok());
    ASSERT_TRUE(save_image(image, path("float.exr")).ok());
    EXPECT_TRUE(is_srgb_encoded(path("srgb.png")));
    EXPECT_FALSE(is_srgb_encoded(path("linear.png")));
    EXPECT_FALSE(is_srgb_encoded(path("float.exr")));
    EXPECT_FALSE(is_srgb_encoded(path("missing.png")));
    // The same decision as load_image: the linear PNG loads as stored, the sRGB one decoded.
    const Result<Image> as_linear = load_image(path("linear.png"));
    ASSERT_TRUE(as_linear.ok());
    EXPECT_LE(max_abs_diff(*as_linear, image), 1.0f / 255);
}

TEST_F(ImageIo, Srgb16PngRoundTrip) {
    const Image image = make_image(16, 9, 3, 0.0f, 1.0f);
    const fs::path file = path("srgb16.png");
    ImageSaveOptions options;
    options.bits = 16;
    ASSERT_TRUE(save_image(image, file, options).ok());
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    expect_same_shape(*loaded, image);
    EXPECT_LE(max_abs_diff(*loaded, image), kSrgb16RoundTripTolerance);
}

TEST_F(ImageIo, PngAlphaIsStoredLinearAndStraight) {
    // Alpha covers 0 … 1, including 0: the colour under alpha 0 must survive (no premultiply).
    Image image = make_image(8, 8, 4, 0.0f, 1.0f, 3);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) image.at(x, y, 3) = static_cast<float>(y * 8 + x) / 63.0f;
    }
    image.at(0, 0, 0) = 0.75f;  // colour under alpha 0
    const fs::path file = path("alpha.png");
    ASSERT_TRUE(save_image(image, file).ok());
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    expect_same_shape(*loaded, image);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
            EXPECT_NEAR(loaded->at(x, y, 3), image.at(x, y, 3), kLinear8Tolerance);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(loaded->at(x, y, c), image.at(x, y, c), kSrgb8RoundTripTolerance);
            }
        }
    }
    // The alpha code in the file is the linear value, not an sRGB encoding of it.
    auto in = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(in);
    std::vector<std::uint8_t> codes(8 * 8 * 4);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, codes.data()));
    EXPECT_EQ(codes[(4 * 8 + 0) * 4 + 3], std::lround(32.0f / 63.0f * 255.0f));
}

TEST_F(ImageIo, SrgbDecodeIsApplied) {
    // An 8-bit PNG holding code 128 everywhere, written by OpenImageIO directly.
    const fs::path file = path("code128.png");
    write_with_oiio(file, 2, 2, 3, OIIO::TypeDesc::UINT8, std::vector<float>(12, 128.0f / 255.0f));
    const float expected = srgb_to_linear(128.0f / 255.0f);
    EXPECT_NEAR(expected, 0.2158f, 1e-4f);

    const Result<Image> automatic = load_image(file);
    ASSERT_TRUE(automatic.ok()) << automatic.error().message;
    for (float v : automatic->pixels) EXPECT_NEAR(v, expected, kDecodeTolerance);

    const Result<Image> linear = load_image(file, {ColorEncoding::linear});
    ASSERT_TRUE(linear.ok()) << linear.error().message;
    for (float v : linear->pixels) EXPECT_NEAR(v, 128.0f / 255.0f, kDecodeTolerance);

    const Result<Image> srgb = load_image(file, {ColorEncoding::srgb});
    ASSERT_TRUE(srgb.ok()) << srgb.error().message;
    for (float v : srgb->pixels) EXPECT_NEAR(v, expected, kDecodeTolerance);
}

// fuzz_image_load found it: an RGBE file of huge values, forced to sRGB, decoded to +Inf after
// the check that refuses non-finite values. The decode saturates at the largest float.
TEST_F(ImageIo, SrgbDecodeOfHugeFloatsStaysFinite) {
    const fs::path file = path("huge.exr");
    const float huge = 1e30f, large = 1e15f, two = 2.0f;
    write_with_oiio(file, 3, 1, 1, OIIO::TypeDesc::FLOAT, {huge, large, two});
    const Result<Image> srgb = load_image(file, {ColorEncoding::srgb, NonFinitePolicy::refuse});
    ASSERT_TRUE(srgb.ok()) << srgb.error().message;
    EXPECT_EQ(srgb->pixels[0], std::numeric_limits<float>::max());
    EXPECT_EQ(srgb->pixels[1], srgb_to_linear(large));  // ~9e35: below the saturation
    EXPECT_NEAR(srgb->pixels[2], 4.9538f, 1e-3f);       // ((2 + 0.055) / 1.055)^2.4
}

TEST_F(ImageIo, LinearPngIsTaggedAndLoadedBackLinear) {
    Image image(3, 2, 3, 128.0f / 255.0f);
    const fs::path file = path("data.png");
    ImageSaveOptions options;
    options.encoding = ColorEncoding::linear;
    ASSERT_TRUE(save_image(image, file, options).ok());
    // automatic honours the file's "linear" tag …
    const Result<Image> automatic = load_image(file);
    ASSERT_TRUE(automatic.ok()) << automatic.error().message;
    for (float v : automatic->pixels) EXPECT_NEAR(v, 128.0f / 255.0f, kDecodeTolerance);
    // … and srgb overrides it.
    const Result<Image> srgb = load_image(file, {ColorEncoding::srgb});
    ASSERT_TRUE(srgb.ok()) << srgb.error().message;
    for (float v : srgb->pixels) EXPECT_NEAR(v, srgb_to_linear(128.0f / 255.0f), kDecodeTolerance);
}

TEST_F(ImageIo, SaveClampsAndRoundsIntegerFormats) {
    Image image(4, 1, 1);
    image.pixels = {-0.5f, 2.0f, std::numeric_limits<float>::quiet_NaN(), 0.5f};
    const fs::path file = path("clamp.png");
    ImageSaveOptions options;
    options.encoding = ColorEncoding::linear;
    ASSERT_TRUE(save_image(image, file, options).ok());
    const Result<Image> loaded = load_image(file, {ColorEncoding::linear});
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_EQ(loaded->pixels[0], 0.0f);
    EXPECT_EQ(loaded->pixels[1], 1.0f);
    EXPECT_EQ(loaded->pixels[2], 0.0f);
    EXPECT_NEAR(loaded->pixels[3], 128.0f / 255.0f, kDecodeTolerance);  // 127.5 rounds up
}

TEST_F(ImageIo, TiffRoundTrips8And16Bit) {
    const Image image = make_image(10, 6, 4, 0.0f, 1.0f, 5);
    for (int bits : {8, 16}) {
        const fs::path file = path("tiff" + std::to_string(bits) + ".tif");
        ImageSaveOptions options;
        options.bits = bits;
        ASSERT_TRUE(save_image(image, file, options).ok());
        const Result<Image> loaded = load_image(file);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        expect_same_shape(*loaded, image);
        EXPECT_LE(max_abs_diff(*loaded, image),
                  bits == 8 ? kSrgb8RoundTripTolerance : kSrgb16RoundTripTolerance);
    }
}

TEST_F(ImageIo, HdrRoundTripWithinRgbePrecision) {
    Image image = make_image(9, 7, 3, 0.0f, 50.0f, 6);
    image.pixels[0] = 1e5f;
    const fs::path file = path("rgb.hdr");
    ASSERT_TRUE(save_image(image, file).ok());
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    expect_same_shape(*loaded, image);
    for (std::size_t p = 0; p < image.pixel_count(); ++p) {
        const float* a = image.pixels.data() + 3 * p;
        const float* b = loaded->pixels.data() + 3 * p;
        const float m = std::max({a[0], a[1], a[2]});
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], a[c], kRgbeTolerancePerMax * m);
    }
    EXPECT_GT(loaded->pixels[0], 9e4f);  // HDR values survive
}

TEST_F(ImageIo, HdrReplicatesGreyAndDropsAlpha) {
    const Image grey = make_image(5, 3, 1, 0.0f, 10.0f, 7);
    ASSERT_TRUE(save_image(grey, path("grey.hdr")).ok());
    const Result<Image> g = load_image(path("grey.hdr"));
    ASSERT_TRUE(g.ok()) << g.error().message;
    ASSERT_EQ(g->channels, 3);
    for (std::size_t p = 0; p < grey.pixel_count(); ++p) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(g->pixels[3 * p + c], grey.pixels[p],
                        kRgbeTolerancePerMax * grey.pixels[p]);
        }
    }
    const Image rgba = make_image(5, 3, 4, 0.0f, 10.0f, 8);
    ASSERT_TRUE(save_image(rgba, path("rgba.hdr")).ok());
    const Result<Image> r = load_image(path("rgba.hdr"));
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_EQ(r->channels, 3);
    for (std::size_t p = 0; p < rgba.pixel_count(); ++p) {
        const float* a = rgba.pixels.data() + 4 * p;
        const float m = std::max({a[0], a[1], a[2]});
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(r->pixels[3 * p + c], a[c], kRgbeTolerancePerMax * m);
    }
}

TEST_F(ImageIo, JpegRoundTripOnSmoothImage) {
    Image image(32, 32, 4);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
            image.at(x, y, 0) = srgb_to_linear(0.1f + 0.8f * static_cast<float>(x) / 31.0f);
            image.at(x, y, 1) = srgb_to_linear(0.1f + 0.8f * static_cast<float>(y) / 31.0f);
            image.at(x, y, 2) = srgb_to_linear(0.5f);
            image.at(x, y, 3) = 0.25f;  // dropped: JPEG has no alpha
        }
    }
    const fs::path file = path("smooth.jpg");
    ASSERT_TRUE(save_image(image, file).ok());
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    ASSERT_EQ(loaded->channels, 3);
    float max_error = 0.0f;
    double sum_error = 0.0;
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
            for (int c = 0; c < 3; ++c) {
                const float e = std::fabs(linear_to_srgb(loaded->at(x, y, c)) -
                                          linear_to_srgb(image.at(x, y, c)));
                max_error = std::max(max_error, e);
                sum_error += e;
            }
        }
    }
    EXPECT_LE(max_error, kJpegMaxTolerance);
    EXPECT_LE(sum_error / (32 * 32 * 3), kJpegMeanTolerance);
}

// A 3 x 2 grey EXR whose value at (1, 0) is `bad` and whose other values are 1 … 6, row-major.
fs::path write_exr_with(const fs::path& file, float bad) {
    Image image(3, 2, 1);
    image.pixels = {1.0f, bad, 3.0f, 4.0f, 5.0f, 6.0f};
    EXPECT_TRUE(save_image(image, file).ok());
    return file;
}

TEST_F(ImageIo, NonFiniteValuesAreRefusedNamingTheFileAndTheTexel) {
    const float inf = std::numeric_limits<float>::infinity();
    struct Case {
        float value;
        const char* text;
    };
    for (const Case& c : {Case{std::numeric_limits<float>::quiet_NaN(), "(nan)"},
                          Case{inf, "(inf)"}, Case{-inf, "(-inf)"}}) {
        const fs::path file = write_exr_with(path("bad.exr"), c.value);
        const Result<Image> loaded = load_image(file);
        ASSERT_FALSE(loaded.ok()) << c.text;
        EXPECT_EQ(loaded.error().message,
                  "cannot read " + quoted(file) +
                      ": 1 value is not finite (NaN or infinite), the first at texel (1, 0) "
                      "channel 0 " +
                      c.text);
    }
}

TEST_F(ImageIo, NonFiniteValuesAreCountedAndTheFirstInRowOrderNamed) {
    Image image(4, 3, 3, 0.5f);
    image.at(2, 1)[1] = std::numeric_limits<float>::quiet_NaN();
    image.at(3, 2)[2] = std::numeric_limits<float>::infinity();
    image.at(0, 2)[0] = -std::numeric_limits<float>::infinity();
    const fs::path file = path("three.exr");
    ASSERT_TRUE(save_image(image, file).ok());
    const Result<Image> loaded = load_image(file);
    ASSERT_FALSE(loaded.ok());
    EXPECT_NE(loaded.error().message.find(
                  "3 values are not finite (NaN or infinite), the first at texel (2, 1) channel 1 "
                  "(nan)"),
              std::string::npos)
        << loaded.error().message;
}

TEST_F(ImageIo, NonFiniteValuesRepairedByTheMeanOfFiniteNeighboursWithAWarning) {
    const fs::path file =
        write_exr_with(path("repair.exr"), std::numeric_limits<float>::quiet_NaN());
    ImageLoadOptions options;
    options.non_finite = NonFinitePolicy::repair;
    std::vector<std::string> warnings;
    options.warn = [&](const std::string& message) { warnings.push_back(message); };
    const Result<Image> loaded = load_image(file, options);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    // (1, 0)'s neighbours 1, 3, 4, 5, 6: mean 19/5, both sides the float nearest to 3.8.
    constexpr float kMean = 19.0f / 5.0f;
    EXPECT_EQ(loaded->pixels, (std::vector<float>{1.0f, kMean, 3.0f, 4.0f, 5.0f, 6.0f}));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], quoted(file) +
                               ": replaced 1 non-finite value (NaN or infinite) by the mean of the "
                               "finite neighbours, the first at texel (1, 0) channel 0 (nan)");
}

TEST_F(ImageIo, RepairUsesTheFilesValuesAndZeroWithoutFiniteNeighbours) {
    // Two neighbouring bad values: each is repaired from the finite ones only; a value with no
    // finite neighbour (all of a 2 x 1 image) becomes 0.
    Image image(3, 1, 1);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    image.pixels = {2.0f, nan, nan};
    ASSERT_TRUE(save_image(image, path("pair.exr")).ok());
    Image lonely(2, 1, 1);
    lonely.pixels = {nan, std::numeric_limits<float>::infinity()};
    ASSERT_TRUE(save_image(lonely, path("lonely.exr")).ok());
    ImageLoadOptions options;
    options.non_finite = NonFinitePolicy::repair;
    const Result<Image> pair = load_image(path("pair.exr"), options);
    ASSERT_TRUE(pair.ok()) << pair.error().message;
    EXPECT_EQ(pair->pixels, (std::vector<float>{2.0f, 2.0f, 0.0f}));
    const Result<Image> none = load_image(path("lonely.exr"), options);
    ASSERT_TRUE(none.ok()) << none.error().message;
    EXPECT_EQ(none->pixels, (std::vector<float>{0.0f, 0.0f}));
}

TEST_F(ImageIo, NonFiniteValuesKeptWhenAsked) {
    const fs::path file = write_exr_with(path("keep.exr"), std::numeric_limits<float>::infinity());
    ImageLoadOptions options;
    options.non_finite = NonFinitePolicy::keep;
    const Result<Image> loaded = load_image(file, options);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_TRUE(std::isinf(loaded->pixels[1]));
    EXPECT_EQ(loaded->pixels[0], 1.0f);
}

TEST_F(ImageIo, UppercaseExtensionsWork) {
    const Image image = make_image(3, 3, 3, 0.0f, 1.0f);
    ASSERT_TRUE(save_image(image, path("UPPER.PNG")).ok());
    const Result<Image> loaded = load_image(path("UPPER.PNG"));
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_LE(max_abs_diff(*loaded, image), kSrgb8RoundTripTolerance);
}

TEST_F(ImageIo, SupportedExtensions) {
    for (const char* name :
         {"a.png", "a.jpg", "a.jpeg", "a.exr", "a.hdr", "a.tif", "a.tiff", "dir/A.PNG", "b.Exr"}) {
        EXPECT_TRUE(is_supported_image_extension(name)) << name;
    }
    for (const char* name : {"a.bmp", "a", "png", "a.png.txt", ".png"}) {
        EXPECT_FALSE(is_supported_image_extension(name)) << name;
    }
}

// ---- bad input
// -----------------------------------------------------------------------------------

void expect_load_error(const fs::path& file, const std::string& also = "") {
    const Result<Image> loaded = load_image(file);
    ASSERT_FALSE(loaded.ok()) << file << " loaded as " << loaded->width << "x" << loaded->height;
    const std::string& message = loaded.error().message;
    EXPECT_NE(message.find(quoted(file)), std::string::npos) << message;
    if (!also.empty()) {
        EXPECT_NE(message.find(also), std::string::npos) << message;
    }
}

TEST_F(ImageIo, MissingFileIsAnError) {
    expect_load_error(path("missing.png"), "no such file");
}

TEST_F(ImageIo, DirectoryIsAnError) {
    fs::create_directory(path("sub.png"));
    expect_load_error(path("sub.png"), "directory");
}

TEST_F(ImageIo, EmptyFileIsAnError) {
    write_bytes(path("empty.png"), "");
    expect_load_error(path("empty.png"), "empty");
    write_bytes(path("empty.exr"), "");
    expect_load_error(path("empty.exr"), "empty");
}

TEST_F(ImageIo, TruncatedPngIsAnError) {
    ASSERT_TRUE(save_image(make_image(64, 64, 3, 0.0f, 1.0f), path("trunc.png")).ok());
    truncate_to_half(path("trunc.png"));
    expect_load_error(path("trunc.png"), "truncated");
}

TEST_F(ImageIo, CorruptPngIsAnError) {
    ASSERT_TRUE(save_image(make_image(64, 64, 3, 0.0f, 1.0f), path("corrupt.png")).ok());
    std::string bytes = read_bytes(path("corrupt.png"));
    const std::size_t idat = bytes.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    bytes[idat + 20] = static_cast<char>(bytes[idat + 20] ^ 0x55);
    write_bytes(path("corrupt.png"), bytes);
    expect_load_error(path("corrupt.png"), "corrupt");
}

TEST_F(ImageIo, TruncatedExrIsAnError) {
    ASSERT_TRUE(save_image(make_image(64, 64, 4, 0.0f, 1.0f), path("trunc.exr")).ok());
    truncate_to_half(path("trunc.exr"));
    expect_load_error(path("trunc.exr"));
}

TEST_F(ImageIo, TruncatedJpegIsAnError) {
    ASSERT_TRUE(save_image(make_image(64, 64, 3, 0.0f, 1.0f), path("trunc.jpg")).ok());
    truncate_to_half(path("trunc.jpg"));
    expect_load_error(path("trunc.jpg"));
}

TEST_F(ImageIo, RandomBytesAreAnError) {
    std::mt19937 rng(42);
    std::string bytes(3000, '\0');
    for (char& b : bytes) b = static_cast<char>(rng() & 0xff);
    for (const char* name : {"noise.png", "noise.exr", "noise.jpg", "noise.tif", "noise.hdr"}) {
        write_bytes(path(name), bytes);
        expect_load_error(path(name));
    }
}

TEST_F(ImageIo, PngSignatureFollowedByGarbageIsAnError) {
    std::string bytes = "\x89PNG\r\n\x1a\n";
    bytes += std::string(200, '\x5a');
    write_bytes(path("garbage.png"), bytes);
    expect_load_error(path("garbage.png"));
}

TEST_F(ImageIo, FiveChannelExrIsAnError) {
    const fs::path file = path("five.exr");
    write_with_oiio(file, 3, 2, 5, OIIO::TypeDesc::FLOAT, std::vector<float>(30, 0.5f));
    expect_load_error(file, "5 channels");
}

// OpenImageIO hands a file that the extension's reader refuses to every reader it has; footprint
// reads with the extension's reader only, and says which refused.
TEST_F(ImageIo, OnlyTheExtensionsReaderReadsAFile) {
    const Image image = make_image(4, 4, 3, 0.0f, 1.0f);
    ASSERT_TRUE(save_image(image, path("a.png")).ok());
    const std::string png = read_bytes(path("a.png"));
    for (const auto& [name, reader] :
         {std::pair{"png_named.exr", "openexr reader"}, std::pair{"png_named.tif", "tiff reader"},
          std::pair{"png_named.jpg", "jpeg reader"}, std::pair{"png_named.hdr", "hdr reader"}}) {
        write_bytes(path(name), png);
        expect_load_error(path(name), reader);
        EXPECT_FALSE(is_srgb_encoded(path(name))) << name;
    }
    write_bytes(path("png_named.xyz"), png);
    expect_load_error(path("png_named.xyz"), "no reader for .xyz files");
    write_bytes(path("png_without_extension"), png);
    expect_load_error(path("png_without_extension"), "no extension");
    ASSERT_TRUE(load_image(path("a.png")).ok());
}

#ifdef FOOTPRINT_TEST_DATA_DIR
// tests/data/bad/corrupt_header.exr (fuzz_image_load found it): 2 KB of OpenEXR whose first
// header has a line order of 109 and whose second claims a 2 GB string, on which OpenEXR 3.1's
// C++ reader allocates gigabytes. OpenEXR's core library refuses it before any reader runs,
// whatever the extension.
TEST_F(ImageIo, CorruptExrHeaderIsRefusedBeforeAnyReaderRuns) {
    const fs::path corrupt = fs::path(FOOTPRINT_TEST_DATA_DIR) / "bad" / "corrupt_header.exr";
    const std::string cause =
        "the OpenEXR header is corrupt (OpenEXR: Attribute 'lineOrder' (type 'lineOrder'): "
        "Invalid value 109";
    expect_load_error(corrupt, cause);
    const Result<std::vector<Image>> levels = load_image_levels(corrupt);
    ASSERT_FALSE(levels.ok());
    EXPECT_NE(levels.error().message.find(cause), std::string::npos) << levels.error().message;
    EXPECT_FALSE(is_srgb_encoded(corrupt));
    write_bytes(path("exr_named.tif"), read_bytes(corrupt));
    expect_load_error(path("exr_named.tif"), cause);
}

// tests/data/bad/corrupt_attribute_size.exr (fuzz_image_load): a tiled OpenEXR whose "wrapmodes"
// string claims 1.9 GB. OpenEXR's core library skips that attribute and succeeds, but says so;
// the C++ reader would allocate the 1.9 GB. What the core library says is enough to refuse.
TEST_F(ImageIo, AnExrAttributeTheCoreLibrarySkipsIsRefused) {
    const fs::path corrupt =
        fs::path(FOOTPRINT_TEST_DATA_DIR) / "bad" / "corrupt_attribute_size.exr";
    expect_load_error(corrupt,
                      "the OpenEXR header is corrupt (OpenEXR: Attribute 'wrapmodes', type "
                      "'string': Invalid size 1879074048)");
}

// tests/data/bad/huge_tiles.exr (fuzz_image_load): an 8 x 6 OpenEXR whose tiles claim 16 x
// 1511424 texels, 290 MB that OpenImageIO allocated for every tile it read (2.7 s and 400 MB
// for a 923-byte file). Tiles larger than the image are refused beyond 1024² texels; below that
// they are ordinary (64² tiles of a small image).
TEST_F(ImageIo, TilesFarLargerThanTheImageAreRefused) {
    const fs::path corrupt = fs::path(FOOTPRINT_TEST_DATA_DIR) / "bad" / "huge_tiles.exr";
    expect_load_error(corrupt,
                      "part 0: its tiles (16 x 1511424 texels) are larger than the image "
                      "(8 x 6) and than 1024 x 1024: the header is corrupt");
    // Every TIFF directory is checked, not only the first: this MIP level's tiles would cost
    // OpenImageIO 400 MB a tile read.
    expect_load_error(fs::path(FOOTPRINT_TEST_DATA_DIR) / "bad" / "huge_tiles_level1.tif",
                      "subimage 0, MIP level 1: its tiles (8192 x 16384 texels) are larger than "
                      "the image (16 x 16) and than 1024 x 1024: the header is corrupt");
    for (const int tile : {64, 1024}) {
        const fs::path file = path("tiles" + std::to_string(tile) + ".exr");
        auto out = OIIO::ImageOutput::create(file.string());
        ASSERT_TRUE(out);
        OIIO::ImageSpec spec(8, 6, 1, OIIO::TypeDesc::FLOAT);
        spec.tile_width = spec.tile_height = tile;
        const std::vector<float> texels(48, 0.5f);
        ASSERT_TRUE(out->open(file.string(), spec) &&
                    out->write_image(OIIO::TypeDesc::FLOAT, texels.data()) && out->close());
        const Result<Image> loaded = load_image(file);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        EXPECT_EQ(loaded->pixels, texels);
    }
}

// Writes the input `name` of the fuzz target `target` (tests/data/bad/fuzz/<target>) as `file`:
// the input's first byte picks the extension, which `file` carries instead.
void write_fuzz_input(const std::string& target, const std::string& name, const fs::path& file) {
    const std::string input =
        read_bytes(fs::path(FOOTPRINT_TEST_DATA_DIR) / "bad" / "fuzz" / target / name);
    write_bytes(file, input.substr(1));
}
void write_image_load_input(const std::string& name, const fs::path& file) {
    write_fuzz_input("image_load", name, file);
}

// fuzz_image_load found it: an 885-byte uncompressed OpenEXR whose header claims 268435460 × 1
// RGB texels was allocated (3.2 GB of floats) and read for 88 s before its data ran out.
TEST_F(ImageIo, AFileTooShortForItsUncompressedTexelsIsRefusedBeforeReading) {
    const fs::path file = path("claims_gigabytes.exr");
    write_image_load_input("uncompressed_exr_claims_gigabytes", file);
    expect_load_error(file,
                      "the file is truncated: its header claims 268435460 x 1 texels, more than "
                      "its 885 bytes can hold");
}

// fuzz_image_load found them: zip-compressed OpenEXRs of 1 436 and 2 156 bytes whose headers
// claim 16777224 × 1 and 3145729 × 1 half RGB texels, read for 3 s and 0.9 s (200 s and 26 s
// under AddressSanitizer). Deflate holds at most 1032 bytes in one; the second file would pass at
// a bit a value, not at its channels' 6 bytes a texel.
TEST_F(ImageIo, ADeflatedFileTooShortForItsTexelsIsRefusedBeforeReading) {
    const fs::path file = path("too_short_zip.exr");
    write_image_load_input("zip_exr_too_short_for_its_texels", file);
    expect_load_error(file,
                      "the file is truncated: its header claims 16777224 x 1 texels, more than "
                      "its 1436 bytes can hold");
    write_image_load_input("zip_exr_too_short_for_its_half_texels", file);
    expect_load_error(file,
                      "the file is truncated: its header claims 3145729 x 1 texels, more than "
                      "its 2156 bytes can hold");
}

// fuzz_image_load found it: a 785-byte baseline JPEG whose frame claims 25959 × 27248 grey texels
// in scans of 14 bytes. Its float image was allocated (2.8 GB) and read for 50 s in Release, the
// rows libjpeg filled with grey; `footprint metrics` on it was killed at 23 GB. Each 8 × 8 block
// takes at least a bit of Huffman-coded scan.
TEST_F(ImageIo, AJpegTooShortForItsBlocksIsRefusedBeforeReading) {
    const fs::path file = path("claims_gigabytes.jpg");
    write_image_load_input("jpeg_claims_gigabytes", file);
    expect_load_error(file,
                      "the file is truncated: its header claims 25959 x 27248 texels, more than "
                      "its 14 bytes of scans can hold");
    // A JPEG written here whose frame is made to claim 8192² texels: 128 KB of blocks at least.
    const fs::path grown = path("grown.jpg");
    ASSERT_TRUE(save_image(make_image(64, 64, 3, 0.0f, 1.0f), grown).ok());
    std::string bytes = read_bytes(grown);
    const std::size_t frame = bytes.find("\xff\xc0");
    ASSERT_NE(frame, std::string::npos);
    bytes.replace(frame + 5, 4, std::string("\x20\x00\x20\x00", 4));  // height and width 8192
    write_bytes(grown, bytes);
    expect_load_error(grown, "its header claims 8192 x 8192 texels");
}

// A flat image is the fewest bytes a JPEG's blocks take (the smallest Huffman codes for them):
// flat JPEGs load, baseline and progressive, grey and subsampled colour.
TEST_F(ImageIo, FlatJpegsStillLoad) {
    for (const int channels : {1, 3}) {
        for (const bool progressive : {false, true}) {
            const fs::path file = path("flat.jpg");
            auto out = OIIO::ImageOutput::create(file.string());
            ASSERT_TRUE(out) << OIIO::geterror();
            OIIO::ImageSpec spec(2048, 2048, channels, OIIO::TypeDesc::UINT8);
            spec.attribute("jpeg:progressive", progressive ? 1 : 0);
            ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
            const std::vector<std::uint8_t> flat(std::size_t{2048} * 2048 * channels, 128);
            ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, flat.data())) << out->geterror();
            ASSERT_TRUE(out->close()) << out->geterror();
            const Result<Image> loaded = load_image(file);
            ASSERT_TRUE(loaded) << loaded.error().message << " (" << fs::file_size(file)
                                << " bytes, progressive " << progressive << ")";
            EXPECT_EQ(loaded->width, 2048);
            EXPECT_EQ(loaded->channels, channels);
        }
    }
}

// A flat RGB OpenEXR of `width` × `height` texels of `value`, coded with `compression`: half
// channels, the last of type `last_channel`.
void write_flat_exr(const fs::path& file, int width, int height, const std::string& compression,
                    OIIO::TypeDesc last_channel = OIIO::TypeDesc::HALF, float value = 0.5f) {
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::HALF);
    spec.channelformats = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::HALF, last_channel};
    spec.attribute("compression", compression);
    ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
    const std::vector<float> flat(static_cast<std::size_t>(width) * height * 3, value);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, flat.data())) << out->geterror();
    ASSERT_TRUE(out->close()) << out->geterror();
}

// Sets the last column or row of the OpenEXR `file`'s data window, as a corrupt header would.
enum class WindowEnd { last_column = 8, last_row = 12 };  // where in the box2i value
void set_exr_window_end(const fs::path& file, WindowEnd end, std::int32_t value) {
    std::string bytes = read_bytes(file);
    const std::string attribute("dataWindow\0box2i\0", 17);
    const std::size_t at = bytes.find(attribute);
    ASSERT_NE(at, std::string::npos);
    // The attribute's 4-byte size, then xMin, yMin, xMax, yMax (little-endian).
    std::memcpy(bytes.data() + at + attribute.size() + 4 + static_cast<std::size_t>(end), &value,
                sizeof value);
    write_bytes(file, bytes);
}

// OpenImageIO reads OpenEXR files with OpenEXR's C++ reader, which walks a header its own way (a
// channel list up to its empty name, whatever size it states); the core library, which checks
// headers first, walks by the stated sizes. fuzz_image_load found a header the C++ reader walked
// into an attribute of 1.7 GB, which it allocated (10 s under AddressSanitizer); a header the two
// walk differently is refused, whatever it holds.
TEST_F(ImageIo, AnExrHeaderOpenExrsTwoReadersWalkDifferentlyIsRefused) {
    const fs::path file = path("oversized.exr");
    write_image_load_input("exr_attribute_longer_than_the_file_to_the_cxx_reader", file);
    expect_load_error(file, "its attribute 'screenWindowWi' claims more bytes than the file holds");

    // A channel list whose stated size leaves out its closing empty name, as in the fuzz input:
    // the core library ends the list at that size and reads the empty name as the end of the
    // header; the C++ reader ends the list at the empty name and reads on.
    const fs::path ghost = path("short_channel_list.exr");
    write_flat_exr(ghost, 4, 4, "zip");
    std::string bytes = read_bytes(ghost);
    const std::string chlist("channels\0chlist\0", 16);
    const std::size_t size_at = bytes.find(chlist) + chlist.size();
    std::uint32_t size = 0;
    std::memcpy(&size, bytes.data() + size_at, sizeof size);
    --size;
    std::memcpy(bytes.data() + size_at, &size, sizeof size);
    write_bytes(ghost, bytes);
    expect_load_error(ghost, "OpenEXR's two readers read it differently");
}

TEST_F(ImageIo, AnExrTooShortForItsChunksIsRefusedBeforeReading) {
    // PIZ codes 32 rows a chunk and has no bound on its ratio; ten million rows take 312 500
    // chunks, each an 8-byte table entry and a header of at least 8 bytes.
    const fs::path file = path("claims_chunks.exr");
    write_flat_exr(file, 4, 64, "piz");
    set_exr_window_end(file, WindowEnd::last_row, 9'999'999);
    expect_load_error(file, "the file is truncated: its header claims 4 x 10000000 texels");
}

// A chunk whose codec unpacks fewer bytes than its rows take: OpenEXR 3.1's C++ reader,
// OpenImageIO's, left the rest of its rows as they were, without an error (a flat 64 × 1 zip file
// of half RGB widened to 1 000 texels loaded with 192 of its 3 000 values set), and read an
// uncompressed chunk's rows on past its end. Such texels are decoded through OpenEXR's core
// library, which checks every chunk's size; the C++ reader's other decoders refuse such a chunk.
TEST_F(ImageIo, AnExrChunkThatUnpacksShortIsRefused) {
    const fs::path file = path("widened.exr");
    for (const std::string compression : {"zip", "zips", "rle"}) {
        SCOPED_TRACE(compression);
        write_flat_exr(file, 64, 1, compression);
        set_exr_window_end(file, WindowEnd::last_column, 999);
        expect_load_error(file,
                          "chunk 0 (rows 0 to 0) is corrupt or unpacks to fewer bytes than "
                          "its rows take");
    }
    // Uncompressed, one row a chunk: 65 columns fit the file's bytes, not its first chunk's.
    write_flat_exr(file, 64, 64, "none");
    set_exr_window_end(file, WindowEnd::last_column, 64);
    expect_load_error(file, "chunk 0 (rows 0 to 0) holds 384 bytes, but its rows take 390");
    for (const std::string compression : {"piz", "pxr24", "b44", "b44a", "dwaa", "dwab"}) {
        SCOPED_TRACE(compression);
        write_flat_exr(file, 64, 1, compression);
        set_exr_window_end(file, WindowEnd::last_column, 99);
        expect_load_error(file);
    }
    // A tile, widened within itself (64 × 64 tiles; 40 × 1 texels made 60 × 1).
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(40, 1, 3, OIIO::TypeDesc::HALF);
    spec.tile_width = spec.tile_height = 64;
    spec.attribute("compression", "zip");
    ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
    const std::vector<float> flat(40 * 3, 0.5f);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, flat.data())) << out->geterror();
    ASSERT_TRUE(out->close()) << out->geterror();
    ASSERT_TRUE(load_image(file));
    set_exr_window_end(file, WindowEnd::last_column, 59);
    expect_load_error(file, "the chunk of tile (0, 0) is corrupt or unpacks to fewer bytes");
}

// OpenEXR texels are decoded through OpenEXR's core library (the test above), not OpenImageIO's
// reader; a valid file reads to the very floats OpenImageIO reads, whatever its codec, channel
// types, data window and layout (scanlines, tiles, MIP levels).
TEST_F(ImageIo, ExrTexelsAreTheFloatsOpenImageIoReads) {
    struct Layout {
        int width, height, tile;  // tile 0: scanlines
        bool mip;
    };
    const std::vector<std::vector<OIIO::TypeDesc>> types = {
        {OIIO::TypeDesc::HALF, OIIO::TypeDesc::HALF, OIIO::TypeDesc::HALF, OIIO::TypeDesc::HALF},
        {OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT},
        {OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::UINT},
        {OIIO::TypeDesc::HALF}};
    const fs::path file = path("texels.exr");
    for (const std::string compression :
         {"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"}) {
        for (const Layout layout :
             {Layout{301, 77, 0, false}, Layout{300, 70, 32, false}, Layout{129, 67, 16, true}}) {
            for (const auto& channel_types : types) {
                const int channels = static_cast<int>(channel_types.size());
                SCOPED_TRACE(compression + ", " + std::to_string(channels) + " channels, tile " +
                             std::to_string(layout.tile));
                auto out = OIIO::ImageOutput::create(file.string());
                ASSERT_TRUE(out) << OIIO::geterror();
                OIIO::ImageSpec spec(layout.width, layout.height, channels, channel_types[0]);
                spec.channelformats = channel_types;
                spec.x = -3;
                spec.y = 5;
                spec.full_width = layout.width + 10;
                spec.full_height = layout.height + 10;
                spec.tile_width = spec.tile_height = layout.tile;
                spec.attribute("compression", compression);
                const Image pixels = make_image(layout.width, layout.height, channels, -2.0f, 40.0f,
                                                static_cast<unsigned>(channels * 7 + layout.tile));
                if (layout.mip) {
                    spec.attribute("openexr:levelmode", 1);     // MIPMAP_LEVELS
                    spec.attribute("openexr:roundingmode", 0);  // down
                    spec.attribute("textureformat", "Plain Texture");
                }
                ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
                ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.pixels.data()))
                    << out->geterror();
                int levels = 1;
                for (OIIO::ImageSpec level = spec;
                     layout.mip && (level.width > 1 || level.height > 1);
                     ++levels) {  // every level down to 1 × 1
                    level.width = std::max(level.width / 2, 1);
                    level.height = std::max(level.height / 2, 1);
                    ASSERT_TRUE(out->open(file.string(), level, OIIO::ImageOutput::AppendMIPLevel))
                        << out->geterror();
                    const Image small = make_image(level.width, level.height, channels, 0.0f, 1.0f,
                                                   static_cast<unsigned>(levels));
                    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, small.pixels.data()))
                        << out->geterror();
                }
                ASSERT_TRUE(out->close()) << out->geterror();
                out.reset();  // a tiled file's chunk tables are written as the writer goes

                auto in = OIIO::ImageInput::open(file.string());
                ASSERT_TRUE(in) << OIIO::geterror();
                Result<std::vector<Image>> loaded = load_image_levels(file);
                ASSERT_TRUE(loaded) << loaded.error().message;
                for (int level = 0; level < static_cast<int>(loaded->size()); ++level) {
                    ASSERT_TRUE(in->seek_subimage(0, level));
                    const OIIO::ImageSpec& read = in->spec();
                    std::vector<float> expected(static_cast<std::size_t>(read.width) * read.height *
                                                read.nchannels);
                    ASSERT_TRUE(in->read_image(0, level, 0, read.nchannels, OIIO::TypeDesc::FLOAT,
                                               expected.data()))
                        << in->geterror();
                    const Image& got = (*loaded)[level];
                    ASSERT_EQ(got.pixels.size(), expected.size());
                    EXPECT_EQ(std::memcmp(got.pixels.data(), expected.data(),
                                          expected.size() * sizeof(float)),
                              0)
                        << "level " << level;
                }
                EXPECT_EQ(static_cast<int>(loaded->size()), levels);
            }
        }
    }
}

// fuzz_texture_file found it (run 4a): a 451-byte B44A OpenEXR whose header claims 3080193 × 1
// texels of two half channels and a uint channel was allocated and read before its only chunk
// failed: 1.6 s and 210 MB for the fuzz input's opens in Release, 159 s under AddressSanitizer. B44
// codes a 4 × 4 block of a half channel in 3 bytes at the fewest (B44A's flat block) and leaves
// uint and float channels as they are; PIZ, at most 255 of its 16-bit words in 9 bits.
TEST_F(ImageIo, AB44OrPizFileTooShortForItsTexelsIsRefusedBeforeReading) {
    const fs::path file = path("too_short_b44a.exr");
    write_fuzz_input("texture_file", "b44a_exr_too_short_for_its_texels", file);
    expect_load_error(file,
                      "the file is truncated: its header claims 3080193 x 1 texels, more than "
                      "its 451 bytes can hold");
    // Half channels only, in one chunk: 100 000 × 1 texels take 56 KB of B44's flat blocks, 1.3 KB
    // of PIZ's runs.
    for (const std::string compression : {"b44", "b44a", "piz"}) {
        write_flat_exr(file, 64, 1, compression);
        set_exr_window_end(file, WindowEnd::last_column, 99'999);
        expect_load_error(file, "the file is truncated: its header claims 100000 x 1 texels");
    }
}

// An OpenEXR's float and uint values take 4 bytes each before a lossless codec packs them, PXR24's
// floats 3; counted as halves, a file could claim twice the texels its bytes hold.
// fuzz_texture_file found one (run 4j, the input of fix 13): a 3 406-byte zip file of 524 328 × 1
// texels, which 2 bytes a value let through.
TEST_F(ImageIo, AnExrIsHeldToTheBytesOfItsChannelsTypes) {
    const fs::path fuzz = path("half_million_by_one.exr");
    write_fuzz_input("texture_file", "exr_half_million_by_one_texels", fuzz);
    expect_load_error(fuzz,
                      "the file is truncated: its header claims 524328 x 1 texels, more than its "
                      "3406 bytes can hold");
    // Two half channels and a float one, a row made wide enough for a file of halves but not for
    // the float: 8 bytes a texel (7 in PXR24) where halves would take 6.
    for (const auto& [compression, bytes] : {std::pair{"zip", 7.0}, std::pair{"pxr24", 6.5}}) {
        const fs::path file = path(std::string("float_") + compression + ".exr");
        write_flat_exr(file, 64, 1, compression, OIIO::TypeDesc::FLOAT);
        const auto width = static_cast<std::int32_t>(fs::file_size(file) * 1032 / bytes);
        set_exr_window_end(file, WindowEnd::last_column, width - 1);
        expect_load_error(file, "its header claims " + std::to_string(width) + " x 1 texels");
    }
}

TEST_F(ImageIo, SmallCompressedExrFilesStillLoad) {
    // The bounds on compressed OpenEXR files must not refuse the smallest honest ones: flat
    // images, below a bit a texel where deflated, which a bound for uncompressed files would
    // refuse; B44's flat blocks, next to a float channel it leaves as it is.
    for (const std::string compression : {"zip", "zips", "rle", "pxr24", "piz", "b44", "b44a"}) {
        for (const OIIO::TypeDesc last_channel : {OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT}) {
            const fs::path file = path("flat_" + compression + "_" + last_channel.c_str() + ".exr");
            write_flat_exr(file, 1024, 512, compression, last_channel);
            const Result<Image> loaded = load_image(file);
            ASSERT_TRUE(loaded.ok()) << compression << ": " << loaded.error().message;
            EXPECT_EQ(loaded->pixels, std::vector<float>(1024 * 512 * 3, 0.5f)) << compression;
        }
    }
    EXPECT_LT(fs::file_size(path("flat_zip_half.exr")), 1024u * 512 * 3 / 8);
    // 3 bytes a 4 × 4 block of each channel: the fewest B44A allows.
    EXPECT_LT(fs::file_size(path("flat_b44a_half.exr")), 1024u * 512 * 3 * 3 / 16 + 4096);
    // PIZ codes zeros best, in runs of 255 words: within a fifth of the fewest bytes it allows.
    write_flat_exr(path("zero_piz.exr"), 4096, 512, "piz", OIIO::TypeDesc::HALF, 0.0f);
    EXPECT_LT(fs::file_size(path("zero_piz.exr")), 4096u * 512 * 3 * 2 / 454 * 120 / 100);
    const Result<Image> zeros = load_image(path("zero_piz.exr"));
    ASSERT_TRUE(zeros.ok()) << zeros.error().message;
    EXPECT_EQ(zeros->pixels, std::vector<float>(4096 * 512 * 3, 0.0f));
}

// OpenEXR writes a file's chunk tables last: an 8-byte entry for each chunk (a block of rows or a
// tile), its place in the file. The places the tables of the OpenEXR `bytes`, `chunks` entries,
// hold; nothing if there are none. OpenEXR writes the chunks just after the tables, so the first
// entry holds the place just past them.
std::vector<std::uint64_t> exr_tables(const std::string& bytes, std::size_t chunks) {
    for (std::size_t at = 0; at + 8 * chunks <= bytes.size(); ++at) {
        std::uint64_t first = 0;
        std::memcpy(&first, bytes.data() + at, sizeof first);
        if (first != at + 8 * chunks) continue;
        std::vector<std::uint64_t> places(chunks);
        std::memcpy(places.data(), bytes.data() + at, 8 * chunks);
        return places;
    }
    return {};
}

// Sets every entry of the tables of `bytes` to 0, as a writer that stopped before it wrote them
// leaves them; returns the places they held.
std::vector<std::uint64_t> zero_exr_tables(std::string& bytes, std::size_t chunks) {
    const std::vector<std::uint64_t> places = exr_tables(bytes, chunks);
    if (places.empty()) return places;
    const std::size_t at = places[0] - 8 * chunks;
    std::fill_n(bytes.begin() + static_cast<std::ptrdiff_t>(at), 8 * chunks, '\0');
    return places;
}

// OpenImageIO's writer, which save_image_levels() calls, writes a tiled file's tables as it is
// destroyed; destroyed after its bytes had moved out, it left them 0, and each reader had to find
// the tiles by walking them. Each entry is the place of a tile: in the file, after the tables,
// each further than the last.
TEST_F(ImageIo, MipLevelsAreWrittenWithTheirChunkTables) {
    // 37 × 20 texels in tiles of 16²: 6 + 2 + 1 + 1 + 1 + 1 tiles over its six levels; 16 × 16
    // texels, one tile on each of five levels.
    LevelsSaveOptions options;
    options.tile_size = 16;
    const fs::path one = path("one.exr"), two = path("two.exr");
    ASSERT_TRUE(save_image_levels(mip_chain(37, 20, 3), one, options).ok());
    ASSERT_TRUE(save_image_level_chains({{"a", mip_chain(37, 20, 3)}, {"b", mip_chain(16, 16, 1)}},
                                        two, options)
                    .ok());
    for (const auto& [file, chunks] : {std::pair{one, 12u}, std::pair{two, 12u + 5u}}) {
        const std::string bytes = read_bytes(file);
        const std::vector<std::uint64_t> places = exr_tables(bytes, chunks);
        ASSERT_EQ(places.size(), chunks) << file << " has no chunk tables";
        EXPECT_TRUE(std::is_sorted(places.begin(), places.end())) << file;
        EXPECT_EQ(std::adjacent_find(places.begin(), places.end()), places.end()) << file;
        EXPECT_LT(places.back(), bytes.size()) << file;
    }
}

// Sets the 4-byte value `at` bytes into the chunk at `place` in `bytes`.
void set_chunk_leader(std::string& bytes, std::uint64_t place, std::size_t at,
                      std::uint32_t value) {
    std::memcpy(bytes.data() + place + at, &value, sizeof value);
}

// As fuzz_texture_file's input of fix 13 was: a file whose chunk table misses an entry, and whose
// chunk there holds no bytes. OpenEXR's C++ reader, OpenImageIO's, takes a table with an entry of 0
// for one whose writer stopped and finds the chunks by walking them; it read the empty chunk as
// zeros without an error, and footprint loaded a black image.
TEST_F(ImageIo, AChunkMissingFromItsExrTableAndEmptyIsRefusedNotReadAsZeros) {
    // 64 × 64 texels of 0.5 in four chunks of 16 rows. With no tables, OpenEXR finds the chunks by
    // walking them and the file loads whole; with the last chunk emptied as well (its leader: its
    // first row, then its size), its rows read as zeros.
    const fs::path file = path("no_tables.exr");
    write_flat_exr(file, 64, 64, "zip");
    std::string bytes = read_bytes(file);
    const std::vector<std::uint64_t> places = zero_exr_tables(bytes, 4);
    ASSERT_EQ(places.size(), 4u);
    write_bytes(file, bytes);
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_EQ(loaded->pixels, std::vector<float>(64 * 64 * 3, 0.5f));
    set_chunk_leader(bytes, places.back(), 4, 0);
    write_bytes(file, bytes);
    expect_load_error(file,
                      "a chunk of texels is missing or corrupt; OpenEXR: Invalid packed size");
}

// The same for tiles, level by level, and for each part of a file of several.
TEST_F(ImageIo, ATileMissingFromItsExrTableAndEmptyIsRefused) {
    // As in MipLevelsAreWrittenWithTheirChunkTables.
    const std::vector<Image> levels = mip_chain(37, 20, 3), small = mip_chain(16, 16, 3);
    LevelsSaveOptions options;
    options.tile_size = 16;
    const fs::path one = path("no_tables_tiled.exr"), two = path("no_tables_parts.exr");
    ASSERT_TRUE(save_image_levels(levels, one, options).ok());
    ASSERT_TRUE(save_image_level_chains({{"a", levels}, {"b", small}}, two, options).ok());
    // A tile's leader: its column, row and levels (4 bytes each), then its size; in a file of
    // several parts, after the part's number.
    for (const auto& [file, chunks, size_at] :
         {std::tuple{one, 12, 16}, std::tuple{two, 12 + 5, 20}}) {
        std::string bytes = read_bytes(file);
        const std::vector<std::uint64_t> places =
            zero_exr_tables(bytes, static_cast<std::size_t>(chunks));
        ASSERT_EQ(places.size(), static_cast<std::size_t>(chunks)) << file;
        write_bytes(file, bytes);
        const Result<std::vector<Image>> loaded = load_image_levels(file);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        ASSERT_EQ(loaded->size(), levels.size());
        for (std::size_t l = 0; l < levels.size(); ++l)
            EXPECT_EQ((*loaded)[l].pixels, levels[l].pixels) << file << ", level " << l;
        set_chunk_leader(bytes, places.back(), static_cast<std::size_t>(size_at), 0);
        write_bytes(file, bytes);
        expect_load_error(file, "a chunk of texels is missing or corrupt");
    }
    const Result<Image> parts = load_image(two);
    ASSERT_FALSE(parts.ok());
    EXPECT_NE(parts.error().message.find("(part 1: a chunk"), std::string::npos)
        << parts.error().message;
}

// fuzz_image_load found it: OpenImageIO 2.4, reading several rows of a deflated MinIsWhite TIFF
// at once, inverted channels × the strip's values per strip and wrote past the caller's buffer
// (upstream #5083); the 445-byte file's 4 × 260 texels of four channels corrupted the heap, and
// the process aborted. Read a row at a time, it is refused: its only strip is short.
TEST_F(ImageIo, AMinIsWhiteTiffOfSeveralChannelsDoesNotOverrunTheBuffer) {
    const fs::path file = path("minisWhite_overrun.tif");
    write_image_load_input("tiff_miniswhite_strips_overrun", file);
    expect_load_error(file, "the file is truncated or corrupt");
}

TEST_F(ImageIo, DeflatedMinIsWhiteTiffsOfSeveralStripsLoadInverted) {
    // Grey and alpha, 8 bits, deflated, 8 rows a strip: the file the overrun above needs, honest.
    constexpr int kWidth = 5, kHeight = 37, kRowsPerStrip = 8;
    const fs::path file = path("miniswhite.tif");
    TIFF* tiff = TIFFOpen(file.c_str(), "w");
    ASSERT_NE(tiff, nullptr);
    const std::uint16_t extra[] = {EXTRASAMPLE_UNASSALPHA};
    TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, kWidth);
    TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, kHeight);
    TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, 2);
    TIFFSetField(tiff, TIFFTAG_EXTRASAMPLES, 1, extra);
    TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, 8);
    TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISWHITE);
    TIFFSetField(tiff, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(tiff, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
    TIFFSetField(tiff, TIFFTAG_ROWSPERSTRIP, kRowsPerStrip);
    const auto stored = [](int x, int y) { return static_cast<std::uint8_t>(x * 40 + y * 3); };
    for (int y = 0; y < kHeight; ++y) {
        std::array<std::uint8_t, 2 * kWidth> row{};
        for (int x = 0; x < kWidth; ++x) row[2 * x] = stored(x, y);
        ASSERT_EQ(TIFFWriteScanline(tiff, row.data(), y, 0), 1);
    }
    TIFFClose(tiff);

    const Result<Image> loaded = load_image(file, {.encoding = ColorEncoding::linear});
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    ASSERT_EQ(loaded->channels, 2);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            ASSERT_FLOAT_EQ(loaded->at(x, y, 0), (255 - stored(x, y)) / 255.0f) << x << ", " << y;
}

// The bytes of an 8 × 8 grey JPEG OpenImageIO writes (at `file`), with a marker block of `code`
// holding `data` inserted after its SOI.
std::string jpeg_with_block(const fs::path& file, unsigned char code, const std::string& data) {
    write_with_oiio(file, 8, 8, 3, OIIO::TypeDesc::UINT8, std::vector<float>(8 * 8 * 3, 0.5f));
    const std::string jpeg = read_bytes(file);
    const std::size_t length = data.size() + 2;
    return jpeg.substr(0, 2) + std::string{'\xff', static_cast<char>(code)} +
           static_cast<char>(length >> 8) + static_cast<char>(length & 0xff) + data +
           jpeg.substr(2);
}

// fuzz_image_load found it: OpenImageIO 2.4 trusted the length inside a JPEG's IPTC block, 20 480
// bytes in an APP13 block of 106, and read past it (upstream #5081). Its reader also compares the
// start of each APP1, APP2 and APP13 block with an identifier as a C string, and skips or
// subtracts the identifier's length, whether or not the block holds it (#5174).
TEST_F(ImageIo, JpegBlocksOpenImageIOWouldReadPastAreRefused) {
    const fs::path file = path("iptc.jpg");
    write_image_load_input("jpeg_iptc_longer_than_its_block", file);
    expect_load_error(file, "its JPEG IPTC block claims more bytes than its APP13 block holds");

    // An IPTC block of 16 bytes in room for 1.
    const std::string iptc_too_long = std::string(
                                          "Photoshop 3.0\0"
                                          "8BIM\4\4\0\0\0\0\0\x10",
                                          26) +
                                      "x";
    const struct {
        const char* name;
        unsigned char code;
        std::string data;
        const char* cause;
    } cases[] = {{"exif", 0xe1, std::string("Exif\0", 5), "APP1 block is cut short"},
                 {"xmp", 0xe1, "http://ns.adobe.com/xap/1.0/", "APP1 block is cut short"},
                 {"icc", 0xe2, std::string("ICC_PROFILE\0\1", 13), "APP2 block is cut short"},
                 {"iptc", 0xed,
                  std::string("Photoshop 3.0\0"
                              "8BIM\4\4",
                              20),
                  "APP13 block is cut short"},
                 {"iptc_size", 0xed, iptc_too_long, "its JPEG IPTC block claims more bytes"}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path bad = path(std::string(c.name) + ".jpg");
        write_bytes(bad, jpeg_with_block(bad, c.code, c.data));
        expect_load_error(bad, c.cause);
    }

    // fuzz_image_load found it (run 7g): the bytes FF 00 before such a block, which libjpeg skips
    // as stray bytes, were taken for a marker with a length, and the walk stepped over the block.
    write_image_load_input("jpeg_iptc_after_a_stuffed_zero", file);
    expect_load_error(file, "its JPEG IPTC block claims more bytes than its APP13 block holds");
    const fs::path stuffed = path("stuffed.jpg");
    std::string bytes = jpeg_with_block(stuffed, 0xed, iptc_too_long);
    bytes.insert(2, "\xff\x00", 2);
    write_bytes(stuffed, bytes);
    expect_load_error(stuffed, "its JPEG IPTC block claims more bytes than its APP13 block holds");
}

// OpenImageIO 2.4's Exif decoder reads an 8-byte header whatever the block's size, the entry
// count of a sub-directory whose offset is the block's last byte, and an entry of a type beyond
// its table (Exif 3.0's UTF-8, 129) as 2^64 − 1 bytes, which wraps its bounds check (upstream
// #5322, #5399).
// An Exif block: "Exif\0\0", a little-endian TIFF header, IFD0 at 8 holding `entries` (12 bytes
// each), and no next directory.
std::string exif(const std::string& entries) {
    const char count = static_cast<char>(entries.size() / 12);
    return std::string("Exif\0\0II*\0\x08\0\0\0", 14) + count + '\0' + entries +
           std::string(4, '\0');
}

// An Exif directory entry of one value (little-endian).
std::string entry(std::uint16_t tag, std::uint16_t type, std::uint32_t value) {
    std::string e(12, '\0');
    std::memcpy(e.data(), &tag, 2);
    std::memcpy(e.data() + 2, &type, 2);
    e[4] = 1;  // count
    std::memcpy(e.data() + 8, &value, 4);
    return e;
}

TEST_F(ImageIo, ExifBlocksOpenImageIOWouldReadPastAreRefused) {
    const std::string two_entries = exif(entry(0x0112, 3, 1) + entry(0x8769, 4, 0));
    const struct {
        const char* name;
        std::string block;
        const char* cause;
    } cases[] = {
        {"short", std::string("Exif\0\0II*\0", 10), "its Exif block is cut short"},
        {"utf8", exif(entry(0x010e, 129, 0x41)), "an entry of type 129"},
        // The Exif directory's offset: the block's last byte (its length less the "Exif\0\0").
        {"last_byte",
         exif(entry(0x0112, 3, 1) +
              entry(0x8769, 4, static_cast<std::uint32_t>(two_entries.size() - 6 - 1))),
         "a directory at its last byte"}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path bad = path(std::string(c.name) + ".jpg");
        write_bytes(bad, jpeg_with_block(bad, 0xe1, c.block));
        expect_load_error(bad, c.cause);
    }
}

// A PNG OpenImageIO writes (at `file`), with a chunk of `type` holding `data` after its IHDR.
std::string png_with_chunk(const fs::path& file, const std::string& type, const std::string& data) {
    write_with_oiio(file, 8, 8, 3, OIIO::TypeDesc::UINT8, std::vector<float>(8 * 8 * 3, 0.5f));
    const std::string png = read_bytes(file);
    const auto big_endian = [](std::uint32_t v) {
        return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                           static_cast<char>(v >> 8), static_cast<char>(v)};
    };
    const std::string checked = type + data;
    const auto crc = static_cast<std::uint32_t>(crc32(
        0, reinterpret_cast<const Bytef*>(checked.data()), static_cast<uInt>(checked.size())));
    const std::size_t after_ihdr = 8 + 8 + 13 + 4;
    return png.substr(0, after_ihdr) + big_endian(static_cast<std::uint32_t>(data.size())) + type +
           data + big_endian(crc) + png.substr(after_ihdr);
}

// OpenImageIO 2.4 hands a PNG's eXIf chunk, and the hex digits of a "Raw profile type exif" text
// (ImageMagick's; libpng inflates zTXt and iTXt), to the same Exif decoder.
TEST_F(ImageIo, PngExifOpenImageIOWouldReadPastIsRefused) {
    std::string hex = "\nexif\n      30\n";
    for (const char byte : exif(entry(0x010e, 129, 0x41))) {
        constexpr char kDigits[] = "0123456789abcdef";
        hex += kDigits[static_cast<unsigned char>(byte) >> 4];
        hex += kDigits[static_cast<unsigned char>(byte) & 15];
    }
    const fs::path file = path("exif.png");
    write_bytes(file, png_with_chunk(file, "eXIf", exif(entry(0x010e, 129, 0x41)).substr(6)));
    expect_load_error(file, "an entry of type 129");
    const std::string keyword("Raw profile type exif\0", 22);
    write_bytes(file, png_with_chunk(file, "tEXt", keyword + hex));
    expect_load_error(file, "an entry of type 129");
    // Compressed, as ImageMagick writes it: zTXt (method 0, a zlib stream), iTXt (flag 1, method
    // 0, no language or translated keyword).
    std::string deflated(compressBound(static_cast<uLong>(hex.size())), '\0');
    uLongf deflated_size = static_cast<uLongf>(deflated.size());
    ASSERT_EQ(compress(reinterpret_cast<Bytef*>(deflated.data()), &deflated_size,
                       reinterpret_cast<const Bytef*>(hex.data()), static_cast<uLong>(hex.size())),
              Z_OK);
    deflated.resize(deflated_size);
    write_bytes(file, png_with_chunk(file, "zTXt", keyword + '\0' + deflated));
    expect_load_error(file, "an entry of type 129");
    write_bytes(file,
                png_with_chunk(file, "iTXt", keyword + std::string("\1\0\0\0", 4) + deflated));
    expect_load_error(file, "an entry of type 129");

    // The same blocks of an honest entry load.
    write_bytes(file, png_with_chunk(file, "eXIf", exif(entry(0x0112, 3, 1)).substr(6)));
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
}

TEST_F(ImageIo, JpegsWithExifAndIptcBlocksStillLoad) {
    const fs::path file = path("tagged.jpg");
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(8, 8, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("IPTC:Caption", "a caption long enough to matter");
    spec.attribute("Exif:ExposureTime", 0.01f);
    spec.attribute("ImageDescription", "described");
    const std::vector<float> grey(8 * 8 * 3, 0.5f);
    ASSERT_TRUE(out->open(file.string(), spec) &&
                out->write_image(OIIO::TypeDesc::FLOAT, grey.data()) && out->close())
        << out->geterror();
    const std::string bytes = read_bytes(file);
    ASSERT_NE(bytes.find("Photoshop 3.0"), std::string::npos);
    ASSERT_NE(bytes.find("Exif"), std::string::npos);
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_EQ(loaded->width, 8);
}

// A 32 × 32 CMYK TIFF of `bits`-bit samples, in 16² tiles or strips of 8 rows.
void write_cmyk_tiff(const fs::path& file, int bits, bool tiled) {
    constexpr int kSize = 32, kTile = 16;
    TIFF* tiff = TIFFOpen(file.c_str(), "w");
    ASSERT_NE(tiff, nullptr);
    TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, kSize);
    TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, kSize);
    TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, 4);
    TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, bits);
    TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_SEPARATED);
    TIFFSetField(tiff, TIFFTAG_INKSET, INKSET_CMYK);
    TIFFSetField(tiff, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    std::vector<std::uint8_t> inks(kSize * kSize * 4, 0x40);  // every 8-bit sample 1/4
    if (tiled) {
        TIFFSetField(tiff, TIFFTAG_TILEWIDTH, kTile);
        TIFFSetField(tiff, TIFFTAG_TILELENGTH, kTile);
        for (int y = 0; y < kSize; y += kTile)
            for (int x = 0; x < kSize; x += kTile)
                ASSERT_GT(TIFFWriteTile(tiff, inks.data(), x, y, 0, 0), 0);
    } else {
        TIFFSetField(tiff, TIFFTAG_ROWSPERSTRIP, 8);
        for (int y = 0; y < kSize; ++y) ASSERT_EQ(TIFFWriteScanline(tiff, inks.data(), y, 0), 1);
    }
    TIFFClose(tiff);
}

// OpenImageIO 2.4 converts CMYK to RGB, but reading a tile, or a row of fewer than 8 bits a
// sample, it writes the file's four channels into room for three (measured: 256 bytes past a
// 16² tile, 32 past a row of 32); upstream #5082 and #5296.
TEST_F(ImageIo, CmykTiffsOpenImageIOOverrunsAreRefused) {
    const struct {
        const char* name;
        int bits;
        bool tiled;
        const char* cause;
    } cases[] = {{"cmyk_tiled.tif", 8, true, "it is a CMYK TIFF in tiles"},
                 {"cmyk_1bit.tif", 1, false, "it is a CMYK TIFF of 1-bit samples"},
                 {"cmyk_4bit.tif", 4, false, "it is a CMYK TIFF of 4-bit samples"}};
    for (const auto& c : cases) {
        const fs::path file = path(c.name);
        write_cmyk_tiff(file, c.bits, c.tiled);
        expect_load_error(file, c.cause);
    }
}

TEST_F(ImageIo, EightBitCmykTiffsOfStripsLoadAsRgb) {
    // (1 − C)(1 − K) with C = K = 64/255, the conversion OpenImageIO does.
    const fs::path file = path("cmyk_strips.tif");
    write_cmyk_tiff(file, 8, false);
    const Result<Image> loaded = load_image(file, {.encoding = ColorEncoding::linear});
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    ASSERT_EQ(loaded->channels, 3);
    const float ink = 1.0f - 64.0f / 255.0f;
    for (const float v : loaded->pixels) ASSERT_NEAR(v, ink * ink, 1.0f / 255);
}

TEST_F(ImageIo, ARadianceFileTooShortForItsRunLengthsIsRefusedBeforeReading) {
    const fs::path file = path("claims_gigabytes.hdr");
    write_image_load_input("radiance_claims_gigabytes", file);
    expect_load_error(file,
                      "the file is truncated: its header claims 88888888 x 4 texels, more than "
                      "its 133 bytes can hold");
}

TEST_F(ImageIo, ATiffOfACodecLibtiffLacksIsRefusedBeforeReading) {
    const fs::path file = path("unknown_codec.tif");
    write_image_load_input("tiff_codec_libtiff_lacks", file);
    expect_load_error(file, "its compression (TIFF code 10248) is not one libtiff can decode");
}

TEST_F(ImageIo, SmallRunLengthCodedRadianceFilesStillLoad) {
    // The bound on Radiance files must not refuse the smallest honest ones: a flat image, coded
    // in the fewest runs Radiance allows. The widest is below a bit a texel, which a bound for
    // uncompressed files would refuse.
    for (const int width : {8, 127, 128, 1000}) {
        Image flat(width, 3, 3);
        std::fill(flat.pixels.begin(), flat.pixels.end(), 0.5f);
        const fs::path file = path("flat_" + std::to_string(width) + ".hdr");
        ASSERT_TRUE(save_image(flat, file).ok());
        const Result<Image> loaded = load_image(file);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        EXPECT_EQ(loaded->pixels, flat.pixels) << width;
    }
    EXPECT_LT(fs::file_size(path("flat_1000.hdr")), 1000u * 3 / 8);
}

TEST_F(ImageIo, BadFilesInTestDataAreErrors) {
    const fs::path bad = fs::path(FOOTPRINT_TEST_DATA_DIR) / "bad";
    ASSERT_TRUE(fs::is_directory(bad)) << bad;
    int count = 0;
    for (const auto& entry : fs::directory_iterator(bad)) {
        if (!entry.is_regular_file() || entry.path().filename() == "README.md") continue;
        expect_load_error(entry.path());
        ++count;
    }
    EXPECT_GT(count, 0);
}
#endif

// ---- save failures
// -------------------------------------------------------------------------------

TEST_F(ImageIo, SaveToMissingDirectoryFailsAndLeavesNothing) {
    const fs::path file = path("no_such_dir") / "out.png";
    const Status status = save_image(make_image(4, 4, 3, 0.0f, 1.0f), file);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find(quoted(file)), std::string::npos)
        << status.error().message;
    EXPECT_NE(status.error().message.find("no_such_dir"), std::string::npos);
    EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIo, SaveWithUnknownExtensionFailsAndListsSupported) {
    const Status status = save_image(make_image(4, 4, 3, 0.0f, 1.0f), path("out.bmp"));
    ASSERT_FALSE(status.ok());
    const std::string& message = status.error().message;
    EXPECT_NE(message.find("out.bmp"), std::string::npos) << message;
    for (const char* ext : {".png", ".jpg", ".jpeg", ".exr", ".hdr", ".tif", ".tiff"}) {
        EXPECT_NE(message.find(ext), std::string::npos) << message;
    }
    EXPECT_TRUE(entries().empty());
    EXPECT_FALSE(save_image(make_image(4, 4, 3, 0.0f, 1.0f), path("noextension")).ok());
    EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIo, SaveRejectsInvalidImagesAndOptions) {
    const fs::path file = path("out.png");
    EXPECT_FALSE(save_image(Image(), file).ok());
    EXPECT_FALSE(save_image(Image(2, 2, 5), file).ok());
    Image short_pixels(4, 4, 3);
    short_pixels.pixels.resize(10);
    EXPECT_FALSE(save_image(short_pixels, file).ok());
    ImageSaveOptions bits12;
    bits12.bits = 12;
    EXPECT_FALSE(save_image(Image(2, 2, 3), file, bits12).ok());
    ImageSaveOptions bits16;
    bits16.bits = 16;
    const Status jpeg16 = save_image(Image(2, 2, 3), path("out.jpg"), bits16);
    ASSERT_FALSE(jpeg16.ok());
    EXPECT_NE(jpeg16.error().message.find("out.jpg"), std::string::npos);
    EXPECT_TRUE(entries().empty());
    EXPECT_TRUE(save_image(Image(2, 2, 3), path("ignored_bits.exr"), bits12).ok());
}

TEST_F(ImageIo, SaveOntoADirectoryFailsAndLeavesNothing) {
    fs::create_directory(path("target.png"));
    const Status status = save_image(make_image(4, 4, 3, 0.0f, 1.0f), path("target.png"));
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("target.png"), std::string::npos);
    EXPECT_EQ(entries(), std::vector<std::string>{"target.png"});
    EXPECT_TRUE(fs::is_directory(path("target.png")));
}

TEST_F(ImageIo, SaveReplacesAnExistingFileCompletely) {
    const fs::path file = path("replace.png");
    ASSERT_TRUE(save_image(make_image(200, 100, 4, 0.0f, 1.0f, 1), file).ok());
    const auto big_size = fs::file_size(file);
    const Image small = make_image(3, 2, 1, 0.0f, 1.0f, 2);
    ASSERT_TRUE(save_image(small, file).ok());
    EXPECT_LT(fs::file_size(file), big_size);
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    expect_same_shape(*loaded, small);
    EXPECT_LE(max_abs_diff(*loaded, small), kSrgb8RoundTripTolerance);
    EXPECT_EQ(entries(), std::vector<std::string>{"replace.png"});  // no temporary left

    // A failed save leaves the existing file untouched.
    const std::string before = read_bytes(file);
    EXPECT_FALSE(save_image(Image(2, 2, 5), file).ok());
    EXPECT_EQ(read_bytes(file), before);
    EXPECT_EQ(entries(), std::vector<std::string>{"replace.png"});
}

TEST_F(ImageIo, SaveIntoCurrentDirectoryWithRelativePath) {
    const fs::path old_cwd = fs::current_path();
    fs::current_path(dir_);
    const Status status = save_image(make_image(2, 2, 3, 0.0f, 1.0f), "relative.exr");
    const Result<Image> loaded = load_image("relative.exr");
    fs::current_path(old_cwd);
    ASSERT_TRUE(status.ok()) << status.error().message;
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_EQ(entries(), std::vector<std::string>{"relative.exr"});
}

// ---- failed writes and reproducible bytes
// ------------------------------------------------------------------------------------------

const std::vector<std::string> kEveryFormat = {"png", "jpg", "exr", "tif", "hdr"};

// A write() that writes half of what it is given once, then fails as a full disk does.
long half_then_full_disk(int fd, const void* data, std::size_t size) {
    static thread_local bool wrote_half = false;
    if (!wrote_half && size > 1) {
        wrote_half = true;
        return static_cast<long>(::write(fd, data, size / 2));
    }
    wrote_half = false;
    errno = ENOSPC;
    return -1;
}

// Sets image_io's write call for the life of the object.
class FailingWrites {
  public:
    explicit FailingWrites(detail::WriteCall call)
        : previous_(detail::replace_write_call_for_testing(call)) {}
    ~FailingWrites() { detail::replace_write_call_for_testing(previous_); }
    FailingWrites(const FailingWrites&) = delete;
    FailingWrites& operator=(const FailingWrites&) = delete;

  private:
    detail::WriteCall previous_;
};

void expect_full_disk_error(const Status& status, const fs::path& file) {
    ASSERT_FALSE(status.ok()) << file;
    EXPECT_EQ(status.error().message,
              "cannot write " + quoted(file) + ": " + std::strerror(ENOSPC));
}

TEST_F(ImageIo, FailedWriteIsAnErrorAndLeavesNothingInEveryFormat) {
    const Image image = make_image(64, 32, 3, 0.0f, 1.0f);
    for (const std::string& ext : kEveryFormat) {
        const fs::path file = path("out." + ext);
        {
            FailingWrites failing(half_then_full_disk);
            expect_full_disk_error(save_image(image, file), file);
        }
        EXPECT_TRUE(entries().empty()) << ext;
    }
}

TEST_F(ImageIo, FailedMipLevelsWriteIsAnErrorAndLeavesNothing) {
    const fs::path file = path("levels.exr");
    {
        FailingWrites failing(half_then_full_disk);
        expect_full_disk_error(save_image_levels(mip_chain(64, 32, 3), file), file);
    }
    EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIo, FailedWriteLeavesTheExistingTargetUntouched) {
    const fs::path file = path("keep.png");
    ASSERT_TRUE(save_image(make_image(8, 8, 3, 0.0f, 1.0f, 1), file).ok());
    const std::string before = read_bytes(file);
    {
        FailingWrites failing(half_then_full_disk);
        expect_full_disk_error(save_image(make_image(64, 64, 3, 0.0f, 1.0f, 2), file), file);
    }
    EXPECT_EQ(read_bytes(file), before);
    EXPECT_EQ(entries(), std::vector<std::string>{"keep.png"});
}

TEST_F(ImageIo, SaveImagesWritesAllOrNone) {
    const Image a = make_image(16, 16, 3, 0.0f, 1.0f, 1), b = make_image(16, 16, 3, 0.0f, 1.0f, 2);
    // The second target is refused after the first was written under its temporary name.
    const Status refused = save_images({{&a, path("a.png")}, {&b, path("b.bmp")}});
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find(quoted(path("b.bmp"))), std::string::npos);
    EXPECT_TRUE(entries().empty());
    ASSERT_TRUE(save_images({{&a, path("a.png")}, {&b, path("b.exr")}}).ok());
    EXPECT_EQ(entries(), (std::vector<std::string>{"a.png", "b.exr"}));
}

TEST_F(ImageIo, WriteFileAtomicallyChecksTheWrite) {
    const fs::path file = path("report.json");
    ASSERT_TRUE(write_file_atomically(file, "{}\n").ok());
    EXPECT_EQ(read_bytes(file), "{}\n");
    {
        FailingWrites failing(half_then_full_disk);
        expect_full_disk_error(write_file_atomically(file, std::string(4096, 'x')), file);
    }
    EXPECT_EQ(read_bytes(file), "{}\n");
    EXPECT_EQ(entries(), std::vector<std::string>{"report.json"});
    const Status missing = write_file_atomically(path("nowhere") / "r.json", "{}");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("does not exist"), std::string::npos);
}

// A 64 KiB tmpfs mounted on a fresh directory for the life of the object (root only).
class TinyDisk {
  public:
    static constexpr const char* kSize = "size=64k";
    explicit TinyDisk(const fs::path& dir) : dir_(dir) {
        fs::create_directory(dir_);
        if (::geteuid() != 0) {
            why_not_ = "not running as root";
        } else if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, kSize) != 0) {
            why_not_ = std::string("mount -t tmpfs failed: ") + std::strerror(errno);
        } else {
            mounted_ = true;
        }
    }
    ~TinyDisk() {
        if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    }
    TinyDisk(const TinyDisk&) = delete;
    TinyDisk& operator=(const TinyDisk&) = delete;
    bool mounted() const { return mounted_; }
    const std::string& why_not() const { return why_not_; }

  private:
    fs::path dir_;
    bool mounted_ = false;
    std::string why_not_;
};

std::vector<std::string> names_in(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

TEST_F(ImageIo, FullDiskIsAnErrorAndLeavesNothing) {
    const fs::path disk = path("disk");
    TinyDisk tiny(disk);
    if (!tiny.mounted()) GTEST_SKIP() << "no tiny tmpfs to fill: " << tiny.why_not();
    // Noise does not compress: 256 x 256 RGB is far more than 64 KiB in every format.
    const Image noise = make_image(256, 256, 3, 0.0f, 1.0f, 3);
    const Image small = make_image(4, 4, 3, 0.0f, 1.0f, 4);
    ASSERT_TRUE(save_image(small, disk / "old.png").ok());
    const std::string old_bytes = read_bytes(disk / "old.png");
    for (const std::string& ext : kEveryFormat) {
        const fs::path file = disk / ("full." + ext);
        expect_full_disk_error(save_image(noise, file), file);
        EXPECT_EQ(names_in(disk), std::vector<std::string>{"old.png"}) << ext;
    }
    expect_full_disk_error(save_image(noise, disk / "old.png"), disk / "old.png");
    EXPECT_EQ(read_bytes(disk / "old.png"), old_bytes);
    expect_full_disk_error(write_file_atomically(disk / "r.json", std::string(1 << 17, 'x')),
                           disk / "r.json");
    EXPECT_EQ(names_in(disk), std::vector<std::string>{"old.png"});
}

TEST_F(ImageIo, SamePixelsGiveTheSameBytesInEveryFormat) {
    const Image image = make_image(32, 16, 4, 0.0f, 2.0f, 5);
    ImageSaveOptions half;
    half.exr_half = true;
    ImageSaveOptions sixteen;
    sixteen.bits = 16;
    struct Case {
        std::string name;
        ImageSaveOptions options;
    };
    std::vector<Case> cases;
    for (const std::string& ext : kEveryFormat) cases.push_back({"a." + ext, {}});
    cases.push_back({"half.exr", half});
    cases.push_back({"sixteen.png", sixteen});
    cases.push_back({"sixteen.tif", sixteen});
    std::vector<std::string> first;
    for (const Case& c : cases) {
        ASSERT_TRUE(save_image(image, path("1-" + c.name), c.options).ok()) << c.name;
        first.push_back(read_bytes(path("1-" + c.name)));
    }
    // Time stamps have a resolution of one second: the second writes are in another second.
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    for (std::size_t i = 0; i < cases.size(); ++i) {
        ASSERT_TRUE(save_image(image, path("2-" + cases[i].name), cases[i].options).ok());
        EXPECT_EQ(read_bytes(path("2-" + cases[i].name)), first[i]) << cases[i].name;
    }
}

TEST_F(ImageIo, SavedFilesCarryNoTimeStamp) {
    const Image image = make_image(8, 8, 3, 0.0f, 1.0f, 6);
    for (const std::string& ext : kEveryFormat) {
        const fs::path file = path("stamp." + ext);
        ASSERT_TRUE(save_image(image, file).ok());
        auto in = OIIO::ImageInput::open(file.string());
        ASSERT_TRUE(in) << OIIO::geterror();
        EXPECT_EQ(in->spec().find_attribute("DateTime"), nullptr) << ext;
        in->close();
    }
}

// A LevelsWriter writes save_image_levels()' bytes a level at a time; one that fails, or is
// dropped unfinished, or given a level that does not fit, leaves nothing behind.
TEST_F(ImageIo, LevelsWrittenOneAtATimeAreSaveImageLevelsBytes) {
    const std::vector<Image> levels = mip_chain(37, 20, 3);
    LevelsSaveOptions options;
    options.wrap_modes = "periodic,clamp";
    options.tile_size = 16;
    options.float_attributes.push_back({"footprint:test", {1, 2, 3, 4, 5}});
    ASSERT_TRUE(save_image_levels(levels, path("whole.exr"), options));
    {
        Result<LevelsWriter> writer = LevelsWriter::open(path("levels.exr"), options);
        ASSERT_TRUE(writer) << writer.error().message;
        for (const Image& level : levels) ASSERT_TRUE(writer->write(level));
        EXPECT_EQ(entries().size(), 2u) << "the target appears only when finished";
        ASSERT_TRUE(writer->finish());
    }
    EXPECT_EQ(read_bytes(path("levels.exr")), read_bytes(path("whole.exr")));
    EXPECT_EQ(entries().size(), 2u);

    {  // dropped unfinished
        Result<LevelsWriter> writer = LevelsWriter::open(path("dropped.exr"), options);
        ASSERT_TRUE(writer);
        ASSERT_TRUE(writer->write(levels[0]));
    }
    {  // a level of the wrong size
        Result<LevelsWriter> writer = LevelsWriter::open(path("wrong.exr"), options);
        ASSERT_TRUE(writer);
        ASSERT_TRUE(writer->write(levels[0]));
        const Status s = writer->write(levels[2]);
        ASSERT_FALSE(s);
        EXPECT_NE(s.error().message.find("MIP level 1"), std::string::npos) << s.error().message;
        EXPECT_FALSE(writer->finish());
    }
    {  // a full disk
        FailingWrites failing(half_then_full_disk);
        Result<LevelsWriter> writer = LevelsWriter::open(path("full.exr"), options);
        ASSERT_TRUE(writer);
        Status s;
        for (const Image& level : levels)
            if (s) s = writer->write(level);
        if (s) s = writer->finish();
        expect_full_disk_error(s, path("full.exr"));
    }
    EXPECT_EQ(entries().size(), 2u) << "only whole.exr and levels.exr";
    EXPECT_FALSE(LevelsWriter::open(path("levels.png"), options));
    EXPECT_FALSE(LevelsWriter::open(path("no-such-folder") / "levels.exr", options));
}

}  // namespace
}  // namespace footprint
