// Tests of renders split across machines (apps/render_command.h's --tile and --frames A-B/N,
// apps/merge_command.h): bands and frame ranges are bit for bit the whole render's, the merge is
// the same file, and every bad split is refused naming what is wrong. (scripts/farm/check-split.sh
// runs the same split as separate processes.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "gpu/gpu_renderer.h"
#include "gpu/gpu_test_device.h"
#include "image/image_io.h"
#include "merge_command.h"
#include "render/renderer.h"
#include "render_command.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

std::string bytes_of(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FarmTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::random_device random;
        dir_ = fs::temp_directory_path() / ("footprint-farm-" + std::to_string(random()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    // `footprint render water` (a demo scene with a camera path) at 40 × 23.
    RenderCommandOptions render_options(const std::string& output) const {
        RenderCommandOptions o;
        o.scene = "water";
        o.output = dir_ / output;
        o.width = 40;
        o.quiet = true;
        return o;
    }
    static int quietly(int (*command)(const RenderCommandOptions&), const RenderCommandOptions& o,
                       std::string* err = nullptr) {
        ::testing::internal::CaptureStderr();
        const int status = command(o);
        const std::string text = ::testing::internal::GetCapturedStderr();
        if (err) *err = text;
        return status;
    }
    int merge(std::vector<std::string> tiles, const std::string& output,
              std::string* err = nullptr) const {
        MergeCommandOptions o;
        for (const std::string& t : tiles) o.tiles.push_back(dir_ / t);
        o.output = dir_ / output;
        ::testing::internal::CaptureStderr();
        const int status = run_merge_command(o);
        const std::string text = ::testing::internal::GetCapturedStderr();
        if (err) *err = text;
        return status;
    }
    fs::path dir_;
};

// Bands cover every row once, within one row of each other's height.
TEST(TileRows, BandsCoverEveryRowOnce) {
    for (int height : {1, 7, 90, 1081})
        for (int n = 1; n <= std::min(height, 13); ++n) {
            int next = 0;
            for (int i = 1; i <= n; ++i) {
                const RowBand b = tile_rows(i, n, height);
                EXPECT_EQ(b.begin, next);
                EXPECT_GE(b.end - b.begin, height / n);
                EXPECT_LE(b.end - b.begin, height / n + 1);
                next = b.end;
            }
            EXPECT_EQ(next, height);
        }
}

// In every mode, the stochastic and the reference's many samples included, a band is the whole
// image's rows bit for bit: a pixel's samples depend on its place only.
TEST(RenderBands, ABandIsTheWholeImagesRowsInEveryMode) {
    SceneDesc desc;
    desc.width = 20, desc.height = 14;
    desc.camera = {{0, 1, 3}, {0, 0, 0}, {0, 1, 0}, 45};
    desc.background = {0.2f, 0.3f, 0.4f};
    MaterialDesc bumpy;
    bumpy.mirror = 0.5f;
    bumpy.micro_roughness = 0.05f;
    desc.objects.push_back({"ball", SphereShape{{0, 0, 0}, 0.8}, bumpy});
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    for (FilterMode mode : {FilterMode::fa_rough, FilterMode::stochastic, FilterMode::reference}) {
        RenderOptions options;
        options.filter = mode;
        options.spp = mode == FilterMode::reference ? 4 : 1;
        const Image whole = render(*scene, options);
        options.rows = RowBand{5, 11};
        const Image band = render(*scene, options);
        ASSERT_EQ(band.height, 6);
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 20; ++x)
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(band.at(x, y, c), whole.at(x, 5 + y, c)) << filter_mode_name(mode);
    }
}

// A suite (so a process) of its own: see RenderCommandGpuTest in render_cli_test.cpp.
TEST(GpuRenderBands, ABandIsTheWholeImagesRows) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    SceneDesc desc;
    desc.width = 32, desc.height = 18;
    desc.camera = {{0, 1, 3}, {0, 0, 0}, {0, 1, 0}, 45};
    desc.background = {0.2f, 0.3f, 0.4f};
    desc.lights.push_back({});
    desc.objects.push_back({"ball", SphereShape{{0, 0, 0}, 0.8}, MaterialDesc{}});
    Result<RenderScene> scene = prepare_render_scene(desc);
    ASSERT_TRUE(scene) << scene.error().message;
    Result<GpuRenderer> gpu = GpuRenderer::create(*scene);
    ASSERT_TRUE(gpu) << gpu.error().message;
    GpuRenderOptions options;
    Result<Image> whole = gpu->render(options);
    options.rows = RowBand{3, 12};
    Result<Image> band = gpu->render(options);
    ASSERT_TRUE(whole && band);
    ASSERT_EQ(band->height, 9);
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_EQ(band->at(x, y, c), whole->at(x, 3 + y, c));
}

// Three tiles rendered apart and merged in any order: the same PNG and EXR bytes as the whole.
TEST_F(FarmTest, MergedTilesAreTheWholeRendersFiles) {
    ASSERT_EQ(quietly(run_render_command, render_options("whole.png")), 0);
    ASSERT_EQ(quietly(run_render_command, render_options("whole.exr")), 0);
    for (int i = 1; i <= 3; ++i) {
        RenderCommandOptions tile = render_options("tile" + std::to_string(i) + ".exr");
        tile.tile = std::pair{i, 3};
        std::string err;
        ASSERT_EQ(quietly(run_render_command, tile, &err), 0) << err;
    }
    std::string err;
    ASSERT_EQ(merge({"tile3.exr", "tile1.exr", "tile2.exr"}, "merged.png", &err), 0) << err;
    ASSERT_EQ(merge({"tile1.exr", "tile2.exr", "tile3.exr"}, "merged.exr", &err), 0) << err;
    EXPECT_EQ(bytes_of(dir_ / "merged.png"), bytes_of(dir_ / "whole.png"));
    EXPECT_EQ(bytes_of(dir_ / "merged.exr"), bytes_of(dir_ / "whole.exr"));
}

// Frames 0-1 and 2-3 of 4 in two runs: the files the whole sequence writes, byte for byte.
TEST_F(FarmTest, FrameRangesWriteTheWholeSequencesFiles) {
    RenderCommandOptions all = render_options("all/seq.png");
    fs::create_directories(dir_ / "all");
    fs::create_directories(dir_ / "split");
    all.frames = 4;
    ASSERT_EQ(quietly(run_render_command, all), 0);
    for (auto range : {std::pair{0, 1}, std::pair{2, 3}}) {
        RenderCommandOptions part = render_options("split/seq.png");
        ASSERT_TRUE(parse_frames_option(
            std::to_string(range.first) + "-" + std::to_string(range.second) + "/4", part));
        ASSERT_EQ(quietly(run_render_command, part), 0);
    }
    for (const char* name : {"seq_0000.png", "seq_0001.png", "seq_0002.png", "seq_0003.png"}) {
        ASSERT_TRUE(fs::exists(dir_ / "split" / name)) << name;
        EXPECT_EQ(bytes_of(dir_ / "split" / name), bytes_of(dir_ / "all" / name)) << name;
    }
}

TEST_F(FarmTest, BadSplitsAreRefusedNamingWhatIsWrong) {
    struct Case {
        std::string frames, tile, output, message;
    };
    const Case cases[] = {
        {"5-9/8", "", "a.png", "--frames 5-9/8: A-B must lie within 0-7 with A <= B"},
        {"3-1/8", "", "a.png", "--frames 3-1/8: A-B must lie within 0-7"},
        {"", "0/3", "a.exr", "--tile 0/3: I must be 1 to 3"},
        {"", "4/3", "a.exr", "--tile 4/3: I must be 1 to 3"},
        {"", "1/3", "a.png", "--tile: a band is written as an OpenEXR data window, so -o must be"},
        {"", "1/100", "a.exr", "--tile 1/100: the image has only 23 rows"},
    };
    for (const Case& c : cases) {
        RenderCommandOptions o = render_options(c.output);
        if (!c.frames.empty()) {
            ASSERT_TRUE(parse_frames_option(c.frames, o));
        }
        if (!c.tile.empty()) {
            ASSERT_TRUE(parse_tile_option(c.tile, o));
        }
        std::string err;
        EXPECT_EQ(quietly(run_render_command, o, &err), 1) << c.message;
        EXPECT_NE(err.find(c.message), std::string::npos) << err;
        EXPECT_FALSE(fs::exists(o.output));
    }
    RenderCommandOptions o;
    for (const char* text : {"", "x", "3-/8", "-1", "1-2-3/4", "2/"}) {
        const Status parsed = parse_frames_option(text, o);
        ASSERT_FALSE(parsed) << text;
        EXPECT_NE(parsed.error().message.find("expected N or A-B/N"), std::string::npos);
    }
    for (const char* text : {"", "3", "1/", "/3", "a/b"})
        EXPECT_FALSE(parse_tile_option(text, o)) << text;
}

// A merge that lacks a band, has two that overlap, or mixes images: refused, nothing written.
TEST_F(FarmTest, MergeRefusesTilesThatAreNotOneImage) {
    for (int i = 1; i <= 3; ++i) {
        RenderCommandOptions tile = render_options("t" + std::to_string(i) + ".exr");
        tile.tile = std::pair{i, 3};
        ASSERT_EQ(quietly(run_render_command, tile), 0);
    }
    RenderCommandOptions other = render_options("other.exr");
    other.width = 48;
    other.tile = std::pair{3, 3};
    ASSERT_EQ(quietly(run_render_command, other), 0);
    std::string err;
    EXPECT_EQ(merge({"t1.exr", "t3.exr"}, "m.png", &err), 1);
    EXPECT_NE(err.find("rows 7 to 14 are in no tile"), std::string::npos) << err;
    EXPECT_EQ(merge({"t1.exr", "t2.exr"}, "m.png", &err), 1);
    EXPECT_NE(err.find("rows 15 to 22 are in no tile"), std::string::npos) << err;
    EXPECT_EQ(merge({"t1.exr", "t2.exr", "t2.exr", "t3.exr"}, "m.png", &err), 1);
    EXPECT_NE(err.find("overlaps the tile before it"), std::string::npos) << err;
    EXPECT_EQ(merge({"t1.exr", "t2.exr", "other.exr"}, "m.png", &err), 1);
    EXPECT_NE(err.find("is a band of a 48x27 image"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir_ / "m.png"));
}

}  // namespace
}  // namespace footprint
