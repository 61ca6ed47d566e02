#include "texture_demo.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <system_error>
#include <vector>

#include "builtin_texture.h"
#include "cli_options.h"
#include "command_util.h"
#include "image/image_io.h"
#include "plane_view.h"
#include "progress.h"
#include "texture/mip_pyramid.h"
#include "texture/texture_lookup.h"

namespace footprint {

namespace {

// A value as printf writes it ("nan", "inf" as they are), for messages.
std::string text(double v, const char* format = "%.6g") {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, v);
    return buffer;
}
// ... and for JSON, where a value that is not finite is null.
std::string number(double v, const char* format = "%.6g") {
    return std::isfinite(v) ? text(v, format) : "null";
}

int demo(const TextureDemoOptions& options) {
    if (auto problem = range_problem("--size", options.width, kDemoWidths)) return fail(*problem);
    if (options.samples_per_axis < 1 || options.samples_per_axis > 64)
        return fail("--samples " + std::to_string(options.samples_per_axis) +
                    " is out of range (1 to 64)");
    if (options.texture_size < 16 || options.texture_size > 8192)
        return fail("texture size " + std::to_string(options.texture_size) +
                    " is out of range (16 to 8192)");
    const std::filesystem::path& dir = options.out_dir;
    if (dir.empty()) return fail("--out: the output directory name is empty");
    std::error_code ec;
    if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
        return fail("cannot write into " + quoted(dir) + ": it exists and is not a directory");
    RunOutputs outputs;
    if (const Status made = outputs.create_directories(dir); !made)
        return fail(made.error().message);

    const bool show_progress = !options.quiet && Progress::stderr_is_terminal();
    PlaneViewOptions view;
    view.width = options.width;
    view.height = plane_view_height(options.width);

    const Image texture = make_builtin_texture(options.texture_size);
    MipPyramidOptions pyramid_options;
    pyramid_options.summed_area_table = true;
    const MipPyramid pyramid = MipPyramid::build(texture, pyramid_options);

    struct Entry {
        std::string name, file;
        Image image;
        PlaneRenderStats stats;
        double rmse = 0;
    };
    std::vector<Entry> entries;
    {
        PlaneReferenceOptions reference_options;
        reference_options.samples_per_axis = options.samples_per_axis;
        Progress progress("reference", static_cast<std::uint64_t>(view.height), show_progress);
        Entry e{"reference", "demo_reference.png", {}, {}, 0};
        e.image = render_plane_reference(pyramid, view, reference_options, &e.stats, &progress);
        progress.finish();
        entries.push_back(std::move(e));
    }
    for (TextureFilter filter : plane_filters()) {
        LookupOptions lookup;
        lookup.filter = filter;
        const std::string name = to_string(filter);
        Progress progress(name, static_cast<std::uint64_t>(view.height), show_progress);
        Entry e{name, "demo_" + name + ".png", {}, {}, 0};
        e.image = render_plane_view(pyramid, view, lookup, &e.stats, &progress);
        progress.finish();
        entries.push_back(std::move(e));
    }
    std::size_t measured_pixels = 0;
    for (Entry& e : entries) e.rmse = plane_rmse(e.image, entries[0].image, view, &measured_pixels);

    constexpr int kColumns = 4, kGap = 4;
    std::vector<const Image*> images;
    std::vector<std::string> labels;
    for (const Entry& e : entries) {
        images.push_back(&e.image);
        const bool reference = e.name == "reference";
        labels.push_back(
            panel_label(e.name, reference ? options.samples_per_axis * options.samples_per_axis : 1,
                        reference ? NAN : e.rmse, e.stats.seconds));
    }
    const ContactSheet sheet = contact_sheet(images, labels, {kColumns, kGap});
    if (!sheet.warning.empty()) warn(sheet.warning);
    // The images first, all or none, then the JSON that lists them.
    std::vector<ImageToSave> files;
    for (const Entry& e : entries) files.push_back({&e.image, dir / e.file});
    files.push_back({&sheet.image, dir / "demo_contact_sheet.png"});
    if (const Status saved = outputs.save(files); !saved) return fail(saved.error().message);

    const PlaneView camera(view);
    std::ostringstream json;
    json << "{\n";
    json << "  \"image\": {\"width\": " << view.width << ", \"height\": " << view.height << "},\n";
    json << "  \"texture\": {\"name\": \"builtin\", \"width\": " << texture.width
         << ", \"height\": " << texture.height
         << ", \"pyramid\": \"box, repeat, with summed-area table\"},\n";
    json << "  \"camera\": {\"eye_height\": " << number(view.eye_height)
         << ", \"pitch_degrees\": " << number(view.pitch_degrees)
         << ", \"horizontal_fov_degrees\": " << number(view.horizontal_fov_degrees)
         << ", \"yaw_degrees\": " << number(view.yaw_degrees)
         << ", \"uv_scale\": " << number(view.uv_scale)
         << ", \"horizon_row\": " << number(camera.horizon_row()) << "},\n";
    json << "  \"reference\": {\"file\": \"demo_reference.png\", \"samples_per_pixel\": "
         << options.samples_per_axis * options.samples_per_axis
         << ", \"sampling\": \"stratified jittered\", \"pixel_filter\": \"Gaussian, sigma 0.5 "
            "pixel, truncated at 3 sigma (kernel covariance K/4)\", \"texel_lookup\": "
            "\"bilinear, level 0\", \"seconds\": "
         << number(entries[0].stats.seconds) << ", \"lookups\": " << entries[0].stats.lookups
         << "},\n";
    json << "  \"metric\": {\"name\": \"rmse\", \"space\": \"linear\", \"channels\": "
         << texture.channels << ", \"pixels\": " << measured_pixels
         << ", \"region\": \"plane rows whose 3-sigma pixel filter lies below the horizon\"},\n";
    json << "  \"filters\": [\n";
    for (std::size_t i = 1; i < entries.size(); ++i) {
        const Entry& e = entries[i];
        json << "    {\"name\": \"" << e.name << "\", \"file\": \"" << e.file
             << "\", \"rmse\": " << number(e.rmse) << ", \"seconds\": " << number(e.stats.seconds)
             << ", \"lookups\": " << e.stats.lookups << "}" << (i + 1 < entries.size() ? "," : "")
             << "\n";
    }
    json << "  ],\n";
    // A cell is a panel (the image, unchanged) and the label strip under it; cell i's top left
    // corner is (gap + column·(cell_width + gap), gap + row·(cell_height + gap)).
    const int label_height = sheet.strips.empty() ? 0 : sheet.strips.front().height;
    json << "  \"contact_sheet\": {\"file\": \"demo_contact_sheet.png\", \"columns\": " << kColumns
         << ", \"rows\": " << (entries.size() + kColumns - 1) / kColumns << ", \"gap\": " << kGap
         << ", \"cell_width\": " << view.width
         << ", \"cell_height\": " << view.height + label_height
         << ", \"label_height\": " << label_height << ", \"order\": [";
    for (std::size_t i = 0; i < entries.size(); ++i)
        json << (i ? ", " : "") << "\"" << entries[i].name << "\"";
    json << "]}\n}\n";
    if (const Status saved = outputs.write(dir / "demo.json", json.str()); !saved)
        return fail(saved.error().message);
    outputs.keep();

    std::printf("%-10s %10s %10s %12s\n", "filter", "RMSE", "ms", "lookups");
    for (const Entry& e : entries) {
        const std::string rmse = e.name == "reference" ? "-" : number(e.rmse, "%.5f");
        std::printf("%-10s %10s %10.1f %12llu\n", e.name.c_str(), rmse.c_str(),
                    e.stats.seconds * 1e3, static_cast<unsigned long long>(e.stats.lookups));
    }
    std::printf("RMSE: linear light, against the reference, over %zu plane pixels\n",
                measured_pixels);
    std::printf("wrote %zu images, demo_contact_sheet.png and demo.json to %s\n", entries.size(),
                dir.string().c_str());
    std::fflush(stdout);
    return 0;
}

int plane(const PlaneCommandOptions& options) {
    const Result<TextureFilter> filter = parse_plane_filter(options.filter);
    if (!filter) return fail(filter.error().message);
    if (auto problem = range_problem("--size", options.width, kImageWidths)) return fail(*problem);
    if (!std::isfinite(options.uv_scale) || !(options.uv_scale > 0) || options.uv_scale > 1e6)
        return fail("--uv-scale " + text(options.uv_scale) +
                    " is out of range (a positive number up to 1e6)");
    if (const auto problem = output_file_problem(options.output)) return fail(*problem);

    ImageLoadOptions load;
    if (options.repair_non_finite) load.non_finite = NonFinitePolicy::repair;
    load.warn = [](const std::string& message) {
        std::cerr << "footprint: warning: " << message << "\n";
    };
    Result<Image> texture = load_image(options.texture, load);
    if (!texture) return fail(texture.error().message);

    PlaneViewOptions view;
    view.width = options.width;
    view.height = plane_view_height(options.width);
    view.uv_scale = options.uv_scale;
    MipPyramidOptions pyramid_options;
    pyramid_options.summed_area_table = *filter == TextureFilter::summed_area;
    const MipPyramid pyramid = MipPyramid::build(*texture, pyramid_options);
    LookupOptions lookup;
    lookup.filter = *filter;
    Progress progress(to_string(*filter), static_cast<std::uint64_t>(view.height),
                      !options.quiet && Progress::stderr_is_terminal());
    PlaneRenderStats stats;
    const Image image = render_plane_view(pyramid, view, lookup, &stats, &progress);
    progress.finish();
    if (const Status saved = save_image(image, options.output); !saved)
        return fail(saved.error().message);
    if (!options.quiet) {
        report_written(options.output.string(), view.width, view.height, to_string(*filter),
                       std::nullopt, stats.seconds);
    }
    return 0;
}

}  // namespace

int run_texture_demo_command(const TextureDemoOptions& options) {
    try {
        return demo(options);
    } catch (const std::exception& e) {
        return fail(std::string("demo failed: ") + e.what());
    }
}

int run_plane_command(const PlaneCommandOptions& options) {
    try {
        return plane(options);
    } catch (const std::exception& e) {
        return fail(std::string("plane failed: ") + e.what());
    }
}

}  // namespace footprint
