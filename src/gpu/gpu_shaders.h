// gpu/gpu_shaders.h — (private to gpu) the GLSL sources of gpu/shaders/, embedded at build time
// (cmake/embed_shaders.cmake), in the order a program concatenates them.
#pragma once

#include <string_view>

namespace footprint::gpu::shaders {

extern const std::string_view kCommonGlsl;
extern const std::string_view kGeometryGlsl;
extern const std::string_view kFilteringGlsl;
extern const std::string_view kProceduralGlsl;
extern const std::string_view kBumpGlsl;
extern const std::string_view kEnvironmentGlsl;
extern const std::string_view kShadingGlsl;
extern const std::string_view kRenderFrag;
extern const std::string_view kFullscreenVert;
extern const std::string_view kMeshVert;
extern const std::string_view kVisibilityFrag;

}  // namespace footprint::gpu::shaders
