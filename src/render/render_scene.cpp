#include "render/render_scene.h"

#include <algorithm>
#include <string>

#include "bump/slope_map.h"
#include "envmap/env_image_io.h"
#include "image/image_io.h"
#include "scene/mesh.h"
#include "scene/mesh_accel.h"
#include "scene/shapes.h"

namespace footprint {

RenderScene::RenderScene() = default;
RenderScene::~RenderScene() = default;
RenderScene::RenderScene(RenderScene&&) noexcept = default;
RenderScene& RenderScene::operator=(RenderScene&&) noexcept = default;

namespace {

std::string object_key(int i) {
    return "objects[" + std::to_string(i) + "]";
}

// Prefixes an error with the scene file (if any) and the key it came from.
Error scene_error(const SceneDesc& desc, const std::string& key, const Error& error) {
    const std::string file = desc.source.empty() ? "" : desc.source.string() + ": ";
    return Error{file + key + (error.message.empty() ? "" : ": " + error.message)};
}

// The hint added where a NaN or infinite texel was refused: the scene key that repairs them.
std::string repair_hint(const char* where) {
    return std::string(" (the ") + where + " key \"non_finite\": \"repair\" replaces them)";
}

Result<Image> load_source(const ImageSource& source, ColorEncoding encoding,
                          NonFinitePolicy non_finite = NonFinitePolicy::refuse) {
    if (source.image) return *source.image;
    ImageLoadOptions options;
    options.encoding = encoding;
    options.non_finite = non_finite;
    Result<Image> image = load_image(source.file, options);
    if (image || non_finite != NonFinitePolicy::refuse) return image;
    // Point at the material key only where repairing would have helped.
    options.non_finite = NonFinitePolicy::repair;
    if (!load_image(source.file, options)) return image;
    return Error{image.error().message + repair_hint("material")};
}

// RGB of any 1–4 channel image (grey replicated, alpha dropped).
Image to_rgb(const Image& image) {
    if (image.channels == 3) return image;
    Image rgb(image.width, image.height, 3);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const float* p = image.pixels.data() + i * image.channels;
        for (int c = 0; c < 3; ++c) rgb.pixels[i * 3 + c] = image.channels >= 3 ? p[c] : p[0];
    }
    return rgb;
}

Result<std::shared_ptr<const MipPyramid>> color_pyramid(const Image& image) {
    if (image.empty()) return Error{"the image is empty"};
    return std::make_shared<const MipPyramid>(MipPyramid::build(to_rgb(image)));
}

// The slope map b of a bump description (see render_scene.h); `invalid` is the material's
// policy for invalid normal map texels.
Result<Image> bump_slopes(const BumpDesc& bump, const Image& map, InvalidNormalPolicy invalid) {
    if (bump.source == BumpDesc::Source::height_map) {
        HeightMapOptions options;
        options.height_scale = bump.strength;
        options.texel_size_u = 1.0f / static_cast<float>(map.width);
        options.texel_size_v = 1.0f / static_cast<float>(map.height);
        return slopes_from_height_map(map, options);
    }
    NormalMapOptions options;
    options.strength = bump.strength;
    options.invalid_normal_policy = invalid;
    Result<Image> slopes = slopes_from_normal_map(map, options);
    if (slopes || invalid == InvalidNormalPolicy::clamp) return slopes;
    // Point at the scene key only where clamping would have helped (not for a bad channel count).
    options.invalid_normal_policy = InvalidNormalPolicy::clamp;
    if (!slopes_from_normal_map(map, options)) return slopes;
    return Error{slopes.error().message +
                 " (the material key \"invalid_normals\": \"clamp\" replaces such texels)"};
}

Result<RenderMaterial> prepare_material(const MaterialDesc& desc) {
    RenderMaterial material;
    material.desc = desc;
    const float sigma2 = desc.micro_roughness * desc.micro_roughness;
    material.micro_roughness = Sym2{sigma2, 0, sigma2};
    if (!desc.base_color_map.empty()) {
        Result<Image> image =
            load_source(desc.base_color_map, ColorEncoding::automatic, desc.non_finite);
        if (!image) return Error{"base_color: " + image.error().message};
        Result<std::shared_ptr<const MipPyramid>> pyramid = color_pyramid(*image);
        if (!pyramid)
            return Error{"base_color: '" + desc.base_color_map.label() +
                         "': " + pyramid.error().message};
        material.base_color_map = *pyramid;
    }
    if (desc.bump.source != BumpDesc::Source::none) {
        const char* key = desc.bump.source == BumpDesc::Source::height_map ? "bump.height_map"
                                                                           : "bump.normal_map";
        // A normal map's NaN texels are kept: the material's invalid_normals policy decides.
        const NonFinitePolicy non_finite = desc.bump.source == BumpDesc::Source::normal_map
                                               ? NonFinitePolicy::keep
                                               : desc.non_finite;
        Result<Image> map = load_source(desc.bump.map, ColorEncoding::linear, non_finite);
        if (!map) return Error{std::string(key) + ": " + map.error().message};
        Result<Image> slopes = bump_slopes(desc.bump, *map, desc.invalid_normals);
        if (!slopes) {
            return Error{std::string(key) + ": '" + desc.bump.map.label() +
                         "': " + slopes.error().message};
        }
        BumpPyramidOptions options;
        options.micro_roughness = material.micro_roughness;
        Result<BumpPyramid> pyramid = BumpPyramid::build(*slopes, options);
        if (!pyramid) return Error{std::string(key) + ": " + pyramid.error().message};
        material.bump = std::make_shared<const BumpPyramid>(std::move(*pyramid));
    }
    return material;
}

// The material of one part of mesh file `file`: the scene's material combined with the file's own
// colours and normal map (render_scene.h).
Result<RenderMaterial> mesh_part_material(const TriangleMesh& part, const MaterialDesc& scene,
                                          const std::filesystem::path& file) {
    const std::string in_file = " of '" + part.name + "' in '" + file.string() + "'";
    MaterialDesc desc = scene;
    const MeshMaterial& own = part.material;
    desc.base_color = {desc.base_color.x * own.base_color.x, desc.base_color.y * own.base_color.y,
                       desc.base_color.z * own.base_color.z};
    if (desc.base_color_map.empty() && own.has_base_color_texture()) {
        desc.base_color_map = ImageSource{{}, own.base_color_texture, "base colour" + in_file};
    }
    if (desc.bump.source == BumpDesc::Source::none && own.has_normal_texture()) {
        desc.bump.source = BumpDesc::Source::normal_map;
        desc.bump.map = ImageSource{{}, own.normal_texture, "normal texture" + in_file};
        desc.bump.strength = own.normal_scale;
        desc.bump.frame = BumpFrame::main_direction;
        desc.bump.main_direction = {};
        Result<RenderMaterial> material = prepare_material(desc);
        if (material) material->frame_from_mesh_tangents = part.has_tangents();
        return material;
    }
    return prepare_material(desc);
}

Result<std::unique_ptr<RenderEnvironment>> prepare_environment(const EnvironmentDesc& desc) {
    EnvImages images;
    images.layout = desc.layout;
    const bool in_memory = !desc.images.empty() && desc.images[0].image != nullptr;
    if (in_memory) {
        for (const ImageSource& source : desc.images) images.faces.push_back(*source.image);
    } else {
        std::vector<std::filesystem::path> files;
        for (const ImageSource& source : desc.images) files.push_back(source.file);
        EnvImageOptions options;
        if (!desc.detect_layout) options.layout = desc.layout;
        options.image.non_finite = desc.non_finite;
        Result<EnvImages> loaded = load_environment_images(files, options);
        if (!loaded && desc.non_finite == NonFinitePolicy::refuse) {
            options.image.non_finite = NonFinitePolicy::repair;
            if (load_environment_images(files, options))
                return Error{loaded.error().message + repair_hint("environment")};
        }
        if (!loaded) return loaded.error();
        images = std::move(*loaded);
    }
    for (Image& face : images.faces) {
        face = to_rgb(face);
        for (float& v : face.pixels) v *= desc.intensity;
    }
    Result<EnvironmentMap> map = make_environment_map(images);
    if (!map) return map.error();
    auto environment = std::make_unique<RenderEnvironment>();
    environment->map = std::move(*map);
    environment->rotation = rotation_xyz_degrees(static_cast<float>(desc.rotation_deg.x),
                                                 static_cast<float>(desc.rotation_deg.y),
                                                 static_cast<float>(desc.rotation_deg.z));
    environment->intensity = desc.intensity;
    // The mean colour: the coarsest level of every face, averaged (solid-angle weights are
    // ignored: this only sets the ambient term's level).
    for (int f = 0; f < environment->map.face_count(); ++f) {
        const MipPyramid& face = environment->map.face(f);
        const float* texel = face.texel(face.max_level(), 0, 0);
        for (int c = 0; c < 3; ++c) {
            environment->mean[c] += texel[c] / static_cast<float>(environment->map.face_count());
        }
    }
    return environment;
}

}  // namespace

Result<RenderScene> prepare_render_scene(const SceneDesc& desc) {
    RenderScene scene;
    scene.desc_ = desc;
    if (desc.environment) {
        Result<std::unique_ptr<RenderEnvironment>> environment =
            prepare_environment(*desc.environment);
        if (!environment) return scene_error(desc, "environment", environment.error());
        scene.environment_ = std::move(*environment);
    }
    const int object_count = static_cast<int>(desc.objects.size());
    scene.object_material_.assign(object_count, -1);
    scene.mesh_part_material_.resize(object_count);
    scene.meshes_.resize(object_count);
    std::vector<MeshInstance> accel_inputs;
    for (int i = 0; i < object_count; ++i) {
        const ObjectDesc& object = desc.objects[i];
        Result<RenderMaterial> material = prepare_material(object.material);
        if (!material) {
            // prepare_material's messages start with the key inside the material.
            return scene_error(desc, object_key(i) + ".material." + material.error().message, {});
        }
        const auto* mesh = std::get_if<MeshShape>(&object.shape);
        if (!mesh) {
            scene.object_material_[i] = static_cast<int>(scene.materials_.size());
            scene.materials_.push_back(std::move(*material));
            continue;
        }
        Result<MeshAsset> asset = load_mesh(mesh->file, mesh->transform);
        if (!asset) return scene_error(desc, object_key(i) + ".file", asset.error());
        scene.meshes_[i] = std::move(asset->meshes);
        for (const TriangleMesh& part : scene.meshes_[i]) {
            Result<RenderMaterial> own = mesh_part_material(part, object.material, mesh->file);
            if (!own) return scene_error(desc, object_key(i) + ".file", own.error());
            scene.mesh_part_material_[i].push_back(static_cast<int>(scene.materials_.size()));
            scene.materials_.push_back(std::move(*own));
        }
    }
    for (int i = 0; i < object_count; ++i) {
        for (std::size_t m = 0; m < scene.meshes_[i].size(); ++m) {
            accel_inputs.push_back({i, &scene.meshes_[i][m]});
            scene.accel_parts_.push_back({i, static_cast<int>(m)});
        }
    }
    if (!accel_inputs.empty()) {
        Result<MeshAccel> accel = MeshAccel::build(std::move(accel_inputs));
        if (!accel) return scene_error(desc, "objects", accel.error());
        scene.mesh_accel_ = std::make_unique<MeshAccel>(std::move(*accel));
    }
    return scene;
}

std::span<const TriangleMesh> RenderScene::mesh_parts(int object) const {
    return meshes_[static_cast<std::size_t>(object)];
}

std::optional<SceneHit> RenderScene::intersect(const Ray& ray, double t_min, double t_max) const {
    std::optional<SceneHit> nearest;
    for (int i = 0; i < static_cast<int>(desc_.objects.size()); ++i) {
        if (object_material_[i] < 0) continue;
        std::optional<SurfaceHit> hit =
            intersect_analytic(desc_.objects[i].shape, ray, t_min, t_max);
        if (!hit) continue;
        t_max = hit->t;
        hit->object = i;
        nearest = SceneHit{};
        nearest->surface = *hit;
        nearest->material = &materials_[object_material_[i]];
    }
    if (mesh_accel_) {
        if (std::optional<MeshHitRecord> record = mesh_accel_->intersect(ray, t_min, t_max)) {
            const MeshPart part = accel_parts_[record->mesh];
            const TriangleMesh& mesh = meshes_[part.object][part.part];
            SceneHit hit;
            hit.surface =
                mesh_surface_hit(mesh, record->triangle, record->b1, record->b2, ray, record->t);
            hit.surface.object = part.object;
            hit.surface.primitive = record->triangle;
            hit.material = &materials_[mesh_part_material_[part.object][part.part]];
            if (hit.material->frame_from_mesh_tangents) {
                if (auto frame =
                        mesh_tangent_frame(mesh, record->triangle, record->b1, record->b2)) {
                    hit.tangent = frame->tangent;
                    hit.tangent_sign = frame->tangent_sign;
                }
            }
            nearest = hit;
        }
    }
    return nearest;
}

}  // namespace footprint
