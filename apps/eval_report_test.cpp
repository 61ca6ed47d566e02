// Tests of the evaluation report (eval_report.h).
#include "eval_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "image/image_io.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// hardest_regions

// The greedy choice computed directly: every window's mean by summing its pixels.
std::vector<CropRect> brute_force_regions(const Image& error, int count, int size) {
    const int w = std::min(size, error.width), h = std::min(size, error.height);
    std::vector<CropRect> chosen;
    auto overlaps = [](const CropRect& a, const CropRect& b) {
        return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height &&
               b.y < a.y + a.height;
    };
    while (static_cast<int>(chosen.size()) < count) {
        bool found = false;
        CropRect best;
        double best_mean = 0;
        for (int y = 0; y + h <= error.height; ++y)
            for (int x = 0; x + w <= error.width; ++x) {
                const CropRect r{x, y, w, h};
                bool free = true;
                for (const CropRect& c : chosen) free = free && !overlaps(r, c);
                if (!free) continue;
                double sum = 0;
                for (int yy = y; yy < y + h; ++yy)
                    for (int xx = x; xx < x + w; ++xx) sum += error.at(xx, yy, 0);
                const double mean = sum / (w * h);
                if (!found || mean > best_mean) {
                    found = true;
                    best = r;
                    best_mean = mean;
                }
            }
        if (!found) break;
        chosen.push_back(best);
    }
    return chosen;
}

// Values k/1024 (exact in float and in double sums) so that the two computations agree exactly.
Image random_error_image(int width, int height, int channels, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> k(0, 1023);
    Image image(width, height, channels);
    for (float& v : image.pixels) v = static_cast<float>(k(random)) / 1024.0f;
    return image;
}

void expect_same_regions(const std::vector<CropRect>& a, const std::vector<CropRect>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].x, b[i].x) << "region " << i;
        EXPECT_EQ(a[i].y, b[i].y) << "region " << i;
        EXPECT_EQ(a[i].width, b[i].width) << "region " << i;
        EXPECT_EQ(a[i].height, b[i].height) << "region " << i;
    }
}

TEST(EvalReportRegions, MatchBruteForce) {
    struct Case {
        int width, height, channels, count, size;
    };
    const Case cases[] = {{37, 23, 1, 5, 6},
                          {40, 40, 3, 8, 7},
                          {16, 9, 4, 20, 4},
                          {31, 17, 1, 3, 1},
                          {12, 50, 2, 4, 11}};
    unsigned seed = 1;
    for (const Case& c : cases) {
        const Image error = random_error_image(c.width, c.height, c.channels, seed++);
        SCOPED_TRACE(testing::Message()
                     << c.width << "x" << c.height << " count " << c.count << " size " << c.size);
        expect_same_regions(hardest_regions(error, c.count, c.size),
                            brute_force_regions(error, c.count, c.size));
    }
}

TEST(EvalReportRegions, FindsAHotSpotAndNeverOverlaps) {
    Image error(64, 48, 1, 0.01f);
    for (int y = 30; y < 38; ++y)
        for (int x = 50; x < 58; ++x) error.at(x, y, 0) = 1.0f;
    error.at(3, 4, 0) = std::numeric_limits<float>::quiet_NaN();  // counts as 0
    const std::vector<CropRect> regions = hardest_regions(error, 6, 8);
    ASSERT_EQ(regions.size(), 6u);
    EXPECT_EQ(regions[0].x, 50);
    EXPECT_EQ(regions[0].y, 30);
    for (std::size_t i = 0; i < regions.size(); ++i)
        for (std::size_t j = i + 1; j < regions.size(); ++j) {
            const CropRect& a = regions[i];
            const CropRect& b = regions[j];
            EXPECT_FALSE(a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height &&
                         b.y < a.y + a.height)
                << i << " and " << j << " overlap";
        }
}

TEST(EvalReportRegions, ClampsAndHandlesDegenerateInput) {
    const Image error = random_error_image(10, 6, 1, 7);
    const std::vector<CropRect> whole = hardest_regions(error, 3, 100);
    ASSERT_EQ(whole.size(), 1u);  // the one window is the whole image
    EXPECT_EQ(whole[0].width, 10);
    EXPECT_EQ(whole[0].height, 6);
    EXPECT_TRUE(hardest_regions(error, 0, 4).empty());
    EXPECT_TRUE(hardest_regions(error, 3, 0).empty());
    EXPECT_TRUE(hardest_regions(Image(), 3, 4).empty());
    // 2 × 2 windows in 10 × 6: at most 5 × 3 fit without overlap.
    EXPECT_LE(hardest_regions(error, 100, 2).size(), 15u);
    EXPECT_GE(hardest_regions(error, 100, 2).size(), 4u);
}

// ---------------------------------------------------------------------------------------------
// equal_error_speedup

// RMSE = 0.1/√spp and seconds = 0.01·spp: log seconds is linear in log RMSE (slope −2), so the
// interpolation is exact: the time at RMSE r is 0.01 · (0.1/r)².
std::vector<EvalMethod> synthetic_supersampling(std::vector<int> spps = {16, 1, 64, 4}) {
    std::vector<EvalMethod> result;
    for (int spp : spps) {
        EvalMethod m;
        m.name = "supersampling " + std::to_string(spp) + " spp";
        m.family = "supersampling";
        m.spp = spp;
        m.rmse = 0.1 / std::sqrt(double(spp));
        m.seconds = 0.01 * spp;
        result.push_back(m);
    }
    return result;
}

EvalMethod filter_method(const std::string& name, double rmse, double seconds) {
    EvalMethod m;
    m.name = name;
    m.family = "filter";
    m.rmse = rmse;
    m.seconds = seconds;
    return m;
}

TEST(EvalReportSpeedup, InterpolatesExactly) {
    const auto ss = synthetic_supersampling();
    // RMSE of 8 spp, between the 4 and 16 spp points: supersampling takes 0.08 s.
    const EqualErrorSpeedup a =
        equal_error_speedup(filter_method("a", 0.1 / std::sqrt(8.0), 0.004), ss);
    ASSERT_TRUE(a.defined);
    EXPECT_FALSE(a.extrapolated);
    EXPECT_FALSE(a.above_lowest_spp);
    EXPECT_NEAR(a.seconds, 0.08, 1e-12);
    EXPECT_NEAR(a.speedup, 20.0, 1e-9);
    // Exactly on a point (16 spp): 0.16 s.
    const EqualErrorSpeedup b = equal_error_speedup(filter_method("b", 0.025, 0.02), ss);
    ASSERT_TRUE(b.defined);
    EXPECT_NEAR(b.speedup, 8.0, 1e-9);
    // RMSE of 2 spp: 0.02 s, slower than the method's 0.04 s.
    const EqualErrorSpeedup c =
        equal_error_speedup(filter_method("c", 0.1 / std::sqrt(2.0), 0.04), ss);
    ASSERT_TRUE(c.defined);
    EXPECT_NEAR(c.speedup, 0.5, 1e-12);
    // Equal to the 1 spp point: not flagged.
    const EqualErrorSpeedup d = equal_error_speedup(filter_method("d", 0.1, 0.005), ss);
    ASSERT_TRUE(d.defined);
    EXPECT_FALSE(d.above_lowest_spp);
    EXPECT_NEAR(d.speedup, 2.0, 1e-12);
}

TEST(EvalReportSpeedup, ExtrapolatesBelowTheLastPoint) {
    const auto ss = synthetic_supersampling();
    // RMSE of 256 spp: beyond 64 spp; the fitted slope is exact, 2.56 s.
    const EqualErrorSpeedup s = equal_error_speedup(filter_method("x", 0.1 / 16, 0.01), ss);
    ASSERT_TRUE(s.defined);
    EXPECT_TRUE(s.extrapolated);
    EXPECT_FALSE(s.above_lowest_spp);
    EXPECT_NEAR(s.seconds, 2.56, 1e-9);
    EXPECT_NEAR(s.speedup, 256.0, 1e-7);
}

TEST(EvalReportSpeedup, FlagsWorseThanTheLowestSpp) {
    const auto ss = synthetic_supersampling();
    const EqualErrorSpeedup s = equal_error_speedup(filter_method("x", 0.3, 0.02), ss);
    ASSERT_TRUE(s.defined);
    EXPECT_TRUE(s.above_lowest_spp);
    EXPECT_FALSE(s.extrapolated);
    EXPECT_NEAR(s.seconds, 0.01, 1e-12);  // the 1 spp time
    EXPECT_NEAR(s.speedup, 0.5, 1e-12);
}

TEST(EvalReportSpeedup, UndefinedCases) {
    const auto ss = synthetic_supersampling();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(equal_error_speedup(filter_method("x", 0.05, 0.01), {}).defined);
    EXPECT_FALSE(equal_error_speedup(filter_method("x", 0.05, 0.0), ss).defined);
    EXPECT_FALSE(equal_error_speedup(filter_method("x", nan, 0.01), ss).defined);
    EXPECT_FALSE(equal_error_speedup(filter_method("x", 0.0, 0.01), ss).defined);
    const EqualErrorSpeedup u = equal_error_speedup(filter_method("x", 0.05, nan), ss);
    EXPECT_FALSE(u.defined);
    EXPECT_TRUE(std::isnan(u.speedup));
    // One point, method better than it: nothing to extrapolate from.
    EXPECT_FALSE(
        equal_error_speedup(filter_method("x", 0.01, 0.01), synthetic_supersampling({4})).defined);
    // Last two points without decreasing RMSE: no slope to extrapolate with.
    auto flat = synthetic_supersampling({1, 4, 16});
    flat[2].rmse = flat[1].rmse;
    EXPECT_FALSE(equal_error_speedup(filter_method("x", 0.001, 0.01), flat).defined);
    // Invalid supersampling points are ignored.
    auto with_bad = synthetic_supersampling();
    with_bad.push_back(filter_method("bad", nan, 1.0));
    with_bad.back().family = "supersampling";
    with_bad.back().spp = 2;
    EXPECT_NEAR(
        equal_error_speedup(filter_method("a", 0.1 / std::sqrt(8.0), 0.004), with_bad).speedup,
        20.0, 1e-9);
}

TEST(EvalReportSpeedup, Labels) {
    EqualErrorSpeedup s;
    EXPECT_EQ(speedup_label(s), "\u2014");
    s.defined = true;
    s.speedup = 12.3;
    EXPECT_EQ(speedup_label(s), "\u00d712");
    s.speedup = 3.44;
    EXPECT_EQ(speedup_label(s), "\u00d73.4");
    s.speedup = 0.523;
    EXPECT_EQ(speedup_label(s), "\u00d70.52");
    s.speedup = 120;
    s.extrapolated = true;
    EXPECT_EQ(speedup_label(s), "\u2248\u00d7120 (extrapolated)");
    EXPECT_EQ(speedup_label(s, true), "\u2248\u00d7120");
    s.extrapolated = false;
    s.above_lowest_spp = true;
    s.speedup = 0.8;
    EXPECT_EQ(speedup_label(s, true), "\u2264\u00d70.8");
}

// ---------------------------------------------------------------------------------------------
// The plot

int count_of(const std::string& text, const std::string& needle) {
    int n = 0;
    for (std::size_t i = text.find(needle); i != std::string::npos; i = text.find(needle, i + 1))
        ++n;
    return n;
}

EvalScene synthetic_scene(const std::string& name) {
    EvalScene scene;
    scene.name = name;
    scene.title = "Scene " + name + " <&>";
    scene.width = 48;
    scene.height = 27;
    scene.reference_file = name + "/reference.png";
    scene.reference_spp = 256;
    scene.reference_seconds = 2.56;
    for (EvalMethod m : synthetic_supersampling({1, 4, 16, 64})) {
        m.image_file = name + "/ss" + std::to_string(m.spp) + ".png";
        m.heat_map_file = name + "/heat/ss" + std::to_string(m.spp) + ".png";
        scene.methods.push_back(m);
    }
    EvalMethod fa = filter_method("fa-rough", 0.1 / std::sqrt(8.0), 0.004);
    fa.image_file = name + "/fa-rough.png";
    fa.heat_map_file = name + "/heat/fa-rough.png";
    fa.ssim = 0.93;
    fa.flicker = 0.012;
    scene.methods.push_back(fa);
    EvalMethod ewa = filter_method("ewa rough", 0.1 / 16, 0.01);  // extrapolated
    ewa.image_file = name + "/ewa rough.png";                     // a space in the URL
    ewa.heat_map_file = name + "/heat/ewa rough.png";
    scene.methods.push_back(ewa);
    EvalMethod point = filter_method("point", 0.3, 0.002);  // worse than 1 spp
    point.image_file = name + "/point.png";
    point.heat_map_file = name + "/heat/point.png";
    scene.methods.push_back(point);
    scene.crops = {{4, 3, 8, 8}, {30, 15, 8, 8}};
    scene.heat_map_scale = {2.5, 0.0025};
    return scene;
}

TEST(EvalReportPlot, IsWellFormedSvg) {
    const EvalScene scene = synthetic_scene("plot");
    const std::string svg = error_time_plot_svg(scene);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_EQ(count_of(svg, "<text"), count_of(svg, "</text>"));
    EXPECT_EQ(count_of(svg, "<g"), count_of(svg, "</g>"));
    for (const EvalMethod& m : scene.methods)
        EXPECT_NE(svg.find(m.name), std::string::npos) << m.name;
    for (const char* bad : {"nan", "NaN", "inf", "Inf"})
        EXPECT_EQ(svg.find(bad), std::string::npos) << bad;
    EXPECT_NE(svg.find(">\u00d720<"), std::string::npos);         // fa-rough, interpolated
    EXPECT_NE(svg.find(">\u2248\u00d7256<"), std::string::npos);  // ewa rough, extrapolated
    EXPECT_NE(svg.find("64 spp"), std::string::npos);
    EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
    EXPECT_EQ(svg.find("http://", svg.find("xmlns") + 20), std::string::npos);  // no resources
}

TEST(EvalReportPlot, SurvivesMissingData) {
    EvalScene scene;
    std::string svg = error_time_plot_svg(scene);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("no data"), std::string::npos);
    // A single filter method without supersampling, and one with NaN values.
    scene.methods.push_back(filter_method("only", 0.05, 0.01));
    scene.methods.push_back(
        filter_method("broken", std::numeric_limits<double>::quiet_NaN(), 0.01));
    svg = error_time_plot_svg(scene);
    EXPECT_NE(svg.find("only"), std::string::npos);
    for (const char* bad : {"nan", "inf"}) EXPECT_EQ(svg.find(bad), std::string::npos) << bad;
}

bool overlap(const PlotBox& a, const PlotBox& b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

// Crowded plots, as real evaluations give them: five filter modes of nearly the same time and
// error beside the supersampling curve. No label overlaps another, a point, a marker or the
// legend, and every label stays inside the axes.
TEST(EvalReportPlot, LabelsOverlapNothingInACrowdedPlot) {
    struct Crowd {
        const char* name;
        double time_step, rmse_ratio;  // between one filter mode and the next
    };
    for (const Crowd& crowd : {Crowd{"spread", 1.15, 0.9}, Crowd{"close", 1.03, 0.97},
                               Crowd{"identical", 1.0, 1.0}, Crowd{"on the curve", 1.6, 0.8}}) {
        SCOPED_TRACE(crowd.name);
        EvalScene scene;
        scene.methods = synthetic_supersampling({1, 4, 16, 64, 256});
        double seconds = 0.004, rmse = 0.05;
        for (const char* name : {"bilinear", "trilinear", "fa", "fa-rough", "ewa-rough"}) {
            scene.methods.push_back(filter_method(name, rmse, seconds));
            seconds *= crowd.time_step;
            rmse *= crowd.rmse_ratio;
        }
        const PlotLabelLayout layout = error_time_plot_labels(scene);
        // 5 spp labels, 5 names, 5 speedups.
        ASSERT_EQ(layout.labels.size(), 15u);
        ASSERT_EQ(layout.texts.size(), 15u);
        const PlotBox& area = layout.area;
        for (std::size_t i = 0; i < layout.labels.size(); ++i) {
            const PlotBox& a = layout.labels[i];
            EXPECT_TRUE(a.x0 >= area.x0 && a.y0 >= area.y0 && a.x1 <= area.x1 && a.y1 <= area.y1)
                << "'" << layout.texts[i] << "' leaves the plot";
            for (std::size_t j = i + 1; j < layout.labels.size(); ++j)
                EXPECT_FALSE(overlap(a, layout.labels[j]))
                    << "'" << layout.texts[i] << "' overlaps '" << layout.texts[j] << "'";
            for (const PlotBox& mark : layout.marks)
                EXPECT_FALSE(overlap(a, mark)) << "'" << layout.texts[i] << "' covers a mark";
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The heat maps' scale and legend

TEST(EvalReportHeatMaps, SceneScaleSaturatesNoPixel) {
    // Two methods' errors: 1 … 100 (a firefly of 100 among small errors) and 0s.
    Image small(10, 10, 1), zero(10, 10, 1, 0.0f);
    for (std::size_t p = 0; p < 100; ++p) small.pixels[p] = 0.001f * static_cast<float>(p + 1);
    small.pixels[57] = 100.0f;
    const HeatMapScale scale = scene_heat_map_scale({small, zero});
    EXPECT_EQ(scale.top, 100.0);
    // The 5th percentile of the 100 positive errors (rank 5 of 0.001 … 0.1 without 0.058).
    EXPECT_FLOAT_EQ(static_cast<float>(scale.bottom), 0.006f);
    for (float v : small.pixels) EXPECT_LE(heat_map_position(v, scale), 1.0);
    EXPECT_LT(heat_map_position(0.1, scale), 0.5);  // small errors stay distinguishable
    EXPECT_GT(heat_map_position(0.1, scale), heat_map_position(0.01, scale));
    // At most 6 decades, at least 1.
    Image wide(2, 1, 1);
    wide.pixels = {1e-12f, 1.0f};
    EXPECT_NEAR(scene_heat_map_scale({wide}).bottom, 1e-6, 1e-12);
    wide.pixels = {0.9f, 1.0f};
    EXPECT_NEAR(scene_heat_map_scale({wide}).bottom, 0.1, 1e-9);
    // Nothing differs (or only non-finite values): linear, every heat map black.
    Image broken = zero;
    broken.pixels[3] = std::numeric_limits<float>::quiet_NaN();
    const HeatMapScale none = scene_heat_map_scale({zero, broken});
    EXPECT_EQ(none.top, 1.0);
    EXPECT_EQ(none.bottom, 0.0);
}

TEST(EvalReportHeatMaps, LegendShowsTheRampAndTheDecades) {
    const std::string svg = heat_map_legend_svg({10.0, 0.001}, "my scene");
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("id=\"heat-legend-my_scene\""), std::string::npos);
    // The ramp's stops as the PNGs store them: black, pure blue, red, yellow, white.
    for (const char* stop :
         {"offset=\"0.0000\" stop-color=\"#000000\"", "offset=\"0.2500\" stop-color=\"#0000ff\"",
          "offset=\"0.5000\" stop-color=\"#ff0000\"", "offset=\"0.7500\" stop-color=\"#ffff00\"",
          "offset=\"1.0000\" stop-color=\"#ffffff\""})
        EXPECT_NE(svg.find(stop), std::string::npos) << stop;
    for (const char* label : {">\u2264 0.001<", ">0.01<", ">0.1<", ">1<", ">10<"})
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    EXPECT_EQ(count_of(svg, "<text"), count_of(svg, "</text>"));
    for (const char* bad : {"nan", "inf"}) EXPECT_EQ(svg.find(bad), std::string::npos) << bad;
    const std::string linear = heat_map_legend_svg({0.8, 0}, "x");
    for (const char* label : {">0<", ">0.2<", ">0.4<", ">0.6<", ">0.8<"})
        EXPECT_NE(linear.find(label), std::string::npos) << label;
}

// ---------------------------------------------------------------------------------------------
// The HTML file and the browser check

class EvalReportFile : public testing::Test {
  protected:
    void SetUp() override {
        std::random_device random;
        dir_ = fs::temp_directory_path() / ("footprint-eval-report-" + std::to_string(random()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }

    // Writes every image the scene references (a gradient; heat maps in red).
    void write_images(const EvalScene& scene) {
        std::vector<std::string> files = {scene.reference_file};
        for (const EvalMethod& m : scene.methods) {
            files.push_back(m.image_file);
            files.push_back(m.heat_map_file);
        }
        for (const std::string& f : files) {
            if (f.empty()) continue;
            Image image(scene.width, scene.height, 3);
            for (int y = 0; y < scene.height; ++y)
                for (int x = 0; x < scene.width; ++x) {
                    image.at(x, y, 0) = float(x) / scene.width;
                    image.at(x, y, 1) = f.find("heat") == std::string::npos ? float(y) / 27 : 0;
                    image.at(x, y, 2) = 0.3f;
                }
            const fs::path path = dir_ / f;
            fs::create_directories(path.parent_path());
            ASSERT_TRUE(save_image(image, path).ok()) << path;
        }
    }

    EvalReport synthetic_report() {
        EvalReport report;
        report.title = "Evaluation <test> & \"quotes\"";
        report.generated_by = "eval_report_test";
        report.scenes = {synthetic_scene("first"), synthetic_scene("second")};
        report.scenes[1].crops = {hardest_regions(random_error_image(48, 27, 1, 3), 3, 10)};
        return report;
    }

    std::string read(const fs::path& file) {
        std::ifstream in(file, std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }

    fs::path dir_;
};

TEST_F(EvalReportFile, WritesSelfContainedEscapedHtml) {
    const EvalReport report = synthetic_report();
    const fs::path html = dir_ / "report.html";
    ASSERT_TRUE(write_eval_report(report, html).ok());
    const std::string text = read(html);
    EXPECT_EQ(text.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(text.find("Evaluation &lt;test&gt; &amp; &quot;quotes&quot;"), std::string::npos);
    EXPECT_EQ(text.find("<test>"), std::string::npos);
    EXPECT_NE(text.find("Scene first &lt;&amp;&gt;"), std::string::npos);
    EXPECT_NE(text.find("src=\"first/ewa%20rough.png\""), std::string::npos);
    EXPECT_EQ(text.find("<link"), std::string::npos);
    EXPECT_EQ(text.find("<script src"), std::string::npos);
    EXPECT_EQ(text.find("http://", text.find("</style>")), text.find("http://www.w3.org/2000/svg"));
    EXPECT_EQ(count_of(text, "<svg"), 6);  // per scene the legend and the two plots
    EXPECT_EQ(count_of(text, "samples per pixel (log scale)"), 2);
    EXPECT_NE(text.find("\u2248\u00d7256 (extrapolated)"), std::string::npos);
    EXPECT_NE(text.find("\u00d720<"), std::string::npos);
    EXPECT_NE(text.find("image-rendering: pixelated"), std::string::npos);
    // Per scene: reference + 7 methods × (image + heat map), crops × (reference + 7 methods).
    const int first = 1 + 7 * 2 + 2 * 8;
    const int second = 1 + 7 * 2 + static_cast<int>(report.scenes[1].crops.size()) * 8;
    EXPECT_EQ(report_image_count(report), first + second);
    EXPECT_EQ(count_of(text, "<img "), first + second);
    // No temporary file is left behind.
    int entries = 0;
    for (const auto& e : fs::directory_iterator(dir_)) entries += e.is_regular_file();
    EXPECT_EQ(entries, 1);
}

TEST_F(EvalReportFile, SaysWhatTheMethodsAreAndShowsALegendPerScene) {
    EvalReport report = synthetic_report();
    report.scenes[1].heat_map_scale = {0.5, 0};  // linear
    const fs::path html = dir_ / "report.html";
    ASSERT_TRUE(write_eval_report(report, html).ok());
    const std::string text = read(html);
    // The methods header comes before the first scene, one entry per method shown.
    const std::size_t header = text.find("<h2>The methods</h2>");
    ASSERT_NE(header, std::string::npos);
    EXPECT_LT(header, text.find("<section class=\"scene\""));
    for (const char* entry : {"<dt>fa-rough</dt><dd>fa plus the roughness pyramid",
                              "<dt>point</dt><dd>one bilinear lookup of the finest level",
                              "<dt>ewa rough</dt><dd>a filter mode", "<dt>supersampling N spp</dt>",
                              "<dt>reference</dt><dd>the ground truth"})
        EXPECT_NE(text.find(entry), std::string::npos) << entry;
    EXPECT_EQ(count_of(text, "<dt>fa-rough</dt>"), 1);  // once, though both scenes have it
    // A legend per scene, before its images, with its own gradient and its scale's ends.
    EXPECT_EQ(count_of(text, "<div class=\"legend\">"), 2);
    EXPECT_NE(text.find("id=\"heat-legend-first\""), std::string::npos);
    EXPECT_NE(text.find("url(#heat-legend-second)"), std::string::npos);
    EXPECT_LT(text.find("<div class=\"legend\">"), text.find("<div class=\"figures\">"));
    EXPECT_NE(text.find("Logarithmic from 0.0025"), std::string::npos);
    EXPECT_NE(text.find(">\u2264 0.0025</text>"), std::string::npos);
    EXPECT_NE(text.find(">2.5</text>"), std::string::npos);
    EXPECT_NE(text.find("Linear from 0 (black) to 0.5 (white)"), std::string::npos);
    // No legend without a scale.
    report.scenes[0].heat_map_scale = {};
    report.scenes[0].heat_map_scale.top = std::numeric_limits<double>::quiet_NaN();
    ASSERT_TRUE(write_eval_report(report, html).ok());
    EXPECT_EQ(count_of(read(html), "<div class=\"legend\">"), 1);
}

TEST_F(EvalReportFile, WriteFailsForAMissingDirectory) {
    const Status status = write_eval_report(synthetic_report(), dir_ / "missing" / "report.html");
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("report.html"), std::string::npos);
}

TEST_F(EvalReportFile, EveryImageLoadsInChromium) {
    if (!find_chromium()) GTEST_SKIP() << "chromium is not installed (or set FOOTPRINT_CHROMIUM)";
    const EvalReport report = synthetic_report();
    for (const EvalScene& s : report.scenes) write_images(s);
    const fs::path html = dir_ / "report.html";
    ASSERT_TRUE(write_eval_report(report, html).ok());
    const int expected = report_image_count(report);
    const BrowserCheck check = check_report_in_browser(html, expected);
    EXPECT_TRUE(check.chromium_found);
    EXPECT_TRUE(check.ran) << check.problem;
    EXPECT_TRUE(check.passed()) << check.problem;
    EXPECT_EQ(check.images_total, expected);
    EXPECT_EQ(check.images_loaded, expected);
    EXPECT_EQ(check.images_failed, 0);
    // More images expected than there are: a problem.
    const BrowserCheck too_few = check_report_in_browser(html, expected + 1);
    EXPECT_TRUE(too_few.ran);
    EXPECT_FALSE(too_few.passed());
    EXPECT_NE(too_few.problem.find("expected"), std::string::npos) << too_few.problem;
}

TEST_F(EvalReportFile, ChromiumReportsAMissingImage) {
    if (!find_chromium()) GTEST_SKIP() << "chromium is not installed (or set FOOTPRINT_CHROMIUM)";
    EvalReport report = synthetic_report();
    for (const EvalScene& s : report.scenes) write_images(s);
    report.scenes[1].methods[5].heat_map_file = "second/heat/missing.png";
    const fs::path html = dir_ / "report.html";
    ASSERT_TRUE(write_eval_report(report, html).ok());
    const BrowserCheck check = check_report_in_browser(html, report_image_count(report));
    EXPECT_TRUE(check.ran) << check.problem;
    EXPECT_FALSE(check.passed());
    EXPECT_EQ(check.images_failed, 1);
    EXPECT_EQ(check.images_loaded, report_image_count(report) - 1);
    EXPECT_NE(check.problem.find("missing.png"), std::string::npos) << check.problem;
}

TEST_F(EvalReportFile, BrowserCheckWithoutChromiumOrFile) {
    const char* old = std::getenv("FOOTPRINT_CHROMIUM");
    const std::string saved = old ? old : "";
    ::setenv("FOOTPRINT_CHROMIUM", (dir_ / "no-such-browser").c_str(), 1);
    const BrowserCheck check = check_report_in_browser(dir_ / "report.html", 1);
    if (old)
        ::setenv("FOOTPRINT_CHROMIUM", saved.c_str(), 1);
    else
        ::unsetenv("FOOTPRINT_CHROMIUM");
    EXPECT_FALSE(check.chromium_found);
    EXPECT_FALSE(check.ran);
    EXPECT_NE(check.problem.find("FOOTPRINT_CHROMIUM"), std::string::npos) << check.problem;

    if (!find_chromium()) return;
    const BrowserCheck missing = check_report_in_browser(dir_ / "no-report.html", 1);
    EXPECT_TRUE(missing.chromium_found);
    EXPECT_FALSE(missing.ran);
    EXPECT_NE(missing.problem.find("no such file"), std::string::npos) << missing.problem;
}

}  // namespace
}  // namespace footprint
