// Tests of render/bump_frame.h: which frame a material's slopes perturb the normal in.
#include "render/bump_frame.h"

#include <gtest/gtest.h>

namespace footprint {
namespace {

constexpr float kTolerance = 1e-6f;

void expect_vec(Vec3 a, Vec3 b, const char* what) {
    EXPECT_NEAR(a.x, b.x, kTolerance) << what;
    EXPECT_NEAR(a.y, b.y, kTolerance) << what;
    EXPECT_NEAR(a.z, b.z, kTolerance) << what;
}

// A hit on the plane z = 0, n = +z, with p_u = (2, 0, 0) and p_v = (0, 0.5, 0): a stretched,
// orthogonal parameterisation.
SceneHit plane_hit() {
    SceneHit hit;
    hit.surface.n = {0, 0, 1};
    hit.surface.dpdu = {2, 0, 0};
    hit.surface.dpdv = {0, 0.5, 0};
    return hit;
}

TEST(BumpFrame, MainDirectionDefaultsToDpDv) {
    BumpDesc bump;
    bump.frame = BumpFrame::main_direction;
    const BumpFrameAtHit f = bump_frame(bump, plane_hit());
    expect_vec(f.frame.t1, {1, 0, 0}, "e1 = p̂_u");
    expect_vec(f.frame.t2, {0, 1, 0}, "e2 = p̂_v");
    EXPECT_EQ(f.slope_sign, 1);
    // An explicit main direction along x turns the frame: e2 = x̂, e1 = x̂ × n̂ = −ŷ.
    bump.main_direction = {1, 0, 0};
    const BumpFrameAtHit g = bump_frame(bump, plane_hit());
    expect_vec(g.frame.t2, {1, 0, 0}, "e2 = m");
    expect_vec(g.frame.t1, {0, -1, 0}, "e1 = m × n");
}

// The natural frame divides by the parameterisation: b = −∇h per unit of u is a world slope of
// b/|p_u|, and with slope_sign = −1 the perturbation n + T·(−b) leans the same way as the
// orthonormal frame's n + (b1 e1 + b2 e2) — scaled by 1/|p_u|, 1/|p_v|.
TEST(BumpFrame, NaturalFrameScalesWithTheParameterisation) {
    BumpDesc bump;
    bump.frame = BumpFrame::natural;
    const BumpFrameAtHit f = bump_frame(bump, plane_hit());
    EXPECT_EQ(f.slope_sign, -1);
    const Vec2 b{0.3f, -0.2f};
    const Vec3 n_natural = perturbed_normal(Vec3{0, 0, 1}, f.frame, f.slope_sign * b);
    expect_vec(n_natural, {0.3f / 2, -0.2f / 0.5f, 1}, "n' = n̂ + (b1/|p_u|) e_u + (b2/|p_v|) e_v");
    bump.frame = BumpFrame::normalized;
    const BumpFrameAtHit g = bump_frame(bump, plane_hit());
    const Vec3 n_normalized = perturbed_normal(Vec3{0, 0, 1}, g.frame, g.slope_sign * b);
    expect_vec(n_normalized, {0.3f, -0.2f, 1}, "n' = n̂ + b1 e_u + b2 e_v");
}

TEST(BumpFrame, MeshTangentsOverrideTheMaterialFrame) {
    BumpDesc bump;
    bump.frame = BumpFrame::natural;
    SceneHit hit = plane_hit();
    hit.tangent = Vec3d{1, 1, 0.5};  // not unit, not in the tangent plane
    hit.tangent_sign = -1;
    const BumpFrameAtHit f = bump_frame(bump, hit);
    const float r = 1 / std::sqrt(2.0f);
    expect_vec(f.frame.t1, {r, r, 0}, "e1 = the tangent, orthogonal to n");
    expect_vec(f.frame.t2, {r, -r, 0}, "e2 = −(n × e1)");
    EXPECT_EQ(f.slope_sign, 1);
}

TEST(BumpFrame, CovarianceInAnotherFrame) {
    // T = (2x, y): a slope variance k11 along t1 is 4·k11 along x.
    const TangentFrame t{{2, 0, 0}, {0, 1, 0}};
    const Sym2 k{0.01f, 0.002f, 0.03f};
    const Sym2 same = covariance_in_frame(k, t, {1, 0, 0}, {0, 1, 0});
    EXPECT_NEAR(same.xx, 0.04f, 1e-7f);
    EXPECT_NEAR(same.xy, 0.004f, 1e-7f);
    EXPECT_NEAR(same.yy, 0.03f, 1e-7f);
    // Swapped axes swap the variances.
    const Sym2 swapped = covariance_in_frame(k, t, {0, 1, 0}, {1, 0, 0});
    EXPECT_NEAR(swapped.xx, 0.03f, 1e-7f);
    EXPECT_NEAR(swapped.yy, 0.04f, 1e-7f);
}

}  // namespace
}  // namespace footprint
