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
//          The mask does not cut windows: they see all pixels, counted or not; the mask selects
//          which values of the SSIM map are averaged. The reported SSIM is the map averaged over
//          the counted pixels, channels averaged with equal weight.
//
// Errors (core/result.h): nothing is printed or thrown. Messages say what is wrong, naming the
// images "A" and "B" and the mask: "images differ in size: A is 4x4, B is 3x4", "images differ in
// channels: A has 3, B has 1", "mask is 2x2 but the images are 4x4", "mask selects no pixel (no
// value of channel 0 is > 0.5)", "A has a non-finite value at pixel (1, 2) channel 0", "peak must
// be finite and > 0 (got 0)", "A is empty". Callers prefix the file names.
//
// All functions are thread-safe (they only read their arguments).
#pragma once

#include <cstddef>
#include <vector>

#include "core/result.h"
#include "image/image.h"

namespace footprint {

struct MetricsOptions {
    // Pixels count where channel 0 of the mask is > 0.5; null: every pixel counts. The mask must
    // have the images' width and height (any channel count) and outlive the call.
    const Image* mask = nullptr;
    // PSNR's peak value and SSIM's dynamic range L; finite and > 0.
    double peak = 1.0;
};

struct ImageComparison {
    double rmse = 0;
    double psnr = 0;  // dB; +infinity for identical images (rmse == 0)
    double ssim = 1;  // mean SSIM over the counted pixels, channels averaged; 1 for identical
    std::size_t pixels = 0;  // counted pixels
};

// RMSE, PSNR and SSIM of `a` against `b` over the counted pixels (see the top of this file).
// Fails on a size or channel mismatch, an empty image, a mask of the wrong size or that selects
// nothing, a non-finite value in a, b or the mask, or a peak that is not finite and > 0.
Result<ImageComparison> compare_images(const Image& a, const Image& b,
                                       const MetricsOptions& options = {});

// The SSIM map: a 1-channel image of a's size, each pixel the SSIM of its window (border rule at
// the top of this file) averaged over the channels. Requires a and b of the same size and
// channels and peak > 0 (checked by assert; compare_images validates). Symmetric in a and b.
Image ssim_map(const Image& a, const Image& b, double peak);

// An RGB error picture for reports: t = (mean over channels of |a − b|) / scale, clamped to
// [0, 1] (a NaN t, as for 0 / 0, is 0), mapped through the ramp black → blue → red → yellow →
// white (stops at t = 0, ¼, ½, ¾, 1; linear interpolation of linear-light values — saved as PNG
// the stops come out as the pure sRGB colours). Requires a and b of the same size and channels.
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
