// Tests of the `footprint env convert` command, called as a function (env_command.h): outputs,
// exit statuses, one-line error messages naming the file or value, and no output on failure.
#include <gtest/gtest.h>

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>

#include "env_command.h"
#include "envmap/env_image_io.h"
#include "image/image_io.h"
#include "image/image_io_detail.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

class EnvCommandTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::random_device random;
        dir_ = fs::temp_directory_path() / ("footprint-env-cli-test-" + std::to_string(random()));
        fs::create_directories(dir_);
        // A smooth lat-long (64 × 32): channel c = ½ + 0.4·(direction component c).
        Image latlong(64, 32, 3);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 64; ++x) {
                const Vec3d d = normalize(env_direction<double>(
                    EnvLayout::latlong, 0, (x + 0.5) / 64.0, (y + 0.5) / 32.0));
                latlong.at(x, y, 0) = static_cast<float>(0.5 + 0.4 * d.x);
                latlong.at(x, y, 1) = static_cast<float>(0.5 + 0.4 * d.y);
                latlong.at(x, y, 2) = static_cast<float>(0.5 + 0.4 * d.z);
            }
        latlong_ = dir_ / "sky.exr";
        ASSERT_TRUE(save_image(latlong, latlong_).ok());
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    int convert(EnvConvertCommandOptions options, std::string* err = nullptr) {
        options.quiet = true;
        ::testing::internal::CaptureStderr();
        const int status = run_env_convert_command(options);
        const std::string text = ::testing::internal::GetCapturedStderr();
        if (err) *err = text;
        return status;
    }
    EnvConvertCommandOptions from_sky(const std::string& to, const std::string& out) const {
        EnvConvertCommandOptions options;
        options.inputs = {latlong_};
        options.to = to;
        options.outputs = {dir_ / out};
        return options;
    }
    int entries() const {
        int n = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
        return n;
    }
    static bool one_line(const std::string& s) {
        return !s.empty() && s.back() == '\n' && s.find('\n') == s.size() - 1;
    }

    fs::path dir_, latlong_;
};

TEST_F(EnvCommandTest, SaysWhatItWroteOnStderrAsEveryCommandDoes) {
    EnvConvertCommandOptions options = from_sky("cube", "cube.exr");
    ::testing::internal::CaptureStdout();
    ::testing::internal::CaptureStderr();
    ASSERT_EQ(run_env_convert_command(options), 0);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
    EXPECT_EQ(err.rfind("footprint: converted '", 0), 0u) << err;
}

TEST_F(EnvCommandTest, ConvertsToEveryLayout) {
    // Default sizes (env_convert.h): lat-long 64 wide → cube 21, sphere / paraboloid 41.
    struct Case {
        const char* to;
        int width, height;
    };
    for (const Case& c : {Case{"cube", 4 * 21, 3 * 21}, Case{"latlong", 64, 32},
                          Case{"sphere", 41, 41}, Case{"paraboloid", 2 * 41, 41}}) {
        const std::string out = std::string(c.to) + ".exr";
        std::string err;
        ASSERT_EQ(convert(from_sky(c.to, out), &err), 0) << err;
        Result<Image> image = load_image(dir_ / out);
        ASSERT_TRUE(image.ok());
        EXPECT_EQ(image->width, c.width) << c.to;
        EXPECT_EQ(image->height, c.height) << c.to;
    }
}

TEST_F(EnvCommandTest, CubeCrossHasTheFacesInPlace) {
    EnvConvertCommandOptions options = from_sky("cube", "cross.exr");
    options.size = 16;
    options.cube_layout = "vcross";
    ASSERT_EQ(convert(options), 0);
    Result<Image> cross = load_image(dir_ / "cross.exr");
    ASSERT_TRUE(cross.ok());
    ASSERT_EQ(cross->width, 48);
    ASSERT_EQ(cross->height, 64);
    // Face centres: +Z (cell 1,1) has blue high, +Y (cell 1,0) green high, −Z (cell 1,3) blue low,
    // +X (cell 2,1) red high, −X (cell 0,1) red low. Values 0.5 ± 0.4 at the centres.
    EXPECT_NEAR(cross->at(24, 24, 2), 0.9f, 0.02f);
    EXPECT_NEAR(cross->at(24, 8, 1), 0.9f, 0.02f);
    EXPECT_NEAR(cross->at(24, 56, 2), 0.1f, 0.02f);
    EXPECT_NEAR(cross->at(40, 24, 0), 0.9f, 0.02f);
    EXPECT_NEAR(cross->at(8, 24, 0), 0.1f, 0.02f);
    // Read back through the library: the same map, the cross detected from its 3:4 aspect.
    Result<EnvImages> back = load_environment_images({dir_ / "cross.exr"});
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(back->layout, EnvLayout::cube);
}

TEST_F(EnvCommandTest, SixFacesAndTwoHalvesAndBack) {
    EnvConvertCommandOptions options = from_sky("cube", "px.exr");
    options.size = 8;
    options.outputs.clear();
    for (const char* n : {"px", "nx", "py", "ny", "pz", "nz"})
        options.outputs.push_back(dir_ / (std::string(n) + ".exr"));
    ASSERT_EQ(convert(options), 0);
    // The six faces back to a lat-long.
    EnvConvertCommandOptions back;
    back.inputs = options.outputs;
    back.to = "latlong";
    back.size = 32;
    back.outputs = {dir_ / "back.exr"};
    std::string err;
    ASSERT_EQ(convert(back, &err), 0) << err;
    Result<Image> image = load_image(dir_ / "back.exr");
    ASSERT_TRUE(image.ok());
    EXPECT_EQ(image->width, 32);
    // Paraboloid as two files, then from the two.
    EnvConvertCommandOptions para = from_sky("paraboloid", "front.exr");
    para.outputs.push_back(dir_ / "back_half.exr");
    ASSERT_EQ(convert(para), 0);
    EnvConvertCommandOptions again;
    again.inputs = para.outputs;
    again.to = "sphere";
    again.outputs = {dir_ / "sphere.exr"};
    ASSERT_EQ(convert(again, &err), 0) << err;
}

TEST_F(EnvCommandTest, MissingInputFailsWithoutOutput) {
    EnvConvertCommandOptions options = from_sky("cube", "out.png");
    options.inputs = {dir_ / "missing.exr"};
    std::string err;
    EXPECT_EQ(convert(options, &err), 1);
    EXPECT_TRUE(one_line(err)) << err;
    EXPECT_NE(err.find("missing.exr"), std::string::npos) << err;
    EXPECT_EQ(entries(), 1);
}

TEST_F(EnvCommandTest, WrongAspectForAnOverrideNamesTheFile) {
    EnvConvertCommandOptions options = from_sky("latlong", "out.exr");
    options.from_cube_layout = "hcross";  // the 2:1 lat-long is no 4:3 cross
    std::string err;
    EXPECT_EQ(convert(options, &err), 1);
    EXPECT_TRUE(one_line(err)) << err;
    EXPECT_NE(err.find("sky.exr"), std::string::npos) << err;
    EXPECT_NE(err.find("64x32"), std::string::npos) << err;
    EXPECT_NE(err.find("horizontal cross"), std::string::npos) << err;
    options = from_sky("latlong", "out.exr");
    options.from = "sphere";  // not square
    EXPECT_EQ(convert(options, &err), 1);
    EXPECT_NE(err.find("sky.exr"), std::string::npos) << err;
    EXPECT_NE(err.find("not square"), std::string::npos) << err;
    EXPECT_EQ(entries(), 1);
}

TEST_F(EnvCommandTest, BadValuesAreNamed) {
    struct Case {
        std::string field, value, expected, valid;
    };
    for (const Case& c : {Case{"to", "cubemap", "--to: unknown layout 'cubemap'", "latlong"},
                          Case{"from", "equirect", "--from: unknown layout 'equirect'", "latlong"},
                          Case{"from_cube_layout", "cross",
                               "--from-cube-layout: unknown cube layout 'cross'", "hcross"},
                          Case{"cube_layout", "openexr",
                               "--cube-layout: unknown output cube layout 'openexr'", "vcross"}}) {
        EnvConvertCommandOptions options = from_sky("cube", "out.png");
        if (c.field == "to") options.to = c.value;
        if (c.field == "from") options.from = c.value;
        if (c.field == "from_cube_layout") options.from_cube_layout = c.value;
        if (c.field == "cube_layout") options.cube_layout = c.value;
        std::string err;
        EXPECT_EQ(convert(options, &err), 1) << c.value;
        EXPECT_TRUE(one_line(err)) << err;
        EXPECT_NE(err.find(c.expected), std::string::npos) << err;
        EXPECT_NE(err.find(c.valid), std::string::npos) << err;  // the valid values are listed
    }
    for (int size : {-1, 16385}) {
        EnvConvertCommandOptions options = from_sky("cube", "out.png");
        options.size = size;
        std::string err;
        EXPECT_EQ(convert(options, &err), 1);
        EXPECT_NE(err.find("--size " + std::to_string(size)), std::string::npos) << err;
    }
    EnvConvertCommandOptions odd = from_sky("latlong", "out.png");
    odd.size = 63;
    std::string err;
    EXPECT_EQ(convert(odd, &err), 1);
    EXPECT_NE(err.find("--size 63"), std::string::npos) << err;
    EXPECT_EQ(entries(), 1);
}

TEST_F(EnvCommandTest, BadOutputsFailBeforeWork) {
    std::string err;
    EXPECT_EQ(convert(from_sky("cube", "out.bmp"), &err), 1);
    EXPECT_NE(err.find("out.bmp"), std::string::npos) << err;
    EXPECT_EQ(convert(from_sky("cube", "no_dir/out.png"), &err), 1);
    EXPECT_NE(err.find("no_dir"), std::string::npos) << err;
    EnvConvertCommandOptions three = from_sky("cube", "a.png");
    three.outputs.push_back(dir_ / "b.png");
    three.outputs.push_back(dir_ / "c.png");
    EXPECT_EQ(convert(three, &err), 1);
    EXPECT_NE(err.find("not 3"), std::string::npos) << err;
    EXPECT_TRUE(one_line(err)) << err;
    EXPECT_EQ(entries(), 1);
}

std::string bytes_of(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST_F(EnvCommandTest, AnInputAsTheOutputIsRefused) {
    const std::string before = bytes_of(latlong_);
    std::string err;
    // The same path, another spelling of it, and one of six face outputs.
    EnvConvertCommandOptions same = from_sky("latlong", "sky.exr");
    EXPECT_EQ(convert(same, &err), 1);
    EXPECT_TRUE(one_line(err)) << err;
    EXPECT_EQ(err, "footprint: -o '" + latlong_.string() + "' is the input '" + latlong_.string() +
                       "'; write the conversion to another file\n");
    EnvConvertCommandOptions spelled = from_sky("latlong", "");
    spelled.outputs = {dir_ / "." / ".." / dir_.filename() / "sky.exr"};
    EXPECT_EQ(convert(spelled, &err), 1);
    EXPECT_NE(err.find("is the input"), std::string::npos) << err;
    EnvConvertCommandOptions faces = from_sky("cube", "");
    faces.outputs.clear();
    for (const char* n : {"px.exr", "nx.exr", "py.exr", "sky.exr", "pz.exr", "nz.exr"})
        faces.outputs.push_back(dir_ / n);
    EXPECT_EQ(convert(faces, &err), 1);
    EXPECT_NE(err.find("is the input"), std::string::npos) << err;
    EXPECT_EQ(bytes_of(latlong_), before);
    EXPECT_EQ(entries(), 1);
}

TEST_F(EnvCommandTest, AnOutputGivenTwiceIsRefused) {
    EnvConvertCommandOptions twice = from_sky("paraboloid", "front.exr");
    twice.outputs.push_back(dir_ / "front.exr");
    std::string err;
    EXPECT_EQ(convert(twice, &err), 1);
    EXPECT_NE(err.find("is given twice"), std::string::npos) << err;
    EXPECT_EQ(entries(), 1);
}

TEST_F(EnvCommandTest, AnOutputGivenTwiceInTwoSpellingsIsRefused) {
    // Relative to the working directory, "front.exr" and "./front.exr" (neither exists yet) are
    // one file.
    const fs::path cwd = fs::current_path();
    fs::current_path(dir_);
    EnvConvertCommandOptions twice = from_sky("paraboloid", "front.exr");
    twice.outputs = {"front.exr", "./front.exr"};
    std::string err;
    const int status = convert(twice, &err);
    fs::current_path(cwd);
    EXPECT_EQ(status, 1);
    EXPECT_NE(err.find("is given twice"), std::string::npos) << err;
    EXPECT_EQ(entries(), 1);
}

TEST_F(EnvCommandTest, NonFiniteInputIsRefusedOrRepairedWithAWarning) {
    Image sky(64, 32, 3, 0.25f);
    sky.at(5, 9)[1] = std::numeric_limits<float>::quiet_NaN();
    const fs::path bad = dir_ / "nan.exr";
    ASSERT_TRUE(save_image(sky, bad).ok());
    EnvConvertCommandOptions options = from_sky("cube", "cube.exr");
    options.inputs = {bad};
    std::string err;
    EXPECT_EQ(convert(options, &err), 1);
    EXPECT_EQ(err, "footprint: cannot read '" + bad.string() +
                       "': 1 value is not finite (NaN or infinite), the first at texel (5, 9) "
                       "channel 1 (nan)\n");
    EXPECT_EQ(entries(), 2);
    options.repair_non_finite = true;
    EXPECT_EQ(convert(options, &err), 0) << err;
    EXPECT_EQ(err, "footprint: warning: '" + bad.string() +
                       "': replaced 1 non-finite value (NaN or infinite) by the mean of the finite "
                       "neighbours, the first at texel (5, 9) channel 1 (nan)\n");
    // Every neighbour is 0.25, so the repaired map is constant and so is its conversion.
    constexpr float kConstantTolerance = 1e-5f;
    Result<Image> cube = load_image(dir_ / "cube.exr");
    ASSERT_TRUE(cube.ok()) << cube.error().message;
    const int n = cube->height / 3;
    for (int y = n; y < 2 * n; ++y)
        for (int x = 0; x < cube->width; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(cube->at(x, y)[c], 0.25f, kConstantTolerance);
}

TEST_F(EnvCommandTest, ImageOfNoLayoutIsRefusedUnlessFromIsGiven) {
    const fs::path odd = dir_ / "odd.exr";
    ASSERT_TRUE(save_image(Image(60, 25, 3, 0.5f), odd).ok());
    EnvConvertCommandOptions options = from_sky("cube", "cube.exr");
    options.inputs = {odd};
    std::string err;
    EXPECT_EQ(convert(options, &err), 1);
    EXPECT_NE(err.find("cannot tell the layout of '" + odd.string() + "' from its size 60x25"),
              std::string::npos)
        << err;
    options.from = "latlong";
    EXPECT_EQ(convert(options, &err), 0) << err;
}

long full_disk(int, const void*, std::size_t) {
    errno = ENOSPC;
    return -1;
}

TEST_F(EnvCommandTest, FailedWriteFailsNamingTheFileAndLeavesNothing) {
    const detail::WriteCall previous = detail::replace_write_call_for_testing(full_disk);
    std::string err;
    const int status = convert(from_sky("cube", "cube.png"), &err);
    detail::replace_write_call_for_testing(previous);
    EXPECT_EQ(status, 1);
    EXPECT_EQ(err, "footprint: cannot write '" + (dir_ / "cube.png").string() +
                       "': No space left on device\n");
    EXPECT_EQ(entries(), 1);
}

}  // namespace
}  // namespace footprint
