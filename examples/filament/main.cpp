// examples/filament/main.cpp — footprint-filament: a scene in Filament 1.9 with footprint's
// material or Filament's own best practice, against the same engine's supersampled truth.
//
//   footprint-filament SCENE --material footprint|filament --size WxH [--environment ENV]
//                      [--supersample N] -o OUT.exr|.png
//   footprint-filament SCENE --compare [--supersample N] [--size WxH] [-o DIR]
//   footprint-filament sky --check-orientation [--size WxH] [-o DIR]
//
// SCENE is a built-in scene (plate, floor, mirror, sky: scenes.h) or a glTF file (.gltf, .glb:
// gltf_scene.h; lit by the Venice sky unless --environment names another). --supersample N renders
// the truth whatever --material says: N× the size with truth.mat (level-0 maps, authored
// roughness), then the pixel filter below. --compare renders every material and the truth and
// prints one table row per scene: interior RMSE and mean FLIP against the truth (footprint's
// metrics module, as `footprint metrics` and `footprint eval` compute them) and the frame time.
//
// The pixel filter is footprint's (docs/rendering.md#pixel-filter-and-sampling): a Gaussian of
// σ = ½ pixel cut at ±1.5 pixels. It is the measure every footprint filter aims at (K/4,
// docs/method.md), so the truth here is the one footprint's own evaluation uses.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "filament_renderer.h"
#include "gltf_scene.h"
#include "image/image_io.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "scenes.h"

namespace fs = std::filesystem;
using namespace footprint;
using namespace footprint::filament_example;

namespace {

constexpr double kPixelFilterSigma = 0.5;   // pixels: footprint's ground-truth pixel filter
constexpr double kPixelFilterRadius = 1.5;  // pixels: the Gaussian cut at 3σ

// The N×-resolution image filtered down to its 1/N size: each output pixel the normalised
// Gaussian-weighted mean of the subpixels whose centres lie within ±1.5 output pixels of its
// centre. Subpixel x·N + k of output pixel x has its centre (k + ½)/N − ½ output pixels from the
// pixel's centre, so k runs over [−reach, N − 1 + reach]: symmetric about the pixel's centre.
Image downsample(const Image& fine, int factor) {
    const int width = fine.width / factor, height = fine.height / factor;
    Image out(width, height, fine.channels, 0.0f);
    const int reach = static_cast<int>(std::ceil(kPixelFilterRadius * factor));
    const int first = -reach, last = factor - 1 + reach;
    std::vector<double> weights(last - first + 1);
    for (int k = first; k <= last; ++k) {
        const double d = (k + 0.5) / factor - 0.5;
        weights[k - first] = std::abs(d) <= kPixelFilterRadius
                                 ? std::exp(-d * d / (2 * kPixelFilterSigma * kPixelFilterSigma))
                                 : 0.0;
    }
    std::vector<double> sum(fine.channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            std::fill(sum.begin(), sum.end(), 0.0);
            double total = 0;
            for (int j = first; j <= last; ++j) {
                const int fy = y * factor + j;
                if (fy < 0 || fy >= fine.height || weights[j - first] == 0) continue;
                for (int i = first; i <= last; ++i) {
                    const int fx = x * factor + i;
                    if (fx < 0 || fx >= fine.width || weights[i - first] == 0) continue;
                    const double w = weights[j - first] * weights[i - first];
                    const float* p = fine.at(fx, fy);
                    for (int c = 0; c < fine.channels; ++c) sum[c] += w * p[c];
                    total += w;
                }
            }
            for (int c = 0; c < fine.channels; ++c)
                out.at(x, y, c) = static_cast<float>(sum[c] / total);
        }
    }
    return out;
}

// The interior: pixels whose whole pixel filter (±1.5 pixels) sees one object and no background,
// from the object-id pass at the truth's N× resolution — as footprint eval's interior mask, since
// no texture filter can antialias a silhouette.
Image interior_mask(const Image& ids, int factor) {
    const int width = ids.width / factor, height = ids.height / factor;
    Image mask(width, height, 1, 0.0f);
    // The subpixels under the pixel filter, as downsample() reads them.
    const int reach = static_cast<int>(std::ceil(kPixelFilterRadius * factor));
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float id = ids.at(x * factor + factor / 2, y * factor + factor / 2, 0);
            bool single = id > 0.5f;
            for (int j = -reach; j < factor + reach && single; ++j) {
                for (int i = -reach; i < factor + reach && single; ++i) {
                    const int fx = std::clamp(x * factor + i, 0, ids.width - 1);
                    const int fy = std::clamp(y * factor + j, 0, ids.height - 1);
                    single = std::abs(ids.at(fx, fy, 0) - id) < 0.25f;
                }
            }
            mask.at(x, y, 0) = single ? 1.0f : 0.0f;
        }
    }
    return mask;
}

bool parse_size(const std::string& text, int& width, int& height) {
    char x = 0;
    char rest = 0;
    return std::sscanf(text.c_str(), "%d%c%d%c", &width, &x, &height, &rest) == 3 &&
           (x == 'x' || x == 'X') && width > 0 && height > 0 && width <= 8192 && height <= 8192;
}

bool is_gltf(const fs::path& path) {
    const std::string ext = path.extension().string();
    return ext == ".gltf" || ext == ".glb";
}

int fail(const std::string& message) {
    std::fprintf(stderr, "footprint-filament: %s\n", message.c_str());
    return 1;
}

struct Measured {
    double rmse = 0, flip = 0, frame_ms = 0;
};

// Interior RMSE and mean FLIP of `image` against `truth`; HDR-FLIP where the truth has a value
// above 1 (for every method of the scene alike, as footprint eval does).
Result<Measured> measure(const Image& image, const Image& truth, const Image& mask) {
    MetricsOptions metrics;
    metrics.mask = &mask;
    Result<ImageComparison> compared = compare_images(image, truth, metrics);
    if (!compared) return compared.error();
    FlipOptions flip_options;
    flip_options.mask = &mask;
    const bool hdr =
        std::any_of(truth.pixels.begin(), truth.pixels.end(), [](float v) { return v > 1; });
    flip_options.range = hdr ? FlipRange::hdr : FlipRange::ldr;
    Result<FlipResult> flipped = flip(image, truth, flip_options);
    if (!flipped) return flipped.error();
    return Measured{compared->rmse, flipped->mean, 0};
}

// The orientation check: the sky scene with every material and the truth against the colours its
// directions must have (expected_direction_colours()), the mean absolute error over the sky and
// over the mirror separately. A lat-long read mirrored, rotated or upside down in any step —
// footprint's addressing, the cube cross for cmgen, Filament's cube and skybox lookups, the image
// read back — moves a colour by up to 1; a correct one leaves cmgen's RGB_11_11_10 rounding and
// the prefiltered level's blur.
constexpr double kOrientationTolerance = 0.03;

struct RegionError {
    double sky = 0, mirror = 0;
};

RegionError orientation_error(const Image& image, const Image& expected) {
    double sum[3] = {0, 0, 0};
    long count[3] = {0, 0, 0};
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const int region = static_cast<int>(expected.at(x, y, 3) + 0.5f);
            for (int c = 0; c < 3; ++c)
                sum[region] += std::abs(image.at(x, y, c) - expected.at(x, y, c)) / 3;
            ++count[region];
        }
    }
    return {count[1] ? sum[1] / count[1] : 1.0, count[2] ? sum[2] / count[2] : 1.0};
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "footprint-filament: footprint's filtering inside Filament, against Filament's best "
        "practice and "
        "the engine's own supersampled truth"};
    std::string scene_arg, environment, material = "footprint", size = "640x360", output,
                                        materials_dir, cache_dir, assets_dir;
    int supersample = 0, frames = 5;
    bool compare = false, check_orientation = false;
    app.add_option("scene", scene_arg,
                   "a built-in scene (plate, floor, mirror) or a .gltf/.glb file")
        ->required();
    app.add_option(
        "--environment", environment,
        "equirectangular HDR or EXR in footprint's orientation (default: the scene's own)");
    app.add_option("--material", material, "footprint or filament")
        ->check(CLI::IsMember({"footprint", "filament"}));
    app.add_option("--size", size, "output size WxH (default 640x360)");
    app.add_option("--supersample", supersample,
                   "render the truth: N× the size with level-0 maps, then footprint's pixel filter "
                   "(whatever --material says; with --compare, default 8)")
        ->check(CLI::Range(1, 16));
    app.add_option("-o,--output", output,
                   "output image (.exr linear, .png sRGB); with --compare a folder");
    app.add_flag(
        "--compare", compare,
        "render every material and the truth; print interior RMSE, mean FLIP and frame time");
    app.add_flag("--check-orientation", check_orientation,
                 "with the scene sky: compare every material and the truth with the colours the "
                 "directions must have; exit 1 beyond the tolerance");
    app.add_option("--frames", frames,
                   "frames per render: the first warms up, the median of the rest is timed")
        ->check(CLI::Range(1, 1000));
    app.add_option("--materials", materials_dir, "folder of the compiled .filamat files")
        ->default_val(FOOTPRINT_FILAMENT_MATERIALS_DIR);
    app.add_option("--cache", cache_dir, "folder for cmgen's and roughness-prefilter's output")
        ->default_val(FOOTPRINT_FILAMENT_CACHE_DIR);
    app.add_option("--assets", assets_dir, "the repository's assets/ folder")
        ->default_val(FOOTPRINT_ASSETS_DIR);
    CLI11_PARSE(app, argc, argv);

    int width = 0, height = 0;
    if (!parse_size(size, width, height))
        return fail("--size must be WxH with 1 to 8192 pixels each (got '" + size + "')");
    if (check_orientation && scene_arg != "sky")
        return fail("--check-orientation needs the scene sky (got '" + scene_arg + "')");
    if (!compare && !check_orientation && output.empty())
        return fail("-o OUT.exr|.png is required");
    if (!compare && !check_orientation) {
        const std::string ext = fs::path(output).extension().string();
        if (ext != ".exr" && ext != ".png")
            return fail("the output '" + output + "' must end in .exr or .png");
    }
    if (compare && supersample == 0) supersample = 8;
    if (supersample > 0 && (static_cast<long>(width) * supersample > 16384 ||
                            static_cast<long>(height) * supersample > 16384))
        return fail("--size times --supersample exceeds 16384 pixels, OpenGL's usual limit");

    // Inputs first, so that a missing file is named before the engine starts.
    Result<SceneSetup> scene = Error{""};
    if (is_gltf(scene_arg)) {
        std::error_code ec;
        if (!fs::is_regular_file(scene_arg, ec))
            return fail("cannot read the scene '" + scene_arg + "'");
        Result<GltfScene> gltf = load_gltf_scene(scene_arg, assets_dir);
        if (!gltf) return fail(gltf.error().message);
        if (!gltf->note.empty())
            std::fprintf(stderr, "footprint-filament: note: '%s': %s\n", scene_arg.c_str(),
                         gltf->note.c_str());
        scene = std::move(gltf->scene);
    } else {
        scene = make_builtin_scene(scene_arg, assets_dir);
    }
    if (!scene) return fail(scene.error().message);
    MapSource environment_source;
    if (!environment.empty()) {
        std::error_code ec;
        if (!fs::is_regular_file(environment, ec))
            return fail("cannot read the environment '" + environment + "'");
        environment_source.file = environment;
        environment_source.label = environment;
    }

    RendererOptions options;
    options.materials_dir = materials_dir;
    options.cache_dir = cache_dir;
    Result<std::unique_ptr<FilamentRenderer>> made = FilamentRenderer::create(options);
    if (!made) return fail(made.error().message);
    FilamentRenderer& renderer = **made;
    if (Status s = renderer.load(*scene, environment_source); !s) return fail(s.error().message);

    // The truth: N× the size, level-0 maps, the pixel filter.
    auto render_truth = [&](int n) -> Result<RenderedFrame> {
        Result<RenderedFrame> fine = renderer.render(MaterialKind::truth, width * n, height * n, 1);
        if (!fine) return fine.error();
        fine->image = downsample(fine->image, n);
        return fine;
    };

    if (check_orientation) {
        const Image expected = expected_direction_colours(*scene, width, height);
        bool ok = true;
        std::printf("%-10s %12s %12s   (mean |error|, tolerance %.2f)\n", "material", "sky",
                    "mirror", kOrientationTolerance);
        for (MaterialKind kind :
             {MaterialKind::filament, MaterialKind::footprint, MaterialKind::truth}) {
            if (!renderer.has_material(kind)) continue;
            Result<RenderedFrame> frame = kind == MaterialKind::truth
                                              ? render_truth(std::max(supersample, 2))
                                              : renderer.render(kind, width, height, 1);
            if (!frame) return fail(frame.error().message);
            const RegionError e = orientation_error(frame->image, expected);
            const bool pass = e.sky < kOrientationTolerance && e.mirror < kOrientationTolerance;
            ok = ok && pass;
            std::printf("%-10s %12.5f %12.5f   %s\n", material_name(kind), e.sky, e.mirror,
                        pass ? "ok" : "WRONG");
            if (!output.empty()) {
                std::error_code ec;
                fs::create_directories(output, ec);
                const fs::path file =
                    fs::path(output) / (std::string("sky_") + material_name(kind) + ".png");
                if (Status s = save_image(frame->image, file); !s) return fail(s.error().message);
            }
        }
        if (!output.empty()) {
            Image rgb(width, height, 3);
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x)
                    for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = expected.at(x, y, c);
            if (Status s = save_image(rgb, fs::path(output) / "sky_expected.png"); !s)
                return fail(s.error().message);
        }
        if (!ok) return fail("the environment's orientation is wrong (see the table)");
        return 0;
    }

    if (!compare) {
        MaterialKind kind =
            material == "filament" ? MaterialKind::filament : MaterialKind::footprint;
        Result<RenderedFrame> frame = supersample > 0
                                          ? render_truth(supersample)
                                          : renderer.render(kind, width, height, frames);
        if (!frame) return fail(frame.error().message);
        if (Status s = save_image(frame->image, output); !s) return fail(s.error().message);
        std::printf("%s %s %dx%d: first frame %.1f ms, frame %.2f ms -> %s\n", scene->name.c_str(),
                    supersample > 0 ? "truth" : material.c_str(), width, height, frame->first_ms,
                    frame->frame_ms, output.c_str());
        return 0;
    }

    // --compare: the truth, the id pass, then each material.
    Result<RenderedFrame> truth = render_truth(supersample);
    if (!truth) return fail(truth.error().message);
    Result<Image> ids = renderer.render_object_ids(width * supersample, height * supersample);
    if (!ids) return fail(ids.error().message);
    const Image mask = interior_mask(*ids, supersample);
    double interior = 0;
    for (float v : mask.pixels) interior += v;
    // A comment line of the table: how much of the image the figures measure (0: nothing seen).
    std::printf("# %s: interior %.1f %% of the pixels\n", scene->name.c_str(),
                100.0 * interior / static_cast<double>(mask.pixels.size()));
    std::error_code ec;
    if (!output.empty()) {
        fs::create_directories(output, ec);
        if (Status s = save_image(truth->image, fs::path(output) / (scene->name + "_truth.exr"));
            !s)
            return fail(s.error().message);
        if (Status s = save_image(mask, fs::path(output) / (scene->name + "_interior.png")); !s)
            return fail(s.error().message);
    }
    // The contact sheet: footprint's material, Filament's, the truth, side by side.
    std::vector<const Image*> sheet;
    std::vector<Image> rendered;
    rendered.reserve(2);
    for (MaterialKind kind : {MaterialKind::footprint, MaterialKind::filament}) {
        if (!renderer.has_material(kind)) {
            std::printf("%-12s %-10s %10s %10s %10s   (material not built)\n", scene->name.c_str(),
                        material_name(kind), "-", "-", "-");
            continue;
        }
        Result<RenderedFrame> frame = renderer.render(kind, width, height, frames);
        if (!frame) return fail(frame.error().message);
        Result<Measured> m = measure(frame->image, truth->image, mask);
        if (!m)
            return fail(std::string(material_name(kind)) +
                        " against the truth: " + m.error().message);
        std::printf("%-12s %-10s %10.5f %10.5f %10.2f\n", scene->name.c_str(), material_name(kind),
                    m->rmse, m->flip, frame->frame_ms);
        if (!output.empty()) {
            const fs::path file =
                fs::path(output) / (scene->name + "_" + material_name(kind) + ".exr");
            if (Status s = save_image(frame->image, file); !s) return fail(s.error().message);
        }
        rendered.push_back(std::move(frame->image));
        sheet.push_back(&rendered.back());
    }
    std::printf("%-12s %-10s %10s %10s %10.2f   (%dx supersampled, one frame)\n",
                scene->name.c_str(), "truth", "0", "0", truth->first_ms, supersample);
    if (!output.empty()) {
        sheet.push_back(&truth->image);
        constexpr int kGap = 4;  // white pixels between the images
        const int count = static_cast<int>(sheet.size());
        Image strip(count * width + (count - 1) * kGap, height, 3, 1.0f);
        for (int i = 0; i < count; ++i)
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x)
                    for (int c = 0; c < 3; ++c)
                        strip.at(i * (width + kGap) + x, y, c) = sheet[i]->at(x, y, c);
        if (Status s = save_image(strip, fs::path(output) / (scene->name + "_sheet.png")); !s)
            return fail(s.error().message);
    }
    return 0;
}
