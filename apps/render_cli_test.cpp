// Tests of `footprint render` and `footprint demo`, called as functions (render_command.h,
// demo.h): outputs, exit statuses, one-line errors naming the file or value, no partial output.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/test_shared_data.h"
#include "demo.h"
#include "demo_scenes.h"
#include "gpu/gpu_test_device.h"
#include "image/image_io.h"
#include "metrics/image_metrics.h"
#include "render_command.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

class RenderCommandTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::random_device random;
        dir_ = fs::temp_directory_path() / ("footprint-render-cli-" + std::to_string(random()));
        fs::create_directories(dir_);
        // A small lat-long sky and a scene using it.
        Image sky(32, 16, 3, 0.5f);
        for (int x = 0; x < 32; ++x) sky.at(x, 3, 0) = 4.0f;
        ASSERT_TRUE(save_image(sky, dir_ / "sky.exr").ok());
        write("scene.json", R"({
          "image": {"width": 24, "height": 16},
          "camera": {"position": [0, 1, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 45},
          "environment": {"file": "sky.exr", "layout": "latlong"},
          "lights": [{"type": "directional", "direction": [0, -1, 0], "color": [1, 1, 1]}],
          "objects": [
            {"shape": "sphere", "center": [0, 0, 0], "radius": 0.7,
             "material": {"mirror": 1, "fresnel_f0": 0.9, "diffuse": 0, "specular": 0.5}},
            {"shape": "plane", "center": [0, -0.7, 0], "normal": [0, 1, 0], "size": "infinite",
             "material": {"base_color": [0.5, 0.4, 0.3]}}
          ]})");
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    void write(const std::string& name, const std::string& text) {
        std::ofstream(dir_ / name) << text;
    }
    int render_cmd(RenderCommandOptions options, std::string* err = nullptr,
                   std::string* out = nullptr, bool quiet = true) {
        options.quiet = quiet;
        ::testing::internal::CaptureStderr();
        ::testing::internal::CaptureStdout();
        const int status = run_render_command(options);
        const std::string text = ::testing::internal::GetCapturedStderr();
        const std::string stdout_text = ::testing::internal::GetCapturedStdout();
        if (err) *err = text;
        if (out) *out = stdout_text;
        return status;
    }
    RenderCommandOptions options(const std::string& output, const std::string& filter) const {
        RenderCommandOptions o;
        o.scene = dir_ / "scene.json";
        o.output = dir_ / output;
        o.filter = filter;
        return o;
    }
    fs::path dir_;
};

TEST_F(RenderCommandTest, WritesPngAndExrAndJsonSummary) {
    std::string out;
    RenderCommandOptions o = options("fa.png", "fa-rough");
    o.json = true;
    ASSERT_EQ(render_cmd(o, nullptr, &out), 0);
    Result<Image> png = load_image(dir_ / "fa.png");
    ASSERT_TRUE(png.ok());
    EXPECT_EQ(png->width, 24);
    EXPECT_EQ(png->height, 16);
    const nlohmann::json summary = nlohmann::json::parse(out);
    EXPECT_EQ(summary["filter"], "fa-rough");
    EXPECT_EQ(summary["spp"], 1);
    EXPECT_EQ(summary["pixels"], 24 * 16);
    EXPECT_GT(summary["lookups"].get<double>(), 0);
    EXPECT_GE(summary["seconds"].get<double>(), 0);
    EXPECT_EQ(summary["texture_tiles_loaded"], 0);  // no tiled file: the maps are in memory
    EXPECT_GT(summary["texture_peak_bytes"], 0);    // the maps held whole are counted

    // EXR keeps linear HDR values (the sky's 4.0 band is reflected in the sphere), no exposure.
    RenderCommandOptions exr = options("ref.exr", "reference");
    exr.spp = 4;
    exr.exposure = -3;
    ASSERT_EQ(render_cmd(exr), 0);
    Result<Image> hdr = load_image(dir_ / "ref.exr");
    ASSERT_TRUE(hdr.ok());
    float largest = 0;
    for (float v : hdr->pixels) largest = std::max(largest, v);
    EXPECT_GT(largest, 1.0f);
}

TEST_F(RenderCommandTest, BadInputGivesOneLineErrorsAndNoOutput) {
    std::string err;
    EXPECT_EQ(render_cmd(options("a.png", "fa_rough"), &err), 1);
    EXPECT_NE(err.find("--filter"), std::string::npos) << err;
    EXPECT_NE(err.find("fa_rough"), std::string::npos) << err;

    RenderCommandOptions missing = options("a.png", "fa");
    missing.scene = dir_ / "nope.json";
    EXPECT_EQ(render_cmd(missing, &err), 1);
    EXPECT_NE(err.find("nope.json"), std::string::npos) << err;

    write("bad.json", R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0, 0]},
                         "objects": [{"shape": "sphere", "radius": -1}]})");
    RenderCommandOptions bad = options("a.png", "fa");
    bad.scene = dir_ / "bad.json";
    EXPECT_EQ(render_cmd(bad, &err), 1);
    EXPECT_NE(err.find("bad.json"), std::string::npos) << err;
    EXPECT_NE(err.find("objects[0].radius"), std::string::npos) << err;

    write("missing_env.json", R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0, 0]},
                                  "environment": {"file": "absent.hdr"}, "objects": []})");
    RenderCommandOptions env = options("a.png", "fa");
    env.scene = dir_ / "missing_env.json";
    EXPECT_EQ(render_cmd(env, &err), 1);
    EXPECT_NE(err.find("absent.hdr"), std::string::npos) << err;

    EXPECT_EQ(render_cmd(options("a.bmpx", "fa"), &err), 1);
    EXPECT_NE(err.find("a.bmpx"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir_ / "a.png"));
}

// The GPU tests, a suite (so a process) of their own: under the sanitizers a process that made a
// GPU device ends without LeakSanitizer's check (tests/test_main.cpp), which the others keep.
class RenderCommandGpuTest : public RenderCommandTest {};

TEST_F(RenderCommandGpuTest, GpuDeviceWritesTheSameOutputsAndSummary) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    std::string out, err;
    RenderCommandOptions o = options("gpu.exr", "fa-rough");
    o.device = "gpu";
    o.json = true;
    ASSERT_EQ(render_cmd(o, &err, &out), 0) << err;
    const nlohmann::json summary = nlohmann::json::parse(out);
    EXPECT_EQ(summary["device"], "gpu");
    EXPECT_EQ(summary["filter"], "fa-rough");
    EXPECT_EQ(summary["width"], 24);
    EXPECT_EQ(summary["pixels"], 24 * 16);
    EXPECT_FALSE(summary["gpu"].get<std::string>().empty());
    EXPECT_GE(summary["gpu_ms"].get<double>(), 0.0);
    Result<Image> gpu = load_image(dir_ / "gpu.exr");
    ASSERT_TRUE(gpu);
    RenderCommandOptions cpu = options("cpu.exr", "fa-rough");
    ASSERT_EQ(render_cmd(cpu, &err), 0) << err;
    Result<Image> reference = load_image(dir_ / "cpu.exr");
    ASSERT_TRUE(reference);
    double worst = 0;
    for (std::size_t i = 0; i < gpu->pixels.size(); ++i)
        worst = std::max(worst, double(std::abs(gpu->pixels[i] - reference->pixels[i])));
    EXPECT_LT(worst, 0.02);  // the GPU path renders the CPU's image (apps/gpu_scenes_test.cpp)

    RenderCommandOptions frames = options("seq.png", "trilinear");
    frames.device = "gpu";
    frames.scene = "water";  // a built-in demo scene, which has a camera path
    frames.width = 32;
    frames.frames = 2;
    ASSERT_EQ(render_cmd(frames, &err), 0) << err;
    EXPECT_TRUE(fs::exists(dir_ / "seq_0000.png"));
    EXPECT_TRUE(fs::exists(dir_ / "seq_0001.png"));
}

TEST_F(RenderCommandGpuTest, GpuDeviceRefusesWhatItCannotDoInOneLine) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    std::string err;
    RenderCommandOptions o = options("a.png", "ewa-rough");
    o.device = "gpu";
    EXPECT_EQ(render_cmd(o, &err), 1);
    EXPECT_EQ(err,
              "footprint: --filter: footprint render --device gpu has no filter 'ewa-rough'; it "
              "accepts point, trilinear, fa, fa-rough, hw-aniso\n");
    o.filter = "bilinear";
    EXPECT_EQ(render_cmd(o, &err), 1);
    EXPECT_NE(err.find("(did you mean 'point'?)"), std::string::npos) << err;
    o.filter = "fa";
    o.spp = 4;
    EXPECT_EQ(render_cmd(o, &err), 1);
    EXPECT_EQ(err, "footprint: --spp 4: --device gpu renders one sample per pixel (--spp 1)\n");
    o.spp.reset();
    o.device = "tpu";
    EXPECT_EQ(render_cmd(o, &err), 1);
    EXPECT_EQ(err, "footprint: --device: unknown device 'tpu'; it is cpu or gpu\n");

    // A missing environment: the same error as on the CPU (the scene is prepared alike).
    write("missing_env.json", R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0, 0]},
                                  "environment": {"file": "absent.hdr"}, "objects": []})");
    RenderCommandOptions env = options("a.png", "fa");
    env.scene = dir_ / "missing_env.json";
    std::string cpu_err;
    EXPECT_EQ(render_cmd(env, &cpu_err), 1);
    env.device = "gpu";
    EXPECT_EQ(render_cmd(env, &err), 1);
    EXPECT_EQ(err, cpu_err);
    EXPECT_NE(err.find("absent.hdr"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir_ / "a.png"));
}

// The example scenes (examples/README.md) on both devices: the quick start, and the showcase with
// every shape, two meshes and nine maps where the shared data set is present.
TEST_F(RenderCommandGpuTest, TheExampleScenesRenderOnTheGpuAsOnTheCpu) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    const fs::path scenes = FOOTPRINT_EXAMPLE_SCENES_DIR;
    for (const char* name : {"quickstart.json", "showcase.json"}) {
        if (std::string(name) == "showcase.json" &&
            !fs::exists(test::shared_data_dir() / "meshes/FlightHelmet/FlightHelmet.gltf")) {
            std::printf("showcase.json skipped: %s\n",
                        test::missing_shared_data(test::shared_data_dir()).c_str());
            continue;
        }
        std::string err;
        RenderCommandOptions gpu = options("gpu.exr", "fa-rough");
        gpu.scene = scenes / name;
        gpu.width = 240;
        gpu.device = "gpu";
        ASSERT_EQ(render_cmd(gpu, &err), 0) << err;
        RenderCommandOptions cpu = gpu;
        cpu.device = "cpu";
        cpu.output = dir_ / "cpu.exr";
        ASSERT_EQ(render_cmd(cpu, &err), 0) << err;
        Result<Image> a = load_image(dir_ / "gpu.exr"), b = load_image(dir_ / "cpu.exr");
        ASSERT_TRUE(a && b);
        Result<ImageComparison> d = compare_images(*a, *b, {});
        ASSERT_TRUE(d);
        std::printf("%-16s fa-rough GPU vs CPU RMSE %.2e\n", name, d->rmse);
        // The whole-image tolerance of the mesh scenes (apps/gpu_geometry_test.cpp: twice the
        // filtered modes', for the silhouettes' pixels).
        EXPECT_LT(d->rmse, 2e-3) << name;
    }
}

// A scene that reads the shared data set (examples/scenes/showcase.json), on a clone without it:
// the message says where the file was to come from.
TEST_F(RenderCommandTest, AMissingSharedDataFileSaysWhereItComesFrom) {
    const fs::path scenes = dir_ / "repo" / "examples" / "scenes";
    fs::create_directories(scenes);
    std::ofstream(scenes / "showcase.json") << R"({"camera": {}, "objects": [],
        "environment": {"file": "../../../shared/data/envmaps/venice_sunset_1k.hdr"}})";
    RenderCommandOptions o = options("x.png", "fa");
    o.scene = scenes / "showcase.json";
    std::string err;
    EXPECT_EQ(render_cmd(o, &err), 1);
    EXPECT_NE(err.find("environment.file: file '../../../shared/data/envmaps/venice_sunset_1k.hdr' "
                       "not found"),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("the shared data set, which this scene needs in ../shared/data beside the "
                       "repository (examples/README.md)"),
              std::string::npos)
        << err;
    // Another missing file is only that.
    std::ofstream(dir_ / "other.json")
        << R"({"camera": {}, "objects": [], "environment": {"file": "data/sky.hdr"}})";
    o.scene = dir_ / "other.json";
    EXPECT_EQ(render_cmd(o, &err), 1);
    EXPECT_NE(err.find("data/sky.hdr' not found"), std::string::npos) << err;
    EXPECT_EQ(err.find("shared data"), std::string::npos) << err;
}

TEST_F(RenderCommandTest, UnknownFiltersAreAnsweredFromTheVocabulary) {
    const std::string accepted =
        "footprint render accepts bilinear, trilinear, fa, fa-rough, "
        "ewa-rough, reference, lean, toksvig, specular-aa, stochastic\n";
    const std::pair<const char*, std::string> cases[] = {
        {"fa_rough",
         "footprint: --filter: unknown filter 'fa_rough' (did you mean 'fa-rough'?); " + accepted},
        {"point",
         "footprint: --filter: footprint render has no filter 'point' (did you mean 'bilinear'?); "
         "it accepts bilinear, trilinear, fa, fa-rough, ewa-rough, reference, lean, toksvig, "
         "specular-aa, stochastic\n"},
        {"sat",
         "footprint: --filter: footprint render has no filter 'sat'; it accepts bilinear, "
         "trilinear, fa, fa-rough, ewa-rough, reference, lean, toksvig, specular-aa, "
         "stochastic\n"},
        {"anisotropic", "footprint: --filter: unknown filter 'anisotropic'; " + accepted},
    };
    for (const auto& [filter, message] : cases) {
        std::string err;
        EXPECT_EQ(render_cmd(options("a.png", filter), &err), 1) << filter;
        EXPECT_EQ(err, message);
    }
    EXPECT_FALSE(fs::exists(dir_ / "a.png"));
}

// Zero counts as much as a negative number: --spp 0 and --frames 0 are refused, not read as
// "the default".
TEST_F(RenderCommandTest, NumbersOutOfRangeAreRefusedAlike) {
    struct Case {
        std::function<void(RenderCommandOptions&)> set;
        std::string message;
    };
    const Case cases[] = {
        {[](RenderCommandOptions& o) { o.spp = 0; }, "--spp 0 is out of range (1 to 65536)"},
        {[](RenderCommandOptions& o) { o.spp = -1; }, "--spp -1 is out of range (1 to 65536)"},
        {[](RenderCommandOptions& o) { o.spp = 65537; },
         "--spp 65537 is out of range (1 to 65536)"},
        {[](RenderCommandOptions& o) { o.frames = 0; }, "--frames 0 is out of range (1 to 100000)"},
        {[](RenderCommandOptions& o) { o.frames = -1; },
         "--frames -1 is out of range (1 to 100000)"},
        {[](RenderCommandOptions& o) { o.width = 0; }, "--size 0 is out of range (16 to 16384)"},
        {[](RenderCommandOptions& o) { o.width = -8; }, "--size -8 is out of range (16 to 16384)"},
        {[](RenderCommandOptions& o) { o.threads = -1; },
         "--threads -1 is out of range (0 to 1024; 0: all cores)"},
        {[](RenderCommandOptions& o) { o.texture_memory_mb = 0; },
         "--texture-memory-mb 0 is out of range (1 to 1048576)"},
    };
    for (const Case& c : cases) {
        RenderCommandOptions o = options("a.png", "fa");
        c.set(o);
        std::string err;
        EXPECT_EQ(render_cmd(o, &err), 1) << c.message;
        EXPECT_EQ(err, "footprint: " + c.message + "\n");
    }
    EXPECT_FALSE(fs::exists(dir_ / "a.png"));
}

TEST_F(RenderCommandTest, SizeKeepsTheScenesAspectRatio) {
    for (const auto& [width, height] : {std::pair{48, 32}, std::pair{30, 20}, std::pair{16, 11}}) {
        RenderCommandOptions o = options("sized.png", "fa");
        o.width = width;
        std::string out;
        o.json = true;
        ASSERT_EQ(render_cmd(o, nullptr, &out), 0) << width;
        Result<Image> image = load_image(dir_ / "sized.png");
        ASSERT_TRUE(image.ok());
        EXPECT_EQ(image->width, width);
        EXPECT_EQ(image->height, height);  // the scene is 24 × 16
        EXPECT_EQ(nlohmann::json::parse(out)["height"], height);
    }
}

TEST_F(RenderCommandTest, SeedChoosesTheSamples) {
    const auto render_seed = [&](std::uint32_t seed, const std::string& file) {
        RenderCommandOptions o = options(file, "reference");
        o.spp = 4;
        o.seed = seed;
        o.json = true;
        std::string out;
        EXPECT_EQ(render_cmd(o, nullptr, &out), 0);
        EXPECT_EQ(nlohmann::json::parse(out)["seed"], seed);
        Result<Image> image = load_image(dir_ / file);
        EXPECT_TRUE(image.ok());
        return image.ok() ? image->pixels : std::vector<float>{};
    };
    const std::vector<float> one = render_seed(1, "one.exr");
    EXPECT_EQ(render_seed(1, "again.exr"), one);
    EXPECT_NE(render_seed(2, "two.exr"), one);
}

TEST_F(RenderCommandTest, ReportsWhatItWroteAndTheNonFiniteSamples) {
    std::string err, out;
    ASSERT_EQ(render_cmd(options("fa.png", "fa"), &err, &out, false), 0);
    const std::string expected =
        "footprint: wrote " + (dir_ / "fa.png").string() + " (24x16, fa, 1 spp, ";
    EXPECT_EQ(err.rfind(expected, 0), 0u) << err;
    EXPECT_EQ(err.substr(err.size() - 4), " s)\n") << err;

    RenderCommandOptions json = options("fa.png", "fa");
    json.json = true;
    ASSERT_EQ(render_cmd(json, &err, &out), 0);
    const nlohmann::json summary = nlohmann::json::parse(out);
    EXPECT_EQ(summary["non_finite_samples"], 0);
    EXPECT_EQ(summary["non_finite_pixels"], 0);
}

TEST_F(RenderCommandTest, FramesFollowTheCameraPath) {
    write("path.json", R"({"image": {"width": 16, "height": 12},
          "camera": {"position": [0, 1, 3], "look_at": [0, 0, 0]},
          "camera_path": [{"position": [0, 1, 3]}, {"position": [1, 1, 3], "look_at": [1, 0, 0]}],
          "environment": {"file": "sky.exr"},
          "objects": [{"shape": "sphere", "radius": 0.7, "material": {"base_color": [1, 0, 0]}}]})");
    RenderCommandOptions o = options("seq.png", "fa");
    o.scene = dir_ / "path.json";
    o.frames = 3;
    std::string out;
    o.json = true;
    ASSERT_EQ(render_cmd(o, nullptr, &out), 0);
    EXPECT_EQ(nlohmann::json::parse(out)["frames"], 3);
    std::vector<Image> frames;
    for (const char* name : {"seq_0000.png", "seq_0001.png", "seq_0002.png"}) {
        Result<Image> frame = load_image(dir_ / name);
        ASSERT_TRUE(frame.ok()) << name;
        frames.push_back(*frame);
    }
    EXPECT_FALSE(fs::exists(dir_ / "seq.png"));
    EXPECT_NE(frames[0].pixels, frames[2].pixels);  // the camera moved
    EXPECT_EQ(frame_file("a/b.exr", 12, 20000).filename(), "b_00012.exr");

    std::string err;
    RenderCommandOptions still = options("x.png", "fa");  // scene.json has no camera_path
    still.frames = 2;
    EXPECT_EQ(render_cmd(still, &err), 1);
    EXPECT_NE(err.find("camera_path"), std::string::npos) << err;
}

// Everything under `dir`, as paths relative to it.
std::vector<std::string> tree(const fs::path& dir) {
    std::vector<std::string> paths;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        paths.push_back(fs::relative(e.path(), dir).string());
    std::sort(paths.begin(), paths.end());
    return paths;
}

// A sequence whose second frame cannot be written (a directory of that name): the command fails
// naming the frame and removes the first.
TEST_F(RenderCommandTest, FramesThatFailPartWayLeaveNoFrameBehind) {
    write("path.json", R"({"image": {"width": 16, "height": 12},
          "camera": {"position": [0, 1, 3], "look_at": [0, 0, 0]},
          "camera_path": [{"position": [0, 1, 3]}, {"position": [1, 1, 3], "look_at": [1, 0, 0]}],
          "objects": [{"shape": "sphere", "radius": 0.7}]})");
    fs::create_directories(dir_ / "seq" / "seq_0001.png");
    RenderCommandOptions o = options("seq/seq.png", "fa");
    o.scene = dir_ / "path.json";
    o.frames = 3;
    std::string err;
    EXPECT_EQ(render_cmd(o, &err), 1);
    EXPECT_NE(err.find("seq_0001.png"), std::string::npos) << err;
    EXPECT_EQ(tree(dir_ / "seq"), std::vector<std::string>{"seq_0001.png"});
}

// demo.json, written last, cannot be written (a directory of that name): the command fails naming
// it, and no scene's images or folders remain.
TEST_F(RenderCommandTest, DemoThatFailsLeavesNothingOfItsRun) {
    DemoCommandOptions o;
    o.out_dir = dir_ / "demo";
    o.scenes = {"parabolic_mirror", "secret_writing"};
    o.width = 16;
    o.reference_spp = 1;
    o.quiet = true;
    fs::create_directories(o.out_dir / "demo.json" / "inside");
    ::testing::internal::CaptureStdout();
    ::testing::internal::CaptureStderr();
    const int status = run_demo_command(o);
    const std::string err = ::testing::internal::GetCapturedStderr();
    ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(status, 1);
    EXPECT_NE(err.find("demo.json"), std::string::npos) << err;
    EXPECT_EQ(tree(o.out_dir), (std::vector<std::string>{"demo.json", "demo.json/inside"}));
}

TEST_F(RenderCommandTest, DemoWritesEveryModeAContactSheetAndAReport) {
    DemoCommandOptions o;
    o.out_dir = dir_ / "demo";
    o.scenes = {"parabolic_mirror", "secret_writing"};
    o.width = 32;
    o.reference_spp = 4;
    o.quiet = true;
    ::testing::internal::CaptureStdout();
    const int status = run_demo_command(o);
    ::testing::internal::GetCapturedStdout();
    ASSERT_EQ(status, 0);
    for (const char* scene : {"parabolic_mirror", "secret_writing"}) {
        for (const char* file : {"reference", "bilinear", "trilinear", "fa", "fa-rough",
                                 "ewa-rough", "contact_sheet"}) {
            EXPECT_TRUE(fs::exists(o.out_dir / scene / (std::string(file) + ".png")))
                << scene << "/" << file;
        }
    }
    std::ifstream json_file(o.out_dir / "demo.json");
    const nlohmann::json report = nlohmann::json::parse(json_file);
    ASSERT_EQ(report["scenes"].size(), 2u);
    EXPECT_EQ(report["scenes"][0]["modes"].size(), 5u);
    // The parabolic mirror seen from its focus: every reflected ray is parallel to the axis, the
    // footprint vanishes and every mode renders the reference (a uniform image).
    for (const auto& mode : report["scenes"][0]["modes"]) {
        EXPECT_LT(mode["rmse"].get<double>(), 2e-3) << mode["filter"];
    }

    DemoCommandOptions unknown = o;
    unknown.scenes = {"teapot"};
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(run_demo_command(unknown), 1);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("teapot"), std::string::npos) << err;
}

}  // namespace
}  // namespace footprint
