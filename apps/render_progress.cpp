#include "render_progress.h"

#include "progress.h"

namespace footprint {

Result<Image> render_with_progress(const RenderScene& scene, const RenderOptions& options,
                                   const std::string& label, bool show, RenderStats* stats) {
    Progress bar(
        label,
        static_cast<std::uint64_t>(render_tile_count(scene.desc().width, scene.desc().height)),
        show);
    Image image = render(scene, options, stats, [&] { bar.advance(); });
    bar.finish();
    if (Status s = scene.take_texture_errors(); !s) return s.error();
    return image;
}

}  // namespace footprint
