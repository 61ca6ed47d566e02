// apps/eval_report.h — the HTML report of an evaluation: every demo scene rendered with several
// methods (filter modes at 1 spp, supersampling at several spp), measured against a reference.
//
// The evaluation command measures; this file presents:
//   * hardest_regions()        the windows of an error image with the largest mean error (the
//   crops)
//   * equal_error_speedup()    how much faster a method is than supersampling of the same RMSE
//   * error_time_plot_svg()    RMSE against seconds, log–log, as inline SVG
//   * convergence_plot_svg()   RMSE against samples per pixel per method, log–log (inline SVG)
//   * write_eval_report()      one self-contained HTML file: tables, images, heat maps, crops,
//   plots
//   * check_report_in_browser() opens the file in headless Chromium and counts the images that
//                              loaded — the test that every relative path in the report is right
//
// Nothing here prints or throws; failures are returned (core/result.h).
#pragma once

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"
#include "image/image.h"
#include "metrics/image_metrics.h"

namespace footprint {

// A rectangle in pixels of a scene's images: columns x … x + width − 1, rows y … y + height − 1.
struct CropRect {
    int x = 0;
    int y = 0;
    int width = 0;
    int height = 0;
};

// One way of rendering a scene.
struct EvalMethod {
    std::string name;           // "fa-rough", "supersampling 16 spp", …
    std::string family;         // "supersampling", or "filter" (a filter mode, at any spp)
    std::string series;         // the line of the convergence plot: the filter mode, or family
    int spp = 1;                // samples per pixel
    std::string image_file;     // PNG, relative to the report's folder ("" : none shown)
    std::string heat_map_file;  // PNG error heat map against the reference, relative ("" : none)
    double rmse = 0;            // against the reference (linear light)
    // The same over the scene's interior mask (no silhouettes); NaN: not measured
    double rmse_interior = std::numeric_limits<double>::quiet_NaN();
    double ssim = 1;
    // Mean FLIP over the interior mask (metrics/flip.h; HDR-FLIP where the reference is HDR);
    // NaN: not measured
    double flip_interior = std::numeric_limits<double>::quiet_NaN();
    double seconds = 0;                                         // render time
    double flicker = std::numeric_limits<double>::quiet_NaN();  // NaN: not measured
};

// One scene: its reference, the methods measured against it and the regions to zoom into.
struct EvalScene {
    std::string name;   // short identifier ("showcase"), used as the HTML anchor
    std::string title;  // shown as the heading
    int width = 0;      // size of every image of the scene, in pixels (needed for the crops)
    int height = 0;
    std::string reference_file;  // PNG, relative to the report's folder
    int reference_spp = 0;
    double reference_seconds = 0;
    std::vector<EvalMethod> methods;  // in the order shown (table rows, image columns)
    std::vector<CropRect> crops;      // the hardest regions (hardest_regions()), zoomed ×4
    // The colour scale every heat map of the scene was drawn with (scene_heat_map_scale()),
    // shown as a legend above the images; a top that is not positive and finite: no legend.
    HeatMapScale heat_map_scale{std::numeric_limits<double>::quiet_NaN(), 0};
};

// The colour scale of a scene's heat maps, from its methods' per-pixel errors (`errors`: one
// image per method, channel 0 the mean over channels of |method − reference|, as
// error_heat_map() computes it). No pixel saturates: the top is the largest finite error of any
// method. The scale is logarithmic, because the errors of one scene span decades (fireflies of
// an HDR sun next to small filtering errors): its bottom is the 5th percentile of the positive
// errors of all methods together, at least 1 and at most 6 decades below the top (pixels below
// it are black). Without a positive finite error: linear with top 1 (every heat map black).
HeatMapScale scene_heat_map_scale(const std::vector<Image>& errors);

// The legend of `scale` as inline SVG, about 400 pixels wide: the colour ramp as the heat map
// PNGs show it, a tick with its value at each power of ten (or at ¼ steps of a linear scale)
// and the bottom and top values at the ends. `id` makes its gradient's id unique in the page.
std::string heat_map_legend_svg(const HeatMapScale& scale, std::string_view id);

struct EvalReport {
    std::string title;
    std::string generated_by;  // shown under the title ("footprint eval --size 320 …")
    std::vector<EvalScene> scenes;
};

// The `count` windows of size × size pixels (clamped to the image) with the largest mean of
// channel 0 of `error` (a per-pixel error image), chosen greedily: the best window first, then
// the best window that overlaps none chosen so far, and so on. Ties go to the first window in
// row-major order of its top-left corner. Returns fewer windows when no non-overlapping one is
// left, none when `error` is empty or count or size ≤ 0. Non-finite error values count as 0.
// A summed-area table makes it O(pixels · count).
std::vector<CropRect> hardest_regions(const Image& error, int count, int size);

// How much faster `method` reaches its RMSE than supersampling does.
//
// The supersampling points (spp, rmse, seconds; those with positive finite RMSE and seconds) are
// sorted by spp, and log(seconds) is interpolated linearly in log(rmse) along them: the first
// segment (in spp order) whose RMSE range contains the method's RMSE gives the supersampling
// time at equal error, `seconds`; speedup = seconds / method.seconds. Then:
//   * below every point's RMSE (better than the most samples measured): the line through the
//     last two points (the two highest spp) in log–log is extended — extrapolated = true. It
//     needs those two points to have decreasing RMSE with growing time, else undefined.
//   * above the lowest-spp point's RMSE (worse than 1 spp supersampling): `seconds` is that
//     point's time and above_lowest_spp = true — supersampling is better at every cost measured,
//     and the speedup is an upper bound.
//   * defined = false (speedup and seconds NaN) without supersampling points, with a method time
//     or RMSE that is not positive and finite, or when extrapolation is impossible.
struct EqualErrorSpeedup {
    double speedup = std::numeric_limits<double>::quiet_NaN();
    double seconds = std::numeric_limits<double>::quiet_NaN();  // supersampling time, equal RMSE
    bool defined = false;
    bool extrapolated = false;
    bool above_lowest_spp = false;
};
EqualErrorSpeedup equal_error_speedup(const EvalMethod& method,
                                      const std::vector<EvalMethod>& supersampling);

// The methods of `scene` whose family is "supersampling", in the scene's order.
std::vector<EvalMethod> supersampling_methods(const EvalScene& scene);

// "×12", "×3.4", "×0.52"; "≈×120 (extrapolated)" or "≤×0.8 (worse than 1 spp)" when flagged
// (with short = true: "≈×120" and "≤×0.8"); "—" when undefined.
std::string speedup_label(const EqualErrorSpeedup& speedup, bool short_form = false);

// An inline SVG element (no external resources) plotting RMSE against seconds on log–log axes
// with ticks and labels: supersampling as a connected line with points labelled by spp, every
// other method as a labelled marker with a dashed horizontal line to its equal-error time on the
// supersampling curve, labelled with its speedup ("×12"). Points without positive finite RMSE
// and time are left out; with none left the SVG says "no data".
std::string error_time_plot_svg(const EvalScene& scene);

// An inline SVG element plotting each method's RMSE (over the interior where every method has one)
// against its samples per pixel, log–log: one line per series (EvalMethod::series, else the name;
// supersampling blue), a legend beside the plot. With no positive finite point: "no data".
std::string convergence_plot_svg(const EvalScene& scene);

// A rectangle of the plot in SVG pixels (x to the right, y down).
struct PlotBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
// How error_time_plot_svg lays out its text labels (the spp of the supersampling points, the
// methods' names, the speedups): each label's box, estimated from its length in characters, and
// what no label may cover. The plot places each label at the first of its candidate spots that
// stays inside `area` and overlaps no mark and no label placed before it, or, in a crowd, at the
// nearest such spot whole lines of text above or below them.
struct PlotLabelLayout {
    PlotBox area;                    // the inside of the axes
    std::vector<PlotBox> marks;      // the legend, every point and marker
    std::vector<std::string> texts;  // the labels, in the order they were placed
    std::vector<PlotBox> labels;     // their boxes
};
PlotLabelLayout error_time_plot_labels(const EvalScene& scene);

// `text` with & < > " ' replaced by entities: safe in HTML and SVG text and quoted attributes.
std::string html_escape(std::string_view text);

// Writes the report as one self-contained HTML file (inline CSS and script, no external fonts or
// scripts; the images are referenced by their relative paths, percent-encoded): the title, a
// short list of what each method shown is, then per scene a table (method, spp, RMSE, SSIM,
// flicker, seconds, equal-error speedup over supersampling), the heat maps' colour legend, the
// images side by side (reference first, then each method, heat maps below), the crops zoomed ×4
// (fewer for crops over 64 pixels: at most 256 pixels wide) for the reference and every method,
// outlined on the reference, and the error–time plot. Crops need the scene's width and height. A
// small script counts, when the page has loaded, the images that loaded (naturalWidth > 0) and
// failed — every <img> and every distinct CSS background image — into body's data-images-loaded,
// data-images-failed, data-images-total, data-images-failed-list (the failed URLs, one a line), and
// appends " [images N/M]" to the title. The file is written atomically (write_file_atomically).
Status write_eval_report(const EvalReport& report, const std::filesystem::path& html_file);

// The number of images write_eval_report's page holds (what the browser check should see).
int report_image_count(const EvalReport& report);

// The Chromium binary: $FOOTPRINT_CHROMIUM if set (it must be executable), else the first of
// chromium, chromium-browser, google-chrome, google-chrome-stable on PATH. nullopt if none.
std::optional<std::filesystem::path> find_chromium();

// The result of opening a report in headless Chromium.
struct BrowserCheck {
    bool chromium_found = false;  // false: problem says why (not installed, not executable)
    bool ran = false;             // Chromium ran and the dumped page held the image counts
    std::string problem;          // empty: passed; else one line saying what is wrong
    int images_loaded = 0;
    int images_failed = 0;
    int images_total = 0;
    double seconds = 0;  // wall time of the Chromium run
    bool passed() const { return ran && problem.empty(); }
};

// Opens `html_file` (written by write_eval_report) in headless Chromium:
//   timeout 60 CHROMIUM --headless --no-sandbox --disable-gpu --allow-file-access-from-files
//       --virtual-time-budget=10000 --dump-dom file:///ABS/PATH 2>/dev/null
// and reads the counts the page's script left on <body>. Passes when Chromium ran, no image
// failed and at least `expected_images` loaded; otherwise `problem` names the failed images, the
// missing counts (the script did not run) or Chromium's failure (timeout, exit status).
BrowserCheck check_report_in_browser(const std::filesystem::path& html_file, int expected_images);

}  // namespace footprint
