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

namespace {

// The one-line error for non-finite pixels in A or B, naming the files.
std::string non_finite_problem(const MetricsCommandOptions& options, const Image& a,
                               const Image& b) {
    return quoted(options.a) + " has " + non_finite_text(find_non_finite(a)) + ", " +
           quoted(options.b) + " has " + non_finite_text(find_non_finite(b)) +
           " (NaN or infinite); --ignore-non-finite leaves those pixels out of every metric";
}

void print(const ImageComparison& c, bool json) {
    if (json) {
        nlohmann::ordered_json line;
        line["rmse"] = c.rmse;
        if (std::isfinite(c.psnr))
            line["psnr"] = c.psnr;
        else
            line["psnr"] = nullptr;
        line["ssim"] = c.ssim;
        line["pixels"] = c.pixels;
        line["non_finite_a"] = c.non_finite_a;
        line["non_finite_b"] = c.non_finite_b;
        line["excluded"] = c.excluded;
        std::printf("%s\n", line.dump().c_str());
        return;
    }
    std::printf("rmse %.6g  psnr %.2f dB  ssim %.6f  (pixels %zu", c.rmse, c.psnr, c.ssim,
                c.pixels);
    if (c.non_finite_a + c.non_finite_b > 0)
        std::printf("; non-finite pixels: A %zu, B %zu, %zu excluded", c.non_finite_a,
                    c.non_finite_b, c.excluded);
    std::printf(")\n");
}

}  // namespace

int run_metrics_command(const MetricsCommandOptions& options) {
    if (!(std::isfinite(options.peak) && options.peak > 0))
        return fail("--peak: must be finite and > 0 (got " + std::to_string(options.peak) + ")");
    ImageLoadOptions keep;
    keep.non_finite = NonFinitePolicy::keep;  // counted and refused or excluded below
    Result<Image> a = load_image(options.a, keep);
    if (!a) return fail(a.error().message);
    Result<Image> b = load_image(options.b, keep);
    if (!b) return fail(b.error().message);
    std::optional<Image> mask;
    if (!options.mask.empty()) {
        ImageLoadOptions linear;
        linear.encoding = ColorEncoding::linear;
        Result<Image> loaded = load_image(options.mask, linear);
        if (!loaded) return fail(loaded.error().message);
        mask = std::move(*loaded);
    }
    if (!options.ignore_non_finite && (find_non_finite(*a).count || find_non_finite(*b).count))
        return fail(non_finite_problem(options, *a, *b));
    const bool a_srgb = is_srgb_encoded(options.a), b_srgb = is_srgb_encoded(options.b);
    if (a_srgb != b_srgb)
        warn("A " + quoted(options.a) + " is " + (a_srgb ? "sRGB-encoded" : "linear") + ", B " +
             quoted(options.b) + " is " + (b_srgb ? "sRGB-encoded" : "linear") +
             ": compared in linear light, the sRGB file decoded");

    MetricsOptions metrics;
    metrics.peak = options.peak;
    metrics.mask = mask ? &*mask : nullptr;
    metrics.ignore_non_finite = options.ignore_non_finite;
    const Result<ImageComparison> comparison = compare_images(*a, *b, metrics);
    if (!comparison) {
        std::string what =
            "cannot compare A = " + quoted(options.a) + " and B = " + quoted(options.b);
        if (mask) what += " with mask " + quoted(options.mask);
        return fail(what + ": " + comparison.error().message);
    }
    print(*comparison, options.json);
    return 0;
}

}  // namespace footprint
