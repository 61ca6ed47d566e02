#include "render/camera.h"

#include <cmath>
#include <numbers>

namespace footprint {

PinholeCamera::PinholeCamera(const CameraDesc& desc, int width, int height)
    : position_(desc.position), cx_(0.5 * width), cy_(0.5 * height) {
    forward_ = normalize(desc.look_at - desc.position);
    right_ = normalize(cross(forward_, desc.up));
    up_ = cross(right_, forward_);
    a_ = std::tan(0.5 * desc.fov_y_deg * std::numbers::pi / 180.0) / (0.5 * height);
}

RayDifferential PinholeCamera::ray(double x, double y) const {
    RayDifferential r;
    r.ray.origin = position_;
    r.ray.direction = forward_ + (a_ * (x - cx_)) * right_ - (a_ * (y - cy_)) * up_;
    r.dddx = a_ * right_;
    r.dddy = -a_ * up_;
    return r;
}

}  // namespace footprint
