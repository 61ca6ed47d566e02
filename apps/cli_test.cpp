// Tests of the `footprint demo` and `footprint plane` commands, called as functions (demo.h):
// exit statuses, one-line error messages, and no output file on failure.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "cli_options.h"
#include "demo.h"
#include "eval_command.h"
#include "image/image_io.h"
#include "texture_demo.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

class CommandTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::random_device random;
        dir_ = fs::temp_directory_path() / ("footprint-cli-test-" + std::to_string(random()));
        fs::create_directories(dir_);
        Image texture(16, 16, 3);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                for (int c = 0; c < 3; ++c) texture.at(x, y, c) = ((x + y) % 2) ? 0.9f : 0.1f;
        texture_ = dir_ / "checker.png";
        ASSERT_TRUE(save_image(texture, texture_).ok());
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    // Runs the plane command with stderr captured; returns the exit status.
    int plane(PlaneCommandOptions options, std::string* err = nullptr, bool quiet = true) {
        options.quiet = quiet;
        ::testing::internal::CaptureStderr();
        const int status = run_plane_command(options);
        const std::string text = ::testing::internal::GetCapturedStderr();
        if (err) *err = text;
        return status;
    }
    // The directory holds nothing but the texture (no output, no temporary file).
    bool only_texture_left() const {
        int entries = 0;
        for (const auto& e : fs::directory_iterator(dir_)) entries += e.path() != texture_ ? 1 : 0;
        return entries == 0;
    }
    static bool one_line(const std::string& s) {
        return !s.empty() && s.back() == '\n' && s.find('\n') == s.size() - 1;
    }

    fs::path dir_, texture_;
};

TEST_F(CommandTest, PlaneWritesTheImage) {
    PlaneCommandOptions options;
    options.texture = texture_;
    options.output = dir_ / "plane.png";
    options.width = 64;
    options.filter = "ewa";
    ASSERT_EQ(plane(options), 0);
    Result<Image> image = load_image(options.output);
    ASSERT_TRUE(image.ok()) << image.error().message;
    EXPECT_EQ(image->width, 64);
    EXPECT_EQ(image->height, 36);
}

TEST_F(CommandTest, PlaneWritesExrForEveryFilter) {
    for (const char* filter : {"nearest", "bilinear", "trilinear", "fa", "ewa", "sat"}) {
        PlaneCommandOptions options;
        options.texture = texture_;
        options.output = dir_ / (std::string(filter) + ".exr");
        options.width = 32;
        options.filter = filter;
        EXPECT_EQ(plane(options), 0) << filter;
        EXPECT_TRUE(fs::exists(options.output)) << filter;
    }
}

TEST_F(CommandTest, MissingTextureFailsWithoutOutput) {
    PlaneCommandOptions options;
    options.texture = dir_ / "missing.png";
    options.output = dir_ / "out.png";
    std::string err;
    EXPECT_EQ(plane(options, &err), 1);
    EXPECT_TRUE(one_line(err)) << err;
    EXPECT_NE(err.find("missing.png"), std::string::npos) << err;
    EXPECT_TRUE(only_texture_left());
}

TEST_F(CommandTest, CorruptTextureFailsWithoutOutput) {
    const fs::path bad = dir_ / "bad.png";
    std::ofstream(bad, std::ios::binary) << "\x89PNG\r\n\x1a\n this is not a png";
    PlaneCommandOptions options;
    options.texture = bad;
    options.output = dir_ / "out.png";
    std::string err;
    EXPECT_EQ(plane(options, &err), 1);
    EXPECT_TRUE(one_line(err)) << err;
    EXPECT_NE(err.find("bad.png"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(options.output));
}

TEST_F(CommandTest, UnknownFilterListsTheValidOnes) {
    PlaneCommandOptions options;
    options.texture = texture_;
    options.output = dir_ / "out.png";
    options.filter = "anisotropic";
    std::string err;
    EXPECT_EQ(plane(options, &err), 1);
    EXPECT_TRUE(one_line(err)) << err;
    EXPECT_NE(err.find("anisotropic"), std::string::npos) << err;
    EXPECT_NE(err.find("nearest, bilinear, trilinear, brilinear, fa, ewa, sat"), std::string::npos)
        << err;
    EXPECT_TRUE(only_texture_left());
}

TEST_F(CommandTest, UnknownFiltersAreAnsweredFromTheVocabulary) {
    const std::string accepted =
        "footprint plane accepts nearest, bilinear, trilinear, brilinear, fa, ewa, sat\n";
    const std::pair<const char*, std::string> cases[] = {
        {"point",
         "footprint: --filter: footprint plane has no filter 'point' (did you mean 'bilinear'?); "
         "it accepts nearest, bilinear, trilinear, brilinear, fa, ewa, sat\n"},
        {"footprint_assembly",
         "footprint: --filter: unknown filter 'footprint_assembly' (did you mean 'fa'?); " +
             accepted},
        {"trilnear",
         "footprint: --filter: unknown filter 'trilnear' (did you mean 'trilinear'?); " + accepted},
        {"fa-rough",
         "footprint: --filter: footprint plane has no filter 'fa-rough'; it accepts "
         "nearest, bilinear, trilinear, brilinear, fa, ewa, sat\n"},
        {"reference",
         "footprint: --filter: footprint plane has no filter 'reference'; it accepts "
         "nearest, bilinear, trilinear, brilinear, fa, ewa, sat\n"},
    };
    for (const auto& [filter, message] : cases) {
        PlaneCommandOptions options;
        options.texture = texture_;
        options.output = dir_ / "out.png";
        options.filter = filter;
        std::string err;
        EXPECT_EQ(plane(options, &err), 1) << filter;
        EXPECT_EQ(err, message);
    }
    EXPECT_TRUE(only_texture_left());
}

// The names the two kinds of command share mean the same filter: render's bilinear, trilinear and
// fa are the texture filters of those names.
TEST(FilterVocabulary, SharedNamesAreTheSameFilter) {
    EXPECT_EQ(
        render_filter_names(", "),
        "bilinear, trilinear, fa, fa-rough, ewa-rough, reference, lean, toksvig, specular-aa, "
        "stochastic");
    EXPECT_EQ(plane_filter_names("|"), "nearest|bilinear|trilinear|brilinear|fa|ewa|sat");
    for (TextureFilter filter : plane_filters()) {
        const Result<FilterMode> mode = parse_render_filter(to_string(filter));
        if (!mode) continue;
        EXPECT_STREQ(filter_mode_name(*mode), to_string(filter));
    }
    EXPECT_EQ(parse_render_filter("bilinear").value(), FilterMode::bilinear);
    EXPECT_EQ(parse_plane_filter("bilinear").value(), TextureFilter::bilinear);
}

// --help states the widths each command's --size accepts: the range in the command's own refusal.
TEST(ImageSizeOption, ParsesWidthByHeightAndNamesWhatIsWrong) {
    Result<ImageSize> size = parse_image_size("--size", "1920x1080");
    ASSERT_TRUE(size);
    EXPECT_EQ(size->width, 1920);
    EXPECT_EQ(size->height, 1080);
    EXPECT_EQ(parse_image_size("--size", "7X5")->height, 5);
    for (const char* bad : {"1920", "1920x", "x1080", "12by9", "1920x1080px", ""})
        EXPECT_EQ(parse_image_size("--size", bad).error().message,
                  "--size '" + std::string(bad) + "': expected WIDTHxHEIGHT, e.g. 1280x720")
            << bad;
    EXPECT_EQ(parse_image_size("--size", "0x8").error().message,
              "--size width 0 is out of range (1 to 16384)");
    EXPECT_EQ(parse_image_size("--size", "8x20000").error().message,
              "--size height 20000 is out of range (1 to 16384)");
}

TEST(CommandHelp, SizeHelpShowsTheRangeTheCommandChecks) {
    const auto refusal = [](const std::function<int(int)>& run, int width) {
        ::testing::internal::CaptureStderr();
        ::testing::internal::CaptureStdout();
        EXPECT_EQ(run(width), 1) << width;
        ::testing::internal::GetCapturedStdout();
        return ::testing::internal::GetCapturedStderr();
    };
    struct Command {
        const char* name;
        IntRange widths;
        std::function<int(int)> run;
    };
    const Command commands[] = {
        {"texture-demo", kDemoWidths,
         [](int width) {
             TextureDemoOptions o;
             o.width = width;
             return run_texture_demo_command(o);
         }},
        {"demo", kDemoWidths,
         [](int width) {
             DemoCommandOptions o;
             o.width = width;
             return run_demo_command(o);
         }},
        {"eval", kDemoWidths,
         [](int width) {
             EvalCommandOptions o;
             o.width = width;
             return run_eval_command(o);
         }},
        {"plane", kImageWidths,
         [](int width) {
             PlaneCommandOptions o;
             o.width = width;
             return run_plane_command(o);
         }},
    };
    for (const Command& c : commands) {
        const std::string help = width_help("Image width in pixels", c.widths);
        EXPECT_EQ(help, "Image width in pixels, " + std::to_string(c.widths.low) + " to " +
                            std::to_string(c.widths.high) + " (height = width·9/16)");
        for (long long width : {c.widths.low - 1, c.widths.high + 1}) {
            const std::string err = refusal(c.run, static_cast<int>(width));
            EXPECT_EQ(err, "footprint: --size " + std::to_string(width) + " is out of range (" +
                               range_text(c.widths) + ")\n")
                << c.name;
        }
    }
}

TEST_F(CommandTest, PlaneReportsWhatItWrote) {
    PlaneCommandOptions options;
    options.texture = texture_;
    options.output = dir_ / "plane.png";
    options.width = 32;
    options.filter = "sat";
    std::string err;
    ASSERT_EQ(plane(options, &err, false), 0);
    const std::string expected = "footprint: wrote " + options.output.string() + " (32x18, sat, ";
    EXPECT_EQ(err.rfind(expected, 0), 0u) << err;
    EXPECT_EQ(err.substr(err.size() - 4), " s)\n") << err;
    EXPECT_TRUE(one_line(err)) << err;
}

TEST_F(CommandTest, BadOptionValuesFail) {
    PlaneCommandOptions options;
    options.texture = texture_;
    options.output = dir_ / "out.png";
    for (int width : {0, -5, 15, 100000}) {
        options.width = width;
        std::string err;
        EXPECT_EQ(plane(options, &err), 1) << width;
        EXPECT_NE(err.find("--size"), std::string::npos) << err;
    }
    options.width = 32;
    // The value as given, not as JSON writes it ("null").
    for (auto [scale, shown] :
         {std::pair{0.0, "0"}, std::pair{-1.0, "-1"}, std::pair{std::nan(""), "nan"},
          std::pair{double(INFINITY), "inf"}}) {
        options.uv_scale = scale;
        std::string err;
        EXPECT_EQ(plane(options, &err), 1) << scale;
        EXPECT_NE(err.find(std::string("--uv-scale ") + shown + " is out of range"),
                  std::string::npos)
            << err;
    }
    EXPECT_TRUE(only_texture_left());
}

TEST_F(CommandTest, BadOutputPathsFailBeforeRendering) {
    PlaneCommandOptions options;
    options.texture = texture_;
    options.width = 32;
    std::string err;
    options.output = dir_ / "out.bmp";
    EXPECT_EQ(plane(options, &err), 1);
    EXPECT_NE(err.find("out.bmp"), std::string::npos) << err;
    options.output = dir_ / "no_such_dir" / "out.png";
    EXPECT_EQ(plane(options, &err), 1);
    EXPECT_NE(err.find("no_such_dir"), std::string::npos) << err;
    EXPECT_TRUE(one_line(err)) << err;
    EXPECT_TRUE(only_texture_left());
}

TEST_F(CommandTest, DemoWritesEveryFile) {
    TextureDemoOptions options;
    options.out_dir = dir_ / "demo";  // created by the command
    options.width = 32;
    options.samples_per_axis = 2;
    options.texture_size = 64;
    options.quiet = true;
    ::testing::internal::CaptureStdout();
    const int status = run_texture_demo_command(options);
    const std::string table = ::testing::internal::GetCapturedStdout();
    ASSERT_EQ(status, 0);
    for (const char* name : {"reference", "nearest", "bilinear", "trilinear", "fa", "ewa", "sat"}) {
        const fs::path file = options.out_dir / ("demo_" + std::string(name) + ".png");
        EXPECT_TRUE(fs::exists(file)) << file;
        EXPECT_NE(table.find(name), std::string::npos) << table;
    }
    Result<Image> sheet = load_image(options.out_dir / "demo_contact_sheet.png");
    ASSERT_TRUE(sheet.ok());
    EXPECT_EQ(sheet->width, 4 * 32 + 5 * 4);
    EXPECT_GT(sheet->height, 2 * 18 + 3 * 4);  // and a label strip under each row's panels
    std::ifstream json_file(options.out_dir / "demo.json");
    const std::string json((std::istreambuf_iterator<char>(json_file)),
                           std::istreambuf_iterator<char>());
    EXPECT_NE(json.find("\"rmse\""), std::string::npos);
    EXPECT_NE(json.find("\"order\": [\"reference\", \"nearest\""), std::string::npos) << json;
    // The contact sheet as demo.json describes it: cells with their label strips, gaps between.
    const nlohmann::json described = nlohmann::json::parse(json)["contact_sheet"];
    const int gap = described["gap"], rows = described["rows"], columns = described["columns"];
    EXPECT_EQ(rows * described["cell_height"].get<int>() + (rows + 1) * gap, sheet->height);
    EXPECT_EQ(columns * described["cell_width"].get<int>() + (columns + 1) * gap, sheet->width);
    EXPECT_EQ(described["cell_height"].get<int>() - described["label_height"].get<int>(), 18);
    EXPECT_GT(described["label_height"].get<int>(), 0);
    for (const auto& e : fs::directory_iterator(options.out_dir))
        EXPECT_NE(e.path().filename().string().front(), '.') << "temporary file left: " << e.path();
}

// The last file of the run cannot be written (demo.json is a directory): the command fails naming
// it and leaves none of the run's images behind.
TEST_F(CommandTest, DemoThatFailsLeavesNothingOfItsRun) {
    TextureDemoOptions options;
    options.out_dir = dir_ / "demo";
    options.width = 32;
    options.samples_per_axis = 1;
    options.texture_size = 64;
    options.quiet = true;
    fs::create_directories(options.out_dir / "demo.json" / "inside");
    ::testing::internal::CaptureStdout();
    ::testing::internal::CaptureStderr();
    const int status = run_texture_demo_command(options);
    const std::string err = ::testing::internal::GetCapturedStderr();
    ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(status, 1);
    EXPECT_NE(err.find("demo.json"), std::string::npos) << err;
    EXPECT_TRUE(one_line(err)) << err;
    for (const auto& e : fs::directory_iterator(options.out_dir))
        EXPECT_EQ(e.path().filename(), "demo.json") << "left behind: " << e.path();
}

TEST_F(CommandTest, DemoIntoAFileFails) {
    TextureDemoOptions options;
    options.out_dir = texture_;  // exists, not a directory
    options.quiet = true;
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(run_texture_demo_command(options), 1);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("checker.png"), std::string::npos) << err;
    EXPECT_TRUE(one_line(err)) << err;
}

TEST(ViewHud, GpuTimeHasThreeSignificantDigits) {
    EXPECT_EQ(gpu_ms_text(5.4321), "5.43 ms GPU");
    EXPECT_EQ(gpu_ms_text(83.21), "83.2 ms GPU");
    EXPECT_EQ(gpu_ms_text(1169.4), "1169 ms GPU");
    EXPECT_EQ(gpu_ms_text(-1), "- ms GPU");
}

TEST(ViewFilter, AnUnknownOneIsViewsNotRenders) {
    const Result<GpuFilter> filter = parse_gpu_render_filter("sat", "view");
    ASSERT_FALSE(filter);
    EXPECT_EQ(filter.error().message.rfind("--filter: footprint view has no filter 'sat'", 0), 0u)
        << filter.error().message;
}

TEST(UnknownValue, IsNamedWithTheNearestAndTheAcceptedOnes) {
    const std::string_view modes[] = {"box", "tent"};
    EXPECT_EQ(unknown_value_problem("tnet", modes),
              "unknown value 'tnet' (did you mean 'tent'?); it accepts box, tent");
    EXPECT_EQ(unknown_value_problem("gaussian", modes),
              "unknown value 'gaussian'; it accepts box, tent");
    EXPECT_EQ(unknown_value_problem("box", modes), std::nullopt);
}

TEST(UnknownCommand, IsNamedWithTheNearestCommand) {
    const std::string_view commands[] = {"demo", "render", "eval", "metrics", "maketx"};
    EXPECT_EQ(unknown_command_problem("rendr", commands),
              "unknown command 'rendr' (did you mean 'render'?); the commands are demo, render, "
              "eval, metrics, maketx");
    EXPECT_EQ(unknown_command_problem("foo", commands),
              "unknown command 'foo'; the commands are demo, render, eval, metrics, maketx");
    EXPECT_EQ(unknown_command_problem("render", commands), std::nullopt);
    EXPECT_EQ(unknown_command_problem("--version", commands), std::nullopt);
}

}  // namespace
}  // namespace footprint
