// apps/metrics_command.h — `footprint metrics`: how far one image is from another.
//
//   footprint metrics A B [--mask M] [--peak P] [--ignore-non-finite] [--ppd N]
//                     [--flip-range ldr|hdr|auto] [--flip-map FILE] [--json]
//
// Loads A and B with load_image (image/image_io.h): the metrics are computed in linear light as
// loaded — sRGB-encoded files (8/16-bit PNG, JPEG, TIFF) are decoded to linear first, float
// files (EXR, HDR) are compared as stored; all channels count, alpha included. The mask M is
// loaded with ColorEncoding::linear; pixels count where its channel 0 is > 0.5. --peak is PSNR's
// peak and SSIM's dynamic range L (default 1). The metrics are metrics/image_metrics.h's
// compare_images: RMSE, PSNR (dB) and SSIM (Wang et al. 2004, 11×11 Gaussian window σ = 1.5,
// cut and renormalised at the border), and metrics/flip.h's mean FLIP of the test A against the
// reference B (over the same mask): LDR-FLIP, or HDR-FLIP with exposures from B, chosen by
// --flip-range (auto: HDR-FLIP when a colour value of A or B is > 1), for an observer at --ppd
// pixels per degree (default 67.02, the FLIP paper's). --flip-map writes the per-pixel FLIP as a
// 1-channel image: float in EXR/HDR, code round(255 · FLIP) in PNG/TIFF/JPEG (written linear,
// so loading it gives FLIP back); the file is written completely or not at all, and its path is
// checked before any work is done.
//
// Non-finite pixels (NaN or ±infinity in any channel) are an error naming both files, their
// counts and each one's first bad pixel; with --ignore-non-finite the pixels where A or B has one
// are left out of every metric (as if masked out; SSIM's windows skip them) and counted. FLIP's
// filters cannot skip pixels: with such pixels it is not computed (null in JSON, "flip n/a" in the
// line, a warning on stderr; with --flip-map an error). When one file is sRGB-encoded (8/16-bit
// PNG, JPEG, TIFF) and the other linear (EXR, HDR, float TIFF) a warning on stderr says so; they
// are compared in linear light all the same.
//
// Prints one line to stdout:
//   rmse 0.0123  psnr 38.2 dB  ssim 0.9876  flip 0.1597 (ldr)  (pixels 4096)
// ("flip 0.2835 (hdr, 14 exposures -12.54 to 0.94)" for HDR-FLIP; "; non-finite pixels: A 3, B 0,
// 3 excluded" before the last ")" when there were any) or with --json exactly one line
//   {"rmse":0.0123,"psnr":38.2,"ssim":0.9876,"flip":0.1597,"flip_range":"ldr",
//    "flip_exposures":null,"pixels":4096,"non_finite_a":0,"non_finite_b":0,"excluded":0}
// where psnr is null for identical images (PSNR = +infinity), flip and flip_range null when FLIP
// was not computed, flip_exposures {"start":-12.54,"stop":0.94,"count":14} for HDR-FLIP, pixels
// the pixels measured, non_finite_a/b the pixels of each whole image with a non-finite value and
// excluded those of the mask's pixels left out for it.
//
// Returns the exit status: 0, or 1 after exactly one line "footprint: <what is wrong>" on stderr
// naming the file at fault (unreadable file; non-finite pixels without --ignore-non-finite;
// images of different size or channels; a mask of the wrong size or that selects nothing; no
// pixel left; --peak not finite and > 0; --ppd not finite, > 0 and ≤ 1000; FLIP undefined, as
// HDR-FLIP of a black reference; a --flip-map that cannot be written).
#pragma once

#include <filesystem>

#include "metrics/flip.h"

namespace footprint {

struct MetricsCommandOptions {
    std::filesystem::path a;     // the image under test
    std::filesystem::path b;     // the reference
    std::filesystem::path mask;  // empty: every pixel counts
    bool json = false;
    double peak = 1.0;
    bool ignore_non_finite = false;            // leave non-finite pixels out instead of failing
    double ppd = kFlipDefaultPixelsPerDegree;  // FLIP's observer: pixels per degree
    FlipRange flip_range = FlipRange::automatic;
    std::filesystem::path flip_map;  // empty: no error map written
};
int run_metrics_command(const MetricsCommandOptions& options);

}  // namespace footprint
