#include "env_command.h"

#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <system_error>

#include "command_util.h"
#include "envmap/env_convert.h"
#include "envmap/env_image_io.h"
#include "image/image_io.h"
#include "progress.h"

namespace footprint {

namespace {

namespace fs = std::filesystem;

constexpr const char* kLayoutNames = "cube, latlong, sphere, paraboloid";
constexpr const char* kArrangementNames = "hcross, vcross, 3x2, 2x3, column, row";

// True if `a` and `b` name the same file: the same inode where both exist, else the same path
// once resolved (symbolic links, "..", the current directory).
bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) {
        const bool same = fs::equivalent(a, b, ec);
        if (!ec) return same;
    }
    // Absolute first: weakly_canonical() leaves a path none of whose parts exist relative, so that
    // "x.exr" and "./x.exr" would differ.
    const fs::path ca = fs::weakly_canonical(fs::absolute(a, ec), ec);
    if (ec) return a.lexically_normal() == b.lexically_normal();
    const fs::path cb = fs::weakly_canonical(fs::absolute(b, ec), ec);
    return !ec && ca == cb;
}

// Why the outputs cannot be written as given: one of them is an input, or one file is given
// twice as an output; nullopt if they are all distinct.
std::optional<std::string> output_clash(const EnvConvertCommandOptions& options) {
    for (std::size_t i = 0; i < options.outputs.size(); ++i) {
        const fs::path& out = options.outputs[i];
        for (const fs::path& in : options.inputs)
            if (same_file(out, in))
                return "-o " + quoted(out) + " is the input " + quoted(in) +
                       "; write the conversion to another file";
        for (std::size_t k = 0; k < i; ++k)
            if (same_file(out, options.outputs[k]))
                return "-o " + quoted(out) + " is given twice (as " + quoted(options.outputs[k]) +
                       ")";
    }
    return std::nullopt;
}

std::string size_text(const EnvImages& images) {
    const Image& f = images.faces[0];
    std::string text = std::string(env_layout_name(images.layout)) + " ";
    if (images.faces.size() > 1) text += std::to_string(images.faces.size()) + " x ";
    return text + std::to_string(f.width) + "x" + std::to_string(f.height);
}

int env_convert(const EnvConvertCommandOptions& options) {
    const std::optional<EnvLayout> to = parse_env_layout(options.to);
    if (!to) return fail("--to: unknown layout '" + options.to + "' (valid: " + kLayoutNames + ")");
    EnvImageOptions load_options;
    if (!options.from.empty()) {
        load_options.layout = parse_env_layout(options.from);
        if (!load_options.layout)
            return fail("--from: unknown layout '" + options.from + "' (valid: " + kLayoutNames +
                        ")");
    }
    const std::optional<CubeArrangement> from_arrangement =
        parse_cube_arrangement(options.from_cube_layout);
    if (!from_arrangement)
        return fail("--from-cube-layout: unknown cube layout '" + options.from_cube_layout +
                    "' (valid: auto, " + kArrangementNames + ", openexr)");
    load_options.cube_arrangement = *from_arrangement;
    if (*from_arrangement != CubeArrangement::automatic && !load_options.layout)
        load_options.layout = EnvLayout::cube;
    std::optional<CubeArrangement> arrangement = parse_cube_arrangement(options.cube_layout);
    if (!arrangement || *arrangement == CubeArrangement::openexr_column)
        return fail("--cube-layout: unknown output cube layout '" + options.cube_layout +
                    "' (valid: " + kArrangementNames + ")");
    if (options.size < 0 || options.size > 16384)
        return fail("--size " + std::to_string(options.size) +
                    " is out of range (1 to 16384, or 0 for the source's resolution)");
    if (*to == EnvLayout::latlong && options.size % 2 != 0)
        return fail("--size " + std::to_string(options.size) +
                    " is odd; a lat-long map is N x N/2 with N even");
    if (options.inputs.empty()) return fail("no input file given");

    const std::size_t outputs = options.outputs.size();
    const bool outputs_fit = *to == EnvLayout::cube         ? outputs == 1 || outputs == 6
                             : *to == EnvLayout::paraboloid ? outputs == 1 || outputs == 2
                                                            : outputs == 1;
    if (!outputs_fit)
        return fail(std::string("-o: a ") + env_layout_name(*to) + " map is written to " +
                    (*to == EnvLayout::cube ? "1 file (a cross or strip) or 6 (one per face)"
                     : *to == EnvLayout::paraboloid ? "1 file (front | back) or 2 (front, back)"
                                                    : "1 file") +
                    ", not " + std::to_string(outputs));
    for (const fs::path& file : options.outputs)
        if (const auto problem = output_file_problem(file)) return fail(*problem);
    if (const auto clash = output_clash(options)) return fail(*clash);

    if (options.repair_non_finite) {
        load_options.image.non_finite = NonFinitePolicy::repair;
        load_options.image.warn = [](const std::string& message) {
            std::cerr << "footprint: warning: " << message << "\n";
        };
    }
    Result<EnvImages> source_images = load_environment_images(options.inputs, load_options);
    if (!source_images) return fail(source_images.error().message);
    Result<EnvironmentMap> source = make_environment_map(*source_images);
    if (!source)
        return fail("cannot use " + quoted(options.inputs[0]) + ": " + source.error().message);

    EnvConvertOptions convert_options;
    convert_options.size = options.size == 0 ? default_env_size(*source, *to) : options.size;
    Progress progress("convert",
                      static_cast<std::uint64_t>(env_output_rows(*to, convert_options.size)),
                      !options.quiet && Progress::stderr_is_terminal());
    convert_options.on_row = [&progress] { progress.advance(); };
    Result<EnvImages> converted = convert_environment(*source, *to, convert_options);
    progress.finish();
    if (!converted) return fail(converted.error().message);

    EnvSaveOptions save_options;
    save_options.cube_arrangement = *arrangement;
    if (const Status saved = save_environment_images(*converted, options.outputs, save_options);
        !saved)
        return fail(saved.error().message);
    if (!options.quiet) {
        std::string written;
        for (const fs::path& file : options.outputs)
            written += (written.empty() ? "" : ", ") + quoted(file);
        const CubeArrangement shown = *arrangement == CubeArrangement::automatic
                                          ? CubeArrangement::horizontal_cross
                                          : *arrangement;
        const std::string how = *to == EnvLayout::cube && outputs == 1
                                    ? std::string(", ") + cube_arrangement_name(shown)
                                    : std::string();
        // On stderr, prefixed, as every command's "wrote" line (stdout is the commands' data).
        std::fprintf(stderr, "footprint: converted %s (%s) to %s%s: %s\n",
                     quoted(options.inputs[0]).c_str(), size_text(*source_images).c_str(),
                     size_text(*converted).c_str(), how.c_str(), written.c_str());
    }
    return 0;
}

}  // namespace

int run_env_convert_command(const EnvConvertCommandOptions& options) {
    try {
        return env_convert(options);
    } catch (const std::exception& e) {
        return fail(std::string("env convert failed: ") + e.what());
    }
}

}  // namespace footprint
