// fuzz/fuzz_lookup.cpp — the lookup API fed arbitrary floats.
//
// Feeds: a small texture (1–16 texels a side, 1–4 channels, any wrap modes, row-major or tiled,
// with its summed-area table) or environment map (cube, lat-long, sphere or paraboloid, 1–8 texels
// a side) with texels in [0, 1], then up to eight lookups whose coordinates, directions and
// derivatives are arbitrary floats (NaN, ±Inf, denormals, ±1e30, zero-size footprints, any bits),
// through every filter and every probe rule, level blend and option in its documented range.
// Asserts: every result channel is finite (a finite texture filtered is finite, whatever the
// footprint), and the batched lookups return the single lookups' bits.
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "envmap/environment_map.h"
#include "fuzz_input.h"
#include "math/mat3.h"
#include "texture/mip_pyramid.h"
#include "texture/texture_lookup.h"

namespace {

using namespace footprint;
using fuzz::FuzzInput;

constexpr int kMaxLookups = 8;

Image finite_image(FuzzInput& in, int width, int height, int channels) {
    Image image(width, height, channels);
    for (float& v : image.pixels) v = in.byte() / 255.0f;
    return image;
}

LookupOptions lookup_options(FuzzInput& in) {
    LookupOptions options;
    options.filter = static_cast<TextureFilter>(in.in_range(0, 6));
    options.probe_rule = static_cast<ProbeRule>(in.in_range(0, 3));
    options.lod_blend = static_cast<LodBlend>(in.in_range(0, 2));
    options.max_probes = std::array{1, 2, 8, 30, 1024}[in.in_range(0, 4)];
    options.max_anisotropy = std::array{1.0f, 4.0f, 16.0f, 64.0f}[in.in_range(0, 3)];
    options.lod_bias = static_cast<float>(in.in_range(-8, 8)) / 2;
    options.isotropic_ratio = std::array{1.0f, 1.25f, 4.0f}[in.in_range(0, 2)];
    options.ewa_beyond_probes = in.byte() & 1;
    options.brilinear_band = std::array{0.0f, 0.25f, 1.0f}[in.in_range(0, 2)];
    return options;
}

bool same_bits(const float* a, const float* b, int n) {
    for (int i = 0; i < n; ++i)
        if (std::bit_cast<std::uint32_t>(a[i]) != std::bit_cast<std::uint32_t>(b[i])) return false;
    return true;
}

void fuzz_texture(FuzzInput& in) {
    const int width = in.in_range(1, 16), height = in.in_range(1, 16);
    const int channels = in.in_range(1, 4);
    MipPyramidOptions pyramid_options;
    pyramid_options.wrap_s = static_cast<WrapMode>(in.in_range(0, 2));
    pyramid_options.wrap_t = static_cast<WrapMode>(in.in_range(0, 2));
    pyramid_options.downsample = static_cast<DownsampleFilter>(in.in_range(0, 1));
    pyramid_options.tile_log2 = in.in_range(0, 2);
    pyramid_options.summed_area_table = true;
    const LookupOptions options = lookup_options(in);
    const MipPyramid pyramid =
        MipPyramid::build(finite_image(in, width, height, channels), pyramid_options);

    std::vector<TextureCoords> coords;
    while (in.remaining() > 0 && coords.size() < kMaxLookups) {
        TextureCoords c;
        for (float* v : {&c.s, &c.t, &c.dsdx, &c.dtdx, &c.dsdy, &c.dtdy}) *v = in.any_float();
        coords.push_back(c);
    }
    const int stride = pyramid.channels();
    std::vector<float> single(coords.size() * stride), batch(coords.size() * stride);
    for (std::size_t i = 0; i < coords.size(); ++i) {
        texture_lookup(pyramid, coords[i], options, &single[i * stride]);
        fuzz::require_finite(&single[i * stride], stride, "texture_lookup");
    }
    texture_lookup_batch(pyramid, coords, options, batch.data());
    fuzz::require(same_bits(single.data(), batch.data(), static_cast<int>(single.size())),
                  "texture_lookup_batch returns texture_lookup's bits");
}

Result<EnvironmentMap> make_map(FuzzInput& in, EnvLayout layout) {
    const int size = in.in_range(1, 8);
    const int channels = in.in_range(1, 4);
    switch (layout) {
        case EnvLayout::cube: {
            std::array<Image, 6> faces;
            for (Image& face : faces) face = finite_image(in, size, size, channels);
            return EnvironmentMap::from_cube_faces(faces);
        }
        case EnvLayout::latlong: {
            LatLongOptions options;
            options.polar_caps = in.byte() & 1;
            return EnvironmentMap::from_latlong(
                finite_image(in, 2 * size, in.in_range(1, size), channels), options);
        }
        case EnvLayout::sphere:
            return EnvironmentMap::from_sphere(finite_image(in, size, size, channels));
        case EnvLayout::paraboloid: {
            const Image front = finite_image(in, size, size, channels);
            return EnvironmentMap::from_paraboloid(front, finite_image(in, size, size, channels));
        }
    }
    return Error{"unknown layout"};
}

Vec3 any_vec3(FuzzInput& in) {
    const float x = in.any_float(), y = in.any_float();
    return Vec3{x, y, in.any_float()};
}

void fuzz_environment(FuzzInput& in) {
    const EnvLayout layout = static_cast<EnvLayout>(in.in_range(0, 3));
    EnvLookupOptions options(lookup_options(in));
    if (in.byte() & 1) {
        const float x = in.in_range(-180, 180), y = in.in_range(-180, 180);
        options.rotation = rotation_xyz_degrees(x, y, static_cast<float>(in.in_range(-180, 180)));
    }
    const Result<EnvironmentMap> map = make_map(in, layout);
    fuzz::require(map.ok(), "a map of valid finite faces is accepted");

    std::vector<EnvRayDifferential> rays;
    while (in.remaining() > 0 && rays.size() < kMaxLookups) {
        EnvRayDifferential ray;
        ray.direction = any_vec3(in);
        ray.d_dx = any_vec3(in);
        ray.d_dy = any_vec3(in);
        rays.push_back(ray);
    }
    const int stride = map->channels();
    std::vector<float> single(rays.size() * stride), batch(rays.size() * stride);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        environment_lookup(*map, rays[i].direction, rays[i].d_dx, rays[i].d_dy, options,
                           &single[i * stride]);
        fuzz::require_finite(&single[i * stride], stride, "environment_lookup");
    }
    environment_lookup_batch(*map, rays, options, batch.data());
    fuzz::require(same_bits(single.data(), batch.data(), static_cast<int>(single.size())),
                  "environment_lookup_batch returns environment_lookup's bits");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzInput in(data, size);
    if (in.byte() & 1)
        fuzz_environment(in);
    else
        fuzz_texture(in);
    return 0;
}
