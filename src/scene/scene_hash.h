// scene/scene_hash.h — a fingerprint of everything a scene's image depends on, for caches of
// expensive renders (footprint eval's references): a changed scene must never reuse a stale one.
//
// The hash (64-bit FNV-1a) covers every field of the SceneDesc (numbers by their exact bits,
// strings, enum values, the order of lights and objects, the camera path) and the content of
// everything it reads: the bytes of every image file, the pixels of every in-memory image, and for
// a mesh the bytes of the mesh file and of every other file in its folder (the .mtl, .bin and
// texture files it may name). The file names themselves are not hashed, only their content — a
// scene moved with its files keeps its hash. A file that cannot be read contributes its path and
// a marker instead (loading it will fail later, with a message).
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace footprint {

std::uint64_t scene_content_hash(const SceneDesc& scene);

// 16 lower-case hex digits.
std::string hash_hex(std::uint64_t hash);

}  // namespace footprint
