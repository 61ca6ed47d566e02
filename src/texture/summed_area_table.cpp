#include "texture/summed_area_table.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace footprint {

namespace {

// ∫_0^x g over the wrap-extended axis, written as Σ coefficient · G(position) with positions in
// [0, n], G(p) = ∫_0^p g over the texture itself. At most three terms.
struct AxisTerm {
    double coefficient;
    double position;
};

int axis_terms(double x, int n, WrapMode mode, AxisTerm* terms) {
    switch (mode) {
        case WrapMode::repeat: {
            const double q = std::floor(x / n);
            terms[0] = {q, double(n)};
            terms[1] = {1.0, x - q * n};
            return 2;
        }
        case WrapMode::clamp:
            if (x < 0) {  // the edge texel repeated: x · g(0) = x · G(1)
                terms[0] = {x, std::min(1.0, double(n))};
                return 1;
            }
            if (x <= n) {
                terms[0] = {1.0, x};
                return 1;
            }
            // G(n) + (x − n) · g(n − 1), with g(n − 1) = G(n) − G(n − 1)
            terms[0] = {1.0 + (x - n), double(n)};
            terms[1] = {-(x - n), double(n - 1)};
            return 2;
        case WrapMode::mirror: {
            const double period = 2.0 * n;
            const double q = std::floor(x / period);
            const double r = x - q * period;
            if (r <= n) {
                terms[0] = {2 * q, double(n)};
                terms[1] = {1.0, r};
                return 2;
            }
            // ∫_0^r = G(n) + (G(n) − G(2n − r)) on the mirrored half
            terms[0] = {2 * q + 2, double(n)};
            terms[1] = {-1.0, period - r};
            return 2;
        }
    }
    return 0;
}

}  // namespace

SummedAreaTable SummedAreaTable::build(const Image& image, WrapMode wrap_s, WrapMode wrap_t) {
    assert(!image.empty());
    SummedAreaTable sat;
    sat.width_ = image.width;
    sat.height_ = image.height;
    sat.channels_ = image.channels;
    sat.wrap_s_ = wrap_s;
    sat.wrap_t_ = wrap_t;
    const int w1 = image.width + 1, nc = image.channels;
    sat.table_.assign(static_cast<std::size_t>(w1) * (image.height + 1) * nc, 0.0);
    for (int y = 0; y < image.height; ++y) {
        double* row = sat.table_.data() + static_cast<std::size_t>(y + 1) * w1 * nc;
        const double* above = row - static_cast<std::size_t>(w1) * nc;
        for (int c = 0; c < nc; ++c) {
            double running = 0;  // Σ of this row up to x
            for (int x = 0; x < image.width; ++x) {
                running += image.at(x, y, c);
                row[(x + 1) * nc + c] = above[(x + 1) * nc + c] + running;
            }
        }
    }
    return sat;
}

void SummedAreaTable::accumulate_integral(double x, double y, double factor, double* sum) const {
    AxisTerm xs[3], ys[3];
    const int nx = axis_terms(x, width_, wrap_s_, xs);
    const int ny = axis_terms(y, height_, wrap_t_, ys);
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            const double f = factor * xs[i].coefficient * ys[j].coefficient;
            if (f == 0) continue;
            // Bilinear interpolation of the table: exact for a piecewise-constant texture.
            const double px = std::clamp(xs[i].position, 0.0, double(width_));
            const double py = std::clamp(ys[j].position, 0.0, double(height_));
            const int x0 = std::min(static_cast<int>(px), width_ - 1);
            const int y0 = std::min(static_cast<int>(py), height_ - 1);
            const double fx = px - x0, fy = py - y0;
            const double* t00 = corner(x0, y0);
            const double* t10 = corner(x0 + 1, y0);
            const double* t01 = corner(x0, y0 + 1);
            const double* t11 = corner(x0 + 1, y0 + 1);
            for (int c = 0; c < channels_; ++c) {
                const double top = t00[c] + fx * (t10[c] - t00[c]);
                const double bottom = t01[c] + fx * (t11[c] - t01[c]);
                sum[c] += f * (top + fy * (bottom - top));
            }
        }
    }
}

void SummedAreaTable::box_mean(double x0, double y0, double x1, double y1, float* out) const {
    double sum[8] = {};
    assert(channels_ <= 8 && x1 > x0 && y1 > y0);
    accumulate_integral(x1, y1, 1.0, sum);
    accumulate_integral(x0, y1, -1.0, sum);
    accumulate_integral(x1, y0, -1.0, sum);
    accumulate_integral(x0, y0, 1.0, sum);
    const double area = (x1 - x0) * (y1 - y0);
    for (int c = 0; c < channels_; ++c) out[c] = static_cast<float>(sum[c] / area);
}

}  // namespace footprint
