// gaussian_downsample N IN OUT — the last step of bench/oiio-testtex.sh's second reference: an
// image rendered at N× the resolution (N×N point samples per pixel) filtered back down to one
// pixel in N×N by a Gaussian pixel filter of σ = ½ pixel around each pixel's centre, cut at 4σ:
// the measure docs/method.md uses for footprint's own ground truth. At the image's edges the
// weights are those of the samples inside, renormalised. The box reference is oiiotool's
// --resize:filter=box. Writes OUT as float.
#include <OpenImageIO/imagebuf.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

// One axis: output index o covers inputs [o·n, (o+1)·n), centre (o + ½)·n in input units (input
// sample i sits at i + ½). The weights of the inputs within 4σ, σ = n/2, normalised.
std::vector<std::vector<std::pair<int, double>>> axis_weights(int outputs, int n, int inputs) {
    std::vector<std::vector<std::pair<int, double>>> all(outputs);
    const double sigma = 0.5 * n, reach = 4 * sigma;
    for (int o = 0; o < outputs; ++o) {
        const double centre = (o + 0.5) * n;
        double sum = 0;
        for (int i = static_cast<int>(std::floor(centre - reach));
             i <= static_cast<int>(std::ceil(centre + reach)); ++i) {
            if (i < 0 || i >= inputs) continue;
            const double u = (i + 0.5 - centre) / sigma;
            if (std::fabs(u) > 4) continue;
            const double w = std::exp(-0.5 * u * u);
            all[o].emplace_back(i, w);
            sum += w;
        }
        for (auto& [i, w] : all[o]) w /= sum;
    }
    return all;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: gaussian_downsample N IN OUT\n");
        return 2;
    }
    const int n = std::atoi(argv[1]);
    OIIO::ImageBuf in(argv[2]);
    if (n < 1 || !in.read(0, 0, true, OIIO::TypeFloat)) {
        std::fprintf(stderr, "gaussian_downsample: %s\n",
                     n < 1 ? "N must be positive" : in.geterror().c_str());
        return 1;
    }
    const OIIO::ImageSpec& spec = in.spec();
    const int iw = spec.width, ih = spec.height, ch = spec.nchannels;
    if (iw % n || ih % n) {
        std::fprintf(stderr, "gaussian_downsample: %dx%d is not a multiple of %d\n", iw, ih, n);
        return 1;
    }
    const int ow = iw / n, oh = ih / n;
    std::vector<float> src(static_cast<size_t>(iw) * ih * ch);
    in.get_pixels(OIIO::ROI::All(), OIIO::TypeFloat, src.data());

    // Separable: along x into rows of ow pixels, then along y.
    const auto wx = axis_weights(ow, n, iw), wy = axis_weights(oh, n, ih);
    std::vector<double> rows(static_cast<size_t>(ow) * ih * ch, 0.0);
    for (int y = 0; y < ih; ++y)
        for (int x = 0; x < ow; ++x)
            for (const auto& [i, w] : wx[x])
                for (int c = 0; c < ch; ++c)
                    rows[(static_cast<size_t>(y) * ow + x) * ch + c] +=
                        w * src[(static_cast<size_t>(y) * iw + i) * ch + c];
    std::vector<float> dst(static_cast<size_t>(ow) * oh * ch);
    for (int y = 0; y < oh; ++y)
        for (int x = 0; x < ow; ++x)
            for (int c = 0; c < ch; ++c) {
                double v = 0;
                for (const auto& [j, w] : wy[y])
                    v += w * rows[(static_cast<size_t>(j) * ow + x) * ch + c];
                dst[(static_cast<size_t>(y) * ow + x) * ch + c] = static_cast<float>(v);
            }

    OIIO::ImageSpec out_spec(ow, oh, ch, OIIO::TypeFloat);
    out_spec.channelnames = spec.channelnames;
    OIIO::ImageBuf out(out_spec, dst.data());
    if (!out.write(argv[3])) {
        std::fprintf(stderr, "gaussian_downsample: %s\n", out.geterror().c_str());
        return 1;
    }
    return 0;
}
