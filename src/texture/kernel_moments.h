// texture/kernel_moments.h — measuring a filter's kernel by looking up polynomial textures
// (test support; header-only).
//
// Every filter here is linear in the texels: a lookup returns Σ_j w_j texel_j over level-0
// texels j, with weights w_j that sum to 1 (coarser levels are box averages of level-0 texels, so
// their weights spread over the level-0 texels they cover). Looking up the textures x, y, x², xy,
// y² (x, y = level-0 texel-centre coordinates relative to the texture centre) therefore returns the
// first and second moments of that kernel exactly: its mean and its covariance, with no sampling
// noise. Adding 1/12 per axis turns the covariance over texel *centres* into the covariance of the
// continuous kernel (each level-0 texel is a unit box), the quantity spec §2.6/§2.8 speaks of.
#pragma once

#include <functional>

#include "image/image.h"
#include "math/footprint_ellipse.h"
#include "texture/mip_pyramid.h"

namespace footprint {

struct KernelMoments {
    Vec2 mean;        // level-0 texel-centre coordinates relative to the texture centre
    Sym2 covariance;  // continuous-kernel covariance (texel-centre covariance + I/12)
};

// Pyramids of the moment textures on a size × size texture (clamp wrap: keep kernels inside).
class MomentPyramids {
  public:
    explicit MomentPyramids(int size, DownsampleFilter downsample = DownsampleFilter::box)
        : size_(size) {
        Image first(size, size, 4), second(size, size, 1);
        const double c = 0.5 * (size - 1);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const double dx = x - c, dy = y - c;
                float* f = first.at(x, y);
                f[0] = float(dx);
                f[1] = float(dy);
                f[2] = float(dx * dx);
                f[3] = float(dy * dy);
                second.at(x, y, 0) = float(dx * dy);
            }
        MipPyramidOptions options;
        options.wrap_s = options.wrap_t = WrapMode::clamp;
        options.downsample = downsample;
        first_ = MipPyramid::build(first, options);
        second_ = MipPyramid::build(second, options);
    }

    int size() const { return size_; }
    const MipPyramid& first() const { return first_; }

    // The normalised coordinate of an offset (texels) from the texture centre.
    float coordinate(float offset) const { return (0.5f * float(size_) + offset) / float(size_); }

    // Kernel moments of `lookup(pyramid, s, t, out)` at offset (ox, oy) from the centre.
    KernelMoments measure(
        float ox, float oy,
        const std::function<void(const MipPyramid&, float, float, float*)>& lookup) const {
        float a[4], b[1];
        const float s = coordinate(ox), t = coordinate(oy);
        lookup(first_, s, t, a);
        lookup(second_, s, t, b);
        KernelMoments m;
        const double mx = a[0], my = a[1];
        m.mean = {float(mx), float(my)};
        m.covariance = {float(a[2] - mx * mx + 1.0 / 12), float(b[0] - mx * my),
                        float(a[3] - my * my + 1.0 / 12)};
        return m;
    }

  private:
    int size_;
    MipPyramid first_, second_;
};

// ‖A − B‖_F / ‖B‖_F, as check.py's relerr.
inline double relative_error(const Sym2& a, const Sym2& b) {
    const double dxx = a.xx - b.xx, dxy = a.xy - b.xy, dyy = a.yy - b.yy;
    const double num = std::sqrt(dxx * dxx + 2 * dxy * dxy + dyy * dyy);
    const double den = std::sqrt(double(b.xx) * b.xx + 2.0 * b.xy * b.xy + double(b.yy) * b.yy);
    return num / std::max(den, 1e-300);
}

}  // namespace footprint
