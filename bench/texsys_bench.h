// bench/texsys_bench.h — `footprint-bench texsys`: footprint's TextureSystem against OpenImageIO's
// TextureSystem on textures that do not fit in the cache.
//
// It writes `textures` tiled MIP-mapped float EXR files of size² RGB texels (the benchmark texture,
// bench_texture_content.h, shifted and its channels turned per file; 8 × 4096² by default: 2.4 GiB
// of float pyramids against a 256 MiB cache), then renders frames of a plane seen at a grazing
// angle — one lookup per pixel, in scanline order, with the derivatives of the pixel's neighbours'
// hits, the plane's strips textured by the files in turn — through each texture system with the
// same max_memory_mb, in a child process of its own (so that each has its peak resident set to
// itself): ours with footprint assembly, OpenImageIO's with its default TextureOpt (anisotropic,
// smart bicubic), both reading the very same files. For each it reports the first (cold) frame's
// time, the later frames' lookups/s (the best frame's) with 1 and 2 threads, the peak RSS of the
// process and the texture system's own peak of texel memory (each from the system's best of
// `rounds` runs, taken in turn); the RMS error of both against
// reference_lookup() on a subset of pixels; and whether ours with 1 and 2 threads and with an
// unbounded cache gave the same image, bit for bit.
//
// With api = "oiio" it also renders the same frames through OpenImageIO's TextureSystem interface
// with footprint behind it (footprint::oiio::create_texture_system(), the same default TextureOpt
// as OpenImageIO's run, the same cache size): what a renderer that calls OIIO::TextureSystem gets,
// and what the interface costs against footprint's native API with the same probe budget
// (`native-32`: OpenImageIO's default `anisotropic` 32, which the adapter takes for max_probes).
#pragma once

#include <string>
#include <vector>

namespace footprint::bench {

struct TexsysBenchOptions {
    int textures = 8;
    int size = 4096;
    int cache_mb = 256;
    int width = 1280, height = 720;
    int frames = 4;  // the first is the cold one; the best of the others counts
    // Each system runs once per round, the systems in turn, and its best round counts: this
    // machine's slow spells (other tenants) then fall on every system alike rather than on
    // whichever ran during them.
    int rounds = 3;
    std::vector<int> thread_counts = {1, 2};
    std::string dir;  // where the files are written (kept, and reused when present); empty: a
                      // temporary folder, removed afterwards
    bool with_oiio = true;
    std::string api = "native";  // "oiio": also footprint behind OpenImageIO's interface
    std::string json_path;
    bool quiet = false;
};

int run_texsys_bench(const TexsysBenchOptions& options);

}  // namespace footprint::bench
