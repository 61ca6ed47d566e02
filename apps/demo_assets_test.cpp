// Tests of the procedural demo assets (demo_assets.h) and of where the demo scenes find their
// files (demo_scenes.h).
#include "demo_assets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iterator>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "demo_scenes.h"
#include "envmap/env_layout.h"
#include "render/render_scene.h"

namespace footprint {
namespace {

double luminance(const Image& image, int x, int y) {
    const float* p = image.at(x, y);
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

bool all_finite(const Image& image) {
    for (float v : image.pixels)
        if (!std::isfinite(v)) return false;
    return true;
}

// Position of the largest luminance (the first one in row-major order).
void brightest_texel(const Image& image, int& bx, int& by) {
    double best = -1;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (const double l = luminance(image, x, y); l > best) {
                best = l;
                bx = x;
                by = y;
            }
}

// Distance in texels from texel (x, y)'s centre to the lat-long position of direction d, with
// the s seam wrapped.
double texel_distance_to(const Image& image, int x, int y, Vec3 d) {
    const Vec2 st = latlong_coords(d);
    double dx = x + 0.5 - st.x * image.width;
    dx -= image.width * std::round(dx / image.width);
    const double dy = y + 0.5 - st.y * image.height;
    return std::hypot(dx, dy);
}

double mean(const Image& image) {
    double sum = 0;
    for (float v : image.pixels) sum += v;
    return sum / static_cast<double>(image.pixels.size());
}

// Mean |h(x+1, y) − h(x, y)| over the interior (du) or |h(x, y+1) − h(x, y)| (dv), channel 0,
// and the same across the wrap-around border (x = W−1 → 0, y = H−1 → 0).
struct NeighbourDifferences {
    double interior_u = 0, interior_v = 0, border_u = 0, border_v = 0;
};
NeighbourDifferences neighbour_differences(const Image& h) {
    NeighbourDifferences d;
    const int w = h.width, ht = h.height;
    for (int y = 0; y < ht; ++y)
        for (int x = 0; x + 1 < w; ++x) d.interior_u += std::abs(h.at(x + 1, y, 0) - h.at(x, y, 0));
    for (int y = 0; y + 1 < ht; ++y)
        for (int x = 0; x < w; ++x) d.interior_v += std::abs(h.at(x, y + 1, 0) - h.at(x, y, 0));
    for (int y = 0; y < ht; ++y) d.border_u += std::abs(h.at(0, y, 0) - h.at(w - 1, y, 0));
    for (int x = 0; x < w; ++x) d.border_v += std::abs(h.at(x, 0, 0) - h.at(x, ht - 1, 0));
    d.interior_u /= static_cast<double>(w - 1) * ht;
    d.interior_v /= static_cast<double>(ht - 1) * w;
    d.border_u /= ht;
    d.border_v /= w;
    return d;
}

TEST(DemoAssets, SizesAndChannels) {
    struct Case {
        Image image;
        int width, height, channels;
    };
    const Case cases[] = {
        {make_night_sky_latlong(64), 64, 32, 3},
        {make_zebra_latlong(32), 32, 16, 3},
        {make_sky_gradient_latlong(64), 64, 32, 3},
        {make_water_height_map(32), 32, 32, 1},
        {make_brushed_metal_height_map(48), 48, 48, 1},
        {make_secret_writing_texture(128), 128, 128, 3},
        {make_night_sky_latlong(1), 16, 8, 3},
        {make_water_height_map(0), 16, 16, 1},
    };
    for (const Case& c : cases) {
        EXPECT_EQ(c.image.width, c.width);
        EXPECT_EQ(c.image.height, c.height);
        EXPECT_EQ(c.image.channels, c.channels);
        EXPECT_EQ(c.image.pixels.size(), static_cast<std::size_t>(c.width) * c.height * c.channels);
        EXPECT_TRUE(all_finite(c.image));
    }
}

// Default sizes: the same call twice gives bit-identical, finite texels.
TEST(DemoAssets, DeterministicAndFiniteAtDefaultSizes) {
    const std::function<Image()> makers[] = {
        [] { return make_night_sky_latlong(); },
        [] { return make_zebra_latlong(); },
        [] { return make_sky_gradient_latlong(); },
        [] { return make_water_height_map(); },
        [] { return make_brushed_metal_height_map(); },
        [] { return make_secret_writing_texture(); },
    };
    const int widths[] = {2048, 1024, 512, 512, 512, 1024};
    for (std::size_t i = 0; i < std::size(makers); ++i) {
        const Image a = makers[i](), b = makers[i]();
        EXPECT_EQ(a.width, widths[i]) << i;
        EXPECT_TRUE(all_finite(a)) << i;
        EXPECT_TRUE(a.pixels == b.pixels) << i;
    }
}

TEST(DemoAssetsNightSky, MoonDirection) {
    const Vec3 m = night_sky_moon_direction();
    // Float rounding of a unit vector computed in double.
    constexpr float kUnitTolerance = 1e-6f;
    EXPECT_NEAR(m.x * m.x + m.y * m.y + m.z * m.z, 1.0f, kUnitTolerance);
    const double elevation = std::asin(m.y) * 180 / std::numbers::pi;
    EXPECT_NEAR(elevation, kNightSkyMoonElevationDeg, 1e-4);
    EXPECT_GE(elevation, 15.0);
    EXPECT_LE(elevation, 20.0);
}

// The brightest texel is the moon's centre: within one texel of latlong_coords of its direction.
// (Limb darkening makes the texel nearest the centre the brightest; a centre between texel
// centres is at most √½ texel from the nearest one.)
TEST(DemoAssetsNightSky, BrightestTexelIsInTheMoonDirection) {
    for (int width : {2048, 512}) {
        const Image sky = make_night_sky_latlong(width);
        int bx = 0, by = 0;
        brightest_texel(sky, bx, by);
        EXPECT_LE(texel_distance_to(sky, bx, by, night_sky_moon_direction()), 1.0) << width;
        const double peak = luminance(sky, bx, by);
        EXPECT_GE(peak, 20.0);
        EXPECT_LE(peak, 50.0);
        // The disk is ~1.5° in radius: a texel 2° away is plain sky again.
        const Vec3 m = night_sky_moon_direction();
        const Vec2 st = latlong_coords(m);
        const double two_degrees_in_rows = 2.0 / 180.0 * sky.height;
        const int y_out = static_cast<int>(st.y * sky.height + two_degrees_in_rows + 1);
        EXPECT_LT(luminance(sky, bx, y_out), 1.0) << width;
        const int y_in = static_cast<int>(st.y * sky.height + 0.5 * two_degrees_in_rows);
        EXPECT_GT(luminance(sky, bx, y_in), 5.0) << width;
    }
}

TEST(DemoAssetsNightSky, LowerHemisphereIsDarkerAndStarless) {
    const Image sky = make_night_sky_latlong(1024);
    double upper = 0, lower = 0, lower_max = 0;
    for (int y = 0; y < sky.height; ++y)
        for (int x = 0; x < sky.width; ++x) {
            const double l = luminance(sky, x, y);
            if (y < sky.height / 2) {
                upper += l;
            } else {
                lower += l;
                lower_max = std::max(lower_max, l);
            }
        }
    EXPECT_LT(lower, 0.5 * upper);
    EXPECT_LT(lower_max, 0.02);  // a dark sea: no stars, no moon below the horizon
}

// Stars: thousands of isolated local maxima above the sky, outside the moon's glow.
TEST(DemoAssetsNightSky, HasThousandsOfStars) {
    const Image sky = make_night_sky_latlong();
    const Vec3 m = night_sky_moon_direction();
    int stars = 0;
    for (int y = 1; y < sky.height / 2; ++y)
        for (int x = 1; x + 1 < sky.width; ++x) {
            const Vec3 d = latlong_direction((x + 0.5f) / sky.width, (y + 0.5f) / sky.height);
            if (d.x * m.x + d.y * m.y + d.z * m.z > std::cos(0.1f)) continue;  // near the moon
            const double l = luminance(sky, x, y);
            bool is_max = l > 0.06;
            for (int dy = -1; dy <= 1 && is_max; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if ((dx || dy) && luminance(sky, x + dx, y + dy) >= l) is_max = false;
            stars += is_max;
        }
    EXPECT_GE(stars, 2000);
    EXPECT_LE(stars, 5000);
}

TEST(DemoAssetsZebra, MeanIsHalfAndRowsAreConstant) {
    const Image zebra = make_zebra_latlong();
    // The rows hold exact box integrals of a pattern that is white half the time over [0, π].
    EXPECT_NEAR(mean(zebra), 0.5, 1e-4);
    for (int y = 0; y < zebra.height; ++y) {
        const float v = zebra.at(0, y, 0);
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f);
        for (int x = 0; x < zebra.width; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_EQ(zebra.at(x, y, c), v) << x << ' ' << y;
    }
}

// Period: 180°/5° = 36 periods from pole to pole, so 71 black/white edges along a column, evenly
// spaced (one edge every 2.5°); each edge leaves at most one grey row (box filtering).
TEST(DemoAssetsZebra, HasTheClaimedPeriod) {
    for (int width : {1024, 2048, 400}) {
        const Image zebra = make_zebra_latlong(width);
        const double rows_per_degree = zebra.height / 180.0;
        std::vector<double> edges;
        int grey = 0;
        for (int y = 0; y < zebra.height; ++y) {
            const float v = zebra.at(7, y, 0);
            grey += v > 0.0f && v < 1.0f;
            if (y > 0 && (zebra.at(7, y - 1, 0) > 0.5f) != (v > 0.5f)) edges.push_back(y);
        }
        ASSERT_EQ(edges.size(), 71u) << width;
        EXPECT_LE(grey, 71) << width;
        EXPECT_GE(grey, 60) << width;  // nearly every edge falls inside a row
        // Edge k lies at θ = 2.5°(k + 1), i.e. row (k + 1)·2.5·rows_per_degree, ±1 row.
        for (std::size_t k = 0; k < edges.size(); ++k)
            EXPECT_NEAR(edges[k], (k + 1) * 0.5 * kZebraPeriodDeg * rows_per_degree, 1.0)
                << width << ' ' << k;
        EXPECT_GT(zebra.at(0, 0, 0), 0.99f);  // white at the zenith
    }
}

TEST(DemoAssetsSkyGradient, SunAndColours) {
    const Image sky = make_sky_gradient_latlong();
    int bx = 0, by = 0;
    brightest_texel(sky, bx, by);
    EXPECT_LE(texel_distance_to(sky, bx, by, sky_gradient_sun_direction()), 1.0);
    EXPECT_GT(luminance(sky, bx, by), 10.0);
    const float* zenith = sky.at(sky.width / 4, 0);
    EXPECT_GT(zenith[2], 2 * zenith[0]);  // deep blue
    const float* horizon = sky.at(sky.width / 4, sky.height / 2 - 1);
    const float* ground = sky.at(sky.width / 4, sky.height / 2);
    EXPECT_GT(horizon[2], 0.8f);
    EXPECT_LT(luminance(sky, sky.width / 4, sky.height / 2),
              0.5 * luminance(sky, sky.width / 4, sky.height / 2 - 1));
    EXPECT_GT(ground[0], ground[2]);  // brown-grey
}

// A tiling height map: the difference across each border is like a typical neighbour difference
// (a seam would be of the order of the value range, ≫ 2×); the mean is ~0 and the values fill
// most of [−1, 1].
void expect_tiling_height_map(const Image& h) {
    ASSERT_EQ(h.channels, 1);
    const NeighbourDifferences d = neighbour_differences(h);
    EXPECT_LE(d.border_u, 2.0 * d.interior_u + 1e-6);
    EXPECT_LE(d.border_v, 2.0 * d.interior_v + 1e-6);
    EXPECT_NEAR(mean(h), 0.0, 0.01);
    float lo = 0, hi = 0;
    for (float v : h.pixels) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_GE(lo, -1.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_GT(hi - lo, 1.0f);
}

TEST(DemoAssetsHeightMaps, WaterTilesWithZeroMean) {
    for (int size : {512, 100, 16}) expect_tiling_height_map(make_water_height_map(size));
    // Smooth: neighbour differences are small against the range (waves of ≥ 16 texels at 512).
    const NeighbourDifferences d = neighbour_differences(make_water_height_map());
    EXPECT_LT(d.interior_u, 0.1);
    EXPECT_LT(d.interior_v, 0.1);
}

TEST(DemoAssetsHeightMaps, BrushedMetalTilesWithZeroMean) {
    for (int size : {512, 200, 16}) expect_tiling_height_map(make_brushed_metal_height_map(size));
}

TEST(DemoAssetsHeightMaps, BrushedMetalIsAnisotropic) {
    for (int size : {512, 256}) {
        const NeighbourDifferences d = neighbour_differences(make_brushed_metal_height_map(size));
        EXPECT_GE(d.interior_v, 4.0 * d.interior_u) << size;
    }
}

// Fine strokes along u: the mean |horizontal neighbour difference| of luminance is large (each
// 1-texel stroke gives two ~0.8 steps); the 6× stretch makes vertical differences much rarer; the
// paper dominates, so the texture is light on average.
TEST(DemoAssetsSecretWriting, FineHighContrastLightText) {
    const Image tex = make_secret_writing_texture();
    double du = 0, dv = 0, sum = 0;
    for (int y = 0; y + 1 < tex.height; ++y)
        for (int x = 0; x + 1 < tex.width; ++x) {
            const double l = luminance(tex, x, y);
            du += std::abs(luminance(tex, x + 1, y) - l);
            dv += std::abs(luminance(tex, x, y + 1) - l);
            sum += l;
        }
    const double n = static_cast<double>(tex.width - 1) * (tex.height - 1);
    EXPECT_GT(du / n, 0.15);
    EXPECT_GT(du, 3.0 * dv);
    EXPECT_GT(sum / n, 0.5);
    for (float v : tex.pixels) {
        ASSERT_GE(v, 0.0f);
        ASSERT_LE(v, 1.0f);
    }
}

// ---- Where the demo scenes find their real files (demo_scenes.h).

namespace fs = std::filesystem;

// A fresh empty folder under the system temp directory, removed with everything in it.
class TempFolder {
  public:
    TempFolder() {
        std::random_device random;
        path_ = fs::temp_directory_path() / ("footprint-demo-test-" + std::to_string(random()) +
                                             "-" + std::to_string(random()));
        fs::create_directories(path_);
    }
    ~TempFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

// Sets an environment variable for one scope and puts the old value back.
class ScopedEnvironmentVariable {
  public:
    ScopedEnvironmentVariable(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        ::setenv(name, value.c_str(), 1);
    }
    ~ScopedEnvironmentVariable() {
        if (old_) {
            ::setenv(name_, old_->c_str(), 1);
        } else {
            ::unsetenv(name_);
        }
    }
    ScopedEnvironmentVariable(const ScopedEnvironmentVariable&) = delete;
    ScopedEnvironmentVariable& operator=(const ScopedEnvironmentVariable&) = delete;

  private:
    const char* name_;
    std::optional<std::string> old_;
};

// Every file a scene refers to: environment images, base-colour and bump maps.
std::vector<fs::path> scene_files(const SceneDesc& scene) {
    std::vector<fs::path> files;
    if (scene.environment)
        for (const ImageSource& image : scene.environment->images)
            if (!image.file.empty()) files.push_back(image.file);
    for (const ObjectDesc& object : scene.objects)
        for (const ImageSource* image :
             {&object.material.base_color_map, &object.material.bump.map})
            if (!image->file.empty()) files.push_back(image->file);
    return files;
}

const char* const kDemoEnvironment = "envmaps/venice_sunset_1k.hdr";
const char* const kDemoNormalMap = "normals/ambientCG_Bricks102_1K_NormalGL.jpg";

TEST(DemoScenes, ADataFolderThatIsNotThereIsWarnedOf) {
    const ScopedEnvironmentVariable data("FOOTPRINT_DATA", "/nonexistent/footprint-data");
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(DemoSceneOptions::default_demo_data_dir(), fs::path("/nonexistent/footprint-data"));
    EXPECT_EQ(::testing::internal::GetCapturedStderr(),
              "footprint: warning: FOOTPRINT_DATA '/nonexistent/footprint-data' is not a folder; "
              "the demo scenes use the repository's assets\n");
}

TEST(DemoScenes, WithAnEmptyDataFolderTheScenesUseTheRepositorysAssets) {
    TempFolder empty;
    const ScopedEnvironmentVariable data("FOOTPRINT_DATA", empty.path().string());
    EXPECT_EQ(DemoSceneOptions::default_demo_data_dir(), empty.path());
    const DemoSceneOptions options;  // as `footprint demo` makes them
    ASSERT_EQ(options.data_dir, empty.path());
    const fs::path assets = options.assets_dir;
    ASSERT_TRUE(fs::is_regular_file(assets / "LICENSES")) << assets;

    std::vector<std::string> used;
    for (const std::string& name : demo_scene_names()) {
        SCOPED_TRACE(name);
        const Result<DemoScene> demo = make_demo_scene(name, options);
        ASSERT_TRUE(demo.ok()) << demo.error().message;
        for (const fs::path& file : scene_files(demo->scene)) {
            EXPECT_EQ(file.parent_path().parent_path(), assets) << file;
            EXPECT_TRUE(fs::is_regular_file(file)) << file;
            EXPECT_NE(demo->assets.find(file.filename().string()), std::string::npos)
                << demo->assets;
            used.push_back(fs::relative(file, assets).generic_string());
        }
    }
    // The HDR sky in the eleven daylight scenes, the brick normal map on the bump plate and the
    // irradiance demo's floor.
    EXPECT_EQ(std::count(used.begin(), used.end(), kDemoEnvironment), 11) << used.size();
    EXPECT_EQ(std::count(used.begin(), used.end(), kDemoNormalMap), 2) << used.size();

    // The files load and pass the renderer's checks (no invalid normal map texels).
    for (const char* name : {"cylinder", "bump_plate"}) {
        SCOPED_TRACE(name);
        const Result<DemoScene> demo = make_demo_scene(name, options);
        ASSERT_TRUE(demo.ok());
        const Result<RenderScene> scene = prepare_render_scene(demo->scene);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
    }
}

TEST(DemoScenes, TheDataFolderComesFirstThenTheAssetsThenGeneratedAssets) {
    TempFolder data, no_assets;
    fs::create_directories(data.path() / "envmaps");
    DemoSceneOptions options;
    options.data_dir = data.path();
    options.assets_dir = DemoSceneOptions::default_demo_assets_dir();
    fs::copy_file(options.assets_dir / kDemoEnvironment, data.path() / kDemoEnvironment);
    Result<DemoScene> demo = make_demo_scene("bump_plate", options);
    ASSERT_TRUE(demo.ok());
    EXPECT_EQ(scene_files(demo->scene), std::vector<fs::path>{options.assets_dir / kDemoNormalMap});
    demo = make_demo_scene("cylinder", options);
    ASSERT_TRUE(demo.ok());
    EXPECT_EQ(scene_files(demo->scene), std::vector<fs::path>{data.path() / kDemoEnvironment});

    options.assets_dir = no_assets.path();
    options.data_dir = no_assets.path();
    for (const std::string& name : demo_scene_names()) {
        SCOPED_TRACE(name);
        demo = make_demo_scene(name, options);
        ASSERT_TRUE(demo.ok());
        EXPECT_TRUE(scene_files(demo->scene).empty());
        EXPECT_NE(demo->assets.find("generated"), std::string::npos) << demo->assets;
    }
}

}  // namespace
}  // namespace footprint
