// Tests of `footprint eval` (eval_command.h), called as a function: the report, the CSV and JSON
// rows, the reference cache keyed by scene content, and the report shown in headless Chromium.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "eval_command.h"
#include "eval_report.h"
#include "image/image_io.h"
#include "metrics/test_rmse.h"
#include "render/error_budget.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "scene/scene_file.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;
using test::rmse;

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
        // 5 filter modes at 1, 4 and 16 spp + 2 supersampling rates, each with every measure;
        // flicker of the 1-spp filters and supersampling (a camera path: measured).
        ASSERT_EQ(scene["methods"].size(), 17u) << scene["name"];
        EXPECT_FALSE(scene["reference_cached"].get<bool>());
        for (const auto& m : scene["methods"]) {
            EXPECT_GT(m["rmse"].get<double>(), 0) << m["method"];
            EXPECT_LE(m["ssim"].get<double>(), 1.0);
            EXPECT_GT(m["flip_interior"].get<double>(), 0) << m["method"];
            EXPECT_LE(m["flip_interior"].get<double>(), 1.0) << m["method"];
            const bool shown = m["family"] == "supersampling" || m["spp"] == 1;
            EXPECT_EQ(m["flicker"].is_number(), shown) << m["method"];
            if (shown) {
                EXPECT_GT(m["flicker"].get<double>(), 0) << m["method"];
            }
            EXPECT_TRUE(fs::exists(o.out_dir / scene["name"].get<std::string>() / "reference.png"));
        }
    }
    std::ifstream csv(o.out_dir / "results.csv");
    int lines = 0;
    for (std::string line; std::getline(csv, line);) ++lines;
    EXPECT_EQ(lines, 1 + 2 * 17);
    // The report loads every image in headless Chromium.
    const BrowserCheck check = check_report_in_browser(o.out_dir / "index.html", 2 * (1 + 2 * 7));
    if (!check.chromium_found) GTEST_SKIP() << "headless Chromium not installed: " << check.problem;
    EXPECT_TRUE(check.passed()) << check.problem;
    EXPECT_EQ(check.images_failed, 0);
}

TEST_F(EvalCommandTest, PeersAreMethodsOfTheirOwnFamily) {
    EvalCommandOptions o = small({"water"});
    o.filter_spp = {1, 4};
    o.peers = true;
    std::string err;
    ASSERT_EQ(run(o, &err), 0) << err;
    const nlohmann::json scene = results(o)["scenes"][0];
    // 5 filter modes and 4 peers at 1 and 4 spp, 2 supersampling rates.
    ASSERT_EQ(scene["methods"].size(), 9u * 2 + 2);
    std::vector<std::string> peers;
    for (const auto& m : scene["methods"]) {
        if (m["family"] != "peer") continue;
        EXPECT_GT(m["rmse_interior"].get<double>(), 0) << m["method"];
        if (m["spp"] == 1) {
            peers.push_back(m["method"]);
            EXPECT_TRUE(m["flicker"].is_number()) << m["method"];
            EXPECT_TRUE(fs::exists(o.out_dir / "water" / (m["method"].get<std::string>() + ".png")))
                << m["method"];
        }
    }
    EXPECT_EQ(peers, (std::vector<std::string>{"lean", "toksvig", "specular-aa", "stochastic"}));
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

// index.html, written last, cannot be written (a directory of that name): the command fails
// naming it and leaves none of the run's images or rows; only the cached references stay.
TEST_F(EvalCommandTest, ARunThatFailsLeavesNothingButTheCache) {
    EvalCommandOptions o = small({"secret_writing", "water"});
    o.frames = 0;
    fs::create_directories(o.out_dir / "index.html" / "inside");
    std::string err;
    EXPECT_EQ(run(o, &err), 1);
    EXPECT_NE(err.find("index.html"), std::string::npos) << err;
    int cached = 0;
    for (const auto& e : fs::recursive_directory_iterator(o.out_dir)) {
        const fs::path relative = fs::relative(e.path(), o.out_dir);
        const std::string top = relative.begin()->string();
        if (top == "cache") {
            cached += e.is_regular_file() ? 1 : 0;
        } else {
            EXPECT_EQ(top, "index.html") << "left behind: " << relative;
        }
    }
    EXPECT_EQ(cached, 2);  // one reference per scene, reused by the next run
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
    // --frames on a scene without a camera path: refused, as render refuses it.
    const fs::path still = dir_ / "still.json";
    std::ofstream(still) << R"({"image": {"width": 24, "height": 16},
        "camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0]},
        "lights": [{"type": "directional", "direction": [0, -1, -1]}],
        "objects": [{"shape": "sphere", "radius": 0.8}]})";
    o = small({still.string()});
    o.frames_given = true;
    EXPECT_EQ(run(o, &err), 1);
    EXPECT_EQ(err, "footprint: " + still.stem().string() +
                       ": --frames needs a camera_path in the scene\n");
    o = small({"water"});
    o.kappa = -1;
    EXPECT_EQ(run(o, &err), 1);
    EXPECT_NE(err.find("--kappa"), std::string::npos) << err;
    o.budget = true;
    EXPECT_EQ(run(o, &err), 1);
    EXPECT_NE(err.find("--kappa"), std::string::npos) << err;
}

TEST_F(EvalCommandTest, TheBudgetWritesOneRowPerSceneAndTerm) {
    EvalCommandOptions o = small({"secret_writing", "water"});
    o.budget = true;
    ASSERT_EQ(run(o), 0);
    std::ifstream in(o.out_dir / "budget.json");
    const nlohmann::json budget = nlohmann::json::parse(in);
    EXPECT_EQ(budget["filter"], "fa-rough");
    ASSERT_EQ(budget["scenes"].size(), 2u);
    for (const nlohmann::json& scene : budget["scenes"]) {
        const nlohmann::json& terms = scene["terms"];
        ASSERT_EQ(terms.size(), all_budget_terms().size() + 1);
        EXPECT_EQ(terms[0]["term"], "fa-rough");
        EXPECT_TRUE(terms[0]["removed_interior"].is_null());
        const double mode = terms[0]["rmse"].get<double>();
        EXPECT_GT(mode, 0);
        for (std::size_t i = 0; i < all_budget_terms().size(); ++i) {
            const std::string name = budget_term_name(all_budget_terms()[i]);
            EXPECT_EQ(terms[i + 1]["term"], name);
            EXPECT_TRUE(fs::is_regular_file(o.out_dir / scene["name"].get<std::string>() /
                                            ("budget_" + name + ".png")));
        }
    }
    // The secret writing is a textured plane: its texture term removes (nearly) all the error.
    const nlohmann::json& writing = budget["scenes"][0]["terms"];
    EXPECT_EQ(writing[1]["term"], "texture");
    EXPECT_GT(writing[1]["removed_interior"].get<double>(), 0.99);
    std::ifstream csv(o.out_dir / "budget.csv");
    const std::string text((std::istreambuf_iterator<char>(csv)), {});
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'),
              static_cast<long>(1 + 2 * (all_budget_terms().size() + 1)));

    std::string err;
    o.budget_filter = "reference";
    EXPECT_EQ(run(o, &err), 1);
    EXPECT_NE(err.find("--budget-filter: 'reference' is not a filtered mode"), std::string::npos)
        << err;
}

// A textured floor to the horizon (fine checks alias) under a sphere: pixels whose samples vary.
fs::path write_checker_scene(const fs::path& dir) {
    Image checker(64, 64, 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) checker.at(x, y, c) = ((x + y) % 2) ? 0.9f : 0.05f;
    EXPECT_TRUE(save_image(checker, dir / "checker.png").ok());
    const fs::path scene = dir / "floor.json";
    std::ofstream(scene) << R"({"image": {"width": 32, "height": 24},
        "camera": {"position": [0, 1, 4], "look_at": [0, 0.2, 0]},
        "lights": [{"type": "directional", "direction": [0, -1, -1]}],
        "objects": [
          {"shape": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": {"specular": 0.5}},
          {"shape": "plane", "normal": [0, 1, 0], "size": "infinite", "uv_scale": 4,
           "material": {"base_color": "checker.png"}}]})";
    return scene;
}

// Defect: supersampling rendered with the reference's seed took a prefix of the reference's own
// samples, so its error came out too small (exactly 0 at the reference's spp). Each render now
// has its own seed: the error of 8 spp against 16 is that of independent estimates, about √3
// times the error of the 8-sample prefix (variances σ²(1/8 + 1/16) against σ²(1/8 − 1/16)).
TEST_F(EvalCommandTest, SupersamplingDoesNotReuseTheReferenceSamples) {
    const fs::path scene_file = write_checker_scene(dir_);
    EvalCommandOptions o = small({scene_file.string()});
    o.frames = 0;
    o.supersampling_spp = {8};
    std::string err;
    ASSERT_EQ(run(o, &err), 0) << err;
    const nlohmann::json methods = results(o)["scenes"][0]["methods"];
    const double measured = methods.back()["rmse"].get<double>();
    ASSERT_EQ(methods.back()["method"], "supersampling 8 spp");

    // The prefix's error, rendered here with one seed for both.
    Result<SceneDesc> desc = load_scene_file(scene_file);
    ASSERT_TRUE(desc.ok()) << desc.error().message;
    Result<RenderScene> scene = prepare_render_scene(*desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    RenderOptions options;
    options.filter = FilterMode::reference;
    options.spp = 16;
    const Image reference = render(*scene, options);
    options.spp = 8;
    const double prefix = rmse(render(*scene, options), reference);
    ASSERT_GT(prefix, 0);
    constexpr double kIndependentOverPrefix = 1.3;  // expected √3 ≈ 1.73; 1 for a prefix
    EXPECT_GT(measured, kIndependentOverPrefix * prefix) << measured << " vs prefix " << prefix;
}

TEST_F(EvalCommandTest, SupersamplingAtOrAboveTheReferenceSppIsRefused) {
    EvalCommandOptions o = small({"water"});
    for (int spp : {16, 64}) {
        o.supersampling_spp = {4, spp};
        std::string err;
        EXPECT_EQ(run(o, &err), 1) << spp;
        EXPECT_NE(
            err.find("--spp-list: " + std::to_string(spp) + " is not below --reference-spp 16"),
            std::string::npos)
            << err;
        EXPECT_FALSE(fs::exists(o.out_dir / "results.json"));
    }
}

TEST_F(EvalCommandTest, NumbersOutOfRangeAreRefusedAlike) {
    struct Case {
        std::function<void(EvalCommandOptions&)> set;
        std::string message;
    };
    const Case cases[] = {
        {[](EvalCommandOptions& o) { o.reference_spp = 0; },
         "--reference-spp 0 is out of range (1 to 1048576)"},
        {[](EvalCommandOptions& o) { o.supersampling_spp = {-1}; },
         "--spp-list -1 is out of range (1 to 65536)"},
        {[](EvalCommandOptions& o) { o.frames = -1; },
         "--frames -1 is out of range (2 to 1000; 0: no flicker)"},
        {[](EvalCommandOptions& o) { o.flicker_reference_spp = 0; },
         "--flicker-reference-spp 0 is out of range (1 to 1048576)"},
        {[](EvalCommandOptions& o) { o.threads = -1; },
         "--threads -1 is out of range (0 to 1024; 0: all cores)"},
        {[](EvalCommandOptions& o) { o.width = 0; }, "--size 0 is out of range (16 to 4096)"},
    };
    for (const Case& c : cases) {
        EvalCommandOptions o = small({"water"});
        c.set(o);
        std::string err;
        EXPECT_EQ(run(o, &err), 1) << c.message;
        EXPECT_EQ(err, "footprint: " + c.message + "\n");
    }
}

}  // namespace
}  // namespace footprint
