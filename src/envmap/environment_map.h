// envmap/environment_map.h — environment maps as MIP pyramids, and filtered lookups over a
// footprint.
//
// A lat-long map is one pyramid with s repeating (the seam s = 0 ≡ 1 is continuous) and t clamped.
// A cube map is six square pyramids, +X −X +Y −Y +Z −Z (env_layout.h's face table and orientation),
// each clamped to its edges. Lookups take the footprint of env_footprint.h (K in level-0 texels of
// the face the direction lands on) and filter with footprint assembly (spec §2.8–2.9): the probes
// are placed on the centre face's plane along r1, and a probe centre that leaves the face is
// re-projected onto the face that owns its direction (spec §3.1 [E6s]); every probe reads the
// centre face's lod.
//
// Sphere and paraboloid maps keep the sphere in a disk; the texels outside it are filled with the
// environment's continuation (the sphere map folded back through its rim, the paraboloid's other
// hemisphere) so that bilinear taps and coarse levels are seamless across the rim. Probes that
// leave the valid region are placed by direction: cube probes on the neighbour face (§3.1),
// lat-long probes over the pole (the seam wraps in the pyramid), sphere-map probes folded back
// through the rim (§3.2, where λ1 is also clamped to W/2), paraboloid probes onto the other
// hemisphere (§3.3). Bilinear taps cross cube-face edges (seamless cube filtering).
//
// LookupOptions::max_probes (N_max) bounds a footprint's anisotropy on the sphere. A layout adds
// its own in texels: at most 2:1 on a cube face or on the lat-long map outside its polar caps,
// none on the conformal paraboloid, but without bound towards the sphere map's rim, where a round
// footprint is 2/(1 + r̂_z):1 (6.7:1 at r̂_z = −0.7, 67:1 at −0.97). A sphere-map line may therefore
// take N_max times the map's distortion at its centre (the ratio of the singular values of its
// Jacobian), up to 1 024 probes, instead of raising its lod and blurring across the rim. Where a
// lat-long footprint needs more probes than N_max, LookupOptions::ewa_beyond_probes filters it by
// EWA on the map (up to 64:1) instead of raising the probes' level, which blurs its minor axis.
// Only there: EWA is an ellipse in the face's (s, t), which cannot follow a cube's or a
// paraboloid's line onto the next face (measured worse than the raised level on the paraboloid
// near its equator), nor the sphere map's rim.
//
// Lat-long polar caps (beyond the spec's §3.4). Towards a pole a lat-long texel shrinks to nothing
// in s, a footprint there is 1/sin θ long in s (Rule B needs that many probes, and its probe budget
// then blurs t instead), and a footprint that reaches the pole has no (s, t) ellipse at all — the
// spec's isotropic probe there covers a narrow wedge of azimuths, not the polar cap. A lat-long map
// therefore also holds its two polar caps as gnomonic faces (the cube's ±Y faces, where the sphere
// is nearly isotropic: at most 1.15:1 within 30° of the pole), each texel the box-filtered average
// of the map's bilinear reconstruction over it (supersampled finely enough to resolve the lat-long
// texels), ⌈1.5·2H/π⌉ texels wide by default (1.5× the map's t-resolution at the pole;
// LatLongOptions). A lookup whose footprint centre lies within 30° of a pole, and whose footprint
// stays on the cap's face, filters the cap instead: K is carried over through the tangent plane,
// K_cap = M K Mᵀ with M = J_cap J_latlong⁻¹.
//
// Filters other than footprint assembly (trilinear, EWA, …) run texture_lookup() on the centre
// face only, without re-projection: use them for comparisons, not across cube edges.
#pragma once

#include <array>
#include <optional>
#include <span>

#include <footprint/core/result.h>
#include <footprint/envmap/env_footprint.h>
#include <footprint/envmap/env_layout.h>
#include <footprint/image/image.h>
#include <footprint/texture/mip_pyramid.h>
#include <footprint/texture/texture_lookup.h>

namespace footprint {

// How a lat-long map is held (see "Lat-long polar caps" above).
struct LatLongOptions {
    bool polar_caps = true;  // false: the spec's §3.4 behaviour at the poles, no extra memory
    // Cap texels per radian at the pole, relative to the map's H/π: 1.5 keeps the caps' own box
    // prefilter well below a lat-long texel, so that it adds little blur to the footprint's. The
    // two caps of (1.5·2H/π)² texels each add about 0.9 times the map's own 2H² texels (1.0: 0.4
    // times); docs/performance.md has both resolutions' pole_band errors.
    float polar_cap_resolution = 1.5f;
};

class EnvironmentMap {
  public:
    // A lat-long image (any size ≥ 1×1, 1–8 channels).
    static Result<EnvironmentMap> from_latlong(const Image& image,
                                               const LatLongOptions& options = {});
    // Six square faces of one size and channel count, in the order +X −X +Y −Y +Z −Z.
    static Result<EnvironmentMap> from_cube_faces(const std::array<Image, 6>& faces);
    // A square sphere map (spec §3.2; env_layout.h's orientation).
    static Result<EnvironmentMap> from_sphere(const Image& image);
    // Two square paraboloid maps of one size: front (+Z hemisphere) and back (spec §3.3).
    static Result<EnvironmentMap> from_paraboloid(const Image& front, const Image& back);
    // From the levels a map's pyramids stored (env_pyramid_file.h): face(f)'s levels, level 0
    // down to 1×1 in MipPyramid's sizes, for each of the layout's faces (a sphere or paraboloid
    // map's with their continued exterior), and a lat-long map's two polar caps' or none. The
    // same map as the one they came from, bit for bit (a cube's face borders are filled again).
    static Result<EnvironmentMap> from_face_levels(
        EnvLayout layout, const std::vector<std::vector<Image>>& faces,
        const std::vector<std::vector<Image>>& polar_caps = {});

    EnvLayout layout() const { return layout_; }
    int face_count() const { return static_cast<int>(faces_.size()); }
    int channels() const { return faces_.empty() ? 0 : faces_[0].channels(); }
    Vec2 texel_scale() const;  // S = (W0, H0) of a face's level 0
    const MipPyramid& face(int i) const { return faces_[i]; }
    // A lat-long map's polar caps: the +Y (pole 0) and −Y (pole 1) faces of a cube (env_layout.h's
    // face table), resampled from level 0 at build time; nullptr for other layouts.
    const MipPyramid* polar_cap(int pole) const {
        return polar_caps_.empty() ? nullptr : &polar_caps_[pole];
    }

  private:
    EnvLayout layout_ = EnvLayout::latlong;
    std::vector<MipPyramid> faces_;
    std::vector<MipPyramid> polar_caps_;  // lat-long only: +Y, −Y
};

// The options of a form-(a) lookup: LookupOptions and the environment's rotation.
struct EnvLookupOptions : LookupOptions {
    // A: world (ray) space → map space. None: the rays are in map space, and nothing is spent on
    // a rotation (an identity matrix given here is detected and skipped as well).
    std::optional<Mat3> rotation;

    EnvLookupOptions() = default;
    EnvLookupOptions(const LookupOptions& lookup, std::optional<Mat3> rotation = std::nullopt)
        : LookupOptions(lookup), rotation(rotation) {}
};

// The map filtered over `footprint` (from compute_env_footprint with this map's layout and
// texel_scale(), which applied any rotation): channels() floats to out.
void environment_lookup(const EnvironmentMap& map, const EnvFootprint& footprint,
                        const LookupOptions& options, float* out);

// Form (a), like OpenImageIO's environment(): the map filtered over the footprint of direction r
// with ray differentials ∂r/∂x, ∂r/∂y (compute_env_footprint form (a)), rotated into map space by
// options.rotation where it is set.
void environment_lookup(const EnvironmentMap& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                        const EnvLookupOptions& options, float* out);

// environment_lookup() form (a) for many rays at once (EnvRayDifferential, env_footprint.h): the
// same results bit for bit, faster. In each group of 16 rays the footprints, single-probe lods
// and short-line plans are computed four rays at a time (math/float4.h), and the lookups that are
// one probe or a short line on one face (most) have their texels requested then and are filtered
// after the group's last footprint, when the texels have arrived, instead of each waiting on
// memory in turn. `out` receives rays.size()·channels() floats, ray by ray (the role of
// OpenImageIO's batched environment(), without its 16-lane limit and structure-of-arrays layout).
void environment_lookup_batch(const EnvironmentMap& map, std::span<const EnvRayDifferential> rays,
                              const EnvLookupOptions& options, float* out);

// environment_lookup() of many computed footprints (form (b), Schilling's, or any
// compute_env_footprint() result) at once: bit-identical results, faster where the footprints are
// scattered over the map. In each group of 16, the lookups that are one probe or a short line on
// one cube face have their texels requested and are filtered after the group's last footprint is
// routed. `out` receives footprints.size()·channels() floats, footprint by footprint.
void environment_lookup_batch(const EnvironmentMap& map, std::span<const EnvFootprint> footprints,
                              const LookupOptions& options, float* out);

// A point sample: bilinear interpolation of level `level` at the direction r (any nonzero
// length), seamless across cube-face edges and the lat-long seam. The building block of the
// brute-force reference (env_reference.h).
void environment_bilinear(const EnvironmentMap& map, Vec3 r, int level, float* out);

}  // namespace footprint
