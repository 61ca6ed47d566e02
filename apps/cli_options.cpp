#include "cli_options.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "core/suggest.h"

namespace footprint {

namespace {

constexpr TextureFilter kPlaneFilters[] = {
    TextureFilter::nearest,    TextureFilter::bilinear,           TextureFilter::trilinear,
    TextureFilter::brilinear,  TextureFilter::footprint_assembly, TextureFilter::ewa,
    TextureFilter::summed_area};

// Names that are no filter of the vocabulary but are what a user may reach for: each is answered
// with "did you mean" the vocabulary's name for that filter.
struct Hint {
    std::string_view word, name;
};
constexpr Hint kHints[] = {{"point", "bilinear"},        {"bilinear", "point"},
                           {"aniso", "hw-aniso"},        {"footprint_assembly", "fa"},
                           {"footprint-assembly", "fa"}, {"summed_area", "sat"},
                           {"summed-area", "sat"}};

std::vector<std::string_view> render_names() {
    std::vector<std::string_view> names;
    for (FilterMode mode : all_filter_modes()) names.emplace_back(filter_mode_name(mode));
    return names;
}

std::vector<std::string_view> gpu_names() {
    std::vector<std::string_view> names;
    for (GpuFilter filter : all_gpu_filters()) names.emplace_back(gpu_filter_name(filter));
    return names;
}

std::vector<std::string_view> plane_names() {
    std::vector<std::string_view> names;
    for (TextureFilter filter : kPlaneFilters) names.emplace_back(to_string(filter));
    return names;
}

std::string joined(const std::vector<std::string_view>& names, std::string_view separator) {
    std::string out;
    for (std::string_view name : names) {
        if (!out.empty()) out += separator;
        out += name;
    }
    return out;
}

bool contains(const std::vector<std::string_view>& names, std::string_view name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

// Why `name` is not one of `accepted`, the filters of `command`.
// " (did you mean 'x'?)" for a guess, or nothing: every unknown name's message words it so.
std::string did_you_mean(std::optional<std::string_view> guess) {
    return guess ? " (did you mean '" + std::string(*guess) + "'?)" : std::string();
}

Error unknown_filter(std::string_view name, const std::vector<std::string_view>& accepted,
                     std::string_view command, std::string_view option = "--filter") {
    const std::string quoted_name = "'" + std::string(name) + "'";
    const std::string list = joined(accepted, ", ");
    std::vector<std::string_view> vocabulary = render_names();
    for (std::string_view other : plane_names())
        if (!contains(vocabulary, other)) vocabulary.push_back(other);
    for (std::string_view other : gpu_names())
        if (!contains(vocabulary, other)) vocabulary.push_back(other);
    std::optional<std::string_view> guess;
    for (const Hint& hint : kHints)
        if (hint.word == name && contains(accepted, hint.name)) guess = hint.name;
    const bool known = contains(vocabulary, name);
    if (!guess && !known) guess = closest_name(name, accepted);
    const std::string hint = did_you_mean(guess);
    if (known) {
        return Error{std::string(option) + ": footprint " + std::string(command) +
                     " has no filter " + quoted_name + hint + "; it accepts " + list};
    }
    return Error{std::string(option) + ": unknown filter " + quoted_name + hint + "; footprint " +
                 std::string(command) + " accepts " + list};
}

}  // namespace

std::span<const TextureFilter> plane_filters() {
    return kPlaneFilters;
}

std::string render_filter_names(std::string_view separator) {
    return joined(render_names(), separator);
}

std::string plane_filter_names(std::string_view separator) {
    return joined(plane_names(), separator);
}

Result<FilterMode> parse_render_filter(std::string_view name, std::string_view option) {
    if (const std::optional<FilterMode> mode = parse_filter_mode(name)) return *mode;
    return unknown_filter(name, render_names(), "render", option);
}

Result<GpuFilter> parse_gpu_render_filter(std::string_view name, std::string_view command) {
    if (const std::optional<GpuFilter> filter = parse_gpu_filter(name)) return *filter;
    return unknown_filter(name, gpu_names(), command);
}

std::string gpu_ms_text(double ms) {
    if (!(ms >= 0)) return "- ms GPU";
    char text[32];
    std::snprintf(text, sizeof text, "%.*f ms GPU", ms < 10 ? 2 : ms < 100 ? 1 : 0, ms);
    return text;
}

std::string gpu_filter_names(std::string_view separator) {
    return joined(gpu_names(), separator);
}

Result<TextureFilter> parse_plane_filter(std::string_view name) {
    const std::optional<TextureFilter> filter = parse_texture_filter(name);
    if (filter && std::find(std::begin(kPlaneFilters), std::end(kPlaneFilters), *filter) !=
                      std::end(kPlaneFilters)) {
        return *filter;
    }
    return unknown_filter(name, plane_names(), "plane");
}

std::string range_text(IntRange range) {
    return std::to_string(range.low) + " to " + std::to_string(range.high);
}

std::string width_help(std::string_view what, IntRange widths) {
    return std::string(what) + ", " + range_text(widths) + " (height = width·9/16)";
}

std::optional<std::string> range_problem(std::string_view option, long long value, long long low,
                                         long long high, std::string_view note) {
    if (value >= low && value <= high) return std::nullopt;
    std::string message = std::string(option) + " " + std::to_string(value) + " is out of range (" +
                          range_text({low, high});
    if (!note.empty()) message += "; " + std::string(note);
    return message + ")";
}

std::optional<std::string> range_problem(std::string_view option, long long value, IntRange range,
                                         std::string_view note) {
    return range_problem(option, value, range.low, range.high, note);
}

Result<ImageSize> parse_image_size(std::string_view option, const std::string& text) {
    ImageSize size;
    char x = 0;
    char rest = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &size.width, &x, &size.height, &rest) != 3 ||
        (x != 'x' && x != 'X'))
        return Error{std::string(option) + " '" + text + "': expected WIDTHxHEIGHT, e.g. 1280x720"};
    const std::string name(option);
    if (auto p = range_problem(name + " width", size.width, 1, 16384)) return Error{*p};
    if (auto p = range_problem(name + " height", size.height, 1, 16384)) return Error{*p};
    return size;
}

void report_written(const std::string& what, int width, int height, std::string_view filter,
                    std::optional<int> spp, double seconds) {
    const std::string samples = spp ? ", " + std::to_string(*spp) + " spp" : std::string();
    std::fprintf(stderr, "footprint: wrote %s (%dx%d, %.*s%s, %.2f s)\n", what.c_str(), width,
                 height, static_cast<int>(filter.size()), filter.data(), samples.c_str(), seconds);
}

std::optional<std::string> unknown_value_problem(std::string_view value,
                                                 std::span<const std::string_view> accepted) {
    const std::vector<std::string_view> names(accepted.begin(), accepted.end());
    if (contains(names, value)) return std::nullopt;
    return "unknown value '" + std::string(value) + "'" +
           did_you_mean(closest_name(value, accepted)) + "; it accepts " + joined(names, ", ");
}

std::optional<std::string> unknown_command_problem(std::string_view word,
                                                   std::span<const std::string_view> commands) {
    const std::vector<std::string_view> names(commands.begin(), commands.end());
    if (word.empty() || word.front() == '-' || contains(names, word)) return std::nullopt;
    return "unknown command '" + std::string(word) + "'" +
           did_you_mean(closest_name(word, commands)) + "; the commands are " + joined(names, ", ");
}

}  // namespace footprint
