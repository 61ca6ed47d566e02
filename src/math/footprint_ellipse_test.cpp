#include "math/footprint_ellipse.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace footprint {
namespace {

// Relative accuracy of the float eigen-decomposition of a well-conditioned 2×2 matrix.
constexpr float kEigenRelTolerance = 2e-5f;

TEST(FootprintEllipse, KIsDDTransposeNotDTransposeD) {
    // Spec erratum 1: D = [[3, 2], [0, .5]] has its major axis at 4.5° with K = D Dᵀ (34.2° with
    // DᵀD).
    const Vec2 d_dx{3, 0}, d_dy{2, 0.5f};
    const FootprintEllipse e = make_footprint_ellipse(d_dx, d_dy);
    const float angle = std::atan2(e.major_axis.y, e.major_axis.x) * 180 / float(M_PI);
    EXPECT_NEAR(std::fabs(angle), 4.5f, 0.1f);
    // Every image of the unit pixel circle lies on the ellipse: qᵀK⁻¹q = 1.
    const Sym2 k = e.matrix;
    const float det = k.determinant();
    const Sym2 inv{k.yy / det, -k.xy / det, k.xx / det};
    for (int i = 0; i < 32; ++i) {
        const float phi = float(i) * 2 * float(M_PI) / 32;
        const Vec2 q = std::cos(phi) * d_dx + std::sin(phi) * d_dy;
        EXPECT_NEAR(inv.quadratic_form(q), 1.0f, 1e-4f);
    }
}

TEST(FootprintEllipse, AxesReproduceRandomMatrices) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-10, 10);
    for (int i = 0; i < 20000; ++i) {
        const Vec2 a{u(rng), u(rng)}, b{u(rng), u(rng)};
        const FootprintEllipse e = make_footprint_ellipse(a, b);
        const Sym2 k = e.matrix, r = e.from_axes();
        const float scale = k.trace();
        EXPECT_NEAR(r.xx, k.xx, kEigenRelTolerance * scale);
        EXPECT_NEAR(r.xy, k.xy, kEigenRelTolerance * scale);
        EXPECT_NEAR(r.yy, k.yy, kEigenRelTolerance * scale);
        // r1 is the MAJOR axis (erratum 4: the paper's association rule is inverted).
        EXPECT_GE(k.quadratic_form(e.major_axis),
                  k.quadratic_form(e.minor_axis()) * (1 - kEigenRelTolerance));
        EXPECT_GE(e.major_radius, e.minor_radius);
    }
}

TEST(FootprintEllipse, RobustMinorAxisWhereEq17Cancels) {
    // Spec §2.7 / erratum 5: eq. (17) gives λ2² = −2.5e−6 in float for this K; the true value
    // is 9.975e−4.
    const FootprintEllipse e = make_footprint_ellipse(Sym2{1e5f, 0.5f, 1e-3f});
    EXPECT_NEAR(e.minor_radius * e.minor_radius, 9.975e-4f, 1e-6f);
    EXPECT_NEAR(e.major_radius * e.major_radius, 1e5f, 1.0f);
}

TEST(FootprintEllipse, DegenerateMatrices) {
    const FootprintEllipse zero = make_footprint_ellipse(Sym2{});
    EXPECT_EQ(zero.major_radius, 0.0f);
    EXPECT_EQ(zero.minor_radius, 0.0f);
    EXPECT_EQ(zero.major_axis.x, 1.0f);

    const FootprintEllipse iso = make_footprint_ellipse(Sym2{4, 0, 4});
    EXPECT_FLOAT_EQ(iso.major_radius, 2.0f);
    EXPECT_FLOAT_EQ(iso.minor_radius, 2.0f);
    EXPECT_EQ(iso.major_axis.x, 1.0f);

    // Rank 1 along (1, 1)/√2: λ2 = 0, r1 diagonal.
    const FootprintEllipse rank1 = make_footprint_ellipse(Vec2{3, 3}, Vec2{0, 0});
    EXPECT_NEAR(rank1.major_radius, std::sqrt(18.0f), 1e-5f);
    EXPECT_NEAR(rank1.minor_radius, 0.0f, 1e-3f);
    EXPECT_NEAR(rank1.major_axis.x, std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(rank1.major_axis.y, std::sqrt(0.5f), 1e-6f);

    // k11 = k22 with k12 ≠ 0: the major axis is the diagonal (the paper's rule picks the minor
    // one).
    const FootprintEllipse tie = make_footprint_ellipse(Sym2{2, 1, 2});
    EXPECT_NEAR(tie.major_radius * tie.major_radius, 3.0f, 1e-5f);
    EXPECT_NEAR(tie.major_axis.x * tie.major_axis.y, 0.5f, 1e-6f);

    // k22 > k11: the major axis is (close to) y.
    const FootprintEllipse tall = make_footprint_ellipse(Sym2{1, 0, 4});
    EXPECT_NEAR(std::fabs(tall.major_axis.y), 1.0f, 1e-6f);
}

}  // namespace
}  // namespace footprint
