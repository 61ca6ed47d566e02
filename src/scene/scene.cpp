#include "scene/scene.h"

#include <algorithm>

namespace footprint {

namespace {

Vec3d lerp(Vec3d a, Vec3d b, double w) {
    return a + w * (b - a);
}

}  // namespace

CameraDesc camera_at(const SceneDesc& scene, double time) {
    const std::vector<CameraKeyframe>& path = scene.camera_path;
    if (path.empty()) return scene.camera;
    if (path.size() == 1 || time <= path.front().time) return path.front().camera;
    if (time >= path.back().time) return path.back().camera;
    // The first keyframe after `time` and the one before it.
    const auto next =
        std::upper_bound(path.begin(), path.end(), time,
                         [](double t, const CameraKeyframe& k) { return t < k.time; });
    const CameraKeyframe& b = *next;
    const CameraKeyframe& a = *(next - 1);
    const double span = b.time - a.time;
    const double w = span > 0 ? (time - a.time) / span : 1.0;
    CameraDesc camera;
    camera.position = lerp(a.camera.position, b.camera.position, w);
    camera.look_at = lerp(a.camera.look_at, b.camera.look_at, w);
    camera.up = lerp(a.camera.up, b.camera.up, w);
    camera.fov_y_deg = a.camera.fov_y_deg + w * (b.camera.fov_y_deg - a.camera.fov_y_deg);
    return camera;
}

CameraDesc camera_for_frame(const SceneDesc& scene, int frame, int frame_count) {
    if (scene.camera_path.empty()) return scene.camera;
    const double t0 = scene.camera_path.front().time, t1 = scene.camera_path.back().time;
    const double w = frame_count > 1 ? static_cast<double>(frame) / (frame_count - 1) : 0.0;
    return camera_at(scene, t0 + w * (t1 - t0));
}

}  // namespace footprint
