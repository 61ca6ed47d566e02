// math/mat3.h — a 3×3 matrix for rotations (environment rotation A, spec §2.3) — header only.
#pragma once

#include <cmath>
#include <cstring>

#include <footprint/math/vec3.h>

namespace footprint {

struct Mat3 {
    float m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // row-major; default: identity

    Vec3 operator*(Vec3 v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    Mat3 operator*(const Mat3& b) const {
        Mat3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                r.m[i][j] = m[i][0] * b.m[0][j] + m[i][1] * b.m[1][j] + m[i][2] * b.m[2][j];
        return r;
    }
    // Exactly the identity (the default); a −0 entry counts as not.
    bool is_identity() const {
        static constexpr float kIdentity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        return std::memcmp(m, kIdentity, sizeof(m)) == 0;
    }
    Mat3 transposed() const {
        Mat3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.m[i][j] = m[j][i];
        return r;
    }
};

// A rotation applied to several vectors, the identity (no environment rotation: the common case)
// tested once and then skipped: a lookup saves the three matrix products of its direction and
// both differentials.
class IdentitySkippingRotation {
  public:
    explicit IdentitySkippingRotation(const Mat3& a) : a_(a), identity_(a.is_identity()) {}
    // No rotation at all: nothing to test, and inlined callers fold the rotation away.
    static IdentitySkippingRotation none() { return IdentitySkippingRotation(kIdentity, true); }
    Vec3 operator()(Vec3 v) const { return identity_ ? v : a_ * v; }
    const Mat3& matrix() const { return a_; }
    bool is_identity() const { return identity_; }

  private:
    IdentitySkippingRotation(const Mat3& a, bool identity) : a_(a), identity_(identity) {}
    static constexpr Mat3 kIdentity{};
    const Mat3& a_;
    bool identity_;
};

// Rotation by `degrees` about x, then y, then z (R = Rz·Ry·Rx), right-handed.
inline Mat3 rotation_xyz_degrees(float x, float y, float z) {
    const float k = 3.14159265358979f / 180.0f;
    const float cx = std::cos(x * k), sx = std::sin(x * k), cy = std::cos(y * k),
                sy = std::sin(y * k);
    const float cz = std::cos(z * k), sz = std::sin(z * k);
    Mat3 rx, ry, rz;
    rx.m[1][1] = cx, rx.m[1][2] = -sx, rx.m[2][1] = sx, rx.m[2][2] = cx;
    ry.m[0][0] = cy, ry.m[0][2] = sy, ry.m[2][0] = -sy, ry.m[2][2] = cy;
    rz.m[0][0] = cz, rz.m[0][1] = -sz, rz.m[1][0] = sz, rz.m[1][1] = cz;
    return rz * ry * rx;
}

}  // namespace footprint
