#include "texture/reference_filter.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace footprint {

namespace {

// Bilinear reconstruction of level 0 at texel-centre coordinates (x, y), in double.
void bilinear(const Image& image, WrapMode ws, WrapMode wt, double x, double y, double weight,
              double* acc) {
    const double xf = std::floor(x), yf = std::floor(y);
    const double fx = x - xf, fy = y - yf;
    const int x0 = wrap_index(static_cast<int>(xf), image.width, ws);
    const int x1 = wrap_index(static_cast<int>(xf) + 1, image.width, ws);
    const int y0 = wrap_index(static_cast<int>(yf), image.height, wt);
    const int y1 = wrap_index(static_cast<int>(yf) + 1, image.height, wt);
    const float *a = image.at(x0, y0), *b = image.at(x1, y0), *c = image.at(x0, y1),
                *d = image.at(x1, y1);
    for (int k = 0; k < image.channels; ++k)
        acc[k] += weight * ((1 - fx) * (1 - fy) * a[k] + fx * (1 - fy) * b[k] +
                            (1 - fx) * fy * c[k] + fx * fy * d[k]);
}

}  // namespace

void reference_lookup(const Image& level0, double s, double t, const FootprintEllipse& footprint,
                      const ReferenceOptions& options, float* out) {
    // Kernel covariance K/4: σ_i = λ_i/2 along the principal axes.
    const double sigma[2] = {0.5 * footprint.major_radius, 0.5 * footprint.minor_radius};
    const double axis[2][2] = {{footprint.major_axis.x, footprint.major_axis.y},
                               {-footprint.major_axis.y, footprint.major_axis.x}};
    // Nodes per axis: midpoints of n equal cells over [−Rσ, Rσ]; a zero-width axis is one node.
    int n[2];
    double h[2];
    for (int a = 0; a < 2; ++a) {
        const double extent = 2 * options.truncation_sigmas * sigma[a];
        const double spacing =
            std::min(options.max_node_spacing, sigma[a] / options.nodes_per_sigma);
        n[a] = sigma[a] > 0 ? std::max(1, static_cast<int>(std::ceil(extent / spacing))) : 1;
        h[a] = sigma[a] > 0 ? extent / n[a] : 0;
    }
    std::vector<double> wu(n[0]), wv(n[1]);
    auto gaussian_nodes = [&](int a, std::vector<double>& w) {
        for (int i = 0; i < n[a]; ++i) {
            const double u = (i + 0.5) * h[a] - 0.5 * n[a] * h[a];
            w[i] = sigma[a] > 0 ? std::exp(-0.5 * u * u / (sigma[a] * sigma[a])) : 1.0;
        }
    };
    gaussian_nodes(0, wu);
    gaussian_nodes(1, wv);

    const double cx = s * level0.width - 0.5, cy = t * level0.height - 0.5;
    double acc[8] = {}, weight_sum = 0;
    for (int j = 0; j < n[1]; ++j) {
        const double v = (j + 0.5) * h[1] - 0.5 * n[1] * h[1];
        for (int i = 0; i < n[0]; ++i) {
            const double u = (i + 0.5) * h[0] - 0.5 * n[0] * h[0];
            const double w = wu[i] * wv[j];
            const double x = cx + u * axis[0][0] + v * axis[1][0];
            const double y = cy + u * axis[0][1] + v * axis[1][1];
            bilinear(level0, options.wrap_s, options.wrap_t, x, y, w, acc);
            weight_sum += w;
        }
    }
    for (int k = 0; k < level0.channels; ++k) out[k] = static_cast<float>(acc[k] / weight_sum);
}

}  // namespace footprint
