// gpu/shaders/render.frag — one pixel: its camera ray, the nearest hit, and its shading.
// Framebuffer row j is image row j (y down, as the camera's pixel coordinates), so that reading
// the framebuffer back gives the image top row first; the viewer flips it onto the screen.

layout(location = 0) out vec4 out_color;

void main() {
    use_scene_environment();
    vec2 pixel = gl_FragCoord.xy;  // the pixel's centre (i + ½, j + ½)
    Ray ray = camera_ray(pixel);
    vec3 dddx = u_pixel_angle * u_camera_right, dddy = -u_pixel_angle * u_camera_up;
    Hit hit;
    vec3 color = intersect_scene(ray, ivec2(pixel), hit) ? shade_hit(ray, dddx, dddy, hit)
                                           : background(ray, dddx, dddy);
    // Non-finite samples never reach a pixel (render/renderer.h): written as 0.
    if (!fp_is_finite(color.r + color.g + color.b)) color = vec3(0);
    out_color = vec4(color, 1.0);
}
