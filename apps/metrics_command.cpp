#include "metrics_command.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "command_util.h"
#include "image/image_io.h"
#include "metrics/flip.h"
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

std::string flip_range_name(const FlipResult& f) {
    return f.hdr ? "hdr" : "ldr";
}

// `flip`: null when FLIP was not computed (non-finite pixels left out of the other metrics).
void print(const ImageComparison& c, const std::optional<FlipResult>& flip, bool json) {
    if (json) {
        nlohmann::ordered_json line;
        line["rmse"] = c.rmse;
        if (std::isfinite(c.psnr))
            line["psnr"] = c.psnr;
        else
            line["psnr"] = nullptr;
        line["ssim"] = c.ssim;
        line["flip"] = nullptr;
        line["flip_range"] = nullptr;
        line["flip_exposures"] = nullptr;
        if (flip) {
            line["flip"] = flip->mean;
            line["flip_range"] = flip_range_name(*flip);
            if (flip->hdr)
                line["flip_exposures"] = {{"start", flip->start_exposure},
                                          {"stop", flip->stop_exposure},
                                          {"count", flip->exposures}};
        }
        line["pixels"] = c.pixels;
        line["non_finite_a"] = c.non_finite_a;
        line["non_finite_b"] = c.non_finite_b;
        line["excluded"] = c.excluded;
        std::printf("%s\n", line.dump().c_str());
        return;
    }
    std::printf("rmse %.6g  psnr %.2f dB  ssim %.6f  ", c.rmse, c.psnr, c.ssim);
    if (!flip)
        std::printf("flip n/a");
    else if (!flip->hdr)
        std::printf("flip %.6f (ldr)", flip->mean);
    else
        std::printf("flip %.6f (hdr, %d exposures %.2f to %.2f)", flip->mean, flip->exposures,
                    flip->start_exposure, flip->stop_exposure);
    std::printf("  (pixels %zu", c.pixels);
    if (c.non_finite_a + c.non_finite_b > 0)
        std::printf("; non-finite pixels: A %zu, B %zu, %zu excluded", c.non_finite_a,
                    c.non_finite_b, c.excluded);
    std::printf(")\n");
}

}  // namespace

int run_metrics_command(const MetricsCommandOptions& options) {
    if (!(std::isfinite(options.peak) && options.peak > 0))
        return fail("--peak: must be finite and > 0 (got " + std::to_string(options.peak) + ")");
    if (!(std::isfinite(options.ppd) && options.ppd > 0 && options.ppd <= 1000))
        return fail("--ppd: must be finite, > 0 and <= 1000 (got " + std::to_string(options.ppd) +
                    ")");
    if (!options.flip_map.empty())
        if (const auto problem = output_file_problem(options.flip_map)) return fail(*problem);
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
    std::string what = "cannot compare A = " + quoted(options.a) + " and B = " + quoted(options.b);
    if (mask) what += " with mask " + quoted(options.mask);
    if (!comparison) return fail(what + ": " + comparison.error().message);

    std::optional<FlipResult> flip_result;
    if (comparison->non_finite_a + comparison->non_finite_b > 0) {
        const std::string why =
            "FLIP's filters spread each pixel over its neighbours, so the non-finite pixels "
            "cannot be left out of it";
        if (!options.flip_map.empty()) return fail("--flip-map: " + why);
        warn("FLIP not computed: " + why);
    } else {
        FlipOptions flip_options;
        flip_options.pixels_per_degree = options.ppd;
        flip_options.range = options.flip_range;
        flip_options.mask = metrics.mask;
        flip_options.error_map = !options.flip_map.empty();
        Result<FlipResult> computed = flip(*a, *b, flip_options);
        if (!computed) return fail(what + ": FLIP: " + computed.error().message);
        flip_result = std::move(*computed);
    }
    if (!options.flip_map.empty()) {
        ImageSaveOptions linear;
        linear.encoding = ColorEncoding::linear;  // PNG codes 255 · FLIP; EXR the values
        if (Status saved = save_image(flip_result->error_map, options.flip_map, linear); !saved)
            return fail(saved.error().message);
    }
    print(*comparison, flip_result, options.json);
    return 0;
}

}  // namespace footprint
