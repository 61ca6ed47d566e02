// The shared inner loops of texture/sampling.h against their one-at-a-time definitions.
#include "texture/sampling.h"
#include "image/test_images.h"
#include "texture/test_taps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <random>
#include <vector>

namespace footprint {
namespace {

// bilinear_positions() (both levels of a trilinear probe in one SSE register) gives exactly what
// bilinear_position() gives on each level: the same taps, fractions and on-level flags, for
// positions inside, on the edges and beyond them, on levels of odd sizes down to 1×1, with and
// without a border (where a tap reaching into the border counts as inside).
TEST(Sampling, PairedPositionsEqualOneLevelAtATime) {
    for (const int border : {0, 1}) {
        MipPyramidOptions options;
        options.border = border;
        const MipPyramid pyramid = MipPyramid::build(random_image(37, 19, 3, 5), options);
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> coordinate(-0.6f, 1.6f);
        int inside = 0, outside = 0;
        for (int l = 0; l < pyramid.max_level(); ++l) {
            const MipPyramid::LevelView& fine = pyramid.level(l);
            const MipPyramid::LevelView& coarse = pyramid.level(l + 1);
            for (int k = 0; k < 2000; ++k) {
                const float s = k < 4 ? float(k % 2) : coordinate(rng);
                const float t = k < 4 ? float(k / 2) : coordinate(rng);
                const detail::BilinearPositionPair pair =
                    detail::bilinear_positions(fine, coarse, s, t);
                for (const auto& [view, got] :
                     {std::pair{&fine, pair.fine}, std::pair{&coarse, pair.coarse}}) {
                    const detail::BilinearPosition want = detail::bilinear_position(*view, s, t);
                    ASSERT_EQ(got.x0, want.x0) << "level " << l << " s " << s << " t " << t;
                    ASSERT_EQ(got.y0, want.y0) << "level " << l << " s " << s << " t " << t;
                    ASSERT_EQ(got.fx, want.fx) << "level " << l << " s " << s << " t " << t;
                    ASSERT_EQ(got.fy, want.fy) << "level " << l << " s " << s << " t " << t;
                    ASSERT_EQ(got.inside, want.inside) << "level " << l << " s " << s << " t " << t;
                    // Inside: the four taps, columns x0 and x0 + 1, rows y0 and y0 + 1, are stored.
                    const bool stored =
                        want.x0 >= -border && want.x0 + 1 <= view->width - 1 + border &&
                        want.y0 >= -border && want.y0 + 1 <= view->height - 1 + border;
                    ASSERT_EQ(want.inside, stored) << "level " << l << " s " << s << " t " << t;
                    (want.inside ? inside : outside) += 1;
                }
            }
        }
        EXPECT_GT(inside, 1000);  // both branches exercised
        EXPECT_GT(outside, 1000);
    }
}

// blend_probe_line() (probes placed and requested ahead through a ring) equals the plain weighted
// mean of the probes read one by one, for lines shorter and longer than its look-ahead and ring,
// on one level and between two.
TEST(Sampling, ProbeLineIsTheWeightedMeanOfItsProbes) {
    const MipPyramid pyramid = MipPyramid::build(random_image(64, 48, 3, 9));
    ASSERT_EQ(pyramid.stride(), 4);
    for (const float lod : {1.0f, 1.6f}) {
        const detail::TrilinearLevels levels =
            detail::trilinear_levels(lod, pyramid.max_level(), LodBlend::linear);
        for (int count : {1, 2, 5, 6, 7, 8, 9, 16, 23}) {
            std::vector<float> weights(count);
            for (int i = 0; i < count; ++i) weights[i] = 1.0f + 0.37f * float((i * 5) % 7);
            auto position = [&](int i) {
                return std::pair{0.2f + 0.031f * float(i), 0.7f - 0.017f * float(i)};
            };
            const detail::Texel<4> line = detail::blend_probe_line<4>(
                count, weights.data(), levels, pyramid.stride(), [&](int i) {
                    const auto [s, t] = position(i);
                    return detail::probe_taps(pyramid, s, t, levels);
                });
            double want[3] = {}, weight_sum = 0;
            for (int i = 0; i < count; ++i) {
                const auto [s, t] = position(i);
                const detail::Texel<4> probe =
                    detail::sample_trilinear<4>(pyramid, s, t, lod, LodBlend::linear);
                for (int c = 0; c < 3; ++c) want[c] += double(weights[i]) * double(probe.v[c]);
                weight_sum += weights[i];
            }
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(line.v[c], want[c] / weight_sum, 2e-6)
                    << "lod " << lod << ", " << count << " probes, channel " << c;
        }
    }
}

// line_inside() admits a straight line only when every probe on it has all its taps on both levels,
// and there probe_taps_inside() addresses exactly the taps that trilinear_taps() (with its edge
// tests and wrapping) does: the same texels, the same fractions. Random lines on levels of odd
// sizes, near and across the edges, of one and two levels. With a border, an admitted line's
// probes also have their centres on the level, s, t ∈ [0, 1] (their taps may reach the border).
TEST(Sampling, LinesInsideTheLevelsNeedNoEdgeTests) {
    for (const int border : {0, 1}) {
        MipPyramidOptions options;
        options.border = border;
        const MipPyramid pyramid = MipPyramid::build(random_image(53, 29, 3, 11), options);
        std::mt19937 rng(5);
        std::uniform_real_distribution<float> coordinate(-0.1f, 1.1f), unit(0, 1);
        int admitted = 0, refused = 0;
        for (int l = 0; l + 1 < pyramid.max_level(); ++l) {
            for (int k = 0; k < 600; ++k) {
                const float lod = static_cast<float>(l) + (k % 2 ? 0.0f : unit(rng));
                const detail::TrilinearLevels levels =
                    detail::trilinear_levels(lod, pyramid.max_level(), LodBlend::linear);
                const MipPyramid::LevelView& fine = pyramid.level(levels.l0);
                const MipPyramid::LevelView& coarse =
                    pyramid.level(levels.w > 0.0f ? levels.l0 + 1 : levels.l0);
                const float s0 = coordinate(rng), t0 = coordinate(rng);
                const float ds = 0.3f * (unit(rng) - 0.5f), dt = 0.3f * (unit(rng) - 0.5f);
                const int count = 2 + k % 7;
                auto position = [&](int i) {
                    const float u = static_cast<float>(i) / static_cast<float>(count - 1);
                    return std::pair{s0 + u * ds, t0 + u * dt};
                };
                const auto [s1, t1] = position(count - 1);
                if (!detail::line_inside(fine, coarse, s0, t0, s1, t1)) {
                    ++refused;
                    continue;
                }
                ++admitted;
                for (int i = 0; i < count; ++i) {
                    const auto [s, t] = position(i);
                    const detail::ProbeTaps want = detail::probe_taps(pyramid, s, t, levels);
                    const detail::ProbeTaps got =
                        detail::probe_taps_inside(fine, coarse, s, t, levels);
                    const detail::BilinearPositionPair p =
                        detail::bilinear_positions(fine, coarse, s, t);
                    ASSERT_TRUE(p.fine.inside && p.coarse.inside) << "probe " << i << " leaves";
                    if (border > 0) {
                        ASSERT_TRUE(s >= 0 && s <= 1 && t >= 0 && t <= 1)
                            << "probe " << i << " centred off the level at " << s << ", " << t;
                    }
                    const int tap_levels = levels.w > 0.0f ? 2 : 1;
                    for (int level = 0; level < tap_levels; ++level) {
                        ASSERT_TRUE(test::same_taps(level ? got.coarse : got.fine,
                                                    level ? want.coarse : want.fine))
                            << "probe " << i << ", level " << level;
                    }
                }
            }
        }
        EXPECT_GT(admitted, 500);  // both answers exercised
        EXPECT_GT(refused, 500);
    }
}

// blend_probe_line_inside() reads a line inside its levels exactly as the general line does
// (blend_probe_line() over probe_taps(), with its edge tests): bit for bit, on row-major levels
// (RowMajorLine, two pointers a probe) and tiled ones (probe_taps_inside()), for RGB (stride 4) and
// one channel, lines of one and two levels, shorter and longer than the look-ahead. Lines that
// leave the levels are refused and write nothing. The same lines requested now and read later
// (detail::RequestedLine, up to its eight probes on row-major levels) read exactly the same.
TEST(Sampling, LinesInsideTheLevelsReadAsTheGeneralLine) {
    for (const int tile_log2 : {0, 2}) {
        for (const int channels : {3, 1}) {
            MipPyramidOptions options;
            options.tile_log2 = tile_log2;
            const MipPyramid pyramid =
                MipPyramid::build(random_image(61, 37, channels, 13), options);
            std::mt19937 rng(7);
            std::uniform_real_distribution<float> coordinate(-0.05f, 1.05f), unit(0, 1);
            std::vector<float> weights(23);
            int admitted = 0, refused = 0, requests = 0;
            for (int k = 0; k < 1500; ++k) {
                const float lod = (k % 3 ? 2.5f : 2.0f) * unit(rng);
                const detail::TrilinearLevels levels =
                    detail::trilinear_levels(lod, pyramid.max_level(), LodBlend::linear);
                const int count = 2 + k % 22;
                for (int i = 0; i < count; ++i) weights[i] = 0.25f + unit(rng);
                const float s0 = coordinate(rng), t0 = coordinate(rng);
                const float ds = 0.02f * (unit(rng) - 0.5f), dt = 0.02f * (unit(rng) - 0.5f);
                const float first = -0.5f * static_cast<float>(count - 1);
                auto position = [&](int i) {
                    const float c = first + static_cast<float>(i);
                    return Vec2{s0 + c * ds, t0 + c * dt};
                };
                float got[MipPyramid::kMaxChannels];
                std::fill(std::begin(got), std::end(got), -1.0f);
                // The same line requested now and read later (the environment batch's lines).
                constexpr int kRequestedProbes = 8;
                detail::RequestedLine<kRequestedProbes> requested;
                bool request_taken = false;
                detail::dispatch_stride(pyramid.stride(), [&]<int S>() {
                    request_taken =
                        requested.request<S>(pyramid, count, weights.data(), levels, position(0),
                                             position(count - 1), position);
                });
                if (!detail::blend_probe_line_inside(pyramid, count, weights.data(), levels,
                                                     position, got)) {
                    ++refused;
                    ASSERT_EQ(got[0], -1.0f) << "a refused line wrote its result";
                    ASSERT_FALSE(request_taken) << "a line outside the levels was requested";
                    continue;
                }
                ++admitted;
                ASSERT_EQ(request_taken, tile_log2 == 0 && count <= kRequestedProbes)
                    << "tile_log2 " << tile_log2 << ", " << count << " probes";
                requests += request_taken;
                detail::dispatch_stride(pyramid.stride(), [&]<int S>() {
                    const detail::Texel<S> want = detail::blend_probe_line<S>(
                        count, weights.data(), levels, pyramid.stride(), [&](int i) {
                            const Vec2 p = position(i);
                            return detail::probe_taps(pyramid, p.x, p.y, levels);
                        });
                    const detail::Texel<S> read_later = request_taken ? requested.blend<S>() : want;
                    for (int c = 0; c < channels; ++c) {
                        ASSERT_EQ(got[c], want.v[c])
                            << "tile_log2 " << tile_log2 << ", " << count << " probes at lod "
                            << lod << ", channel " << c;
                        ASSERT_EQ(read_later.v[c], want.v[c])
                            << "requested line: " << count << " probes at lod " << lod
                            << ", channel " << c;
                    }
                });
            }
            EXPECT_GT(admitted, 500) << "tile_log2 " << tile_log2;
            EXPECT_GT(refused, 100) << "tile_log2 " << tile_log2;
            if (tile_log2 == 0) {
                EXPECT_GT(requests, 100);
            }
        }
    }
}

}  // namespace
}  // namespace footprint
