// examples/filament/filament_tools.cpp — cmgen and roughness-prefilter on footprint's inputs.
#include "filament_tools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

#include "bump/bump_pyramid.h"
#include "bump/slope_map.h"
#include "image/image_io.h"
#include "texture/mip_pyramid.h"

namespace footprint::filament_example {
namespace fs = std::filesystem;
namespace {

// FNV-1a over the image's size and bytes (and any extra key): the cache folder's name.
std::string content_hash(const Image& image, const std::string& extra) {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    };
    const int header[3] = {image.width, image.height, image.channels};
    mix(header, sizeof header);
    mix(image.pixels.data(), image.pixels.size() * sizeof(float));
    mix(extra.data(), extra.size());
    std::ostringstream out;
    out << std::hex << h;
    return out.str();
}

// Bilinear lookup of a lat-long image with wrap in s and clamp in t (RGB of channels 0–2).
std::array<float, 3> latlong_bilinear(const Image& map, double s, double t) {
    const double x = s * map.width - 0.5,
                 y = std::clamp(t * map.height - 0.5, 0.0, map.height - 1.0);
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    std::array<float, 3> out{0, 0, 0};
    for (int dy = 0; dy < 2; ++dy) {
        const int yy = std::min(y0 + dy, map.height - 1);
        for (int dx = 0; dx < 2; ++dx) {
            const int xx = ((x0 + dx) % map.width + map.width) % map.width;
            const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
            for (int c = 0; c < 3; ++c)
                out[c] += static_cast<float>(w * map.at(xx, yy, std::min(c, map.channels - 1)));
        }
    }
    return out;
}

// footprint's lat-long addressing (docs/environment-maps.md): s = 0 at +Z, ¼ at −X, ½ at −Z,
// ¾ at +X; t = 0 at +Y.
std::array<double, 2> latlong_st(double x, double y, double z) {
    const double len = std::sqrt(x * x + y * y + z * z);
    double s = std::atan2(-x, z) / (2 * std::numbers::pi);
    if (s < 0) s += 1;
    const double t = std::acos(std::clamp(y / len, -1.0, 1.0)) / std::numbers::pi;
    return {s, t};
}

// The direction of texel (u, v) ∈ [−1, 1]² (v down) of a GL cube face: the OpenGL face table,
// which libibl's Cubemap::getDirectionFor and Filament's cube textures follow.
std::array<double, 3> cube_direction(int face, double u, double v) {
    switch (face) {
        case 0:
            return {1, -v, -u};  // +X
        case 1:
            return {-1, -v, u};  // −X
        case 2:
            return {u, 1, v};  // +Y
        case 3:
            return {u, -1, -v};  // −Y
        case 4:
            return {u, -v, 1};  // +Z
        default:
            return {-u, -v, -1};  // −Z
    }
}

// A horizontal cross (4 × 3 faces: −X +Z +X −Z in the middle row, +Y above +Z, −Y below), the
// layout cmgen reads. Each texel is the mean of 4 × 4 bilinear lookups over its area, so that a
// lat-long finer than the cube does not alias into it.
Image latlong_to_cross(const Image& latlong, int face_size) {
    Image cross(4 * face_size, 3 * face_size, 3, 0.0f);
    const int origin[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};
    constexpr int kSub = 4;
    for (int face = 0; face < 6; ++face) {
        for (int y = 0; y < face_size; ++y) {
            for (int x = 0; x < face_size; ++x) {
                std::array<double, 3> sum{0, 0, 0};
                for (int j = 0; j < kSub; ++j) {
                    for (int i = 0; i < kSub; ++i) {
                        const double u = 2 * (x + (i + 0.5) / kSub) / face_size - 1;
                        const double v = 2 * (y + (j + 0.5) / kSub) / face_size - 1;
                        const std::array<double, 3> d = cube_direction(face, u, v);
                        const std::array<double, 2> st = latlong_st(d[0], d[1], d[2]);
                        const std::array<float, 3> c = latlong_bilinear(latlong, st[0], st[1]);
                        for (int k = 0; k < 3; ++k) sum[k] += c[k];
                    }
                }
                float* out =
                    cross.at(origin[face][0] * face_size + x, origin[face][1] * face_size + y);
                for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(sum[k] / (kSub * kSub));
            }
        }
    }
    return cross;
}

std::string quoted(const fs::path& path) {
    std::string out = "'";
    for (char c : path.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace

Result<Image> load_map(const MapSource& map, bool linear) {
    if (map.file.empty()) return map.image;
    ImageLoadOptions options;
    if (linear) options.encoding = ColorEncoding::linear;
    return load_image(map.file, options);
}

Status run_tool(const std::string& command, const fs::path& log) {
    const std::string line = command + " > " + quoted(log) + " 2>&1";
    const int status = std::system(line.c_str());
    if (status == 0) return {};
    std::ifstream in(log);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    if (text.size() > 600) text = "..." + text.substr(text.size() - 600);
    return Error{"'" + command + "' failed (status " + std::to_string(status) + "): " + text};
}

Result<PrefilteredEnvironment> prefilter_environment(const Image& latlong,
                                                     const fs::path& cache_dir, int face_size) {
    const fs::path dir = cache_dir / ("env-" + content_hash(latlong, std::to_string(face_size)));
    // cmgen names its deployed files after the folder: DIR/env_ibl.ktx, DIR/env_skybox.ktx.
    const fs::path deploy = dir / "env";
    PrefilteredEnvironment out{deploy / "env_ibl.ktx", deploy / "env_skybox.ktx"};
    std::error_code ec;
    if (fs::is_regular_file(out.ibl_ktx, ec) && fs::is_regular_file(out.skybox_ktx, ec)) return out;
    fs::create_directories(dir, ec);
    if (ec) return Error{"cannot create the cache folder '" + dir.string() + "': " + ec.message()};
    const fs::path cross = dir / "cross.exr";
    ImageSaveOptions save;
    save.encoding = ColorEncoding::linear;
    if (Status s = save_image(latlong_to_cross(latlong, face_size), cross, save); !s)
        return s.error();
    // --no-mirror: the cross is already in the direction convention the IBL is looked up with.
    const std::string command =
        "cmgen --quiet --no-mirror --format=ktx --size=" + std::to_string(face_size) +
        " --deploy=" + quoted(deploy) + " " + quoted(cross);
    if (Status s = run_tool(command, dir / "cmgen.log"); !s) return s.error();
    if (!fs::is_regular_file(out.ibl_ktx, ec))
        return Error{"cmgen wrote no '" + out.ibl_ktx.string() + "' (see " +
                     (dir / "cmgen.log").string() + ")"};
    return out;
}

Result<std::vector<Image>> prefilter_roughness(const Image& normal_map, const std::string& label,
                                               const Image& roughness,
                                               const std::string& roughness_label,
                                               const fs::path& cache_dir) {
    auto square_power_of_two = [](const Image& map) {
        return map.width == map.height && map.width >= 1 && (map.width & (map.width - 1)) == 0;
    };
    auto not_square = [](const Image& map, const std::string& name) {
        return Error{"roughness-prefilter needs a square power-of-two map; '" + name + "' is " +
                     std::to_string(map.width) + "x" + std::to_string(map.height)};
    };
    if (!square_power_of_two(normal_map)) return not_square(normal_map, label);
    const bool constant = roughness.width == 1 && roughness.height == 1;
    if (!constant && !square_power_of_two(roughness)) return not_square(roughness, roughness_label);
    const float value = roughness.at(0, 0, 0);
    const std::string key = constant ? std::to_string(value) : "map-" + content_hash(roughness, "");
    const fs::path dir = cache_dir / ("roughness-" + content_hash(normal_map, key));
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) return Error{"cannot create the cache folder '" + dir.string() + "': " + ec.message()};
    const int size = std::max(normal_map.width, constant ? 1 : roughness.width);
    int levels = 1;
    while ((size >> (levels - 1)) > 1) ++levels;
    auto level_file = [&dir](int level) {
        return dir / ("roughness_" + std::to_string(level) + ".png");
    };
    if (!fs::is_regular_file(level_file(levels - 1), ec)) {
        // The tool reads PNG, HDR, PSD or EXR; a 16-bit PNG of the values as stored keeps the map's
        // bytes (its EXR and HDR output are empty files in 1.9, so the levels come back as PNG).
        ImageSaveOptions save;
        save.encoding = ColorEncoding::linear;
        save.bits = 16;
        // The tool wants both maps of one size: the smaller one's texels repeated (both are
        // powers of two), which keeps every level's normal variance and roughness.
        auto enlarged = [size](const Image& map) {
            if (map.width == size) return map;
            const int factor = size / map.width;
            Image out(size, size, map.channels);
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x)
                    for (int c = 0; c < map.channels; ++c)
                        out.at(x, y, c) = map.at(x / factor, y / factor, c);
            return out;
        };
        const fs::path input = dir / "normal.png";
        if (Status s = save_image(enlarged(normal_map), input, save); !s) return s.error();
        std::ostringstream command;
        command << "roughness-prefilter";
        if (constant) {
            command << " --roughness=" << value;
        } else {
            // Grey as RGB: whichever channel the tool reads holds the roughness.
            const Image map = enlarged(roughness);
            Image grey(size, size, 3);
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x)
                    for (int c = 0; c < 3; ++c) grey.at(x, y, c) = map.at(x, y, 0);
            const fs::path roughness_input = dir / "roughness_in.png";
            if (Status s = save_image(grey, roughness_input, save); !s) return s.error();
            command << " --roughness-map=" << quoted(roughness_input);
        }
        command << " --format=png " << quoted(input) << " " << quoted(dir / "roughness.png");
        if (Status s = run_tool(command.str(), dir / "roughness-prefilter.log"); !s)
            return s.error();
    }
    std::vector<Image> chain;
    for (int level = 0; level < levels; ++level) {
        ImageLoadOptions load;
        load.encoding = ColorEncoding::linear;  // the tool writes roughness values, not colours
        Result<Image> image = load_image(level_file(level), load);
        if (!image) return image.error();
        chain.push_back(std::move(*image));
    }
    return chain;
}

std::vector<Image> colour_pyramid(const Image& image) {
    const MipPyramid pyramid = MipPyramid::build(image);  // box, repeat: footprint's defaults
    std::vector<Image> levels;
    for (int level = 0; level < pyramid.level_count(); ++level)
        levels.push_back(pyramid.level_image(level));
    return levels;
}

Result<BumpMoments> make_bump_moments(const Image& normal_map, const std::string& label) {
    Result<Image> slopes = slopes_from_normal_map(normal_map);
    if (!slopes) return Error{"'" + label + "': " + slopes.error().message};
    Result<BumpPyramid> pyramid = BumpPyramid::build(*slopes);
    if (!pyramid) return Error{"'" + label + "': " + pyramid.error().message};
    const MipPyramid& moments = pyramid->moments();
    BumpMoments out;
    for (int level = 0; level < moments.level_count(); ++level) {
        const int w = moments.width(level), h = moments.height(level);
        Image a(w, h, 4), b(w, h, 1);
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const float* m = moments.texel(level, x, y);
                for (int c = 0; c < 4; ++c) a.at(x, y, c) = m[c];
                b.at(x, y, 0) = m[4];
            }
        }
        out.moments0.push_back(std::move(a));
        out.moments1.push_back(std::move(b));
    }
    out.slope_offset[0] = static_cast<float>(pyramid->slope_offset().x);
    out.slope_offset[1] = static_cast<float>(pyramid->slope_offset().y);
    return out;
}

}  // namespace footprint::filament_example
