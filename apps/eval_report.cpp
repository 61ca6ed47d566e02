#include "eval_report.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "command_util.h"
#include "image/color.h"
#include "image/image_io.h"

namespace footprint {

namespace fs = std::filesystem;

namespace {

constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();

bool positive_finite(double v) {
    return std::isfinite(v) && v > 0;
}

// printf-style formatting of one number.
std::string format(const char* pattern, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, pattern, value);
    return buffer;
}

// `value` with `digits` significant digits, "—" when not finite.
std::string number(double value, int digits = 4) {
    if (!std::isfinite(value)) return "\u2014";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    return buffer;
}

// Coordinates in SVG: one decimal.
std::string coord(double v) {
    return format("%.1f", v);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Hardest regions

std::vector<CropRect> hardest_regions(const Image& error, int count, int size) {
    std::vector<CropRect> result;
    if (error.empty() || error.width <= 0 || error.height <= 0 || error.channels <= 0 ||
        count <= 0 || size <= 0)
        return result;
    const int width = error.width, height = error.height;
    const int w = std::min(size, width), h = std::min(size, height);

    // sat[(y)·(width+1) + x] = sum of channel 0 over columns < x, rows < y.
    const std::size_t stride = static_cast<std::size_t>(width) + 1;
    std::vector<double> sat(stride * (static_cast<std::size_t>(height) + 1), 0.0);
    for (int y = 0; y < height; ++y) {
        double row = 0;
        for (int x = 0; x < width; ++x) {
            const float v = error.at(x, y, 0);
            row += std::isfinite(v) ? v : 0.0;
            sat[(y + 1) * stride + x + 1] = sat[y * stride + x + 1] + row;
        }
    }
    const int nx = width - w + 1, ny = height - h + 1;  // window positions
    std::vector<double> sums(static_cast<std::size_t>(nx) * ny);
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x)
            sums[static_cast<std::size_t>(y) * nx + x] =
                sat[(y + h) * stride + x + w] - sat[y * stride + x + w] -
                sat[(y + h) * stride + x] + sat[y * stride + x];
    std::vector<char> blocked(sums.size(), 0);
    while (static_cast<int>(result.size()) < count) {
        std::size_t best = sums.size();
        for (std::size_t i = 0; i < sums.size(); ++i)
            if (!blocked[i] && (best == sums.size() || sums[i] > sums[best])) best = i;
        if (best == sums.size()) break;
        const int bx = static_cast<int>(best % nx), by = static_cast<int>(best / nx);
        result.push_back({bx, by, w, h});
        // Windows overlapping the chosen one have their corner within (bx − w, bx + w) ×
        // (by − h, by + h).
        for (int y = std::max(0, by - h + 1); y <= std::min(ny - 1, by + h - 1); ++y)
            for (int x = std::max(0, bx - w + 1); x <= std::min(nx - 1, bx + w - 1); ++x)
                blocked[static_cast<std::size_t>(y) * nx + x] = 1;
    }
    return result;
}

// ---------------------------------------------------------------------------------------------
// Equal-error speedup

EqualErrorSpeedup equal_error_speedup(const EvalMethod& method,
                                      const std::vector<EvalMethod>& supersampling) {
    EqualErrorSpeedup result;
    if (!positive_finite(method.seconds) || !positive_finite(method.rmse)) return result;
    struct Point {
        int spp;
        double log_rmse, log_seconds;
    };
    std::vector<Point> points;
    for (const EvalMethod& m : supersampling)
        if (positive_finite(m.rmse) && positive_finite(m.seconds))
            points.push_back({m.spp, std::log(m.rmse), std::log(m.seconds)});
    if (points.empty()) return result;
    std::stable_sort(points.begin(), points.end(),
                     [](const Point& a, const Point& b) { return a.spp < b.spp; });

    const double r = std::log(method.rmse);
    auto finish = [&](double log_seconds) {
        result.seconds = std::exp(log_seconds);
        result.speedup = result.seconds / method.seconds;
        result.defined = std::isfinite(result.speedup);
        if (!result.defined) result = {};
        return result;
    };
    if (r >= points.front().log_rmse) {
        if (r > points.front().log_rmse) result.above_lowest_spp = true;
        return finish(points.front().log_seconds);
    }
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        const Point& a = points[i];
        const Point& b = points[i + 1];
        const double lo = std::min(a.log_rmse, b.log_rmse), hi = std::max(a.log_rmse, b.log_rmse);
        if (r < lo || r > hi) continue;
        if (a.log_rmse == b.log_rmse) return finish(a.log_seconds);
        const double t = (r - a.log_rmse) / (b.log_rmse - a.log_rmse);
        return finish(a.log_seconds + t * (b.log_seconds - a.log_seconds));
    }
    // The method's RMSE is below that of every point (above the first was handled, and every
    // value in between lies in some segment's range): extrapolate from the last two points.
    if (points.size() < 2) return result;
    const Point& a = points[points.size() - 2];
    const Point& b = points.back();
    if (!(b.log_rmse < a.log_rmse) || !(b.log_seconds > a.log_seconds)) return result;
    const double slope = (b.log_seconds - a.log_seconds) / (b.log_rmse - a.log_rmse);
    result.extrapolated = true;
    return finish(b.log_seconds + slope * (r - b.log_rmse));
}

std::vector<EvalMethod> supersampling_methods(const EvalScene& scene) {
    std::vector<EvalMethod> result;
    for (const EvalMethod& m : scene.methods)
        if (m.family == "supersampling") result.push_back(m);
    return result;
}

std::string speedup_label(const EqualErrorSpeedup& s, bool short_form) {
    if (!s.defined) return "\u2014";
    const double v = s.speedup;
    const std::string text = "\u00d7" + (v >= 9.95 ? format("%.0f", v) : format("%.2g", v));
    if (s.extrapolated) return "\u2248" + text + (short_form ? "" : " (extrapolated)");
    if (s.above_lowest_spp) return "\u2264" + text + (short_form ? "" : " (worse than 1 spp)");
    return text;
}

std::string html_escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// The error–time plot

namespace {

// Tick values (powers of ten times 1, 2, 5, or every mantissa for narrow ranges) within
// [lo, hi], both log10.
std::vector<double> log_ticks(double lo, double hi) {
    const double span = hi - lo;
    std::vector<double> mantissas = {1};
    if (span < 1.2)
        mantissas = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    else if (span < 3.5)
        mantissas = {1, 2, 5};
    const int step = span > 8 ? static_cast<int>(std::ceil(span / 6)) : 1;
    std::vector<double> ticks;
    for (int k = static_cast<int>(std::floor(lo)); k <= static_cast<int>(std::ceil(hi)); ++k) {
        if (k % step != 0) continue;
        for (double m : mantissas) {
            const double v = std::log10(m) + k;
            if (v >= lo - 1e-9 && v <= hi + 1e-9) ticks.push_back(v);
        }
    }
    return ticks;
}

std::string tick_label(double log_value) {
    const double v = std::pow(10.0, log_value);
    if (v >= 1e-3 && v < 1e5) return format("%.4g", v);
    return format("%.0e", v);
}

// [lo, hi] of log10(values), padded, at least half a decade wide.
std::pair<double, double> log_range(const std::vector<double>& values) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (double v : values) {
        lo = std::min(lo, std::log10(v));
        hi = std::max(hi, std::log10(v));
    }
    if (hi - lo < 0.5) {
        const double mid = 0.5 * (lo + hi);
        lo = mid - 0.25;
        hi = mid + 0.25;
    }
    const double pad = 0.08 * (hi - lo);
    return {lo - pad, hi + pad};
}

// An SVG plot's opening tag and white background (`label`: what it shows, for screen readers).
std::string svg_open(double width, double height, const char* label) {
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" viewBox=\"0 0 " << width << " "
        << height << "\" width=\"" << width << "\" height=\"" << height
        << "\" role=\"img\" aria-label=\"" << label
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect x=\"0\" y=\"0\" width=\""
        << width << "\" height=\"" << height << "\" fill=\"white\"/>\n";
    return svg.str();
}

// The rest of a plot that has nothing to show.
std::string svg_no_data(double width, double height) {
    std::ostringstream svg;
    svg << "<text x=\"" << width / 2 << "\" y=\"" << height / 2
        << "\" text-anchor=\"middle\" fill=\"#666\">no data</text>\n</svg>\n";
    return svg.str();
}

constexpr std::array<const char*, 8> palette = {"#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                                "#17becf", "#8c564b", "#e377c2", "#bcbd22"};

// Places the plot's text labels so that none overlaps another, a marker or the legend: each
// label takes the first of its candidate spots whose box (estimated from its length in
// characters) stays inside the plot and overlaps nothing taken so far; the first spot when none
// is free.
class LabelPlacer {
  public:
    struct Spot {
        double x, y;         // the baseline's anchor point
        const char* anchor;  // SVG text-anchor: "start", "middle" or "end"
    };
    LabelPlacer(double x0, double y0, double x1, double y1) { layout_.area = {x0, y0, x1, y1}; }
    // A mark no label may cover.
    void take(double x0, double y0, double x1, double y1) {
        layout_.marks.push_back({x0, y0, x1, y1});
    }
    // `text` placed: its <text …> start tag without the closing '>' (attributes x, y, anchor).
    std::string place(std::string_view text, const std::vector<Spot>& spots) {
        const double width = kCharWidth * static_cast<double>(characters(text));
        const Spot chosen = free_spot(spots, width).value_or(spots.front());
        layout_.texts.emplace_back(text);
        layout_.labels.push_back(box(chosen, width));
        return "<text x=\"" + coord(chosen.x) + "\" y=\"" + coord(chosen.y) + "\" text-anchor=\"" +
               chosen.anchor + "\"";
    }
    const PlotLabelLayout& layout() const { return layout_; }

  private:
    using Box = PlotBox;
    static constexpr double kCharWidth = 7.2, kAscent = 11, kDescent = 3;  // 12-pixel sans-serif

    static std::size_t characters(std::string_view utf8) {
        std::size_t n = 0;
        for (char c : utf8) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
        return n;
    }
    static Box box(const Spot& s, double width) {
        const std::string_view anchor = s.anchor;
        const double x0 = anchor == "end"      ? s.x - width
                          : anchor == "middle" ? s.x - width / 2
                                               : s.x;
        return {x0, s.y - kAscent, x0 + width, s.y + kDescent};
    }
    // The first of `spots` where a label `width` wide fits; when none does (a crowd of markers),
    // the first that fits moved up or down by whole lines of text, the nearest first: the label
    // then stands in a column beside the crowd, in its marker's colour.
    std::optional<Spot> free_spot(const std::vector<Spot>& spots, double width) const {
        constexpr double kLine = kAscent + kDescent;
        const Box& area = layout_.area;
        const int lines = static_cast<int>((area.y1 - area.y0) / kLine) + 1;
        for (int k = 0; k <= lines; ++k)
            for (double dy : {k * kLine, -k * kLine}) {
                for (const Spot& spot : spots) {
                    const Spot moved{spot.x, spot.y + dy, spot.anchor};
                    if (fits(box(moved, width))) return moved;
                }
                if (k == 0) break;  // the spots as given, once
            }
        return std::nullopt;
    }
    static bool overlap(const Box& a, const Box& b) {
        return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
    }
    bool fits(const Box& b) const {
        const Box& area = layout_.area;
        if (b.x0 < area.x0 || b.y0 < area.y0 || b.x1 > area.x1 || b.y1 > area.y1) return false;
        for (const std::vector<Box>* taken : {&layout_.marks, &layout_.labels})
            for (const Box& t : *taken)
                if (overlap(b, t)) return false;
        return true;
    }

    PlotLabelLayout layout_;
};

// The plot's SVG; its label layout in `layout` when given.
std::string error_time_plot(const EvalScene& scene, PlotLabelLayout* layout) {
    constexpr double svg_w = 680, svg_h = 420;
    constexpr double left = 72, right = 24, top = 24, bottom = 56;
    const double plot_w = svg_w - left - right, plot_h = svg_h - top - bottom;

    std::vector<EvalMethod> ss;
    for (const EvalMethod& m : supersampling_methods(scene))
        if (positive_finite(m.rmse) && positive_finite(m.seconds)) ss.push_back(m);
    std::stable_sort(ss.begin(), ss.end(),
                     [](const EvalMethod& a, const EvalMethod& b) { return a.spp < b.spp; });
    struct Marker {
        const EvalMethod* method;
        EqualErrorSpeedup speedup;
    };
    std::vector<Marker> markers;
    for (const EvalMethod& m : scene.methods)
        if (m.family != "supersampling" && m.spp == 1 && positive_finite(m.rmse) &&
            positive_finite(m.seconds))
            markers.push_back({&m, equal_error_speedup(m, ss)});

    std::ostringstream svg;
    svg << svg_open(svg_w, svg_h, "RMSE against seconds, log-log");

    std::vector<double> xs, ys;
    for (const EvalMethod& m : ss) {
        xs.push_back(m.seconds);
        ys.push_back(m.rmse);
    }
    for (const Marker& k : markers) {
        xs.push_back(k.method->seconds);
        ys.push_back(k.method->rmse);
        if (k.speedup.defined && positive_finite(k.speedup.seconds))
            xs.push_back(k.speedup.seconds);
    }
    if (xs.empty()) return svg.str() + svg_no_data(svg_w, svg_h);
    const auto [x0, x1] = log_range(xs);
    const auto [y0, y1] = log_range(ys);
    auto px = [&](double seconds) {
        return left + (std::log10(seconds) - x0) / (x1 - x0) * plot_w;
    };
    auto py = [&](double rmse) { return top + (y1 - std::log10(rmse)) / (y1 - y0) * plot_h; };

    // Grid, ticks and labels.
    svg << "<g stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
    for (double t : log_ticks(x0, x1)) {
        const double x = left + (t - x0) / (x1 - x0) * plot_w;
        svg << "<line x1=\"" << coord(x) << "\" y1=\"" << top << "\" x2=\"" << coord(x)
            << "\" y2=\"" << top + plot_h << "\"/>\n";
    }
    for (double t : log_ticks(y0, y1)) {
        const double y = top + (y1 - t) / (y1 - y0) * plot_h;
        svg << "<line x1=\"" << left << "\" y1=\"" << coord(y) << "\" x2=\"" << left + plot_w
            << "\" y2=\"" << coord(y) << "\"/>\n";
    }
    svg << "</g>\n<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << plot_w
        << "\" height=\"" << plot_h << "\" fill=\"none\" stroke=\"#333\"/>\n";
    svg << "<g fill=\"#333\">\n";
    for (double t : log_ticks(x0, x1)) {
        const double x = left + (t - x0) / (x1 - x0) * plot_w;
        svg << "<line x1=\"" << coord(x) << "\" y1=\"" << top + plot_h << "\" x2=\"" << coord(x)
            << "\" y2=\"" << top + plot_h + 5 << "\" stroke=\"#333\"/>";
        svg << "<text x=\"" << coord(x) << "\" y=\"" << top + plot_h + 18
            << "\" text-anchor=\"middle\">" << tick_label(t) << "</text>\n";
    }
    for (double t : log_ticks(y0, y1)) {
        const double y = top + (y1 - t) / (y1 - y0) * plot_h;
        svg << "<line x1=\"" << left - 5 << "\" y1=\"" << coord(y) << "\" x2=\"" << left
            << "\" y2=\"" << coord(y) << "\" stroke=\"#333\"/>";
        svg << "<text x=\"" << left - 8 << "\" y=\"" << coord(y + 4) << "\" text-anchor=\"end\">"
            << tick_label(t) << "</text>\n";
    }
    svg << "<text x=\"" << coord(left + plot_w / 2) << "\" y=\"" << svg_h - 12
        << "\" text-anchor=\"middle\">render time (seconds, log scale)</text>\n";
    svg << "<text transform=\"translate(16 " << coord(top + plot_h / 2)
        << ") rotate(-90)\" text-anchor=\"middle\">RMSE against the reference (log scale)</text>\n";
    svg << "</g>\n";

    // What labels must not cover: the legend (top right) and every point.
    const double lx = left + plot_w - 190, ly = top + 10;
    LabelPlacer labels(left + 2, top + 2, left + plot_w - 2, top + plot_h - 2);
    labels.take(lx, ly, lx + 182, ly + 40);
    for (const EvalMethod& m : ss)
        labels.take(px(m.seconds) - 5, py(m.rmse) - 5, px(m.seconds) + 5, py(m.rmse) + 5);
    for (const Marker& k : markers) {
        const double mx = px(k.method->seconds), my = py(k.method->rmse);
        labels.take(mx - 8, my - 8, mx + 8, my + 8);
        if (k.speedup.defined && positive_finite(k.speedup.seconds))
            labels.take(px(k.speedup.seconds) - 4, my - 4, px(k.speedup.seconds) + 4, my + 4);
    }

    // Supersampling: a connected line with points labelled by spp.
    if (!ss.empty()) {
        svg << "<polyline fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"2\" points=\"";
        for (const EvalMethod& m : ss)
            svg << coord(px(m.seconds)) << "," << coord(py(m.rmse)) << " ";
        svg << "\"/>\n<g fill=\"#1f77b4\">\n";
        for (const EvalMethod& m : ss) {
            const double x = px(m.seconds), y = py(m.rmse);
            svg << "<circle cx=\"" << coord(x) << "\" cy=\"" << coord(y) << "\" r=\"4\"><title>"
                << html_escape(m.name) << "</title></circle>";
            const std::string text = std::to_string(m.spp) + " spp";
            svg << labels.place(text, {{x + 6, y - 7, "start"},
                                       {x + 6, y + 15, "start"},
                                       {x - 6, y - 7, "end"},
                                       {x - 6, y + 15, "end"}})
                << ">" << text << "</text>\n";
        }
        svg << "</g>\n";
    }

    // Every other method: a marker and a dashed line to its equal-error time (labels below).
    for (std::size_t i = 0; i < markers.size(); ++i) {
        const Marker& k = markers[i];
        const char* colour = palette[i % palette.size()];
        const double mx = px(k.method->seconds), my = py(k.method->rmse);
        if (k.speedup.defined && positive_finite(k.speedup.seconds)) {
            const double ex = px(k.speedup.seconds);
            if (k.speedup.extrapolated && !ss.empty())  // the extended supersampling curve
                svg << "<line x1=\"" << coord(px(ss.back().seconds)) << "\" y1=\""
                    << coord(py(ss.back().rmse)) << "\" x2=\"" << coord(ex) << "\" y2=\""
                    << coord(my) << "\" stroke=\"#1f77b4\" stroke-dasharray=\"2 3\"/>\n";
            svg << "<line x1=\"" << coord(mx) << "\" y1=\"" << coord(my) << "\" x2=\"" << coord(ex)
                << "\" y2=\"" << coord(my) << "\" stroke=\"" << colour
                << "\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"/>\n";
            svg << "<circle cx=\"" << coord(ex) << "\" cy=\"" << coord(my)
                << "\" r=\"3\" fill=\"white\" stroke=\"" << colour << "\"/>\n";
        }
        svg << "<rect x=\"" << coord(mx - 5) << "\" y=\"" << coord(my - 5)
            << "\" width=\"10\" height=\"10\" fill=\"" << colour << "\" transform=\"rotate(45 "
            << coord(mx) << " " << coord(my) << ")\"><title>" << html_escape(k.method->name)
            << "</title></rect>\n";
    }
    // The names beside their markers (away from the dashed line first), then the speedups along
    // their lines: each where it overlaps nothing placed before it.
    for (std::size_t i = 0; i < markers.size(); ++i) {
        const Marker& k = markers[i];
        const double mx = px(k.method->seconds), my = py(k.method->rmse);
        const bool line_right = !(k.speedup.defined && positive_finite(k.speedup.seconds)) ||
                                px(k.speedup.seconds) >= mx;
        const LabelPlacer::Spot away{line_right ? mx - 10 : mx + 10, my + 4,
                                     line_right ? "end" : "start"};
        const LabelPlacer::Spot along{line_right ? mx + 10 : mx - 10, my + 16,
                                      line_right ? "start" : "end"};
        svg << labels.place(k.method->name, {away,
                                             {mx, my + 20, "middle"},
                                             {mx, my - 11, "middle"},
                                             along,
                                             {mx, my + 34, "middle"},
                                             {mx, my - 25, "middle"}})
            << " fill=\"" << palette[i % palette.size()] << "\">" << html_escape(k.method->name)
            << "</text>\n";
    }
    for (std::size_t i = 0; i < markers.size(); ++i) {
        const Marker& k = markers[i];
        if (!k.speedup.defined || !positive_finite(k.speedup.seconds)) continue;
        const double mx = px(k.method->seconds), my = py(k.method->rmse);
        const double ex = px(k.speedup.seconds);
        const std::string text = speedup_label(k.speedup, true);
        std::vector<LabelPlacer::Spot> spots;
        for (double f : {0.5, 0.3, 0.7, 0.15, 0.85})
            for (double dy : {-6.0, 15.0}) spots.push_back({mx + f * (ex - mx), my + dy, "middle"});
        svg << labels.place(text, spots) << " fill=\"" << palette[i % palette.size()]
            << "\" font-weight=\"bold\">" << text << "</text>\n";
    }

    // Legend.
    svg << "<g font-size=\"11\"><rect x=\"" << lx << "\" y=\"" << ly
        << "\" width=\"182\" height=\"40\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#ccc\"/>"
        << "<line x1=\"" << lx + 8 << "\" y1=\"" << ly + 13 << "\" x2=\"" << lx + 30 << "\" y2=\""
        << ly + 13 << "\" stroke=\"#1f77b4\" stroke-width=\"2\"/><text x=\"" << lx + 36 << "\" y=\""
        << ly + 17 << "\">supersampling</text><line x1=\"" << lx + 8 << "\" y1=\"" << ly + 29
        << "\" x2=\"" << lx + 30 << "\" y2=\"" << ly + 29
        << "\" stroke=\"#555\" stroke-dasharray=\"6 4\"/><text x=\"" << lx + 36 << "\" y=\""
        << ly + 33 << "\">equal RMSE: speedup</text></g>\n";
    svg << "</svg>\n";
    if (layout) *layout = labels.layout();
    return svg.str();
}

// The convergence plot's SVG (convergence_plot_svg()).
std::string convergence_plot(const EvalScene& scene) {
    constexpr double svg_w = 680, svg_h = 380;
    constexpr double left = 72, right = 170, top = 20, bottom = 52;
    const double plot_w = svg_w - left - right, plot_h = svg_h - top - bottom;
    bool interior = !scene.methods.empty();
    for (const EvalMethod& m : scene.methods)
        interior = interior && positive_finite(m.rmse_interior);
    auto error_of = [&](const EvalMethod& m) { return interior ? m.rmse_interior : m.rmse; };

    // The series in order of appearance, each with its points sorted by spp.
    std::vector<std::pair<std::string, std::vector<const EvalMethod*>>> series;
    for (const EvalMethod& m : scene.methods) {
        if (!positive_finite(error_of(m)) || m.spp < 1) continue;
        const std::string& name = m.series.empty() ? m.name : m.series;
        auto it = std::find_if(series.begin(), series.end(),
                               [&](const auto& s) { return s.first == name; });
        if (it == series.end()) it = series.insert(series.end(), {name, {}});
        it->second.push_back(&m);
    }
    std::ostringstream svg;
    svg << svg_open(svg_w, svg_h, "RMSE against samples per pixel, log-log");
    std::vector<double> xs, ys;
    for (auto& [name, points] : series) {
        std::stable_sort(points.begin(), points.end(),
                         [](const EvalMethod* a, const EvalMethod* b) { return a->spp < b->spp; });
        for (const EvalMethod* m : points) {
            xs.push_back(m->spp);
            ys.push_back(error_of(*m));
        }
    }
    if (xs.empty()) return svg.str() + svg_no_data(svg_w, svg_h);
    const auto [x0, x1] = log_range(xs);
    const auto [y0, y1] = log_range(ys);
    auto px = [&](double spp) { return left + (std::log10(spp) - x0) / (x1 - x0) * plot_w; };
    auto py = [&](double e) { return top + (y1 - std::log10(e)) / (y1 - y0) * plot_h; };

    svg << "<g stroke=\"#e4e4e4\">\n";
    for (double t : log_ticks(y0, y1))
        svg << "<line x1=\"" << left << "\" y1=\"" << coord(py(std::pow(10.0, t))) << "\" x2=\""
            << left + plot_w << "\" y2=\"" << coord(py(std::pow(10.0, t))) << "\"/>\n";
    svg << "</g>\n<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << plot_w
        << "\" height=\"" << plot_h << "\" fill=\"none\" stroke=\"#333\"/>\n<g fill=\"#333\">\n";
    std::vector<int> rates;
    for (double x : xs) rates.push_back(static_cast<int>(x));
    std::sort(rates.begin(), rates.end());
    rates.erase(std::unique(rates.begin(), rates.end()), rates.end());
    for (int spp : rates) {
        const double x = px(spp);
        svg << "<line x1=\"" << coord(x) << "\" y1=\"" << top + plot_h << "\" x2=\"" << coord(x)
            << "\" y2=\"" << top + plot_h + 5 << "\" stroke=\"#333\"/><text x=\"" << coord(x)
            << "\" y=\"" << top + plot_h + 18 << "\" text-anchor=\"middle\">" << spp << "</text>\n";
    }
    for (double t : log_ticks(y0, y1)) {
        const double y = py(std::pow(10.0, t));
        svg << "<text x=\"" << left - 8 << "\" y=\"" << coord(y + 4) << "\" text-anchor=\"end\">"
            << tick_label(t) << "</text>\n";
    }
    svg << "<text x=\"" << coord(left + plot_w / 2) << "\" y=\"" << svg_h - 10
        << "\" text-anchor=\"middle\">samples per pixel (log scale)</text>\n<text transform=\""
        << "translate(16 " << coord(top + plot_h / 2) << ") rotate(-90)\" text-anchor=\"middle\">"
        << (interior ? "interior RMSE (log scale)" : "RMSE (log scale)") << "</text>\n</g>\n";

    // One line per series (supersampling blue and thicker, as in the error-time plot), and the
    // legend beside the plot.
    std::size_t colour_index = 0;
    for (std::size_t i = 0; i < series.size(); ++i) {
        const auto& [name, points] = series[i];
        const bool ss = name == "supersampling";
        const std::string colour = ss ? "#1f77b4" : palette[colour_index++ % palette.size()];
        svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\""
            << (ss ? 2.5 : 1.5) << "\" points=\"";
        for (const EvalMethod* m : points)
            svg << coord(px(m->spp)) << "," << coord(py(error_of(*m))) << " ";
        svg << "\"/>\n";
        for (const EvalMethod* m : points) {
            svg << "<circle cx=\"" << coord(px(m->spp)) << "\" cy=\"" << coord(py(error_of(*m)))
                << "\" r=\"3.5\" fill=\"" << colour << "\"><title>" << html_escape(m->name) << ": "
                << number(error_of(*m)) << "</title></circle>\n";
        }
        const double ly = top + 14 + 18 * static_cast<double>(i);
        svg << "<line x1=\"" << left + plot_w + 12 << "\" y1=\"" << coord(ly - 4) << "\" x2=\""
            << left + plot_w + 34 << "\" y2=\"" << coord(ly - 4) << "\" stroke=\"" << colour
            << "\" stroke-width=\"2\"/><text x=\"" << left + plot_w + 40 << "\" y=\"" << coord(ly)
            << "\">" << html_escape(name) << "</text>\n";
    }
    svg << "</svg>\n";
    return svg.str();
}

}  // namespace

std::string error_time_plot_svg(const EvalScene& scene) {
    return error_time_plot(scene, nullptr);
}

std::string convergence_plot_svg(const EvalScene& scene) {
    return convergence_plot(scene);
}

PlotLabelLayout error_time_plot_labels(const EvalScene& scene) {
    PlotLabelLayout layout;
    error_time_plot(scene, &layout);
    return layout;
}

// ---------------------------------------------------------------------------------------------
// The heat maps' colour scale and its legend

HeatMapScale scene_heat_map_scale(const std::vector<Image>& errors) {
    constexpr double kBottomPercentile = 0.05;
    constexpr double kMinDecades = 1, kMaxDecades = 6;
    std::vector<float> positive;
    for (const Image& e : errors)
        for (std::size_t p = 0; p < e.pixel_count(); ++p) {
            const float v = e.pixels[p * e.channels];
            if (std::isfinite(v) && v > 0) positive.push_back(v);
        }
    if (positive.empty()) return {1, 0};
    const double top = *std::max_element(positive.begin(), positive.end());
    const auto rank = static_cast<std::ptrdiff_t>(positive.size() * kBottomPercentile);
    std::nth_element(positive.begin(), positive.begin() + rank, positive.end());
    const double low = positive[static_cast<std::size_t>(rank)];
    return {top, std::clamp(low, top * std::pow(10.0, -kMaxDecades),
                            top * std::pow(10.0, -kMinDecades))};
}

namespace {

// "#rrggbb" of a linear-light colour as the PNGs store it (sRGB).
std::string srgb_hex(const std::array<float, 3>& linear) {
    char buffer[8];
    int code[3];
    for (int c = 0; c < 3; ++c)
        code[c] = static_cast<int>(
            std::lround(255.0f * linear_to_srgb(std::clamp(linear[c], 0.0f, 1.0f))));
    std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", code[0], code[1], code[2]);
    return buffer;
}

// A legend value: "0.0012", "3.4", "6500", "1e-07".
std::string legend_value(double v) {
    if (v == 0) return "0";
    if (v >= 1e-3 && v < 1e5) return format("%.2g", v);
    return format("%.0e", v);
}

}  // namespace

std::string heat_map_legend_svg(const HeatMapScale& scale, std::string_view id) {
    constexpr double width = 420, bar_x = 10, bar_w = 400, bar_y = 4, bar_h = 14;
    constexpr int kStops = 33;  // the ramp is interpolated in linear light: many sRGB stops
    std::string gradient = "heat-legend-";
    for (char c : id) gradient += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"legend\" width=\"" << width
        << "\" height=\"40\" viewBox=\"0 0 " << width << " 40\" font-family=\"sans-serif\" "
        << "font-size=\"11\" role=\"img\" aria-label=\"heat map colour scale\">\n<defs>"
        << "<linearGradient id=\"" << gradient << "\">";
    for (int i = 0; i < kStops; ++i) {
        const double t = double(i) / (kStops - 1);
        svg << "<stop offset=\"" << format("%.4f", t) << "\" stop-color=\""
            << srgb_hex(heat_map_colour(t)) << "\"/>";
    }
    svg << "</linearGradient></defs>\n<rect x=\"" << bar_x << "\" y=\"" << bar_y << "\" width=\""
        << bar_w << "\" height=\"" << bar_h << "\" fill=\"url(#" << gradient
        << ")\" stroke=\"#888\"/>\n";
    // Ticks: the ends, and each power of ten (log) or quarter (linear) not crowding an end.
    struct Tick {
        double t, value;
    };
    const bool log_scale = scale.bottom > 0;
    std::vector<Tick> ticks = {{0, log_scale ? scale.bottom : 0}, {1, scale.top}};
    if (log_scale) {
        for (int k = static_cast<int>(std::ceil(std::log10(scale.bottom)));
             std::pow(10.0, k) < scale.top; ++k)
            ticks.push_back({heat_map_position(std::pow(10.0, k), scale), std::pow(10.0, k)});
    } else {
        for (int q = 1; q < 4; ++q) ticks.push_back({q / 4.0, scale.top * q / 4.0});
    }
    constexpr double kLabelRoom = 44;  // pixels a label needs beside the end labels
    for (std::size_t i = 0; i < ticks.size(); ++i) {
        const double x = bar_x + ticks[i].t * bar_w;
        if (i >= 2 && (x - bar_x < kLabelRoom || bar_x + bar_w - x < kLabelRoom)) continue;
        const char* anchor = i == 0 ? "start" : i == 1 ? "end" : "middle";
        std::string label = legend_value(ticks[i].value);
        if (i == 0 && log_scale) label = "\u2264 " + label;
        const double text_x = i == 0 ? x - 2 : i == 1 ? x + 2 : x;
        svg << "<line x1=\"" << coord(x) << "\" y1=\"" << bar_y + bar_h << "\" x2=\"" << coord(x)
            << "\" y2=\"" << bar_y + bar_h + 4 << "\" stroke=\"#333\"/><text x=\"" << coord(text_x)
            << "\" y=\"" << bar_y + bar_h + 16 << "\" text-anchor=\"" << anchor
            << "\" fill=\"#333\">" << label << "</text>\n";
    }
    svg << "</svg>";
    return svg.str();
}

// ---------------------------------------------------------------------------------------------
// The HTML report

namespace {

// A relative path as a URL: bytes outside A–Z a–z 0–9 - . _ ~ / percent-encoded.
std::string url_of(std::string_view path) {
    static const char hex[] = "0123456789ABCDEF";
    std::string out;
    for (unsigned char c : path) {
        if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
            out += static_cast<char>(c);
        } else {
            out += '%';
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    return out;
}

constexpr const char* style_sheet = R"css(
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 24px;
       color: #222; background: #fafafa; }
h1 { margin-bottom: 4px; }
.generated { color: #666; margin-top: 0; }
nav a { margin-right: 12px; }
section.scene { background: white; border: 1px solid #ddd; border-radius: 6px; padding: 8px 20px;
                margin: 24px 0; }
table { border-collapse: collapse; margin: 8px 0 16px; }
th, td { padding: 3px 10px; border-bottom: 1px solid #e4e4e4; }
th { text-align: left; background: #f0f0f0; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
tr.reference td { color: #666; }
tr.supersampling td.name { color: #1f77b4; }
.figures { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; }
figure { margin: 0; }
figure img { display: block; margin-bottom: 4px; background: #eee; }
figcaption { font-size: 13px; color: #444; max-width: 320px; }
.outlined { position: relative; display: inline-block; }
.outline { position: absolute; border: 2px solid #ff2; box-shadow: 0 0 0 1px #000;
           pointer-events: none; }
.outline span { position: absolute; left: 2px; top: 0; font: bold 11px sans-serif; color: #ff2;
                text-shadow: 0 0 2px #000; }
.crop-row { display: flex; flex-wrap: wrap; gap: 10px; align-items: flex-start; margin: 8px 0; }
.crop-row > .label { width: 70px; font-weight: bold; }
.crop { position: relative; overflow: hidden; border: 1px solid #999; background: #eee; }
.crop img { position: absolute; max-width: none; image-rendering: pixelated;
            image-rendering: crisp-edges; }
.crop-caption { font-size: 12px; color: #444; margin-top: 2px; }
svg.plot { max-width: 100%; height: auto; border: 1px solid #ddd; }
.legend { margin: 4px 0 12px; }
.legend .note { margin: 2px 0; max-width: 760px; }
section.methods dl { display: grid; grid-template-columns: max-content 1fr; gap: 2px 14px;
                     margin: 8px 0; font-size: 14px; }
section.methods dt { font-weight: bold; }
section.methods dd { margin: 0; }
.note { font-size: 13px; color: #555; }
)css";

// Checks every image once the page has loaded; see write_eval_report in eval_report.h.
constexpr const char* check_script = R"js(
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.images);
  var loaded = 0, failed = [];
  imgs.forEach(function (img) {
    if (img.complete && img.naturalWidth > 0) loaded++; else failed.push(img.getAttribute('src'));
  });
  var urls = [];
  Array.prototype.forEach.call(document.querySelectorAll('*'), function (el) {
    var bg = getComputedStyle(el).backgroundImage, re = /url\("?(.*?)"?\)/g, m;
    while ((m = re.exec(bg))) if (urls.indexOf(m[1]) < 0) urls.push(m[1]);
  });
  var pending = urls.length;
  function finish() {
    var total = imgs.length + urls.length, d = document.body.dataset;
    d.imagesLoaded = loaded; d.imagesFailed = failed.length; d.imagesTotal = total;
    d.imagesFailedList = failed.join('\n');
    document.title = document.title + ' [images ' + loaded + '/' + total + ']';
  }
  if (pending === 0) finish();
  urls.forEach(function (u) {
    var probe = new Image();
    probe.onload = function () {
      if (probe.naturalWidth > 0) loaded++; else failed.push(u);
      if (--pending === 0) finish();
    };
    probe.onerror = function () { failed.push(u); if (--pending === 0) finish(); };
    probe.src = u;
  });
});
)js";

class HtmlWriter {
  public:
    std::ostringstream out;
    int images = 0;

    void img(const std::string& file, const std::string& alt, const std::string& attributes) {
        out << "<img src=\"" << html_escape(url_of(file)) << "\" alt=\"" << html_escape(alt) << "\""
            << attributes << ">";
        ++images;
    }

    void scene(const EvalScene& scene);

  private:
    void table(const EvalScene& scene, const std::vector<EvalMethod>& ss);
    void legend(const EvalScene& scene);
    void figures(const EvalScene& scene);
    void crops(const EvalScene& scene);
};

// Displayed width of a scene's images: their width, at most 320 pixels.
int display_width(const EvalScene& scene) {
    return scene.width > 0 ? std::min(scene.width, 320) : 320;
}

std::string size_attributes(const EvalScene& scene) {
    const int w = display_width(scene);
    std::string a = " width=\"" + std::to_string(w) + "\"";
    if (scene.width > 0 && scene.height > 0)
        a += " height=\"" +
             std::to_string(static_cast<int>(std::lround(double(w) * scene.height / scene.width))) +
             "\"";
    return a;
}

// The crops clamped to the scene; empty ones dropped (none without the scene's size).
std::vector<CropRect> visible_crops(const EvalScene& scene) {
    std::vector<CropRect> result;
    if (scene.width <= 0 || scene.height <= 0) return result;
    for (CropRect c : scene.crops) {
        const int x0 = std::clamp(c.x, 0, scene.width), y0 = std::clamp(c.y, 0, scene.height);
        const int x1 = std::clamp(c.x + std::max(c.width, 0), 0, scene.width);
        const int y1 = std::clamp(c.y + std::max(c.height, 0), 0, scene.height);
        if (x1 > x0 && y1 > y0) result.push_back({x0, y0, x1 - x0, y1 - y0});
    }
    return result;
}

std::string crop_name(std::size_t i) {
    return i < 26 ? std::string(1, static_cast<char>('A' + i)) : std::to_string(i + 1);
}

void HtmlWriter::scene(const EvalScene& scene) {
    const std::vector<EvalMethod> ss = supersampling_methods(scene);
    out << "<section class=\"scene\" id=\"" << html_escape(url_of(scene.name)) << "\">\n<h2>"
        << html_escape(scene.title.empty() ? scene.name : scene.title) << "</h2>\n";
    if (!scene.title.empty() && scene.name != scene.title)
        out << "<p class=\"note\">scene <code>" << html_escape(scene.name) << "</code>, "
            << scene.width << " \u00d7 " << scene.height << " pixels</p>\n";
    table(scene, ss);
    legend(scene);
    figures(scene);
    crops(scene);
    out << "<h3>Error against time</h3>\n" << error_time_plot_svg(scene);
    out << "<p class=\"note\">Log\u2013log. The blue line is supersampling; each dashed line runs "
           "from a method to the supersampling time of the same RMSE (interpolated in "
           "log\u2013log; \u2248 extrapolated beyond the most samples measured, \u2264 worse than "
           "the fewest samples measured).</p>\n";
    out << "<h3>Error against samples per pixel</h3>\n" << convergence_plot_svg(scene);
    out << "<p class=\"note\">Log\u2013log. Each filter mode with N samples per pixel on top of "
           "its filtering (each sample's footprint 1/\u221aN of the pixel's), and supersampling. A "
           "method without bias falls towards the reference as N grows; one that flattens "
           "carries an error more samples do not remove (<code>footprint eval --budget</code> "
           "says which term).</p>\n</section>\n";
}

void HtmlWriter::table(const EvalScene& scene, const std::vector<EvalMethod>& ss) {
    out << "<table>\n<tr><th>method</th><th>spp</th><th>RMSE</th><th>RMSE interior</th>"
           "<th>SSIM</th><th>FLIP interior</th><th>flicker</th>"
           "<th>seconds</th><th>equal-error speedup over supersampling</th></tr>\n";
    out << "<tr class=\"reference\"><td class=\"name\">reference</td><td class=\"num\">"
        << scene.reference_spp << "</td><td class=\"num\">0</td><td class=\"num\">0</td>"
        << "<td class=\"num\">1</td><td class=\"num\">0</td>"
        << "<td class=\"num\">\u2014</td><td class=\"num\">" << number(scene.reference_seconds, 3)
        << "</td><td></td></tr>\n";
    for (const EvalMethod& m : scene.methods) {
        const bool is_ss = m.family == "supersampling";
        out << "<tr class=\"" << (is_ss ? "supersampling" : "filter") << "\"><td class=\"name\">"
            << html_escape(m.name) << "</td><td class=\"num\">" << m.spp
            << "</td><td class=\"num\">" << number(m.rmse) << "</td><td class=\"num\">"
            << number(m.rmse_interior) << "</td><td class=\"num\">" << number(m.ssim) << "</td>"
            << "<td class=\"num\">" << number(m.flip_interior) << "</td>"
            << "<td class=\"num\">" << number(m.flicker, 3) << "</td><td class=\"num\">"
            << number(m.seconds, 3) << "</td><td class=\"num\">"
            << (is_ss ? "\u2014" : html_escape(speedup_label(equal_error_speedup(m, ss))))
            << "</td></tr>\n";
    }
    out << "</table>\n";
}

void HtmlWriter::legend(const EvalScene& scene) {
    const HeatMapScale& scale = scene.heat_map_scale;
    if (!positive_finite(scale.top)) return;
    bool heat_maps = false;
    for (const EvalMethod& m : scene.methods) heat_maps = heat_maps || !m.heat_map_file.empty();
    if (!heat_maps) return;
    out << "<div class=\"legend\">" << heat_map_legend_svg(scale, scene.name)
        << "<p class=\"note\">Heat maps: each pixel's error, the mean over RGB of |method \u2212 "
           "reference| in linear light, under each method's image, on one scale for the scene. ";
    if (scale.bottom > 0)
        out << "Logarithmic from " << legend_value(scale.bottom)
            << " (black at or below it: the 5th percentile of all methods' errors) to "
            << legend_value(scale.top)
            << " (white: the largest error of any method, so no pixel saturates).";
    else
        out << "Linear from 0 (black) to " << legend_value(scale.top) << " (white).";
    out << "</p></div>\n";
}

void HtmlWriter::figures(const EvalScene& scene) {
    const std::vector<CropRect> crops = visible_crops(scene);
    const int w = display_width(scene);
    const double scale = scene.width > 0 ? double(w) / scene.width : 1.0;
    // Each figure as wide as its images, so that captions wrap under them, never beside.
    const std::string figure = "<figure style=\"width:" + std::to_string(w) + "px\">";
    out << "<div class=\"figures\">\n";
    if (!scene.reference_file.empty()) {
        out << figure << "<div class=\"outlined\">";
        img(scene.reference_file, "reference", size_attributes(scene));
        for (std::size_t i = 0; i < crops.size(); ++i) {
            const CropRect& c = crops[i];
            out << "<div class=\"outline\" style=\"left:" << coord(c.x * scale - 2)
                << "px;top:" << coord(c.y * scale - 2) << "px;width:" << coord(c.width * scale)
                << "px;height:" << coord(c.height * scale) << "px\"><span>" << crop_name(i)
                << "</span></div>";
        }
        out << "</div><figcaption>reference \u00b7 " << scene.reference_spp
            << " spp</figcaption></figure>\n";
    }
    for (const EvalMethod& m : scene.methods) {
        if (m.image_file.empty() && m.heat_map_file.empty()) continue;
        out << figure;
        if (!m.image_file.empty()) img(m.image_file, m.name, size_attributes(scene));
        if (!m.heat_map_file.empty())
            img(m.heat_map_file, m.name + " error heat map", size_attributes(scene));
        out << "<figcaption>" << html_escape(m.name) << " \u00b7 RMSE " << number(m.rmse)
            << "</figcaption></figure>\n";
    }
    out << "</div>\n";
}

void HtmlWriter::crops(const EvalScene& scene) {
    const std::vector<CropRect> crops = visible_crops(scene);
    if (crops.empty()) return;
    struct Source {
        std::string name, file;
    };
    std::vector<Source> sources;
    if (!scene.reference_file.empty()) sources.push_back({"reference", scene.reference_file});
    for (const EvalMethod& m : scene.methods)
        if (!m.image_file.empty()) sources.push_back({m.name, m.image_file});
    if (sources.empty()) return;
    out << "<h3>Hardest regions</h3>\n";
    for (std::size_t i = 0; i < crops.size(); ++i) {
        const CropRect& c = crops[i];
        const int zoom = std::clamp(256 / std::max(c.width, c.height), 1, 4);
        out << "<div class=\"crop-row\"><div class=\"label\">" << crop_name(i)
            << "<div class=\"crop-caption\">" << c.width << "\u00d7" << c.height << " at (" << c.x
            << ", " << c.y << "), \u00d7" << zoom << "</div></div>\n";
        for (const Source& s : sources) {
            out << "<div><div class=\"crop\" style=\"width:" << c.width * zoom
                << "px;height:" << c.height * zoom << "px\">";
            img(s.file, s.name + " crop " + crop_name(i),
                " style=\"left:-" + std::to_string(c.x * zoom) + "px;top:-" +
                    std::to_string(c.y * zoom) + "px;width:" + std::to_string(scene.width * zoom) +
                    "px;height:" + std::to_string(scene.height * zoom) + "px\"");
            out << "</div><div class=\"crop-caption\">" << html_escape(s.name) << "</div></div>\n";
        }
        out << "</div>\n";
    }
}

// One line on what a filter mode is (README "Rendering"); "" for a name not known here.
std::string filter_description(const std::string& name) {
    static const std::pair<const char*, const char*> kFilters[] = {
        {"bilinear",
         "one bilinear lookup of the finest level per map and pixel, no footprint: the aliased "
         "baseline"},
        {"point",
         "one bilinear lookup of the finest level per map and pixel, no footprint: the aliased "
         "baseline"},
        {"trilinear",
         "isotropic MIP mapping (two levels, bilinear in each) sized by the footprint's major "
         "axis: the 1997 hardware baseline, blurry where the footprint is long and thin"},
        {"fa",
         "footprint assembly (Schilling 1996): a line of probes along the footprint's major axis, "
         "for the texture, the bumps' mean slope and the environment"},
        {"fa-rough",
         "fa plus the roughness pyramid (Schilling 1997): the bumps' slope covariance widens the "
         "environment footprint and the highlights"},
        {"ewa-rough",
         "elliptical weighted average (Heckbert 1989) with the roughness pyramid: a costlier "
         "filter of the same footprint, for comparison"},
        {"lean",
         "peer: LEAN mapping (Olano & Baker 2010), the slopes' first and second moments in the "
         "MIP pyramid, read by a GPU's 16x anisotropic filter; Fresnel at the mean normal"},
        {"toksvig",
         "peer: Toksvig (2005), a MIP pyramid of unit normals whose shortened mean gives an "
         "isotropic roughness"},
        {"specular-aa",
         "peer: geometric specular antialiasing (Kaplanyan et al. 2016; Tokuyoshi & Kaplanyan "
         "2019), roughness from the normal's change across the pixel, clamped; what Filament, "
         "Unity and Unreal ship"},
        {"stochastic",
         "peer: stochastic texture filtering (Pharr, Wronski, Salvi & Fajardo 2024), each lookup "
         "reads one position the filter picks at random and the shading is averaged by the "
         "pixel's samples: unbiased, noisy"},
    };
    for (const auto& [key, text] : kFilters)
        if (name == key) return text;
    return "";
}

void methods_header(std::ostringstream& out, const EvalReport& report) {
    std::vector<std::string> filters;
    bool supersampling = false;
    for (const EvalScene& scene : report.scenes)
        for (const EvalMethod& m : scene.methods) {
            if (m.family == "supersampling")
                supersampling = true;
            else if (std::find(filters.begin(), filters.end(), m.name) == filters.end())
                filters.push_back(m.name);
        }
    out << "<section class=\"methods\"><h2>The methods</h2>\n<dl>\n";
    for (const std::string& name : filters) {
        const std::string text = filter_description(name);
        out << "<dt>" << html_escape(name) << "</dt><dd>"
            << html_escape(text.empty() ? "a filter mode" : text) << ", at 1 spp</dd>\n";
    }
    if (supersampling)
        out << "<dt>supersampling N spp</dt><dd>N jittered samples per pixel under the same "
               "Gaussian pixel filter, each an unfiltered bilinear lookup of the finest level; its "
               "own samples, independent of the reference's</dd>\n";
    out << "<dt>reference</dt><dd>the ground truth: that supersampling with many more samples "
           "per pixel (the spp in each scene's table)</dd>\n</dl>\n<p class=\"note\">RMSE in "
           "linear light against the reference; SSIM on the displayed (sRGB) images; mean FLIP "
           "(Andersson et al. 2020; HDR-FLIP where the reference is HDR) over the interior; "
           "heat maps "
           "show each pixel's error on the scene's colour scale (legend above the images).</p>\n"
           "</section>\n";
}

// The page and the number of images in it.
std::pair<std::string, int> build_html(const EvalReport& report) {
    HtmlWriter w;
    const std::string title = report.title.empty() ? "footprint evaluation" : report.title;
    w.out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>"
          << html_escape(title) << "</title>\n<style>" << style_sheet << "</style>\n</head>\n"
          << "<body>\n<h1>" << html_escape(title) << "</h1>\n";
    if (!report.generated_by.empty())
        w.out << "<p class=\"generated\">" << html_escape(report.generated_by) << "</p>\n";
    if (report.scenes.size() > 1) {
        w.out << "<nav>";
        for (const EvalScene& s : report.scenes)
            w.out << "<a href=\"#" << html_escape(url_of(s.name)) << "\">"
                  << html_escape(s.title.empty() ? s.name : s.title) << "</a>";
        w.out << "</nav>\n";
    }
    if (!report.scenes.empty()) methods_header(w.out, report);
    for (const EvalScene& s : report.scenes) w.scene(s);
    w.out << "<script>" << check_script << "</script>\n</body>\n</html>\n";
    return {w.out.str(), w.images};
}

}  // namespace

Status write_eval_report(const EvalReport& report, const fs::path& html_file) {
    return write_file_atomically(html_file, build_html(report).first);
}

int report_image_count(const EvalReport& report) {
    return build_html(report).second;
}

// ---------------------------------------------------------------------------------------------
// The browser check

namespace {

bool is_executable_file(const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

std::optional<fs::path> on_path(const std::string& name) {
    const char* path = std::getenv("PATH");
    if (!path) return std::nullopt;
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        if (dir.empty()) continue;
        const fs::path candidate = fs::path(dir) / name;
        if (is_executable_file(candidate)) return candidate;
    }
    return std::nullopt;
}

std::string shell_quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string decode_entities(std::string_view s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '&') {
            static const std::pair<std::string_view, char> entities[] = {
                {"&amp;", '&'}, {"&quot;", '"'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&#39;", '\''}};
            bool done = false;
            for (const auto& [entity, c] : entities)
                if (s.substr(i, entity.size()) == entity) {
                    out += c;
                    i += entity.size() - 1;
                    done = true;
                    break;
                }
            if (done) continue;
        }
        out += s[i];
    }
    return out;
}

// The attributes of the first <body …> start tag in `html`.
std::vector<std::pair<std::string, std::string>> body_attributes(const std::string& html) {
    std::vector<std::pair<std::string, std::string>> result;
    std::size_t i = html.find("<body");
    if (i == std::string::npos) return result;
    i += 5;
    auto space = [&](char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r'; };
    while (i < html.size()) {
        while (i < html.size() && space(html[i])) ++i;
        if (i >= html.size() || html[i] == '>' || html[i] == '/') break;
        std::string name;
        while (i < html.size() && !space(html[i]) && html[i] != '=' && html[i] != '>')
            name += html[i++];
        std::string value;
        if (i < html.size() && html[i] == '=') {
            ++i;
            if (i < html.size() && (html[i] == '"' || html[i] == '\'')) {
                const char q = html[i++];
                const std::size_t end = html.find(q, i);
                if (end == std::string::npos) break;
                value = decode_entities(std::string_view(html).substr(i, end - i));
                i = end + 1;
            } else {
                while (i < html.size() && !space(html[i]) && html[i] != '>') value += html[i++];
            }
        }
        result.emplace_back(name, value);
    }
    return result;
}

std::string file_url(const fs::path& absolute) {
    return "file://" + url_of(absolute.string());
}

}  // namespace

std::optional<fs::path> find_chromium() {
    if (const char* env = std::getenv("FOOTPRINT_CHROMIUM"); env && *env) {
        if (is_executable_file(env)) return fs::path(env);
        if (auto found = on_path(env)) return found;
        return std::nullopt;
    }
    for (const char* name :
         {"chromium", "chromium-browser", "google-chrome", "google-chrome-stable"})
        if (auto found = on_path(name)) return found;
    return std::nullopt;
}

BrowserCheck check_report_in_browser(const fs::path& html_file, int expected_images) {
    BrowserCheck check;
    const std::optional<fs::path> chromium = find_chromium();
    if (!chromium) {
        const char* env = std::getenv("FOOTPRINT_CHROMIUM");
        check.problem = env && *env
                            ? "FOOTPRINT_CHROMIUM=" + quoted(env) + " is not an executable file"
                            : "chromium not found (looked for chromium, chromium-browser, "
                              "google-chrome, google-chrome-stable on PATH; set "
                              "FOOTPRINT_CHROMIUM)";
        return check;
    }
    check.chromium_found = true;
    std::error_code ec;
    fs::path absolute = fs::absolute(html_file, ec);
    if (ec || !fs::is_regular_file(absolute, ec)) {
        check.problem = "cannot check " + quoted(html_file) + ": no such file";
        return check;
    }
    absolute = absolute.lexically_normal();

    std::string command;
    if (on_path("timeout")) command = "timeout 60 ";
    command += shell_quote(chromium->string()) +
               " --headless --no-sandbox --disable-gpu --allow-file-access-from-files"
               " --virtual-time-budget=10000 --dump-dom " +
               shell_quote(file_url(absolute)) + " 2>/dev/null";
    const auto start = std::chrono::steady_clock::now();
    std::string dom;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) {
        check.problem = "cannot run " + quoted(*chromium);
        return check;
    }
    std::array<char, 65536> buffer;
    while (const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
        dom.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    check.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    int found = 0;
    std::string failed_list;
    for (const auto& [name, value] : body_attributes(dom)) {
        auto as_int = [&](int& target) {
            char* end = nullptr;
            const long v = std::strtol(value.c_str(), &end, 10);
            if (end != value.c_str() && *end == '\0') {
                target = static_cast<int>(v);
                ++found;
            }
        };
        if (name == "data-images-loaded") as_int(check.images_loaded);
        if (name == "data-images-failed") as_int(check.images_failed);
        if (name == "data-images-total") as_int(check.images_total);
        if (name == "data-images-failed-list") failed_list = value;
    }
    if (found < 3) {
        const int code = status == -1 ? -1 : WIFEXITED(status) ? WEXITSTATUS(status) : 128;
        if (code == 124)
            check.problem = quoted(*chromium) + " timed out after 60 s on " + quoted(absolute);
        else if (dom.empty())
            check.problem = quoted(*chromium) + " printed no page for " + quoted(absolute) +
                            " (exit status " + std::to_string(code) + ")";
        else
            check.problem = "the image counts are missing from " + quoted(absolute) +
                            " in Chromium (the report's script did not run)";
        return check;
    }
    check.ran = true;
    if (check.images_failed > 0) {
        std::string names;
        std::stringstream lines(failed_list);
        std::string line;
        int listed = 0;
        while (std::getline(lines, line)) {
            if (line.empty()) continue;
            if (listed == 5) {
                names += ", …";
                break;
            }
            names += (listed++ ? ", " : "") + line;
        }
        check.problem = std::to_string(check.images_failed) + " of " +
                        std::to_string(check.images_total) + " images failed to load in " +
                        quoted(absolute) + (names.empty() ? "" : ": " + names);
    } else if (check.images_loaded < expected_images) {
        check.problem = "only " + std::to_string(check.images_loaded) + " images in " +
                        quoted(absolute) + ", expected " + std::to_string(expected_images);
    }
    return check;
}

}  // namespace footprint
