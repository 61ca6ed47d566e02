#include "envmap/cube_edges.h"

#include <array>

namespace footprint {

namespace {

// How a neighbour's texel coordinate follows the index k along a shared edge of faces w wide.
enum class EdgeCoordinate : unsigned char { first, last, along, reversed };

int edge_coordinate(EdgeCoordinate c, int k, int w) {
    switch (c) {
        case EdgeCoordinate::first:
            return 0;
        case EdgeCoordinate::last:
            return w - 1;
        case EdgeCoordinate::along:
            return k;
        case EdgeCoordinate::reversed:
            break;
    }
    return w - 1 - k;
}

struct CubeEdge {
    int face;
    EdgeCoordinate x, y;
};

// The tap k along `side` of a face w wide (cube_edges.h's diagram).
void tap_beyond(int side, int k, int w, int& x, int& y) {
    x = side == 0 ? -1 : side == 1 ? w : k;
    y = side == 2 ? -1 : side == 3 ? w : k;
}

// Each face's four edges, read from the directions of the first and last taps along them on faces
// 8 texels wide (enough to tell first, last, along and reversed apart).
std::array<std::array<CubeEdge, 4>, 6> tabulate_edges() {
    constexpr int kWidth = 8;
    auto classify = [](int first, int last) {
        if (first == last) return first == 0 ? EdgeCoordinate::first : EdgeCoordinate::last;
        return first == 0 ? EdgeCoordinate::along : EdgeCoordinate::reversed;
    };
    std::array<std::array<CubeEdge, 4>, 6> edges{};
    for (int face = 0; face < 6; ++face) {
        for (int side = 0; side < 4; ++side) {
            int x0, y0, x1, y1;
            tap_beyond(side, 0, kWidth, x0, y0);
            tap_beyond(side, kWidth - 1, kWidth, x1, y1);
            const EnvTexel a =
                env_texel_of_direction(EnvLayout::cube, face, x0, y0, kWidth, kWidth);
            const EnvTexel b =
                env_texel_of_direction(EnvLayout::cube, face, x1, y1, kWidth, kWidth);
            edges[face][side] = {a.face, classify(a.x, b.x), classify(a.y, b.y)};
        }
    }
    return edges;
}

}  // namespace

EnvTexel cube_texel_across_edge(int face, int x, int y, int w) {
    static const std::array<std::array<CubeEdge, 4>, 6> edges = tabulate_edges();
    const int side = x < 0 ? 0 : x >= w ? 1 : y < 0 ? 2 : 3;
    const int k = side < 2 ? y : x;
    const CubeEdge& edge = edges[face][side];
    return {edge.face, edge_coordinate(edge.x, k, w), edge_coordinate(edge.y, k, w)};
}

}  // namespace footprint
