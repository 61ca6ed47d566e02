#include "envmap/environment_map.h"

#include <algorithm>
#include <string>

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

// One texel of a cube face level, where (x, y) may lie one texel beyond the face: such a tap is
// taken from the neighbour face that owns the direction of its centre (seamless filtering).
const float* cube_texel(const EnvironmentMap& map, int face, int level, int x, int y) {
    const MipPyramid::LevelView view = map.face(face).level(level);
    const int n = view.width;
    if (x >= 0 && y >= 0 && x < n && y < n) return view.texel(x, y);
    const float fn = static_cast<float>(n);
    const EnvCoords c = cube_reproject(face, (static_cast<float>(x) + 0.5f) / fn,
                                       (static_cast<float>(y) + 0.5f) / fn);
    const MipPyramid::LevelView other = map.face(c.face).level(level);
    const int xo = std::clamp(static_cast<int>(c.s * fn), 0, n - 1);
    const int yo = std::clamp(static_cast<int>(c.t * fn), 0, n - 1);
    return other.texel(xo, yo);
}

// Bilinear on a cube face level with taps across the face's edges (spec §3.1: seamless filtering).
template <int S>
detail::Texel<S> cube_bilinear(const EnvironmentMap& map, int face, int level, float s, float t) {
    const float n = static_cast<float>(map.face(face).width(level));
    const float x = s * n - 0.5f, y = t * n - 0.5f;
    const int x0 = detail::floor_to_int(x), y0 = detail::floor_to_int(y);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    detail::Texel<S> r{};
    detail::add_scaled(r, (1 - fx) * (1 - fy),
                       detail::Texel<S>::load(cube_texel(map, face, level, x0, y0)));
    detail::add_scaled(r, fx * (1 - fy),
                       detail::Texel<S>::load(cube_texel(map, face, level, x0 + 1, y0)));
    detail::add_scaled(r, (1 - fx) * fy,
                       detail::Texel<S>::load(cube_texel(map, face, level, x0, y0 + 1)));
    detail::add_scaled(r, fx * fy,
                       detail::Texel<S>::load(cube_texel(map, face, level, x0 + 1, y0 + 1)));
    return r;
}

template <int S>
detail::Texel<S> cube_trilinear(const EnvironmentMap& map, int face, float s, float t, float lod,
                                LodBlend blend) {
    const int max_level = map.face(face).max_level();
    const int l0 = std::min(static_cast<int>(lod), max_level);
    const float w =
        l0 < max_level ? detail::lod_blend_weight(lod - static_cast<float>(l0), blend) : 0.0f;
    detail::Texel<S> r = cube_bilinear<S>(map, face, l0, s, t);
    if (w > 0.0f) {
        const detail::Texel<S> coarse = cube_bilinear<S>(map, face, l0 + 1, s, t);
        r.v += w * (coarse.v - r.v);
    }
    return r;
}

}  // namespace

Vec2 EnvironmentMap::texel_scale() const {
    if (faces_.empty()) return {1, 1};
    return {static_cast<float>(faces_[0].width(0)), static_cast<float>(faces_[0].height(0))};
}

Result<EnvironmentMap> EnvironmentMap::from_latlong(const Image& image) {
    if (Status s = check_image(image, "lat-long map"); !s) return s.error();
    EnvironmentMap map;
    map.layout_ = EnvLayout::latlong;
    MipPyramidOptions options;
    options.wrap_s = WrapMode::repeat;  // the seam
    options.wrap_t = WrapMode::clamp;   // the poles
    map.faces_.push_back(MipPyramid::build(image, options));
    return map;
}

Result<EnvironmentMap> EnvironmentMap::from_cube_faces(const std::array<Image, 6>& faces) {
    static const char* kNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    EnvironmentMap map;
    map.layout_ = EnvLayout::cube;
    MipPyramidOptions options;
    options.wrap_s = options.wrap_t = WrapMode::clamp;
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
    return map;
}

void environment_lookup(const EnvironmentMap& map, const EnvFootprint& footprint,
                        const LookupOptions& options, float* out) {
    const EnvCoords& c = footprint.coords;
    const MipPyramid& centre = map.face(c.face);
    const FootprintEllipse ellipse = make_footprint_ellipse(footprint.matrix);
    if (map.layout() != EnvLayout::cube || options.filter != TextureFilter::footprint_assembly) {
        texture_lookup(centre, c.s, c.t, ellipse, options, out);
        return;
    }
    // Footprint assembly across cube faces (spec §2.8, §3.1): probes along r1 on the centre face's
    // plane, each re-projected onto the face that owns its direction, all at the centre face's lod.
    const FootprintEllipse e = ellipse.matrix.is_finite() ? ellipse : FootprintEllipse{};
    const ProbePlan plan = plan_probes(e, options.probe_rule, options.max_probes,
                                       centre.max_level(), options.lod_bias);
    const LodBlend blend = effective_lod_blend(plan, options.lod_blend);
    float weights[kMaxProbeCount];
    probe_weights(plan, weights);
    const float size = static_cast<float>(centre.width(0));
    detail::dispatch_stride(centre.stride(), [&]<int S>() {
        detail::Texel<S> sum{};
        float weight_sum = 0;
        for (int i = 0; i < plan.count; ++i) {
            const Vec2 o = plan.offset(i);
            float s = c.s + o.x / size, t = c.t + o.y / size;
            int face = c.face;
            if (s < 0 || s > 1 || t < 0 || t > 1) {
                const EnvCoords moved = cube_reproject(c.face, s, t);
                face = moved.face, s = moved.s, t = moved.t;
            }
            detail::add_scaled(sum, weights[i],
                               cube_trilinear<S>(map, face, s, t, plan.lod, blend));
            weight_sum += weights[i];
        }
        sum.v *= 1.0f / weight_sum;
        detail::store(sum, centre.channels(), out);
    });
}

}  // namespace footprint
