// env_sampling.h's shortcut for a probe on its own face (probe_taps_on_face) against the general
// seamless taps (probe_taps): the same texels and fractions, on every layout, at every level.
#include "envmap/env_sampling.h"

#include <gtest/gtest.h>

#include <random>

#include "envmap/env_test_maps.h"
#include "texture/test_taps.h"

namespace footprint {
namespace {

TEST(EnvSampling, ProbeOnItsFaceReadsTheSeamlessTaps) {
    for (const EnvLayout layout :
         {EnvLayout::cube, EnvLayout::latlong, EnvLayout::sphere, EnvLayout::paraboloid}) {
        const EnvironmentMap map = test::env_noise_map(layout, 37, 3);
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> unit(0, 1);
        int on_face = 0, beyond = 0;
        for (int k = 0; k < 4000; ++k) {
            const int face = static_cast<int>(unit(rng) * static_cast<float>(map.face_count())) %
                             map.face_count();
            // Up to 0.06 beyond the face: past a cube face's one-texel border on every level.
            const float s = 1.12f * unit(rng) - 0.06f, t = 1.12f * unit(rng) - 0.06f;
            const float lod = (k % 2 ? 1.0f : 0.0f) * unit(rng) * 4.0f + static_cast<float>(k % 3);
            const MipPyramid& pyramid = map.face(face);
            const detail::TrilinearLevels levels =
                detail::trilinear_levels(std::min(lod, static_cast<float>(pyramid.max_level())),
                                         pyramid.max_level(), LodBlend::linear);
            const detail::ProbeTaps want = detail::probe_taps(map, face, s, t, levels);
            const detail::ProbeTaps got = detail::probe_taps_on_face(map, face, s, t, levels);
            EXPECT_TRUE(test::same_taps(got.fine, want.fine))
                << "face " << face << " at " << s << ", " << t;
            if (levels.w > 0.0f) {
                EXPECT_TRUE(test::same_taps(got.coarse, want.coarse))
                    << "face " << face << " at " << s << ", " << t;
            }
            const detail::BilinearPosition p =
                detail::bilinear_position(pyramid.level(levels.l0), s, t);
            (p.inside ? on_face : beyond) += 1;
        }
        EXPECT_GT(on_face, 1000);  // both the shortcut and the seamless path exercised
        EXPECT_GT(beyond, 100);
    }
}

}  // namespace
}  // namespace footprint
