#include "envmap/environment_map.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "envmap/env_lookup_route.h"
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

Result<EnvironmentMap> EnvironmentMap::from_face_levels(
    EnvLayout layout, const std::vector<std::vector<Image>>& faces,
    const std::vector<std::vector<Image>>& polar_caps) {
    if (static_cast<int>(faces.size()) != footprint::face_count(layout))
        return Error{std::string("a ") + env_layout_name(layout) + " map has " +
                     std::to_string(footprint::face_count(layout)) + " faces, not " +
                     std::to_string(faces.size())};
    if (!polar_caps.empty() && (layout != EnvLayout::latlong || polar_caps.size() != 2))
        return Error{"only a lat-long map has polar caps, two of them"};
    EnvironmentMap map;
    map.layout_ = layout;
    MipPyramidOptions options;  // as the layout's factory above builds its faces
    options.wrap_s = layout == EnvLayout::latlong ? WrapMode::repeat : WrapMode::clamp;
    options.wrap_t = WrapMode::clamp;
    options.border = layout == EnvLayout::cube ? 1 : 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        Result<MipPyramid> face = MipPyramid::from_levels(faces[f], options);
        if (!face) return Error{"face " + std::to_string(f) + ": " + face.error().message};
        if (f > 0 &&
            (face->channels() != map.channels() || face->width(0) != map.faces_[0].width(0)))
            return Error{"face " + std::to_string(f) + " differs in size or channels from face 0"};
        if (layout != EnvLayout::latlong && face->width(0) != face->height(0))
            return Error{"face " + std::to_string(f) + " is not square"};
        map.faces_.push_back(std::move(*face));
    }
    MipPyramidOptions cap_options;
    cap_options.wrap_s = cap_options.wrap_t = WrapMode::clamp;
    for (std::size_t p = 0; p < polar_caps.size(); ++p) {
        Result<MipPyramid> cap = MipPyramid::from_levels(polar_caps[p], cap_options);
        if (!cap) return Error{"polar cap " + std::to_string(p) + ": " + cap.error().message};
        map.polar_caps_.push_back(std::move(*cap));
    }
    if (layout == EnvLayout::cube) fill_cube_borders(map, map.faces_);
    return map;
}

namespace env_route {

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

namespace {

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

}  // namespace

// Flattened: everything it calls that can be inlined is, so that its probe loop compiles the same
// however much else this file inlines (otherwise GCC's unit-growth limit can push the probe taps
// out of line as the file grows).
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

namespace {

// A form (a) lookup (the single-call entry points).
inline void single_lookup(const EnvironmentMap& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                          const LookupOptions& options, const IdentitySkippingRotation& to_map,
                          float* out) {
    CentreProbe probe;
    if (route_lookup(map, r, dr_dx, dr_dy, options, to_map, out, probe, nullptr) ==
        Routed::centre_probe)
        filter_centre_probe(map, probe, out);
}

}  // namespace
}  // namespace env_route

void environment_lookup(const EnvironmentMap& map, const EnvFootprint& footprint,
                        const LookupOptions& options, float* out) {
    env_route::CentreProbe probe;
    if (env_route::route_lookup(map, footprint, options, out, probe, nullptr) ==
        env_route::Routed::centre_probe)
        env_route::filter_centre_probe(map, probe, out);
}

void environment_lookup(const EnvironmentMap& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                        const EnvLookupOptions& options, float* out) {
    if (options.rotation)
        env_route::single_lookup(map, r, dr_dx, dr_dy, options,
                                 IdentitySkippingRotation(*options.rotation), out);
    else
        env_route::single_lookup(map, r, dr_dx, dr_dy, options, IdentitySkippingRotation::none(),
                                 out);
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
