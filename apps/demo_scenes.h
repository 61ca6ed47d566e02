// apps/demo_scenes.h — the built-in demo scenes: the papers' figures, built in code.
//
//   cylinder          a mirror cylinder in an environment: curvature in one direction only, so
//                     the environment footprint is a long thin ellipse ([S97a] §2: K = D Dᵀ)
//   parabolic_mirror  a parabolic mirror seen from its focus: every reflected ray is parallel to
//                     the axis, the curvature cancels the aperture and the footprint must vanish
//                     ([S97a]'s compensation example, spec erratum 2)
//   water             a wavy water plane at a grazing angle reflecting a night sky with a moon
//                     ([S97a] Fig. 10/11: the bump roughness stretches the moon into a glitter
//                     path)
//   bump_plate        a flat bump-mapped plate reflecting a zebra-stripe environment ([S97a]
//                     Fig. 12/13: sub-pixel bumps must blur the stripes, not alias them)
//   secret_writing    the "secret writing" plane at a grazing angle ([S96] Fig. 1/2: trilinear
//                     blurs the writing away, footprint assembly keeps it legible)
//   brushed_sphere    a brushed-metal sphere: anisotropic roughness stretches the highlights
//                     and the reflections across the grooves
//   terrain           a fractal terrain (the lecture's "Fractal landscapes", scene/terrain.h)
//                     wearing its own topographic map, contour lines crowding towards the
//                     horizon, around a lake that mirrors the sky
//   procedural        solid procedural textures (the lectures' "Texturing, part 2",
//                     texture/procedural.h): a marble floor at a grazing angle, whose octaves
//                     fade to their mean as the footprint outgrows them, and two spheres
// Each scene also has a short camera_path (a dolly, truck or pan over a fraction of a unit) for
// temporal-stability measurements. Assets come from apps/demo_assets.h (generated in code) and
// from real files (an HDR environment, a normal map), looked up in the data folder and then in
// the repository's assets/ folder, which holds the few the demos use (assets/LICENSES); a scene
// falls back to a generated asset when a file is in neither, and says which in DemoScene::assets.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/result.h"
#include "scene/scene.h"

namespace footprint {

struct DemoSceneOptions {
    int width = 320, height = 180;
    // Where a scene's real files are looked for, in this order: data_dir, ../shared/data by
    // default (the full data set; the FOOTPRINT_DATA environment variable overrides it), then
    // assets_dir, the repository's assets/ (the demos' files only, so that a fresh clone shows
    // real data). A file in neither is replaced by a generated asset.
    std::filesystem::path data_dir = default_demo_data_dir();
    std::filesystem::path assets_dir = default_demo_assets_dir();

    static std::filesystem::path default_demo_data_dir();
    static std::filesystem::path default_demo_assets_dir();
};

struct DemoScene {
    std::string name;
    std::string title;   // one line: what the figure shows
    std::string assets;  // where the environment/maps came from ("generated", or file names)
    SceneDesc scene;
};

// The scene names above, in that order.
const std::vector<std::string>& demo_scene_names();

// One scene, or an Error naming an unknown scene (listing the valid names).
Result<DemoScene> make_demo_scene(const std::string& name, const DemoSceneOptions& options = {});

}  // namespace footprint
