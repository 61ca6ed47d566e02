// apps/cli_options.h — what the `footprint` commands' options share: one filter vocabulary and one
// way of refusing a number out of range.
//
// The filter vocabulary. A name means the same filter in every command; each command accepts the
// filters it can do (render: render/renderer.h's FilterMode; plane and texture-demo:
// texture/texture_lookup.h's TextureFilter; demo and eval render every FilterMode but reference
// and name their files and rows by these names):
//
//   name       filter                                                  render plane texture-demo
//   nearest    the nearest texel of the finest level                     -      x      x
//   bilinear   one bilinear lookup of the finest level, no footprint     x      x      x
//   trilinear  isotropic MIP: two levels, bilinear in each               x      x      x
//   fa         footprint assembly (Schilling 1996)                       x      x      x
//   fa-rough   fa plus the roughness pyramid (environment and            x      -      -
//              highlights widened by the bumps' slopes)
//   ewa        elliptical weighted average (Heckbert 1989)               -      x      x
//   ewa-rough  ewa plus the roughness pyramid                            x      -      -
//   sat        summed-area table (Crow 1984)                             -      x      x
//   reference  the ground truth: N samples per pixel, each a bilinear    x     (texture-demo's
//              lookup of the finest level                                       reference image)
//   point      the GPU path's bilinear (render --device gpu, view)
//   hw-aniso   the GPU's own anisotropic filtering (render --device gpu, view)
// With --device gpu, render (and view) take point, trilinear, fa, fa-rough and hw-aniso
// (gpu/gpu_renderer.h's GpuFilter).
//
// An unknown name is refused with one message naming the option, the value, the closest name
// ("did you mean", core/suggest.h) and the names the command accepts.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/result.h"
#include "gpu/gpu_renderer.h"
#include "render/renderer.h"
#include "texture/texture_lookup.h"

namespace footprint {

// The filters of `footprint plane`, in the vocabulary's order: the filters texture-demo renders.
std::span<const TextureFilter> plane_filters();

// The filters of `footprint render`, separated by `separator` ("|" for --help, ", " for messages).
std::string render_filter_names(std::string_view separator);
// The filters of `footprint plane` (and the filters texture-demo renders).
std::string plane_filter_names(std::string_view separator);

// --filter NAME of `footprint render` / `footprint plane`; the error is the whole message:
//   "--filter: unknown filter 'fa_rough' (did you mean 'fa-rough'?); footprint render accepts
//    bilinear, trilinear, fa, fa-rough, ewa-rough, reference"
//   "--filter: footprint render has no filter 'sat'; it accepts bilinear, …"
// `option` names the argument ("filter" for Python's render()).
Result<FilterMode> parse_render_filter(std::string_view name, std::string_view option = "--filter");
Result<TextureFilter> parse_plane_filter(std::string_view name);
// --filter NAME of `footprint render --device gpu` and `footprint view` (`command` names it in
// the message).
Result<GpuFilter> parse_gpu_render_filter(std::string_view name,
                                          std::string_view command = "render --device gpu");
std::string gpu_filter_names(std::string_view separator);

// The GPU time of `footprint view`'s HUD, three significant digits ("5.43 ms GPU", "83.2 ms GPU",
// "1169 ms GPU"), or "- ms GPU" before the first frame's time is known (a negative `ms`).
std::string gpu_ms_text(double ms);

// An option's value that is none of `accepted` (--downsample, --flip-range, …): "unknown value
// 'gauss' (did you mean 'box'?); it accepts box, tent", or nullopt for an accepted one. The
// command line prints it after the option's name and exits 1, as for every bad value.
std::optional<std::string> unknown_value_problem(std::string_view value,
                                                 std::span<const std::string_view> accepted);

// `footprint WORD …` where WORD is none of `commands`: the whole message, with the nearest command
// ("unknown command 'rendr' (did you mean 'render'?); the commands are …"), or nullopt for a
// command or an option (CLI11 alone says only that a subcommand is required).
std::optional<std::string> unknown_command_problem(std::string_view word,
                                                   std::span<const std::string_view> commands);

// The integers an option accepts, low … high: what range_problem checks and --help says.
struct IntRange {
    long long low = 0, high = 0;
};
// --size of demo, eval and texture-demo (each renders many images of that width) and of plane and
// render (one image).
inline constexpr IntRange kDemoWidths{16, 4096}, kImageWidths{16, 16384};
// render's samples per pixel and threads (0: all cores); Python's render() takes the same.
inline constexpr IntRange kRenderSpp{1, 1 << 16}, kRenderThreads{0, 1024};

// "16 to 4096": a range as range_problem's message and --help write it.
std::string range_text(IntRange range);

// --size's help for images `width` × width·9/16: "<what>, 16 to 4096 (height = width·9/16)".
std::string width_help(std::string_view what, IntRange widths);

// "--spp 0 is out of range (1 to 65536)" ("…(0 to 1024; 0: all cores)" with a `note`) when
// `value` is outside [low, high]; nullopt when it is inside.
std::optional<std::string> range_problem(std::string_view option, long long value, long long low,
                                         long long high, std::string_view note = {});
std::optional<std::string> range_problem(std::string_view option, long long value, IntRange range,
                                         std::string_view note = {});

// --size WIDTHxHEIGHT of the GPU commands (view, footprint-bench gpu), each side 1 to 16384:
//   "--size '12by9': expected WIDTHxHEIGHT, e.g. 1280x720"
//   "--size width 0 is out of range (1 to 16384)"
struct ImageSize {
    int width = 0, height = 0;
};
Result<ImageSize> parse_image_size(std::string_view option, const std::string& text);

// What a command wrote, one line on stderr, as every command that writes an image says it:
//   "footprint: wrote out.png (480x270, fa, 1 spp, 0.05 s)"
// `what` is the file, or a sequence's "8 frames a_0000.png … a_0007.png"; `spp` is left out when
// nullopt (a command without samples per pixel).
void report_written(const std::string& what, int width, int height, std::string_view filter,
                    std::optional<int> spp, double seconds);

}  // namespace footprint
