#include "envmap/env_reference.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "envmap/env_layout.h"

namespace footprint {

namespace {

// A unit vector ⟂ unit n (any one).
Vec3d perpendicular(Vec3d n) {
    Vec3d u, v;
    tangent_basis(n, u, v);
    return u;
}

// Level-0 texels per unit step of the node coordinate along `axis` at the (unnormalised) node
// direction q: |S J_P(q) axis|. J_P is homogeneous of degree −1 and J_P q = 0, so J_P(q) axis is
// exactly the derivative of P(normalize(r̂ + a·axis1 + b·axis2)) along a (or b) at that node.
double texels_per_step(EnvLayout layout, Vec2d texel_scale, Vec3d q, Vec3d axis) {
    const Jacobian23d j = env_jacobian(layout, q);
    return std::hypot(texel_scale.x * dot(j.ds, axis), texel_scale.y * dot(j.dt, axis));
}

// Odd node count and step for one axis of the grid over [−cutoff, cutoff] (see the header).
struct AxisGrid {
    int count = 1;
    double step = 0;
};

AxisGrid axis_grid(double texels_per_sigma, const EnvReferenceOptions& options) {
    constexpr double kMaxStepInSigmas = 0.5;  // at least two nodes per σ
    if (!(texels_per_sigma > 0) || !(options.cutoff_sigma > 0)) return {};
    double step = kMaxStepInSigmas;
    if (std::isfinite(texels_per_sigma))
        step = std::min(step, options.step_texels / texels_per_sigma);
    const int max_half = std::max(0, (options.max_samples_per_axis - 1) / 2);
    const double half = std::ceil(options.cutoff_sigma / step);
    const int half_count = static_cast<int>(std::min<double>(half, max_half));
    if (half_count == 0) return {};
    return {2 * half_count + 1, options.cutoff_sigma / half_count};
}

}  // namespace

SphereGaussian sphere_gaussian_from_ray_differentials(Vec3d r, Vec3d dr_dx, Vec3d dr_dy) {
    const Vec3d spread[2] = {dr_dx, dr_dy};
    return sphere_gaussian_from_spread(r, spread);
}

SphereGaussian sphere_gaussian_from_spread(Vec3d r, std::span<const Vec3d> spread) {
    SphereGaussian g;
    const double length_r = length(r);
    if (!is_finite(r) || !(length_r > 0)) return g;  // direction +z, a point
    const Vec3d n = r / length_r;
    g.direction = n;
    for (const Vec3d& s : spread) {
        if (!is_finite(s)) return g;
    }
    // Σ = ¼ Σ_i s_i s_iᵀ on the unit sphere (P s_i / |r|), in a tangent basis (u, v) at n,
    // principal axes by the robust form of spec §2.7.
    const Vec3d u = perpendicular(n), v = cross(n, u);
    double k11 = 0, k12 = 0, k22 = 0;
    for (const Vec3d& s : spread) {
        const double a = dot(s, u) / length_r, b = dot(s, v) / length_r;
        k11 += 0.25 * a * a, k12 += 0.25 * a * b, k22 += 0.25 * b * b;
    }
    const double w = std::hypot(k11 - k22, 2 * k12);
    const double major_sq = 0.5 * (k11 + k22 + w);
    if (!(major_sq > 0) || !std::isfinite(major_sq)) return g;
    const double minor_sq = std::max(0.0, k11 * k22 - k12 * k12) / major_sq;
    double e0 = k11 >= k22 ? k11 - k22 + w : 2 * k12;
    double e1 = k11 >= k22 ? 2 * k12 : k22 - k11 + w;
    const double e_length = std::hypot(e0, e1);
    if (e_length > 0) {
        e0 /= e_length, e1 /= e_length;
    } else {
        e0 = 1, e1 = 0;
    }
    const Vec3d major_direction = e0 * u + e1 * v, minor_direction = -e1 * u + e0 * v;
    g.axis1 = std::sqrt(major_sq) * major_direction;
    g.axis2 = std::sqrt(minor_sq) * minor_direction;
    return g;
}

void environment_reference(const EnvironmentMap& map, const SphereGaussian& footprint, float* out,
                           const EnvReferenceOptions& options) {
    const int channels = map.channels();
    Vec3d centre = normalize(footprint.direction);
    if (centre.x == 0 && centre.y == 0 && centre.z == 0) centre = kEnvFallbackDirection<double>;
    // The axes, projected onto the tangent plane (P = I − r̂r̂ᵀ); non-finite axes give a point.
    Vec3d axes[2] = {footprint.axis1, footprint.axis2};
    for (Vec3d& axis : axes) axis = is_finite(axis) ? axis - dot(axis, centre) * centre : Vec3d{};

    // Texels per σ along each axis: the largest over a 5×5 lattice of the grid's square (the
    // centre, the boundary and between), so that the step holds where the map is finest.
    const Vec2 scale_float = map.texel_scale();
    const Vec2d texel_scale{scale_float.x, scale_float.y};
    double texels_per_sigma[2] = {0, 0};
    for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
            const double a = 0.5 * i * options.cutoff_sigma, b = 0.5 * j * options.cutoff_sigma;
            const Vec3d q = centre + a * axes[0] + b * axes[1];
            for (int k = 0; k < 2; ++k)
                if (length(axes[k]) > 0)
                    texels_per_sigma[k] =
                        std::max(texels_per_sigma[k],
                                 texels_per_step(map.layout(), texel_scale, q, axes[k]));
        }
    const AxisGrid grid[2] = {axis_grid(texels_per_sigma[0], options),
                              axis_grid(texels_per_sigma[1], options)};

    // Separable Gaussian weights over the symmetric nodes.
    std::vector<double> weights[2];
    for (int k = 0; k < 2; ++k) {
        weights[k].resize(grid[k].count);
        const int half = grid[k].count / 2;
        for (int i = 0; i < grid[k].count; ++i) {
            const double a = (i - half) * grid[k].step;
            weights[k][i] = std::exp(-0.5 * a * a);
        }
    }

    double sum[MipPyramid::kMaxChannels] = {};
    double weight_sum = 0;
    float sample[MipPyramid::kMaxChannels];
    for (int j = 0; j < grid[1].count; ++j) {
        const double b = (j - grid[1].count / 2) * grid[1].step;
        for (int i = 0; i < grid[0].count; ++i) {
            const double a = (i - grid[0].count / 2) * grid[0].step;
            const double w = weights[0][i] * weights[1][j];
            const Vec3d d = normalize(centre + a * axes[0] + b * axes[1]);
            environment_bilinear(map, vec3_cast<float>(d), 0, sample);
            for (int c = 0; c < channels; ++c) sum[c] += w * sample[c];
            weight_sum += w;
        }
    }
    for (int c = 0; c < channels; ++c) out[c] = static_cast<float>(sum[c] / weight_sum);
}

}  // namespace footprint
