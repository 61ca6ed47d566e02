// render/test_scene_parts.h — test support: the parts the render tests build their scenes of.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "scene/scene.h"

namespace footprint::test {

// A lat-long environment of `image`; `name` labels it (and keys it in a texture system).
inline EnvironmentDesc latlong_environment(std::shared_ptr<const Image> image,
                                           std::string name = "test environment") {
    EnvironmentDesc env;
    env.layout = EnvLayout::latlong;
    env.images.push_back(ImageSource{{}, std::move(image), std::move(name)});
    return env;
}

// A mirror of Fresnel reflectance `f0` at normal incidence, with no diffuse part.
inline MaterialDesc mirror_material(float f0) {
    MaterialDesc m;
    m.diffuse = 0;
    m.mirror = 1;
    m.fresnel_f0 = f0;
    return m;
}

}  // namespace footprint::test
