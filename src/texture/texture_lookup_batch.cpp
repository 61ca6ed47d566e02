// texture_lookup_batch(): texture_lookup_route.h's routing, the texels of a group of lookups
// requested before any of them is read.
#include <algorithm>
#include <cstddef>
#include <span>

#include "texture/sampling.h"
#include "texture/texture_lookup.h"
#include "texture/texture_lookup_route.h"

namespace footprint {

// Flattened: alone in its file, GCC would otherwise leave the probe taps out of line.
[[gnu::flatten]] void texture_lookup_batch(const MipPyramid& pyramid,
                                           std::span<const TextureCoords> coords,
                                           const LookupOptions& options, float* out) {
    // Lookups are taken kGroup at a time: those that are one probe or a short line have their
    // texels requested, and are read once the whole group is routed, when the texels have arrived
    // (enough lookups in flight to cover a miss to memory, few enough that their texels are still
    // cached when read; footprint-bench texture chose 16 over 8 and 32, docs/performance.md).
    // Every other lookup is done at once.
    constexpr std::size_t kGroup = 16;
    const int channels = pyramid.channels();
    detail::RequestedReads<kGroup> reads;
    for (std::size_t first = 0; first < coords.size(); first += kGroup) {
        const std::size_t count = std::min(kGroup, coords.size() - first);
        for (std::size_t i = 0; i < count; ++i) {
            float* result = out + (first + i) * channels;
            const texture_route::Requests requests{reads.next_probe(), reads.next_line()};
            reads.add(
                texture_route::route_lookup(pyramid, coords[first + i], options, result, &requests),
                result);
        }
        reads.read(pyramid.stride(), channels);
    }
}

}  // namespace footprint
