// README.md's snippet of footprint behind OpenImageIO's TextureSystem, as written between its
// markers, around it the declarations it takes from the text and a texture written by
// OpenImageIO's make_texture (what `maketx` writes). Built and run against the installed package
// by cmake/test_snippets.cmake; check_snippets.py holds the README to this region.
#include <footprint/oiio/texture_system.h>

#include <cmath>
#include <cstdio>

#include "support.h"

// The snippet's own #include line stands inside the function below: the header was included
// above, so there it adds nothing (#pragma once).

namespace {

int drop_in() {
    snippets::write_tx(snippets::bricks(), "albedo.tx");  // as maketx writes it
    const float s = 0.3f, t = 0.6f, dsdx = 0.02f, dtdx = 0, dsdy = 0.005f, dtdy = 0.01f;
    float rgb[3] = {-1, -1, -1};
    // clang-format off
    // snippet begin: README.md
    #include <footprint/oiio/texture_system.h>

    OIIO::TextureSystem* ts = footprint::oiio::create_texture_system();  // was TextureSystem::create()
    OIIO::TextureOpt opt;                                                 // every call as before
    ts->texture(OIIO::ustring("albedo.tx"), opt, s, t, dsdx, dtdx, dsdy, dtdy, 3, rgb);
    footprint::oiio::destroy_texture_system(ts);                          // was TextureSystem::destroy()
    // snippet end
    // clang-format on
    snippets::check(snippets::finite(rgb, 3) && rgb[0] >= 0.4f && rgb[0] <= 0.9f,
                    "README: the drop-in texture() looked the bricks up");
    return 0;
}

}  // namespace

int main() {
    if (drop_in() != 0) return 1;
    std::printf("README.md's OpenImageIO snippet ran\n");
    return 0;
}
