#include "metrics/image_metrics.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace footprint {

namespace {

constexpr int kSsimRadius = 5;  // 11×11 window
constexpr double kSsimSigma = 1.5;
constexpr double kSsimK1 = 0.01;
constexpr double kSsimK2 = 0.03;

std::string size_text(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

std::optional<Error> check_finite(const Image& image, const std::string& name) {
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        if (!std::isfinite(image.pixels[i])) {
            const std::size_t p = i / image.channels;
            return Error{name + " has a non-finite value at pixel (" +
                         std::to_string(p % image.width) + ", " + std::to_string(p / image.width) +
                         ") channel " + std::to_string(i % image.channels)};
        }
    }
    return std::nullopt;
}

// Whether `b` has a's size and channels; the error names them "A" and "B" (or `a_name`, `b_name`).
std::optional<Error> check_same_shape(const Image& a, const Image& b, const std::string& a_name,
                                      const std::string& b_name) {
    if (a.empty()) return Error{a_name + " is empty"};
    if (b.empty()) return Error{b_name + " is empty"};
    if (a.width != b.width || a.height != b.height)
        return Error{"images differ in size: " + a_name + " is " + size_text(a) + ", " + b_name +
                     " is " + size_text(b)};
    if (a.channels != b.channels)
        return Error{"images differ in channels: " + a_name + " has " + std::to_string(a.channels) +
                     ", " + b_name + " has " + std::to_string(b.channels)};
    return std::nullopt;
}

// The counted pixels' indices (y * width + x) for images of `shape`'s size, or an Error.
Result<std::vector<std::size_t>> counted_pixels(const Image& shape, const Image* mask) {
    std::vector<std::size_t> counted;
    if (!mask) {
        counted.resize(shape.pixel_count());
        for (std::size_t p = 0; p < counted.size(); ++p) counted[p] = p;
        return counted;
    }
    if (mask->empty()) return Error{"mask is empty"};
    if (mask->width != shape.width || mask->height != shape.height)
        return Error{"mask is " + size_text(*mask) + " but the images are " + size_text(shape)};
    if (auto e = check_finite(*mask, "mask")) return *e;
    for (std::size_t p = 0; p < mask->pixel_count(); ++p)
        if (mask->pixels[p * mask->channels] > 0.5f) counted.push_back(p);
    if (counted.empty()) return Error{"mask selects no pixel (no value of channel 0 is > 0.5)"};
    return counted;
}

bool pixel_is_finite(const Image& image, std::size_t p) {
    for (int c = 0; c < image.channels; ++c)
        if (!std::isfinite(image.pixels[p * image.channels + c])) return false;
    return true;
}

// The non-finite values of a and b: an error unless ignored; ignored, the counted pixels where a
// or b has one are removed from `counted` (and `valid`, one flag per pixel, is filled).
std::optional<Error> handle_non_finite(const Image& a, const Image& b, bool ignore,
                                       std::vector<std::size_t>& counted,
                                       std::vector<unsigned char>& valid, ImageComparison& result) {
    const NonFinitePixels in_a = find_non_finite(a), in_b = find_non_finite(b);
    result.non_finite_a = in_a.count;
    result.non_finite_b = in_b.count;
    if (in_a.count == 0 && in_b.count == 0) return std::nullopt;
    if (!ignore)
        return Error{"A has " + non_finite_text(in_a) + "; B has " + non_finite_text(in_b)};
    valid.assign(a.pixel_count(), 1);
    for (std::size_t p = 0; p < valid.size(); ++p)
        valid[p] = pixel_is_finite(a, p) && pixel_is_finite(b, p);
    const std::size_t before = counted.size();
    std::erase_if(counted, [&](std::size_t p) { return !valid[p]; });
    result.excluded = before - counted.size();
    if (counted.empty())
        return Error{"no pixel left: every counted pixel has a non-finite value in A or B"};
    return std::nullopt;
}

// Mean of |a − b| over the counted pixels and all channels (same shapes assumed).
double mean_abs_over(const Image& a, const Image& b, const std::vector<std::size_t>& counted) {
    double sum = 0;
    const int channels = a.channels;
    for (std::size_t p : counted)
        for (int c = 0; c < channels; ++c) {
            const std::size_t i = p * channels + c;
            sum += std::abs(static_cast<double>(a.pixels[i]) - static_cast<double>(b.pixels[i]));
        }
    return sum / (static_cast<double>(counted.size()) * channels);
}

// The 1-D Gaussian weights g(d) = exp(−d² / 2σ²), d = −5 … 5 (index d + 5). The 11×11 window is
// their outer product; normalisation happens per pixel (border rule), so they are not normalised.
std::array<double, 2 * kSsimRadius + 1> gaussian_weights() {
    std::array<double, 2 * kSsimRadius + 1> g{};
    for (int d = -kSsimRadius; d <= kSsimRadius; ++d)
        g[d + kSsimRadius] = std::exp(-(d * d) / (2.0 * kSsimSigma * kSsimSigma));
    return g;
}

// Filters `planes` (each width × height, row-major) in place with the window cut to the image
// and renormalised. The cut window is the rectangle [x−5, x+5] ∩ [0, w) × [y−5, y+5] ∩ [0, h), and
// the Gaussian is separable, so its renormalised 2-D weights are the product of the renormalised
// 1-D weights of a horizontal and a vertical pass.
void filter_planes(std::vector<std::vector<double>>& planes, int width, int height) {
    const auto g = gaussian_weights();
    std::vector<double> line(static_cast<std::size_t>(std::max(width, height)));
    for (std::vector<double>& plane : planes) {
        for (int y = 0; y < height; ++y) {
            double* row = plane.data() + static_cast<std::size_t>(y) * width;
            for (int x = 0; x < width; ++x) {
                double sum = 0, weight = 0;
                const int lo = std::max(0, x - kSsimRadius),
                          hi = std::min(width - 1, x + kSsimRadius);
                for (int s = lo; s <= hi; ++s) {
                    sum += g[s - x + kSsimRadius] * row[s];
                    weight += g[s - x + kSsimRadius];
                }
                line[x] = sum / weight;
            }
            std::copy_n(line.data(), width, row);
        }
        for (int x = 0; x < width; ++x) {
            for (int y = 0; y < height; ++y) {
                double sum = 0, weight = 0;
                const int lo = std::max(0, y - kSsimRadius);
                const int hi = std::min(height - 1, y + kSsimRadius);
                for (int s = lo; s <= hi; ++s) {
                    sum += g[s - y + kSsimRadius] * plane[static_cast<std::size_t>(s) * width + x];
                    weight += g[s - y + kSsimRadius];
                }
                line[y] = sum / weight;
            }
            for (int y = 0; y < height; ++y)
                plane[static_cast<std::size_t>(y) * width + x] = line[y];
        }
    }
}

// The SSIM map averaged over channels, in double (width × height values). With `valid` (one
// flag per pixel; empty: all valid) the windows skip invalid pixels: their values count as 0
// and a sixth plane, the filtered flags, renormalises the rest — the per-pass normalisation of
// filter_planes cancels in the ratio, leaving Σ w m v / Σ w m. Invalid pixels' values are
// meaningless.
std::vector<double> ssim_values(const Image& a, const Image& b, double peak,
                                const std::vector<unsigned char>& valid = {}) {
    const std::size_t n = a.pixel_count();
    const double c1 = (kSsimK1 * peak) * (kSsimK1 * peak);
    const double c2 = (kSsimK2 * peak) * (kSsimK2 * peak);
    std::vector<double> result(n, 0.0);
    // a, b, a², b², ab for one channel, filtered into μa, μb, E[a²], E[b²], E[ab] (and the flags).
    std::vector<std::vector<double>> planes(valid.empty() ? 5 : 6, std::vector<double>(n));
    for (int c = 0; c < a.channels; ++c) {
        for (std::size_t p = 0; p < n; ++p) {
            const bool use = valid.empty() || valid[p];
            const double va = use ? a.pixels[p * a.channels + c] : 0.0;
            const double vb = use ? b.pixels[p * b.channels + c] : 0.0;
            planes[0][p] = va;
            planes[1][p] = vb;
            planes[2][p] = va * va;
            planes[3][p] = vb * vb;
            planes[4][p] = va * vb;
            if (!valid.empty()) planes[5][p] = use ? 1.0 : 0.0;
        }
        filter_planes(planes, a.width, a.height);
        for (std::size_t p = 0; p < n; ++p) {
            const double share = valid.empty() ? 1.0 : planes[5][p];
            if (!(share > 0)) continue;
            const double mu_a = planes[0][p] / share, mu_b = planes[1][p] / share;
            const double var_a = planes[2][p] / share - mu_a * mu_a;
            const double var_b = planes[3][p] / share - mu_b * mu_b;
            const double cov = planes[4][p] / share - mu_a * mu_b;
            result[p] += (2 * mu_a * mu_b + c1) * (2 * cov + c2) /
                         ((mu_a * mu_a + mu_b * mu_b + c1) * (var_a + var_b + c2));
        }
    }
    for (double& v : result) v /= a.channels;
    return result;
}

bool same_shape(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels;
}

// temporal_variation with its reasons; `name` is "sequence" or "reference sequence".
Result<double> checked_temporal_variation(const std::vector<Image>& sequence, const Image& shape,
                                          const std::vector<std::size_t>& counted,
                                          const std::string& name) {
    if (sequence.size() < 2)
        return Error{"the " + name + " has " + std::to_string(sequence.size()) +
                     " frame(s); temporal variation needs at least 2"};
    for (std::size_t i = 0; i < sequence.size(); ++i) {
        const std::string frame = "frame " + std::to_string(i) + " of the " + name;
        if (sequence[i].empty()) return Error{frame + " is empty"};
        if (!same_shape(sequence[i], shape))
            return Error{frame + " is " + size_text(sequence[i]) + " with " +
                         std::to_string(sequence[i].channels) + " channel(s), but frame 0 of the " +
                         "sequence is " + size_text(shape) + " with " +
                         std::to_string(shape.channels)};
        if (auto e = check_finite(sequence[i], frame)) return *e;
    }
    double sum = 0;
    for (std::size_t i = 1; i < sequence.size(); ++i)
        sum += mean_abs_over(sequence[i], sequence[i - 1], counted);
    return sum / static_cast<double>(sequence.size() - 1);
}

}  // namespace

NonFinitePixels find_non_finite(const Image& image) {
    NonFinitePixels found;
    for (std::size_t p = 0; p < image.pixel_count(); ++p) {
        if (pixel_is_finite(image, p)) continue;
        if (found.count++ > 0) continue;
        found.x = static_cast<int>(p % image.width);
        found.y = static_cast<int>(p / image.width);
        for (found.channel = 0; std::isfinite(image.pixels[p * image.channels + found.channel]);)
            ++found.channel;
        found.value = image.pixels[p * image.channels + found.channel];
    }
    return found;
}

std::string non_finite_text(const NonFinitePixels& n) {
    std::string text = std::to_string(n.count) + " non-finite pixel" + (n.count == 1 ? "" : "s");
    if (n.count == 0) return text;
    const char* value = std::isnan(n.value) ? "nan" : n.value > 0 ? "inf" : "-inf";
    return text + ", the first at (" + std::to_string(n.x) + ", " + std::to_string(n.y) +
           ") channel " + std::to_string(n.channel) + " = " + value;
}

Result<ImageComparison> compare_images(const Image& a, const Image& b,
                                       const MetricsOptions& options) {
    if (!(std::isfinite(options.peak) && options.peak > 0))
        return Error{"peak must be finite and > 0 (got " + std::to_string(options.peak) + ")"};
    if (auto e = check_same_shape(a, b, "A", "B")) return *e;
    Result<std::vector<std::size_t>> counted = counted_pixels(a, options.mask);
    if (!counted) return counted.error();
    ImageComparison result;
    std::vector<unsigned char> valid;  // empty: every pixel is finite
    if (auto e = handle_non_finite(a, b, options.ignore_non_finite, *counted, valid, result))
        return *e;
    result.pixels = counted->size();
    double squared = 0;
    for (std::size_t p : *counted)
        for (int c = 0; c < a.channels; ++c) {
            const std::size_t i = p * a.channels + c;
            const double d = static_cast<double>(a.pixels[i]) - static_cast<double>(b.pixels[i]);
            squared += d * d;
        }
    result.rmse = std::sqrt(squared / (static_cast<double>(counted->size()) * a.channels));
    result.psnr = result.rmse > 0 ? 20.0 * std::log10(options.peak / result.rmse)
                                  : std::numeric_limits<double>::infinity();

    const std::vector<double> map = ssim_values(a, b, options.peak, valid);
    double ssim_sum = 0;
    for (std::size_t p : *counted) ssim_sum += map[p];
    result.ssim = ssim_sum / static_cast<double>(counted->size());
    return result;
}

Image ssim_map(const Image& a, const Image& b, double peak) {
    assert(same_shape(a, b) && peak > 0);
    if (!same_shape(a, b) || a.empty()) return {};
    const std::vector<double> values = ssim_values(a, b, peak);
    Image map(a.width, a.height, 1);
    for (std::size_t p = 0; p < values.size(); ++p) map.pixels[p] = static_cast<float>(values[p]);
    return map;
}

double heat_map_position(double error, const HeatMapScale& scale) {
    double t = scale.bottom > 0
                   ? std::log(error / scale.bottom) / std::log(scale.top / scale.bottom)
                   : error / scale.top;
    if (!(t > 0)) t = 0;  // also NaN
    return std::min(t, 1.0);
}

std::array<float, 3> heat_map_colour(double t) {
    // Black, blue, red, yellow, white at t = 0, 1/4, 1/2, 3/4, 1.
    static constexpr float kStops[5][3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}};
    const double u = std::clamp(t, 0.0, 1.0) * 4;
    const int k = std::min(3, static_cast<int>(u));
    const double f = u - k;
    std::array<float, 3> colour{};
    for (int c = 0; c < 3; ++c)
        colour[c] = static_cast<float>(kStops[k][c] + f * (kStops[k + 1][c] - kStops[k][c]));
    return colour;
}

Image error_heat_map(const Image& a, const Image& b, const HeatMapScale& scale) {
    assert(same_shape(a, b));
    if (!same_shape(a, b) || a.empty()) return {};
    Image heat(a.width, a.height, 3);
    for (std::size_t p = 0; p < a.pixel_count(); ++p) {
        double diff = 0;
        for (int c = 0; c < a.channels; ++c) {
            const std::size_t i = p * a.channels + c;
            diff += std::abs(static_cast<double>(a.pixels[i]) - static_cast<double>(b.pixels[i]));
        }
        const std::array<float, 3> colour =
            heat_map_colour(heat_map_position(diff / a.channels, scale));
        std::copy(colour.begin(), colour.end(),
                  heat.pixels.begin() + static_cast<std::ptrdiff_t>(p * 3));
    }
    return heat;
}

Image error_heat_map(const Image& a, const Image& b, double scale) {
    return error_heat_map(a, b, HeatMapScale{scale, 0});
}

double mean_absolute_difference(const Image& a, const Image& b) {
    if (!same_shape(a, b)) return std::numeric_limits<double>::quiet_NaN();
    if (a.empty()) return 0;
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        sum += std::abs(static_cast<double>(a.pixels[i]) - static_cast<double>(b.pixels[i]));
    return sum / static_cast<double>(a.pixels.size());
}

double temporal_variation(const std::vector<Image>& sequence, const MetricsOptions& options) {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    if (sequence.empty() || sequence.front().empty()) return kNaN;
    Result<std::vector<std::size_t>> counted = counted_pixels(sequence.front(), options.mask);
    if (!counted) return kNaN;
    Result<double> variation =
        checked_temporal_variation(sequence, sequence.front(), *counted, "sequence");
    return variation ? *variation : kNaN;
}

Result<double> flicker(const std::vector<Image>& sequence,
                       const std::vector<Image>& reference_sequence,
                       const MetricsOptions& options) {
    if (sequence.size() < 2)
        return Error{"the sequence has " + std::to_string(sequence.size()) +
                     " frame(s); flicker needs at least 2"};
    if (reference_sequence.size() != sequence.size())
        return Error{"the sequence has " + std::to_string(sequence.size()) +
                     " frames but the reference sequence has " +
                     std::to_string(reference_sequence.size())};
    const Image& shape = sequence.front();
    if (shape.empty()) return Error{"frame 0 of the sequence is empty"};
    Result<std::vector<std::size_t>> counted = counted_pixels(shape, options.mask);
    if (!counted) return counted.error();
    Result<double> numerator = checked_temporal_variation(sequence, shape, *counted, "sequence");
    if (!numerator) return numerator.error();
    Result<double> denominator =
        checked_temporal_variation(reference_sequence, shape, *counted, "reference sequence");
    if (!denominator) return denominator.error();
    if (!(*denominator > 0))
        return Error{
            "the reference sequence is static over the counted pixels (temporal variation 0); "
            "flicker is undefined"};
    return *numerator / *denominator;
}

}  // namespace footprint
