#include "render/sample_shader.h"

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>

#include "bump/local_frame.h"
#include "core/parallel.h"
#include "envmap/env_footprint.h"
#include "math/sample_patterns.h"
#include "shading/blinn_phong.h"
#include "shading/fresnel.h"
#include "shading/microfacet.h"
#include "texture/footprint_assembly.h"

namespace footprint::detail {

namespace {

Vec3 to_float(Vec3d v) {
    return vec3_cast<float>(v);
}

// How far a shadow ray starts off the surface: beyond the rounding of a float hit point (the
// GPU's geometry and Embree's triangles are float) at the hit's distance from the eye and from
// the origin, so that the surface never shadows itself; gpu/shaders/shading.glsl's twin.
constexpr double kShadowBias = 1e-4;
Vec3d shadow_origin(const SurfaceHit& s, Vec3d eye) {
    const Vec3d ng =
        dot(s.geometric_normal, eye - s.p) < 0 ? -s.geometric_normal : s.geometric_normal;
    return s.p + kShadowBias * (1 + length(s.p - eye) + length(s.p)) * ng;
}

std::array<float, 3> to_array(Vec3 v) {
    return {v.x, v.y, v.z};
}

// A standard normal pair from two uniforms (Box–Muller).
Vec2d gaussian_pair(double u1, double u2) {
    const double r = std::sqrt(-2.0 * std::log(std::max(u1, 1e-12)));
    const double phi = 2.0 * std::numbers::pi * u2;
    return {r * std::cos(phi), r * std::sin(phi)};
}

// ∂(n̂·v̂)/∂b at the point's mean slope: n_m = n + |n| T (σ b) (σ the frame's slope sign), so
// ∂(n̂_m·v̂)/∂b = σ |n|/|n_m| Tᵀ(v̂ − (n̂_m·v̂) n̂_m).
Vec2 cos_slope_gradient(const SurfacePoint& point, Vec3 n_hat, Vec3 v_hat) {
    const Vec3 n_m =
        perturbed_normal(point.n, point.frame.frame, point.frame.slope_sign * point.slope);
    const float scale = point.frame.slope_sign * length(point.n) / length(n_m);
    const Vec3 tangential = v_hat - dot(n_hat, v_hat) * n_hat;
    const Vec2 gradient{scale * dot(point.frame.frame.t1, tangential),
                        scale * dot(point.frame.frame.t2, tangential)};
    return is_finite(gradient) ? gradient : Vec2{};
}
// The scene's maps are valid once prepared (prepare_render_scene() checked them), so the lookups'
// Status is not looked at: only a tiled texture's tile that cannot be read fails, and that gives
// kMissing here and is reported by the texture system's take_errors().
constexpr float kMissing[3] = {0, 0, 0};

constexpr int kTileSize = 16;

// The peers' texture filter: a GPU's anisotropic filtering, up to 16 trilinear probes along the
// major axis placed by EXT_texture_filter_anisotropic's rule.
LookupOptions gpu_anisotropic() {
    LookupOptions options;
    options.filter = TextureFilter::footprint_assembly;
    options.probe_rule = ProbeRule::ext;
    options.max_probes = 16;
    return options;
}

// A map's size (zero if the texture system cannot say: level0_size() then takes 1 × 1).
template <class Handle>
TextureInfo info_of(TextureSystem& textures, Handle* map) {
    const Result<TextureInfo> info = textures.info(map);
    return info ? *info : TextureInfo{};
}

// The seed of a sample's stream of draws, from its two uniforms (24 bits each, sample_ray()).
std::uint32_t stream_seed(Vec2d random) {
    const auto bits = [](double u) { return static_cast<std::uint32_t>(u * 16777216.0); };
    return hash32(bits(random.x) ^ hash32(bits(random.y) + 1));
}

// Below this share of slopes facing away from the eye their second lookup is not worth it.
constexpr float kFacingAwayThreshold = 1e-3f;

// R2 quasi-random offsets (Roberts 2018), Cranley–Patterson rotated per pixel.
constexpr double kR2a = 0.7548776662466927, kR2b = 0.5698402909980532;

std::uint32_t pixel_seed(int x, int y, std::uint32_t seed) {
    return hash32(seed ^ hash32(static_cast<std::uint32_t>(y) ^
                                hash32(static_cast<std::uint32_t>(x) + 0x9e3779b9u)));
}

}  // namespace

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
            policy.lookup.ewa_beyond_probes = true;
            break;
        case FilterMode::fa_rough:
            policy.roughness = policy.fresnel_over_slopes = true;
            policy.lookup.filter = TextureFilter::footprint_assembly;
            policy.lookup.ewa_beyond_probes = true;
            break;
        case FilterMode::ewa_rough:
            policy.roughness = policy.fresnel_over_slopes = true;
            policy.lookup.filter = TextureFilter::ewa;
            break;
        case FilterMode::lean:
            policy.roughness = true;
            policy.lookup = gpu_anisotropic();
            break;
        case FilterMode::toksvig:
            policy.roughness = true;
            policy.slopes = SlopeSource::toksvig;
            policy.lookup = gpu_anisotropic();
            break;
        case FilterMode::specular_aa:
            policy.roughness = true;
            policy.slopes = SlopeSource::screen_space;
            policy.lookup = gpu_anisotropic();
            break;
        case FilterMode::stochastic:
            policy.stochastic = policy.sample_micro_roughness = true;
            policy.slopes = SlopeSource::sampled;
            policy.lookup.filter = TextureFilter::trilinear;  // reads the one level it picks
            break;
    }
    return policy;
}

SampleShader::SampleShader(const RenderScene& scene, const RenderOptions& options,
                           int hidden_object)
    : scene_(scene),
      textures_(scene.textures()),
      options_(options),
      policy_(policy_of(options.filter)),
      hidden_object_(hidden_object) {
    // footprint's own footprint assembly (the peers' GPU-style filter keeps its 16).
    if (policy_.lookup.filter == TextureFilter::footprint_assembly &&
        policy_.lookup.probe_rule == ProbeRule::gaussian)
        policy_.lookup.max_probes = std::clamp(options.max_probes, 1, kMaxProbeCount);
}

Rgb SampleShader::background(const RayDifferential& ray) {
    const Vec3 origin = to_float(ray.ray.origin), direction = to_float(ray.ray.direction);
    const RenderEnvironment* env = scene_.environment_at(origin);
    if (!env) {
        const Vec3 b = scene_.desc().background;
        return {b.x, b.y, b.z};
    }
    ++lookups;
    Rgb out{};
    if (policy_.filtered) {
        // A local map's direction from its capture point, the ray differentials moved with it.
        const std::optional<ProxyStep> step =
            env->proxy ? proxy_step(*env->proxy, origin, direction) : std::nullopt;
        const Vec3 d = step ? step->direction : direction;
        const Vec3 dd_dx =
            step ? step->move(to_float(ray.dodx), to_float(ray.dddx)) : to_float(ray.dddx);
        const Vec3 dd_dy =
            step ? step->move(to_float(ray.dody), to_float(ray.dddy)) : to_float(ray.dddy);
        static_cast<void>(textures_.environment(
            env->map, d, dd_dx, dd_dy, EnvLookupOptions{policy_.lookup, env->rotation}, out));
    } else {
        static_cast<void>(textures_.environment_sample(
            env->map, env->rotation * local_direction(*env, origin, direction), out));
    }
    return out;
}

// The direction in which the environment shows what a ray from p along r meets: r itself for a
// map at infinity, else from the local map's capture point to where the ray leaves its proxy.
Vec3 SampleShader::local_direction(const RenderEnvironment& env, Vec3 p, Vec3 r) const {
    if (!env.proxy) return r;
    const std::optional<ProxyStep> step = proxy_step(*env.proxy, p, r);
    return step ? step->direction : r;
}

// A form-(b) footprint of the reflection at `point` moved onto a local map's direction (envmap/
// env_proxy.h): its spreads ∂v_r/∂x, ∂v_r/∂y and roughness columns through ∂d = P ∂p + (t/|r|) P
// ∂r, the pixel's own ∂p added; unchanged for a map at infinity or a ray that does not leave the
// proxy.
EnvFootprint SampleShader::through_proxy(const RenderEnvironment& env, const EnvFootprint& f,
                                         const SurfacePoint& point,
                                         const EnvFootprintOptions& options) const {
    const std::optional<ProxyStep> step =
        env.proxy ? proxy_step(*env.proxy, point.p, f.reflected) : std::nullopt;
    if (!step) return f;
    const Mat3 to_world = env.rotation.transposed();
    const float unkappa = options.kappa != 0 ? 1 / options.kappa : 0;  // the columns hold κ
    return compute_env_footprint(env.layout, env.texel_scale, step->direction,
                                 step->move(to_float(point.diff.dpdx), to_world * f.map_dr_dx),
                                 step->move(to_float(point.diff.dpdy), to_world * f.map_dr_dy),
                                 step->move({}, unkappa * (to_world * f.map_roughness1)),
                                 step->move({}, unkappa * (to_world * f.map_roughness2)), options);
}

// The nearest hit on any object but `hidden_object` (the ray goes on through that one's surfaces).
std::optional<SceneHit> SampleShader::nearest_hit(const Ray& ray, int hidden_object) const {
    constexpr int kMaxPassed = 64;  // surfaces of the hidden object passed through (a mesh's many)
    double t_min = 1e-9;
    for (int i = 0; i < kMaxPassed; ++i) {
        std::optional<SceneHit> hit = scene_.intersect(ray, t_min, INFINITY);
        if (!hit || hit->surface.object != hidden_object) return hit;
        t_min = hit->surface.t * (1 + 1e-9) + 1e-9;
    }
    return std::nullopt;
}

std::optional<SurfacePoint> SampleShader::trace(const RayDifferential& ray, Vec2d random,
                                                int hidden_object) {
    const std::optional<SceneHit> hit = nearest_hit(ray.ray, hidden_object);
    if (!hit) return std::nullopt;
    const SurfaceHit& s = hit->surface;
    SurfacePoint point;
    point.material = hit->material;
    point.object = s.object;
    const RenderMaterial& material = *hit->material;
    const MaterialDesc& desc = material.desc;

    // Ray differentials → texture coordinates and their derivatives. (s, t) = (u, 1 − v), wrapped
    // in double before rounding (uv grows without bound on an infinite plane).
    if (policy_.filtered) point.diff = surface_differentials(ray, s);
    const SurfaceDifferentials& diff = point.diff;
    TextureCoords& coords = point.coords;
    const double t_coord = 1.0 - s.uv.y;
    coords.s = static_cast<float>(s.uv.x - std::floor(s.uv.x));
    coords.t = static_cast<float>(t_coord - std::floor(t_coord));
    if (diff.valid) {
        coords.dsdx = static_cast<float>(diff.duvdx.x);
        coords.dtdx = static_cast<float>(-diff.duvdx.y);
        coords.dsdy = static_cast<float>(diff.duvdy.x);
        coords.dtdy = static_cast<float>(-diff.duvdy.y);
    }

    if (material.height_map) parallax_coords(material, s, ray, coords);

    point.random_seed = stream_seed(random);
    RandomStream draws(point.random_seed);
    const Vec3 colour = desc.base_color;
    point.base = desc.base_color_procedural
                     ? procedural_colour(*desc.base_color_procedural,
                                         {colour.x, colour.y, colour.z}, s.p, diff, draws)
                     : this->colour(material.base_color_map, {colour.x, colour.y, colour.z},
                                    material.base_color_grey, coords, draws);
    read_f0(material, coords, draws, point);
    const Sym2 micro =
        material.micro_roughness + Sym2{point.micro_variance, 0, point.micro_variance};  // K_0 here

    // A frame is needed wherever there are slopes: a bump map, a procedural bump or
    // micro-roughness.
    const bool procedural_bump = desc.bump.source == BumpDesc::Source::procedural;
    point.bumped = material.bump != nullptr || procedural_bump || material.has_micro_slopes();
    if (point.bumped) point.frame = bump_frame(desc.bump, *hit);

    // Bump: mean slope b and roughness K_b of the filtered region (spec §5.4).
    point.roughness = material.micro_roughness;
    if (material.bump || procedural_bump) {
        const SlopeStatistics stats =
            procedural_bump
                ? procedural_slopes_at(desc.bump, s.p, diff, point.frame.frame, micro, draws)
                : slopes(material, coords, micro, draws);
        point.slope = stats.mean;
        point.roughness = stats.covariance;
    }
    point.highlight_alpha = desc.roughness * desc.roughness;
    if (material.metallic_roughness()) {
        // Its own α is in K_b (material_model.h); where the mode leaves K_b out, the texel's.
        point.highlight_alpha = policy_.roughness ? 0 : std::sqrt(2 * micro.xx);
    }
    if (policy_.sample_micro_roughness) sample_micro_slopes(material, micro, random, point);
    if (!policy_.roughness) point.roughness = Sym2{};

    // Face the viewer: a surface seen from behind is shaded as its mirror image (n, ∂n and the
    // tangent frame negated, so n_m = −(n + T b)).
    point.p = to_float(s.p);
    point.n = to_float(s.n), point.dndx = to_float(diff.dndx), point.dndy = to_float(diff.dndy);
    point.v = to_float(ray.ray.origin - s.p);
    point.shadow_origin = shadow_origin(s, ray.ray.origin);
    if (dot(to_float(s.geometric_normal), point.v) < 0) {
        point.n = -point.n, point.dndx = -point.dndx, point.dndy = -point.dndy;
        point.frame.frame.t1 = -point.frame.frame.t1, point.frame.frame.t2 = -point.frame.frame.t2;
    }
    return point;
}

// Parallax-occlusion mapping (texture/parallax.h): (s, t) and their derivatives moved to where
// the view ray meets the height map's relief, the heights read as the mode filters (at the level
// the pixel's footprint selects; level 0 where the mode has no footprint), their gradient by
// central differences half a footprint (at least half a texel) apart.
void SampleShader::parallax_coords(const RenderMaterial& material, const SurfaceHit& s,
                                   const RayDifferential& ray, TextureCoords& coords) {
    // (s, t) = (u, 1 − v): ∂p/∂s = ∂p/∂u, ∂p/∂t = −∂p/∂v.
    const Vec2 w = parallax_direction(to_float(ray.ray.origin - s.p), to_float(s.dpdu),
                                      -to_float(s.dpdv), to_float(s.n));
    const auto [width, height] =
        level0_size(material.height_map, [&] { return info_of(textures_, material.height_map); });
    TextureCoords at = coords;
    auto read = [&](Vec2 st) {
        at.s = st.x, at.t = st.y;
        float h = 0;
        static_cast<void>(
            textures_.texture(material.height_map, at, policy_.lookup, {&h, 1}, kMissing));
        ++lookups;
        return h;
    };
    const Vec2 step{0.5f * std::max(std::abs(coords.dsdx) + std::abs(coords.dsdy), 1.0f / width),
                    0.5f * std::max(std::abs(coords.dtdx) + std::abs(coords.dtdy), 1.0f / height)};
    auto gradient = [&](Vec2 st) {
        return Vec2{(read(st + Vec2{step.x, 0}) - read(st - Vec2{step.x, 0})) / (2 * step.x),
                    (read(st + Vec2{0, step.y}) - read(st - Vec2{0, step.y})) / (2 * step.y)};
    };
    const ParallaxResult r =
        parallax_march(read, gradient, {coords.s, coords.t}, {coords.dsdx, coords.dtdx},
                       {coords.dsdy, coords.dtdy}, w, *material.desc.bump.parallax);
    coords.s = r.st.x - std::floor(r.st.x);
    coords.t = r.st.y - std::floor(r.st.y);
    coords.dsdx = r.dst_dx.x, coords.dtdx = r.dst_dx.y;
    coords.dsdy = r.dst_dy.x, coords.dtdy = r.dst_dy.y;
}

// The micro-roughness `micro` (σ² I) as a random slope, in the modes that sample slopes, where
// it is not in a bump map's sampled moments already (stochastic's). A metallic-roughness
// material's tilts the mirror only, its σ² being the highlight's α (SurfacePoint::micro_slope).
void SampleShader::sample_micro_slopes(const RenderMaterial& material, const Sym2& micro,
                                       Vec2d random, SurfacePoint& point) {
    const bool pbr = material.metallic_roughness();
    const bool sampled = material.bump && policy_.slopes == SlopeSource::sampled;
    if (!material.has_micro_slopes() || (sampled && !pbr)) return;
    const float sigma = std::sqrt(micro.xx);
    const Vec2d z = gaussian_pair(random.x, random.y);
    const Vec2 slope = sigma * Vec2{static_cast<float>(z.x), static_cast<float>(z.y)};
    if (pbr) {
        point.micro_slope = slope;
    } else {
        point.slope = point.slope + slope;
    }
}

// A material map's texel at `coords`, filtered as the mode filters (out.size() channels).
void SampleShader::read_map(TextureHandle* map, const TextureCoords& coords, RandomStream& random,
                            std::span<float> out) {
    TextureCoords at = coords;
    if (policy_.stochastic) {
        const auto [width, height] = level0_size(map, [&] { return info_of(textures_, map); });
        at = stochastic_probe(coords, width, height, random);
    }
    static_cast<void>(textures_.texture(map, at, policy_.lookup, out, kMissing));
    ++lookups;
}

// c: a material's colour × its texture.
Rgb SampleShader::colour(TextureHandle* map, Rgb constant, bool grey, const TextureCoords& coords,
                         RandomStream& random) {
    if (!map) return constant;
    Rgb texel;
    read_map(map, coords, random, texel);
    if (grey) texel[1] = texel[2] = texel[0];
    for (int c = 0; c < 3; ++c) constant[c] *= texel[c];
    return constant;
}

// c: a material's colour × its procedural texture at p, band-limited by the footprint in the
// filtered modes, a point value in the others; stochastic filtering's at a point drawn from the
// pixel filter's Gaussian over the footprint, as its texture lookups are.
Rgb SampleShader::procedural_colour(const ProceduralTexture& texture, Rgb constant, Vec3d p,
                                    const SurfaceDifferentials& diff, RandomStream& random) {
    Vec3 c;
    if (policy_.stochastic && diff.valid) {
        const Vec2 z = random.gaussian();
        c = procedural_color(texture,
                             p + 0.5 * double(z.x) * diff.dpdx + 0.5 * double(z.y) * diff.dpdy);
    } else if (policy_.filtered && diff.valid) {
        c = procedural_color(texture, p, diff.dpdx, diff.dpdy);
    } else {
        c = procedural_color(texture, p);
    }
    return {constant[0] * c.x, constant[1] * c.y, constant[2] * c.z};
}

// A procedural bump's b and K_b at p (BumpDesc::Source::procedural): the height h = strength·v,
// b = −∇h in the orthonormal frame (t1, t2), K_b the gradient covariance the band limit removed,
// projected onto it, plus the micro-roughness — in the filtered modes, over the footprint; a
// point's gradient in the others (stochastic filtering's at a point drawn from the pixel filter's
// Gaussian, as its colour's), whose micro-roughness is sampled apart.
SlopeStatistics SampleShader::procedural_slopes_at(const BumpDesc& bump, Vec3d p,
                                                   const SurfaceDifferentials& diff,
                                                   const TangentFrame& frame, const Sym2& micro,
                                                   RandomStream& random) {
    ProceduralSlopes slopes;
    const bool band_limited = policy_.filtered && !policy_.stochastic && diff.valid;
    if (band_limited) {
        slopes = procedural_slopes(bump.procedural, p, diff.dpdx, diff.dpdy);
    } else if (policy_.stochastic && diff.valid) {
        const Vec2 z = random.gaussian();
        slopes = procedural_slopes(
            bump.procedural, p + 0.5 * double(z.x) * diff.dpdx + 0.5 * double(z.y) * diff.dpdy);
    } else {
        slopes = procedural_slopes(bump.procedural, p);
    }
    const double a = bump.strength;
    const Vec3d t1{frame.t1.x, frame.t1.y, frame.t1.z}, t2{frame.t2.x, frame.t2.y, frame.t2.z};
    SlopeStatistics stats;
    stats.mean = {static_cast<float>(-a * dot(slopes.gradient, t1)),
                  static_cast<float>(-a * dot(slopes.gradient, t2))};
    if (!band_limited) return stats;
    const auto& c = slopes.covariance;   // xx, yy, zz, xy, xz, yz
    auto form = [&](Vec3d u, Vec3d v) {  // uᵀ C v
        return u.x * (c[0] * v.x + c[3] * v.y + c[4] * v.z) +
               u.y * (c[3] * v.x + c[1] * v.y + c[5] * v.z) +
               u.z * (c[4] * v.x + c[5] * v.y + c[2] * v.z);
    };
    stats.covariance =
        Sym2{static_cast<float>(a * a * form(t1, t1)), static_cast<float>(a * a * form(t1, t2)),
             static_cast<float>(a * a * form(t2, t2))} +
        micro;
    return stats;
}

// F0 and, from a textured metallic-roughness material's F0 map, the slope variance σ².
void SampleShader::read_f0(const RenderMaterial& material, const TextureCoords& coords,
                           RandomStream& random, SurfacePoint& point) {
    point.f0 = material.f0;
    if (!material.f0_map) return;
    float texel[4];
    read_map(material.f0_map, coords, random, texel);
    for (int c = 0; c < 3; ++c) point.f0[c] = std::clamp(point.f0[c] * texel[c], 0.0f, 1.0f);
    point.micro_variance = std::max(0.0f, texel[3]);
}

// b and K_b where the mode takes them from (SlopeSource).
SlopeStatistics SampleShader::slopes(const RenderMaterial& material, const TextureCoords& coords,
                                     const Sym2& micro, RandomStream& random) {
    switch (policy_.slopes) {
        case SlopeSource::moments:
            return read_moments(material, coords);
        case SlopeSource::toksvig:
            return read_toksvig(material, coords, micro);
        case SlopeSource::screen_space:
            return read_screen_space(material, coords, micro);
        case SlopeSource::sampled:
            return read_sampled(material, coords, micro, random);
    }
    return {};
}

SlopeStatistics SampleShader::read_moments(const RenderMaterial& material,
                                           const TextureCoords& coords) {
    SlopeStatistics stats;
    const BumpLookupOptions options(policy_.lookup, material.bump_strength,
                                    material.bump_micro_roughness);
    static_cast<void>(textures_.bump(material.bump, coords, options, &stats));
    ++lookups;
    return stats;
}

// Toksvig: the filtered unit normals' mean and length, plus the material's micro-roughness (the
// artist's base roughness, which a map of unit normals cannot hold).
SlopeStatistics SampleShader::read_toksvig(const RenderMaterial& material,
                                           const TextureCoords& coords, const Sym2& micro) {
    TextureHandle* normals = scene_.toksvig_normals(material);
    if (!normals) return read_moments(material, coords);  // no map to make them from
    float n[3];
    static_cast<void>(textures_.texture(normals, coords, policy_.lookup, n, kMissing));
    ++lookups;
    SlopeStatistics stats = toksvig_slopes(Vec3{n[0], n[1], n[2]});
    stats.covariance = stats.covariance + micro;
    return stats;
}

// Specular AA: the mean slope here and one pixel step away in x and in y (a GPU quad's
// derivatives), K_b from their differences plus the material's micro-roughness. The bump map's
// own K_b is not used: engines without a roughness pyramid do not have it.
SlopeStatistics SampleShader::read_screen_space(const RenderMaterial& material,
                                                const TextureCoords& coords, const Sym2& micro) {
    const Vec2 b = read_moments(material, coords).mean;
    const auto [dx, dy] = slope_steps(material, coords, b);
    return {b, screen_space_roughness(dx, dy) + micro};
}

// The filtered mean slope's change per pixel step in x and in y, as a GPU quad's derivatives
// take it: its value one step away less `slope`, its value here.
std::pair<Vec2, Vec2> SampleShader::slope_steps(const RenderMaterial& material,
                                                const TextureCoords& coords, Vec2 slope) {
    TextureCoords next_x = coords, next_y = coords;
    next_x.s += coords.dsdx, next_x.t += coords.dtdx;
    next_y.s += coords.dsdy, next_y.t += coords.dtdy;
    return {read_moments(material, next_x).mean - slope,
            read_moments(material, next_y).mean - slope};
}

// Stochastic: the moments of a texel the filter picks, and one slope drawn from them (their
// covariance holds the micro-roughness).
SlopeStatistics SampleShader::read_sampled(const RenderMaterial& material,
                                           const TextureCoords& coords, const Sym2& micro,
                                           RandomStream& random) {
    const auto [width, height] =
        level0_size(material.bump, [&] { return info_of(textures_, material.bump); });
    const TextureCoords probe = stochastic_probe(coords, width, height, random);
    SlopeStatistics moments = read_moments(material, probe);
    if (material.metallic_roughness()) {
        // The texel's own σ² is drawn apart (sample_micro_slopes()): the mirror's alone.
        Sym2& k = moments.covariance;
        k = {std::max(0.0f, k.xx - micro.xx), k.xy - micro.xy, std::max(0.0f, k.yy - micro.yy)};
    }
    return {sample_slope(moments, random.gaussian()), Sym2{}};
}

std::pair<int, int> SampleShader::level0_size(const void* handle,
                                              const std::function<TextureInfo()>& info) {
    auto it = sizes_.find(handle);
    if (it == sizes_.end()) {
        const TextureInfo i = info();
        it = sizes_.emplace(handle, std::pair{std::max(1, i.width), std::max(1, i.height)}).first;
    }
    return it->second;
}

ShadingFactors SampleShader::shade(const SurfacePoint& point) {
    const MaterialDesc& desc = point.material->desc;
    const Vec3 v_hat = normalize(point.v);
    const Vec2 b_t = point.frame.slope_sign * point.slope;
    const Vec3 n_m = point.bumped ? perturbed_normal(point.n, point.frame.frame, b_t) : point.n;
    Vec3 n_hat = normalize(n_m);
    if (dot(n_hat, v_hat) <= 0) n_hat = point.n;  // a slope tilted past the viewer: drop it (§4)
    if (dot(n_hat, v_hat) <= 0) n_hat = v_hat;

    ShadingFactors out;
    out.base = point.base;
    add_lights(point, n_hat, v_hat, out);
    const RenderEnvironment* env = scene_.environment_at(point.p);
    const float ambient = point.material->ambient_weight;
    if (env && ambient > 0) {
        const Vec3 e = irradiance(env->irradiance, n_hat, diffuse_slope_variance(point));
        const float scale = ambient / std::numbers::pi_v<float>;
        out.diffuse[0] += scale * e.x, out.diffuse[1] += scale * e.y, out.diffuse[2] += scale * e.z;
    }
    if (desc.mirror > 0 && reflected_environment(point)) add_reflection(point, n_hat, v_hat, out);
    return out;
}

// The slopes' mean variance about n̂ that averages the environment's diffuse light (irradiance.h):
// K_b's in the rough modes, less a metallic-roughness material's own σ² (its microfacets', which
// only the highlight and the mirror see, as sample_micro_slopes() draws them).
float SampleShader::diffuse_slope_variance(const SurfacePoint& point) const {
    if (!policy_.roughness) return 0;
    float variance = 0.5f * (point.roughness.xx + point.roughness.yy);
    if (point.material->metallic_roughness())
        variance -= point.material->micro_roughness.xx + point.micro_variance;
    return std::max(0.0f, variance);
}

// Whether an object lies between `origin` and the light (none where the light casts no shadows).
bool SampleShader::in_shadow(const LightDesc& light, Vec3d origin) const {
    if (!light.shadows) return false;
    if (light.type == LightType::directional)
        return scene_.occluded({origin, -light.direction}, 0,
                               std::numeric_limits<double>::infinity());
    return scene_.occluded({origin, light.position - origin}, 0, 1);  // the light at t = 1
}

// Lambert + the material's highlight (Blinn-Phong or a microfacet BRDF, widened by K_b in the
// rough modes) for every light that sees the point.
void SampleShader::add_lights(const SurfacePoint& point, Vec3 n_hat, Vec3 v_hat,
                              ShadingFactors& out) const {
    const MaterialDesc& desc = point.material->desc;
    Vec3 e1, e2;
    tangent_basis(n_hat, e1, e2);
    const Sym2 k_e = point.bumped && policy_.roughness
                         ? covariance_in_frame(point.roughness, point.frame.frame, e1, e2)
                         : point.roughness;
    const RoughShadingModel model =
        policy_.roughness ? RoughShadingModel::gaussian : RoughShadingModel::plain;
    // A microfacet highlight (shading/microfacet.h) is widened by the filtered K_b in the rough
    // modes and by nothing in the others, as specular() with `model`.
    const Sym2 k_microfacet = policy_.roughness ? k_e : Sym2{};
    const float alpha = point.highlight_alpha;
    const MicrofacetModel microfacet = desc.highlight == MaterialDesc::Highlight::ggx
                                           ? MicrofacetModel::ggx
                                           : MicrofacetModel::beckmann;
    for (const LightDesc& light : scene_.desc().lights) {
        Vec3 l;
        float scale = 1;
        if (light.type == LightType::directional) {
            l = normalize(-to_float(light.direction));
        } else {
            const Vec3 d = to_float(light.position) - point.p;
            const float d2 = dot(d, d);
            if (!(d2 > 0)) continue;
            l = d / std::sqrt(d2);
            scale = 1.0f / d2;
        }
        const float cos_l = dot(n_hat, l);
        if (cos_l <= 0 || in_shadow(light, point.shadow_origin)) continue;
        const Vec3 h = normalize(l + v_hat);
        Rgb spec{};
        if (desc.specular > 0 && desc.highlight == MaterialDesc::Highlight::blinn_phong) {
            const float lobe = specular(model, to_array(n_hat), to_array(e1), to_array(e2),
                                        to_array(h), k_e, desc.shininess);
            spec.fill(desc.specular * lobe);
        } else if (desc.specular > 0) {  // f_r·cos_l, at F0 per channel
            const MicrofacetTerms terms =
                microfacet_terms(microfacet, to_array(n_hat), to_array(e1), to_array(e2),
                                 to_array(l), to_array(v_hat), k_microfacet, alpha);
            for (int c = 0; c < 3; ++c) spec[c] = desc.specular * terms.times(point.f0[c]);
        }
        const float diffuse = desc.diffuse * cos_l;
        const float rgb[3] = {light.color.x, light.color.y, light.color.z};
        for (int c = 0; c < 3; ++c) {
            out.diffuse[c] += scale * rgb[c] * diffuse;
            out.highlight[c] += scale * rgb[c] * spec[c];
        }
    }
}

const RenderEnvironment* SampleShader::reflected_environment(const SurfacePoint& point) const {
    const RenderEnvironment* probe = tracing_reflection_ ? nullptr : point.material->probe;
    return probe ? probe : scene_.environment_at(point.p);
}

// The reference's view of a probed mirror: the reflected ray traced into the scene (the object
// that wears the probe passed through, as its probe leaves it out), its hit shaded with one bounce
// (its own mirror reads the environment), or the background where it escapes.
Rgb SampleShader::traced_reflection(const SurfacePoint& point, Vec3 r, Vec2d random) {
    const RayDifferential ray{{point.shadow_origin, vec3_cast<double>(r)}, {}, {}, {}, {}};
    tracing_reflection_ = true;
    const std::optional<SurfacePoint> hit = trace(ray, random, point.object);
    const Rgb c = hit ? combine(shade(*hit)) : background(ray);
    tracing_reflection_ = false;
    return c;
}

// The mirror reflection: the environment filtered over the footprint of spec §2 (the curvature,
// the aperture and, in the rough modes, the slopes' covariance), or sampled in the reflected
// direction; weighted by Schlick's Fresnel. In the rough modes Fresnel is averaged over the slopes
// and the reflection looked up under the slopes weighted by it (shading/fresnel.h).
void SampleShader::add_reflection(const SurfacePoint& point, Vec3 n_hat, Vec3 v_hat,
                                  ShadingFactors& out) {
    const RenderEnvironment& env = *reflected_environment(point);  // shade() checked it
    out.environment = &env;
    const MaterialDesc& desc = point.material->desc;
    const Rgb& f0 = point.f0;
    // One F0 steers the Fresnel-weighted slopes: the channels' mean (their means are exact).
    const float f0_mean = channel_mean(f0);
    if (!policy_.filtered) {
        if (point.bumped && (point.micro_slope.x != 0 || point.micro_slope.y != 0)) {
            const Vec2 b_t = point.frame.slope_sign * (point.slope + point.micro_slope);
            const Vec3 n_m = normalize(perturbed_normal(point.n, point.frame.frame, b_t));
            if (dot(n_m, v_hat) > 0) n_hat = n_m;  // else the bump is dropped (§4)
        }
        const Vec3 r = 2.0f * dot(n_hat, v_hat) * n_hat - v_hat;
        out.map_reflection = env.rotation * local_direction(env, point.p, r);
        if (&env == point.material->probe && options_.filter == FilterMode::reference) {
            out.reflection = traced_reflection(point, r, {0.5, 0.5});
        } else {
            static_cast<void>(
                textures_.environment_sample(env.map, out.map_reflection, out.reflection));
        }
        ++lookups;
        for (int c = 0; c < 3; ++c)
            out.fresnel[c] = desc.mirror * schlick_fresnel(f0[c], dot(n_hat, v_hat));
        return;
    }
    ReflectionGeometry geometry;
    geometry.v = point.v;
    geometry.dv_dx = -to_float(point.diff.dpdx);  // the eye is fixed: ∂v = −∂p
    geometry.dv_dy = -to_float(point.diff.dpdy);
    geometry.n = point.n;
    geometry.dn_dx = point.dndx;
    geometry.dn_dy = point.dndy;
    Rgb fresnel;
    for (int c = 0; c < 3; ++c) fresnel[c] = schlick_fresnel(f0[c], dot(n_hat, v_hat));
    float facing_away = 0;
    const ReflectionGeometry flat = geometry;
    if (point.bumped) {
        Vec2 slope = point.slope + point.micro_slope;  // stochastic: a drawn micro-slope
        Sym2 roughness = point.roughness;
        if (policy_.fresnel_over_slopes) {
            const FresnelOverSlopes weighted =
                fresnel_over_slopes(f0_mean, dot(n_hat, v_hat),
                                    cos_slope_gradient(point, n_hat, v_hat), point.roughness);
            for (int c = 0; c < 3; ++c) fresnel[c] = mean_fresnel(weighted, f0[c]);
            slope = slope + weighted.mean_slope_shift;
            roughness = weighted.covariance;
            facing_away = weighted.facing_away;
        }
        geometry.bump_slope = point.frame.slope_sign * slope;
        geometry.t1 = point.frame.frame.t1;
        geometry.t2 = point.frame.frame.t2;
        geometry.roughness = roughness_factor(roughness);
    }
    EnvFootprintOptions env_options;
    env_options.kappa = options_.kappa;
    env_options.rotation = env.rotation;
    out.env_footprint = through_proxy(
        env, compute_env_footprint(env.layout, env.texel_scale, geometry, env_options), point,
        env_options);
    out.map_reflection = normalize(out.env_footprint->map_direction);
    if (policy_.stochastic) {
        // One direction the footprint's Gaussian picks (the pixel filter's σ = ½ pixel), read at
        // level 0.
        RandomStream draws(point.random_seed ^ 0x5bd1e995u);
        const Vec2 z = 0.5f * draws.gaussian();
        const EnvFootprint& f = *out.env_footprint;
        const Vec3 r = f.map_direction + z.x * f.map_dr_dx + z.y * f.map_dr_dy;
        static_cast<void>(textures_.environment_sample(env.map, r, out.reflection));
    } else {
        static_cast<void>(
            textures_.environment(env.map, *out.env_footprint, policy_.lookup, out.reflection));
    }
    ++lookups;
    const float cos_surface = dot(normalize(point.n), v_hat);
    const float f_away = facing_away * schlick_fresnel(f0_mean, cos_surface);
    const float f_mean = channel_mean(fresnel);
    if (facing_away > kFacingAwayThreshold && f_mean + f_away > 0) {
        // Slopes facing away from the eye are shaded with the surface's own normal (spec §4), as
        // the reference shades them: their share of the mirror term is a second lookup.
        out.away_footprint = through_proxy(
            env, compute_env_footprint(env.layout, env.texel_scale, flat, env_options), point,
            env_options);
        Rgb texel;
        static_cast<void>(
            textures_.environment(env.map, *out.away_footprint, policy_.lookup, texel));
        ++lookups;
        out.away_weight = f_away / (f_mean + f_away);
        for (int c = 0; c < 3; ++c) {
            out.reflection[c] += out.away_weight * (texel[c] - out.reflection[c]);
            fresnel[c] += facing_away * schlick_fresnel(f0[c], cos_surface);
        }
    }
    for (int c = 0; c < 3; ++c) out.fresnel[c] = desc.mirror * fresnel[c];
}

namespace {

// Offset i of m: the Gaussian quantile Φ⁻¹((i + ½)/m) of a grid axis, the m of them scaled to unit
// variance.
double quantile_node(int i, int m) {
    double variance = 0;
    for (int j = 0; j < m; ++j) variance += std::pow(inverse_normal_cdf((j + 0.5) / m), 2) / m;
    return inverse_normal_cdf((i + 0.5) / m) / std::sqrt(variance);
}

}  // namespace

RayDifferential sample_ray(const PinholeCamera& camera, const RenderOptions& options, int x, int y,
                           int k, Vec2d& random) {
    const int n = std::max(1, options.spp);
    const std::uint32_t seed = pixel_seed(x, y, options.seed);
    const std::uint32_t h = hash32(seed + 2 + static_cast<std::uint32_t>(k));
    random = {unit_float(h), unit_float(hash32(h))};
    if (options.filter == FilterMode::reference) {
        // Point samples: R2 points warped to the pixel filter, differentials of a 1/N share.
        const double rot_x = unit_float(hash32(seed)), rot_y = unit_float(hash32(seed + 1));
        const double ux = std::fmod(rot_x + kR2a * (k + 0.5), 1.0);
        const double uy = std::fmod(rot_y + kR2b * (k + 0.5), 1.0);
        RayDifferential ray =
            camera.ray(x + 0.5 + gaussian_pixel_offset(ux), y + 0.5 + gaussian_pixel_offset(uy));
        const double scale = 1.0 / std::sqrt(static_cast<double>(n));
        ray.dodx = scale * ray.dodx, ray.dody = scale * ray.dody;
        ray.dddx = scale * ray.dddx, ray.dddy = scale * ray.dddy;
        return ray;
    }
    // Filtered samples: each sample's kernel is a Gaussian of α/4 pixel² (K/4 of differentials
    // scaled by √α), and the sample positions spread by the rest of the pixel filter's ¼, so that
    // the kernels add up to the σ = ½-pixel filter at any N. Positions drawn at random would make
    // that sum lumpy — noise a 1-spp filtered pixel does not have — so N = m² takes the m × m grid
    // of Gaussian quantiles with α = 1/m, wide kernels that overlap into a smooth sum; other N
    // take the R2 points with α = 1/N.
    const int m = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n))));
    double alpha = 1, ox = 0, oy = 0;
    if (m * m == n) {
        alpha = 1.0 / m;
        const double spread = 0.5 * std::sqrt(1 - alpha);
        ox = m > 1 ? spread * quantile_node(k % m, m) : 0;
        oy = m > 1 ? spread * quantile_node(k / m, m) : 0;
    } else {
        alpha = 1.0 / n;
        const double spread = std::sqrt(1 - alpha);
        const double rot_x = unit_float(hash32(seed)), rot_y = unit_float(hash32(seed + 1));
        ox = spread * gaussian_pixel_offset(std::fmod(rot_x + kR2a * (k + 0.5), 1.0));
        oy = spread * gaussian_pixel_offset(std::fmod(rot_y + kR2b * (k + 0.5), 1.0));
    }
    RayDifferential ray = camera.ray(x + 0.5 + ox, y + 0.5 + oy);
    const double scale = std::sqrt(alpha);
    ray.dodx = scale * ray.dodx, ray.dody = scale * ray.dody;
    ray.dddx = scale * ray.dddx, ray.dddy = scale * ray.dddy;
    return ray;
}

int tile_count(int width, int height) {
    return ((width + kTileSize - 1) / kTileSize) * ((height + kTileSize - 1) / kTileSize);
}

namespace {

// The arena of `threads` workers, made once and kept for the process. oneTBB 2021 keeps memory,
// and a cost every later arena pays, for every task_arena ever constructed: one per render call
// made a long-running process (a soak, a renderer's frames) grow and slow down without bound
// (docs/testing.md's soak). Several renders may share an arena at once.
tbb::task_arena& arena_of(int threads) {
    static std::mutex mutex;
    static auto* arenas = new std::map<int, std::unique_ptr<tbb::task_arena>>;  // never destroyed
    const std::lock_guard lock(mutex);
    std::unique_ptr<tbb::task_arena>& arena = (*arenas)[threads];
    if (!arena) arena = std::make_unique<tbb::task_arena>(threads);
    return *arena;
}

}  // namespace

void for_each_tile(int width, int height, int threads,
                   const std::function<void(const Tile&)>& body) {
    const int tiles_x = (width + kTileSize - 1) / kTileSize;
    auto run = [&] {
        parallel_for_each(0, tile_count(width, height), [&](int i) {
            const int x0 = (i % tiles_x) * kTileSize;
            const int y0 = (i / tiles_x) * kTileSize;
            body(Tile{x0, y0, std::min(width, x0 + kTileSize), std::min(height, y0 + kTileSize)});
        });
    };
    if (threads > 0) {
        // More threads than oneTBB allows by default (the machine's cores) is a request to
        // oversubscribe: the limit is raised while they run, where oneTBB would otherwise run
        // fewer and print a warning. A lower limit the host set stays in force.
        std::optional<tbb::global_control> allow;
        const auto limit =
            tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
        if (static_cast<std::size_t>(threads) > limit)
            allow.emplace(tbb::global_control::max_allowed_parallelism, threads);
        arena_of(threads).execute(run);
    } else {
        run();
    }
}

}  // namespace footprint::detail
