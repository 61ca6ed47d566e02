// texture/summed_area_table.h — summed-area tables (Crow 1984): box means in constant time.
//
// The table holds, in double precision, T(x, y) = Σ_{i<x, j<y} texel(i, j) for the level-0 image,
// so the integral of the piecewise-constant texture over any axis-aligned box is four look-ups
// (the lecture notes' A − B − C + D). Box corners at fractional positions interpolate the table
// bilinearly, which is exact for a piecewise-constant texture. Boxes that leave the texture are
// integrated over the texture extended by the wrap modes (repeat, clamp-to-edge, mirror), so a
// box straddling an edge is still one exact integral.
//
// Coordinates here are texel *edges*: texel i covers [i, i+1), i.e. E = s·W (spec §1's texel
// centre coordinate is X = E − ½). A SAT can only represent axis-aligned boxes; the lookup filter
// (TextureFilter::summed_area) uses the footprint ellipse's bounding rectangle, so it blurs rotated
// anisotropic footprints — it is here as the classic baseline, not as a recommendation (spec §8).
#pragma once

#include <vector>

#include <footprint/image/image.h>
#include <footprint/texture/wrap.h>

namespace footprint {

class SummedAreaTable {
  public:
    static SummedAreaTable build(const Image& image, WrapMode wrap_s, WrapMode wrap_t);

    int width() const { return width_; }
    int height() const { return height_; }
    int channels() const { return channels_; }

    // Mean over the box [x0, x1] × [y0, y1] (texel-edge coordinates, x0 < x1, y0 < y1, each
    // within a few texture periods of the texture) of the wrap-extended texture: channels() floats.
    void box_mean(double x0, double y0, double x1, double y1, float* out) const;

  private:
    // The table entry at integer corner (x, y), x ∈ [0, W], y ∈ [0, H]; `channels_` doubles.
    const double* corner(int x, int y) const {
        return table_.data() + (static_cast<std::size_t>(y) * (width_ + 1) + x) * channels_;
    }
    // ∫∫ over [0, x] × [0, y] of the wrap-extended texture, added into sum[] with a factor.
    void accumulate_integral(double x, double y, double factor, double* sum) const;

    int width_ = 0, height_ = 0, channels_ = 0;
    WrapMode wrap_s_ = WrapMode::repeat, wrap_t_ = WrapMode::repeat;
    std::vector<double> table_;  // (W+1) × (H+1) × channels
};

}  // namespace footprint
