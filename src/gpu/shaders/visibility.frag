#version 450 core
// gpu/shaders/visibility.frag — the raster pass of triangle meshes writes 1 + the triangle's index
// (0 is the clear value: no triangle); render.frag intersects the pixel's ray with it.
layout(location = 0) out uint out_triangle;

void main() {
    out_triangle = uint(gl_PrimitiveID) + 1u;
}
