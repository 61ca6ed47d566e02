// cube_texel_across_edge() against the direction of each tap's centre (env_texel_of_direction():
// what seamless cube filtering means, spec §3.1), for every tap beyond every edge of faces of many
// sizes.
#include "envmap/cube_edges.h"

#include <gtest/gtest.h>

#include "envmap/env_layout.h"

namespace footprint {
namespace {

TEST(CubeEdges, TheTexelAcrossAnEdgeHoldsTheDirectionOfTheTapsCentre) {
    int checked = 0;
    for (const int w : {1, 2, 3, 4, 5, 7, 8, 16, 37, 64, 255, 256, 1024, 2048, 4096}) {
        for (int face = 0; face < 6; ++face) {
            for (int side = 0; side < 4; ++side) {
                for (int k = 0; k < w; ++k) {
                    const int x = side == 0 ? -1 : side == 1 ? w : k;
                    const int y = side == 2 ? -1 : side == 3 ? w : k;
                    const EnvTexel want = env_texel_of_direction(EnvLayout::cube, face, x, y, w, w);
                    const EnvTexel got = cube_texel_across_edge(face, x, y, w);
                    ASSERT_NE(got.face, face);
                    ASSERT_EQ(got.face, want.face)
                        << "face " << face << " side " << side << " k " << k << " of " << w;
                    ASSERT_EQ(got.x, want.x)
                        << "face " << face << " side " << side << " k " << k << " of " << w;
                    ASSERT_EQ(got.y, want.y)
                        << "face " << face << " side " << side << " k " << k << " of " << w;
                    // The neighbour's texel lies on its edge row or column.
                    ASSERT_TRUE(got.x == 0 || got.x == w - 1 || got.y == 0 || got.y == w - 1);
                    ++checked;
                }
            }
        }
    }
    EXPECT_EQ(checked, 187824);  // 6 faces × 4 edges × every size above
}

}  // namespace
}  // namespace footprint
