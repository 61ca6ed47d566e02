// Tests of `footprint metrics`, called as a function (metrics_command.h): the JSON and human
// lines against compare_images and flip, masks, linear-light loading, the FLIP options and error
// map, one-line errors naming the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "image/image_io.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "metrics_command.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

class MetricsCommandTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::random_device random;
        dir_ = fs::temp_directory_path() / ("footprint-metrics-cli-" + std::to_string(random()));
        fs::create_directories(dir_);
        a_ = Image(6, 5, 3);
        b_ = Image(6, 5, 3);
        for (std::size_t i = 0; i < a_.pixels.size(); ++i) {
            a_.pixels[i] = static_cast<float>((i * 7) % 11) / 10.0f;
            b_.pixels[i] = a_.pixels[i] + static_cast<float>((i * 3) % 5) / 40.0f - 0.05f;
        }
        ASSERT_TRUE(save_image(a_, dir_ / "a.exr").ok());
        ASSERT_TRUE(save_image(b_, dir_ / "b.exr").ok());
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    int metrics_cmd(const MetricsCommandOptions& options, std::string* out, std::string* err) {
        ::testing::internal::CaptureStderr();
        ::testing::internal::CaptureStdout();
        const int status = run_metrics_command(options);
        *err = ::testing::internal::GetCapturedStderr();
        *out = ::testing::internal::GetCapturedStdout();
        return status;
    }
    MetricsCommandOptions options(const std::string& a, const std::string& b) const {
        MetricsCommandOptions o;
        o.a = dir_ / a;
        o.b = dir_ / b;
        return o;
    }
    fs::path dir_;
    Image a_, b_;
};

TEST_F(MetricsCommandTest, JsonLineMatchesCompareImages) {
    MetricsCommandOptions o = options("a.exr", "b.exr");
    o.json = true;
    o.peak = 2.0;
    std::string out, err;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    EXPECT_EQ(err, "");
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out.find('\n'), out.size() - 1);  // exactly one line
    const nlohmann::json j = nlohmann::json::parse(out);
    MetricsOptions m;
    m.peak = 2.0;
    const Result<ImageComparison> expected = compare_images(a_, b_, m);  // EXR: float-exact
    ASSERT_TRUE(expected.ok());
    EXPECT_DOUBLE_EQ(j.at("rmse").get<double>(), expected->rmse);
    EXPECT_DOUBLE_EQ(j.at("psnr").get<double>(), expected->psnr);
    EXPECT_DOUBLE_EQ(j.at("ssim").get<double>(), expected->ssim);
    EXPECT_EQ(j.at("pixels").get<std::size_t>(), 30u);
    EXPECT_GT(expected->rmse, 0.01);
    // FLIP of A (the test) against B (the reference); B reaches 1.05, so HDR-FLIP.
    const Result<FlipResult> flip_expected = flip(a_, b_);
    ASSERT_TRUE(flip_expected.ok()) << flip_expected.error().message;
    ASSERT_TRUE(flip_expected->hdr);
    EXPECT_DOUBLE_EQ(j.at("flip").get<double>(), flip_expected->mean);
    EXPECT_EQ(j.at("flip_range").get<std::string>(), "hdr");
    EXPECT_DOUBLE_EQ(j.at("flip_exposures").at("start").get<double>(),
                     flip_expected->start_exposure);
    EXPECT_DOUBLE_EQ(j.at("flip_exposures").at("stop").get<double>(), flip_expected->stop_exposure);
    EXPECT_EQ(j.at("flip_exposures").at("count").get<int>(), flip_expected->exposures);
    EXPECT_GT(flip_expected->mean, 0.01);
}

TEST_F(MetricsCommandTest, IdenticalImagesPrintNullPsnrAndHumanLine) {
    MetricsCommandOptions o = options("a.exr", "a.exr");
    o.json = true;
    std::string out, err;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    const nlohmann::json j = nlohmann::json::parse(out);
    EXPECT_TRUE(j.at("psnr").is_null());
    EXPECT_EQ(j.at("rmse").get<double>(), 0.0);
    EXPECT_NEAR(j.at("ssim").get<double>(), 1.0, 1e-12);
    EXPECT_EQ(j.at("flip").get<double>(), 0.0);
    EXPECT_EQ(j.at("flip_range").get<std::string>(), "ldr");  // a_ lies in [0, 1]
    EXPECT_TRUE(j.at("flip_exposures").is_null());

    o = options("a.exr", "b.exr");
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    EXPECT_EQ(out.rfind("rmse ", 0), 0u) << out;
    EXPECT_NE(out.find(" dB  ssim "), std::string::npos) << out;
    EXPECT_NE(out.find("  flip 0."), std::string::npos) << out;
    EXPECT_NE(out.find(" (hdr, 2 exposures "), std::string::npos) << out;
    EXPECT_NE(out.find("(pixels 30)\n"), std::string::npos) << out;
}

TEST_F(MetricsCommandTest, FlipRangeAndPixelsPerDegreeReachFlip) {
    MetricsCommandOptions o = options("a.exr", "b.exr");
    o.json = true;
    o.ppd = 30;
    o.flip_range = FlipRange::ldr;
    std::string out, err;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    nlohmann::json j = nlohmann::json::parse(out);
    FlipOptions f;
    f.pixels_per_degree = 30;
    f.range = FlipRange::ldr;
    Result<FlipResult> expected = flip(a_, b_, f);
    ASSERT_TRUE(expected.ok()) << expected.error().message;
    EXPECT_DOUBLE_EQ(j.at("flip").get<double>(), expected->mean);
    EXPECT_EQ(j.at("flip_range").get<std::string>(), "ldr");
    EXPECT_TRUE(j.at("flip_exposures").is_null());
    o.json = false;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    EXPECT_NE(out.find(" (ldr)  (pixels 30)\n"), std::string::npos) << out;

    // HDR-FLIP forced, B as the test and A as the reference: exposures from A.
    o = options("b.exr", "a.exr");
    o.json = true;
    o.flip_range = FlipRange::hdr;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    j = nlohmann::json::parse(out);
    f = FlipOptions{};
    f.range = FlipRange::hdr;
    expected = flip(b_, a_, f);
    ASSERT_TRUE(expected.ok()) << expected.error().message;
    EXPECT_DOUBLE_EQ(j.at("flip").get<double>(), expected->mean);
    EXPECT_EQ(j.at("flip_exposures").at("count").get<int>(), expected->exposures);

    o.ppd = 0;
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_EQ(err.rfind("footprint: --ppd: must be finite, > 0 and <= 1000 (got 0", 0), 0u) << err;
    EXPECT_EQ(out, "");

    // FLIP's own errors name both files: HDR-FLIP against a black reference has no exposures.
    ASSERT_TRUE(save_image(Image(6, 5, 3, 0.0f), dir_ / "black.exr").ok());
    o = options("a.exr", "black.exr");
    o.flip_range = FlipRange::hdr;
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_EQ(err, "footprint: cannot compare A = '" + (dir_ / "a.exr").string() + "' and B = '" +
                       (dir_ / "black.exr").string() +
                       "': FLIP: B has no pixel of positive luminance: HDR-FLIP's automatic "
                       "exposures are undefined; give the start and stop exposures\n");
    EXPECT_EQ(out, "");
}

TEST_F(MetricsCommandTest, FlipMapIsWrittenWholeOrNotAtAll) {
    MetricsCommandOptions o = options("a.exr", "b.exr");
    o.flip_range = FlipRange::ldr;
    o.flip_map = dir_ / "flip.exr";
    std::string out, err;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    FlipOptions f;
    f.range = FlipRange::ldr;
    f.error_map = true;
    const Result<FlipResult> expected = flip(a_, b_, f);
    ASSERT_TRUE(expected.ok()) << expected.error().message;
    Result<Image> map = load_image(dir_ / "flip.exr");
    ASSERT_TRUE(map.ok()) << map.error().message;
    EXPECT_EQ(map->channels, 1);
    EXPECT_EQ(map->pixels, expected->error_map.pixels);  // 32-bit float EXR: exact

    // PNG: codes round(255 FLIP), written linear, so loading gives FLIP back to 1/510.
    o.flip_map = dir_ / "flip.png";
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    map = load_image(dir_ / "flip.png");
    ASSERT_TRUE(map.ok()) << map.error().message;
    ASSERT_EQ(map->pixels.size(), expected->error_map.pixels.size());
    for (std::size_t i = 0; i < map->pixels.size(); ++i)
        EXPECT_NEAR(map->pixels[i], expected->error_map.pixels[i], 0.5 / 255 + 1e-6) << i;

    // A path that cannot be written is refused before any work, and nothing is left.
    const auto entries = [&] {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().string());
        std::sort(names.begin(), names.end());
        return names;
    };
    const std::vector<std::string> before = entries();
    o.flip_map = dir_ / "missing" / "flip.exr";
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_NE(err.find("'" + (dir_ / "missing" / "flip.exr").string() + "'"), std::string::npos)
        << err;
    EXPECT_EQ(out, "");
    o.flip_map = dir_ / "flip.txt";
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_NE(err.find("unsupported extension '.txt'"), std::string::npos) << err;
    // A directory in the way is refused too.
    fs::create_directories(dir_ / "taken.exr");
    o.flip_map = dir_ / "taken.exr";
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_EQ(err.rfind("footprint: ", 0), 0u) << err;
    EXPECT_EQ(out, "");
    fs::remove(dir_ / "taken.exr");
    EXPECT_EQ(entries(), before);
}

TEST_F(MetricsCommandTest, MaskSelectsPixels) {
    Image mask(6, 5, 1, 0.0f);
    mask.at(2, 3, 0) = 1.0f;
    mask.at(5, 0, 0) = 1.0f;
    ASSERT_TRUE(save_image(mask, dir_ / "mask.png").ok());  // sRGB PNG: 0 and 1 stay 0 and 1
    MetricsCommandOptions o = options("a.exr", "b.exr");
    o.mask = dir_ / "mask.png";
    o.json = true;
    std::string out, err;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    const nlohmann::json j = nlohmann::json::parse(out);
    MetricsOptions m;
    m.mask = &mask;
    const Result<ImageComparison> expected = compare_images(a_, b_, m);
    ASSERT_TRUE(expected.ok());
    EXPECT_EQ(j.at("pixels").get<std::size_t>(), 2u);
    EXPECT_DOUBLE_EQ(j.at("rmse").get<double>(), expected->rmse);
    EXPECT_DOUBLE_EQ(j.at("ssim").get<double>(), expected->ssim);
    FlipOptions f;
    f.mask = &mask;
    const Result<FlipResult> flip_expected = flip(a_, b_, f);
    ASSERT_TRUE(flip_expected.ok()) << flip_expected.error().message;
    EXPECT_EQ(flip_expected->pixels, 2u);
    EXPECT_DOUBLE_EQ(j.at("flip").get<double>(), flip_expected->mean);
}

TEST_F(MetricsCommandTest, SrgbFilesAreComparedInLinearLight) {
    // A PNG of linear 0.2 holds the sRGB code for 0.2 (≈ 0.484); loaded, it is ≈ 0.2 again.
    Image grey(4, 4, 3, 0.2f);
    ASSERT_TRUE(save_image(grey, dir_ / "grey.png").ok());
    ASSERT_TRUE(save_image(grey, dir_ / "grey.exr").ok());
    MetricsCommandOptions o = options("grey.png", "grey.exr");
    o.json = true;
    std::string out, err;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    EXPECT_LT(nlohmann::json::parse(out).at("rmse").get<double>(), 0.003);  // 8-bit rounding
    // One encoded file against a linear one: a one-line warning naming both, still exit 0.
    EXPECT_EQ(err.rfind("footprint: warning: ", 0), 0u) << err;
    EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
    EXPECT_NE(err.find("'" + (dir_ / "grey.png").string() + "' is sRGB-encoded"), std::string::npos)
        << err;
    EXPECT_NE(err.find("'" + (dir_ / "grey.exr").string() + "' is linear"), std::string::npos)
        << err;
    EXPECT_NE(err.find("compared in linear light"), std::string::npos) << err;
    // Two encoded files: no warning.
    ASSERT_TRUE(save_image(grey, dir_ / "grey2.png").ok());
    ASSERT_EQ(metrics_cmd(options("grey.png", "grey2.png"), &out, &err), 0) << err;
    EXPECT_EQ(err, "");
}

// NaN and infinity are refused, not read as 0: NaN against NaN must not give RMSE 0 and exit 0.
TEST_F(MetricsCommandTest, NonFinitePixelsFailNamingTheFileAndTheFirstPixel) {
    Image nan_a = a_, nan_b = a_;
    nan_a.at(3, 2, 1) = std::numeric_limits<float>::quiet_NaN();
    nan_b.at(3, 2, 1) = std::numeric_limits<float>::quiet_NaN();
    nan_b.at(5, 4, 0) = std::numeric_limits<float>::infinity();
    ASSERT_TRUE(save_image(nan_a, dir_ / "nan_a.exr").ok());
    ASSERT_TRUE(save_image(nan_b, dir_ / "nan_b.exr").ok());
    std::string out, err;
    MetricsCommandOptions o = options("nan_a.exr", "nan_b.exr");
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_EQ(out, "");
    EXPECT_EQ(err, "footprint: '" + (dir_ / "nan_a.exr").string() +
                       "' has 1 non-finite pixel, the first at (3, 2) channel 1 = nan, '" +
                       (dir_ / "nan_b.exr").string() +
                       "' has 2 non-finite pixels, the first at (3, 2) channel 1 = nan (NaN or "
                       "infinite); --ignore-non-finite leaves those pixels out of every metric\n");
    o = options("a.exr", "nan_b.exr");
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_NE(err.find("a.exr' has 0 non-finite pixels"), std::string::npos) << err;
}

TEST_F(MetricsCommandTest, IgnoreNonFiniteExcludesAndCountsThePixels) {
    Image nan_a = a_, inf_b = b_;
    nan_a.at(1, 1, 0) = std::numeric_limits<float>::quiet_NaN();
    inf_b.at(1, 1, 2) = -std::numeric_limits<float>::infinity();
    inf_b.at(4, 3, 1) = std::numeric_limits<float>::infinity();
    ASSERT_TRUE(save_image(nan_a, dir_ / "nan_a.exr").ok());
    ASSERT_TRUE(save_image(inf_b, dir_ / "inf_b.exr").ok());
    MetricsCommandOptions o = options("nan_a.exr", "inf_b.exr");
    o.ignore_non_finite = true;
    o.json = true;
    std::string out, err;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    // FLIP cannot leave pixels out (its filters spread them): not computed, with a warning.
    EXPECT_EQ(err,
              "footprint: warning: FLIP not computed: FLIP's filters spread each pixel over its "
              "neighbours, so the non-finite pixels cannot be left out of it\n");
    const nlohmann::json j = nlohmann::json::parse(out);
    EXPECT_TRUE(j.at("flip").is_null());
    EXPECT_TRUE(j.at("flip_range").is_null());
    EXPECT_EQ(j.at("non_finite_a").get<std::size_t>(), 1u);
    EXPECT_EQ(j.at("non_finite_b").get<std::size_t>(), 2u);
    EXPECT_EQ(j.at("excluded").get<std::size_t>(), 2u);
    EXPECT_EQ(j.at("pixels").get<std::size_t>(), 28u);
    MetricsOptions m;
    m.ignore_non_finite = true;
    const Result<ImageComparison> expected = compare_images(nan_a, inf_b, m);
    ASSERT_TRUE(expected.ok());
    EXPECT_DOUBLE_EQ(j.at("rmse").get<double>(), expected->rmse);
    EXPECT_DOUBLE_EQ(j.at("ssim").get<double>(), expected->ssim);
    EXPECT_GT(j.at("rmse").get<double>(), 0.01);

    o.json = false;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    EXPECT_NE(out.find("flip n/a  (pixels 28; non-finite pixels: A 1, B 2, 2 excluded)\n"),
              std::string::npos)
        << out;
    // An error map cannot be made: an error.
    o.flip_map = dir_ / "flip.exr";
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_EQ(err.rfind("footprint: --flip-map: FLIP's filters spread", 0), 0u) << err;
    EXPECT_EQ(out, "");
    EXPECT_FALSE(fs::exists(dir_ / "flip.exr"));
    o.flip_map.clear();
    // Finite images: the JSON's counts are 0, the line unchanged.
    o = options("a.exr", "b.exr");
    o.json = true;
    ASSERT_EQ(metrics_cmd(o, &out, &err), 0) << err;
    EXPECT_EQ(nlohmann::json::parse(out).at("excluded").get<std::size_t>(), 0u);
}

TEST_F(MetricsCommandTest, ErrorsNameTheFile) {
    std::string out, err;
    MetricsCommandOptions o = options("a.exr", "missing.exr");
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_EQ(err.rfind("footprint: ", 0), 0u) << err;
    EXPECT_NE(err.find("missing.exr"), std::string::npos) << err;
    EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
    EXPECT_EQ(out, "");

    ASSERT_TRUE(save_image(Image(5, 5, 3, 0.5f), dir_ / "small.exr").ok());
    o = options("a.exr", "small.exr");
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_EQ(err, "footprint: cannot compare A = '" + (dir_ / "a.exr").string() + "' and B = '" +
                       (dir_ / "small.exr").string() +
                       "': images differ in size: A is 6x5, B is 5x5\n");
    EXPECT_EQ(out, "");

    ASSERT_TRUE(save_image(Image(5, 5, 1, 1.0f), dir_ / "mask.exr").ok());
    o = options("a.exr", "b.exr");
    o.mask = dir_ / "mask.exr";
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_NE(err.find("mask '" + (dir_ / "mask.exr").string() + "'"), std::string::npos) << err;
    EXPECT_NE(err.find("mask is 5x5 but the images are 6x5"), std::string::npos) << err;

    o.mask = dir_ / "no-mask.png";
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_NE(err.find("no-mask.png"), std::string::npos) << err;

    o = options("a.exr", "b.exr");
    o.peak = -1;
    EXPECT_EQ(metrics_cmd(o, &out, &err), 1);
    EXPECT_EQ(err.rfind("footprint: --peak: must be finite and > 0", 0), 0u) << err;
}

}  // namespace
}  // namespace footprint
