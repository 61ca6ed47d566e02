// Tests of `footprint eval` (eval_command.h), called as a function: the report, the CSV and JSON
// rows, the reference cache keyed by scene content, and the report shown in headless Chromium.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "eval_command.h"
#include "eval_report.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

class EvalCommandTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::random_device random;
        dir_ = fs::temp_directory_path() / ("footprint-eval-cli-" + std::to_string(random()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    EvalCommandOptions small(std::vector<std::string> scenes) const {
        EvalCommandOptions o;
        o.scenes = std::move(scenes);
        o.out_dir = dir_ / "eval";
        o.width = 32;
        o.reference_spp = 16;
        o.supersampling_spp = {1, 4};
        o.frames = 3;
        o.flicker_reference_spp = 4;
        o.quiet = true;
        o.browser_check = false;  // checked explicitly where it is the point
        return o;
    }
    static int run(const EvalCommandOptions& o, std::string* err = nullptr) {
        ::testing::internal::CaptureStderr();
        ::testing::internal::CaptureStdout();
        const int status = run_eval_command(o);
        ::testing::internal::GetCapturedStdout();
        const std::string text = ::testing::internal::GetCapturedStderr();
        if (err) *err = text;
        return status;
    }
    static nlohmann::json results(const EvalCommandOptions& o) {
        std::ifstream in(o.out_dir / "results.json");
        return nlohmann::json::parse(in);
    }
    fs::path dir_;
};

TEST_F(EvalCommandTest, WritesTheReportRowsAndEveryImage) {
    EvalCommandOptions o = small({"secret_writing", "water"});
    std::string err;
    ASSERT_EQ(run(o, &err), 0) << err;
    const nlohmann::json r = results(o);
    ASSERT_EQ(r["scenes"].size(), 2u);
    for (const auto& scene : r["scenes"]) {
        // 5 filter modes + 2 supersampling rates, each with every measure.
        ASSERT_EQ(scene["methods"].size(), 7u) << scene["name"];
        EXPECT_FALSE(scene["reference_cached"].get<bool>());
        for (const auto& m : scene["methods"]) {
            EXPECT_GT(m["rmse"].get<double>(), 0) << m["method"];
            EXPECT_LE(m["ssim"].get<double>(), 1.0);
            EXPECT_GT(m["flicker"].get<double>(), 0) << m["method"];  // a camera path: measured
            EXPECT_TRUE(fs::exists(o.out_dir / scene["name"].get<std::string>() / "reference.png"));
        }
    }
    std::ifstream csv(o.out_dir / "results.csv");
    int lines = 0;
    for (std::string line; std::getline(csv, line);) ++lines;
    EXPECT_EQ(lines, 1 + 2 * 7);
    // The report loads every image in headless Chromium.
    const BrowserCheck check = check_report_in_browser(o.out_dir / "index.html", 2 * (1 + 2 * 7));
    if (!check.chromium_found) GTEST_SKIP() << "headless Chromium not installed: " << check.problem;
    EXPECT_TRUE(check.passed()) << check.problem;
    EXPECT_EQ(check.images_failed, 0);
}

TEST_F(EvalCommandTest, ReferencesAreCachedByContent) {
    const fs::path scene_file = dir_ / "mirror.json";
    const auto write_scene = [&](double radius) {
        std::ofstream(scene_file) << R"({"image": {"width": 24, "height": 16},
            "camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0]},
            "lights": [{"type": "directional", "direction": [0, -1, -1]}],
            "objects": [{"shape": "sphere", "radius": )"
                                  << radius << R"(, "material": {"specular": 0.5}}]})";
    };
    write_scene(0.8);
    EvalCommandOptions o = small({scene_file.string()});
    o.frames = 0;  // no camera path here
    ASSERT_EQ(run(o), 0);
    EXPECT_FALSE(results(o)["scenes"][0]["reference_cached"].get<bool>());
    ASSERT_EQ(run(o), 0);
    EXPECT_TRUE(results(o)["scenes"][0]["reference_cached"].get<bool>());
    EXPECT_TRUE(results(o)["scenes"][0]["methods"][0]["flicker"].is_null());
    write_scene(0.7);  // a changed scene: a new reference
    ASSERT_EQ(run(o), 0);
    EXPECT_FALSE(results(o)["scenes"][0]["reference_cached"].get<bool>());
}

TEST_F(EvalCommandTest, BadArgumentsNameTheProblem) {
    std::string err;
    EXPECT_EQ(run(small({"teapot"}), &err), 1);
    EXPECT_NE(err.find("teapot"), std::string::npos) << err;
    EvalCommandOptions o = small({"water"});
    o.supersampling_spp = {0};
    EXPECT_EQ(run(o, &err), 1);
    EXPECT_NE(err.find("--spp-list"), std::string::npos) << err;
    o = small({"water"});
    o.frames = 1;
    EXPECT_EQ(run(o, &err), 1);
    EXPECT_NE(err.find("--frames"), std::string::npos) << err;
}

}  // namespace
}  // namespace footprint
