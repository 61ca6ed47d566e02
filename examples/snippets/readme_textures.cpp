// README.md's snippets of the library, the texture lookup, the texture system and the procedural
// texture, each as written between its markers, around them the declarations they take from the
// text (coordinates, a colour, files written here). Built and run against the installed package
// by cmake/test_snippets.cmake; check_snippets.py holds the README to these regions.
#include <footprint/footprint.h>

#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include "support.h"

// The snippets' own #include lines stand inside the functions below: the headers were included
// above, so there they add nothing (#pragma once).

namespace {

using snippets::check;
using snippets::checked;

int version() {
    // clang-format off
    // snippet begin: README.md
    #include <footprint/footprint.h>                 // or one module's, <footprint/texture/texture_lookup.h>
    std::printf("footprint %s\n", footprint::version());
    // snippet end
    // clang-format on
    return 0;
}

int texture_lookup() {
    const float s = 0.3f, t = 0.6f, dsdx = 0.02f, dtdx = 0, dsdy = 0.005f, dtdy = 0.01f;
    std::vector<footprint::TextureCoords> many_coords(40, {s, t, dsdx, dtdx, dsdy, dtdy});
    for (std::size_t i = 0; i < many_coords.size(); ++i) many_coords[i].s += 0.01f * i;
    std::vector<float> storage(many_coords.size() * 3);
    float* out = storage.data();
    // clang-format off
    // snippet begin: README.md
    #include <footprint/image/image_io.h>
    #include <footprint/texture/texture_lookup.h>
    using namespace footprint;

    Result<Image> image = load_image("bricks.png");            // sRGB 8-bit → linear float
    if (!image) { std::fprintf(stderr, "%s\n", image.error().message.c_str()); return 1; }
    const MipPyramid pyramid = MipPyramid::build(*image);      // repeat wrap, box downsampling

    LookupOptions options;                                     // filter = footprint_assembly
    TextureCoords c{s, t, dsdx, dtdx, dsdy, dtdy};             // like OpenImageIO's texture()
    float colour[4];                                           // pyramid.channels() floats
    texture_lookup(pyramid, c, options, colour);               // thread-safe
    texture_lookup_batch(pyramid, many_coords, options, out);  // the same results, faster
    // snippet end
    // clang-format on
    check(pyramid.channels() == 3 && snippets::finite(colour, 3), "README: texture_lookup");
    float first[3];
    texture_lookup(pyramid, many_coords[0], options, first);
    check(std::equal(first, first + 3, out), "README: texture_lookup_batch = texture_lookup");
    return 0;
}

int texture_system() {
    using namespace footprint;
    checked(save_environment_pyramid(EnvironmentMap::from_latlong(snippets::latlong_sky()).value(),
                                     "sky_env.exr"),
            "sky_env.exr");
    const TextureCoords c{0.3f, 0.6f, 0.02f, 0, 0.005f, 0.01f};
    const Vec3 r{0, 0.3f, -1}, dr_dx{0.01f, 0, 0}, dr_dy{0, 0.01f, 0};
    float colour[4] = {-1, -1, -1, -1};
    // clang-format off
    // snippet begin: README.md
    #include <footprint/texture_system.h>

    TextureSystemOptions options;  // max_memory_mb = 1024 bounds every file's texels, tile_size = 64;
                                   // plain images' pyramids go to $XDG_CACHE_HOME/footprint
    Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create(options);  // checks the options
    std::unique_ptr<TextureSystem> ts = std::move(*made);
    Status s = ts->texture("albedo.exr", c, LookupOptions{}, colour);  // `footprint maketx`, .tx: tile by tile
    if (!s) std::fprintf(stderr, "%s\n", s.error().message.c_str());   // "cannot read 'albedo.exr': …"
    ts->environment("sky_env.exr", r, dr_dx, dr_dy, {}, colour);       // `maketx --env`: tile by tile too
    // snippet end
    // clang-format on
    check(s.ok() && snippets::finite(colour, 3), "README: TextureSystem::texture");
    check(ts->take_errors().empty(), "README: TextureSystem::environment");
    return 0;
}

int procedural() {
    using namespace footprint;
    const Vec3d p{0.2, 0.5, -0.3}, dp_dx{0.01, 0, 0}, dp_dy{0, 0.01, 0};
    // clang-format off
    // snippet begin: README.md
    #include <footprint/texture/procedural.h>

    ProceduralTexture marble{ProceduralPattern::marble, /*scale*/ 6, /*octaves*/ 6,
                             {Vec3{0.16f, 0.15f, 0.14f}, Vec3{0.85f, 0.83f, 0.78f}}};
    Vec3 rgb = procedural_color(marble, p, dp_dx, dp_dy);  // world point and its ray differentials
    // snippet end
    // clang-format on
    check(rgb.x >= 0.15f && rgb.x <= 0.86f, "README: procedural_color between the two colours");
    return 0;
}

}  // namespace

int main() {
    snippets::write_files();
    for (int (*snippet)() : {version, texture_lookup, texture_system, procedural})
        if (snippet() != 0) return 1;
    std::printf("README.md's texture snippets ran\n");
    return 0;
}
