#include "metrics/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "metrics/image_metrics.h"

namespace footprint {

namespace {

// ---- constants (FLIP paper unless noted) -------------------------------------------------------

constexpr float kQc = 0.7f;                   // exponent of the colour difference, q_c
constexpr float kPc = 0.4f;                   // the colour error's knee: p_c · c_max …
constexpr float kPt = 0.95f;                  // … maps to p_t
constexpr float kFeatureWidth = 0.082f;       // w, degrees: the feature filters' σ is w/2
constexpr double kMaxPixelsPerDegree = 1000;  // filters of > 250 pixels: no real display

// The contrast sensitivity of one opponent channel as a sum of two Gaussians, in the spatial
// domain S(x) = a1 √(π/b1) exp(−π² x²/b1) + a2 √(π/b2) exp(−π² x²/b2), x in degrees.
struct CsfGaussians {
    float a1, b1, a2, b2;
};
constexpr CsfGaussians kCsfAchromatic{1.0f, 0.0047f, 0.0f, 1e-5f};
constexpr CsfGaussians kCsfRedGreen{1.0f, 0.0053f, 0.0f, 1e-5f};
constexpr CsfGaussians kCsfBlueYellow{34.1f, 0.04f, 13.5f, 0.025f};
constexpr float kCsfLargestB = 0.04f;  // the widest of the six Gaussians sets the filter radius

// HDR-FLIP: the exposure range maps the reference's largest luminance, and its median, to the
// input that the tone mapper takes to this value.
constexpr double kToneMappedTarget = 0.85;
// Narkowicz's fit of the ACES filmic curve, T(c) = y (A y + B) / (y (C y + D) + E), y = 0.6 c.
constexpr float kAcesA = 2.51f, kAcesB = 0.03f, kAcesC = 2.43f, kAcesD = 0.59f, kAcesE = 0.14f;
constexpr float kAcesPreScale = 0.6f;  // cancels the exposure the fit has built in

// Linear sRGB (D65) → XYZ, exact rational form; its rows sum to the D65 white point.
constexpr double kRgbToXyz[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};

struct Float3 {
    float x, y, z;
};

struct Matrix3f {
    float m[3][3];
    Float3 operator*(Float3 v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
};

constexpr Matrix3f to_float(const double (&m)[3][3]) {
    Matrix3f f{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) f.m[r][c] = static_cast<float>(m[r][c]);
    return f;
}

// The inverse of kRgbToXyz (adjugate over determinant, in double), as float.
constexpr Matrix3f inverse_to_float(const double (&m)[3][3]) {
    double inv[3][3]{};
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            // Cofactor of element (c, r): the transpose gives the adjugate.
            const int r0 = (c + 1) % 3, r1 = (c + 2) % 3, c0 = (r + 1) % 3, c1 = (r + 2) % 3;
            inv[r][c] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
        }
    return to_float(inv);
}

constexpr Matrix3f kLinearRgbToXyz = to_float(kRgbToXyz);
constexpr Matrix3f kXyzToLinearRgb = inverse_to_float(kRgbToXyz);
constexpr Float3 kWhite = {static_cast<float>(kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2]),
                           static_cast<float>(kRgbToXyz[1][0] + kRgbToXyz[1][1] + kRgbToXyz[1][2]),
                           static_cast<float>(kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2])};

// ---- colour spaces -----------------------------------------------------------------------------

// YCxCz: CIELAB without its cube root, linear in XYZ, so filtering commutes with it.
Float3 xyz_to_ycxcz(Float3 xyz) {
    const float x = xyz.x / kWhite.x, y = xyz.y / kWhite.y, z = xyz.z / kWhite.z;
    return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
}

Float3 ycxcz_to_xyz(Float3 v) {
    const float y = (v.x + 16.0f) / 116.0f;
    return {(y + v.y / 500.0f) * kWhite.x, y * kWhite.y, (y - v.z / 200.0f) * kWhite.z};
}

// CIELAB with the Hunt adjustment: a and b scaled by 0.01 L, as colourfulness drops with
// luminance.
Float3 xyz_to_hunt_lab(Float3 xyz) {
    constexpr float delta = 6.0f / 29.0f;
    auto f = [&](float t) {
        return t > delta * delta * delta ? std::cbrt(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
    };
    const float fx = f(xyz.x / kWhite.x), fy = f(xyz.y / kWhite.y), fz = f(xyz.z / kWhite.z);
    const float lightness = 116.0f * fy - 16.0f;
    const float a = 500.0f * (fx - fy), b = 200.0f * (fy - fz);
    return {lightness, 0.01f * lightness * a, 0.01f * lightness * b};
}

// HyAB distance (Abasi et al. 2020): city block in L, Euclidean in (a, b).
float hyab(Float3 p, Float3 q) {
    const float da = p.y - q.y, db = p.z - q.z;
    return std::abs(p.x - q.x) + std::sqrt(da * da + db * db);
}

Float3 clamp01(Float3 c) {
    return {std::clamp(c.x, 0.0f, 1.0f), std::clamp(c.y, 0.0f, 1.0f), std::clamp(c.z, 0.0f, 1.0f)};
}

// c_max: the difference between pure green and pure blue, the largest of all, raised to q_c.
float max_colour_difference() {
    const Float3 green = xyz_to_hunt_lab(kLinearRgbToXyz * Float3{0, 1, 0});
    const Float3 blue = xyz_to_hunt_lab(kLinearRgbToXyz * Float3{0, 0, 1});
    return std::pow(hyab(green, blue), kQc);
}

// The colour error in [0, 1] from the CSF-filtered YCxCz of the two images.
float colour_error(Float3 filtered_a, Float3 filtered_b, float c_max) {
    const Float3 lab_a =
        xyz_to_hunt_lab(kLinearRgbToXyz * clamp01(kXyzToLinearRgb * ycxcz_to_xyz(filtered_a)));
    const Float3 lab_b =
        xyz_to_hunt_lab(kLinearRgbToXyz * clamp01(kXyzToLinearRgb * ycxcz_to_xyz(filtered_b)));
    const float difference = std::pow(hyab(lab_a, lab_b), kQc);
    // Compress the large differences: [0, p_c c_max) onto [0, p_t), the rest onto [p_t, 1].
    const float knee = kPc * c_max;
    if (difference < knee) return difference * (kPt / knee);
    return kPt + (difference - knee) / (c_max - knee) * (1.0f - kPt);
}

// Narkowicz's ACES fit (HDR-FLIP paper), per channel. T exceeds 1 for |y| > 7.3 (and is then
// clamped to 1), so limiting y to ±10⁴ changes nothing but keeps y² finite for any input.
float aces(float c) {
    const float y = std::clamp(kAcesPreScale * c, -1e4f, 1e4f);
    return y * (kAcesA * y + kAcesB) / (y * (kAcesC * y + kAcesD) + kAcesE);
}

// The input x ≥ 0 that aces() maps to `target`: the larger root of
// (A − tC) y² + (B − tD) y − tE = 0, y = 0.6 x.
double aces_inverse(double target) {
    const double a = kAcesA - target * kAcesC, b = kAcesB - target * kAcesD, c = -target * kAcesE;
    const double y = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
    return y / kAcesPreScale;
}

float luminance(Float3 rgb) {
    return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}

// ---- planes and separable filters --------------------------------------------------------------

struct Plane {
    int width = 0, height = 0;
    std::vector<float> v;
    Plane() = default;
    Plane(int w, int h) : width(w), height(h), v(static_cast<std::size_t>(w) * h) {}
    float* row(int y) { return v.data() + static_cast<std::size_t>(y) * width; }
    const float* row(int y) const { return v.data() + static_cast<std::size_t>(y) * width; }
};

// Runs body(y) for every row, rows in parallel.
template <class Body>
void for_each_row(int height, const Body& body) {
    parallel_for_each(0, height, body);
}

// A 1-D filter: weight[k + radius] for offsets k = −radius … radius. The derivative filters are
// applied in a form that is exactly 0 on a constant signal, as they are in exact arithmetic (a
// plain float sum leaves ~1e-8, which q_f = ½ would raise to ~1e-4 of feature error).
enum class TapsShape {
    general,        // Σ_k w_k s(k)
    odd,            // w_−k = −w_k: Σ_{k>0} w_k (s(k) − s(−k))
    even_zero_sum,  // w_−k = w_k, Σ w = 0: Σ_{k>0} w_k ((s(k) − s(0)) + (s(−k) − s(0)))
};
struct Taps {
    int radius = 0;
    std::vector<float> weight;
    TapsShape shape = TapsShape::general;
};

// dst[x] = Σ_k w_k source(k)[x], x = 0 … n − 1, where source(k) points at the samples offset by k.
template <class Source>
void convolve_line(const Taps& taps, int n, const Source& source, float* dst) {
    const int r = taps.radius;
    std::fill_n(dst, n, 0.0f);
    switch (taps.shape) {
        case TapsShape::general:
            for (int k = -r; k <= r; ++k) {
                const float w = taps.weight[k + r];
                const float* s = source(k);
                for (int x = 0; x < n; ++x) dst[x] += w * s[x];
            }
            return;
        case TapsShape::odd:
            for (int k = 1; k <= r; ++k) {
                const float w = taps.weight[k + r];
                const float *plus = source(k), *minus = source(-k);
                for (int x = 0; x < n; ++x) dst[x] += w * (plus[x] - minus[x]);
            }
            return;
        case TapsShape::even_zero_sum: {
            const float* centre = source(0);
            for (int k = 1; k <= r; ++k) {
                const float w = taps.weight[k + r];
                const float *plus = source(k), *minus = source(-k);
                for (int x = 0; x < n; ++x)
                    dst[x] += w * ((plus[x] - centre[x]) + (minus[x] - centre[x]));
            }
            return;
        }
    }
}

// out(x, y) = Σ_k w_k in(clamp(x + k), y): the row extended by its edge pixels.
Plane filter_rows(const Plane& in, const Taps& taps) {
    Plane out(in.width, in.height);
    const int r = taps.radius, w = in.width;
    for_each_row(in.height, [&](int y) {
        std::vector<float> padded(static_cast<std::size_t>(w) + 2 * r);
        const float* src = in.row(y);
        for (int i = 0; i < w + 2 * r; ++i) padded[i] = src[std::clamp(i - r, 0, w - 1)];
        convolve_line(
            taps, w, [&](int k) { return padded.data() + r + k; }, out.row(y));
    });
    return out;
}

// out(x, y) = Σ_k w_k in(x, clamp(y + k)).
Plane filter_columns(const Plane& in, const Taps& taps) {
    Plane out(in.width, in.height);
    for_each_row(in.height, [&](int y) {
        convolve_line(
            taps, in.width, [&](int k) { return in.row(std::clamp(y + k, 0, in.height - 1)); },
            out.row(y));
    });
    return out;
}

// A 2-D CSF filter as one or two separable terms: Σ_i u_i(dx) u_i(dy).
struct CsfFilter {
    std::vector<Taps> terms;
};

// Each Gaussian a √(π/b) exp(−π² (dx² + dy²)/b) of S is the product of
// u(d) = √(a √(π/b)) exp(−π² d²/b) in dx and in dy (d in degrees = pixels / ppd). All terms are
// scaled by 1/√(Σ_i (Σ_d u_i(d))²), so the 2-D filter's weights sum to 1 over the square.
CsfFilter make_csf_filter(const CsfGaussians& g, float ppd, int radius) {
    constexpr float pi = std::numbers::pi_v<float>;
    CsfFilter filter;
    const std::array<std::array<float, 2>, 2> gaussians = {{{g.a1, g.b1}, {g.a2, g.b2}}};
    double squared_sums = 0;
    for (const auto& [a, b] : gaussians) {
        if (a == 0.0f) continue;  // the achromatic and red-green CSFs are a single Gaussian
        Taps taps{radius, std::vector<float>(2 * radius + 1)};
        double sum = 0;
        for (int d = -radius; d <= radius; ++d) {
            const float degrees = static_cast<float>(d) / ppd;
            taps.weight[d + radius] =
                std::sqrt(a * std::sqrt(pi / b)) * std::exp(-pi * pi * degrees * degrees / b);
            sum += taps.weight[d + radius];
        }
        squared_sums += sum * sum;
        filter.terms.push_back(std::move(taps));
    }
    const float scale = static_cast<float>(1.0 / std::sqrt(squared_sums));
    for (Taps& taps : filter.terms)
        for (float& w : taps.weight) w *= scale;
    return filter;
}

Plane filter_csf(const CsfFilter& filter, const Plane& in) {
    Plane sum;
    for (const Taps& taps : filter.terms) {
        Plane term = filter_columns(filter_rows(in, taps), taps);
        if (sum.v.empty()) {
            sum = std::move(term);
        } else {
            for (std::size_t i = 0; i < sum.v.size(); ++i) sum.v[i] += term.v[i];
        }
    }
    return sum;
}

// The feature filters' 1-D factors: the Gaussian G (σ = w/2 · ppd pixels), its
// first derivative −d G and its second (d²/σ² − 1) G. The edge filter in x is G′(dx) G(dy), the
// point filter G″(dx) G(dy), and likewise in y. G is normalised to sum 1; G′ and G″ have their
// positive weights normalised to sum 1 and their negative ones to sum −1, so the 2-D filters
// (times the normalised G) are too.
struct FeatureFilters {
    Taps gaussian, first, second;
};

void normalise_signed(Taps& taps) {
    double positive = 0, negative = 0;
    for (float w : taps.weight) (w > 0 ? positive : negative) += std::abs(w);
    for (float& w : taps.weight) {
        const double sum = w > 0 ? positive : negative;
        if (sum > 0) w = static_cast<float>(w / sum);  // a tiny σ leaves no weight off centre
    }
}

FeatureFilters make_feature_filters(float ppd) {
    const float sigma = 0.5f * kFeatureWidth * ppd;
    const int radius = static_cast<int>(std::ceil(3.0f * sigma));
    FeatureFilters f;
    for (Taps* taps : {&f.gaussian, &f.first, &f.second}) {
        taps->radius = radius;
        taps->weight.assign(2 * radius + 1, 0.0f);
    }
    f.first.shape = TapsShape::odd;
    f.second.shape = TapsShape::even_zero_sum;
    double gaussian_sum = 0;
    for (int d = -radius; d <= radius; ++d) {
        const float x = static_cast<float>(d);
        const float g = std::exp(-(x * x) / (2.0f * sigma * sigma));
        f.gaussian.weight[d + radius] = g;
        f.first.weight[d + radius] = -x * g;
        f.second.weight[d + radius] = (x * x / (sigma * sigma) - 1.0f) * g;
        gaussian_sum += g;
    }
    for (float& w : f.gaussian.weight) w = static_cast<float>(w / gaussian_sum);
    normalise_signed(f.first);
    normalise_signed(f.second);
    return f;
}

struct Filters {
    CsfFilter achromatic, red_green, blue_yellow;
    FeatureFilters feature;
    float c_max = 0;
};

Filters make_filters(float ppd) {
    constexpr float pi = std::numbers::pi_v<float>;
    // Three standard deviations of the widest Gaussian: its σ is √(b / 2π²) degrees.
    const int radius =
        static_cast<int>(std::ceil(3.0f * std::sqrt(kCsfLargestB / (2.0f * pi * pi)) * ppd));
    return {make_csf_filter(kCsfAchromatic, ppd, radius),
            make_csf_filter(kCsfRedGreen, ppd, radius),
            make_csf_filter(kCsfBlueYellow, ppd, radius), make_feature_filters(ppd),
            max_colour_difference()};
}

// ---- LDR-FLIP ----------------------------------------------------------------------------------

// Linear RGB, 3 floats a pixel, width × height.
struct Rgb {
    int width = 0, height = 0;
    std::vector<float> values;
    Float3 at(std::size_t p) const { return {values[3 * p], values[3 * p + 1], values[3 * p + 2]}; }
};

// What the observer takes in of one image: its CSF-filtered YCxCz and, per pixel, the strength
// of its edges and points.
struct Perceived {
    Plane y, cx, cz;    // CSF-filtered YCxCz
    Plane edge, point;  // |(G′x, G′y) ∗ Y|, |(G″x, G″y) ∗ Y| on Y normalised to [0, 1]
};

Perceived perceive(const Rgb& rgb, const Filters& filters) {
    const int w = rgb.width, h = rgb.height;
    Plane y(w, h), cx(w, h), cz(w, h), achromatic(w, h);
    for_each_row(h, [&](int row) {
        for (int x = 0; x < w; ++x) {
            const std::size_t p = static_cast<std::size_t>(row) * w + x;
            const Float3 v = xyz_to_ycxcz(kLinearRgbToXyz * rgb.at(p));
            y.v[p] = v.x;
            cx.v[p] = v.y;
            cz.v[p] = v.z;
            achromatic.v[p] = (v.x + 16.0f) / 116.0f;
        }
    });
    Perceived seen;
    seen.y = filter_csf(filters.achromatic, y);
    seen.cx = filter_csf(filters.red_green, cx);
    seen.cz = filter_csf(filters.blue_yellow, cz);

    const FeatureFilters& f = filters.feature;
    const Plane smooth_x = filter_rows(achromatic, f.gaussian);
    const Plane dx = filter_columns(filter_rows(achromatic, f.first), f.gaussian);
    const Plane ddx = filter_columns(filter_rows(achromatic, f.second), f.gaussian);
    const Plane dy = filter_columns(smooth_x, f.first);
    const Plane ddy = filter_columns(smooth_x, f.second);
    seen.edge = Plane(w, h);
    seen.point = Plane(w, h);
    for_each_row(h, [&](int row) {
        for (std::size_t p = static_cast<std::size_t>(row) * w;
             p < static_cast<std::size_t>(row + 1) * w; ++p) {
            seen.edge.v[p] = std::sqrt(dx.v[p] * dx.v[p] + dy.v[p] * dy.v[p]);
            seen.point.v[p] = std::sqrt(ddx.v[p] * ddx.v[p] + ddy.v[p] * ddy.v[p]);
        }
    });
    return seen;
}

// The LDR-FLIP map of a against b, both linear RGB in [0, 1].
std::vector<float> ldr_flip(const Rgb& a, const Rgb& b, const Filters& filters) {
    const Perceived sa = perceive(a, filters), sb = perceive(b, filters);
    const int w = a.width;
    std::vector<float> map(a.values.size() / 3);
    const float feature_scale = 1.0f / std::sqrt(2.0f);
    for_each_row(a.height, [&](int row) {
        for (int x = 0; x < w; ++x) {
            const std::size_t p = static_cast<std::size_t>(row) * w + x;
            const float colour = colour_error({sa.y.v[p], sa.cx.v[p], sa.cz.v[p]},
                                              {sb.y.v[p], sb.cx.v[p], sb.cz.v[p]}, filters.c_max);
            const float edge = std::abs(sa.edge.v[p] - sb.edge.v[p]);
            const float point = std::abs(sa.point.v[p] - sb.point.v[p]);
            // q_f = ½: the exponent of the feature difference.
            const float feature = std::sqrt(feature_scale * std::max(edge, point));
            map[p] = std::pow(colour, 1.0f - feature);  // features raise the error
        }
    });
    return map;
}

// ---- input ---------------------------------------------------------------------------------

std::string size_text(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

std::string number_text(double value) {
    std::string text = std::to_string(value);
    if (text.find('.') != std::string::npos) {
        text.erase(text.find_last_not_of('0') + 1);
        if (text.back() == '.') text.pop_back();
    }
    return text;
}

// The colour channels as RGB: channels 0–2 of a 3- or 4-channel image, channel 0 thrice of a
// 1- or 2-channel one (alpha is ignored).
Rgb colour_of(const Image& image) {
    Rgb rgb{image.width, image.height, std::vector<float>(image.pixel_count() * 3)};
    for (std::size_t p = 0; p < image.pixel_count(); ++p)
        for (int c = 0; c < 3; ++c)
            rgb.values[3 * p + c] =
                image.pixels[p * image.channels + (image.channels >= 3 ? c : 0)];
    return rgb;
}

std::optional<Error> check_inputs(const Image& a, const Image& b, const FlipOptions& options) {
    const double ppd = options.pixels_per_degree;
    if (!(std::isfinite(ppd) && ppd > 0 && ppd <= kMaxPixelsPerDegree))
        return Error{"pixels per degree must be finite, > 0 and <= " +
                     number_text(kMaxPixelsPerDegree) + " (got " + number_text(ppd) + ")"};
    if (a.empty()) return Error{"A is empty"};
    if (b.empty()) return Error{"B is empty"};
    if (a.width != b.width || a.height != b.height)
        return Error{"images differ in size: A is " + size_text(a) + ", B is " + size_text(b)};
    if (a.channels != b.channels)
        return Error{"images differ in channels: A has " + std::to_string(a.channels) + ", B has " +
                     std::to_string(b.channels)};
    const NonFinitePixels in_a = find_non_finite(a), in_b = find_non_finite(b);
    if (in_a.count > 0 || in_b.count > 0)
        return Error{"A has " + non_finite_text(in_a) + "; B has " + non_finite_text(in_b)};
    for (const auto& [value, name] :
         {std::pair{options.start_exposure, "start"}, std::pair{options.stop_exposure, "stop"}})
        if (value && !std::isfinite(*value))
            return Error{std::string(name) + " exposure must be finite (got " +
                         number_text(*value) + ")"};
    if (options.start_exposure && options.stop_exposure &&
        *options.start_exposure > *options.stop_exposure)
        return Error{"start exposure " + number_text(*options.start_exposure) +
                     " is above stop exposure " + number_text(*options.stop_exposure)};
    if (options.exposures < 0)
        return Error{"the number of exposures must be >= 0, 0 for automatic (got " +
                     std::to_string(options.exposures) + ")"};
    return std::nullopt;
}

// The counted pixels as flags, or an Error (the rules of image_metrics.h).
Result<std::vector<unsigned char>> counted_pixels(const Image& shape, const Image* mask) {
    if (!mask) return std::vector<unsigned char>(shape.pixel_count(), 1);
    if (mask->empty()) return Error{"mask is empty"};
    if (mask->width != shape.width || mask->height != shape.height)
        return Error{"mask is " + size_text(*mask) + " but the images are " + size_text(shape)};
    if (const NonFinitePixels bad = find_non_finite(*mask); bad.count > 0)
        return Error{"mask has " + non_finite_text(bad)};
    std::vector<unsigned char> counted(mask->pixel_count());
    bool any = false;
    for (std::size_t p = 0; p < counted.size(); ++p) {
        counted[p] = mask->pixels[p * mask->channels] > 0.5f;
        any = any || counted[p];
    }
    if (!any) return Error{"mask selects no pixel (no value of channel 0 is > 0.5)"};
    return counted;
}

bool exceeds_one(const Rgb& rgb) {
    return std::any_of(rgb.values.begin(), rgb.values.end(), [](float v) { return v > 1.0f; });
}

// ---- HDR-FLIP ----------------------------------------------------------------------------------

struct ExposureRange {
    double start = 0, stop = 0;
    int count = 0;
};

// The exposures: given, or from the reference's luminance (HDR-FLIP paper, see flip.h).
Result<ExposureRange> exposure_range(const Rgb& reference, const FlipOptions& options) {
    ExposureRange range;
    if (!options.start_exposure || !options.stop_exposure) {
        std::vector<float> luminances(reference.values.size() / 3);
        for (std::size_t p = 0; p < luminances.size(); ++p)
            luminances[p] = luminance(reference.at(p));
        const float largest = *std::max_element(luminances.begin(), luminances.end());
        if (!(largest > 0))
            return Error{
                "B has no pixel of positive luminance: HDR-FLIP's automatic exposures are "
                "undefined; give the start and stop exposures"};
        auto median_of = [](std::vector<float>& values) {
            const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
            std::nth_element(values.begin(), middle, values.end());
            return *middle;
        };
        float median = median_of(luminances);
        if (!(median > 0)) {
            std::erase_if(luminances, [](float y) { return !(y > 0); });
            median = median_of(luminances);
        }
        const double x_max = aces_inverse(kToneMappedTarget);
        range.start = options.start_exposure.value_or(std::log2(x_max / largest));
        range.stop = options.stop_exposure.value_or(std::log2(x_max / median));
        if (range.start > range.stop)
            return Error{"start exposure " + number_text(range.start) + " is above stop exposure " +
                         number_text(range.stop)};
    } else {
        range.start = *options.start_exposure;
        range.stop = *options.stop_exposure;
    }
    range.count = options.exposures > 0
                      ? options.exposures
                      : static_cast<int>(std::max(2.0, std::ceil(range.stop - range.start)));
    return range;
}

// The image at exposure e, tone mapped and clamped to [0, 1].
Rgb tone_map(const Rgb& rgb, double exposure) {
    const float scale = std::exp2(static_cast<float>(exposure));
    Rgb out{rgb.width, rgb.height, std::vector<float>(rgb.values.size())};
    for (std::size_t i = 0; i < out.values.size(); ++i)
        out.values[i] = std::clamp(aces(rgb.values[i] * scale), 0.0f, 1.0f);
    return out;
}

}  // namespace

double flip_pixels_per_degree(double distance, double resolution_x, double width) {
    return distance * (resolution_x / width) * std::numbers::pi / 180.0;
}

Result<FlipResult> flip(const Image& a, const Image& b, const FlipOptions& options) {
    if (auto e = check_inputs(a, b, options)) return *e;
    Result<std::vector<unsigned char>> counted = counted_pixels(a, options.mask);
    if (!counted) return counted.error();

    Rgb test = colour_of(a), reference = colour_of(b);
    FlipResult result;
    result.hdr = options.range == FlipRange::hdr || (options.range == FlipRange::automatic &&
                                                     (exceeds_one(test) || exceeds_one(reference)));
    const Filters filters = make_filters(static_cast<float>(options.pixels_per_degree));
    std::vector<float> map;
    if (!result.hdr) {
        for (Rgb* rgb : {&test, &reference})
            for (float& v : rgb->values) v = std::clamp(v, 0.0f, 1.0f);
        map = ldr_flip(test, reference, filters);
    } else {
        Result<ExposureRange> range = exposure_range(reference, options);
        if (!range) return range.error();
        result.start_exposure = range->start;
        result.stop_exposure = range->stop;
        result.exposures = range->count;
        const double step =
            range->count > 1 ? (range->stop - range->start) / (range->count - 1) : 0.0;
        for (int i = 0; i < range->count; ++i) {
            const double exposure = range->start + i * step;
            const std::vector<float> at_exposure =
                ldr_flip(tone_map(test, exposure), tone_map(reference, exposure), filters);
            if (map.empty()) {
                map = at_exposure;
            } else {
                for (std::size_t p = 0; p < map.size(); ++p)
                    map[p] = std::max(map[p], at_exposure[p]);
            }
        }
    }

    double sum = 0;
    for (std::size_t p = 0; p < map.size(); ++p)
        if ((*counted)[p]) {
            sum += map[p];
            ++result.pixels;
        }
    result.mean = sum / static_cast<double>(result.pixels);
    if (options.error_map) {
        result.error_map = Image(a.width, a.height, 1);
        result.error_map.pixels = std::move(map);
    }
    return result;
}

}  // namespace footprint
