// apps/plane_view.h — an infinite textured ground plane seen at a grazing angle ("checkerboard to
// the horizon"), rendered with any texture filter, and its supersampled ground truth.
//
// Scene (world: y up). A pinhole camera at E = (0, h, 0) looks along +z, pitched down by
// `pitch_degrees`; the image is width × height pixels, horizontal field of view
// `horizontal_fov_degrees`, square pixels, no roll. Pixel (i, j) covers [i, i+1) × [j, j+1) in
// continuous pixel coordinates (x, y), y growing downwards; its centre is (i + ½, j + ½). The ray
// through (x, y) is r(τ) = E + τ d(x, y) with the (unnormalised) direction
//     d(x, y) = f + a (x − W/2) r − a (y − H/2) u,      a = tan(fov/2) / (W/2),
// f = (0, −sin p, cos p), u = (0, cos p, sin p), r = (1, 0, 0): d is linear in (x, y).
// It hits the plane y = 0 where d_y < 0, at τ = h / (−d_y), P = E + τ d. The texture coordinates
// are an affine map of the hit point's (P_x, P_z), rotated by `yaw_degrees` and scaled by
// `uv_scale` (texture repeats per world unit); t decreases with distance so that the texture's top
// row faces away from the viewer:
//     s = s0 + k ( cos θ P_x + sin θ P_z),   t = t0 + k ( sin θ P_x − cos θ P_z),   k = uv_scale.
// Pixels whose centre ray misses the plane (above the horizon) get the constant sky colour.
//
// Derivatives (exact ray differentials of the plane; PlaneView::sample). Let d' be ∂d/∂x = a r or
// ∂d/∂y = −a u (constant). Differentiating τ = −h/d_y gives ∂τ = h d'_y/d_y² = −τ d'_y/d_y, so
//     ∂P = τ d' + ∂τ d = τ ( d' − (d'_y / d_y) d )      (∂P_y = 0: P stays on the plane)
// and ∂(s, t) is the linear part of the (s, t) map applied to (∂P_x, ∂P_z). These are exact
// derivatives of the pixel → (s, t) map at the pixel centre, not finite differences.
//
// Every pixel is computed independently from its own coordinates, rows in parallel with oneTBB:
// the images are bit-identical for any thread count.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "image/image.h"
#include "texture/mip_pyramid.h"
#include "texture/texture_lookup.h"

namespace footprint {

class Progress;

struct PlaneViewOptions {
    int width = 480;
    int height = 270;
    double eye_height = 1.0;                           // h, world units above the plane
    double pitch_degrees = 10.0;                       // view direction below the horizontal
    double horizontal_fov_degrees = 60.0;              // vertical fov follows from the aspect ratio
    double yaw_degrees = 25.0;                         // rotation of the texture on the plane
    double uv_scale = 0.125;                           // texture periods per world unit
    double s_offset = 0.5, t_offset = 1.0;             // (s, t) below the eye
    std::array<float, 3> sky = {0.42f, 0.58f, 0.85f};  // linear RGB
};

// The demo's aspect ratio: height = round(width · 9/16), at least 1.
int plane_view_height(int width);

// Where a ray meets the plane. (s, t) are not wrapped (they grow without bound towards the horizon;
// doubles keep them exact enough to wrap later); derivatives are per pixel step.
struct PlaneSample {
    bool hit = false;
    double s = 0, t = 0;
    double dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;
};

class PlaneView {
  public:
    explicit PlaneView(const PlaneViewOptions& options);

    // The ray through continuous pixel position (x, y) (pixel centres at +½) with derivatives.
    PlaneSample sample(double x, double y) const;
    // The same without derivatives (the reference's inner loop).
    bool hit(double x, double y, double& s, double& t) const;
    // True if the ray through row position y meets the plane (independent of x: no roll).
    bool hits_row(double y) const { return direction_y(y) < -kMinDirectionY; }
    // True if, for every pixel of row `row`, the reference's whole pixel filter (±3σ = ±1.5 px
    // around the centre) lies on the plane: the rows the RMSE is measured on.
    bool covers_row(int row) const { return hits_row(row + 0.5 - 1.5); }
    // The continuous row of the horizon, y where d_y = 0.
    double horizon_row() const;

    const PlaneViewOptions& options() const { return options_; }

  private:
    // Rays flatter than this never hit: keeps τ ≤ h·1e9, all values finite.
    static constexpr double kMinDirectionY = 1e-9;
    double direction_y(double y) const { return -sin_p_ - a_ * (y - cy_) * cos_p_; }

    PlaneViewOptions options_;
    double a_ = 0, cx_ = 0, cy_ = 0, sin_p_ = 0, cos_p_ = 0, cos_yaw_ = 1, sin_yaw_ = 0;
};

struct PlaneRenderStats {
    double seconds = 0;
    std::uint64_t lookups = 0;  // texture_lookup() calls
};

// One image with one filter: pixel centres on the plane get texture_lookup(pyramid, coords,
// lookup) with the analytic derivatives; the others the sky. The image has pyramid.channels()
// channels (sky: RGB → grey for 1–2 channels, alpha 1). (s, t) are wrapped in double precision
// before they are rounded to float. `progress` (optional) is advanced once per row.
Image render_plane_view(const MipPyramid& pyramid, const PlaneViewOptions& view,
                        const LookupOptions& lookup, PlaneRenderStats* stats = nullptr,
                        Progress* progress = nullptr);

// Ground truth: per pixel, N × N stratified jittered samples of the scene, each a bilinear
// level-0 lookup (or the sky where its ray misses), averaged with equal weights. The samples are
// distributed as a Gaussian pixel filter of σ = ½ pixel (truncated at ±3σ): each stratum of the
// unit square is mapped through the inverse normal CDF, per axis. That is the pixel filter whose
// image in texel space has covariance K/4 — the measure every filter of the library implements
// (texture_lookup.h, spec §2.6) — so the comparison measures filtering error, not a different
// choice of pixel filter. A box pixel filter would penalise the correct K/4 kernels for being
// wider than the box. Jitter comes from a hash of (pixel, sample, seed): deterministic.
// Noise: towards the horizon a pixel covers the texture many times over and N² samples estimate
// that mean with an error of order (texture std)/N, a floor under every filter's RMSE there.
struct PlaneReferenceOptions {
    int samples_per_axis = 16;
    std::uint32_t seed = 1;
};
Image render_plane_reference(const MipPyramid& pyramid, const PlaneViewOptions& view,
                             const PlaneReferenceOptions& options = {},
                             PlaneRenderStats* stats = nullptr, Progress* progress = nullptr);

// RMSE in linear light over all channels of the pixels for which PlaneView::covers_row holds
// (the plane, away from the horizon's sky/ground edge that no texture filter is meant to
// antialias). `pixels` (optional) receives the number of pixels measured. 0 if there are none.
double plane_rmse(const Image& image, const Image& reference, const PlaneViewOptions& view,
                  std::size_t* pixels = nullptr);

}  // namespace footprint
