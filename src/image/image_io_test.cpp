#include "image/image_io.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "image/color.h"

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

TEST_F(ImageIo, NonFiniteValuesInFilesBecomeZero) {
    Image image(4, 1, 1);
    const float inf = std::numeric_limits<float>::infinity();
    image.pixels = {std::numeric_limits<float>::quiet_NaN(), inf, -inf, 2.5f};
    const fs::path file = path("nonfinite.exr");
    ASSERT_TRUE(save_image(image, file).ok());
    const Result<Image> loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_EQ(loaded->pixels, (std::vector<float>{0.0f, 0.0f, 0.0f, 2.5f}));
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

#ifdef FOOTPRINT_TEST_DATA_DIR
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

}  // namespace
}  // namespace footprint
