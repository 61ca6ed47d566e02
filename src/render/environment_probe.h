// render/environment_probe.h — (internal) the lectures' dynamic environment maps: a cube map of the
// scene rendered from a material's probe centre, with the object that wears it left out, so that
// the other objects appear in its mirror.
#pragma once

#include "core/result.h"
#include "envmap/environment_map.h"
#include "render/render_scene.h"

namespace footprint {

// The six faces (+X −X +Y −Y +Z −Z; s to the right, t down, as cube_direction()), probe.size²
// texels each: every texel the fa-rough colour of the ray from probe.center through its centre,
// with the face's ray differentials (one texel per pixel step), `object` passed through. The
// scene's probes are not used (one bounce); lights and shadows are.
Result<EnvironmentMap> render_environment_probe(const RenderScene& scene,
                                                const EnvironmentProbeDesc& probe, int object);

}  // namespace footprint
