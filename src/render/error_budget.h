// render/error_budget.h — where a filtered mode's error comes from: each term of its pixel taken
// in turn from the ground truth, the rest left as the mode computes it.
//
// A pixel of a filtered mode at 1 spp is c ⊙ D + S + F·R, every factor computed once at the pixel
// centre from filtered maps (render/renderer.h's shading): base colour c, diffuse D, highlight S,
// Fresnel F, reflection R. The reference is the mean over N jittered samples of c_k ⊙ D_k + S_k +
// F_k·R_k, each from finest-level lookups with the micro-roughness sampled. The budget renders both
// in one pass, with the same N samples, and for each term below a hybrid: the filtered pixel with
// that one term replaced by its value from the samples. The error a term removes is what it
// carries; what no single term removes lies between them.
//
//   texture         c ← mean c_k: the texture's filtering (the filter's kernel and its
//                   consistency with the σ = ½-pixel pixel filter)
//   texture-filter  c ← the exact Gaussian of the texture over the mode's own footprint K/4
//                   (texture/reference_filter.h): what the filter's kernel (MIP levels, probes)
//                   costs; texture − texture-filter is the footprint's consistency with the pixel
//                   filter
//   bump            the slope mean and covariance ← their moments over the samples (finest-level
//                   slopes plus the sampled micro-roughness), shaded as the mode shades: what the
//                   bump pyramid's filtering costs
//   diffuse         D ← mean D_k: Lambert of the mean normal against the mean of Lambert
//   lambert         c ⊙ D ← mean c_k ⊙ D_k: the diffuse light with the colour's correlation with
//                   the normal (dark mortar in steep grooves); lambert − texture − diffuse is that
//                   correlation
//   highlight       S ← mean S_k: the (rough) Blinn-Phong of the moments against the mean lobe
//   fresnel         F ← mean F_k: the mode's Fresnel (over the slopes, in the rough modes)
//                   against the mean of Schlick
//   env-filter      R ← the exact Gaussian of the environment over the mode's own footprint(s)
//                   (envmap/env_reference.h): what the environment filter's kernel costs
//   env-footprint   R ← the exact Gaussian over the covariance the samples' reflected directions
//                   actually have, weighted by their Fresnel: the footprint model (aperture,
//                   curvature, roughness, κ, Fresnel's weighting) and the filter together, with
//                   the directions' distribution taken as Gaussian
//   env-two-lobes   R ← two such Gaussians, the samples split by their slope's Mahalanobis radius
//                   (beyond 1.5) from the slopes' mean, weighted by their share of Fresnel: what a
//                   two-lobe slope model could reach, measured before building one
//   reflection      R ← Σ F_k R_k / Σ F_k: all of the environment term, weighted as the mirror
//                   term weights it; reflection − env-footprint is the part of the directions'
//                   distribution that is not Gaussian
//   mirror          F·R ← mean F_k·R_k: the whole mirror term (= fresnel and reflection together)
//   factors         c, D, S, F and R all ← their means (R weighted as above): what remains is the
//                   correlation of colour and diffuse inside the pixel (mean of c·D ≠ mean c ·
//                   mean D)
//
// Hybrids are formed where the pixel is covered by one object (every sample hits the object the
// centre hits); elsewhere they equal the filtered pixel. Their errors are meant to be read on
// renderer.h's interior_mask().
#pragma once

#include <span>
#include <string>
#include <vector>

#include <footprint/image/image.h>
#include <footprint/render/renderer.h>

namespace footprint {

enum class BudgetTerm {
    texture,
    texture_filter,
    bump,
    diffuse,
    lambert,
    highlight,
    fresnel,
    env_filter,
    env_footprint,
    env_two_lobes,
    reflection,
    mirror,
    factors
};

// Every term, in the order above.
std::span<const BudgetTerm> all_budget_terms();
const char* budget_term_name(BudgetTerm term);  // "texture", "texture-filter", …
// One line: what the term's hybrid takes from the reference.
const char* budget_term_description(BudgetTerm term);

struct ErrorBudgetOptions {
    FilterMode filter = FilterMode::fa_rough;  // the filtered mode examined (not `reference`)
    int spp = 1024;                            // the reference's samples per pixel
    int threads = 0;                           // 0: all cores
    float kappa = 2;                           // κ of the environment footprint
    int max_probes = 30;                       // RenderOptions::max_probes
    std::uint32_t seed = 1;                    // the reference's samples (RenderOptions::seed)
};

struct ErrorBudgetImages {
    Image reference;           // = render(`reference`, spp, seed)
    Image filtered;            // = render(filter, 1 spp)
    std::vector<Image> terms;  // one hybrid per all_budget_terms() entry, in that order
    double seconds = 0;
};

// Renders the budget's images (linear RGB, the scene's size). `tile_done` as in render().
ErrorBudgetImages render_error_budget(const RenderScene& scene, const ErrorBudgetOptions& options,
                                      const std::function<void()>& tile_done = {});

}  // namespace footprint
