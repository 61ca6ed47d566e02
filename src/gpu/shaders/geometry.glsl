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
    vec3 ng;       // the geometric normal: n on analytic shapes, the triangle's on a mesh
    vec4 tangent;  // a mesh's interpolated tangent and the bitangent's sign in w (0: none)
    int material;  // index into materials[]
};

// An analytic shape's hit (its normal is the geometric normal), its material set by the caller.
Hit surface_hit(float t, vec3 p, vec3 n, vec3 dpdu, vec3 dpdv, vec3 dndu, vec3 dndv, vec2 uv) {
    return Hit(t, p, n, dpdu, dpdv, dndu, dndv, uv, n, vec4(0), -1);
}

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
    hit = surface_hit(t, p, n, o.axis_u.xyz / scale, o.axis_v.xyz / scale, vec3(0), vec3(0),
              scale * local + 0.5);
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
        hit = surface_hit(t, p, n, dpdu, dpdv, dpdu / radius, dpdv / radius,
                  vec2(azimuth_u(phi), 1.0 - atan(theta.y, theta.x) / PI));
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
        hit = surface_hit(t, p, e, (TWO_PI * radius) * de, height * a, TWO_PI * de, vec3(0),
                  vec2(azimuth_u(phi), along / height + 0.5));
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
        hit = surface_hit(t, p, n, dpdu, dpdv, dndu, dndv, vec2(x / two_r + 0.5, y / two_r + 0.5));
        return true;
    }
    return false;
}

// ---- Real roots of small polynomials Σ c[i] sⁱ (shapes.cpp's real_roots, with the recursion
// over the derivatives unrolled: the roots of p‴ bracket those of p″, which bracket those of p′,
// which bracket those of p; between neighbouring brackets p is monotonic).
float poly_eval(float c[5], int n, float x) {
    float r = c[n];
    for (int i = n - 1; i >= 0; --i) r = r * x + c[i];
    return r;
}

float[5] derivative(float c[5], int n) {
    float d[5] = float[5](0.0, 0.0, 0.0, 0.0, 0.0);
    for (int i = 0; i < n; ++i) d[i] = float(i + 1) * c[i + 1];
    return d;
}

// The root in (a, b) of p, p(a) = fa and p(b) of the opposite sign: Newton steps, bisection
// whenever they leave the bracket.
float bracketed_root(float c[5], int n, float a, float b, float fa) {
    float dc[5] = derivative(c, n);
    float x = 0.5 * (a + b);
    for (int it = 0; it < 100; ++it) {
        float f = poly_eval(c, n, x);
        if (f == 0.0) return x;
        if ((f < 0.0) == (fa < 0.0)) {
            a = x;
            fa = f;
        } else {
            b = x;
        }
        float next = x - f / poly_eval(dc, n - 1, x);
        if (!(next > a && next < b)) next = 0.5 * (a + b);  // also NaN
        if (next == x || b - a <= 2.4e-7 * max(1.0, max(abs(a), abs(b)))) return next;
        x = next;
    }
    return x;
}

// The roots of p (degree n) in [lo, hi], ascending, from the ascending roots `critical` of p′
// there; returns their number.
int roots_between(float c[5], int n, float lo, float hi, float critical[4], int k,
                  out float roots[4]) {
    float points[6];
    points[0] = lo;
    for (int i = 0; i < k; ++i) points[i + 1] = critical[i];
    points[k + 1] = hi;
    int count = 0;
    float fa = poly_eval(c, n, lo);
    if (fa == 0.0) roots[count++] = lo;
    for (int j = 0; j <= k && count < n; ++j) {
        float a = points[j], b = points[j + 1];
        float fb = poly_eval(c, n, b);
        if (fb == 0.0) {
            if (count == 0 || roots[count - 1] != b) roots[count++] = b;
        } else if (fa != 0.0 && (fa < 0.0) != (fb < 0.0)) {
            roots[count++] = bracketed_root(c, n, a, b, fa);
        }
        fa = fb;
    }
    return count;
}

// The real roots of the quartic c (c[4] ≠ 0) in [lo, hi], ascending; returns their number.
int quartic_roots(float c[5], float lo, float hi, out float roots[4]) {
    float c3[5] = derivative(c, 4), c2[5] = derivative(c3, 3), c1[5] = derivative(c2, 2);
    float r1[4], r2[4], r3[4];
    float linear = -c1[0] / c1[1];
    int k = 0;
    if (linear >= lo && linear <= hi) r1[k++] = linear;
    k = roots_between(c2, 2, lo, hi, r1, k, r2);
    k = roots_between(c3, 3, lo, hi, r2, k, r3);
    return roots_between(c, 4, lo, hi, r3, k, roots);
}

bool hit_torus(Object o, Ray ray, float len, vec3 dir, inout Hit hit) {
    vec3 u = o.axis_u.xyz, v = o.axis_v.xyz, a = o.axis.xyz;
    float big_r = o.params.x, small_r = o.params.y;
    // shapes.cpp's form: the torus frame, lengths in units of B = R + r, the origin moved to the
    // ray's point nearest the centre (τ0), so that the quartic's coefficients are O(1):
    //   s⁴ + 4m s³ + (4m² + 2k − 4R² d⊥²) s² + (4mk − 8R² o⊥·d⊥) s + k² − 4R² o⊥² = 0.
    float bound = big_r + small_r;
    vec3 q0 = ray.origin - o.origin.xyz;
    vec3 o0 = vec3(dot(q0, u), dot(q0, v), dot(q0, a));
    vec3 d = vec3(dot(dir, u), dot(dir, v), dot(dir, a));
    float tau0 = -dot(o0, d);
    vec3 oc = (o0 + tau0 * d) / bound;
    float oo = dot(oc, oc);
    if (!(oo <= 1.0 + 1e-6)) return false;  // misses the bounding sphere
    float half_chord = sqrt(max(0.0, 1.0 - oo)) * (1.0 + 1e-6) + 1e-6;
    float s_lo = max(-half_chord, -tau0 / bound);
    float s_hi = min(half_chord, (min(hit.t, 1e30) * len - tau0) / bound);
    if (!(s_lo <= s_hi)) return false;
    float big = big_r / bound, small = small_r / bound, big2 = big * big;
    float m = dot(oc, d), k = oo + (big - small) * (big + small);
    float d_perp2 = d.x * d.x + d.y * d.y, od_perp = oc.x * d.x + oc.y * d.y,
          o_perp2 = oc.x * oc.x + oc.y * oc.y;
    float c[5] = float[5](k * k - 4.0 * big2 * o_perp2, 4.0 * m * k - 8.0 * big2 * od_perp,
                          4.0 * m * m + 2.0 * k - 4.0 * big2 * d_perp2, 4.0 * m, 1.0);
    float roots[4];
    int count = quartic_roots(c, s_lo, s_hi, roots);
    for (int i = 0; i < count; ++i) {
        float t = (tau0 + bound * roots[i]) / len;
        if (!(t > 0.0 && t < hit.t)) continue;
        vec3 p = ray.origin + t * ray.direction;
        vec3 q = p - o.origin.xyz;
        vec2 phi = cos_sin(-dot(q, v), dot(q, u));
        float rho = length(vec2(dot(q, u), dot(q, v)));
        vec2 theta = cos_sin(rho - big_r, dot(q, a));
        float tv = atan(theta.y, theta.x) / TWO_PI;
        if (tv < 0.0) tv += 1.0;
        vec3 e = radial(o, phi), de = radial_derivative(o, phi);
        vec3 n = theta.x * e + theta.y * a;
        vec3 dn_dtheta = -theta.y * e + theta.x * a;
        hit = surface_hit(t, p, n, (TWO_PI * (big_r + small_r * theta.x)) * de,
                          (TWO_PI * small_r) * dn_dtheta, (TWO_PI * theta.x) * de,
                          TWO_PI * dn_dtheta, vec2(azimuth_u(phi), tv));
        return true;
    }
    return false;
}

// ---- Triangle meshes: the raster pass (mesh.vert, visibility.frag) finds each pixel's nearest
// triangle; the ray is intersected with that triangle here, for the exact hit and differentials
// (scene/mesh_accel.h's mesh_surface_hit).
struct MeshVertex {
    vec4 position;  // relative to the mesh anchor: + u_mesh_offset = camera-relative
    vec4 normal;    // zero where the part has none
    vec4 uv;        // (u, v), v up
    vec4 tangent;   // xyz, and the bitangent's sign in w
};
struct MeshPart {
    ivec4 info;  // material, has normals, has uvs, has tangents
};
layout(std430, binding = 4) readonly buffer MeshVertices { MeshVertex mesh_vertices[]; };
layout(std430, binding = 5) readonly buffer MeshTriangles { uvec4 mesh_triangles[]; };
layout(std430, binding = 6) readonly buffer MeshParts { MeshPart mesh_parts[]; };
uniform vec3 u_mesh_offset;  // the mesh anchor − the camera position
uniform usampler2D u_visibility;  // per pixel: 1 + the nearest triangle, 0 for none
uniform int u_mesh_triangles;     // how many there are (0: no meshes, u_visibility unbound)

// ∂b/∂(u, v) of a triangle with UV edges e1, e2: (∂b1/∂u, ∂b2/∂u, ∂b1/∂v, ∂b2/∂v); the identity
// (derivatives with respect to (b1, b2)) where the UV map is singular.
vec4 barycentric_derivatives(vec2 e1, vec2 e2) {
    float det = e1.x * e2.y - e1.y * e2.x;
    if (!(abs(det) > 1e-12 * (dot(e1, e1) + dot(e2, e2))) || !fp_is_finite(det))
        return vec4(1, 0, 0, 1);
    return vec4(e2.y, -e1.y, -e2.x, e1.x) / det;
}

// The differential geometry at barycentrics b of triangle `triangle` (mesh_surface_hit).
Hit mesh_hit(int triangle, float t, vec2 b, Ray ray) {
    uvec4 tri = mesh_triangles[triangle];
    MeshVertex v0 = mesh_vertices[tri.x], v1 = mesh_vertices[tri.y], v2 = mesh_vertices[tri.z];
    ivec4 part = mesh_parts[tri.w].info;
    float b0 = 1.0 - b.x - b.y;
    vec3 p0 = v0.position.xyz + u_mesh_offset, p1 = v1.position.xyz + u_mesh_offset,
         p2 = v2.position.xyz + u_mesh_offset;
    vec3 dp1 = p1 - p0, dp2 = p2 - p0;
    Hit hit;
    hit.t = t;
    hit.p = b0 * p0 + b.x * p1 + b.y * p2;
    hit.material = part.x;
    vec4 db = vec4(1, 0, 0, 1);
    hit.uv = b;
    if (part.z != 0) {
        hit.uv = b0 * v0.uv.xy + b.x * v1.uv.xy + b.y * v2.uv.xy;
        db = barycentric_derivatives(v1.uv.xy - v0.uv.xy, v2.uv.xy - v0.uv.xy);
    }
    hit.dpdu = db.x * dp1 + db.y * dp2;
    hit.dpdv = db.z * dp1 + db.w * dp2;
    vec3 ng = cross(dp1, dp2);
    ng = dot(ng, ng) > 0.0 ? normalize(ng) : vec3(0);
    bool shading = false;
    hit.dndu = hit.dndv = vec3(0);
    if (part.y != 0) {
        vec3 nn = b0 * v0.normal.xyz + b.x * v1.normal.xyz + b.y * v2.normal.xyz;
        float len = length(nn);
        if (len > 0.0 && fp_is_finite(len)) {
            shading = true;
            hit.n = nn / len;
            vec3 dn1 = v1.normal.xyz - v0.normal.xyz, dn2 = v2.normal.xyz - v0.normal.xyz;
            vec3 dndu = db.x * dn1 + db.y * dn2, dndv = db.z * dn1 + db.w * dn2;
            hit.dndu = (dndu - dot(hit.n, dndu) * hit.n) / len;
            hit.dndv = (dndv - dot(hit.n, dndv) * hit.n) / len;
        }
    }
    if (ng == vec3(0)) ng = shading ? hit.n : -normalize(ray.direction);  // degenerate
    if (!shading) hit.n = ng;
    else if (dot(ng, hit.n) < 0.0) ng = -ng;
    hit.ng = ng;
    hit.tangent = vec4(0);
    if (part.w != 0) {
        vec3 tt = b0 * v0.tangent.xyz + b.x * v1.tangent.xyz + b.y * v2.tangent.xyz;
        if (dot(tt, tt) > 0.0) hit.tangent = vec4(normalize(tt), v0.tangent.w < 0.0 ? -1.0 : 1.0);
    }
    return hit;
}

// The ray against the triangle the raster pass found at this pixel (Möller–Trumbore, its
// barycentrics kept inside the triangle, which the rasteriser says the pixel centre is in).
bool hit_triangle(int triangle, Ray ray, inout Hit hit) {
    uvec4 tri = mesh_triangles[triangle];
    vec3 p0 = mesh_vertices[tri.x].position.xyz + u_mesh_offset;
    vec3 e1 = mesh_vertices[tri.y].position.xyz + u_mesh_offset - p0;
    vec3 e2 = mesh_vertices[tri.z].position.xyz + u_mesh_offset - p0;
    vec3 pv = cross(ray.direction, e2);
    float det = dot(e1, pv);
    if (det == 0.0) return false;
    vec3 tv = ray.origin - p0, qv = cross(tv, e1);
    float t = dot(e2, qv) / det;
    if (!(t > 0.0 && t < hit.t)) return false;
    float b1 = clamp(dot(tv, pv) / det, 0.0, 1.0);
    float b2 = clamp(dot(ray.direction, qv) / det, 0.0, 1.0 - b1);
    hit = mesh_hit(triangle, t, vec2(b1, b2), ray);
    return true;
}

// Analytic object o against the ray, nearer than hit.t (d = the direction / len, len its length).
bool hit_object(Object o, Ray ray, float len, vec3 d, inout Hit hit) {
    switch (o.info.x) {
        case SHAPE_PLANE: return hit_plane(o, ray, len, d, hit);
        case SHAPE_SPHERE: return hit_sphere(o, ray, len, d, hit);
        case SHAPE_CYLINDER: return hit_cylinder(o, ray, len, d, hit);
        case SHAPE_PARABOLOID: return hit_paraboloid(o, ray, len, d, hit);
        case SHAPE_TORUS: return hit_torus(o, ray, len, d, hit);
    }
    return false;
}

// The nearest hit over all objects at pixel `pixel`; false where the ray escapes.
bool intersect_scene(Ray ray, ivec2 pixel, out Hit hit) {
    hit.t = FLT_MAX;
    hit.material = -1;
    if (u_mesh_triangles > 0) {
        uint id = texelFetch(u_visibility, pixel, 0).r;
        if (id > 0u && id <= uint(u_mesh_triangles)) hit_triangle(int(id - 1u), ray, hit);
    }
    float len = length(ray.direction);
    vec3 d = ray.direction / len;
    for (int i = 0; i < u_object_count; ++i)
        if (hit_object(objects[i], ray, len, d, hit)) hit.material = objects[i].info.y;
    return hit.material >= 0;
}

// ---- Shadow rays (RenderScene::occluded()): the analytic shapes, then the meshes through a BVH
// built on the CPU by Embree's builder (scene/triangle_bvh.h's layout), any hit ending the search.
struct BvhNode {
    vec3 lo;
    int next;  // inner: the second child (the first is the next node); leaf: its first entry
    vec3 hi;
    int count;  // 0: inner; a leaf's triangle count
};
layout(std430, binding = 7) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, binding = 8) readonly buffer BvhTriangles { uint bvh_triangles[]; };
const int BVH_MAX_DEPTH = 48;  // kTriangleBvhMaxDepth

bool box_hit(BvhNode n, vec3 o, vec3 inv, float t_max) {
    vec3 a = (n.lo - o) * inv, b = (n.hi - o) * inv;
    vec3 near = min(a, b), far = max(a, b);
    return max(max(near.x, near.y), max(near.z, 0.0)) <= min(min(far.x, far.y), min(far.z, t_max));
}

// Möller–Trumbore with t in (0, t_max), in the anchor's frame of the vertices.
bool triangle_blocks(uint triangle, vec3 o, vec3 d, float t_max) {
    uvec4 tri = mesh_triangles[triangle];
    vec3 p0 = mesh_vertices[tri.x].position.xyz;
    vec3 e1 = mesh_vertices[tri.y].position.xyz - p0, e2 = mesh_vertices[tri.z].position.xyz - p0;
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    if (det == 0.0) return false;
    vec3 tv = o - p0, qv = cross(tv, e1);
    float u = dot(tv, pv) / det, v = dot(d, qv) / det, t = dot(e2, qv) / det;
    return u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < t_max;
}

bool mesh_occluded(Ray ray, float t_max) {
    if (u_mesh_triangles == 0) return false;
    vec3 o = ray.origin - u_mesh_offset, d = ray.direction;
    vec3 inv = 1.0 / mix(d, vec3(1e-30), equal(d, vec3(0)));  // no division by zero
    int stack[BVH_MAX_DEPTH];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        int index = stack[--top];
        BvhNode n = bvh_nodes[index];
        if (!box_hit(n, o, inv, t_max)) continue;
        if (n.count > 0) {
            for (int k = 0; k < n.count; ++k)
                if (triangle_blocks(bvh_triangles[n.next + k], o, d, t_max)) return true;
        } else if (top + 2 <= BVH_MAX_DEPTH) {
            stack[top++] = n.next;
            stack[top++] = index + 1;
        }
    }
    return false;
}

// Whether any object is hit with t in (0, t_max) (units of |direction|).
bool scene_occluded(Ray ray, float t_max) {
    float len = length(ray.direction);
    vec3 d = ray.direction / len;
    Hit probe;
    probe.t = t_max;
    for (int i = 0; i < u_object_count; ++i)
        if (hit_object(objects[i], ray, len, d, probe)) return true;
    return mesh_occluded(ray, t_max);
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
    vec3 ng = normalize(hit.ng);
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
