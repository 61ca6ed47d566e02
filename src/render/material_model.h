// render/material_model.h — (private) glTF's metallic-roughness material in the renderer's terms:
// a diffuse colour, a Fresnel F0 per channel and a slope variance per texel.
//
// glTF 2.0 (appendix B) shades base colour c, metallic m and perceptual roughness r as a mix of a
// dielectric (F0 = 0.04, Lambert of albedo c) and a metal (F0 = c, no diffuse), weighted by m. The
// renderer's shading (render/renderer.h) takes it as
//     diffuse colour   c (1 − m)               Lambert, BRDF c (1 − m)/π
//     F0               0.04 (1 − m) + c m      Schlick, per channel, in the highlight and the
//     mirror slope variance   α²/2 per axis, α = r²   Beckmann's slopes (GGX's moment match)
// Each is made texel by texel from the textures at level 0 and only then filtered: filtering c and
// m apart and combining them after would be biased (the mean of c·m is not the product of the
// means). The slope variance enters the bump pyramid's K_0 texel by texel
// (BumpPyramidOptions::micro_variance), so that a filtered K_b holds the mean roughness of the
// region plus the spread of its normals: the roughness pyramid does for r what mipmapping r
// cannot. The diffuse term is not reduced by (1 − F), as in glTF's simplest implementations.
#pragma once

#include <footprint/image/image.h>
#include <footprint/math/vec3.h>

namespace footprint::detail {

constexpr float kDielectricF0 = 0.04f;  // glTF's: an index of refraction of 1.5

Vec3 diffuse_color(Vec3 base, float metallic);  // c (1 − m)
Vec3 specular_f0(Vec3 base, float metallic);    // 0.04 (1 − m) + c m
float slope_variance(float roughness);          // α²/2 = r⁴/2

// The three maps of one material, at the larger of its textures' sizes.
struct MetallicRoughnessTexels {
    Image diffuse;   // 3 channels: c (1 − m)
    Image f0;        // 3 channels: 0.04 (1 − m) + c m
    Image variance;  // 1 channel: α²/2
};

// From a base colour texture (linear; 1–2 channels grey, 3–4 RGB, alpha ignored) × `base`, and a
// metallic-roughness texture (glTF's: G roughness, B metallic) × `metallic` and `roughness`; either
// texture may be null (the factor alone), not both. A texture smaller than the other is
// interpolated bilinearly at the finer texels' centres (wrapping, as the maps repeat).
MetallicRoughnessTexels metallic_roughness_texels(const Image* base_texture, Vec3 base,
                                                  const Image* metallic_roughness_texture,
                                                  float metallic, float roughness);

// `image` (any channels) at width × height: itself if it is that size, else interpolated
// bilinearly at the new texels' centres with wrapping.
Image resampled(const Image& image, int width, int height);

}  // namespace footprint::detail
