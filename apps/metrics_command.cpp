#include "metrics_command.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "command_util.h"
#include "image/image_io.h"
#include "metrics/image_metrics.h"

namespace footprint {

int run_metrics_command(const MetricsCommandOptions& options) {
    if (!(std::isfinite(options.peak) && options.peak > 0))
        return fail("--peak: must be finite and > 0 (got " + std::to_string(options.peak) + ")");
    Result<Image> a = load_image(options.a);
    if (!a) return fail(a.error().message);
    Result<Image> b = load_image(options.b);
    if (!b) return fail(b.error().message);
    std::optional<Image> mask;
    if (!options.mask.empty()) {
        ImageLoadOptions linear;
        linear.encoding = ColorEncoding::linear;
        Result<Image> loaded = load_image(options.mask, linear);
        if (!loaded) return fail(loaded.error().message);
        mask = std::move(*loaded);
    }

    MetricsOptions metrics;
    metrics.peak = options.peak;
    metrics.mask = mask ? &*mask : nullptr;
    const Result<ImageComparison> comparison = compare_images(*a, *b, metrics);
    if (!comparison) {
        std::string what =
            "cannot compare A = " + quoted(options.a) + " and B = " + quoted(options.b);
        if (mask) what += " with mask " + quoted(options.mask);
        return fail(what + ": " + comparison.error().message);
    }

    const ImageComparison& c = *comparison;
    if (options.json) {
        nlohmann::ordered_json line;
        line["rmse"] = c.rmse;
        if (std::isfinite(c.psnr))
            line["psnr"] = c.psnr;
        else
            line["psnr"] = nullptr;
        line["ssim"] = c.ssim;
        line["pixels"] = c.pixels;
        std::printf("%s\n", line.dump().c_str());
    } else {
        std::printf("rmse %.6g  psnr %.2f dB  ssim %.6f  (pixels %zu)\n", c.rmse, c.psnr, c.ssim,
                    c.pixels);
    }
    return 0;
}

}  // namespace footprint
