// render/sample_shader.h — (private) the colour of one camera sample, in the steps of
// render/renderer.h's "one pixel's journey", for render() and the error budget (error_budget.h).
//
//   trace()    the nearest hit and what the maps say there: base colour c, mean slope b and its
//              covariance K_b (filtered, or finest-level with the micro-roughness sampled), the
//              surface's normal, tangent frame and ray differentials, turned to face the viewer;
//   shade()    the factors of the shading formula at that point (ShadingFactors);
//   combine()  the sample's colour from its factors: c ⊙ D + S + F·R.
// The error budget takes each factor (or the slope moments) from the reference path and the rest
// from a filtered mode, which is why the steps are separate.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>

#include "render/bump_frame.h"
#include "render/camera.h"
#include "render/peer_filters.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "scene/ray_differentials.h"

namespace footprint::detail {

using Rgb = std::array<float, 3>;

// Where a mode's mean slope b and slope covariance K_b come from.
enum class SlopeSource {
    moments,       // the bump pyramid's first and second moments (Schilling; LEAN mapping)
    toksvig,       // the mean of unit normals and its length (render/peer_filters.h)
    screen_space,  // the mean slope, K_b from its change across the pixel (specular AA)
    sampled,       // one slope drawn from the moments of a texel the filter picks (stochastic)
};

// What one mode does at every lookup.
struct ModePolicy {
    bool filtered = true;              // use the ray differentials (false: finest-level bilinear)
    bool roughness = false;            // K_b enters the env footprint and the highlights
    bool fresnel_over_slopes = false;  // Fresnel averaged over the slopes (shading/fresnel.h)
    bool sample_micro_roughness = false;  // micro-roughness as random slopes (no bump map)
    bool stochastic = false;  // lookups at positions the filter picks at random (peer_filters.h)
    SlopeSource slopes = SlopeSource::moments;
    LookupOptions lookup;
};
ModePolicy policy_of(FilterMode mode);

// A hit and what the maps say there: the inputs of shading.
struct SurfacePoint {
    const RenderMaterial* material = nullptr;
    int object = -1;       // SurfaceHit::object
    TextureCoords coords;  // (s, t) of the maps and, in filtered modes, their derivatives
    Rgb base{};            // c: the material's colour × its (filtered) texture
    Rgb f0{};              // Schlick's F0 per channel (RenderMaterial::f0 × its filtered map)
    Vec2 slope;            // b: the mean bump slope (plus a sampled micro-slope in the reference)
    Sym2 roughness;        // K_b: the slopes' covariance (zero where the mode ignores roughness)
    // A metallic-roughness material where the mode samples slopes (reference, stochastic): the
    // micro-slope drawn from the texel's σ², which tilts the mirror's normal only, while the
    // lights' highlight takes that σ² as its own α = √2 σ (sampling a microfacet BRDF's peak
    // instead would take millions of samples to converge).
    Vec2 micro_slope;
    float highlight_alpha = 0;  // the microfacet highlight's α beyond K_b
    // σ² of the slopes below the maps' resolution beyond micro_roughness: a textured
    // metallic-roughness material's, from its F0 map (RenderMaterial::f0_map).
    float micro_variance = 0;
    bool bumped = false;  // a bump map or micro-roughness: the normal is perturbed in `frame`
    BumpFrameAtHit frame;
    // Facing the viewer (a surface seen from behind is shaded as its mirror image).
    Vec3 p, n, dndx, dndy;  // n any length, ∂n per pixel step
    Vec3 v;                 // surface → eye
    Vec3d shadow_origin;    // p lifted off the surface towards the eye: where shadow rays start
    SurfaceDifferentials diff;
    std::uint32_t random_seed = 0;  // the sample's draws, for stochastic lookups
};

// The factors of one sample's colour: combine() = c ⊙ D + S + F·R.
struct ShadingFactors {
    Rgb base{};        // c
    Rgb diffuse{};     // D = diffuse·(Σ_i E_i max(0, n̂·l̂_i) + E_env(n̂)/π)
    Rgb highlight{};   // S = specular·Σ_i E_i S(n̂, ĥ_i, K_b)
    Rgb fresnel{};     // F = mirror·Schlick(F0, n̂·v̂), per channel of F0
    Rgb reflection{};  // R = the environment in the reflected direction (filtered or not)
    // How R was looked up: the unit reflected direction in map space, and (filtered modes) the
    // footprint; where some of the slopes face away from the eye, R = (1 − w)·R(env_footprint) +
    // w·R(away_footprint), w = away_weight (shading/fresnel.h).
    Vec3 map_reflection;
    const RenderEnvironment* environment = nullptr;  // the map R was read from
    std::optional<EnvFootprint> env_footprint, away_footprint;
    float away_weight = 0;
};

inline Rgb combine(const ShadingFactors& f) {
    Rgb out;
    for (int c = 0; c < 3; ++c) {
        out[c] = f.base[c] * f.diffuse[c] + f.highlight[c] + f.fresnel[c] * f.reflection[c];
    }
    return out;
}

// The mean of three channels; exactly their value where they are equal (a grey F0): the one F0
// that steers the Fresnel-weighted slopes, and the weight of a sample's reflected direction.
inline float channel_mean(const Rgb& rgb) {
    if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) return rgb[0];
    return (rgb[0] + rgb[1] + rgb[2]) / 3;
}

class SampleShader {
  public:
    // `options` is kept by reference: it must outlive the shader. `hidden_object` (≥ 0): an object
    // the camera rays pass through, as an environment probe's views leave out the object that
    // wears it (render/environment_probe.h).
    SampleShader(const RenderScene& scene, const RenderOptions& options, int hidden_object = -1);

    // The colour seen along one camera ray; `random` = two uniforms for the micro-roughness.
    Rgb shade(const RayDifferential& ray, Vec2d random) {
        const std::optional<SurfacePoint> point = trace(ray, random);
        return point ? combine(shade(*point)) : background(ray);
    }

    // The hit along `ray` and its inputs; nullopt if the ray escapes.
    std::optional<SurfacePoint> trace(const RayDifferential& ray, Vec2d random) {
        return trace(ray, random, hidden_object_);
    }
    ShadingFactors shade(const SurfacePoint& point);
    Rgb background(const RayDifferential& ray);

    std::uint64_t lookups = 0;

  private:
    std::optional<SurfacePoint> trace(const RayDifferential& ray, Vec2d random, int hidden_object);
    std::optional<SceneHit> nearest_hit(const Ray& ray, int hidden_object) const;
    // The environment a point's mirror reflects: its material's probe, else the innermost local
    // map around it, else the scene's (if any).
    const RenderEnvironment* reflected_environment(const SurfacePoint& point) const;
    Rgb traced_reflection(const SurfacePoint& point, Vec3 r, Vec2d random);
    float diffuse_slope_variance(const SurfacePoint& point) const;
    Vec3 local_direction(const RenderEnvironment& env, Vec3 p, Vec3 r) const;
    void parallax_coords(const RenderMaterial& material, const SurfaceHit& s,
                         const RayDifferential& ray, TextureCoords& coords);
    EnvFootprint through_proxy(const RenderEnvironment& env, const EnvFootprint& f,
                               const SurfacePoint& point, const EnvFootprintOptions& options) const;
    void add_lights(const SurfacePoint& point, Vec3 n_hat, Vec3 v_hat, ShadingFactors& out) const;
    bool in_shadow(const LightDesc& light, Vec3d origin) const;
    void add_reflection(const SurfacePoint& point, Vec3 n_hat, Vec3 v_hat, ShadingFactors& out);
    void read_map(TextureHandle* map, const TextureCoords& coords, RandomStream& random,
                  std::span<float> out);
    Rgb colour(TextureHandle* map, Rgb constant, bool grey, const TextureCoords& coords,
               RandomStream& random);
    Rgb procedural_colour(const ProceduralTexture& texture, Rgb constant, Vec3d p,
                          const SurfaceDifferentials& diff, RandomStream& random);
    void read_f0(const RenderMaterial& material, const TextureCoords& coords, RandomStream& random,
                 SurfacePoint& point);
    void sample_micro_slopes(const RenderMaterial& material, const Sym2& micro, Vec2d random,
                             SurfacePoint& point);
    // b and K_b; `micro` = K_0 here (the micro-roughness), for the sources outside the moments.
    SlopeStatistics slopes(const RenderMaterial& material, const TextureCoords& coords,
                           const Sym2& micro, RandomStream& random);
    SlopeStatistics read_moments(const RenderMaterial& material, const TextureCoords& coords);
    SlopeStatistics read_toksvig(const RenderMaterial& material, const TextureCoords& coords,
                                 const Sym2& micro);
    SlopeStatistics read_screen_space(const RenderMaterial& material, const TextureCoords& coords,
                                      const Sym2& micro);
    std::pair<Vec2, Vec2> slope_steps(const RenderMaterial& material, const TextureCoords& coords,
                                      Vec2 slope);
    SlopeStatistics procedural_slopes_at(const BumpDesc& bump, Vec3d p,
                                         const SurfaceDifferentials& diff,
                                         const TangentFrame& frame, const Sym2& micro,
                                         RandomStream& random);
    SlopeStatistics read_sampled(const RenderMaterial& material, const TextureCoords& coords,
                                 const Sym2& micro, RandomStream& random);
    // Level 0's size of a map (cached: the texture system's info() takes a lock).
    std::pair<int, int> level0_size(const void* handle, const std::function<TextureInfo()>& info);

    const RenderScene& scene_;
    TextureSystem& textures_;
    const RenderOptions& options_;
    ModePolicy policy_;
    int hidden_object_ = -1;
    bool tracing_reflection_ = false;  // shading a traced reflection's hit: one bounce only
    std::unordered_map<const void*, std::pair<int, int>> sizes_;
};

// The ray of sample k of n in pixel (x, y): the pixel centre for a filtered mode's single sample,
// else a Gaussian-warped R2 point (σ = ½ pixel) with its differentials scaled by 1/√n; `random`
// gets the sample's two uniforms for the micro-roughness.
RayDifferential sample_ray(const PinholeCamera& camera, const RenderOptions& options, int x, int y,
                           int k, Vec2d& random);

// The image in tiles of 16 × 16 pixels, run on oneTBB (`threads` > 0: an arena of that many).
struct Tile {
    int x0, y0, x1, y1;  // pixels [x0, x1) × [y0, y1)
};
int tile_count(int width, int height);
void for_each_tile(int width, int height, int threads,
                   const std::function<void(const Tile&)>& body);

}  // namespace footprint::detail
