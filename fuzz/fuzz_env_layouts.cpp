// fuzz/fuzz_env_layouts.cpp — cube crosses and strips, paraboloid pairs and OpenEXR lat-longs
// assembled and taken apart (envmap/env_image_io.h), and environment maps made of the pieces.
//
// Feeds: an image of 1–48 × 1–48 texels and 1–4 channels built from the bytes — texels from a
// byte each, or (one input in two) from raw float bits, NaN and ±Inf among them — and a cube
// arrangement chosen from the bytes.
// Asserts: size detection agrees with splitting (env_layout_from_size / cube_arrangement_from_size
// name only sizes that split); a split either fails with a message or gives six (two) square faces
// of one size and the image's channels; assembling the faces and splitting again gives the same
// bits; a paraboloid pair and an OpenEXR lat-long reassemble into the image bit for bit; a map made
// of the pieces (make_environment_map) is an error or, for texels within ±1e30, gives finite
// lookups.
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>

#include "envmap/env_image_io.h"
#include "envmap/environment_map.h"
#include "fuzz_input.h"

namespace {

using namespace footprint;
using fuzz::FuzzInput;

bool same_bits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

bool square_faces(const Image* faces, int n, int channels) {
    for (int i = 0; i < n; ++i)
        if (faces[i].width != faces[0].width || faces[i].height != faces[0].width ||
            faces[i].channels != channels || faces[i].width < 1)
            return false;
    return true;
}

// A few lookups on a map of finite texels: finite results.
void look_up(const EnvironmentMap& map, FuzzInput& in) {
    for (int i = 0; i < 4; ++i) {
        const Vec3 r{in.any_float(), in.any_float(), in.any_float()};
        EnvLookupOptions options;
        options.filter = static_cast<TextureFilter>(in.in_range(0, 6));
        std::array<float, MipPyramid::kMaxChannels> out{};
        environment_lookup(map, r, Vec3{0.01f, 0, 0}, Vec3{0, 0.01f, 0}, options, out.data());
        fuzz::require_finite(out.data(), map.channels(), "environment_lookup");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzInput in(data, size);
    const int width = in.in_range(1, 48), height = in.in_range(1, 48);
    const int channels = in.in_range(1, 4);
    const bool raw_bits = in.byte() & 1;
    const auto arrangement = static_cast<CubeArrangement>(in.in_range(0, 7));
    Image image(width, height, channels);
    for (float& v : image.pixels)
        v = raw_bits ? std::bit_cast<float>(in.u32()) : in.byte() / 255.0f;
    // Lookups are finite for finite texels up to 1e30: a filter's float sums of texels near FLT_MAX
    // (a polar cap texel's 64² samples) may overflow, the float format's limit.
    constexpr float kLargestTexel = 1e30f;
    bool finite = true;
    for (float v : image.pixels) finite = finite && std::fabs(v) <= kLargestTexel;

    // A cube of one image.
    const std::optional<CubeArrangement> by_size = cube_arrangement_from_size(width, height);
    const Result<std::array<Image, 6>> cube = split_cube_image(image, arrangement);
    if (by_size && arrangement == CubeArrangement::automatic)
        fuzz::require(cube.ok(), "a size cube_arrangement_from_size names splits");
    if (cube.ok()) {
        fuzz::require(square_faces(cube->data(), 6, channels), "six square faces of one size");
        const CubeArrangement used =
            arrangement == CubeArrangement::automatic ? *by_size : arrangement;
        const Image assembled = assemble_cube_image(*cube, used);
        const Result<std::array<Image, 6>> again = split_cube_image(assembled, used);
        fuzz::require(again.ok(), "an assembled cube splits");
        for (int f = 0; f < 6; ++f)
            fuzz::require(same_bits((*cube)[f], (*again)[f]),
                          "assemble then split is the identity");
        const Result<EnvironmentMap> map =
            make_environment_map({EnvLayout::cube, {cube->begin(), cube->end()}});
        if (map.ok() && finite) look_up(*map, in);
    } else {
        fuzz::require(!cube.error().message.empty(), "a split that fails says why");
    }

    // A paraboloid pair side by side.
    const Result<std::array<Image, 2>> pair = split_paraboloid_image(image);
    if (pair.ok()) {
        fuzz::require(square_faces(pair->data(), 2, channels), "two square faces of one size");
        fuzz::require(same_bits(assemble_paraboloid_image((*pair)[0], (*pair)[1]), image),
                      "split then assemble is the identity");
        const Result<EnvironmentMap> map =
            make_environment_map({EnvLayout::paraboloid, {(*pair)[0], (*pair)[1]}});
        if (map.ok() && finite) look_up(*map, in);
    } else {
        fuzz::require(!pair.error().message.empty(), "a split that fails says why");
    }

    // The image as the layout its size stands for, and as an OpenEXR lat-long.
    fuzz::require(same_bits(latlong_to_openexr(latlong_from_openexr(image)), image),
                  "OpenEXR's lat-long and back is the identity");
    if (const std::optional<EnvLayout> layout = env_layout_from_size(width, height);
        layout && *layout != EnvLayout::cube && *layout != EnvLayout::paraboloid) {
        const Result<EnvironmentMap> map = make_environment_map({*layout, {image}});
        if (map.ok() && finite) look_up(*map, in);
    }
    return 0;
}
