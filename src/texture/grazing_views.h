// texture/grazing_views.h — test support: procedural textures on a grazing plane, rendered as the
// renderer renders them (render/sample_shader.cpp), for the band limit's held-out check
// (ProceduralGrazing) and its fitting tool's sweep (bench/fit-procedural-band-limit.cpp).
//
// A plane y = 0 seen from a camera 1 unit above it, its view direction at `angle` from the normal
// at the image's centre: one band-limited sample at the pixel's centre with the ray's
// differentials, or point samples at R2 points warped to the σ = ½-pixel Gaussian pixel filter,
// rotated per pixel (the reference mode).
#pragma once

#include <cmath>
#include <cstdint>

#include "math/sample_patterns.h"
#include "texture/procedural.h"

namespace footprint::test {

struct GrazingView {
    double angle, scale, fov;  // degrees from the normal, lattice cells per unit, vertical degrees
    int width, height;
};

struct GrazingCamera {
    Vec3d forward, right{1, 0, 0}, up;
    double pixel;  // the image plane's pixel size at distance 1
    int width, height;
    explicit GrazingCamera(const GrazingView& v) : width(v.width), height(v.height) {
        constexpr double kDegree = 3.14159265358979323846 / 180;
        forward = {0, -std::cos(v.angle * kDegree), -std::sin(v.angle * kDegree)};
        up = cross(right, forward);
        pixel = 2 * std::tan(0.5 * v.fov * kDegree) / v.height;
    }
    // The plane's point through image point (x, y) (pixels, y down) and its derivatives along x
    // and y; false above the horizon.
    bool hit(double x, double y, Vec3d& p, Vec3d& dpdx, Vec3d& dpdy) const {
        const Vec3d d =
            forward + (x - 0.5 * width) * pixel * right - (y - 0.5 * height) * pixel * up;
        if (!(d.y < -1e-9)) return false;
        const double t = 1 / -d.y;
        p = Vec3d{0, 1, 0} + t * d;
        const Vec3d ddx = pixel * right, ddy = -pixel * up;
        dpdx = t * (ddx - (ddx.y / d.y) * d);
        dpdy = t * (ddy - (ddy.y / d.y) * d);
        return true;
    }
};

// The mean of n point samples of the pixel (x, y); false where one misses the plane.
inline bool supersampled_value(const ProceduralTexture& texture, const GrazingCamera& camera, int x,
                               int y, int n, std::uint32_t salt, double& out) {
    constexpr double kR2a = 0.7548776662466927, kR2b = 0.5698402909980532;
    const std::uint32_t seed =
        hash32(static_cast<std::uint32_t>(x) * 9781u + static_cast<std::uint32_t>(y) * 6271u) ^
        salt;
    const double rx = unit_float(hash32(seed)), ry = unit_float(hash32(seed + 1));
    double sum = 0;
    for (int k = 0; k < n; ++k) {
        Vec3d p, a, b;
        if (!camera.hit(x + 0.5 + gaussian_pixel_offset(std::fmod(rx + kR2a * (k + 0.5), 1.0)),
                        y + 0.5 + gaussian_pixel_offset(std::fmod(ry + kR2b * (k + 0.5), 1.0)), p,
                        a, b))
            return false;
        sum += procedural_value(texture, p);
    }
    out = sum / n;
    return true;
}

// RMSE of v against `reference_spp` point samples: of the band-limited value at one sample per
// pixel and of 16 point samples, over the pixels whose samples all hit the plane.
struct GrazingError {
    double filtered = 0, sixteen = 0;
    int pixels = 0;
};
inline GrazingError grazing_error(const ProceduralTexture& texture, const GrazingView& view,
                                  int reference_spp) {
    const GrazingCamera camera(view);
    double filtered_sq = 0, sixteen_sq = 0;
    int pixels = 0;
    for (int y = 0; y < view.height; ++y)
        for (int x = 0; x < view.width; ++x) {
            double truth = 0, sixteen = 0;
            if (!supersampled_value(texture, camera, x, y, reference_spp, 0x9e3779b9u, truth))
                continue;
            supersampled_value(texture, camera, x, y, 16, 0x85ebca6bu, sixteen);
            Vec3d p, a, b;
            camera.hit(x + 0.5, y + 0.5, p, a, b);
            const double filtered = procedural_value(texture, p, a, b);
            filtered_sq += (filtered - truth) * (filtered - truth);
            sixteen_sq += (sixteen - truth) * (sixteen - truth);
            ++pixels;
        }
    if (pixels == 0) return {};
    return {std::sqrt(filtered_sq / pixels), std::sqrt(sixteen_sq / pixels), pixels};
}

}  // namespace footprint::test
