// metrics/image_metrics.h — comparing two images (RMSE, PSNR, SSIM), per-pixel maps for reports,
// and the temporal stability (flicker) of an image sequence.
//
// Conventions
//   * Images are compared as given: linear light as loaded (image_io.h), all channels including
//     alpha, no clamping, no colour conversion. Both images must have the same width, height and
//     channel count.
//   * A mask (MetricsOptions::mask) selects the pixels that count: those whose channel 0 is
//     > 0.5 (any channel count; only channel 0 is read). Every other pixel has weight 0. The mask
//     must have the images' width and height and select at least one pixel. Without a mask every
//     pixel counts.
//   * `peak` is PSNR's peak value and SSIM's dynamic range L (1 for images in [0, 1]).
//   * Non-finite values (NaN, ±infinity) in A or B are an error. With
//     MetricsOptions::ignore_non_finite the pixels where A or B has one (in any channel) are left
//     out of every metric like masked-out pixels, and SSIM's windows skip them as well (their
//     weights are dropped and the rest renormalised, as at the border).
//
// The metrics (n = counted pixels, C = channels; sums over counted pixels p and channels c)
//   RMSE = sqrt( Σ (a − b)² / (n C) )
//   PSNR = 20 log10(peak / RMSE) dB; +infinity when RMSE = 0 (identical images). JSON cannot hold
//          infinity: `footprint metrics --json` prints null for it.
//   SSIM = Wang, Bovik, Sheikh & Simoncelli, "Image quality assessment: from error visibility to
//          structural similarity", IEEE TIP 2004. Per channel, on the values as given:
//            SSIM(x, y) = (2 μa μb + C1)(2 σab + C2) / ((μa² + μb² + C1)(σa² + σb² + C2)),
//          C1 = (0.01 L)², C2 = (0.03 L)², with μ, σ², σab the weighted means, variances and
//          covariance over an 11×11 circular-symmetric Gaussian window (σ = 1.5 pixels) centred
//          on (x, y): μa = Σ w a, σa² = Σ w a² − μa², σab = Σ w a b − μa μb.
//          Border rule: near the border the window is cut to the pixels inside the image and its
//          weights are renormalised to sum to 1 (so images smaller than 11×11 work and every
//          pixel has a value). Where the full window fits this is exactly the paper's window.
//          The mask does not cut windows: they see all pixels, counted or not (except ignored
//          non-finite ones); the mask selects which values of the SSIM map are averaged. The
//          reported SSIM is the map averaged over the counted pixels, channels averaged with
//          equal weight.
//
// Errors (core/result.h): nothing is printed or thrown. Messages say what is wrong, naming the
// images "A" and "B" and the mask: "images differ in size: A is 4x4, B is 3x4", "images differ in
// channels: A has 3, B has 1", "mask is 2x2 but the images are 4x4", "mask selects no pixel (no
// value of channel 0 is > 0.5)", "A has 3 non-finite pixels, the first at (1, 2) channel 0 = nan;
// B has 0", "peak must be finite and > 0 (got 0)", "A is empty". Callers prefix the file names.
//
// All functions are thread-safe (they only read their arguments).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <footprint/core/result.h>
#include <footprint/image/image.h>

namespace footprint {

struct MetricsOptions {
    // Pixels count where channel 0 of the mask is > 0.5; null: every pixel counts. The mask must
    // have the images' width and height (any channel count) and outlive the call.
    const Image* mask = nullptr;
    // PSNR's peak value and SSIM's dynamic range L; finite and > 0.
    double peak = 1.0;
    // false: a non-finite value in A or B is an error. true: the pixels where A or B has one are
    // left out of every metric (ImageComparison::excluded counts them).
    bool ignore_non_finite = false;
};

struct ImageComparison {
    double rmse = 0;
    double psnr = 0;  // dB; +infinity for identical images (rmse == 0)
    double ssim = 1;  // mean SSIM over the counted pixels, channels averaged; 1 for identical
    std::size_t pixels = 0;        // counted pixels (without the excluded ones)
    std::size_t non_finite_a = 0;  // pixels of A (whole image) with a non-finite channel value
    std::size_t non_finite_b = 0;
    std::size_t excluded = 0;  // pixels the mask selects that were left out as non-finite
};

// The pixels of an image with a non-finite channel value, and the first of them (row-major).
struct NonFinitePixels {
    std::size_t count = 0;
    int x = -1, y = -1, channel = -1;  // the first one; −1 when count is 0
    float value = 0;                   // its value (NaN or ±infinity)
};
NonFinitePixels find_non_finite(const Image& image);

// "3 non-finite pixels, the first at (1, 2) channel 0 = nan"; "0 non-finite pixels".
std::string non_finite_text(const NonFinitePixels& non_finite);

// RMSE, PSNR and SSIM of `a` against `b` over the counted pixels (see the top of this file).
// Fails on a size or channel mismatch, an empty image, a mask of the wrong size or that selects
// nothing, a non-finite value in the mask, in a or b (unless ignored; then also when no counted
// pixel is left), or a peak that is not finite and > 0.
Result<ImageComparison> compare_images(const Image& a, const Image& b,
                                       const MetricsOptions& options = {});

// The SSIM map: a 1-channel image of a's size, each pixel the SSIM of its window (border rule at
// the top of this file) averaged over the channels. Requires a and b of the same size and
// channels and peak > 0 (checked by assert; compare_images validates). Symmetric in a and b.
Image ssim_map(const Image& a, const Image& b, double peak);

// How an error picture maps a pixel's error e (the mean over channels of |a − b|) to a position
// t in [0, 1] on its colour ramp: linear from 0 to `top` (bottom = 0): t = e / top; or
// logarithmic from bottom > 0 to top: t = log(e / bottom) / log(top / bottom). Clamped to
// [0, 1]; a NaN t (0 / 0, a non-finite pixel) is 0.
struct HeatMapScale {
    double top = 1;
    double bottom = 0;
};
double heat_map_position(double error, const HeatMapScale& scale);

// The ramp black → blue → red → yellow → white (stops at t = 0, ¼, ½, ¾, 1), linear
// interpolation of linear-light values: saved as PNG the stops come out as the pure sRGB colours.
std::array<float, 3> heat_map_colour(double t);

// An RGB error picture for reports: each pixel heat_map_colour(heat_map_position(e, scale)).
// Requires a and b of the same size and channels. The `double` form is the linear scale with top
// `scale`.
Image error_heat_map(const Image& a, const Image& b, const HeatMapScale& scale);
Image error_heat_map(const Image& a, const Image& b, double scale);

// Mean of |a − b| over all pixels and channels (no mask); 0 for empty images. Requires a and b
// of the same size and channels (NaN otherwise).
double mean_absolute_difference(const Image& a, const Image& b);

// Temporal variation of a sequence of frames f_0 … f_{N−1}: the mean over i = 1 … N−1 of the
// mean of |f_i − f_{i−1}| over the counted pixels and all channels. 0 for a static sequence.
// Returns NaN when the input is invalid (fewer than 2 frames, frames of different sizes or
// channels, a mask that is invalid for them, non-finite values); flicker() says why.
double temporal_variation(const std::vector<Image>& sequence, const MetricsOptions& options = {});

// Temporal stability of a rendered sequence against a reference sequence of the same scene:
//   flicker = temporal_variation(sequence) / temporal_variation(reference_sequence)
// (same mask for both; peak is not used). 1: the sequence changes from frame to frame as much
// as the reference does; above 1: it flickers (e.g. aliasing that crawls); 0: it is static.
// Fails if either sequence has fewer than 2 frames, their lengths differ, any frame differs in
// size or channels from sequence[0], the mask is invalid, a value is non-finite, or the
// reference's temporal variation is 0 (flicker is undefined).
Result<double> flicker(const std::vector<Image>& sequence,
                       const std::vector<Image>& reference_sequence,
                       const MetricsOptions& options = {});

}  // namespace footprint
