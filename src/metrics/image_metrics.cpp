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

// The SSIM map averaged over channels, in double (width × height values).
std::vector<double> ssim_values(const Image& a, const Image& b, double peak) {
    const std::size_t n = a.pixel_count();
    const double c1 = (kSsimK1 * peak) * (kSsimK1 * peak);
    const double c2 = (kSsimK2 * peak) * (kSsimK2 * peak);
    std::vector<double> result(n, 0.0);
    // a, b, a², b², ab for one channel, filtered into μa, μb, E[a²], E[b²], E[ab].
    std::vector<std::vector<double>> planes(5, std::vector<double>(n));
    for (int c = 0; c < a.channels; ++c) {
        for (std::size_t p = 0; p < n; ++p) {
            const double va = a.pixels[p * a.channels + c];
            const double vb = b.pixels[p * b.channels + c];
            planes[0][p] = va;
            planes[1][p] = vb;
            planes[2][p] = va * va;
            planes[3][p] = vb * vb;
            planes[4][p] = va * vb;
        }
        filter_planes(planes, a.width, a.height);
        for (std::size_t p = 0; p < n; ++p) {
            const double mu_a = planes[0][p], mu_b = planes[1][p];
            const double var_a = planes[2][p] - mu_a * mu_a;
            const double var_b = planes[3][p] - mu_b * mu_b;
            const double cov = planes[4][p] - mu_a * mu_b;
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

Result<ImageComparison> compare_images(const Image& a, const Image& b,
                                       const MetricsOptions& options) {
    if (!(std::isfinite(options.peak) && options.peak > 0))
        return Error{"peak must be finite and > 0 (got " + std::to_string(options.peak) + ")"};
    if (auto e = check_same_shape(a, b, "A", "B")) return *e;
    Result<std::vector<std::size_t>> counted = counted_pixels(a, options.mask);
    if (!counted) return counted.error();
    if (auto e = check_finite(a, "A")) return *e;
    if (auto e = check_finite(b, "B")) return *e;

    ImageComparison result;
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

    const std::vector<double> map = ssim_values(a, b, options.peak);
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

Image error_heat_map(const Image& a, const Image& b, double scale) {
    assert(same_shape(a, b));
    if (!same_shape(a, b) || a.empty()) return {};
    // Black, blue, red, yellow, white at t = 0, 1/4, 1/2, 3/4, 1.
    static constexpr float kStops[5][3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}};
    Image heat(a.width, a.height, 3);
    for (std::size_t p = 0; p < a.pixel_count(); ++p) {
        double diff = 0;
        for (int c = 0; c < a.channels; ++c) {
            const std::size_t i = p * a.channels + c;
            diff += std::abs(static_cast<double>(a.pixels[i]) - static_cast<double>(b.pixels[i]));
        }
        double t = diff / a.channels / scale;
        if (!(t > 0)) t = 0;  // also NaN
        if (t > 1) t = 1;
        const double u = t * 4;
        const int k = std::min(3, static_cast<int>(u));
        const double f = u - k;
        for (int c = 0; c < 3; ++c)
            heat.pixels[p * 3 + c] =
                static_cast<float>(kStops[k][c] + f * (kStops[k + 1][c] - kStops[k][c]));
    }
    return heat;
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
