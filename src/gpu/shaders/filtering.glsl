// gpu/shaders/filtering.glsl — texture footprints and footprint assembly (texture/texture_lookup.h,
// texture/footprint_assembly.h, spec §2.7–2.9), each probe one hardware trilinear lookup.
//
// Every 2D map is a sampler2DArray in one array, u_maps, addressed by its index: the materials'
// maps (units 0 … 15, each an array of maps of one shape: one layer per colour map, two per bump
// map's moments), the lat-long map and its polar caps (gpu/gpu_scene.h's units). GLSL indexes sampler arrays
// only with dynamically uniform indices, and neighbouring pixels may show different materials, so
// a probe reaches its map through a switch of constant indices: one filter loop for every map
// (the compiler folds the switch where the index is a constant). The levels are the C++
// pyramids, uploaded level by level; the GPU's bilinear weights (8 fractional bits on most
// hardware) are the one difference in the probes themselves.

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

Texel texel_scaled(Texel x, float w) {
    return Texel(w * x.a, w * x.b);
}

Texel texel_sum(Texel x, Texel y) {
    return Texel(x.a + y.a, x.b + y.b);
}

// One trilinear probe at a hardware lod (the level blend GL_LINEAR_MIPMAP_LINEAR does) of layer
// `first` and, with layers = 2, the layer after it.
Texel probe(int map, int first, int layers, vec2 st, float lod) {
    return Texel(sample_lod(map, vec3(st, first), lod),
                 layers > 1 ? sample_lod(map, vec3(st, first + 1), lod) : vec4(0));
}

// The hardware lod that reads `lod`'s two levels with the blend weight w' = (4^w − 1)/3 instead of
// w (LodBlend::variance_matched, spec §2.8): footprint assembly's blend for a line of probes.
float variance_matched_lod(float lod, int max_level) {
    float l0 = min(floor(lod), float(max_level));
    if (l0 >= float(max_level)) return l0;
    float w = lod - l0;
    return l0 + (exp2(2.0 * w) - 1.0) / 3.0;
}

// The footprint ellipse of K = (xx, xy, yy) (math/footprint_ellipse.h): semi-axes λ1 ≥ λ2 and the
// unit major axis r1, from the eigenvector form without cancellation.
struct Ellipse {
    float l1, l2;
    vec2 r1;
};

Ellipse ellipse_of(vec3 k) {
    float w = sqrt((k.x - k.z) * (k.x - k.z) + 4.0 * k.y * k.y);
    float major_sq = 0.5 * (k.x + k.z + w);
    float minor_sq = major_sq > 0.0 ? max(0.0, k.x * k.z - k.y * k.y) / major_sq : 0.0;
    float l1 = sqrt(max(0.0, major_sq));
    vec2 r = k.x >= k.z ? vec2(k.x - k.z + w, 2.0 * k.y) : vec2(2.0 * k.y, k.z - k.x + w);
    float len = length(r);
    return Ellipse(l1, min(sqrt(minor_sq), l1), len > 0.0 && !isinf(len) ? r / len : vec2(1, 0));
}

// K = D Dᵀ of D's columns.
vec3 footprint_matrix(vec2 d_dx, vec2 d_dy) {
    return vec3(d_dx.x * d_dx.x + d_dy.x * d_dy.x, d_dx.x * d_dx.y + d_dy.x * d_dy.y,
                d_dx.y * d_dx.y + d_dy.y * d_dy.y);
}

// ---- Probe placement: Rule B with Gaussian weights (ProbeRule::gaussian, the CPU's default).
struct Plan {
    int count;     // N
    vec2 step;     // level-0 texels between neighbouring probes, along r1
    float lod;     // the probes' level (a hardware lod: the blend is already applied)
    float falloff; // a: weights ∝ exp(−½(a·k)²), k = i − (N−1)/2
    float texel_size;  // T_p, raised where the line needed more than max_probes probes
};

const float kGaussianProbeExtent = 2.0;
const float kIsotropicRatio = 1.001;

float probe_lod(float texel_size, int max_level) {
    return clamp(log2(max(texel_size, 1.0)), 0.0, float(max_level));
}

// Λ = max(√(λ² + ρ), 1), ρ = clamp(λ1² + λ2² − 1, 0, 1): a semi-axis of `e` with the share of
// the reconstruction the ground truth filters (texture/footprint_assembly.h).
float planned_axis(Ellipse e, float l) {
    float rho = clamp(e.l1 * e.l1 + e.l2 * e.l2 - 1.0, 0.0, 1.0);
    return max(sqrt(l * l + rho), 1.0);
}

// Planned on the axes Λ.
Plan plan_probes(Ellipse e, int max_probes, int max_level) {
    float l1 = planned_axis(e, e.l1), tp = planned_axis(e, e.l2);  // Λ1, T_p = Λ2
    if (l1 <= tp * kIsotropicRatio)  // one probe of size √(Λ1 Λ2)
        return Plan(1, vec2(0), probe_lod(sqrt(tp * l1), max_level), 0.0, sqrt(tp * l1));
    float sigma = 0.5 * sqrt(l1 * l1 - tp * tp);
    int n = 2;
    if (!(sigma * gaussian_spacing[2] <= tp)) {
        n = max(3, int(ceil(2.0 * kGaussianProbeExtent * sigma / (tp * 0.88))) + 1);
        while (n < max_probes && sigma * gaussian_spacing[n] > tp) ++n;
        while (n > 3 && sigma * gaussian_spacing[n - 1] <= tp) --n;
    }
    if (n >= max_probes) {
        n = max(2, max_probes);
        if (max_probes == 1)
            return Plan(1, vec2(0), probe_lod(max(tp, l1), max_level), 0.0, max(tp, l1));
        // Raise T_p until the spacing closes the gaps.
        float c = gaussian_spacing[n];
        tp = max(tp, l1 * 0.5 * c / sqrt(1.0 + 0.25 * c * c));
        sigma = 0.5 * sqrt(max(0.0, l1 * l1 - tp * tp));
    }
    float lod = variance_matched_lod(probe_lod(tp, max_level), max_level);
    return Plan(n, (sigma * gaussian_spacing[n]) * e.r1, lod,
                2.0 * kGaussianProbeExtent / float(n - 1), tp);
}

// Whether `plan` raised its probes' level because the line needed more than its max_probes
// (texture/footprint_assembly.h's exceeds_probe_budget()).
bool exceeds_probe_budget(Plan plan, Ellipse e) {
    return plan.count > 1 && plan.texel_size > 1.0001 * planned_axis(e, e.l2);  // beyond Λ2
}

// Probe i's offset from the centre (level-0 texels) and weight.
vec2 probe_offset(Plan plan, int i) {
    return (float(i) - 0.5 * float(plan.count - 1)) * plan.step;
}
float probe_weight(Plan plan, int i) {
    float k = float(i) - 0.5 * float(plan.count - 1);
    return plan.count <= 2 ? 1.0 : exp(-0.5 * (plan.falloff * k) * (plan.falloff * k));
}

// C = Σ w_i trilinear(c + o_i) / Σ w_i (spec §2.9), probes along r1 in (s, t), of layers `first`
// … first + layers − 1.
Texel assemble(int map, int first, int layers, vec2 st, Plan plan) {
    if (plan.count == 1) return probe(map, first, layers, st, plan.lod);
    vec2 size = map_size(map);
    Texel sum = Texel(vec4(0), vec4(0));
    float weights = 0.0;
    for (int i = 0; i < plan.count; ++i) {
        float w = probe_weight(plan, i);
        sum = texel_sum(sum, texel_scaled(probe(map, first, layers,
                                                st + probe_offset(plan, i) / size, plan.lod),
                                          w));
        weights += w;
    }
    return texel_scaled(sum, 1.0 / weights);
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
    if (!is_finite(len_x2 + len_y2) || len_x2 + len_y2 <= 1.0)  // magnification, or no footprint
        return probe(map, first, layers, st, 0.0);
    if (mode == MODE_TRILINEAR)  // GL's rule: ρ = max(|∂(X,Y)/∂x|, |∂(X,Y)/∂y|)
        return probe(map, first, layers, st,
                     clamp(0.5 * log2(max(len_x2, len_y2)), 0.0, float(max_level)));
    Ellipse e = ellipse_of(footprint_matrix(d_dx, d_dy));
    float limit = 4.0 * max(size.x, size.y);  // larger footprints read the coarsest levels
    e.l1 = min(e.l1, limit);
    e.l2 = min(e.l2, limit);
    return assemble(map, first, layers, st, plan_probes(e, u_max_probes, max_level));
}
