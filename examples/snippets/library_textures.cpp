// docs/library.md's snippets of errors, texture lookups, batched texture lookups, the texture
// system and its bump and environment pyramid files, each as written between its markers, around
// them the declarations they take from the text (coordinates, files written here). Built and run
// against the installed package by cmake/test_snippets.cmake; check_snippets.py holds
// docs/library.md to these regions.
#include <footprint/footprint.h>

#include <array>
#include <cstdio>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "support.h"

namespace {

using namespace footprint;
using snippets::check;
using snippets::checked;

// What a program does with an image it loaded.
void use(const Image& image) {
    check(image.width == 64 && image.height == 64, "use(*image)");
}

int errors() {
    // clang-format off
    // snippet begin: docs/library.md
    Result<Image> image = load_image("bricks.png");
    if (!image) { std::fprintf(stderr, "%s\n", image.error().message.c_str()); return 1; }
    use(*image);                                   // or image.value(), image->width
    // snippet end
    // clang-format on
    return 0;
}

int texture_lookups(const TextureCoords& lookup) {
    Result<Image> image = load_image("bricks.png");
    check(image.ok(), "bricks.png");
    const auto [s, t, dsdx, dtdx, dsdy, dtdy] = lookup;
    // A row of pixels' lookups, as a renderer makes them.
    auto pixel_lookups = [&] {
        std::vector<TextureCoords> row(40, lookup);
        for (std::size_t i = 0; i < row.size(); ++i) row[i].s += 0.01f * static_cast<float>(i);
        return row;
    };
    // clang-format off
    // snippet begin: docs/library.md
    const MipPyramid pyramid = MipPyramid::build(*image, MipPyramidOptions{});
    LookupOptions options;                                   // footprint assembly by default
    TextureCoords c{s, t, dsdx, dtdx, dsdy, dtdy};           // like OpenImageIO's texture()
    float rgb[3];                                            // pyramid.channels() floats
    texture_lookup(pyramid, c, options, rgb);
    // snippet end
    // clang-format on
    check(snippets::finite(rgb, 3), "docs/library.md: texture_lookup");

    // clang-format off
    // snippet begin: docs/library.md
    std::vector<TextureCoords> many = pixel_lookups();       // e.g. a row of pixels' lookups
    std::vector<float> colours(many.size() * pyramid.channels());
    texture_lookup_batch(pyramid, many, options, colours.data());
    // snippet end
    // clang-format on
    float last[3];
    texture_lookup(pyramid, many.back(), options, last);
    check(std::equal(last, last + 3, colours.end() - 3),
          "docs/library.md: texture_lookup_batch = the single calls");
    return 0;
}

int texture_system(const TextureCoords& c) {
    checked(save_image(snippets::bricks(), "paint.1001.exr"), "paint.1001.exr");
    const Vec3 r{0, 0.3f, -1}, dr_dx{0.01f, 0, 0}, dr_dy{0, 0.01f, 0};
    const float sigma2 = 0.002f;  // the micro-roughness's slope variance
    // clang-format off
    // snippet begin: docs/library.md
    TextureSystemOptions options;
    options.max_memory_mb = 512;                       // the cached tiles' texels
    options.cache_dir = "texture-cache";               // where built pyramids go (default below)
    // options.build_in_memory = true;                 // or hold them whole, unbounded (as before)
    Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create(options);
    std::unique_ptr<TextureSystem> ts = std::move(*made);

    float rgb[3];
    Status s = ts->texture("albedo.tx", c, LookupOptions{}, rgb);        // TextureCoords as above
    TextureHandle* albedo = ts->handle("albedo.tx");                    // skip the name lookup
    ts->texture(albedo, c, LookupOptions{}, rgb, std::array{1.f, 0.f, 1.f});  // pink where missing
    ts->texture("paint.<UDIM>.exr", c, LookupOptions{}, rgb);           // UDIM 1001 + ⌊s⌋ + 10⌊t⌋
    ts->environment("sky.hdr", r, dr_dx, dr_dy, EnvLookupOptions{}, rgb);
    SlopeStatistics st;
    ts->bump("bricks_normal.png", c, LookupOptions{}, &st);
    for (const Error& e : ts->take_errors()) std::fprintf(stderr, "%s\n", e.message.c_str());
    for (const Error& w : ts->take_warnings()) std::fprintf(stderr, "warning: %s\n", w.message.c_str());
    TextureSystemStats stats = ts->stats();      // files, tiles_loaded, tile_hits/misses, bytes_resident, peak_bytes
    // snippet end
    // clang-format on
    check(s.ok() && snippets::finite(rgb, 3), "docs/library.md: TextureSystem lookups");
    check(stats.files >= 4, "docs/library.md: TextureSystem::stats");

    {
        // clang-format off
    // snippet begin: docs/library.md
    BumpPyramid pyramid = BumpPyramid::build(*load_slope_map("bricks_normal.png")).value();
    Status saved = save_bump_pyramid(pyramid, "bricks_bump.exr");     // atomic; tiles of 64²
    Result<BumpPyramid> same = load_bump_pyramid("bricks_bump.exr");  // bit for bit, read whole
    std::optional<Vec2> offset = bump_pyramid_file_offset("bricks_bump.exr");  // is it one?
    SlopeStatistics st;
    ts->bump("bricks_bump.exr", c, BumpLookupOptions(LookupOptions{}, 0.8f, Sym2{sigma2, 0, sigma2}), &st);
    // snippet end
        // clang-format on
        check(saved.ok() && same.ok() && offset.has_value(), "docs/library.md: bump pyramid files");
        check(st.covariance.trace() > 0 && ts->take_errors().empty(),
              "docs/library.md: a bump pyramid file through the texture system");
    }
    {
        // clang-format off
    // snippet begin: docs/library.md
    EnvironmentMap sky = load_environment({"sky.hdr"}).value();
    Status saved = save_environment_pyramid(sky, "sky_env.exr");          // atomic
    Result<EnvironmentMap> same = load_environment_pyramid("sky_env.exr");  // lookups bit for bit
    bool stored = is_environment_pyramid_file("sky_env.exr");
    // snippet end
        // clang-format on
        check(saved.ok() && same.ok() && stored, "docs/library.md: environment pyramid files");
    }
    return 0;
}

}  // namespace

int main() {
    snippets::write_files();
    snippets::write_tx(snippets::bricks(), "albedo.tx");  // as maketx writes it
    const TextureCoords c{0.3f, 0.6f, 0.02f, 0, 0.005f, 0.01f};
    if (errors() != 0 || texture_lookups(c) != 0 || texture_system(c) != 0) return 1;
    std::printf("docs/library.md's texture snippets ran\n");
    return 0;
}
