// Tests of `footprint bake`, called as a function (bake_command.h): each KTX and EXR file holds
// footprint's own levels (the colour MIP pyramid, the bump moment pyramid, the cube map's face
// pyramids) to half-float rounding; the cube's faces are where OpenGL's cube map rule looks for
// them; bad input is one line naming the file, option or value, with nothing written. The files
// are read back here by a reader of the KTX 1 layout written from the spec, and by Filament's own
// KtxBundle in bake_filament_test.cpp where Filament is installed.
#include <gtest/gtest.h>

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "bake_command.h"
#include "bump/bump_pyramid.h"
#include "bump/slope_map.h"
#include "core/test_temp_dir.h"
#include "envmap/env_convert.h"
#include "envmap/env_image_io.h"
#include "envmap/env_pyramid_file.h"
#include "image/image_io.h"
#include "image/test_images.h"

namespace footprint {
namespace {

int bake(const BakeCommandOptions& options, std::string* err) {
    ::testing::internal::CaptureStderr();
    const int status = run_bake_command(options);
    *err = ::testing::internal::GetCapturedStderr();
    return status;
}

// A KTX 1 file as the spec lays it out, read independently of ktx_writer.cpp.
struct KtxFile {
    std::uint32_t endianness = 0, gl_type = 0, gl_type_size = 0, gl_format = 0,
                  gl_internal_format = 0, gl_base_internal_format = 0;
    std::uint32_t width = 0, height = 0, depth = 0, array_elements = 0, faces = 0, levels = 0;
    std::vector<std::pair<std::string, std::string>> key_values;
    std::vector<std::uint32_t> image_sizes;
    // images[level][face]: RGBA texels as floats, rows in file order.
    std::vector<std::vector<std::vector<float>>> images;
    std::vector<std::vector<std::vector<std::uint16_t>>> half_bits;  // for GL_HALF_FLOAT

    std::string value(const std::string& key) const {
        for (const auto& [k, v] : key_values)
            if (k == key) return v;
        return "(no key " + key + ")";
    }
};

std::string read_bytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

std::uint32_t u32(const std::string& bytes, std::size_t& at) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t(std::uint8_t(bytes.at(at + i))) << (8 * i);
    at += 4;
    return v;
}

KtxFile read_ktx(const std::filesystem::path& file) {
    const std::string bytes = read_bytes(file);
    KtxFile ktx;
    const std::string identifier = "\xABKTX 11\xBB\r\n\x1A\n";
    EXPECT_EQ(bytes.substr(0, 12), identifier) << file;
    std::size_t at = 12;
    for (std::uint32_t* field :
         {&ktx.endianness, &ktx.gl_type, &ktx.gl_type_size, &ktx.gl_format, &ktx.gl_internal_format,
          &ktx.gl_base_internal_format, &ktx.width, &ktx.height, &ktx.depth, &ktx.array_elements,
          &ktx.faces, &ktx.levels})
        *field = u32(bytes, at);
    const std::uint32_t key_value_bytes = u32(bytes, at);
    const std::size_t end = at + key_value_bytes;
    while (at < end) {
        const std::uint32_t size = u32(bytes, at);
        const std::string pair = bytes.substr(at, size);
        const std::size_t nul = pair.find('\0');
        std::string value = pair.substr(nul + 1);
        if (!value.empty() && value.back() == '\0') value.pop_back();
        ktx.key_values.emplace_back(pair.substr(0, nul), value);
        at += (size + 3) / 4 * 4;
    }
    const bool half = ktx.gl_type == 0x140B;
    for (std::uint32_t l = 0; l < ktx.levels; ++l) {
        const std::uint32_t w = std::max(1u, ktx.width >> l), h = std::max(1u, ktx.height >> l);
        const std::size_t values = std::size_t(w) * h * 4;
        ktx.image_sizes.push_back(u32(bytes, at));
        auto& level = ktx.images.emplace_back();
        auto& level_bits = ktx.half_bits.emplace_back();
        for (std::uint32_t f = 0; f < ktx.faces; ++f) {
            auto& image = level.emplace_back(values);
            auto& bits = level_bits.emplace_back(half ? values : 0);
            for (std::size_t i = 0; i < values; ++i) {
                if (half) {
                    bits[i] = std::uint16_t(std::uint8_t(bytes.at(at)) |
                                            std::uint8_t(bytes.at(at + 1)) << 8);
                    Imath::half h16;
                    h16.setBits(bits[i]);
                    image[i] = h16;
                    at += 2;
                } else {
                    const std::uint32_t b = u32(bytes, at);
                    std::memcpy(&image[i], &b, 4);
                }
            }
        }
    }
    EXPECT_EQ(at, bytes.size()) << file << ": bytes after the last level";
    return ktx;
}

// The RGBA texel a baked level holds for texel (x, y) of `image` (grey in R, G, B; alpha 1).
std::array<float, 4> as_rgba(const Image& image, int x, int y) {
    const float* v = image.at(x, y);
    switch (image.channels) {
        case 1:
            return {v[0], v[0], v[0], 1};
        case 2:
            return {v[0], v[0], v[0], v[1]};
        case 3:
            return {v[0], v[1], v[2], 1};
        default:
            return {v[0], v[1], v[2], v[3]};
    }
}

// Half-float rounding is the only change a KTX level makes: each stored value is the half nearest
// to footprint's float (Imath's round to nearest even), bit for bit.
void expect_level_is_half_of(const KtxFile& ktx, int l, int face, const Image& want,
                             const std::string& what) {
    ASSERT_EQ(ktx.images[l][face].size(), want.pixel_count() * 4) << what << " level " << l;
    for (int y = 0; y < want.height; ++y)
        for (int x = 0; x < want.width; ++x) {
            const std::array<float, 4> rgba = as_rgba(want, x, y);
            for (int c = 0; c < 4; ++c) {
                const std::size_t i = (std::size_t(y) * want.width + x) * 4 + c;
                ASSERT_EQ(ktx.half_bits[l][face][i], Imath::half(rgba[c]).bits())
                    << what << " level " << l << " face " << face << " texel (" << x << ", " << y
                    << ") channel " << c << ": " << ktx.images[l][face][i] << " vs " << rgba[c];
            }
        }
}

TEST(BakeCommand, ColorKtxHoldsThePyramidLevelByLevelToHalfRounding) {
    test::TempDir dir;
    ASSERT_TRUE(save_image(random_image(37, 20, 3, 5), dir / "in.png"));  // sRGB 8-bit
    BakeCommandOptions options;
    options.kind = "color";
    options.input = dir / "in.png";
    options.output = dir / "albedo.ktx";
    options.wrap = "repeat,clamp";
    options.downsample = DownsampleFilter::tent;
    std::string err;
    ASSERT_EQ(bake(options, &err), 0) << err;
    EXPECT_NE(err.find("wrote " + options.output.string() + " (color, 37x20, 6 levels, RGBA16F"),
              std::string::npos)
        << err;

    // The library's pyramid of the decoded (linear) image: what the lookups filter.
    MipPyramidOptions built;
    built.wrap_t = WrapMode::clamp;
    built.downsample = DownsampleFilter::tent;
    const MipPyramid pyramid = MipPyramid::build(*load_image(dir / "in.png"), built);
    const KtxFile ktx = read_ktx(options.output);
    EXPECT_EQ(ktx.endianness, 0x04030201u);
    EXPECT_EQ(ktx.gl_type, 0x140Bu);  // GL_HALF_FLOAT
    EXPECT_EQ(ktx.gl_type_size, 2u);
    EXPECT_EQ(ktx.gl_format, 0x1908u);           // GL_RGBA
    EXPECT_EQ(ktx.gl_internal_format, 0x881Au);  // GL_RGBA16F
    EXPECT_EQ(ktx.gl_base_internal_format, 0x1908u);
    EXPECT_EQ(ktx.width, 37u);
    EXPECT_EQ(ktx.height, 20u);
    EXPECT_EQ(ktx.depth, 0u);
    EXPECT_EQ(ktx.array_elements, 0u);
    EXPECT_EQ(ktx.faces, 1u);
    ASSERT_EQ(int(ktx.levels), pyramid.level_count());
    EXPECT_EQ(ktx.value("KTXorientation"), "S=r,T=d");
    EXPECT_NE(ktx.value("footprint").find("color"), std::string::npos);
    for (int l = 0; l < pyramid.level_count(); ++l) {
        EXPECT_EQ(ktx.image_sizes[l], std::uint32_t(pyramid.width(l) * pyramid.height(l) * 8));
        expect_level_is_half_of(ktx, l, 0, pyramid.level_image(l), "color");
    }

    // --float32: the pyramid's floats bit for bit.
    options.float32 = true;
    options.quiet = true;
    ASSERT_EQ(bake(options, &err), 0) << err;
    EXPECT_EQ(err, "");
    const KtxFile ktx32 = read_ktx(options.output);
    EXPECT_EQ(ktx32.gl_type, 0x1406u);             // GL_FLOAT
    EXPECT_EQ(ktx32.gl_internal_format, 0x8814u);  // GL_RGBA32F
    for (int l = 0; l < pyramid.level_count(); ++l) {
        const Image want = pyramid.level_image(l);
        for (int y = 0; y < want.height; ++y)
            for (int x = 0; x < want.width; ++x)
                for (int c = 0; c < 4; ++c)
                    ASSERT_EQ(ktx32.images[l][0][(std::size_t(y) * want.width + x) * 4 + c],
                              as_rgba(want, x, y)[c]);
    }
}

TEST(BakeCommand, ColorExrIsThePyramidAndGreyBecomesRgbInKtx) {
    test::TempDir dir;
    Image grey = random_image(16, 9, 1, 8);
    for (float& v : grey.pixels) v *= 40.0f;  // HDR stays HDR
    ASSERT_TRUE(save_image(grey, dir / "in.exr"));
    BakeCommandOptions options;
    options.kind = "color";
    options.input = dir / "in.exr";
    options.output = dir / "out.exr";
    std::string err;
    ASSERT_EQ(bake(options, &err), 0) << err;
    const MipPyramid pyramid = MipPyramid::build(grey);
    Result<std::vector<Image>> levels = load_image_levels(options.output);
    ASSERT_TRUE(levels) << levels.error().message;
    ASSERT_EQ(int(levels->size()), pyramid.level_count());
    for (int l = 0; l < pyramid.level_count(); ++l)
        EXPECT_EQ((*levels)[l].pixels, pyramid.level_image(l).pixels) << "level " << l;

    options.output = dir / "out.ktx";
    ASSERT_EQ(bake(options, &err), 0) << err;
    const KtxFile ktx = read_ktx(options.output);
    for (int l = 0; l < pyramid.level_count(); ++l)
        expect_level_is_half_of(ktx, l, 0, pyramid.level_image(l), "grey");
}

TEST(BakeCommand, BumpMapsHoldTheMomentPyramid) {
    test::TempDir dir;
    // A normal map of random slopes with a mean tilt (so that the offset is not zero).
    Image slopes = random_image(24, 17, 2, 13);
    for (std::size_t i = 0; i < slopes.pixels.size(); ++i)
        slopes.pixels[i] = (slopes.pixels[i] - 0.5f) * 0.8f + (i % 2 ? -0.1f : 0.2f);
    ImageSaveOptions linear;
    linear.encoding = ColorEncoding::linear;
    linear.bits = 16;
    ASSERT_TRUE(save_image(normals_from_slopes(slopes), dir / "normal.png", linear));

    BakeCommandOptions options;
    options.kind = "bump";
    options.input = dir / "normal.png";
    options.output = dir / "bricks.ktx";
    std::string err;
    ASSERT_EQ(bake(options, &err), 0) << err;
    EXPECT_NE(err.find("bricks_a.ktx and "), std::string::npos) << err;

    // The pyramid `maketx --bump` and the renderer build from the same file (bump_pyramid.h).
    ImageLoadOptions data;
    data.encoding = ColorEncoding::linear;
    Result<BumpPyramid> pyramid =
        BumpPyramid::build(*slopes_from_normal_map(*load_image(dir / "normal.png", data)));
    ASSERT_TRUE(pyramid);
    const MipPyramid& moments = pyramid->moments();
    const KtxFile a = read_ktx(dir / "bricks_a.ktx"), b = read_ktx(dir / "bricks_b.ktx");
    ASSERT_EQ(int(a.levels), moments.level_count());
    ASSERT_EQ(int(b.levels), moments.level_count());
    const Vec2 offset = pyramid->slope_offset();
    EXPECT_NE(offset.x, 0.0f);
    for (const KtxFile* file : {&a, &b}) {
        float x = 0, y = 0;
        ASSERT_EQ(std::sscanf(file->value("footprint:slope_offset").c_str(), "%f %f", &x, &y), 2);
        EXPECT_EQ(x, offset.x);  // %.9g: the float back bit for bit
        EXPECT_EQ(y, offset.y);
        EXPECT_EQ(file->value("KTXorientation"), "S=r,T=d");
    }
    for (int l = 0; l < moments.level_count(); ++l) {
        const Image level = moments.level_image(l);
        Image want_a(level.width, level.height, 4), want_b(level.width, level.height, 4);
        for (std::size_t i = 0; i < level.pixel_count(); ++i) {
            for (int c = 0; c < 4; ++c) want_a.pixels[i * 4 + c] = level.pixels[i * 5 + c];
            const float rest[4] = {level.pixels[i * 5 + 4], 0, 0, 1};
            std::copy_n(rest, 4, &want_b.pixels[i * 4]);
        }
        expect_level_is_half_of(a, l, 0, want_a, "A");
        expect_level_is_half_of(b, l, 0, want_b, "B");
    }
    // What a shader computes from the maps (docs/engine.md): μ = A.rg + offset, K = M2' − μ'μ'ᵀ,
    // against the pyramid's statistics of a texel of level 1. Half floats keep 11 significant
    // bits: a moment of size ~0.1 is within ~1e-4, and K is their difference.
    constexpr float kHalfMomentTolerance = 2e-3f;
    const SlopeStatistics want = pyramid->statistics(1, 3, 2);
    const std::size_t t = (2 * std::size_t(moments.width(1)) + 3) * 4;
    const float* A = &a.images[1][0][t];
    const float* B = &b.images[1][0][t];
    EXPECT_NEAR(A[0] + offset.x, want.mean.x, kHalfMomentTolerance);
    EXPECT_NEAR(A[1] + offset.y, want.mean.y, kHalfMomentTolerance);
    EXPECT_NEAR(A[2] - A[0] * A[0], want.covariance.xx, kHalfMomentTolerance);
    EXPECT_NEAR(A[3] - A[0] * A[1], want.covariance.xy, kHalfMomentTolerance);
    EXPECT_NEAR(B[0] - A[1] * A[1], want.covariance.yy, kHalfMomentTolerance);

    // EXR: one file, layers a and b, 32-bit: the moments bit for bit, the offset as an attribute.
    options.output = dir / "bricks.exr";
    ASSERT_EQ(bake(options, &err), 0) << err;
    auto in = OIIO::ImageInput::open((dir / "bricks.exr").string());
    ASSERT_TRUE(in);
    for (int l = 0; l < moments.level_count(); ++l) {
        ASSERT_TRUE(in->seek_subimage(0, l)) << "level " << l;
        const OIIO::ImageSpec& spec = in->spec();
        ASSERT_EQ(spec.nchannels, 8);
        if (l == 0) {
            float o[2] = {0, 0};
            ASSERT_TRUE(spec.getattribute("footprint:bake_slope_offset",
                                          OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 2), o));
            EXPECT_EQ(o[0], offset.x);
            EXPECT_EQ(o[1], offset.y);
        }
        std::vector<float> texels(spec.image_pixels() * 8);
        ASSERT_TRUE(in->read_image(0, l, 0, 8, OIIO::TypeDesc::FLOAT, texels.data()));
        const Image level = moments.level_image(l);
        for (int c = 0; c < 8; ++c) {
            const std::string name = spec.channelnames[c];
            const int k = (name[0] == 'a' ? 0 : 4) + int(std::string("RGBA").find(name[2]));
            for (std::size_t i = 0; i < level.pixel_count(); ++i) {
                const float want_value = k < 5 ? level.pixels[i * 5 + k] : k == 7 ? 1.0f : 0.0f;
                ASSERT_EQ(texels[i * 8 + c], want_value) << name << " level " << l;
            }
        }
    }
}

// OpenGL's cube map rule (OpenGL 4.5 §8.13, table 8.19), written here from the specification: the
// face of the major axis, then s = ½(sc/|ma| + 1), t = ½(tc/|ma| + 1), t = 0 the first row given.
struct GlCubeTexel {
    int face, x, y;
};
GlCubeTexel gl_cube_texel(Vec3 r, int n) {
    const float ax = std::abs(r.x), ay = std::abs(r.y), az = std::abs(r.z);
    int face;
    float sc, tc, ma;
    if (ax >= ay && ax >= az) {
        face = r.x > 0 ? 0 : 1;
        sc = r.x > 0 ? -r.z : r.z;
        tc = -r.y;
        ma = ax;
    } else if (ay >= az) {
        face = r.y > 0 ? 2 : 3;
        sc = r.x;
        tc = r.y > 0 ? r.z : -r.z;
        ma = ay;
    } else {
        face = r.z > 0 ? 4 : 5;
        sc = r.z > 0 ? r.x : -r.x;
        tc = -r.y;
        ma = az;
    }
    const float s = 0.5f * (sc / ma + 1), t = 0.5f * (tc / ma + 1);
    return {face, std::min(n - 1, int(s * n)), std::min(n - 1, int(t * n))};
}

// The direction through the centre of texel (x, y) of `face` by the same table, inverted.
Vec3 gl_texel_direction(int face, int x, int y, int n) {
    const float sc = 2 * (x + 0.5f) / n - 1, tc = 2 * (y + 0.5f) / n - 1;
    switch (face) {
        case 0:
            return {1, -tc, -sc};
        case 1:
            return {-1, -tc, sc};
        case 2:
            return {sc, 1, tc};
        case 3:
            return {sc, -1, -tc};
        case 4:
            return {sc, -tc, 1};
        default:
            return {-sc, -tc, -1};
    }
}

TEST(BakeCommand, EnvCubeFacesAreWhereOpenGLsCubeMapRuleLooks) {
    test::TempDir dir;
    // A lat-long sky whose colour is its direction, 0.5 + 0.5·r̂: any face, row or column in the
    // wrong place reads a colour far from its direction's.
    const int W = 128, H = 64;
    Image sky(W, H, 3);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float phi = 2 * float(M_PI) * ((x + 0.5f) / W - 0.5f),
                        theta = float(M_PI) * (y + 0.5f) / H;
            const float r[3] = {std::sin(theta) * std::sin(phi), std::cos(theta),
                                -std::sin(theta) * std::cos(phi)};  // env_layout.h's lat-long
            for (int c = 0; c < 3; ++c) sky.at(x, y, c) = 0.5f + 0.5f * r[c];
        }
    ASSERT_TRUE(save_image(sky, dir / "sky.exr"));
    BakeCommandOptions options;
    options.kind = "env";
    options.input = dir / "sky.exr";
    options.output = dir / "sky.ktx";
    options.size = 16;
    std::string err;
    ASSERT_EQ(bake(options, &err), 0) << err;
    const KtxFile ktx = read_ktx(options.output);
    ASSERT_EQ(ktx.faces, 6u);
    ASSERT_EQ(ktx.width, 16u);
    ASSERT_EQ(ktx.height, 16u);
    ASSERT_EQ(ktx.levels, 5u);                    // 16, 8, 4, 2, 1
    EXPECT_EQ(ktx.image_sizes[0], 16u * 16 * 8);  // one face's bytes (a non-array cube map)

    // Footprint's own cube of the same file, as the command builds it.
    Result<EnvironmentMap> source = load_environment({dir / "sky.exr"});
    ASSERT_TRUE(source);
    EnvConvertOptions convert;
    convert.size = 16;
    Result<EnvironmentMap> cube =
        make_environment_map(*convert_environment(*source, EnvLayout::cube, convert));
    ASSERT_TRUE(cube);
    for (int l = 0; l < 5; ++l)
        for (int f = 0; f < 6; ++f)
            expect_level_is_half_of(ktx, l, f, cube->face(f).level_image(l), "cube");

    // The smooth sky blurred by one cube texel's footprint: within 0.02 of its direction's colour;
    // a misplaced face, row or column is off by ~0.5 or more.
    constexpr float kSmoothSkyTolerance = 0.02f;
    // Bilinear at a texel centre reads that texel: its weights round in float.
    constexpr float kTexelCentreTolerance = 1e-3f;
    for (int f = 0; f < 6; ++f)
        for (const auto& [x, y] : {std::pair{0, 0}, {15, 0}, {3, 12}, {8, 8}, {15, 15}}) {
            const Vec3 r = gl_texel_direction(f, x, y, 16);
            const GlCubeTexel texel = gl_cube_texel(r, 16);
            ASSERT_EQ(texel.face, f);
            ASSERT_EQ(texel.x, x);
            ASSERT_EQ(texel.y, y);
            const float* stored = &ktx.images[0][f][(std::size_t(y) * 16 + x) * 4];
            float looked_up[3];
            environment_bilinear(*cube, r, 0, looked_up);
            const float length = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
            const float direction[3] = {r.x / length, r.y / length, r.z / length};
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(stored[c], looked_up[c], kTexelCentreTolerance)
                    << "face " << f << " texel (" << x << ", " << y << ") channel " << c;
                EXPECT_NEAR(stored[c], 0.5f + 0.5f * direction[c], kSmoothSkyTolerance)
                    << "face " << f << " texel (" << x << ", " << y << ") channel " << c;
            }
        }

    // EXR: an environment pyramid file of that cube.
    options.output = dir / "sky_env.exr";
    ASSERT_EQ(bake(options, &err), 0) << err;
    Result<EnvironmentMap> stored = load_environment_pyramid(options.output);
    ASSERT_TRUE(stored) << stored.error().message;
    ASSERT_EQ(stored->layout(), EnvLayout::cube);
    for (int f = 0; f < 6; ++f)
        for (int l = 0; l < 5; ++l)
            EXPECT_EQ(stored->face(f).level_image(l).pixels, cube->face(f).level_image(l).pixels);
}

TEST(BakeCommand, BadInputIsOneLineNamingItAndWritesNothing) {
    test::TempDir dir;
    ASSERT_TRUE(save_image(random_image(8, 8, 3, 2), dir / "in.exr"));
    Image not_normals(8, 8, 3, 0.5f);
    not_normals.at(5, 3, 2) = 0.1f;  // n_z < 0: below the surface
    ImageSaveOptions linear;
    linear.encoding = ColorEncoding::linear;
    ASSERT_TRUE(save_image(not_normals, dir / "photo.png", linear));
    Image bright(4, 4, 3, 1.0f);
    bright.at(2, 1, 0) = 1e5f;
    ASSERT_TRUE(save_image(bright, dir / "sun.exr"));
    std::filesystem::create_directory(dir / "folder.ktx");
    const int entries = dir.entries();

    struct Case {
        std::string kind, input, output;
        std::optional<int> size;
        std::string expected;
    } cases[] = {
        {"colour", "in.exr", "out.ktx", {}, "kind: unknown value 'colour' (did you mean 'color'?)"},
        {"color",
         "in.exr",
         "out.png",
         {},
         "cannot write '" + (dir / "out.png").string() +
             "': footprint bake writes KTX 1 (.ktx) or OpenEXR"},
        {"color", "in.exr", "no/such/out.ktx", {}, "does not exist"},
        {"color", "in.exr", "folder.ktx", {}, "folder.ktx': it is a directory"},
        {"color", "missing.png", "out.ktx", {}, "missing.png"},
        {"bump", "photo.png", "out.ktx", {}, "photo.png' is not a tangent-space normal map"},
        {"color", "in.exr", "out.ktx", 64, "--size applies to footprint bake env only"},
        {"env", "in.exr", "out.ktx", 0, "--size 0 is out of range (1 to 16384)"},
        {"color", "sun.exr", "out.ktx", {}, "beyond half floats' range (±65504) (--float32"},
    };
    for (const Case& c : cases) {
        BakeCommandOptions options;
        options.kind = c.kind;
        options.input = dir / c.input;
        options.output = dir / c.output;
        options.size = c.size;
        std::string err;
        EXPECT_EQ(bake(options, &err), 1) << c.expected;
        EXPECT_NE(err.find(c.expected), std::string::npos) << err;
        EXPECT_EQ(err.find('\n'), err.size() - 1) << err;  // one line
    }
    EXPECT_EQ(dir.entries(), entries);  // nothing written, no temporary file left
}

}  // namespace
}  // namespace footprint
