// render/camera.h — the pinhole camera and its primary rays with ray differentials.
//
// Image plane: pixel (i, j) covers [i, i+1) × [j, j+1) in continuous pixel coordinates (x, y), x to
// the right, y DOWN, centre (i + ½, j + ½). The camera sits at `position` looking at `look_at`;
// with the orthonormal basis
//     f = normalize(look_at − position),  r = normalize(f × up),  u = r × f
// the ray through (x, y) is  o = position,  d(x, y) = f + a (x − W/2) r − a (y − H/2) u,
// a = tan(fov_y/2) / (H/2) (square pixels). d is linear in (x, y), so its derivatives per pixel
// step are the constants ∂d/∂x = a r, ∂d/∂y = −a u, and ∂o/∂x = ∂o/∂y = 0.
#pragma once

#include <footprint/scene/ray_differentials.h>
#include <footprint/scene/scene.h>

namespace footprint {

class PinholeCamera {
  public:
    // The scene parser validated the description (look_at ≠ position, up not ∥ the view).
    PinholeCamera(const CameraDesc& desc, int width, int height);

    // The ray through continuous pixel position (x, y), with its differentials per pixel step.
    RayDifferential ray(double x, double y) const;

    Vec3d position() const { return position_; }
    Vec3d forward() const { return forward_; }
    Vec3d right() const { return right_; }
    Vec3d up() const { return up_; }
    double pixel_angle() const { return a_; }  // a: ∂d/∂x = a r, ∂d/∂y = −a u

  private:
    Vec3d position_, forward_, right_, up_;
    double a_ = 0, cx_ = 0, cy_ = 0;
};

}  // namespace footprint
