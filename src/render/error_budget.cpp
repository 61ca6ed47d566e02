#include "render/error_budget.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "envmap/env_reference.h"
#include "render/camera.h"
#include "render/sample_shader.h"
#include "texture/reference_filter.h"

namespace footprint {

namespace {

using detail::Rgb;
using detail::ShadingFactors;
using detail::SurfacePoint;

// Every term, in the order of all_budget_terms(), with its name and what it takes from the
// samples.
struct TermInfo {
    BudgetTerm term;
    const char* name;
    const char* description;
};
constexpr TermInfo kTermInfo[] = {
    {BudgetTerm::texture, "texture", "base colour from the samples (the texture's filtering)"},
    {BudgetTerm::texture_filter, "texture-filter",
     "base colour by the exact Gaussian of the mode's own footprint (the filter's kernel)"},
    {BudgetTerm::bump, "bump",
     "slope mean and covariance from the samples (the bump pyramid's filtering)"},
    {BudgetTerm::diffuse, "diffuse", "diffuse from the samples (Lambert of the mean normal)"},
    {BudgetTerm::lambert, "lambert", "colour x diffuse from the samples (with their correlation)"},
    {BudgetTerm::highlight, "highlight", "highlight from the samples (the rough lobe)"},
    {BudgetTerm::fresnel, "fresnel", "Fresnel from the samples (Schlick of the mean normal)"},
    {BudgetTerm::env_filter, "env-filter",
     "reflection by the exact Gaussian of the mode's own footprint (the environment filter's "
     "kernel)"},
    {BudgetTerm::env_footprint, "env-footprint",
     "reflection by the exact Gaussian of the samples' directions (the footprint model)"},
    {BudgetTerm::env_two_lobes, "env-two-lobes",
     "reflection by two exact Gaussians, the samples split at 1.5 sigma of their slopes (what a "
     "two-lobe slope model could reach)"},
    {BudgetTerm::reflection, "reflection",
     "reflection from the samples (all of the environment term)"},
    {BudgetTerm::mirror, "mirror",
     "Fresnel x reflection from the samples (with their correlation)"},
    {BudgetTerm::factors, "factors",
     "every factor from the samples (what remains: their correlation in the pixel)"},
};
constexpr auto kTerms = [] {
    std::array<BudgetTerm, std::size(kTermInfo)> terms{};
    for (std::size_t i = 0; i < terms.size(); ++i) terms[i] = kTermInfo[i].term;
    return terms;
}();
constexpr int kTermCount = static_cast<int>(std::size(kTerms));

// The exact Gaussians are dense quadratures; these caps keep one pixel's at a few thousand taps
// (a 65-node axis of a Gaussian is already exact to far below the errors measured).
constexpr int kEnvNodesPerAxis = 65;
constexpr double kTextureNodesPerAxis = 128;

bool finite(const Rgb& c) {
    return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]);
}

// The weighted first and second moments of unit directions, and their Gaussian on the sphere.
struct DirectionMoments {
    double weight = 0, dir[3] = {}, dir2[3][3] = {};  // Σ w, Σ w r̂, Σ w r̂ r̂ᵀ

    void add(double w, Vec3 r) {
        const double v[3] = {r.x, r.y, r.z};
        weight += w;
        for (int i = 0; i < 3; ++i) {
            dir[i] += w * v[i];
            for (int j = 0; j < 3; ++j) dir2[i][j] += w * v[i] * v[j];
        }
    }

    // The Gaussian of the mean and covariance (a point without weight), as a SphereGaussian: the
    // covariance in a tangent basis (u, w) at the mean direction, factored Σ = L Lᵀ, spread
    // vectors 2·L's columns (sphere_gaussian_from_spread's ¼).
    SphereGaussian gaussian() const {
        if (!(weight > 0)) return {};
        const Vec3d mean{dir[0] / weight, dir[1] / weight, dir[2] / weight};
        const Vec3d m = normalize(mean);
        const Vec3d u = std::abs(m.x) < 0.9 ? normalize(cross(m, Vec3d{1, 0, 0}))
                                            : normalize(cross(m, Vec3d{0, 1, 0}));
        const Vec3d w = cross(m, u);
        auto covariance = [&](Vec3d a, Vec3d b) {
            double sum = 0;
            const double av[3] = {a.x, a.y, a.z}, bv[3] = {b.x, b.y, b.z};
            for (int i = 0; i < 3; ++i) {
                for (int j = 0; j < 3; ++j) sum += av[i] * dir2[i][j] * bv[j];
            }
            return sum / weight - dot(a, mean) * dot(b, mean);
        };
        const double cuu = std::max(0.0, covariance(u, u)), cuw = covariance(u, w),
                     cww = std::max(0.0, covariance(w, w));
        const double l11 = std::sqrt(cuu);
        const double l21 = l11 > 0 ? cuw / l11 : 0;
        const double l22 = std::sqrt(std::max(0.0, cww - l21 * l21));
        const Vec3d spread[2] = {2.0 * (l11 * u + l21 * w), 2.0 * (l22 * w)};
        return sphere_gaussian_from_spread(m, spread);
    }
};

// Where a two-lobe slope model would split a pixel's slopes: beyond this Mahalanobis radius of
// their own mean and covariance.
constexpr double kLobeSplit = 1.5;

// Sums over one pixel's reference samples that hit the object (and material) the pixel centre
// hits: each factor, the slopes' first and second moments, and the reflected directions' weighted
// by Fresnel. The reflection's reference value is its Fresnel-weighted mean E[F·R]/E[F], so that
// with E[F] it makes the mirror term E[F·R] (shading/fresnel.h: what the rough modes estimate).
struct SampleSums {
    int count = 0;
    double base[3] = {}, diffuse[3] = {}, highlight[3] = {}, reflection[3] = {}, fresnel[3] = {};
    double lambert[3] = {}, mirror[3] = {};  // Σ c ⊙ D, Σ F·R
    double slope[2] = {}, slope2[3] = {};    // Σ b, Σ b bᵀ (xx, xy, yy)
    DirectionMoments directions;             // weighted by Fresnel
    struct Sample {
        Vec2 slope;
        float fresnel;
        Vec3 direction;
    };
    std::vector<Sample> samples;  // for the two-lobe split

    void add(const SurfacePoint& p, const ShadingFactors& f) {
        ++count;
        for (int c = 0; c < 3; ++c) {
            base[c] += f.base[c], diffuse[c] += f.diffuse[c];
            highlight[c] += f.highlight[c], reflection[c] += f.reflection[c];
            lambert[c] += double(f.base[c]) * f.diffuse[c];
            mirror[c] += double(f.fresnel[c]) * f.reflection[c];
            fresnel[c] += f.fresnel[c];
        }
        // The directions weighted by the channels' mean Fresnel.
        const float weight = detail::channel_mean(f.fresnel);
        slope[0] += p.slope.x, slope[1] += p.slope.y;
        slope2[0] += double(p.slope.x) * p.slope.x, slope2[1] += double(p.slope.x) * p.slope.y;
        slope2[2] += double(p.slope.y) * p.slope.y;
        directions.add(weight, f.map_reflection);
        samples.push_back({p.slope, weight, f.map_reflection});
    }

    ShadingFactors means() const {
        ShadingFactors m;
        for (int c = 0; c < 3; ++c) {
            m.base[c] = static_cast<float>(base[c] / count);
            m.diffuse[c] = static_cast<float>(diffuse[c] / count);
            m.highlight[c] = static_cast<float>(highlight[c] / count);
            m.reflection[c] =
                static_cast<float>(fresnel[c] > 0 ? mirror[c] / fresnel[c] : reflection[c] / count);
            m.fresnel[c] = static_cast<float>(fresnel[c] / count);
        }
        return m;
    }

    Vec2 mean_slope() const {
        return {static_cast<float>(slope[0] / count), static_cast<float>(slope[1] / count)};
    }
    Sym2 slope_covariance() const {
        const Vec2 m = mean_slope();
        return {static_cast<float>(std::max(0.0, slope2[0] / count - double(m.x) * m.x)),
                static_cast<float>(slope2[1] / count - double(m.x) * m.y),
                static_cast<float>(std::max(0.0, slope2[2] / count - double(m.y) * m.y))};
    }

    // The reflection as two lobes: the samples split by their slope's Mahalanobis radius from the
    // slopes' mean, each lobe the exact Gaussian of its Fresnel-weighted directions, weighted by
    // its share of Fresnel.
    template <class Exact>
    Rgb two_lobes(const Exact& exact) const {
        const Vec2 m = mean_slope();
        const Sym2 k = slope_covariance();
        const double det = double(k.xx) * k.yy - double(k.xy) * k.xy;
        DirectionMoments lobes[2];
        for (const Sample& s : samples) {
            const double dx = s.slope.x - m.x, dy = s.slope.y - m.y;
            const double r2 =
                det > 0 ? (k.yy * dx * dx - 2 * k.xy * dx * dy + k.xx * dy * dy) / det : 0;
            lobes[r2 > kLobeSplit * kLobeSplit ? 1 : 0].add(s.fresnel, s.direction);
        }
        Rgb out{0, 0, 0};
        const double total = lobes[0].weight + lobes[1].weight;
        for (const DirectionMoments& lobe : lobes) {
            if (!(lobe.weight > 0)) continue;
            const Rgb r = exact(lobe.gaussian());
            for (int c = 0; c < 3; ++c) out[c] += static_cast<float>(lobe.weight / total) * r[c];
        }
        return out;
    }
};

// Each base-colour texture's pyramid and level 0, read once, for the exact texture Gaussian.
class LevelZeroImages {
  public:
    struct Entry {
        std::shared_ptr<const MipPyramid> pyramid;  // null if it could not be read
        std::shared_ptr<const Image> level0;
    };

    explicit LevelZeroImages(TextureSystem& textures) : textures_(textures) {}

    Entry get(TextureHandle* texture) {
        const std::lock_guard lock(mutex_);
        auto [it, inserted] = entries_.try_emplace(texture);
        if (inserted) {
            Result<std::shared_ptr<const MipPyramid>> pyramid = textures_.pyramid(texture);
            if (pyramid) {
                it->second.pyramid = *pyramid;
                it->second.level0 = std::make_shared<Image>((*pyramid)->level_image(0));
            }
        }
        return it->second;
    }

  private:
    TextureSystem& textures_;
    std::mutex mutex_;
    std::map<TextureHandle*, Entry> entries_;
};

// The base colour with the texture filtered by the exact Gaussian of the centre's footprint.
Rgb exact_texture(const SurfacePoint& centre, LevelZeroImages& images) {
    const RenderMaterial& material = *centre.material;
    const Vec3 colour = material.desc.base_color;
    Rgb base{colour.x, colour.y, colour.z};
    if (!material.base_color_map) return base;
    const LevelZeroImages::Entry texture = images.get(material.base_color_map);
    if (!texture.pyramid) return centre.base;
    const FootprintEllipse footprint = footprint_of(*texture.pyramid, centre.coords);
    ReferenceOptions options;
    options.wrap_s = texture.pyramid->wrap_s(), options.wrap_t = texture.pyramid->wrap_t();
    options.nodes_per_sigma = 4;
    options.max_node_spacing = std::max(
        0.5, 2 * options.truncation_sigmas * 0.5 * footprint.major_radius / kTextureNodesPerAxis);
    float texel[8] = {};
    reference_lookup(*texture.level0, centre.coords.s, centre.coords.t, footprint, options, texel);
    if (material.base_color_grey) texel[1] = texel[2] = texel[0];
    for (int c = 0; c < 3; ++c) base[c] *= texel[c];
    return base;
}

Rgb exact_environment(const EnvironmentMap& map, const SphereGaussian& footprint) {
    EnvReferenceOptions options;
    options.max_samples_per_axis = kEnvNodesPerAxis;
    float texel[8] = {};
    environment_reference(map, footprint, texel, options);
    return {texel[0], texel[1], texel[2]};
}

SphereGaussian footprint_gaussian(const EnvFootprint& f) {
    const Vec3d spread[4] = {vec3_cast<double>(f.map_dr_dx), vec3_cast<double>(f.map_dr_dy),
                             vec3_cast<double>(f.map_roughness1),
                             vec3_cast<double>(f.map_roughness2)};
    return sphere_gaussian_from_spread(vec3_cast<double>(f.map_direction), spread);
}

class BudgetPixel {
  public:
    BudgetPixel(const RenderScene& scene, const ErrorBudgetOptions& options,
                LevelZeroImages& images)
        : scene_(scene),
          filtered_options_(render_options(options, options.filter, 1)),
          reference_options_(render_options(options, FilterMode::reference, options.spp)),
          filtered_(scene, filtered_options_),
          reference_(scene, reference_options_),
          images_(images) {}

    // Writes the reference, the filtered pixel and every hybrid of pixel (x, y).
    void render(const PinholeCamera& camera, int x, int y, ErrorBudgetImages& out) {
        Vec2d random;
        const RayDifferential centre_ray =
            detail::sample_ray(camera, filtered_options_, x, y, 0, random);
        const std::optional<SurfacePoint> centre = filtered_.trace(centre_ray, random);
        ShadingFactors factors;
        Rgb filtered;
        if (centre) {
            factors = filtered_.shade(*centre);
            filtered = detail::combine(factors);
        } else {
            filtered = filtered_.background(centre_ray);
        }

        SampleSums sums;
        bool covered = centre.has_value();
        double colour[3] = {};
        int kept = 0;
        for (int k = 0; k < reference_options_.spp; ++k) {
            const RayDifferential ray =
                detail::sample_ray(camera, reference_options_, x, y, k, random);
            const std::optional<SurfacePoint> point = reference_.trace(ray, random);
            Rgb c;
            if (point) {
                const ShadingFactors f = reference_.shade(*point);
                c = detail::combine(f);
                const bool same = centre && point->object == centre->object &&
                                  point->material == centre->material;
                covered = covered && same;
                if (same && finite(c)) sums.add(*point, f);
            } else {
                c = reference_.background(ray);
                covered = false;
            }
            if (!finite(c)) continue;
            for (int i = 0; i < 3; ++i) colour[i] += c[i];
            ++kept;
        }
        const Rgb reference = kept == 0 ? Rgb{0, 0, 0}
                                        : Rgb{static_cast<float>(colour[0] / kept),
                                              static_cast<float>(colour[1] / kept),
                                              static_cast<float>(colour[2] / kept)};
        put(out.reference, x, y, reference);
        put(out.filtered, x, y, filtered);
        for (int t = 0; t < kTermCount; ++t) {
            const Rgb hybrid = covered && sums.count > 0
                                   ? combine_with(kTerms[t], *centre, factors, sums)
                                   : filtered;
            put(out.terms[static_cast<std::size_t>(t)], x, y, hybrid);
        }
    }

  private:
    static RenderOptions render_options(const ErrorBudgetOptions& options, FilterMode mode,
                                        int spp) {
        RenderOptions r;
        r.filter = mode;
        r.spp = spp;
        r.kappa = options.kappa;
        r.max_probes = options.max_probes;
        r.seed = options.seed;
        return r;
    }

    static void put(Image& image, int x, int y, const Rgb& c) {
        std::copy(c.begin(), c.end(), image.at(x, y));
    }

    // The filtered pixel with `term` taken from the samples.
    Rgb combine_with(BudgetTerm term, const SurfacePoint& centre, ShadingFactors f,
                     const SampleSums& sums) {
        const ShadingFactors mean = sums.means();
        const EnvironmentMap* env_map = whole_map(f.environment);  // the map R was read from
        switch (term) {
            case BudgetTerm::texture:
                f.base = mean.base;
                break;
            case BudgetTerm::texture_filter:
                f.base = exact_texture(centre, images_);
                break;
            case BudgetTerm::bump: {
                SurfacePoint moments = centre;
                moments.slope = sums.mean_slope();
                if (detail::policy_of(filtered_options_.filter).roughness) {
                    moments.roughness = sums.slope_covariance();
                }
                return detail::combine(filtered_.shade(moments));
            }
            case BudgetTerm::diffuse:
                f.diffuse = mean.diffuse;
                break;
            case BudgetTerm::lambert: {
                Rgb out;
                for (int c = 0; c < 3; ++c) {
                    out[c] = static_cast<float>(sums.lambert[c] / sums.count) + f.highlight[c] +
                             f.fresnel[c] * f.reflection[c];
                }
                return out;
            }
            case BudgetTerm::highlight:
                f.highlight = mean.highlight;
                break;
            case BudgetTerm::fresnel:
                f.fresnel = mean.fresnel;
                break;
            case BudgetTerm::env_filter:
                if (env_map && f.env_footprint) {
                    f.reflection =
                        exact_environment(*env_map, footprint_gaussian(*f.env_footprint));
                    if (f.away_footprint) {
                        const Rgb away =
                            exact_environment(*env_map, footprint_gaussian(*f.away_footprint));
                        for (int c = 0; c < 3; ++c) {
                            f.reflection[c] += f.away_weight * (away[c] - f.reflection[c]);
                        }
                    }
                }
                break;
            case BudgetTerm::env_footprint:
                if (env_map && f.fresnel != Rgb{}) {
                    f.reflection = exact_environment(*env_map, sums.directions.gaussian());
                }
                break;
            case BudgetTerm::env_two_lobes:
                if (env_map && f.fresnel != Rgb{}) {
                    f.reflection = sums.two_lobes(
                        [&](const SphereGaussian& g) { return exact_environment(*env_map, g); });
                }
                break;
            case BudgetTerm::reflection:
                f.reflection = mean.reflection;
                break;
            case BudgetTerm::mirror: {
                Rgb out;
                for (int c = 0; c < 3; ++c) {
                    out[c] = f.base[c] * f.diffuse[c] + f.highlight[c] +
                             static_cast<float>(sums.mirror[c] / sums.count);
                }
                return out;
            }
            case BudgetTerm::factors:
                f.base = mean.base, f.diffuse = mean.diffuse, f.highlight = mean.highlight;
                f.fresnel = mean.fresnel, f.reflection = mean.reflection;
                break;
        }
        return detail::combine(f);
    }

    // An environment's whole map (the scene's, a local map or a probe), for the exact integrals;
    // null for none or a map that cannot be read whole. Cached: the texture system takes a lock.
    const EnvironmentMap* whole_map(const RenderEnvironment* environment) {
        if (!environment) return nullptr;
        auto [it, added] = maps_.try_emplace(environment);
        if (added) {
            Result<std::shared_ptr<const EnvironmentMap>> map =
                scene_.textures().environment_map(environment->map);
            if (map) it->second = *map;
        }
        return it->second.get();
    }

    const RenderScene& scene_;
    RenderOptions filtered_options_, reference_options_;
    detail::SampleShader filtered_, reference_;
    LevelZeroImages& images_;
    std::unordered_map<const RenderEnvironment*, std::shared_ptr<const EnvironmentMap>> maps_;
};

}  // namespace

std::span<const BudgetTerm> all_budget_terms() {
    return kTerms;
}

const char* budget_term_name(BudgetTerm term) {
    for (const TermInfo& info : kTermInfo) {
        if (info.term == term) return info.name;
    }
    return "?";
}

const char* budget_term_description(BudgetTerm term) {
    for (const TermInfo& info : kTermInfo) {
        if (info.term == term) return info.description;
    }
    return "?";
}

ErrorBudgetImages render_error_budget(const RenderScene& scene, const ErrorBudgetOptions& options,
                                      const std::function<void()>& tile_done) {
    const auto start = std::chrono::steady_clock::now();
    const int width = scene.desc().width, height = scene.desc().height;
    const PinholeCamera camera(scene.desc().camera, width, height);
    ErrorBudgetImages out;
    out.reference = Image(width, height, 3);
    out.filtered = Image(width, height, 3);
    out.terms.assign(kTermCount, Image(width, height, 3));

    LevelZeroImages images(scene.textures());
    detail::for_each_tile(width, height, options.threads, [&](const detail::Tile& tile) {
        BudgetPixel pixel(scene, options, images);
        for (int y = tile.y0; y < tile.y1; ++y) {
            for (int x = tile.x0; x < tile.x1; ++x) pixel.render(camera, x, y, out);
        }
        if (tile_done) tile_done();
    });
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace footprint
