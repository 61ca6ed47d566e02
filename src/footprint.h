// footprint/footprint.h — every public header of footprint, for users of the installed package
// (find_package(footprint CONFIG), target footprint::footprint). One module's header alone is
// <footprint/MODULE/NAME.h>, e.g. <footprint/texture/texture_lookup.h>; docs/library.md lists them.
#pragma once

#include <footprint/version.h>

#include <footprint/core/result.h>
#include <footprint/math/footprint_ellipse.h>
#include <footprint/math/mat3.h>
#include <footprint/math/vec.h>
#include <footprint/math/vec3.h>

#include <footprint/image/color.h>
#include <footprint/image/image.h>
#include <footprint/image/image_io.h>

#include <footprint/texture/ewa.h>
#include <footprint/texture/footprint_assembly.h>
#include <footprint/texture/mip_pyramid.h>
#include <footprint/texture/parallax.h>
#include <footprint/texture/procedural.h>
#include <footprint/texture/reference_filter.h>
#include <footprint/texture/summed_area_table.h>
#include <footprint/texture/texture_lookup.h>
#include <footprint/texture/wrap.h>

#include <footprint/bump/bump_pyramid.h>
#include <footprint/bump/bump_pyramid_file.h>
#include <footprint/bump/local_frame.h>
#include <footprint/bump/roughness.h>
#include <footprint/bump/slope_map.h>
#include <footprint/shading/blinn_phong.h>
#include <footprint/shading/microfacet.h>

#include <footprint/envmap/env_convert.h>
#include <footprint/envmap/env_footprint.h>
#include <footprint/envmap/env_image_io.h>
#include <footprint/envmap/env_layout.h>
#include <footprint/envmap/env_proxy.h>
#include <footprint/envmap/env_pyramid_file.h>
#include <footprint/envmap/env_reference.h>
#include <footprint/envmap/environment_map.h>
#include <footprint/envmap/irradiance.h>
#include <footprint/texture_system.h>

#include <footprint/scene/mesh.h>
#include <footprint/scene/ray_differentials.h>
#include <footprint/scene/scene.h>
#include <footprint/scene/scene_file.h>
#include <footprint/scene/shapes.h>
#include <footprint/scene/surface.h>

#include <footprint/render/camera.h>
#include <footprint/render/render_scene.h>
#include <footprint/render/renderer.h>

#include <footprint/metrics/flip.h>
#include <footprint/metrics/image_metrics.h>

#include <footprint/gpu/gpu_renderer.h>
