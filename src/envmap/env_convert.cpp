#include "envmap/env_convert.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/parallel.h"

namespace footprint {

namespace {

constexpr int kMaxSize = 16384;

// The output size whose ρ is at least `rho` (env_convert.h), before clamping.
double size_for_density(EnvLayout to, double rho) {
    switch (to) {
        case EnvLayout::latlong:
            return 2.0 * std::numbers::pi * rho;
        case EnvLayout::cube:
            return 2.0 * rho;
        case EnvLayout::sphere:
        case EnvLayout::paraboloid:
            return 4.0 * rho;
    }
    return 2.0 * rho;
}

Vec3d unit_direction(EnvLayout layout, int face, double s, double t) {
    return normalize(env_direction<double>(layout, face, s, t));
}

}  // namespace

double env_texels_per_radian(EnvLayout layout, Vec2 texel_scale) {
    const double w = texel_scale.x, h = texel_scale.y;
    switch (layout) {
        case EnvLayout::latlong:
            return std::min(w / (2.0 * std::numbers::pi), h / std::numbers::pi);
        case EnvLayout::cube:
            return w / 2.0;
        case EnvLayout::sphere:
        case EnvLayout::paraboloid:
            return w / 4.0;
    }
    return w / 2.0;
}

int default_env_size(const EnvironmentMap& source, EnvLayout to) {
    const double rho = env_texels_per_radian(source.layout(), source.texel_scale());
    // A relative tolerance so that a conversion to the same layout keeps the size exactly.
    const double exact = size_for_density(to, rho);
    double size = std::ceil(exact * (1.0 - 1e-9));
    if (to == EnvLayout::latlong) size = 2.0 * std::ceil(size / 2.0);
    const int lower = to == EnvLayout::latlong ? 2 : 1;
    return static_cast<int>(std::clamp(size, static_cast<double>(lower), double(kMaxSize)));
}

std::array<int, 2> env_face_size(EnvLayout to, int size) {
    if (to == EnvLayout::latlong) return {size, std::max(1, size / 2)};
    return {size, size};
}

int env_output_rows(EnvLayout to, int size) {
    return face_count(to) * env_face_size(to, size)[1];
}

Result<EnvImages> convert_environment(const EnvironmentMap& source, EnvLayout to,
                                      const EnvConvertOptions& options) {
    const int size = options.size == 0 ? default_env_size(source, to) : options.size;
    const int lower = to == EnvLayout::latlong ? 2 : 1;
    if (size < lower || size > kMaxSize)
        return Error{"output size " + std::to_string(options.size) + " is out of range (" +
                     std::to_string(lower) + " to " + std::to_string(kMaxSize) + ")"};
    if (source.face_count() < 1 || source.channels() < 1)
        return Error{"the source environment map is empty"};
    if (to == EnvLayout::latlong && size % 2 != 0)
        return Error{"output size " + std::to_string(size) +
                     " is odd; a lat-long map is N x N/2 with N even"};

    // (Not a structured binding: clang 14 cannot capture one in the lambda below.)
    const std::array<int, 2> face_size = env_face_size(to, size);
    const int width = face_size[0], height = face_size[1];
    const int faces = face_count(to);
    const int channels = source.channels();
    EnvImages result;
    result.layout = to;
    result.faces.assign(faces, Image(width, height, channels));

    const double half_step_s = 0.5 / width, half_step_t = 0.5 / height;
    parallel_for(0, faces * height, 4, [&](int first_row, int end_row) {
        std::vector<EnvRayDifferential> rays(static_cast<std::size_t>(width));
        for (int row = first_row; row != end_row; ++row) {
            const int face = row / height, y = row % height;
            const double t = (y + 0.5) / height;
            for (int x = 0; x < width; ++x) {
                const double s = (x + 0.5) / width;
                // Ray differentials per output texel (env_convert.h).
                const Vec3d r = unit_direction(to, face, s, t);
                const Vec3d dx = unit_direction(to, face, s + half_step_s, t) -
                                 unit_direction(to, face, s - half_step_s, t);
                const Vec3d dy = unit_direction(to, face, s, t + half_step_t) -
                                 unit_direction(to, face, s, t - half_step_t);
                rays[static_cast<std::size_t>(x)] = {vec3_cast<float>(r), vec3_cast<float>(dx),
                                                     vec3_cast<float>(dy)};
            }
            // The row's texels are contiguous, channels interleaved: the batch's layout.
            environment_lookup_batch(source, rays, options.lookup,
                                     result.faces[static_cast<std::size_t>(face)].at(0, y));
            if (options.on_row) options.on_row();
        }
    });
    return result;
}

}  // namespace footprint
