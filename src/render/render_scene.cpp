#include "render/render_scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>

#include "bump/bump_pyramid_file.h"
#include "bump/slope_map.h"
#include "envmap/env_image_io.h"
#include "envmap/env_pyramid_file.h"
#include "image/image_io.h"
#include "render/environment_probe.h"
#include "render/material_model.h"
#include "render/peer_filters.h"
#include "scene/mesh.h"
#include "scene/mesh_accel.h"
#include "scene/shapes.h"
#include "scene/terrain.h"

namespace footprint {

// toksvig_normals()'s maps: one per bump map and strength, made on first use.
struct RenderScene::ToksvigMaps {
    std::mutex mutex;
    std::map<std::pair<const BumpHandle*, float>, TextureHandle*> maps;
};

RenderScene::RenderScene() : toksvig_(std::make_unique<ToksvigMaps>()) {}
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
std::string repair_hint(const std::string& where) {
    return " (the " + where + " key \"non_finite\": \"repair\" replaces them)";
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

// The scene's registrations in its texture system: names unique to this preparation (a shared
// texture system may hold other scenes' maps), each map registered once.
class SceneMaps {
  public:
    explicit SceneMaps(TextureSystem& textures) : textures(textures) {
        static std::atomic<std::uint64_t> next_scene{1};
        prefix_ = "scene " + std::to_string(next_scene++) + ": ";
    }

    // The handle registered as `key`, or the one `add(name)` registers under a name made of it.
    template <class Handle, class Add>
    Result<Handle*> find_or_add(const std::string& key, const Add& add) {
        auto& handles = std::get<std::map<std::string, Handle*>>(handles_);
        if (auto it = handles.find(key); it != handles.end()) return it->second;
        Result<Handle*> handle = add(prefix_ + key);
        if (handle) handles.emplace(key, *handle);
        return handle;
    }

    // The texture system's name of the map this scene calls `key`.
    std::string name(const std::string& key) const { return prefix_ + key; }

    TextureSystem& textures;

  private:
    std::string prefix_;
    std::tuple<std::map<std::string, TextureHandle*>, std::map<std::string, BumpHandle*>> handles_;
};

// What identifies an image source: its file, or the image in memory.
std::string source_key(const ImageSource& source) {
    if (!source.image) return source.file.string();
    std::ostringstream key;
    key << source.label() << " (in memory at " << source.image.get() << ")";
    return key.str();
}

// The texture of a base-colour map: a file by name unless it is in memory or its non-finite
// texels are to be repaired, which are loaded here and registered.
Result<TextureHandle*> color_texture(const ImageSource& source, NonFinitePolicy non_finite,
                                     SceneMaps& maps) {
    if (!source.image && non_finite == NonFinitePolicy::refuse) {
        TextureHandle* texture = maps.textures.handle(source.file.string());
        Result<TextureInfo> info = maps.textures.info(texture);
        if (info) return texture;
        ImageLoadOptions repair;
        repair.non_finite = NonFinitePolicy::repair;
        if (!load_image(source.file, repair)) return info.error();
        return Error{info.error().message + repair_hint("material")};
    }
    const std::string key = source_key(source) + (source.image ? "" : " (repaired)");
    return maps.find_or_add<TextureHandle>(key, [&](const std::string& name) {
        using R = Result<TextureHandle*>;
        Result<Image> image = load_source(source, ColorEncoding::automatic, non_finite);
        if (!image) return R(image.error());
        if (image->empty()) return R(Error{"'" + source.label() + "': the image is empty"});
        return maps.textures.add_image(name, *image);
    });
}

// A parallax-mapped material's height map as a one-channel texture (data, not decoded), for the
// march; registered once per map.
Result<TextureHandle*> height_texture(const MaterialDesc& desc, SceneMaps& maps) {
    const ImageSource& source = desc.bump.map;
    return maps.find_or_add<TextureHandle>(
        source_key(source) + " as parallax heights", [&](const std::string& name) {
            using R = Result<TextureHandle*>;
            Result<Image> image = load_source(source, ColorEncoding::linear, desc.non_finite);
            if (!image) return R(image.error());
            if (image->empty()) return R(Error{"'" + source.label() + "': the image is empty"});
            Image heights(image->width, image->height, 1);
            for (std::size_t i = 0; i < heights.pixel_count(); ++i)
                heights.pixels[i] = image->pixels[i * static_cast<std::size_t>(image->channels)];
            return maps.textures.add_image(name, heights);
        });
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

// The F0 map of a textured metallic-roughness material: F0 in RGB, the slope variance in A.
Image f0_and_variance(const detail::MetallicRoughnessTexels& texels) {
    Image out(texels.f0.width, texels.f0.height, 4);
    for (std::size_t i = 0; i < texels.f0.pixel_count(); ++i) {
        std::copy_n(&texels.f0.pixels[3 * i], 3, &out.pixels[4 * i]);
        out.pixels[4 * i + 3] = texels.variance.pixels[i];
    }
    return out;
}

// The slopes and the per-texel variance (if any) at one size, the larger of the two.
void common_size(Image& slopes, Image& variance) {
    if (variance.empty()) return;
    const int width = std::max(slopes.width, variance.width);
    const int height = std::max(slopes.height, variance.height);
    slopes = detail::resampled(slopes, width, height);
    variance = detail::resampled(variance, width, height);
}

// The bump pyramid of a material's bump map, registered (once per map, strength and roughness);
// `variance` (keyed `variance_key`): a per-texel slope variance added to K_0, or empty.
Result<BumpHandle*> bump_map(const MaterialDesc& desc, Sym2 micro_roughness, SceneMaps& maps,
                             const Image& variance = {}, const std::string& variance_key = {}) {
    const BumpDesc& bump = desc.bump;
    const bool height = bump.source == BumpDesc::Source::height_map;
    // A normal map's NaN texels are kept: the material's invalid_normals policy decides.
    const NonFinitePolicy non_finite = height ? desc.non_finite : NonFinitePolicy::keep;
    std::ostringstream key;
    key << source_key(bump.map) << (height ? " as heights" : " as normals") << " × "
        << bump.strength << ", σ² " << micro_roughness.xx << variance_key << ", policies "
        << static_cast<int>(non_finite) << static_cast<int>(desc.invalid_normals);
    return maps.find_or_add<BumpHandle>(key.str(), [&](const std::string& name) {
        using R = Result<BumpHandle*>;
        Result<Image> map = load_source(bump.map, ColorEncoding::linear, non_finite);
        if (!map) return R(map.error());
        Result<Image> slopes = bump_slopes(bump, *map, desc.invalid_normals);
        if (!slopes) return R(Error{"'" + bump.map.label() + "': " + slopes.error().message});
        BumpPyramidOptions options;
        options.micro_roughness = micro_roughness;
        options.micro_variance = variance;
        common_size(*slopes, options.micro_variance);
        Result<BumpPyramid> pyramid = BumpPyramid::build(*slopes, options);
        if (!pyramid) return R(pyramid.error());
        return maps.textures.add_bump(name, std::move(*pyramid));
    });
}

// A flat bump pyramid holding only a per-texel slope variance (a roughness texture without a
// normal map).
Result<BumpHandle*> flat_bump_map(const Image& variance, const std::string& key, SceneMaps& maps) {
    return maps.find_or_add<BumpHandle>(key + " (flat)", [&](const std::string& name) {
        using R = Result<BumpHandle*>;
        BumpPyramidOptions options;
        options.micro_variance = variance;
        Result<BumpPyramid> pyramid =
            BumpPyramid::build(Image(variance.width, variance.height, 2), options);
        if (!pyramid) return R(pyramid.error());
        return maps.textures.add_bump(name, std::move(*pyramid));
    });
}

// A bump map stored as a bump pyramid file (`footprint maketx --bump`): read tile by tile by the
// texture system, the material's strength and micro-roughness applied at each lookup.
Result<BumpHandle*> stored_bump_map(const BumpDesc& bump, Sym2 micro_roughness,
                                    RenderMaterial& material, SceneMaps& maps) {
    BumpHandle* handle = maps.textures.bump_handle(bump.map.file.string());
    if (Result<TextureInfo> info = maps.textures.info(handle); !info) return info.error();
    material.bump_strength = bump.strength;
    material.bump_micro_roughness = micro_roughness;
    return handle;
}

// A material of the footprint model, or a metallic-roughness one reduced to it
// (prepare_metallic_roughness()); `variance`: a per-texel slope variance (keyed `variance_key`)
// for the bump pyramid's K_0, or empty.
Result<RenderMaterial> prepare_material(const MaterialDesc& desc, SceneMaps& maps,
                                        const Image& variance = {},
                                        const std::string& variance_key = {}) {
    RenderMaterial material;
    material.desc = desc;
    material.f0 = {desc.fresnel_f0, desc.fresnel_f0, desc.fresnel_f0};
    material.ambient_weight = desc.diffuse;
    const float sigma2 = desc.micro_roughness * desc.micro_roughness;
    material.micro_roughness = Sym2{sigma2, 0, sigma2};
    if (!desc.base_color_map.empty()) {
        Result<TextureHandle*> texture = color_texture(desc.base_color_map, desc.non_finite, maps);
        if (!texture) return Error{"base_color: " + texture.error().message};
        material.base_color_map = *texture;
        material.base_color_grey = maps.textures.info(*texture)->channels < 3;
    }
    const bool has_bump_map = desc.bump.source == BumpDesc::Source::height_map ||
                              desc.bump.source == BumpDesc::Source::normal_map;
    if (has_bump_map) {
        const char* key = desc.bump.source == BumpDesc::Source::height_map ? "bump.height_map"
                                                                           : "bump.normal_map";
        const bool stored = !desc.bump.map.image && bump_pyramid_file_offset(desc.bump.map.file);
        if (stored && desc.bump.parallax)
            return Error{std::string(key) +
                         ": a bump pyramid file holds slopes, not the heights parallax marches "
                         "through (give the height map itself)"};
        if (stored && !variance.empty())
            return Error{std::string(key) +
                         ": a bump pyramid file cannot take a roughness texture's variance (give "
                         "the normal map itself)"};
        Result<BumpHandle*> bump =
            stored ? stored_bump_map(desc.bump, material.micro_roughness, material, maps)
                   : bump_map(desc, material.micro_roughness, maps, variance, variance_key);
        if (!bump) return Error{std::string(key) + ": " + bump.error().message};
        material.bump = *bump;
        if (desc.bump.parallax) {
            Result<TextureHandle*> heights = height_texture(desc, maps);
            if (!heights) return Error{std::string(key) + ": " + heights.error().message};
            material.height_map = *heights;
        }
    } else if (!variance.empty()) {
        Result<BumpHandle*> bump = flat_bump_map(variance, variance_key, maps);
        if (!bump) return Error{"roughness: " + bump.error().message};
        material.bump = *bump;
    }
    return material;
}

// A metallic-roughness material (render/material_model.h) in the footprint model's terms:
// Lambert of BRDF c (1 − m)/π for the lights and c (1 − m) times the environment's mean, the
// highlight and the mirror at F0 per channel, the roughness as slope variance. Textures (the
// colour map, glTF's metallicRoughnessTexture `texture`) make a diffuse-colour map and an F0 map
// with the slope variance beside it, texel by texel, and the variance enters the bump pyramid's
// K_0 texel by texel; without them every term is a constant and the variance micro-roughness.
Result<RenderMaterial> prepare_metallic_roughness(MaterialDesc desc, ImageSource texture,
                                                  SceneMaps& maps) {
    if (!texture.empty() && !texture.image) {  // the scene's file: read as data
        Result<Image> loaded = load_source(texture, ColorEncoding::linear, desc.non_finite);
        if (!loaded) return Error{"metallic_roughness: " + loaded.error().message};
        texture.name = texture.file.string();
        texture.image = std::make_shared<const Image>(std::move(*loaded));
    }
    desc.diffuse = 1 / static_cast<float>(M_PI);
    desc.specular = desc.mirror = 1;
    const Vec3 base = desc.base_color;
    if (desc.base_color_map.empty() && !texture.image) {
        desc.base_color = detail::diffuse_color(base, desc.metallic);
        desc.micro_roughness = std::sqrt(detail::slope_variance(desc.roughness));
        Result<RenderMaterial> material = prepare_material(desc, maps);
        if (!material) return material;
        const Vec3 f0 = detail::specular_f0(base, desc.metallic);
        material->f0 = {f0.x, f0.y, f0.z};
        material->ambient_weight = 1;
        return material;
    }
    std::optional<Image> colour;
    if (!desc.base_color_map.empty()) {
        Result<Image> loaded =
            load_source(desc.base_color_map, ColorEncoding::automatic, desc.non_finite);
        if (!loaded) return Error{"base_color: " + loaded.error().message};
        colour = std::move(*loaded);
    }
    detail::MetallicRoughnessTexels texels = detail::metallic_roughness_texels(
        colour ? &*colour : nullptr, base, texture.image.get(), desc.metallic, desc.roughness);
    std::ostringstream key;
    key << (desc.base_color_map.empty() ? "" : source_key(desc.base_color_map)) << " × (" << base.x
        << ", " << base.y << ", " << base.z << "), " << (texture.image ? source_key(texture) : "")
        << " × (" << desc.metallic << ", " << desc.roughness << ")";
    auto add = [&](const char* what, const Image& image) {
        return maps.find_or_add<TextureHandle>(key.str() + what, [&](const std::string& name) {
            return maps.textures.add_image(name, image);
        });
    };
    Result<TextureHandle*> diffuse = add(": diffuse colour", texels.diffuse);
    if (!diffuse) return Error{"base_color: " + diffuse.error().message};
    Result<TextureHandle*> f0 = add(": F0 and slope variance", f0_and_variance(texels));
    if (!f0) return Error{"base_color: " + f0.error().message};
    desc.base_color = {1, 1, 1};
    desc.base_color_map = {};
    desc.micro_roughness = 0;
    Result<RenderMaterial> material =
        prepare_material(desc, maps, texels.variance, ", σ² of " + key.str());
    if (!material) return material;
    material->base_color_map = *diffuse;
    material->f0_map = *f0;
    material->ambient_weight = 1;
    return material;
}

// The material of an object: its model's.
Result<RenderMaterial> object_material(const MaterialDesc& desc, SceneMaps& maps,
                                       const ImageSource& metallic_roughness_texture = {}) {
    if (desc.model == MaterialDesc::Model::metallic_roughness)
        return prepare_metallic_roughness(desc,
                                          metallic_roughness_texture.empty()
                                              ? desc.metallic_roughness_map
                                              : metallic_roughness_texture,
                                          maps);
    return prepare_material(desc, maps);
}

// The material of one part of mesh file `file`: the scene's material combined with the file's own
// colours, normal map and (metallic-roughness, from a glTF file) metallic and roughness
// (render_scene.h).
Result<RenderMaterial> mesh_part_material(const TriangleMesh& part, const MaterialDesc& scene,
                                          const std::filesystem::path& file, SceneMaps& maps) {
    const std::string in_file = " of '" + part.name + "' in '" + file.string() + "'";
    MaterialDesc desc = scene;
    const MeshMaterial& own = part.material;
    desc.base_color = {desc.base_color.x * own.base_color.x, desc.base_color.y * own.base_color.y,
                       desc.base_color.z * own.base_color.z};
    if (desc.base_color_map.empty() && own.has_base_color_texture()) {
        desc.base_color_map = ImageSource{{}, own.base_color_texture, "base colour" + in_file};
    }
    ImageSource metallic_roughness;
    if (desc.model == MaterialDesc::Model::metallic_roughness && own.metallic_roughness) {
        desc.metallic = own.metallic, desc.roughness = own.roughness;
        if (own.metallic_roughness_texture)
            metallic_roughness = ImageSource{
                {}, own.metallic_roughness_texture, "metallic-roughness texture" + in_file};
    }
    const bool own_normals = desc.bump.source == BumpDesc::Source::none && own.has_normal_texture();
    if (own_normals) {
        desc.bump.source = BumpDesc::Source::normal_map;
        desc.bump.map = ImageSource{{}, own.normal_texture, "normal texture" + in_file};
        desc.bump.strength = own.normal_scale;
        desc.bump.frame = BumpFrame::main_direction;
        desc.bump.main_direction = {};
    }
    Result<RenderMaterial> material = object_material(desc, maps, metallic_roughness);
    if (material && own_normals) material->frame_from_mesh_tangents = part.has_tangents();
    return material;
}

// An environment pyramid file's map (`footprint maketx --env`) in RGB × intensity, levels and caps
// as stored.
Result<EnvironmentMap> rgb_times(const EnvironmentMap& stored, float intensity) {
    auto levels_of = [&](const MipPyramid& pyramid) {
        std::vector<Image> levels;
        for (int l = 0; l < pyramid.level_count(); ++l) {
            Image& level = levels.emplace_back(to_rgb(pyramid.level_image(l)));
            for (float& v : level.pixels) v *= intensity;
        }
        return levels;
    };
    std::vector<std::vector<Image>> faces, caps;
    for (int f = 0; f < stored.face_count(); ++f) faces.push_back(levels_of(stored.face(f)));
    for (int pole = 0; pole < 2 && stored.polar_cap(pole); ++pole)
        caps.push_back(levels_of(*stored.polar_cap(pole)));
    return EnvironmentMap::from_face_levels(stored.layout(), faces, caps);
}

// The environment's images in RGB × intensity, from memory or its files; `key` is its scene key.
Result<EnvImages> environment_images(const EnvironmentDesc& desc, const std::string& key) {
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
                return Error{loaded.error().message + repair_hint(key)};
        }
        if (!loaded) return loaded.error();
        images = std::move(*loaded);
    }
    for (Image& face : images.faces) {
        face = to_rgb(face);
        for (float& v : face.pixels) v *= desc.intensity;
    }
    return images;
}

// What the renderer keeps of the map `handle` besides the handle: layout and texel scale
// (environment_shape()), and the irradiance's nine coefficients in world space, projected through
// the map's filtered lookups.
Status describe(TextureSystem& textures, EnvironmentHandle* handle,
                RenderEnvironment& environment) {
    Result<TextureSystem::EnvironmentShape> shape = textures.environment_shape(handle);
    if (!shape) return shape.error();
    environment.map = handle;
    environment.layout = shape->layout;
    environment.texel_scale = shape->texel_scale;
    const EnvLookupOptions options(LookupOptions{}, environment.rotation);
    Status status;
    environment.irradiance = project_radiance([&](Vec3 w, Vec3 d1, Vec3 d2) {
        float rgb[3] = {0, 0, 0};
        if (Status s = textures.environment(handle, w, d1, d2, options, rgb); !s) status = s;
        return Vec3{rgb[0], rgb[1], rgb[2]};
    });
    return status;
}

// The environment in the texture system: an environment pyramid file by its name, read tile by
// tile (a copy in RGB × intensity, held whole, where it is not that already), any other files' or
// images' pyramids built here and registered.
// `key`: the scene's key of the map, which names it in the texture system.
Result<std::unique_ptr<RenderEnvironment>> prepare_environment(const EnvironmentDesc& desc,
                                                               const std::string& key,
                                                               SceneMaps& maps) {
    auto environment = std::make_unique<RenderEnvironment>();
    environment->rotation = rotation_xyz_degrees(static_cast<float>(desc.rotation_deg.x),
                                                 static_cast<float>(desc.rotation_deg.y),
                                                 static_cast<float>(desc.rotation_deg.z));
    environment->intensity = desc.intensity;
    environment->proxy = desc.proxy;
    Result<EnvironmentMap> map = Error{""};
    const bool stored = desc.images.size() == 1 && !desc.images[0].image &&
                        is_environment_pyramid_file(desc.images[0].file);
    if (stored) {
        EnvironmentHandle* handle = maps.textures.environment_handle(desc.images[0].file.string());
        Result<TextureSystem::EnvironmentShape> shape = maps.textures.environment_shape(handle);
        if (!shape) return shape.error();
        if (desc.intensity == 1 && shape->channels == 3) {
            if (Status s = describe(maps.textures, handle, *environment); !s) return s.error();
            return environment;
        }
        Result<std::shared_ptr<const EnvironmentMap>> whole = maps.textures.environment_map(handle);
        if (!whole) return whole.error();
        map = rgb_times(**whole, desc.intensity);
    } else {
        Result<EnvImages> images = environment_images(desc, key);
        if (!images) return images.error();
        map = make_environment_map(*images);
    }
    if (!map) return map.error();
    Result<EnvironmentHandle*> handle =
        maps.textures.add_environment(maps.name(key), std::move(*map));
    if (!handle) return handle.error();
    if (Status s = describe(maps.textures, *handle, *environment); !s) return s.error();
    return environment;
}

// The scene's local maps, innermost first: by their proxies' volume, the scene's order where
// equal (the first that contains a point is then the innermost, RenderScene::environment_at()).
Status prepare_local_environments(const SceneDesc& desc, SceneMaps& maps,
                                  std::vector<std::unique_ptr<RenderEnvironment>>& out) {
    for (std::size_t i = 0; i < desc.local_environments.size(); ++i) {
        const std::string key = "local_environments[" + std::to_string(i) + "]";
        const EnvironmentDesc& local = desc.local_environments[i];
        if (!local.proxy) return scene_error(desc, key + ".proxy", Error{"a local map needs one"});
        Result<std::unique_ptr<RenderEnvironment>> environment =
            prepare_environment(local, key, maps);
        if (!environment) return scene_error(desc, key, environment.error());
        out.push_back(std::move(*environment));
    }
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return proxy_volume(*a->proxy) < proxy_volume(*b->proxy);
    });
    return {};
}

}  // namespace

Result<RenderScene> prepare_render_scene(const SceneDesc& desc,
                                         std::shared_ptr<TextureSystem> textures) {
    RenderScene scene;
    scene.desc_ = desc;
    if (!textures) {
        Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create();
        if (!made) return made.error();
        textures = std::move(*made);
    }
    scene.textures_ = textures;
    SceneMaps maps(*textures);
    if (desc.environment) {
        Result<std::unique_ptr<RenderEnvironment>> environment =
            prepare_environment(*desc.environment, "environment", maps);
        if (!environment) return scene_error(desc, "environment", environment.error());
        scene.environment_ = std::move(*environment);
    }
    if (Status s = prepare_local_environments(desc, maps, scene.local_environments_); !s)
        return s.error();
    const int object_count = static_cast<int>(desc.objects.size());
    scene.object_material_.assign(object_count, -1);
    scene.mesh_part_material_.resize(object_count);
    scene.meshes_.resize(object_count);
    std::vector<MeshInstance> accel_inputs;
    for (int i = 0; i < object_count; ++i) {
        const ObjectDesc& object = desc.objects[i];
        Result<RenderMaterial> material = object_material(object.material, maps);
        if (!material) {
            // object_material's messages start with the key inside the material.
            return scene_error(desc, object_key(i) + ".material." + material.error().message, {});
        }
        if (const auto* terrain = std::get_if<TerrainShape>(&object.shape)) {
            // One generated part, in the object's own material.
            scene.meshes_[i].push_back(make_terrain_mesh(*terrain, object_key(i)));
            scene.mesh_part_material_[i].push_back(static_cast<int>(scene.materials_.size()));
            scene.materials_.push_back(std::move(*material));
            continue;
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
            Result<RenderMaterial> own =
                mesh_part_material(part, object.material, mesh->file, maps);
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
    // Environment probes last, as their views see every object. All are rendered before any is
    // used, so that none shows another's reflection (one bounce).
    std::vector<std::pair<int, std::unique_ptr<RenderEnvironment>>> probes;
    for (int i = 0; i < object_count; ++i) {
        const auto& probe = desc.objects[i].material.environment_probe;
        if (!probe) continue;
        const std::string key = object_key(i) + ".material.environment_probe";
        Result<EnvironmentMap> map = render_environment_probe(scene, *probe, i);
        if (!map) return scene_error(desc, key, map.error());
        Result<EnvironmentHandle*> handle =
            maps.textures.add_environment(maps.name(key), std::move(*map));
        if (!handle) return scene_error(desc, key, handle.error());
        auto environment = std::make_unique<RenderEnvironment>();
        if (Status s = describe(maps.textures, *handle, *environment); !s)
            return scene_error(desc, key, s.error());
        probes.emplace_back(i, std::move(environment));
    }
    for (auto& [object, environment] : probes) {
        if (scene.object_material_[object] >= 0)
            scene.materials_[scene.object_material_[object]].probe = environment.get();
        for (int m : scene.mesh_part_material_[object])
            scene.materials_[m].probe = environment.get();
        scene.probes_.push_back(std::move(environment));
    }
    return scene;
}

const RenderEnvironment* RenderScene::environment_at(Vec3 p) const {
    for (const std::unique_ptr<RenderEnvironment>& local : local_environments_)
        if (proxy_contains(*local->proxy, p)) return local.get();
    return environment_.get();
}

TextureHandle* RenderScene::toksvig_normals(const RenderMaterial& material) const {
    const std::lock_guard lock(toksvig_->mutex);
    const auto key =
        std::pair{static_cast<const BumpHandle*>(material.bump), material.bump_strength};
    if (auto it = toksvig_->maps.find(key); it != toksvig_->maps.end()) return it->second;
    TextureHandle* handle = nullptr;
    if (Result<std::shared_ptr<const BumpPyramid>> bump = textures_->bump_pyramid(material.bump)) {
        const BumpPyramid& pyramid = **bump;
        // Level 0's slopes: the moments' first two channels plus the offset they are centred on.
        const Image moments = pyramid.moments().level_image(0);
        Image slopes(moments.width, moments.height, 2);
        for (int y = 0; y < moments.height; ++y) {
            for (int x = 0; x < moments.width; ++x) {
                slopes.at(x, y, 0) = moments.at(x, y, 0) + pyramid.slope_offset().x;
                slopes.at(x, y, 1) = moments.at(x, y, 1) + pyramid.slope_offset().y;
            }
        }
        // Named after the bump map's entry and strength: another scene sharing the texture system
        // and the map finds the same normals under that name.
        std::ostringstream name;
        name << "toksvig normals of bump map " << static_cast<const void*>(material.bump) << " × "
             << material.bump_strength;
        const Result<TextureHandle*> added =
            textures_->add_image(name.str(), detail::unit_normals(slopes, material.bump_strength),
                                 pyramid.options().wrap_s, pyramid.options().wrap_t);
        if (added) {
            handle = *added;
        } else if (TextureHandle* shared = textures_->handle(name.str()); textures_->info(shared)) {
            handle = shared;
        }
    }
    toksvig_->maps.emplace(key, handle);
    return handle;
}

Status RenderScene::take_texture_errors() const {
    const std::vector<Error> errors = textures_->take_errors();
    if (errors.empty()) return {};
    std::string message = errors[0].message;
    if (errors.size() > 1) message += " (and " + std::to_string(errors.size() - 1) + " more)";
    return Error{message};
}

std::span<const TriangleMesh> RenderScene::mesh_parts(int object) const {
    return meshes_[static_cast<std::size_t>(object)];
}

bool RenderScene::occluded(const Ray& ray, double t_min, double t_max) const {
    for (int i = 0; i < static_cast<int>(desc_.objects.size()); ++i) {
        if (object_material_[i] >= 0 &&
            intersect_analytic(desc_.objects[i].shape, ray, t_min, t_max))
            return true;
    }
    return mesh_accel_ && mesh_accel_->occluded(ray, t_min, t_max);
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
