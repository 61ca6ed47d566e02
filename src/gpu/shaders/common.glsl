#version 450 core
#include "footprint/common.glsl"
// gpu/shaders/common.glsl — what every stage of the GPU path shares: constants, the filter modes,
// the scene's buffers and the frame's uniforms. The later files are appended in pipeline order
// (geometry, filtering, bump, environment, shading, render.frag), as the C++ pipeline's modules.
// The method itself is footprint's GLSL library (glsl/footprint/, docs/engine.md), which these
// files include: cmake/embed_shaders.cmake inlines each of its files once, where it is first
// included.

const float PI = FP_PI;
const float TWO_PI = 6.28318530717958647692;
const float FLT_MAX = 3.402823466e+38;

// The filter modes (gpu/gpu_renderer.h's GpuFilter, in its order).
const int MODE_POINT = 0;      // level-0 bilinear everywhere: the CPU's `bilinear`
const int MODE_TRILINEAR = 1;  // isotropic MIP, the CPU's `trilinear`
const int MODE_FA = 2;         // footprint assembly, mean slopes only
const int MODE_FA_ROUGH = 3;   // footprint assembly + the roughness pyramid
const int MODE_HW_ANISO = 4;   // the GPU's anisotropic filtering (textureGrad), no roughness

// Shape types (the order of scene.h's ShapeDesc).
const int SHAPE_PLANE = 0;
const int SHAPE_SPHERE = 1;
const int SHAPE_CYLINDER = 2;
const int SHAPE_PARABOLOID = 3;
const int SHAPE_TORUS = 4;

// An analytic object, in camera-relative world coordinates (the camera at the origin, so that
// float keeps the hit points' differences; the CPU renderer works in double).
struct Object {
    vec4 origin;  // plane, sphere, cylinder and torus centre, paraboloid vertex
    vec4 axis_u;  // scene/shapes.h's ShapeAxes (u, v, axis)
    vec4 axis_v;
    vec4 axis;
    vec4 params;  // plane: size x, size y, uv_scale; sphere: radius; cylinder: radius, height;
                  // paraboloid: focal length, aperture radius; torus: major, minor radius
    ivec4 info;   // shape type, material, infinite plane, unused
};

struct Material {
    vec4 base_color;  // rgb; w = 1: the bump frame is the mesh's tangents where it has them
    vec4 weights;     // diffuse, specular, shininess, mirror
    vec4 bump;        // unused, unused, frame (0 natural, 1 normalized, 2 main direction),
                      // micro-roughness σ
    vec4 main_direction;  // xyz; zero: ∂p/∂v; w: the bump map's mean slope b1
    vec4 roughness;       // micro-roughness K_0 = (xx, xy, yy) in xyz; w: mean slope b2
    ivec4 maps;  // the base colour map's u_maps index (−1: none) and layer, the bump map's
    vec4 highlight;  // FP_HIGHLIGHT_* (footprint/highlight.glsl), microfacet α, 1: metallic-roughness, unused
    vec4 f0;         // Schlick's F0 per channel (× the F0 map); w: the environment's diffuse weight
    ivec4 f0_map;    // the F0 map's u_maps index (−1: none; its alpha: the slope variance σ²)
                     // and layer, unused, unused
    vec4 procedural;               // PROCEDURAL_* (0: none), scale, octaves, unused
    vec4 procedural_colors[2];     // the pattern's two colours
    vec4 procedural_bump;          // a procedural bump: PROCEDURAL_* (0: none), scale, octaves,
                                   // strength
    vec4 parallax;                 // depth (0: none), steps, max_shift, unused
    ivec4 height_map;              // the parallax height map's u_maps index and layer, unused
    ivec4 probe;                   // the environment probe's cube slot (−1: none), unused
};

struct Light {
    vec4 direction;  // directional: the direction light travels; w = 0 directional, 1 point
    vec4 position;   // point light, camera-relative
    vec4 color;      // w = 1 where it casts shadows
};

layout(std430, binding = 0) readonly buffer Objects { Object objects[]; };
layout(std430, binding = 1) readonly buffer Materials { Material materials[]; };
layout(std430, binding = 2) readonly buffer Lights { Light lights[]; };

// The camera (render/camera.h): d(x, y) = f + a(x − W/2) r − a(y − H/2) u, at the origin.
uniform vec3 u_camera_forward;
uniform vec3 u_camera_right;
uniform vec3 u_camera_up;
uniform float u_pixel_angle;  // a = tan(fov_y/2)/(H/2)
uniform ivec2 u_size;         // W, H

uniform int u_mode;
uniform int u_object_count;
uniform int u_light_count;
uniform int u_max_probes;  // N_max of footprint assembly
uniform float u_kappa;     // κ of the environment footprint
uniform vec3 u_background;
uniform vec3 u_camera_position;  // world: a hit's p is relative to it
