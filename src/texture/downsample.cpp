#include "texture/downsample.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/parallel.h"

namespace footprint::detail {

namespace {

// One source texel's weight in a destination texel.
struct Tap {
    int index;
    double weight;
};

// The taps of every destination texel along one axis (compressed rows: taps[first[i]..first[i+1])).
struct AxisTaps {
    std::vector<int> first;
    std::vector<Tap> taps;
};

// Cumulative distribution of the downsampling kernel, in destination-texel units: box = B-spline of
// order 0 (support ±½), tent = B-spline of order 1 (support ±1).
double kernel_cdf(DownsampleFilter filter, double u) {
    switch (filter) {
        case DownsampleFilter::box:
            return std::clamp(u + 0.5, 0.0, 1.0);
        case DownsampleFilter::tent:
            if (u <= -1) return 0;
            if (u >= 1) return 1;
            return u <= 0 ? 0.5 * (u + 1) * (u + 1) : 1 - 0.5 * (1 - u) * (1 - u);
    }
    return 0;
}

double kernel_radius(DownsampleFilter filter) {
    return filter == DownsampleFilter::box ? 0.5 : 1.0;
}

// Exact integral of the kernel over each source texel [j, j+1), for destination texel centres at
// (i + ½)·r in source units. Source indices outside [0, src) wrap with the pyramid's wrap mode.
AxisTaps make_axis_taps(int src, int dst, DownsampleFilter filter, WrapMode wrap) {
    AxisTaps axis;
    const double r = static_cast<double>(src) / dst;
    const double radius = kernel_radius(filter) * r;
    axis.first.reserve(dst + 1);
    for (int i = 0; i < dst; ++i) {
        axis.first.push_back(static_cast<int>(axis.taps.size()));
        const double centre = (i + 0.5) * r;
        const int j0 = static_cast<int>(std::floor(centre - radius));
        const int j1 = static_cast<int>(std::ceil(centre + radius));
        double sum = 0;
        const std::size_t begin = axis.taps.size();
        for (int j = j0; j < j1; ++j) {
            const double w =
                kernel_cdf(filter, (j + 1 - centre) / r) - kernel_cdf(filter, (j - centre) / r);
            if (w <= 1e-12) continue;
            axis.taps.push_back({wrap_index(j, src, wrap), w});
            sum += w;
        }
        // The weights are a partition of unity analytically; renormalise away the rounding.
        for (std::size_t k = begin; k < axis.taps.size(); ++k) axis.taps[k].weight /= sum;
    }
    axis.first.push_back(static_cast<int>(axis.taps.size()));
    return axis;
}

// Variance of one destination texel's taps about its centre, in source texels² (the variance the
// downsampling step adds; for the box with r = 2 it is ¼, for the tent ¾).
}  // namespace

double tap_variance(int src, int dst, DownsampleFilter filter) {
    if (src == dst) return 0;
    const AxisTaps axis = make_axis_taps(src, dst, filter, WrapMode::repeat);
    const int i = dst / 2;  // an interior texel (wrap cannot fold taps onto each other there)
    const double centre = (i + 0.5) * src / dst - 0.5;  // in source texel-centre coordinates
    double var = 0;
    for (int k = axis.first[i]; k < axis.first[i + 1]; ++k) {
        const double d = axis.taps[k].index - centre;
        var += axis.taps[k].weight * d * d;
    }
    return var;
}

// Separable downsampling of a row-major (sw × sh × stride) buffer into a row-major (dw × dh ×
// stride) buffer, fused per output row: the vertical taps combine source rows into one row of
// scratch, then the horizontal taps read it. No level-sized temporary, and each source row is read
// once per output row that needs it.
template <class In, class T>
void downsample(const In* src, int sw, int sh, T* dst, int dw, int dh, int stride,
                const MipPyramidOptions& options, std::ptrdiff_t src_pitch,
                std::ptrdiff_t dst_pitch) {
    const AxisTaps xt = make_axis_taps(sw, dw, options.downsample, options.wrap_s);
    const AxisTaps yt = make_axis_taps(sh, dh, options.downsample, options.wrap_t);
    const std::size_t src_row = static_cast<std::size_t>(sw) * stride;
    if (src_pitch == 0) src_pitch = static_cast<std::ptrdiff_t>(src_row);
    if (dst_pitch == 0) dst_pitch = static_cast<std::ptrdiff_t>(dw) * stride;
    parallel_for(0, dh, 8, [&](int first, int end) {
        std::vector<T> column_sum(src_row);
        T acc[MipPyramid::kMaxChannels];
        for (int y = first; y < end; ++y) {
            std::fill(column_sum.begin(), column_sum.end(), T(0));
            for (int k = yt.first[y]; k < yt.first[y + 1]; ++k) {
                const T w = static_cast<T>(yt.taps[k].weight);
                const In* in = src + yt.taps[k].index * src_pitch;
                for (std::size_t i = 0; i < src_row; ++i)
                    column_sum[i] += w * static_cast<T>(in[i]);
            }
            T* out = dst + y * dst_pitch;
            for (int x = 0; x < dw; ++x) {
                std::fill(acc, acc + stride, T(0));
                for (int k = xt.first[x]; k < xt.first[x + 1]; ++k) {
                    const T w = static_cast<T>(xt.taps[k].weight);
                    const T* t =
                        column_sum.data() + static_cast<std::size_t>(xt.taps[k].index) * stride;
                    for (int c = 0; c < stride; ++c) acc[c] += w * t[c];
                }
                std::copy(acc, acc + stride, out + static_cast<std::size_t>(x) * stride);
            }
        }
    });
}

template void downsample<float, float>(const float*, int, int, float*, int, int, int,
                                       const MipPyramidOptions&, std::ptrdiff_t, std::ptrdiff_t);
template void downsample<float, double>(const float*, int, int, double*, int, int, int,
                                        const MipPyramidOptions&, std::ptrdiff_t, std::ptrdiff_t);
template void downsample<double, double>(const double*, int, int, double*, int, int, int,
                                         const MipPyramidOptions&, std::ptrdiff_t, std::ptrdiff_t);

}  // namespace footprint::detail
