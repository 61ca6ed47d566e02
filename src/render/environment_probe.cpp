// render/environment_probe.cpp — a probe's six faces, rendered by the CPU renderer's shader.
#include "render/environment_probe.h"

#include <cmath>

#include "core/parallel.h"
#include "envmap/env_layout.h"
#include "render/sample_shader.h"

namespace footprint {

Result<EnvironmentMap> render_environment_probe(const RenderScene& scene,
                                                const EnvironmentProbeDesc& probe, int object) {
    const int n = probe.size;
    RenderOptions options;  // fa-rough, one sample per texel
    std::array<Image, 6> faces;
    for (Image& face : faces) face = Image(n, n, 3);
    parallel_for(0, 6 * n, 1, [&](int first_row, int end_row) {  // the six faces' rows
        detail::SampleShader shader(scene, options, object);
        for (int row = first_row; row != end_row; ++row)
            for (int face = row / n, j = row % n, i = 0; i < n; ++i) {
                const double s = (i + 0.5) / n, t = (j + 0.5) / n;
                const Vec3d d = cube_direction(face, s, t);
                // cube_direction is linear in (s, t) on a face: exact differentials.
                const RayDifferential ray{{probe.center, d},
                                          {},
                                          cube_direction(face, s + 1.0 / n, t) - d,
                                          {},
                                          cube_direction(face, s, t + 1.0 / n) - d};
                const detail::Rgb c = shader.shade(ray, {0.5, 0.5});
                const bool finite =
                    std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]);
                for (int k = 0; k < 3; ++k) faces[face].at(i, j)[k] = finite ? c[k] : 0.0f;
            }
    });
    return EnvironmentMap::from_cube_faces(faces);
}

}  // namespace footprint
