// Tests of `footprint maketx`, called as a function (maketx_command.h): the file it writes holds
// the pyramid MipPyramid::build makes, the texture system reads it tile by tile with the same
// results, and bad input is one line naming the file or value, with nothing written.
#include <gtest/gtest.h>

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "bump/bump_pyramid_file.h"
#include "bump/slope_map.h"
#include "core/test_temp_dir.h"
#include "envmap/env_image_io.h"
#include "envmap/env_pyramid_file.h"
#include "image/image_io.h"
#include "image/test_images.h"
#include "maketx_command.h"
#include "texture_system.h"

namespace footprint {
namespace {

int maketx(const MaketxCommandOptions& options, std::string* err) {
    ::testing::internal::CaptureStderr();
    const int status = run_maketx_command(options);
    *err = ::testing::internal::GetCapturedStderr();
    return status;
}

TEST(MaketxCommand, WritesThePyramidThatTheTextureSystemReadsAsBuilt) {
    test::TempDir dir;
    const Image image = random_image(96, 40, 3, 21);
    ASSERT_TRUE(save_image(image, dir / "in.png"));
    MaketxCommandOptions options;
    options.input = dir / "in.png";
    options.output = dir / "out.exr";
    options.wrap = "repeat,clamp";
    options.downsample = DownsampleFilter::tent;
    options.tile_size = 16;
    std::string err;
    ASSERT_EQ(maketx(options, &err), 0) << err;
    EXPECT_NE(err.find("wrote"), std::string::npos);
    EXPECT_NE(err.find("7 levels"), std::string::npos) << err;
    options.quiet = true;  // --quiet: nothing but errors
    ASSERT_EQ(maketx(options, &err), 0) << err;
    EXPECT_EQ(err, "");
    options.quiet = false;

    MipPyramidOptions built;
    built.wrap_t = WrapMode::clamp;
    built.downsample = DownsampleFilter::tent;
    const MipPyramid pyramid = MipPyramid::build(*load_image(dir / "in.png"), built);
    Result<std::vector<Image>> levels = load_image_levels(dir / "out.exr");
    ASSERT_TRUE(levels);
    ASSERT_EQ(static_cast<int>(levels->size()), pyramid.level_count());
    for (int l = 0; l < pyramid.level_count(); ++l) {
        const Image want = pyramid.level_image(l);
        ASSERT_EQ((*levels)[l].pixels, want.pixels) << "level " << l;
    }

    auto ts = std::move(TextureSystem::create().value());
    Result<TextureInfo> info = ts->info((dir / "out.exr").string());
    ASSERT_TRUE(info) << info.error().message;
    EXPECT_TRUE(info->tiled);
    EXPECT_EQ(info->wrap_s, WrapMode::repeat);
    EXPECT_EQ(info->wrap_t, WrapMode::clamp);
    // Trilinear reads no prefilter variance: the stored levels give the built pyramid's bits.
    LookupOptions trilinear;
    trilinear.filter = TextureFilter::trilinear;
    const TextureCoords c{0.3f, 0.97f, 0.05f, 0.01f, -0.01f, 0.04f};
    float want[3], got[3];
    texture_lookup(pyramid, c, trilinear, want);
    ASSERT_TRUE(ts->texture((dir / "out.exr").string(), c, trilinear, got));
    for (int k = 0; k < 3; ++k)
        EXPECT_EQ(std::bit_cast<std::uint32_t>(got[k]), std::bit_cast<std::uint32_t>(want[k]));
}

TEST(MaketxCommand, BadInputIsOneLineNamingItAndWritesNothing) {
    test::TempDir dir;
    ASSERT_TRUE(save_image(random_image(8, 8, 1, 2), dir / "in.exr"));
    struct Case {
        std::string input, output, wrap;
        int tile_size;
        std::string expected;
    } cases[] = {
        {"missing.png", "out.exr", "repeat", 64, "missing.png"},
        {"in.exr", "out.png", "repeat", 64, "out.png"},
        {"in.exr", "out.exr", "wrapped", 64, "expected repeat (or periodic), clamp or mirror"},
        {"in.exr", "out.exr", "black", 64, "--wrap 'black': footprint's filters have no black"},
        {"in.exr", "out.exr", "clamp,black", 64, "no black wrap"},
        {"in.exr", "out.exr", "clamp,clamp,clamp", 64, "clamp,clamp,clamp"},
        {"in.exr", "out.exr", "repeat", 48, "48"},
        {"in.exr", "no/such/folder/out.exr", "repeat", 64, "no/such/folder"},
    };
    for (const Case& c : cases) {
        MaketxCommandOptions options;
        options.input = dir / c.input;
        options.output = dir / c.output;
        options.wrap = c.wrap;
        options.tile_size = c.tile_size;
        std::string err;
        EXPECT_EQ(maketx(options, &err), 1) << c.output;
        EXPECT_NE(err.find(c.expected), std::string::npos) << err;
        EXPECT_EQ(err.find('\n'), err.size() - 1) << err;  // one line
    }
    EXPECT_EQ(dir.entries(), 1);  // in.exr alone
}

TEST(MaketxCommand, BumpWritesTheBumpPyramidOfTheNormalOrHeightMapAtStrengthOne) {
    test::TempDir dir;
    Image slopes = random_image(48, 40, 2, 31);
    for (float& v : slopes.pixels) v -= 0.5f;
    ASSERT_TRUE(save_image(normals_from_slopes(slopes), dir / "normals.exr"));
    ASSERT_TRUE(save_image(random_image(48, 40, 1, 32), dir / "height.exr"));
    for (const bool height : {false, true}) {
        MaketxCommandOptions options;
        options.input = dir / (height ? "height.exr" : "normals.exr");
        options.output = dir / "bump.exr";
        options.bump = true;
        options.height = height;
        options.wrap = "clamp,repeat";
        options.tile_size = 16;
        std::string err;
        ASSERT_EQ(maketx(options, &err), 0) << err;
        EXPECT_NE(err.find("bump pyramid, 6 levels, 5 moment channels"), std::string::npos) << err;
        SlopeMapLoadOptions load;
        load.source = height ? SlopeMapSource::height_map : SlopeMapSource::normal_map;
        load.height_map.texel_size_u = 1.0f / 48;
        load.height_map.texel_size_v = 1.0f / 40;
        BumpPyramidOptions built;
        built.wrap_s = WrapMode::clamp;
        const BumpPyramid want =
            BumpPyramid::build(*load_slope_map(options.input, load), built).value();
        const BumpPyramid got = load_bump_pyramid(options.output).value();
        EXPECT_EQ(got.slope_offset().x, want.slope_offset().x);
        EXPECT_EQ(got.moments().wrap_s(), WrapMode::clamp);
        for (int l = 0; l < want.level_count(); ++l)
            ASSERT_EQ(got.moments().level_image(l).pixels, want.moments().level_image(l).pixels)
                << "level " << l << (height ? " of the height map" : " of the normal map");
    }
}

TEST(MaketxCommand, BumpRefusesInvalidNormalsUnlessClampedAndFlagsWithoutBump) {
    test::TempDir dir;
    Image normals(8, 8, 3, 0.0f);  // n = 0: not a normal
    ASSERT_TRUE(save_image(normals, dir / "zero.exr"));
    MaketxCommandOptions options;
    options.input = dir / "zero.exr";
    options.output = dir / "bump.exr";
    options.bump = true;
    std::string err;
    EXPECT_EQ(maketx(options, &err), 1);
    EXPECT_NE(err.find("zero.exr"), std::string::npos) << err;
    EXPECT_NE(err.find("--invalid-normals clamp"), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(options.output));
    options.clamp_invalid_normals = true;
    EXPECT_EQ(maketx(options, &err), 0) << err;
    EXPECT_TRUE(bump_pyramid_file_offset(options.output));

    MaketxCommandOptions height_alone;
    height_alone.input = dir / "zero.exr";
    height_alone.output = dir / "other.exr";
    height_alone.height = true;
    EXPECT_EQ(maketx(height_alone, &err), 1);
    EXPECT_EQ(err, "footprint: --height describes a bump map: give --bump too\n");
    EXPECT_FALSE(std::filesystem::exists(height_alone.output));
}

TEST(MaketxCommand, EnvWritesTheEnvironmentsPyramidsThatLoadAsBuilt) {
    test::TempDir dir;
    Image latlong = random_image(64, 32, 3, 41);
    ASSERT_TRUE(save_image(latlong, dir / "sky.exr"));
    Image cross = random_image(64, 48, 3, 42);  // a 4:3 horizontal cross
    ASSERT_TRUE(save_image(cross, dir / "cross.exr"));
    for (const auto& [file, layout] : {std::pair{"sky.exr", "auto"}, {"cross.exr", "cube"}}) {
        MaketxCommandOptions options;
        options.input = dir / file;
        options.output = dir / "env.exr";
        options.env = layout;
        options.tile_size = 16;
        std::string err;
        ASSERT_EQ(maketx(options, &err), 0) << err;
        EXPECT_NE(err.find(std::string(layout) == "cube" ? "cube environment, 6 faces"
                                                         : "latlong environment, 1 face"),
                  std::string::npos)
            << err;
        const EnvironmentMap want = load_environment({options.input}).value();
        const EnvironmentMap got = load_environment_pyramid(options.output).value();
        ASSERT_EQ(got.face_count(), want.face_count());
        for (int f = 0; f < want.face_count(); ++f)
            for (int l = 0; l < want.face(f).level_count(); ++l)
                ASSERT_EQ(got.face(f).level_image(l).pixels, want.face(f).level_image(l).pixels)
                    << file << " face " << f << " level " << l;
        EXPECT_EQ(got.polar_cap(0) != nullptr, want.polar_cap(0) != nullptr);
    }
    MaketxCommandOptions bad;
    bad.input = dir / "sky.exr";
    bad.output = dir / "bad.exr";
    bad.env = "mercator";
    std::string err;
    EXPECT_EQ(maketx(bad, &err), 1);
    EXPECT_EQ(err,
              "footprint: --env 'mercator': expected auto, latlong, cube, sphere or paraboloid\n");
    bad.env = "latlong";
    bad.bump = true;
    EXPECT_EQ(maketx(bad, &err), 1);
    EXPECT_EQ(err, "footprint: --bump and --env: give one of them\n");
    EXPECT_FALSE(std::filesystem::exists(bad.output));
}

// ---- memory: a build's peak, measured in a process of its own

// What BuildMemory's child process does (FOOTPRINT_BUILD_MEMORY_CHILD: "maketx IN OUT", or
// "texsys IN CACHE": the texture system's first use of IN, its pyramid built into CACHE).
TEST(BuildMemoryChild, DISABLED_Run) {
    const char* job = std::getenv("FOOTPRINT_BUILD_MEMORY_CHILD");
    ASSERT_NE(job, nullptr);
    std::istringstream words(job);
    std::string kind, input, output;
    words >> kind >> input >> output;
    if (kind == "maketx") {
        MaketxCommandOptions options;
        options.input = input;
        options.output = output;
        options.quiet = true;
        ASSERT_EQ(run_maketx_command(options), 0);
    } else {
        TextureSystemOptions options;
        options.cache_dir = output;
        auto ts = std::move(TextureSystem::create(options).value());
        float rgb[3];
        ASSERT_TRUE(ts->texture(input, TextureCoords{0.5f, 0.5f, 0.01f, 0, 0, 0.01f},
                                LookupOptions{}, rgb));
        ASSERT_TRUE(ts->info(input)->tiled);
    }
}

// The peak resident memory (bytes) of this test program running BuildMemoryChild with `job`.
std::size_t child_peak_rss(const std::string& job) {
    const std::string variable = "FOOTPRINT_BUILD_MEMORY_CHILD=" + job;
    std::vector<std::string> env_strings{variable, "FOOTPRINT_TEST_KEEP_XDG_CACHE=1"};
    for (char** e = environ; *e != nullptr; ++e)
        if (std::string_view(*e).rfind("FOOTPRINT_BUILD_MEMORY_CHILD=", 0) != 0)
            env_strings.emplace_back(*e);
    std::vector<char*> env;
    for (std::string& e : env_strings) env.push_back(e.data());
    env.push_back(nullptr);
    std::string exe = "/proc/self/exe", filter = "--gtest_filter=BuildMemoryChild.DISABLED_Run",
                also = "--gtest_also_run_disabled_tests", brief = "--gtest_brief=1";
    char* argv[] = {exe.data(), filter.data(), also.data(), brief.data(), nullptr};
    pid_t pid = 0;
    if (::posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv, env.data()) != 0) return 0;
    int status = 0;
    struct rusage usage {};
    if (::wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return 0;
    return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // Linux: KiB
}

// Building a pyramid needs at most twice the image as floats above the process's own memory
// (a 2048² RGB image: 48 MiB of floats), for `footprint maketx` and for the texture system's
// cache alike (docs/performance.md, "Building pyramids: memory"). Before the streaming build the
// pyramid, its level copies and the encoded file were all held: about 8 times.
TEST(BuildMemory, APyramidBuildPeaksBelowTwiceTheImageAsFloats) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    GTEST_SKIP() << "a sanitizer's shadow memory and quarantine are in the peak resident set: the "
                    "bound is checked in the Release build";
#endif
    test::TempDir dir;
    constexpr int kSize = 2048;
    ASSERT_TRUE(save_image(random_image(kSize, kSize, 3, 50), dir / "big.png"));
    ASSERT_TRUE(save_image(random_image(8, 8, 3, 51), dir / "tiny.png"));
    constexpr std::size_t kLevel0 = std::size_t{kSize} * kSize * 3 * sizeof(float);
    for (const std::string kind : {"maketx", "texsys"}) {
        const auto job = [&](const char* input, const char* output) {
            return kind + " " + (dir / input).string() + " " + (dir / output).string();
        };
        const std::size_t baseline =
            child_peak_rss(job("tiny.png", ("tiny-" + kind + ".exr").c_str()));
        const std::size_t peak = child_peak_rss(job("big.png", ("big-" + kind + ".exr").c_str()));
        ASSERT_GT(baseline, 0u) << kind << ": the child failed";
        ASSERT_GT(peak, 0u) << kind << ": the child failed";
        EXPECT_LE(peak, baseline + 2 * kLevel0)
            << kind << ": " << ((peak - baseline) >> 20) << " MiB above the baseline of "
            << (baseline >> 20) << " MiB; level 0 is " << (kLevel0 >> 20) << " MiB of floats";
    }
}

}  // namespace
}  // namespace footprint
