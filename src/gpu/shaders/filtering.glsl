// gpu/shaders/filtering.glsl — 2D maps and their lookups in each filter mode
// (texture/texture_lookup.h). Footprint assembly itself — the plan, the probes' offsets, weights
// and levels, and the loop that blends them — is the library's (footprint/texture.glsl,
// docs/method.md, "Footprint assembly"); this file reaches the scene's maps for it.
//
// Every 2D map is a sampler2DArray in one array, u_maps, addressed by its index: the materials'
// maps (units 0 … 15, each an array of maps of one shape: one layer per colour map, two per bump
// map's moments), the lat-long map and its polar caps (gpu/gpu_scene.h's units). GLSL indexes sampler arrays
// only with dynamically uniform indices, and neighbouring pixels may show different materials, so
// a probe reaches its map through a switch of constant indices: one filter loop for every map
// (the compiler folds the switch where the index is a constant). The levels are the C++
// pyramids, uploaded level by level; the GPU's bilinear weights (8 fractional bits on most
// hardware) are the one difference in the probes themselves.

#include "footprint/texture.glsl"

const int kMapCount = 18;
const int MAP_ENV = 16;
const int MAP_CAPS = 17;
uniform sampler2DArray u_maps[kMapCount];
uniform vec4 u_map_info[kMapCount];  // level-0 width, height, max level, layers

#define MAP_CASES(CALL)                                                                          \
    switch (map) {                                                                               \
        case 0: return CALL(0); case 1: return CALL(1); case 2: return CALL(2);                  \
        case 3: return CALL(3); case 4: return CALL(4); case 5: return CALL(5);                  \
        case 6: return CALL(6); case 7: return CALL(7); case 8: return CALL(8);                  \
        case 9: return CALL(9); case 10: return CALL(10); case 11: return CALL(11);              \
        case 12: return CALL(12); case 13: return CALL(13); case 14: return CALL(14);            \
        case 15: return CALL(15); case 16: return CALL(16); default: return CALL(17);            \
    }

vec4 sample_lod(int map, vec3 stl, float lod) {
#define SAMPLE_LOD(i) textureLod(u_maps[i], stl, lod)
    MAP_CASES(SAMPLE_LOD)
#undef SAMPLE_LOD
}

vec4 sample_grad(int map, vec3 stl, vec2 dx, vec2 dy) {
#define SAMPLE_GRAD(i) textureGrad(u_maps[i], stl, dx, dy)
    MAP_CASES(SAMPLE_GRAD)
#undef SAMPLE_GRAD
}

vec2 map_size(int map) {
    return u_map_info[map].xy;
}
int map_max_level(int map) {
    return int(u_map_info[map].z);
}

// A lookup's result: layer 0 in a, layer 1 (the bump moments' fifth channel) in b.
struct Texel {
    vec4 a, b;
};

// One trilinear probe at a hardware lod (the level blend GL_LINEAR_MIPMAP_LINEAR does) of layer
// `first` and, with layers = 2, the layer after it, as the columns of a mat2x4 (which adds up in
// FP_ASSEMBLE).
mat2x4 probe_layers(int map, int first, int layers, vec2 st, float lod) {
    return mat2x4(sample_lod(map, vec3(st, first), lod),
                  layers > 1 ? sample_lod(map, vec3(st, first + 1), lod) : vec4(0));
}

Texel probe(int map, int first, int layers, vec2 st, float lod) {
    mat2x4 m = probe_layers(map, first, layers, st, lod);
    return Texel(m[0], m[1]);
}

// C = Σ w_i trilinear(c + o_i) / Σ w_i over the plan's probes (footprint/texture.glsl's
// FP_ASSEMBLE), of layers `first` … first + layers − 1.
Texel assemble(int map, int first, int layers, vec2 st, FpPlan plan) {
    mat2x4 sum;
#define PROBE_LAYERS(i, at, lod) probe_layers(map, first, layers, at, lod)
    FP_ASSEMBLE(mat2x4, sum, plan, st, map_size(map), PROBE_LAYERS)
#undef PROBE_LAYERS
    return Texel(sum[0], sum[1]);
}

// The GPU's own anisotropic filter (hw-aniso) over D = (d_dx, d_dy) in level-0 texels: textureGrad
// with the exact derivatives, through the sampler with the driver's maximum anisotropy.
Texel hardware_lookup(int map, int first, int layers, vec2 st, vec2 d_dx, vec2 d_dy) {
    vec2 size = map_size(map);
    return Texel(sample_grad(map, vec3(st, first), d_dx / size, d_dy / size),
                 layers > 1 ? sample_grad(map, vec3(st, first + 1), d_dx / size, d_dy / size)
                            : vec4(0));
}

// A filtered lookup of a 2D map in `mode` (texture/texture_lookup.h's coords overload):
// st = (s, t), dst = (∂s/∂x, ∂t/∂x, ∂s/∂y, ∂t/∂y) in normalised units; the map's layers `first`
// … first + layers − 1.
Texel lookup_2d(int map, int first, int layers, vec2 st, vec4 dst, int mode) {
    if (mode == MODE_POINT) return probe(map, first, layers, st, 0.0);
    vec2 size = map_size(map);
    if (mode == MODE_HW_ANISO)
        return hardware_lookup(map, first, layers, st, dst.xy * size, dst.zw * size);
    int max_level = map_max_level(map);
    vec2 d_dx = dst.xy * size, d_dy = dst.zw * size;  // the columns of D, level-0 texels
    float len_x2 = dot(d_dx, d_dx), len_y2 = dot(d_dy, d_dy);
    if (!fp_is_finite(len_x2 + len_y2) || len_x2 + len_y2 <= 1.0)  // magnification, or no footprint
        return probe(map, first, layers, st, 0.0);
    if (mode == MODE_TRILINEAR)  // GL's rule: ρ = max(|∂(X,Y)/∂x|, |∂(X,Y)/∂y|)
        return probe(map, first, layers, st,
                     clamp(0.5 * log2(max(len_x2, len_y2)), 0.0, float(max_level)));
    return assemble(map, first, layers, st,
                    fp_texture_plan(size, max_level, d_dx, d_dy, u_max_probes));
}
