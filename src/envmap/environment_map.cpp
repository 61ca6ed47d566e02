#include "envmap/environment_map.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "envmap/env_lookup_general.h"
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
namespace {

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

}  // namespace

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

// The steps the batch (environment_map_batch.cpp) calls.
template float centre_probe_lod(const EnvironmentMap&, const EnvFootprint&, const LookupOptions&);
template bool general_lookup(const EnvironmentMap&, const FootprintCentre&,
                             const PolarCapFootprint&, const LookupOptions&, float*,
                             DeferredCubeLine*);
template bool lookup_plan(const EnvironmentMap&, const FootprintCentre&, const ProbePlan&,
                          const LookupOptions&, float*, DeferredCubeLine*);
template bool polar_cap_lookup(const EnvironmentMap&, Vec3, Vec3, Vec3, Vec3,
                               const IdentitySkippingRotation&, const LookupOptions&, float*);

}  // namespace env_route

void environment_lookup(const EnvironmentMap& map, const EnvFootprint& footprint,
                        const LookupOptions& options, float* out) {
    env_route::lookup(map, footprint, options, out);
}

void environment_lookup(const EnvironmentMap& map, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                        const EnvLookupOptions& options, float* out) {
    env_route::lookup(map, r, dr_dx, dr_dy, options, out);
}

void environment_bilinear(const EnvironmentMap& map, Vec3 r, int level, float* out) {
    env_route::bilinear(map, r, level, out);
}

}  // namespace footprint
