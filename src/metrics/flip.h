// metrics/flip.h — FLIP, the perceptual difference between a rendered image and its reference as
// a viewer flipping between the two would see it: LDR-FLIP and HDR-FLIP, a per-pixel error in
// [0, 1] and its mean.
//
// Sources
//   * LDR-FLIP: Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström & Fairchild, "FLIP: A
//     Difference Evaluator for Alternating Images", HPG 2020 (the "FLIP paper").
//   * HDR-FLIP: Andersson, Nilsson, Shirley & Akenine-Möller, "Visualizing Errors in Rendered High
//     Dynamic Range Images", Eurographics 2021 short papers (the "HDR-FLIP paper").
//   * The constants and the order of the steps are those of the authors' reference implementation
//     (NVlabs/flip v1.6, BSD-3-Clause), whose 32-bit float results this one reproduces (means to
//     ~1e-6, pixels to ~5e-5; flip_test.cpp); the code here is written from the papers, not taken
//     from it. One deliberate difference: the derivative filters are evaluated so that they give
//     exactly 0 on a flat region, so a uniform patch's FLIP is exactly its colour error (the
//     reference's plain float sums leave ~1e-8 there, which q_f = ½ raises to ~1e-4).
//
// LDR-FLIP (FLIP paper; per pixel, test image A against reference B)
//   1. Linear RGB, clamped to [0, 1], to XYZ (sRGB primaries, D65) and to the opponent space
//      YCxCz: Y = 116 y/yn − 16, Cx = 500 (x/xn − y/yn), Cz = 200 (y/yn − z/zn) (no cube root).
//   2. Colour pipeline: each channel filtered with the contrast sensitivity function of its
//      channel, in the spatial domain a sum of Gaussians (x in degrees of visual angle,
//      x = pixels / pixels_per_degree):
//        S(x) = a1 √(π/b1) exp(−π² x² / b1) + a2 √(π/b2) exp(−π² x² / b2),
//      achromatic a1 = 1, b1 = 0.0047; red-green a1 = 1, b1 = 0.0053 (a2 = 0 for both);
//      blue-yellow a1 = 34.1, b1 = 0.04, a2 = 13.5, b2 = 0.025; evaluated with x² = dx² + dy² on a
//      square of radius ⌈3 √(max b / 2π²) · ppd⌉ pixels and normalised to sum 1. The filtered
//      YCxCz goes back to linear RGB, is clamped to [0, 1], to CIELAB (D65) with the Hunt
//      adjustment a' = 0.01 L a, b' = 0.01 L b, and the colour difference is HyAB:
//        ΔE_HyAB = |ΔL| + √(Δa'² + Δb'²),  ΔE_c = ΔE_HyAB^qc,  qc = 0.7,
//      remapped to [0, 1] with c_max = ΔE_HyAB(green, blue)^qc (pure linear green against pure
//      blue, the largest difference), pc = 0.4, pt = 0.95:
//        ΔE_c < pc c_max: ΔE_c · pt / (pc c_max);  else pt + (ΔE_c − pc c_max) / (c_max − pc c_max)
//        · (1 − pt).
//   3. Feature pipeline: the achromatic channel as (Y + 16) / 116 ∈ [0, 1] is filtered with the
//      first and second derivatives of a Gaussian, σ = ½ · 0.082° · ppd, on a square of radius
//      ⌈3σ⌉ (edges: ∂G/∂x and ∂G/∂y; points: ∂²G/∂x², ∂²G/∂y²), their positive weights normalised
//      to sum 1 and their negative ones to sum −1 (the Gaussian itself to 1). With
//      edge = |(∂G/∂x, ∂G/∂y) ∗ Y| and point = |(∂²G/∂x², ∂²G/∂y²) ∗ Y| (Euclidean norms):
//        ΔE_f = (max(|edge_A − edge_B|, |point_A − point_B|) / √2)^qf,  qf = 0.5.
//   4. FLIP = ΔE_c^(1 − ΔE_f), in [0, 1].
//   Every filter is separable (the blue-yellow one as a sum of two separable terms) and runs as
//   a horizontal and a vertical pass; at the border the image is extended by its edge pixels.
//
// Linear input. The FLIP paper's LDR pipeline starts from sRGB-encoded pixels and decodes them to
// linear RGB first; footprint's images are linear light already (image_io.h decodes sRGB files
// on load), so LDR-FLIP starts from the linear values, clamped to [0, 1].
//
// HDR-FLIP (HDR-FLIP paper): both images are exposed at N exposures e between the start and stop
// exposure, c' = 2^e c, each tone mapped with the ACES filmic curve as fitted by Narkowicz,
//   T(c) = y (2.51 y + 0.03) / (y (2.43 y + 0.59) + 0.14),  y = 0.6 c (0.6 cancels the fit's
//   built-in exposure),
// per channel and clamped to [0, 1], then compared with LDR-FLIP; a pixel's HDR-FLIP is the
// largest of its N LDR-FLIP values. Unless given, the exposures come from the reference B's
// luminance Y = 0.2126 R + 0.7152 G + 0.0722 B: with x_max the input that T maps to 0.85,
//   start = log2(x_max / max Y),  stop = log2(x_max / median Y),  N = max(2, ⌈stop − start⌉),
// exposures start + i (stop − start) / (N − 1), i = 0 … N − 1. The median is the element at index
// ⌊n/2⌋ of the n sorted luminances. Where it is ≤ 0 (more than half of B black) the median of the
// positive luminances is used instead (the reference implementation's stop would be infinite); a B
// without any positive luminance has no automatic exposures (an error: give them).
//
// Conventions
//   * A is the test image, B the reference (the argument order of flip()). Images are linear
//     light as loaded (image_io.h). Channels: 3 or 4 are R, G, B (and alpha, ignored); 1 or 2 are
//     grey (and alpha, ignored), compared as R = G = B. Both images must have the same width,
//     height and channel count.
//   * FlipRange::automatic picks HDR-FLIP when a colour value of A or B is > 1, else LDR-FLIP.
//   * A mask (FlipOptions::mask) selects the pixels that are averaged, those whose channel 0 is
//     > 0.5, as in image_metrics.h; the filters still see every pixel, and the automatic
//     exposures are taken from the whole of B. The error map covers every pixel.
//   * The mean is the plain mean of the per-pixel FLIP over the counted pixels (summed in double):
//     the single number the authors recommend reporting (their tools print it as "Mean").
//   * Arithmetic is 32-bit float per pixel, as in the reference implementation; the map is the
//     same for any thread count (each pixel is computed by one fixed sequence of operations).
//
// Errors (core/result.h): nothing is printed or thrown. The messages follow image_metrics.h:
// "images differ in size: A is 4x4, B is 3x4", "images differ in channels: A has 3, B has 1",
// "A is empty", "mask is 2x2 but the images are 4x4", "mask selects no pixel (no value of channel
// 0 is > 0.5)", "A has 3 non-finite pixels, the first at (1, 2) channel 0 = nan; B has 0
// non-finite pixels",
// "pixels per degree must be finite, > 0 and <= 1000 (got 0)", "start exposure 2 is above stop
// exposure 1", "B has no pixel of positive luminance: HDR-FLIP's automatic exposures are
// undefined; give the start and stop exposures". Callers prefix the file names.
//
// Thread-safe (only reads its arguments); rows are processed in parallel with oneTBB.
#pragma once

#include <cstddef>
#include <optional>

#include <footprint/core/result.h>
#include <footprint/image/image.h>

namespace footprint {

// Pixels per degree of visual angle for a viewer `distance` metres from a monitor `width` metres
// wide showing `resolution_x` pixels across (FLIP paper):
//   ppd = distance · (resolution_x / width) · π / 180.
double flip_pixels_per_degree(double distance, double resolution_x, double width);

// The FLIP paper's default observer: 0.7 m from a 0.7 m wide 4K monitor (3840 pixels across),
// 3840 π / 180 = 67.0206 pixels per degree.
inline constexpr double kFlipDefaultPixelsPerDegree = 3840.0 * 3.14159265358979323846 / 180.0;

enum class FlipRange {
    ldr,        // LDR-FLIP on the linear values clamped to [0, 1]
    hdr,        // HDR-FLIP: several exposures, tone mapped, the largest LDR-FLIP per pixel
    automatic,  // HDR-FLIP when a colour value of A or B is > 1, else LDR-FLIP
};

struct FlipOptions {
    // The observer (see flip_pixels_per_degree); finite, > 0 and ≤ 1000.
    double pixels_per_degree = kFlipDefaultPixelsPerDegree;
    FlipRange range = FlipRange::automatic;
    // HDR-FLIP's exposure range in stops (finite, start ≤ stop); each one unset is taken from the
    // reference as at the top of this file.
    std::optional<double> start_exposure;
    std::optional<double> stop_exposure;
    // HDR-FLIP's number of exposures; 0: max(2, ⌈stop − start⌉). With 1 only the start exposure.
    int exposures = 0;
    // Pixels count where channel 0 of the mask is > 0.5; null: every pixel counts. The mask must
    // have the images' width and height (any channel count) and outlive the call.
    const Image* mask = nullptr;
    // Whether FlipResult::error_map is filled.
    bool error_map = false;
};

struct FlipResult {
    double mean = 0;         // mean FLIP over the counted pixels, in [0, 1]; 0 for identical images
    std::size_t pixels = 0;  // counted pixels
    bool hdr = false;        // whether HDR-FLIP was used
    // HDR-FLIP only: the exposures used (given or automatic) and their number.
    double start_exposure = 0;
    double stop_exposure = 0;
    int exposures = 0;
    // With FlipOptions::error_map: a 1-channel image of A's size, each pixel its FLIP in [0, 1]
    // (HDR: the largest over the exposures); otherwise empty.
    Image error_map;
};

// FLIP of the test image `a` against the reference `b` (see the top of this file). Fails on a size
// or channel mismatch, an empty image, a non-finite value in a, b or the mask, a mask of the wrong
// size or that selects nothing, pixels per degree out of range, non-finite exposures or start >
// stop, a negative exposure count, or automatic exposures with a reference without light.
Result<FlipResult> flip(const Image& a, const Image& b, const FlipOptions& options = {});

}  // namespace footprint
