#include "envmap/environment_map.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "envmap/env_sampling.h"
#include "envmap/latlong_path.h"
#include "envmap/polar_caps.h"
#include "texture/footprint_assembly.h"
#include "texture/sampling.h"

namespace footprint {

namespace {

Status check_image(const Image& image, const std::string& what) {
    if (image.empty() || image.width < 1 || image.height < 1) return Error{what + " is empty"};
    if (image.channels < 1 || image.channels > MipPyramid::kMaxChannels)
        return Error{what + " has " + std::to_string(image.channels) +
                     " channels (1 to 8 supported)"};
    if (image.pixels.size() != image.pixel_count() * image.channels)
        return Error{what + " is malformed"};
    return {};
}

// Probe placement on the sphere for the curved layouts (lat-long, sphere, paraboloid): a probe
// offset o (level-0 texels, along r1) is taken back to the tangent plane at r̂ through the inverse
// of the tangent Jacobian J_t = S·J_P·[e1 e2] and placed at the direction r̂ + J_t⁻¹o (the gnomonic
// point, so the probes lie on the great circle through r̂ — exactly what the cube's face-plane
// offsets are). In (s, t) the probes then follow the map's own curvature: latitude circles near
// the poles, the sphere map's bent iso-lines near its rim, the paraboloid's other hemisphere.
struct TangentProbes {
    bool valid = false;
    Vec3 centre, e1, e2;   // r̂ and a tangent basis
    float inv[2][2] = {};  // J_t⁻¹ (radians per texel)

    static TangentProbes at(const EnvironmentMap& map, Vec3 direction) {
        TangentProbes p;
        if (map.layout() == EnvLayout::cube) return p;  // face-plane offsets are already gnomonic
        const float len = std::sqrt(dot(direction, direction));
        if (!(len > 0) || !std::isfinite(len)) return p;
        p.centre = direction / len;
        tangent_basis(p.centre, p.e1, p.e2);
        const Jacobian23 j = env_jacobian(map.layout(), p.centre);
        const Vec2 scale = map.texel_scale();
        const float j11 = scale.x * dot(j.ds, p.e1), j12 = scale.x * dot(j.ds, p.e2);
        const float j21 = scale.y * dot(j.dt, p.e1), j22 = scale.y * dot(j.dt, p.e2);
        const float det = j11 * j22 - j12 * j21;
        if (!(std::fabs(det) > 1e-12f * (j11 * j11 + j12 * j12 + j21 * j21 + j22 * j22)) ||
            !std::isfinite(det))
            return p;
        p.inv[0][0] = j22 / det, p.inv[0][1] = -j12 / det;
        p.inv[1][0] = -j21 / det, p.inv[1][1] = j11 / det;
        p.valid = true;
        return p;
    }

    // The ratio of J_t's singular values (≥ 1): how much the layout stretches a round footprint,
    // the anisotropy of the ellipse of J_t⁻¹'s columns.
    float distortion() const {
        const FootprintEllipse e =
            make_footprint_ellipse(Vec2{inv[0][0], inv[1][0]}, Vec2{inv[0][1], inv[1][1]});
        const float ratio = e.major_radius / e.minor_radius;
        return std::isfinite(ratio) ? std::max(ratio, 1.0f) : 1.0f;
    }

    EnvCoords place(EnvLayout layout, Vec2 offset) const {
        const float a = inv[0][0] * offset.x + inv[0][1] * offset.y;
        const float b = inv[1][0] * offset.x + inv[1][1] * offset.y;
        return env_coords(layout, centre + a * e1 + b * e2);
    }
};

// N_max for a sphere-map line centred at `direction`: scaled by the map's distortion there
// (TangentProbes::distortion()), within kMaxProbeCount. Out of line: the rare layout.
[[gnu::noinline]] int sphere_probe_limit(const EnvironmentMap& map, Vec3 direction,
                                         int max_probes) {
    const TangentProbes tangent = TangentProbes::at(map, direction);
    if (!tangent.valid) return max_probes;
    const float scaled =
        std::ceil(static_cast<float>(std::max(max_probes, 1)) * tangent.distortion());
    return scaled < static_cast<float>(kMaxProbeCount) ? static_cast<int>(scaled) : kMaxProbeCount;
}

// Where a probe centre (s, t) of `face` lands: itself while it lies on the face's valid region,
// otherwise the face and (s, t) that own its direction (spec §3.1 [E6s], §3.3, §3.4): cube
// probes move to the neighbour face, lat-long probes beyond a pole continue over it along the
// great circle (the seam s = 0 ≡ 1 wraps in the pyramid itself), sphere-map probes beyond the rim
// fold back into the disk, and paraboloid probes beyond the equator move to the other hemisphere.
EnvCoords place_probe(EnvLayout layout, int face, float s, float t) {
    switch (layout) {
        case EnvLayout::cube:
            if (s < 0 || s > 1 || t < 0 || t > 1) return cube_reproject(face, s, t);
            break;
        case EnvLayout::latlong:
            if (t < 0 || t > 1) {
                const Vec2 st = latlong_coords(latlong_direction(s, t));
                return {0, st.x, st.y};
            }
            break;
        case EnvLayout::sphere:
        case EnvLayout::paraboloid: {
            const float a = 2 * s - 1, b = 2 * t - 1;
            if (a * a + b * b > 1) return env_coords(layout, env_direction(layout, face, s, t));
            break;
        }
    }
    return {face, s, t};
}

// Bilinear sample of `image` at (s, t) with clamp-to-edge (building the disk exteriors).
void image_bilinear(const Image& image, float s, float t, float* out) {
    const float x = std::clamp(s * static_cast<float>(image.width) - 0.5f, 0.0f,
                               static_cast<float>(image.width - 1));
    const float y = std::clamp(t * static_cast<float>(image.height) - 0.5f, 0.0f,
                               static_cast<float>(image.height - 1));
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    for (int c = 0; c < image.channels; ++c)
        out[c] = (1 - fy) * ((1 - fx) * image.at(x0, y0, c) + fx * image.at(x1, y0, c)) +
                 fy * ((1 - fx) * image.at(x0, y1, c) + fx * image.at(x1, y1, c));
}

// Sphere and paraboloid images hold the sphere in a disk; the texels outside it (the corners of
// the square) are unused by point lookups but read by bilinear taps at the rim and averaged into
// the coarser levels. They are filled with the environment's own continuation — the direction
// env_direction() gives them (the sphere map folded back through its rim, the paraboloid's
// other hemisphere) — so that taps, probes and pyramid levels stay seamless across the rim.
std::vector<Image> with_continued_exterior(EnvLayout layout, const std::vector<Image>& faces) {
    std::vector<Image> result = faces;
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
        Image& image = result[f];
        const float w = static_cast<float>(image.width), h = static_cast<float>(image.height);
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const float s = (static_cast<float>(x) + 0.5f) / w;
                const float t = (static_cast<float>(y) + 0.5f) / h;
                const float a = 2 * s - 1, b = 2 * t - 1;
                if (a * a + b * b <= 1) continue;
                const EnvCoords c = env_coords(layout, env_direction(layout, f, s, t));
                image_bilinear(faces[c.face], c.s, c.t, image.at(x, y));
            }
    }
    return result;
}

// Fills each cube face's one-texel border (MipPyramidOptions::border), on every level, with the
// texels env_texel_beyond_edge() reads there: a neighbour face's edge texels along each edge, and
// at each corner the texel its direction finds. Bilinear taps then cross face edges as plain reads.
void fill_cube_borders(const EnvironmentMap& map, std::vector<MipPyramid>& faces) {
    for (int f = 0; f < 6; ++f)
        for (int l = 0; l < faces[f].level_count(); ++l) {
            const int w = faces[f].width(l), stride = faces[f].stride();
            auto fill = [&](int x, int y) {
                std::copy_n(detail::env_texel_beyond_edge(map, f, l, x, y), stride,
                            faces[f].writable_texel(l, x, y));
            };
            for (int i = -1; i <= w; ++i) fill(i, -1), fill(i, w);
            for (int i = 0; i < w; ++i) fill(-1, i), fill(w, i);
        }
}
}  // namespace

Vec2 EnvironmentMap::texel_scale() const {
    if (faces_.empty()) return {1, 1};
    return {static_cast<float>(faces_[0].width(0)), static_cast<float>(faces_[0].height(0))};
}

Result<EnvironmentMap> EnvironmentMap::from_latlong(const Image& image,
                                                    const LatLongOptions& latlong_options) {
    if (Status s = check_image(image, "lat-long map"); !s) return s.error();
    if (latlong_options.polar_caps &&
        !(latlong_options.polar_cap_resolution > 0 && latlong_options.polar_cap_resolution <= 4))
        return Error{"lat-long polar cap resolution " +
                     std::to_string(latlong_options.polar_cap_resolution) + " is outside (0, 4]"};
    EnvironmentMap map;
    map.layout_ = EnvLayout::latlong;
    MipPyramidOptions options;
    options.wrap_s = WrapMode::repeat;  // the seam
    options.wrap_t = WrapMode::clamp;   // the poles
    map.faces_.push_back(MipPyramid::build(image, options));
    if (!latlong_options.polar_caps) return map;
    MipPyramidOptions cap_options;
    cap_options.wrap_s = cap_options.wrap_t = WrapMode::clamp;
    const int cap_size = polar_cap_size(image.height, latlong_options.polar_cap_resolution);
    for (int face : {2, 3})  // +Y, −Y
        map.polar_caps_.push_back(
            MipPyramid::build(polar_cap_image(map, face, cap_size), cap_options));
    return map;
}

Result<EnvironmentMap> EnvironmentMap::from_cube_faces(const std::array<Image, 6>& faces) {
    static const char* kNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    EnvironmentMap map;
    map.layout_ = EnvLayout::cube;
    MipPyramidOptions options;
    options.wrap_s = options.wrap_t = WrapMode::clamp;
    options.border = 1;  // the neighbour faces' texels, filled below: taps cross edges as reads
    for (int f = 0; f < 6; ++f) {
        const std::string name = std::string("cube face ") + kNames[f];
        if (Status s = check_image(faces[f], name); !s) return s.error();
        if (faces[f].width != faces[f].height)
            return Error{name + " is " + std::to_string(faces[f].width) + "x" +
                         std::to_string(faces[f].height) + ", not square"};
        if (faces[f].width != faces[0].width || faces[f].channels != faces[0].channels)
            return Error{name + " differs in size or channels from face +X"};
        map.faces_.push_back(MipPyramid::build(faces[f], options));
    }
    fill_cube_borders(map, map.faces_);
    return map;
}

Result<EnvironmentMap> EnvironmentMap::from_sphere(const Image& image) {
    if (Status s = check_image(image, "sphere map"); !s) return s.error();
    if (image.width != image.height)
        return Error{"sphere map is " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + ", not square"};
    EnvironmentMap map;
    map.layout_ = EnvLayout::sphere;
    MipPyramidOptions options;
    options.wrap_s = options.wrap_t = WrapMode::clamp;
    map.faces_.push_back(
        MipPyramid::build(with_continued_exterior(EnvLayout::sphere, {image})[0], options));
    return map;
}

Result<EnvironmentMap> EnvironmentMap::from_paraboloid(const Image& front, const Image& back) {
    if (Status s = check_image(front, "paraboloid front map"); !s) return s.error();
    if (Status s = check_image(back, "paraboloid back map"); !s) return s.error();
    if (front.width != front.height)
        return Error{"paraboloid front map is " + std::to_string(front.width) + "x" +
                     std::to_string(front.height) + ", not square"};
    if (back.width != front.width || back.height != front.height || back.channels != front.channels)
        return Error{"paraboloid back map differs in size or channels from the front map"};
    EnvironmentMap map;
    map.layout_ = EnvLayout::paraboloid;
    MipPyramidOptions options;
    options.wrap_s = options.wrap_t = WrapMode::clamp;
    for (const Image& face : with_continued_exterior(EnvLayout::paraboloid, {front, back}))
        map.faces_.push_back(MipPyramid::build(face, options));
    return map;
}

namespace {

// The level of the one trilinear probe at the footprint's centre that a near-isotropic footprint
// takes (without the ellipse's axes), or −1 where the lookup takes another path: a polar cap, a
// line of probes, another filter, or the sphere map's rim.
float centre_probe_lod(const EnvironmentMap& map, const EnvFootprint& footprint,
                       const LookupOptions& options) {
    if (!footprint.matrix.is_finite()) return -1;
    if (map.layout() == EnvLayout::latlong && map.polar_cap(0) &&
        in_polar_cap_region(footprint.map_direction))
        return -1;
    const float width = map.texel_scale().x;
    if (map.layout() == EnvLayout::sphere && footprint.matrix.trace() > 0.25f * width * width)
        return -1;
    return single_probe_lod(footprint.matrix, options, map.face(footprint.coords.face).max_level());
}

// The one trilinear probe at the footprint's centre, c at lod (centre_probe_lod()): where it is and
// which levels it reads. A single lookup reads it at once (filter_centre_probe); the batch
// requests its taps first and reads them later (batch_lookup()).
struct CentreProbe {
    EnvCoords coords;
    detail::TrilinearLevels levels;
};
[[gnu::always_inline]] inline CentreProbe centre_probe(const EnvironmentMap& map,
                                                       const EnvCoords& c, float lod,
                                                       const LookupOptions& options) {
    return {c, detail::trilinear_levels(lod, map.face(c.face).max_level(),
                                        single_probe_blend(options.lod_blend))};
}

void filter_probe_taps(const EnvironmentMap& map, const detail::ProbeTaps& taps,
                       detail::TrilinearLevels levels, float* out) {
    detail::dispatch_stride(map.face(0).stride(), [&]<int S>() {
        detail::store(detail::blend_probe<S>(taps, levels), map.channels(), out);
    });
}

void filter_centre_probe(const EnvironmentMap& map, const CentreProbe& probe, float* out) {
    const EnvCoords& c = probe.coords;
    filter_probe_taps(map, detail::probe_taps_on_face(map, c.face, c.s, c.t, probe.levels),
                      probe.levels, out);
}

// A lat-long footprint near a pole, carried onto its polar cap; invalid elsewhere.
PolarCapFootprint cap_footprint(const EnvironmentMap& map, const EnvFootprint& footprint) {
    return map.layout() == EnvLayout::latlong && map.polar_cap(0)
               ? polar_cap_footprint(map, footprint)
               : PolarCapFootprint{};
}

// What general_lookup() reads of a footprint: taken from an EnvFootprint or, without building one,
// from a PlainEnvFootprint (implicitly: either is passed as is).
struct FootprintCentre {
    EnvCoords coords;
    Sym2 matrix;
    Vec3 map_direction;

    FootprintCentre(const EnvFootprint& f)
        : coords(f.coords), matrix(f.matrix), map_direction(f.map_direction) {}
    FootprintCentre(const PlainEnvFootprint& f)
        : coords(f.coords), matrix(f.matrix), map_direction(f.map_direction) {}
    FootprintCentre(const PlainEnvFootprints4& f, int lane)
        : coords(f.coords(lane)), matrix(f.matrix(lane)), map_direction(f.map_direction(lane)) {}
};

// The position on face c.face of each probe of a cube line centred at c: c + the probe's offset, in
// (s, t).
struct FacePositions {
    const EnvCoords& c;
    const ProbePlan& plan;
    Vec2 size;

    FacePositions(const MipPyramid& face, const EnvCoords& c, const ProbePlan& plan)
        : c(c),
          plan(plan),
          size{static_cast<float>(face.width(0)), static_cast<float>(face.height(0))} {}
    Vec2 operator()(int i) const {
        const Vec2 o = plan.offset(i);
        return Vec2{c.s + o.x / size.x, c.t + o.y / size.y};
    }
};

// A cube line of probes whose ends' taps lie on the centre face's levels (detail::line_inside()):
// all its probes' taps lie there too (a face is convex), at the positions place_probe() is given,
// so they are read without placing each on its face. False, with nothing written, for any other
// line. Out of line, so that its body does not change how general_lookup()'s other loops compile,
// and given the plan and centre by value, so that its loop keeps them in registers instead of
// reloading them through references.
[[gnu::noinline, gnu::flatten]] bool cube_line_on_face(const MipPyramid& face, const EnvCoords c,
                                                       const ProbePlan plan, const float* weights,
                                                       detail::TrilinearLevels levels, float* out) {
    return detail::blend_probe_line_inside(face, plan.count, weights, levels,
                                           FacePositions{face, c, plan}, out);
}

// The cube lines on their face (cube_line_on_face()) of at most kDeferredProbes probes: the batch
// requests them and reads them once its group's footprints are computed.
constexpr int kDeferredProbes = detail::kRequestedLineProbes;
using DeferredCubeLine = detail::RequestedLine<kDeferredProbes>;

// cube_line_on_face()'s line, requested into `line` for a later read (DeferredCubeLine::blend());
// false, with nothing requested, for any other line or one of more than kDeferredProbes probes.
[[gnu::noinline, gnu::flatten]] bool request_cube_line_on_face(
    const MipPyramid& face, const EnvCoords c, const ProbePlan plan, const float* weights,
    detail::TrilinearLevels levels, DeferredCubeLine& line) {
    const FacePositions position_of{face, c, plan};
    bool requested = false;
    detail::dispatch_stride(face.stride(), [&]<int S>() {
        requested = line.request<S>(face, plan.count, weights, levels, position_of(0),
                                    position_of(plan.count - 1), position_of);
    });
    return requested;
}

// A lat-long line of probes on its quadratic path whose taps all lie on the map's levels, clear of
// the seam and the poles (the path's bounds() admitted by detail::line_inside()): its probes are
// read without placing each (the seam's wrap leaves s ∈ (0, 1) as it is). False, with nothing
// written, for any other line. Out of line and given the path by value, as cube_line_on_face().
[[gnu::noinline, gnu::flatten]] bool latlong_path_inside(const MipPyramid& map,
                                                         const QuadraticPath path, int count,
                                                         const float* weights,
                                                         detail::TrilinearLevels levels,
                                                         float* out) {
    const auto [lower, upper] = path.bounds();
    return detail::blend_probe_path_inside(
        map, count, weights, levels, lower, upper, [&](int i) { return path.position(i, count); },
        out);
}

bool lookup_plan(const EnvironmentMap& map, const FootprintCentre& footprint, const ProbePlan& plan,
                 const LookupOptions& options, float* out, DeferredCubeLine* defer);

// Every other lookup (a line of probes, another filter), given the footprint's cap_footprint(),
// done into out; or, given `defer` (the batch), a cube line on its face requested into it for a
// later read: then true. Flattened: everything it calls that can be inlined is, so that its probe
// loop compiles the same however much else this file inlines (otherwise GCC's unit-growth limit
// can push the probe taps out of line as the file grows).
[[gnu::flatten]] bool general_lookup(const EnvironmentMap& map, const FootprintCentre& footprint,
                                     const PolarCapFootprint& cap, const LookupOptions& options,
                                     float* out, DeferredCubeLine* defer) {
    if (cap.valid) {
        polar_cap_filter(cap, options, out);
        return false;
    }
    const EnvCoords& c = footprint.coords;
    const MipPyramid& centre = map.face(c.face);
    const Vec2 size = map.texel_scale();
    FootprintEllipse e = footprint.matrix.is_finite() ? make_footprint_ellipse(footprint.matrix)
                                                      : FootprintEllipse{};
    if (map.layout() == EnvLayout::sphere && e.major_radius > 0.5f * size.x) {
        // §3.2: towards the singular rim the anisotropy grows without bound; clamp λ1 ≤ W/2.
        e.major_radius = 0.5f * size.x;
        e.minor_radius = std::min(e.minor_radius, e.major_radius);
        e.matrix = e.from_axes();
    }
    if (options.filter != TextureFilter::footprint_assembly) {
        texture_lookup(centre, c.s, c.t, e, options, out);  // on the centre face only
        return false;
    }
    // Footprint assembly (spec §2.8–2.9): probes along r1 on the centre face's (s, t) plane, each
    // placed on the face that owns its direction (place_probe), all at the centre face's lod.
    // N_max bounds the anisotropy on the sphere (environment_map.h): towards the sphere map's rim
    // the map adds up to 67:1 of its own, so a line there may take N_max × its distortion.
    const int max_probes =
        map.layout() == EnvLayout::sphere
            ? sphere_probe_limit(map, footprint.map_direction, options.max_probes)
            : options.max_probes;
    return lookup_plan(map, footprint,
                       plan_probes(e, options.probe_rule, max_probes, centre.max_level(),
                                   options.lod_bias, options.isotropic_ratio),
                       options, out, defer);
}

// Footprint assembly of a planned line (general_lookup()'s, or the batch's short_plans4()):
// done into out, or, given `defer`, a cube line on its face requested into it (then true).
[[gnu::flatten]] bool lookup_plan(const EnvironmentMap& map, const FootprintCentre& footprint,
                                  const ProbePlan& plan, const LookupOptions& options, float* out,
                                  DeferredCubeLine* defer) {
    const EnvCoords& c = footprint.coords;
    const MipPyramid& centre = map.face(c.face);
    const Vec2 size = map.texel_scale();
    const LodBlend blend = effective_lod_blend(plan, options.lod_blend);
    float weights[kMaxProbeCount];
    probe_weights(plan, weights);
    const TangentProbes tangent =
        plan.count > 1 ? TangentProbes::at(map, footprint.map_direction) : TangentProbes{};
    const QuadraticPath path =
        map.layout() == EnvLayout::latlong && tangent.valid && plan.count > 2
            ? QuadraticPath::through(
                  c, tangent.place(EnvLayout::latlong, plan.offset(plan.count - 1)),
                  tangent.place(EnvLayout::latlong, -plan.offset(plan.count - 1)))
            : QuadraticPath{};
    // All probes read plan.lod's levels (the centre face's).
    const detail::TrilinearLevels levels =
        detail::trilinear_levels(plan.lod, centre.max_level(), blend);
    if (map.layout() == EnvLayout::cube) {
        // (The count is tested here too, so that longer lines skip the call.)
        if (defer && plan.count <= kDeferredProbes &&
            request_cube_line_on_face(centre, c, plan, weights, levels, *defer))
            return true;
        if (cube_line_on_face(centre, c, plan, weights, levels, out)) return false;
    }
    if (path.valid && latlong_path_inside(centre, path, plan.count, weights, levels, out))
        return false;
    // Each probe is placed on the face or at the direction that owns it (place_probe,
    // TangentProbes, QuadraticPath), its taps read seamlessly.
    auto place = [&](int i) {
        const Vec2 o = plan.offset(i);
        EnvCoords p;
        if (!(path.valid && path.place(i, plan.count, p)))
            p = tangent.valid
                    ? tangent.place(map.layout(), o)
                    : place_probe(map.layout(), c.face, c.s + o.x / size.x, c.t + o.y / size.y);
        return p;
    };
    detail::dispatch_stride(centre.stride(), [&]<int S>() {
        const detail::Texel<S> result =
            detail::blend_probe_line<S>(plan.count, weights, levels, centre.stride(), [&](int i) {
                const EnvCoords p = place(i);
                return detail::probe_taps(map, p.face, p.s, p.t, levels);
            });
        detail::store(result, centre.channels(), out);
    });
    return false;
}

// Whether the polar caps of a lat-long map take a direction (map space) rather than the map.
bool in_caps_region(const EnvironmentMap& map, Vec3 map_direction) {
    return map.layout() == EnvLayout::latlong && map.polar_cap(0) &&
           in_polar_cap_region(map_direction);
}

// Form (a) on a lat-long map, for a direction within a polar cap's region (in_caps_region()): the
// cap's footprint needs only the map-space direction and its differentials (as
// compute_env_footprint() sets them), so the lat-long footprint (two atan2 and its Jacobian) is
// skipped. False, with nothing written, where the cap cannot take it (then the lat-long footprint
// decides).
bool polar_cap_lookup(const EnvironmentMap& map, Vec3 r, Vec3 map_direction, Vec3 dr_dx, Vec3 dr_dy,
                      const IdentitySkippingRotation& to_map, const LookupOptions& options,
                      float* out) {
    if (!is_finite(r)) return false;
    const bool spread = is_finite(dr_dx) && is_finite(dr_dy);  // else a point lookup
    const PolarCapFootprint cap = polar_cap_footprint(
        map, map_direction, spread ? to_map(dr_dx) : Vec3{}, spread ? to_map(dr_dy) : Vec3{});
    if (!cap.valid) return false;
    polar_cap_filter(cap, options, out);
    return true;
}

// What route_lookup() did with a lookup: done it into out, left its centre probe to the
// caller, or (given a DeferredCubeLine) requested its cube line there for the caller to read.
enum class Routed { done, centre_probe, deferred_line };

// A lookup of a computed footprint: one probe at its centre, returned in `probe` for the caller to
// filter, a cube line on its face requested into `defer` where given, or any other lookup, done
// here into out.
[[gnu::always_inline]] inline Routed route_lookup(const EnvironmentMap& map,
                                                  const EnvFootprint& footprint,
                                                  const LookupOptions& options, float* out,
                                                  CentreProbe& probe, DeferredCubeLine* defer) {
    const float lod = centre_probe_lod(map, footprint, options);
    if (lod >= 0.0f) {
        probe = centre_probe(map, footprint.coords, lod, options);
        return Routed::centre_probe;
    }
    return general_lookup(map, footprint, cap_footprint(map, footprint), options, out, defer)
               ? Routed::deferred_line
               : Routed::done;
}

// A form (a) lookup, routed: a polar cap's (in its region), the common case in one pass
// (plain_env_footprint()), or the careful path (compute_env_footprint()). A lookup that is one
// probe at the footprint's centre (most are) is returned in `probe`, for the caller to filter (the
// batch defers it until its texels have arrived); given `defer` (the batch), a cube line on its
// face is requested there; every other lookup is done here, into out.
[[gnu::always_inline]] inline Routed route_lookup(const EnvironmentMap& map, Vec3 r, Vec3 dr_dx,
                                                  Vec3 dr_dy, const LookupOptions& options,
                                                  const IdentitySkippingRotation& to_map,
                                                  float* out, CentreProbe& probe,
                                                  DeferredCubeLine* defer) {
    const Vec3 map_direction = to_map(r);
    if (in_caps_region(map, map_direction)) {
        if (polar_cap_lookup(map, r, map_direction, dr_dx, dr_dy, to_map, options, out))
            return Routed::done;
    } else if (PlainEnvFootprint plain; plain_env_footprint(map.layout(), map.texel_scale(), r,
                                                            dr_dx, dr_dy, to_map, plain)) {
        const float lod =
            single_probe_lod(plain.matrix, options, map.face(plain.coords.face).max_level());
        if (lod >= 0.0f) {
            probe = centre_probe(map, plain.coords, lod, options);
            return Routed::centre_probe;
        }
        return general_lookup(map, plain, PolarCapFootprint{}, options, out, defer)  // no caps
                   ? Routed::deferred_line
                   : Routed::done;
    }
    return route_lookup(
        map,
        compute_env_footprint(map.layout(), map.texel_scale(), r, dr_dx, dr_dy, to_map.matrix()),
        options, out, probe, defer);
}

// What a batch does with a routed lookup whose result goes to `result`: a deferred line is added
// to `reads`, a centre probe's taps are requested into it, a lookup done needs nothing.
template <std::size_t Capacity>
[[gnu::always_inline]] inline void add_routed(const EnvironmentMap& map, Routed routed,
                                              const CentreProbe& probe, int stride, float* result,
                                              detail::RequestedReads<Capacity>& reads) {
    switch (routed) {
        case Routed::done:
            break;
        case Routed::deferred_line:
            reads.add(detail::Requested::line, result);
            break;
        case Routed::centre_probe: {
            const EnvCoords& c = probe.coords;
            detail::RequestedProbe& requested = reads.next_probe();
            requested = {detail::probe_taps(map, c.face, c.s, c.t, probe.levels), probe.levels};
            requested.request(stride);
            reads.add(detail::Requested::probe, result);
            break;
        }
    }
}

// A form (a) lookup (the single-call entry points).
[[gnu::always_inline]] inline void single_lookup(const EnvironmentMap& map, Vec3 r, Vec3 dr_dx,
                                                 Vec3 dr_dy, const LookupOptions& options,
                                                 const IdentitySkippingRotation& to_map,
                                                 float* out) {
    CentreProbe probe;
    if (route_lookup(map, r, dr_dx, dr_dy, options, to_map, out, probe, nullptr) ==
        Routed::centre_probe)
        filter_centre_probe(map, probe, out);
}

// The footprints of four rays of a batch, computed at once (math/float4.h), each lane exactly what
// route_lookup() computes for its ray: the polar-cap footprint where a lat-long map's caps take it,
// the plain footprint (plain_env_footprint()) of a cube or lat-long map elsewhere, the
// single-probe lods, and the plans of the short lines among them. A lane that none of them takes
// goes the scalar way (route_lookup()).
struct FourFootprints {
    // What every group computes the same way: the map's and the options' constants.
    struct Setting {
        bool four_at_once;  // a cube or lat-long map
        bool caps;          // a lat-long map with polar caps
        bool rule_b;        // has_single_probe_rule(): else every lod is −1 and no plan is made
        int max_level, cap_max_level;  // every face's, both caps'

        Setting(const EnvironmentMap& map, const LookupOptions& options)
            : four_at_once(map.layout() == EnvLayout::cube || map.layout() == EnvLayout::latlong),
              caps(map.layout() == EnvLayout::latlong && map.polar_cap(0)),
              rule_b(has_single_probe_rule(options)),
              max_level(map.face(0).max_level()),
              cap_max_level(caps ? map.polar_cap(0)->max_level() : 0) {}
    };

    PolarCapFootprints4 capped;  // region: the caps' lanes; valid: the lanes they take
    PlainEnvFootprints4 plain;   // outside the caps' region
    float lod[4];                // the plain footprints' single-probe lods (< 0: a line)
    ShortPlans4 plans, cap_plans;

    [[gnu::always_inline]] void compute(const EnvironmentMap& map, const EnvRayDifferential* rays,
                                        const IdentitySkippingRotation& to_map,
                                        const LookupOptions& options, const Setting& setting) {
        plain.plain = plans.planned = 0;
        if (setting.caps) {
            polar_cap_footprints4(map, rays, to_map, options, capped);
            cap_plans.planned = 0;
            if (setting.rule_b &&
                (capped.valid & (Float4::load(capped.lod) < Float4(0.0f)).bits()) != 0)
                short_plans4(Float4::load(capped.xx), Float4::load(capped.xy),
                             Float4::load(capped.yy), options.probe_rule, options.max_probes,
                             setting.cap_max_level, options.lod_bias, options.isotropic_ratio,
                             cap_plans);
            if (capped.region == 0xf) return;  // no lane for plain_env_footprint()
        }
        plain_env_footprints4(map.layout(), map.texel_scale(), rays, to_map, plain);
        if (!setting.rule_b) {
            Float4(-1.0f).store(lod);
            return;
        }
        const Float4 xx = Float4::load(plain.xx), xy = Float4::load(plain.xy),
                     yy = Float4::load(plain.yy);
        const Float4 lods = single_probe_lod(xx, xy, yy, options.lod_bias, setting.max_level,
                                             options.isotropic_ratio);
        lods.store(lod);
        if (((lods < Float4(0.0f)).bits() & plain.plain) != 0)
            short_plans4(xx, xy, yy, options.probe_rule, options.max_probes, setting.max_level,
                         options.lod_bias, options.isotropic_ratio, plans);
    }

    bool cap_takes(int lane) const { return capped.valid >> lane & 1; }
    bool plain_takes(int lane) const {
        return (plain.plain >> lane & 1) && !(capped.region >> lane & 1);
    }
};

// Form (a) lookups of many rays (the batch entry points).
[[gnu::always_inline]] inline void batch_lookup(const EnvironmentMap& map,
                                                std::span<const EnvRayDifferential> rays,
                                                const LookupOptions& options,
                                                const IdentitySkippingRotation& to_map,
                                                float* out) {
    // The footprints are computed four at a time (FourFootprints). The lookups that are one probe
    // (most of them: at the footprint's centre, or on a polar cap), the cube lines on their face
    // (DeferredCubeLine) and the short lines on a polar cap are deferred: their texels are
    // requested, and they are filtered once the group's footprints are all computed, when the
    // texels have arrived. Enough lookups in flight to cover a miss to memory, few enough that
    // their texels are still cached when read. Every other lookup is done at once.
    constexpr std::size_t kGroup = 16;
    const int channels = map.channels();
    detail::RequestedReads<kGroup> reads;
    const int stride = map.face(0).stride();  // the caps' too (the same channels)
    const FourFootprints::Setting setting(map, options);
    FourFootprints footprints[kGroup / 4];
    for (std::size_t first = 0; first < rays.size(); first += kGroup) {
        const std::size_t count = std::min(kGroup, rays.size() - first);
        if (setting.four_at_once)
            for (std::size_t lane = 0; lane < count; lane += 4) {
                EnvRayDifferential tail[4];  // the last lanes, padded with the last ray
                const EnvRayDifferential* four = &rays[first + lane];
                if (count - lane < 4) {
                    for (std::size_t i = 0; i < 4; ++i)
                        tail[i] = rays[first + std::min(lane + i, count - 1)];
                    four = tail;
                }
                footprints[lane / 4].compute(map, four, to_map, options, setting);
            }
        for (std::size_t i = 0; i < count; ++i) {
            const EnvRayDifferential& ray = rays[first + i];
            float* result = out + (first + i) * channels;
            const FourFootprints& f = footprints[i / 4];
            const int lane = static_cast<int>(i % 4);
            if (setting.caps && f.cap_takes(lane)) {
                // route_lookup()'s polar cap branch, from the lane.
                const PolarCapFootprint cap = f.capped.footprint(map, lane);
                reads.add(f.cap_plans.planned >> lane & 1
                              ? detail::request_footprint_assembly(
                                    *cap.cap, cap.coords.s, cap.coords.t, f.cap_plans.plan(lane),
                                    options, result, reads.next_probe(), reads.next_line())
                              : polar_cap_request(cap, f.capped.lod[lane], options, result,
                                                  reads.next_probe(), reads.next_line()),
                          result);
                continue;
            }
            CentreProbe probe;
            Routed routed;
            if (setting.four_at_once && f.plain_takes(lane)) {
                // route_lookup()'s plain branch, from the lane.
                DeferredCubeLine* defer = &reads.next_line();
                if (f.lod[lane] >= 0.0f) {
                    probe = centre_probe(map, f.plain.coords(lane), f.lod[lane], options);
                    routed = Routed::centre_probe;
                } else if (f.plans.planned >> lane & 1) {
                    routed = lookup_plan(map, FootprintCentre(f.plain, lane), f.plans.plan(lane),
                                         options, result, defer)
                                 ? Routed::deferred_line
                                 : Routed::done;
                } else {
                    routed = general_lookup(map, FootprintCentre(f.plain, lane),
                                            PolarCapFootprint{}, options, result, defer)
                                 ? Routed::deferred_line
                                 : Routed::done;
                }
            } else {
                routed = route_lookup(map, ray.direction, ray.d_dx, ray.d_dy, options, to_map,
                                      result, probe, &reads.next_line());
            }
            add_routed(map, routed, probe, stride, result, reads);
        }
        reads.read(stride, channels);
    }
}

}  // namespace

void environment_lookup(const EnvironmentMap& map, const EnvFootprint& footprint,
                        const LookupOptions& options, float* out) {
    CentreProbe probe;
    if (route_lookup(map, footprint, options, out, probe, nullptr) == Routed::centre_probe)
        filter_centre_probe(map, probe, out);
}

void environment_lookup(const EnvironmentMap& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                        const LookupOptions& options, float* out) {
    single_lookup(map, r, dr_dx, dr_dy, options, IdentitySkippingRotation::none(), out);
}

void environment_lookup(const EnvironmentMap& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                        const LookupOptions& options, float* out, const Mat3& rotation) {
    single_lookup(map, r, dr_dx, dr_dy, options, IdentitySkippingRotation(rotation), out);
}

void environment_lookup_batch(const EnvironmentMap& map, std::span<const EnvRayDifferential> rays,
                              const LookupOptions& options, float* out) {
    batch_lookup(map, rays, options, IdentitySkippingRotation::none(), out);
}

void environment_lookup_batch(const EnvironmentMap& map, std::span<const EnvRayDifferential> rays,
                              const LookupOptions& options, float* out, const Mat3& rotation) {
    batch_lookup(map, rays, options, IdentitySkippingRotation(rotation), out);
}

void environment_lookup_batch(const EnvironmentMap& map, std::span<const EnvFootprint> footprints,
                              const LookupOptions& options, float* out) {
    // Each footprint routed as the single call routes it, its centre probe, cube line or polar
    // cap's probe or line read with its group's (as batch_lookup() reads them). On a cube or
    // lat-long map the lines off the polar caps are set aside and planned four at a time
    // (short_plans4(), each lane plan_probes()' plan bit for bit), as batch_lookup() plans them.
    constexpr std::size_t kGroup = 16;
    const int channels = map.channels();
    const int stride = map.face(0).stride();
    const FourFootprints::Setting setting(map, options);
    const bool plan_four_at_once = setting.four_at_once && setting.rule_b;
    detail::RequestedReads<kGroup> reads;
    std::size_t lines[kGroup];  // the group's footprints set aside to be planned four at a time
    for (std::size_t first = 0; first < footprints.size(); first += kGroup) {
        const std::size_t count = std::min(kGroup, footprints.size() - first);
        std::size_t line_count = 0;
        for (std::size_t i = first; i < first + count; ++i) {
            // route_lookup()'s steps, with a polar cap's probe or line requested as well.
            const EnvFootprint& footprint = footprints[i];
            float* result = out + i * channels;
            if (const float lod = centre_probe_lod(map, footprint, options); lod >= 0.0f) {
                add_routed(map, Routed::centre_probe,
                           centre_probe(map, footprint.coords, lod, options), stride, result,
                           reads);
                continue;
            }
            if (plan_four_at_once && footprint.matrix.is_finite() &&
                !in_caps_region(map, footprint.map_direction)) {
                lines[line_count++] = i;  // general_lookup() without a cap, below
                continue;
            }
            const PolarCapFootprint cap = cap_footprint(map, footprint);
            if (cap.valid) {  // polar_cap_filter(), requested
                reads.add(polar_cap_request(
                              cap, single_probe_lod(cap.matrix, options, cap.cap->max_level()),
                              options, result, reads.next_probe(), reads.next_line()),
                          result);
                continue;
            }
            if (general_lookup(map, footprint, cap, options, result, &reads.next_line()))
                reads.add(detail::Requested::line, result);
        }
        // The lines set aside (cap_footprint() invalid off the caps): general_lookup()'s plan,
        // four at a time where short_plans4() takes it.
        for (std::size_t k = 0; k < line_count; k += 4) {
            float xx[4], xy[4], yy[4];  // the last lanes padded with the last line
            for (std::size_t j = 0; j < 4; ++j) {
                const Sym2& m = footprints[lines[std::min(k + j, line_count - 1)]].matrix;
                xx[j] = m.xx, xy[j] = m.xy, yy[j] = m.yy;
            }
            ShortPlans4 plans;
            short_plans4(Float4::load(xx), Float4::load(xy), Float4::load(yy), options.probe_rule,
                         options.max_probes, setting.max_level, options.lod_bias,
                         options.isotropic_ratio, plans);
            for (std::size_t j = 0; j < 4 && k + j < line_count; ++j) {
                const std::size_t i = lines[k + j];
                float* result = out + i * channels;
                const bool deferred =
                    plans.planned >> j & 1
                        ? lookup_plan(map, footprints[i], plans.plan(static_cast<int>(j)), options,
                                      result, &reads.next_line())
                        : general_lookup(map, footprints[i], PolarCapFootprint{}, options, result,
                                         &reads.next_line());
                if (deferred) reads.add(detail::Requested::line, result);
            }
        }
        reads.read(stride, channels);
    }
}

void environment_bilinear(const EnvironmentMap& map, Vec3 r, int level, float* out) {
    const EnvCoords c = env_coords(map.layout(), r);
    const MipPyramid& pyramid = map.face(c.face);
    level = std::clamp(level, 0, pyramid.max_level());
    detail::dispatch_stride(pyramid.stride(), [&]<int S>() {
        detail::store(detail::env_bilinear<S>(map, c.face, level, c.s, c.t), pyramid.channels(),
                      out);
    });
}

}  // namespace footprint
