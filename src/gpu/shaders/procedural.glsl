// ---- Procedural textures (texture/procedural.h): gradient noise on the integer lattice, its
// gradients picked by the same integer hash, and the patterns band-limited by fading each octave
// to its mean by the share of it the footprint's Gaussian keeps.

const float PROCEDURAL_NOISE = 1.0, PROCEDURAL_TURBULENCE = 2.0, PROCEDURAL_MARBLE = 3.0,
            PROCEDURAL_CHECKER = 4.0;
const float kMeanAbsNoise = 0.2200;            // procedural.h's E|n|
const float kNoiseGradientVariance = 0.496;    // procedural.h's Var(∂n/∂x_k)
const float kAbsNoiseVariance = 0.0244;        // procedural.h's Var|n|
const float kNoiseBandLimit = 0.448, kAbsNoiseBandLimit = 0.677;  // procedural.cpp's c for n, |n|
// procedural.cpp's kLatticeRotation (columns): the octaves' lattice u = R x.
const mat3 kLatticeRotation = mat3(0.57313785544898699, 0.74034884046078198, -0.35127851212351696,
                                   -0.60900664213739331, 0.67164450419152844, 0.42190587791811218,
                                   0.54829180960859991, -0.02787928294794625, 0.83582225209576422);

uint lattice_hash(ivec3 c) {
    uint h = uint(c.x) * 0x8da6b343u ^ uint(c.y) * 0xd8163841u ^ uint(c.z) * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h & 15u;
}

float gradient_dot(uint h, vec3 d) {
    float u = h < 8u ? d.x : d.y;
    float v = h < 4u ? d.y : (h == 12u || h == 14u ? d.x : d.z);
    return ((h & 1u) != 0u ? -u : u) + ((h & 2u) != 0u ? -v : v);
}

float gradient_noise(vec3 x) {
    vec3 i = floor(x), d = x - i;
    ivec3 c = ivec3(i);
    vec3 q = d * d * d * (d * (d * 6.0 - 15.0) + 10.0);
    float n000 = gradient_dot(lattice_hash(c), d);
    float n100 = gradient_dot(lattice_hash(c + ivec3(1, 0, 0)), d - vec3(1, 0, 0));
    float n010 = gradient_dot(lattice_hash(c + ivec3(0, 1, 0)), d - vec3(0, 1, 0));
    float n110 = gradient_dot(lattice_hash(c + ivec3(1, 1, 0)), d - vec3(1, 1, 0));
    float n001 = gradient_dot(lattice_hash(c + ivec3(0, 0, 1)), d - vec3(0, 0, 1));
    float n101 = gradient_dot(lattice_hash(c + ivec3(1, 0, 1)), d - vec3(1, 0, 1));
    float n011 = gradient_dot(lattice_hash(c + ivec3(0, 1, 1)), d - vec3(0, 1, 1));
    float n111 = gradient_dot(lattice_hash(c + ivec3(1, 1, 1)), d - vec3(1, 1, 1));
    return mix(mix(mix(n000, n100, q.x), mix(n010, n110, q.x), q.y),
               mix(mix(n001, n101, q.x), mix(n011, n111, q.x), q.y), q.z);
}

// The noise and its gradient ∇n (procedural.cpp's gradient_noise_sample()): xyz the gradient,
// w the value.
vec4 gradient_noise_sample(vec3 x) {
    vec3 i = floor(x), d = x - i;
    ivec3 c = ivec3(i);
    vec3 fade = d * d * d * (d * (d * 6.0 - 15.0) + 10.0);
    vec3 fade_slope = 30.0 * d * d * (d - 1.0) * (d - 1.0);
    vec4 n = vec4(0);
    for (int k = 0; k < 8; ++k) {
        ivec3 corner = ivec3(k & 1, (k >> 1) & 1, k >> 2);
        uint h = lattice_hash(c + corner);
        vec3 g = vec3(gradient_dot(h, vec3(1, 0, 0)), gradient_dot(h, vec3(0, 1, 0)),
                      gradient_dot(h, vec3(0, 0, 1)));
        vec3 e = d - vec3(corner);
        float value = dot(g, e);
        vec3 w = mix(1.0 - fade, fade, vec3(corner));
        vec3 s = mix(-fade_slope, fade_slope, vec3(corner));
        n.w += w.x * w.y * w.z * value;
        n.xyz += w.x * w.y * w.z * g + value * vec3(s.x * w.y * w.z, w.x * s.y * w.z, w.x * w.y * s.z);
    }
    return n;
}

// The pixel filter's Gaussian over the footprint in lattice units: its principal variances
// (procedural.cpp's footprint_spread()).
vec2 footprint_spread(vec3 a, vec3 b, float scale) {
    float k = 0.25 * scale * scale;
    float aa = k * dot(a, a), bb = k * dot(b, b), ab = k * dot(a, b);
    float mean = 0.5 * (aa + bb), root = sqrt(0.25 * (aa - bb) * (aa - bb) + ab * ab);
    if (isinf(mean + root) || isnan(mean + root)) return vec2(1e30);
    return vec2(mean + root, max(0.0, mean - root));
}

// The share of an octave's amplitude the footprint keeps (procedural.cpp's octave_weight()).
float octave_weight(float spacing, vec2 spread, bool absolute) {
    float c = absolute ? kAbsNoiseBandLimit : kNoiseBandLimit;
    float k = 4.0 * 9.8696044 * (c / spacing) * (c / spacing);  // 4π² σ_f²
    return 1.0 / sqrt((1.0 + k * spread.x) * (1.0 + k * spread.y));
}

// Σ_i 2^−i (a_i f(n(2^i x)) + (1 − a_i) mean), f = identity or |·|; norm = Σ_i 2^−i.
float fractal_sum(vec3 x, int octaves, vec2 w, bool absolute, out float norm, out float residual) {
    float mean = absolute ? kMeanAbsNoise : 0.0;
    vec3 u = kLatticeRotation * x;
    float sum = 0.0, amplitude = 1.0;
    norm = 0.0;
    residual = 0.0;
    for (int i = 0; i < octaves; ++i, amplitude *= 0.5) {
        float a = octave_weight(amplitude, w, absolute);
        float n = mean;
        if (a > 0.0) {
            n = gradient_noise(u / amplitude);
            if (absolute) n = abs(n);
        }
        sum += amplitude * (a * n + (1.0 - a) * mean);
        norm += amplitude;
        residual += amplitude * amplitude * (1.0 - a * a);
    }
    return sum;
}

// procedural.cpp's stripe_factor(): exp(−σ_x²/2 − Var|n|·residual/2).
float stripe_factor(float scale, vec3 dpdx, vec3 dpdy, float residual) {
    float along = 0.25 * scale * scale * (dpdx.x * dpdx.x + dpdy.x * dpdy.x);
    float e = -0.5 * (along + kAbsNoiseVariance * residual);
    return isinf(e) || isnan(e) ? 0.0 : exp(e);
}

float square_wave_mean(float u, float h) {
    if (isinf(h) || isnan(h)) return 0.0;
    if (!(h > 1e-6)) return floor(u) == 2.0 * floor(0.5 * u) ? 1.0 : -1.0;
    // The triangle wave S(u) = 1 − |(u mod 2) − 1| integrates the square wave.
    float a = u + h, b = u - h;
    float sa = 1.0 - abs(a - 2.0 * floor(0.5 * a) - 1.0);
    float sb = 1.0 - abs(b - 2.0 * floor(0.5 * b) - 1.0);
    return (sa - sb) / (2.0 * h);
}

// procedural_value() at world point p, over the footprint spanned by dpdx, dpdy (zero: a point).
float procedural_value(vec4 info, vec3 p, vec3 dpdx, vec3 dpdy) {
    float scale = info.y;
    vec3 x = scale * p;
    vec2 w = footprint_spread(dpdx, dpdy, scale);
    int octaves = clamp(int(info.z), 1, 16);
    float norm, residual;
    if (info.x == PROCEDURAL_NOISE)
        return clamp(0.5 + 0.5 * fractal_sum(x, octaves, w, false, norm, residual) / norm, 0.0,
                     1.0);
    if (info.x == PROCEDURAL_TURBULENCE)
        return clamp(fractal_sum(x, octaves, w, true, norm, residual) / norm, 0.0, 1.0);
    if (info.x == PROCEDURAL_MARBLE) {
        float turbulence = fractal_sum(x, octaves, w, true, norm, residual);
        float stripes = stripe_factor(scale, dpdx, dpdy, residual);
        return 0.5 + 0.5 * stripes * sin(x.x + turbulence);
    }
    vec3 half_width = 0.8660254 * scale * (abs(dpdx) + abs(dpdy));  // the checker
    float product = square_wave_mean(x.x, half_width.x) * square_wave_mean(x.y, half_width.y) *
                    square_wave_mean(x.z, half_width.z);
    return 0.5 * (1.0 - product);
}

// Σ_i a_i f'(n_i) ∇n(2^i x) and Σ_i (1 − a_i²) (procedural.cpp's fractal_gradient()).
vec3 fractal_gradient(vec3 x, int octaves, vec2 w, bool absolute, out float removed) {
    vec3 sum = vec3(0);
    float amplitude = 1.0;
    removed = 0.0;
    for (int i = 0; i < octaves; ++i, amplitude *= 0.5) {
        float a = octave_weight(amplitude, w, absolute);
        removed += 1.0 - a * a;
        if (!(a > 0.0)) continue;
        vec4 n = gradient_noise_sample((kLatticeRotation * x) / amplitude);
        sum += (absolute && n.w < 0.0 ? -a : a) * (n.xyz * kLatticeRotation);  // Rᵀ ∇n
    }
    return sum;
}

// procedural_slopes(): ∇v band-limited, and the removed covariance, as mat3.
struct ProceduralSlopes {
    vec3 gradient;
    mat3 covariance;
};

ProceduralSlopes procedural_slopes(vec4 info, vec3 p, vec3 dpdx, vec3 dpdy) {
    ProceduralSlopes out_slopes = ProceduralSlopes(vec3(0), mat3(0));
    float scale = info.y;
    vec3 x = scale * p;
    vec2 w = footprint_spread(dpdx, dpdy, scale);
    int octaves = clamp(int(info.z), 1, 16);
    float norm = 2.0 - exp2(1.0 - float(octaves));  // Σ_{i<N} 2^−i
    float removed;
    if (info.x == PROCEDURAL_NOISE || info.x == PROCEDURAL_TURBULENCE) {
        bool absolute = info.x == PROCEDURAL_TURBULENCE;
        float k = (absolute ? 1.0 : 0.5) * scale / norm;
        out_slopes.gradient = k * fractal_gradient(x, octaves, w, absolute, removed);
        out_slopes.covariance = mat3(k * k * removed * kNoiseGradientVariance);
    } else if (info.x == PROCEDURAL_MARBLE) {
        float unused, residual;
        float turbulence = fractal_sum(x, octaves, w, true, unused, residual);
        vec3 turbulence_gradient = scale * fractal_gradient(x, octaves, w, true, removed);
        float stripes = stripe_factor(scale, dpdx, dpdy, residual);
        float c = cos(x.x + turbulence);
        out_slopes.gradient = 0.5 * stripes * c * (vec3(scale, 0, 0) + turbulence_gradient);
        float c2 = 0.5 + stripes * stripes * (c * c - 0.5);
        out_slopes.covariance = mat3(0.25 * c2 * scale * scale * removed * kNoiseGradientVariance);
        out_slopes.covariance[0][0] += 0.125 * scale * scale * (1.0 - stripes * stripes);
    }
    return out_slopes;
}

vec3 procedural_color(Material material, vec3 p, vec3 dpdx, vec3 dpdy) {
    float v = procedural_value(material.procedural, p, dpdx, dpdy);
    return mix(material.procedural_colors[0].rgb, material.procedural_colors[1].rgb, v);
}
