// apps/metrics_command.h — `footprint metrics`: how far one image is from another.
//
//   footprint metrics A B [--mask M] [--peak P] [--json]
//
// Loads A and B with load_image (image/image_io.h): the metrics are computed in linear light as
// loaded — sRGB-encoded files (8/16-bit PNG, JPEG, TIFF) are decoded to linear first, float
// files (EXR, HDR) are compared as stored; all channels count, alpha included. The mask M is
// loaded with ColorEncoding::linear; pixels count where its channel 0 is > 0.5. --peak is PSNR's
// peak and SSIM's dynamic range L (default 1). The metrics are metrics/image_metrics.h's
// compare_images: RMSE, PSNR (dB) and SSIM (Wang et al. 2004, 11×11 Gaussian window σ = 1.5,
// cut and renormalised at the border).
//
// Prints one line to stdout:
//   rmse 0.0123  psnr 38.2 dB  ssim 0.9876  (pixels 4096)
// or with --json exactly one line
//   {"rmse":0.0123,"psnr":38.2,"ssim":0.9876,"pixels":4096}
// where psnr is null for identical images (PSNR = +infinity).
//
// Returns the exit status: 0, or 1 after exactly one line "footprint: <what is wrong>" on stderr
// naming the file at fault (unreadable file; images of different size or channels; a mask of the
// wrong size or that selects nothing; --peak not finite and > 0).
#pragma once

#include <filesystem>

namespace footprint {

struct MetricsCommandOptions {
    std::filesystem::path a;     // the image under test
    std::filesystem::path b;     // the reference
    std::filesystem::path mask;  // empty: every pixel counts
    bool json = false;
    double peak = 1.0;
};
int run_metrics_command(const MetricsCommandOptions& options);

}  // namespace footprint
