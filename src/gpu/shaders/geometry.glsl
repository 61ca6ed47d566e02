// gpu/shaders/geometry.glsl — camera rays, analytic shapes and ray differentials: scene/shapes.cpp,
// render/camera.cpp and scene/ray_differentials.cpp on the GPU, in float around the camera.
//
// Every shape is intersected exactly as on the CPU (the same quadratic forms that avoid
// cancellation) and returns the same differential geometry: p, n, ∂p/∂(u,v), ∂n/∂(u,v), (u, v).
// The pixel's differentials are then the exact ray differentials of the pinhole camera transferred
// to the hit (Igehy 1999), not screen-space derivatives: dFdx of a fragment quad is a one-sided
// difference over two pixels that breaks at every silhouette and every wrap of (u, v), while the
// analytic transfer is exact to first order at every pixel, as on the CPU.

struct Ray {
    vec3 origin;
    vec3 direction;  // any nonzero length; t in units of |direction|
};

struct Hit {
    float t;
    vec3 p, n, dpdu, dpdv, dndu, dndv;
    vec2 uv;
    int object;
};

Ray camera_ray(vec2 pixel) {
    vec2 c = 0.5 * vec2(u_size);
    return Ray(vec3(0), u_camera_forward + (u_pixel_angle * (pixel.x - c.x)) * u_camera_right -
                            (u_pixel_angle * (pixel.y - c.y)) * u_camera_up);
}

// (cos, sin) of the angle of (along_cos, along_sin); (1, 0) for the zero vector.
vec2 cos_sin(float along_cos, float along_sin) {
    float h = length(vec2(along_cos, along_sin));
    return h > 0.0 ? vec2(along_cos, along_sin) / h : vec2(1, 0);
}

// The radial direction e(φ) about an object's axes and its derivative e'(φ) (shapes.cpp's
// radial() and radial_derivative()), φ as (cos φ, sin φ).
vec3 radial(Object o, vec2 phi) {
    return phi.y * o.axis_u.xyz - phi.x * o.axis_v.xyz;
}
vec3 radial_derivative(Object o, vec2 phi) {
    return phi.x * o.axis_u.xyz + phi.y * o.axis_v.xyz;
}

// u = ½ + φ/(2π) for φ as (cos φ, sin φ) (shapes.cpp's azimuth_u).
float azimuth_u(vec2 phi) {
    if (phi.y == 0.0 && phi.x > 0.0) return 0.5;
    return 0.5 + atan(phi.y, phi.x) / TWO_PI;
}

// The nearest root of the sphere-like quadratic |f + τd|² = R² (|d| = 1) above tau_min, from the
// forms of Haines et al. (Ray Tracing Gems ch. 7); −1 for none.
vec2 sphere_roots(vec3 f, vec3 d, float radius) {
    float b = dot(f, d);
    float l = length(f - b * d);
    float disc = (radius - l) * (radius + l);
    if (!(disc >= 0.0)) return vec2(-1);
    float fl = length(f);
    float c = (fl - radius) * (fl + radius);
    float q = -b - (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc);
    vec2 tau = vec2(q, q != 0.0 ? c / q : 0.0);
    return tau.x <= tau.y ? tau : tau.yx;
}

bool hit_plane(Object o, Ray ray, float len, vec3 d, inout Hit hit) {
    vec3 n = o.axis.xyz;
    float cosine = dot(d, n);
    if (cosine == 0.0) return false;
    float t = dot(o.origin.xyz - ray.origin, n) / cosine / len;
    if (!(t > 0.0 && t < hit.t)) return false;
    vec3 p = ray.origin + t * ray.direction;
    vec3 q = p - o.origin.xyz;
    vec2 local = vec2(dot(q, o.axis_u.xyz), dot(q, o.axis_v.xyz));
    if (o.info.z == 0 && (abs(local.x) > 0.5 * o.params.x || abs(local.y) > 0.5 * o.params.y))
        return false;
    float scale = o.params.z;
    hit = Hit(t, p, n, o.axis_u.xyz / scale, o.axis_v.xyz / scale, vec3(0), vec3(0),
              scale * local + 0.5, hit.object);
    return true;
}

bool hit_sphere(Object o, Ray ray, float len, vec3 d, inout Hit hit) {
    float radius = o.params.x;
    vec2 tau = sphere_roots(ray.origin - o.origin.xyz, d, radius);
    for (int k = 0; k < 2; ++k) {
        float t = tau[k] / len;
        if (!(t > 0.0 && t < hit.t)) continue;
        vec3 p = ray.origin + t * ray.direction;
        vec3 q = p - o.origin.xyz;
        vec3 u = o.axis_u.xyz, v = o.axis_v.xyz, a = o.axis.xyz;
        float rho = length(vec2(dot(q, u), dot(q, v)));
        vec2 phi = cos_sin(-dot(q, v), dot(q, u));
        vec2 theta = cos_sin(dot(q, a), rho);
        vec3 e = radial(o, phi), de = radial_derivative(o, phi);
        vec3 n = theta.y * e + theta.x * a;
        vec3 dpdu = (TWO_PI * radius * theta.y) * de;
        vec3 dpdv = (-PI * radius) * (theta.x * e - theta.y * a);
        hit = Hit(t, p, n, dpdu, dpdv, dpdu / radius, dpdv / radius,
                  vec2(azimuth_u(phi), 1.0 - atan(theta.y, theta.x) / PI), hit.object);
        return true;
    }
    return false;
}

bool hit_cylinder(Object o, Ray ray, float len, vec3 d, inout Hit hit) {
    vec3 u = o.axis_u.xyz, v = o.axis_v.xyz, a = o.axis.xyz;
    float radius = o.params.x, height = o.params.y;
    vec3 f = ray.origin - o.origin.xyz;
    vec2 f2 = vec2(dot(f, u), dot(f, v)), d2 = vec2(dot(d, u), dot(d, v));
    float d_len = length(d2);
    if (!(d_len > 1e-30)) return false;  // parallel to the axis
    vec2 sigma = sphere_roots(vec3(f2, 0), vec3(d2 / d_len, 0), radius);
    for (int k = 0; k < 2; ++k) {
        float t = sigma[k] / d_len / len;
        if (!(t > 0.0 && t < hit.t)) continue;
        vec3 p = ray.origin + t * ray.direction;
        vec3 q = p - o.origin.xyz;
        float along = dot(q, a);
        if (!(abs(along) <= 0.5 * height)) continue;
        vec2 phi = cos_sin(-dot(q, v), dot(q, u));
        vec3 e = radial(o, phi), de = radial_derivative(o, phi);
        hit = Hit(t, p, e, (TWO_PI * radius) * de, height * a, TWO_PI * de, vec3(0),
                  vec2(azimuth_u(phi), along / height + 0.5), hit.object);
        return true;
    }
    return false;
}

bool hit_paraboloid(Object o, Ray ray, float len, vec3 dir, inout Hit hit) {
    vec3 u = o.axis_u.xyz, v = o.axis_v.xyz, a = o.axis.xyz;
    float fl = o.params.x, radius = o.params.y;
    // In the frame at the vertex: x² + y² − 4f z = A τ² + B τ + C = 0.
    vec3 q0 = ray.origin - o.origin.xyz;
    vec3 oo = vec3(dot(q0, u), dot(q0, v), dot(q0, a));
    vec3 d = vec3(dot(dir, u), dot(dir, v), dot(dir, a));
    float qa = d.x * d.x + d.y * d.y;
    float qb = 2.0 * (oo.x * d.x + oo.y * d.y) - 4.0 * fl * d.z;
    float qc = oo.x * oo.x + oo.y * oo.y - 4.0 * fl * oo.z;
    vec2 tau = vec2(-1);
    int count = 0;
    if (qa == 0.0) {
        if (qb == 0.0) return false;
        tau.x = -qc / qb;
        count = 1;
    } else {
        float disc = qb * qb - 4.0 * qa * qc;
        if (!(disc >= 0.0)) return false;
        float q = -0.5 * (qb + (qb >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
        if (q == 0.0) {
            tau.x = 0.0;
            count = 1;
        } else {
            tau = vec2(q / qa, qc / q);
            if (tau.x > tau.y) tau = tau.yx;
            count = 2;
        }
    }
    for (int k = 0; k < count; ++k) {
        // One Newton step on the direct form (the expanded quadratic cancels from far away).
        float s = tau[k];
        vec3 ps = oo + s * d;
        float g = ps.x * ps.x + ps.y * ps.y - 4.0 * fl * ps.z;
        float dg = 2.0 * (ps.x * d.x + ps.y * d.y) - 4.0 * fl * d.z;
        float polished = s - g / dg;
        vec3 pp = oo + polished * d;
        if (!isinf(polished) && !isnan(polished) &&
            abs(pp.x * pp.x + pp.y * pp.y - 4.0 * fl * pp.z) < abs(g))
            s = polished;
        float t = s / len;
        if (!(t > 0.0 && t < hit.t)) continue;
        vec3 p = ray.origin + t * ray.direction;
        vec3 qv = p - o.origin.xyz;
        float x = dot(qv, u), y = dot(qv, v);
        if (!(x * x + y * y <= radius * radius)) continue;
        float two_r = 2.0 * radius;
        float l = sqrt(x * x + y * y + 4.0 * fl * fl);
        vec3 n = ((2.0 * fl) * a - x * u - y * v) / l;
        vec3 dpdu = two_r * (u + (x / (2.0 * fl)) * a);
        vec3 dpdv = two_r * (v + (y / (2.0 * fl)) * a);
        vec3 dndu = two_r * (-u / l - (x / (l * l)) * n);
        vec3 dndv = two_r * (-v / l - (y / (l * l)) * n);
        hit = Hit(t, p, n, dpdu, dpdv, dndu, dndv, vec2(x / two_r + 0.5, y / two_r + 0.5),
                  hit.object);
        return true;
    }
    return false;
}

// The nearest hit over all objects; false where the ray escapes.
bool intersect_scene(Ray ray, out Hit hit) {
    hit.t = FLT_MAX;
    hit.object = -1;
    float len = length(ray.direction);
    vec3 d = ray.direction / len;
    for (int i = 0; i < u_object_count; ++i) {
        Object o = objects[i];
        bool found = false;
        switch (o.info.x) {
            case SHAPE_PLANE: found = hit_plane(o, ray, len, d, hit); break;
            case SHAPE_SPHERE: found = hit_sphere(o, ray, len, d, hit); break;
            case SHAPE_CYLINDER: found = hit_cylinder(o, ray, len, d, hit); break;
            case SHAPE_PARABOLOID: found = hit_paraboloid(o, ray, len, d, hit); break;
        }
        if (found) hit.object = i;
    }
    return hit.object >= 0;
}

// ---- Ray differentials (scene/ray_differentials.h): the pinhole camera has ∂o = 0 and
// ∂d/∂x = a r, ∂d/∂y = −a u.
struct Differentials {
    vec3 dpdx, dpdy, dndx, dndy;
    vec2 duvdx, duvdy;
    bool valid;
};

// Least-squares (a, b) with a·pu + b·pv ≈ w (the 2×2 normal equations).
vec2 solve_tangent(vec3 pu, vec3 pv, vec3 w) {
    float uu = dot(pu, pu), uv = dot(pu, pv), vv = dot(pv, pv);
    float ru = dot(pu, w), rv = dot(pv, w);
    float det = uu * vv - uv * uv;
    if (det > 1e-12 * uu * vv && det > 0.0)
        return vec2(vv * ru - uv * rv, uu * rv - uv * ru) / det;
    if (uu >= vv && uu > 0.0) return vec2(ru / uu, 0);
    if (vv > 0.0) return vec2(0, rv / vv);
    return vec2(0);
}

Differentials surface_differentials(Ray ray, vec3 dddx, vec3 dddy, Hit hit) {
    Differentials out_d;
    out_d.valid = false;
    vec3 ng = normalize(hit.n);
    float cosine = dot(ray.direction, ng);
    if (!(abs(cosine) / length(ray.direction) >= 1e-8)) return out_d;
    vec3 moved_x = hit.t * dddx, moved_y = hit.t * dddy;
    out_d.dpdx = moved_x - (dot(moved_x, ng) / cosine) * ray.direction;
    out_d.dpdy = moved_y - (dot(moved_y, ng) / cosine) * ray.direction;
    out_d.duvdx = solve_tangent(hit.dpdu, hit.dpdv, out_d.dpdx);
    out_d.duvdy = solve_tangent(hit.dpdu, hit.dpdv, out_d.dpdy);
    out_d.dndx = out_d.duvdx.x * hit.dndu + out_d.duvdx.y * hit.dndv;
    out_d.dndy = out_d.duvdy.x * hit.dndu + out_d.duvdy.y * hit.dndv;
    out_d.valid = !any(isnan(out_d.dpdx + out_d.dpdy + out_d.dndx + out_d.dndy)) &&
                  !any(isinf(out_d.dpdx + out_d.dpdy + out_d.dndx + out_d.dndy)) &&
                  !any(isnan(out_d.duvdx + out_d.duvdy)) && !any(isinf(out_d.duvdx + out_d.duvdy));
    return out_d;
}
