#include "render/material_model.h"

#include <algorithm>
#include <cmath>

namespace footprint::detail {

Vec3 diffuse_color(Vec3 base, float metallic) {
    return (1 - metallic) * base;
}

Vec3 specular_f0(Vec3 base, float metallic) {
    const float dielectric = kDielectricF0 * (1 - metallic);
    return {dielectric + metallic * base.x, dielectric + metallic * base.y,
            dielectric + metallic * base.z};
}

float slope_variance(float roughness) {
    const float alpha = roughness * roughness;
    return 0.5f * alpha * alpha;
}

Image resampled(const Image& image, int width, int height) {
    if (image.width == width && image.height == height) return image;
    Image out(width, height, image.channels);
    auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
    for (int y = 0; y < height; ++y) {
        const double fy = (y + 0.5) * image.height / height - 0.5;
        const int y0 = static_cast<int>(std::floor(fy));
        const float wy = static_cast<float>(fy - y0);
        for (int x = 0; x < width; ++x) {
            const double fx = (x + 0.5) * image.width / width - 0.5;
            const int x0 = static_cast<int>(std::floor(fx));
            const float wx = static_cast<float>(fx - x0);
            const int xa = wrap(x0, image.width), xb = wrap(x0 + 1, image.width);
            const int ya = wrap(y0, image.height), yb = wrap(y0 + 1, image.height);
            for (int c = 0; c < image.channels; ++c) {
                const float top = (1 - wx) * image.at(xa, ya, c) + wx * image.at(xb, ya, c);
                const float bottom = (1 - wx) * image.at(xa, yb, c) + wx * image.at(xb, yb, c);
                out.at(x, y, c) = (1 - wy) * top + wy * bottom;
            }
        }
    }
    return out;
}

MetallicRoughnessTexels metallic_roughness_texels(const Image* base_texture, Vec3 base,
                                                  const Image* metallic_roughness_texture,
                                                  float metallic, float roughness) {
    int width = 1, height = 1;
    for (const Image* texture : {base_texture, metallic_roughness_texture}) {
        if (!texture) continue;
        width = std::max(width, texture->width);
        height = std::max(height, texture->height);
    }
    const Image colour = base_texture ? resampled(*base_texture, width, height) : Image();
    const Image material = metallic_roughness_texture
                               ? resampled(*metallic_roughness_texture, width, height)
                               : Image();
    MetallicRoughnessTexels out{Image(width, height, 3), Image(width, height, 3),
                                Image(width, height, 1)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            Vec3 c = base;
            if (!colour.empty()) {
                const bool grey = colour.channels < 3;
                c = {c.x * colour.at(x, y, 0), c.y * colour.at(x, y, grey ? 0 : 1),
                     c.z * colour.at(x, y, grey ? 0 : 2)};
            }
            float m = metallic, r = roughness;
            if (!material.empty()) {  // glTF: roughness in G, metallic in B
                const int channels = material.channels;
                r *= material.at(x, y, std::min(1, channels - 1));
                m *= material.at(x, y, std::min(2, channels - 1));
            }
            const Vec3 d = diffuse_color(c, m), f0 = specular_f0(c, m);
            out.diffuse.at(x, y, 0) = d.x, out.diffuse.at(x, y, 1) = d.y;
            out.diffuse.at(x, y, 2) = d.z;
            out.f0.at(x, y, 0) = f0.x, out.f0.at(x, y, 1) = f0.y, out.f0.at(x, y, 2) = f0.z;
            out.variance.at(x, y, 0) = slope_variance(r);
        }
    return out;
}

}  // namespace footprint::detail
