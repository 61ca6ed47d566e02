#include "render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>

#include "bump/local_frame.h"
#include "envmap/env_footprint.h"
#include "math/sample_patterns.h"
#include "render/bump_frame.h"
#include "render/camera.h"
#include "scene/ray_differentials.h"
#include "shading/blinn_phong.h"

namespace footprint {

namespace {

constexpr int kTileSize = 16;

constexpr FilterMode kAllModes[] = {FilterMode::bilinear,  FilterMode::trilinear,
                                    FilterMode::fa,        FilterMode::fa_rough,
                                    FilterMode::ewa_rough, FilterMode::reference};

using Rgb = std::array<float, 3>;

Vec3 to_float(Vec3d v) {
    return vec3_cast<float>(v);
}
std::array<float, 3> to_array(Vec3 v) {
    return {v.x, v.y, v.z};
}

// What one mode does at every lookup.
struct ModePolicy {
    bool filtered = true;    // use the ray differentials (false: finest-level bilinear)
    bool roughness = false;  // the roughness pyramid enters the env footprint and the highlights
    bool sample_micro_roughness = false;  // reference: micro-roughness as random slopes
    LookupOptions lookup;
};

ModePolicy policy_of(FilterMode mode) {
    ModePolicy policy;
    switch (mode) {
        case FilterMode::bilinear:
            policy.filtered = false;
            policy.lookup.filter = TextureFilter::bilinear;
            break;
        case FilterMode::reference:
            policy.filtered = false;
            policy.sample_micro_roughness = true;
            policy.lookup.filter = TextureFilter::bilinear;
            break;
        case FilterMode::trilinear:
            policy.lookup.filter = TextureFilter::trilinear;
            break;
        case FilterMode::fa:
            policy.lookup.filter = TextureFilter::footprint_assembly;
            break;
        case FilterMode::fa_rough:
            policy.roughness = true;
            policy.lookup.filter = TextureFilter::footprint_assembly;
            break;
        case FilterMode::ewa_rough:
            policy.roughness = true;
            policy.lookup.filter = TextureFilter::ewa;
            break;
    }
    return policy;
}

// A standard normal pair from two uniforms (Box–Muller).
Vec2d gaussian_pair(double u1, double u2) {
    const double r = std::sqrt(-2.0 * std::log(std::max(u1, 1e-12)));
    const double phi = 2.0 * std::numbers::pi * u2;
    return {r * std::cos(phi), r * std::sin(phi)};
}

// The per-sample state of the shading code.
class SampleShader {
  public:
    SampleShader(const RenderScene& scene, const RenderOptions& options)
        : scene_(scene),
          textures_(scene.textures()),
          options_(options),
          policy_(policy_of(options.filter)) {}

    // The colour seen along one camera ray; `random` = two uniforms for the micro-roughness.
    Rgb shade(const RayDifferential& ray, Vec2d random) {
        const std::optional<SceneHit> hit = scene_.intersect(ray.ray, 1e-9, INFINITY);
        if (!hit) return background(ray);
        return shade_hit(ray, *hit, random);
    }

    std::uint64_t lookups = 0;

  private:
    Rgb background(const RayDifferential& ray) {
        const RenderEnvironment* env = scene_.environment();
        if (!env) {
            const Vec3 b = scene_.desc().background;
            return {b.x, b.y, b.z};
        }
        ++lookups;
        Rgb out{};
        if (policy_.filtered) {
            static_cast<void>(textures_.environment(
                env->map, to_float(ray.ray.direction), to_float(ray.dddx), to_float(ray.dddy),
                EnvLookupOptions{policy_.lookup, env->rotation}, out));
        } else {
            static_cast<void>(textures_.environment_sample(
                env->map, env->rotation * to_float(ray.ray.direction), out));
        }
        return out;
    }

    Rgb shade_hit(const RayDifferential& ray, const SceneHit& hit, Vec2d random);

    // The scene's maps are valid once prepared (prepare_render_scene() checked them), so the
    // lookups' Status is not looked at: only a tiled texture's tile that cannot be read fails, and
    // that gives kMissing here and is reported by the texture system's take_errors().
    static constexpr float kMissing[3] = {0, 0, 0};

    const RenderScene& scene_;
    TextureSystem& textures_;
    const RenderOptions& options_;
    ModePolicy policy_;
};

float schlick_fresnel(float f0, float cos_theta) {
    const float c = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
    const float c2 = c * c;
    return f0 + (1.0f - f0) * c2 * c2 * c;
}

Rgb SampleShader::shade_hit(const RayDifferential& ray, const SceneHit& hit, Vec2d random) {
    const SurfaceHit& s = hit.surface;
    const RenderMaterial& material = *hit.material;
    const MaterialDesc& desc = material.desc;

    // Ray differentials → texture coordinates and their derivatives. (s, t) = (u, 1 − v), wrapped
    // in double before rounding (uv grows without bound on an infinite plane).
    SurfaceDifferentials diff{};
    if (policy_.filtered) diff = surface_differentials(ray, s);
    TextureCoords coords;
    const double t_coord = 1.0 - s.uv.y;
    coords.s = static_cast<float>(s.uv.x - std::floor(s.uv.x));
    coords.t = static_cast<float>(t_coord - std::floor(t_coord));
    if (diff.valid) {
        coords.dsdx = static_cast<float>(diff.duvdx.x);
        coords.dtdx = static_cast<float>(-diff.duvdx.y);
        coords.dsdy = static_cast<float>(diff.duvdy.x);
        coords.dtdy = static_cast<float>(-diff.duvdy.y);
    }

    Rgb base{desc.base_color.x, desc.base_color.y, desc.base_color.z};
    if (material.base_color_map) {
        Rgb texel;
        static_cast<void>(
            textures_.texture(material.base_color_map, coords, policy_.lookup, texel, kMissing));
        ++lookups;
        if (material.base_color_grey) texel[1] = texel[2] = texel[0];
        for (int c = 0; c < 3; ++c) base[c] *= texel[c];
    }

    // Bump: mean slope b and roughness K_b of the filtered region (spec §5.4).
    Vec2 slope;
    Sym2 roughness = material.micro_roughness;
    if (material.bump) {
        SlopeStatistics stats;
        const BumpLookupOptions bump_options(policy_.lookup, material.bump_strength,
                                             material.bump_micro_roughness);
        static_cast<void>(textures_.bump(material.bump, coords, bump_options, &stats));
        ++lookups;
        slope = stats.mean;
        roughness = stats.covariance;
    }
    if (policy_.sample_micro_roughness && desc.micro_roughness > 0) {
        const Vec2d z = gaussian_pair(random.x, random.y);
        slope =
            slope + desc.micro_roughness * Vec2{static_cast<float>(z.x), static_cast<float>(z.y)};
    }
    if (!policy_.roughness) roughness = Sym2{};

    // A frame is needed wherever there are slopes: a bump map or micro-roughness.
    const bool bumped = material.bump != nullptr || desc.micro_roughness > 0;
    BumpFrameAtHit frame{};
    if (bumped) frame = bump_frame(desc.bump, hit);
    const Vec2 b_t = frame.slope_sign * slope;

    // Face the viewer: a surface seen from behind is shaded as its mirror image (n, ∂n and the
    // tangent frame negated, so n_m = −(n + T b)).
    Vec3 n = to_float(s.n), dndx = to_float(diff.dndx), dndy = to_float(diff.dndy);
    const Vec3 v = to_float(ray.ray.origin - s.p);  // surface → eye
    const Vec3 v_hat = normalize(v);
    const Vec3 facing = to_float(s.geometric_normal);
    if (dot(facing, v) < 0) {
        n = -n, dndx = -dndx, dndy = -dndy;
        frame.frame.t1 = -frame.frame.t1, frame.frame.t2 = -frame.frame.t2;
    }
    Vec3 n_m = bumped ? perturbed_normal(n, frame.frame, b_t) : n;
    Vec3 n_hat = normalize(n_m);
    if (dot(n_hat, v_hat) <= 0) n_hat = n;  // a slope tilted past the viewer: drop it (spec §4)
    if (dot(n_hat, v_hat) <= 0) n_hat = v_hat;

    Rgb color{0, 0, 0};
    // Lights: Lambert + Blinn-Phong (rough in the rough modes).
    Vec3 e1, e2;
    tangent_basis(n_hat, e1, e2);
    const Sym2 k_e = bumped && policy_.roughness
                         ? covariance_in_frame(roughness, frame.frame, e1, e2)
                         : roughness;
    const RoughShadingModel model =
        policy_.roughness ? RoughShadingModel::gaussian : RoughShadingModel::plain;
    const Vec3 p = to_float(s.p);
    for (const LightDesc& light : scene_.desc().lights) {
        Vec3 l;
        float scale = 1;
        if (light.type == LightType::directional) {
            l = normalize(-to_float(light.direction));
        } else {
            const Vec3 d = to_float(light.position) - p;
            const float d2 = dot(d, d);
            if (!(d2 > 0)) continue;
            l = d / std::sqrt(d2);
            scale = 1.0f / d2;
        }
        const float cos_l = dot(n_hat, l);
        if (cos_l <= 0) continue;
        const Vec3 h = normalize(l + v_hat);
        const float spec =
            desc.specular > 0
                ? desc.specular * specular(model, to_array(n_hat), to_array(e1), to_array(e2),
                                           to_array(h), k_e, desc.shininess)
                : 0.0f;
        const float diffuse = desc.diffuse * cos_l;
        const float rgb[3] = {light.color.x, light.color.y, light.color.z};
        for (int c = 0; c < 3; ++c) color[c] += scale * rgb[c] * (diffuse * base[c] + spec);
    }

    const RenderEnvironment* env = scene_.environment();
    if (env && desc.diffuse > 0) {
        for (int c = 0; c < 3; ++c) color[c] += desc.diffuse * base[c] * env->mean[c];
    }
    if (env && desc.mirror > 0) {
        Rgb texel;
        if (policy_.filtered) {
            ReflectionGeometry geometry;
            geometry.v = v;
            geometry.dv_dx = -to_float(diff.dpdx);  // the eye is fixed: ∂v = −∂p
            geometry.dv_dy = -to_float(diff.dpdy);
            geometry.n = n;
            geometry.dn_dx = dndx;
            geometry.dn_dy = dndy;
            if (bumped) {
                geometry.bump_slope = b_t;
                geometry.t1 = frame.frame.t1;
                geometry.t2 = frame.frame.t2;
                geometry.roughness = roughness_factor(roughness);
            }
            EnvFootprintOptions env_options;
            env_options.kappa = options_.kappa;
            env_options.rotation = env->rotation;
            const EnvFootprint footprint =
                compute_env_footprint(env->layout, env->texel_scale, geometry, env_options);
            static_cast<void>(textures_.environment(env->map, footprint, policy_.lookup, texel));
        } else {
            const Vec3 r = 2.0f * dot(n_hat, v_hat) * n_hat - v_hat;
            static_cast<void>(textures_.environment_sample(env->map, env->rotation * r, texel));
        }
        ++lookups;
        const float fresnel = desc.mirror * schlick_fresnel(desc.fresnel_f0, dot(n_hat, v_hat));
        for (int c = 0; c < 3; ++c) color[c] += fresnel * texel[c];
    }
    return color;
}

// R2 quasi-random offsets (Roberts 2018), Cranley–Patterson rotated per pixel.
constexpr double kR2a = 0.7548776662466927, kR2b = 0.5698402909980532;

std::uint32_t pixel_seed(int x, int y, std::uint32_t seed) {
    return hash32(seed ^ hash32(static_cast<std::uint32_t>(y) ^
                                hash32(static_cast<std::uint32_t>(x) + 0x9e3779b9u)));
}

CameraDesc view_camera(const SceneDesc& scene, const RenderOptions& options) {
    if (options.frame_count < 1) return scene.camera;
    return camera_for_frame(scene, options.frame, options.frame_count);
}

// What a tile counts of its pixels' samples.
struct SampleCounts {
    std::uint64_t non_finite_samples = 0, non_finite_pixels = 0;
};

// The mean of the pixel's finite samples (0 if none is finite).
Rgb render_pixel_with(SampleShader& shader, const PinholeCamera& camera,
                      const RenderOptions& options, int x, int y, SampleCounts& counts) {
    const int n = std::max(1, options.spp);
    const bool centre_only = n == 1 && options.filter != FilterMode::reference;
    const std::uint32_t seed = pixel_seed(x, y, options.seed);
    const double rot_x = unit_float(hash32(seed)), rot_y = unit_float(hash32(seed + 1));
    const double differential_scale = 1.0 / std::sqrt(static_cast<double>(n));
    double sum[3] = {0, 0, 0};
    int kept = 0;
    for (int k = 0; k < n; ++k) {
        double ox = 0, oy = 0;
        if (!centre_only) {
            const double ux = std::fmod(rot_x + kR2a * (k + 0.5), 1.0);
            const double uy = std::fmod(rot_y + kR2b * (k + 0.5), 1.0);
            ox = gaussian_pixel_offset(ux), oy = gaussian_pixel_offset(uy);
        }
        RayDifferential ray = camera.ray(x + 0.5 + ox, y + 0.5 + oy);
        ray.dodx = differential_scale * ray.dodx, ray.dody = differential_scale * ray.dody;
        ray.dddx = differential_scale * ray.dddx, ray.dddy = differential_scale * ray.dddy;
        const std::uint32_t h = hash32(seed + 2 + static_cast<std::uint32_t>(k));
        const Rgb c = shader.shade(ray, {unit_float(h), unit_float(hash32(h))});
        if (!(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]))) {
            ++counts.non_finite_samples;
            continue;
        }
        for (int i = 0; i < 3; ++i) sum[i] += c[i];
        ++kept;
    }
    if (kept == 0) {
        ++counts.non_finite_pixels;
        return {0, 0, 0};
    }
    return {static_cast<float>(sum[0] / kept), static_cast<float>(sum[1] / kept),
            static_cast<float>(sum[2] / kept)};
}

}  // namespace

std::optional<FilterMode> parse_filter_mode(std::string_view name) {
    for (FilterMode mode : kAllModes) {
        if (name == filter_mode_name(mode)) return mode;
    }
    return std::nullopt;
}

const char* filter_mode_name(FilterMode mode) {
    switch (mode) {
        case FilterMode::bilinear:
            return "bilinear";
        case FilterMode::trilinear:
            return "trilinear";
        case FilterMode::fa:
            return "fa";
        case FilterMode::fa_rough:
            return "fa-rough";
        case FilterMode::ewa_rough:
            return "ewa-rough";
        case FilterMode::reference:
            return "reference";
    }
    return "?";
}

std::span<const FilterMode> all_filter_modes() {
    return kAllModes;
}

Image interior_mask(const RenderScene& scene) {
    const SceneDesc& desc = scene.desc();
    const PinholeCamera camera(desc.camera, desc.width, desc.height);
    Image mask(desc.width, desc.height, 1, 0.0f);
    constexpr double kReach = 1.5;
    const double offsets[3] = {-kReach, 0, kReach};
    for (int y = 0; y < desc.height; ++y) {
        for (int x = 0; x < desc.width; ++x) {
            int object = -2;
            bool same = true;
            for (double dy : offsets) {
                for (double dx : offsets) {
                    const RayDifferential ray = camera.ray(x + 0.5 + dx, y + 0.5 + dy);
                    const std::optional<SceneHit> hit = scene.intersect(ray.ray, 1e-9, INFINITY);
                    const int id = hit ? hit->surface.object : -1;
                    if (object == -2) object = id;
                    same = same && id == object && id >= 0;
                }
            }
            mask.at(x, y, 0) = same ? 1.0f : 0.0f;
        }
    }
    return mask;
}

int render_tile_count(int width, int height) {
    return ((width + kTileSize - 1) / kTileSize) * ((height + kTileSize - 1) / kTileSize);
}

Image render(const RenderScene& scene, const RenderOptions& options, RenderStats* stats,
             const std::function<void()>& tile_done) {
    const auto start = std::chrono::steady_clock::now();
    const int width = scene.desc().width, height = scene.desc().height;
    const PinholeCamera camera(view_camera(scene.desc(), options), width, height);
    Image image(width, height, 3);
    const int tiles_x = (width + kTileSize - 1) / kTileSize;
    const int tiles = render_tile_count(width, height);
    std::atomic<std::uint64_t> lookups{0}, non_finite_samples{0}, non_finite_pixels{0};
    auto render_tiles = [&] {
        tbb::parallel_for(
            tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) {
                for (int tile = r.begin(); tile != r.end(); ++tile) {
                    SampleShader shader(scene, options);
                    SampleCounts counts;
                    const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
                    for (int y = y0; y < std::min(height, y0 + kTileSize); ++y) {
                        for (int x = x0; x < std::min(width, x0 + kTileSize); ++x) {
                            const Rgb c = render_pixel_with(shader, camera, options, x, y, counts);
                            std::copy(c.begin(), c.end(), image.at(x, y));
                        }
                    }
                    lookups += shader.lookups;
                    non_finite_samples += counts.non_finite_samples;
                    non_finite_pixels += counts.non_finite_pixels;
                    if (tile_done) tile_done();
                }
            });
    };
    if (options.threads > 0) {
        tbb::task_arena arena(options.threads);
        arena.execute(render_tiles);
    } else {
        render_tiles();
    }
    if (stats) {
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->pixels = static_cast<std::uint64_t>(width) * height;
        stats->samples = stats->pixels * static_cast<std::uint64_t>(std::max(1, options.spp));
        stats->lookups = lookups;
        stats->non_finite_samples = non_finite_samples;
        stats->non_finite_pixels = non_finite_pixels;
    }
    return image;
}

}  // namespace footprint
