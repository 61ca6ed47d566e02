// apps/render_progress.h — render() (render/renderer.h) with a progress bar on stderr, as every
// command that renders shows it: one bar per image, advanced per finished tile, drawn only when
// `show` (a terminal and not --quiet). A texture the scene's texture system could not read while
// rendering (RenderScene::take_texture_errors()) makes it an Error naming the file.
#pragma once

#include <string>

#include "render/renderer.h"

namespace footprint {

Result<Image> render_with_progress(const RenderScene& scene, const RenderOptions& options,
                                   const std::string& label, bool show,
                                   RenderStats* stats = nullptr);

}  // namespace footprint
