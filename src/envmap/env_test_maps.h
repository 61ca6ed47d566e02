// envmap/env_test_maps.h — environment maps of known content for the envmap tests (test support,
// not part of the library): any layout filled with a function of direction at its texel centres.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "envmap/environment_map.h"

namespace footprint::test {

// The images of `layout` (cube: 6 faces; paraboloid: front, back; otherwise one) with `size` texels
// per face side (lat-long: 2·size × size), texel (x, y) of face f = value(unit direction of its
// centre, out), the direction computed in precision T (float, or double for reference tests).
template <class T = float, class F>
std::vector<Image> env_images(EnvLayout layout, int size, int channels, F&& value) {
    const int faces = face_count(layout);
    const int width = layout == EnvLayout::latlong ? 2 * size : size;
    std::vector<Image> images;
    for (int f = 0; f < faces; ++f) {
        Image image(width, size, channels);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < width; ++x) {
                const Vec3T<T> r =
                    env_direction(layout, f, (T(x) + T(0.5)) / T(width), (T(y) + T(0.5)) / T(size));
                value(r / std::sqrt(dot(r, r)), image.at(x, y));
            }
        images.push_back(std::move(image));
    }
    return images;
}

inline EnvironmentMap env_map_from_images(EnvLayout layout, const std::vector<Image>& images) {
    switch (layout) {
        case EnvLayout::cube:
            return std::move(EnvironmentMap::from_cube_faces(
                                 {images[0], images[1], images[2], images[3], images[4], images[5]})
                                 .value());
        case EnvLayout::latlong:
            return std::move(EnvironmentMap::from_latlong(images[0]).value());
        case EnvLayout::sphere:
            return std::move(EnvironmentMap::from_sphere(images[0]).value());
        case EnvLayout::paraboloid:
            return std::move(EnvironmentMap::from_paraboloid(images[0], images[1]).value());
    }
    return {};
}

// A one-channel map of `layout` holding value(r̂).
template <class F>
EnvironmentMap env_map(EnvLayout layout, int size, F&& value) {
    return env_map_from_images(
        layout, env_images(layout, size, 1, [&](Vec3 r, float* out) { *out = value(r); }));
}

// A one-channel map of independent uniform noise per texel (σ = 0.29): the hardest content for
// continuity tests, since neighbouring texels are unrelated.
inline EnvironmentMap env_noise_map(EnvLayout layout, int size, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, 1);
    return env_map_from_images(
        layout, env_images(layout, size, 1, [&](Vec3, float* out) { *out = u(rng); }));
}

// The ray differentials of a footprint of angular radius `angle` (radians) around r: two
// orthogonal tangent vectors of length `angle` (an isotropic footprint on the sphere).
inline void isotropic_differentials(Vec3 r, float angle, Vec3& dr_dx, Vec3& dr_dy) {
    Vec3 u, v;
    tangent_basis(normalize(r), u, v);
    dr_dx = angle * u;
    dr_dy = angle * v;
}

inline constexpr EnvLayout kAllEnvLayouts[] = {EnvLayout::cube, EnvLayout::latlong,
                                               EnvLayout::sphere, EnvLayout::paraboloid};

inline const char* layout_name(EnvLayout layout) {
    return env_layout_name(layout);
}

}  // namespace footprint::test
