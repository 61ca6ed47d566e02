#version 450 core
// gpu/shaders/mesh.vert — the raster pass of triangle meshes: each vertex projected by the pinhole
// camera of render/camera.h (image row y down = framebuffer row y, as render.frag's pixels), so
// that the rasteriser finds the nearest triangle at exactly the pixel centres whose rays
// render.frag then intersects with it.
//
// Depth is reversed and without a far plane: z_ndc = near/z in [0, 1] (glClipControl's
// GL_ZERO_TO_ONE, GL_GREATER), whose float precision is relative to the distance everywhere.

layout(location = 0) in vec3 a_position;  // relative to the mesh anchor

uniform vec3 u_mesh_offset;  // the mesh anchor − the camera position
uniform vec3 u_camera_forward;
uniform vec3 u_camera_right;
uniform vec3 u_camera_up;
uniform float u_pixel_angle;  // a = tan(fov_y/2)/(H/2)
uniform ivec2 u_size;         // W, H

const float kNear = 1e-4;  // the nearest visible distance along the view axis

void main() {
    vec3 p = a_position + u_mesh_offset;
    float z = dot(p, u_camera_forward);
    // Pixel x = W/2 + (p·r)/(a z), y = H/2 − (p·u)/(a z): clip = (ndc · z, near, z).
    gl_Position = vec4(dot(p, u_camera_right) / (0.5 * u_pixel_angle * float(u_size.x)),
                       -dot(p, u_camera_up) / (0.5 * u_pixel_angle * float(u_size.y)), kNear, z);
}
