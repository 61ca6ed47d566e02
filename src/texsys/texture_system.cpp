#include "texture_system.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>
#include <shared_mutex>
#include <unordered_map>

#include "bump/bump_pyramid_file.h"
#include "bump/slope_map.h"
#include "envmap/env_image_io.h"
#include "envmap/env_pyramid_file.h"
#include "envmap/tiled_environment.h"
#include "texsys/texture_file.h"
#include "texsys/tile_cache.h"
#include "texture/tiled_texels.h"

namespace footprint {

namespace fs = std::filesystem;

namespace texsys {

// A map held whole (environment and bump maps), opened once.
template <class T>
struct WholeMap {
    std::once_flag opened;
    std::shared_ptr<const T> value;
    std::optional<Error> error;
    std::atomic<bool> error_reported{false};
};

}  // namespace texsys

class BumpHandle : public texsys::WholeMap<BumpPyramid> {
  public:
    // A bump pyramid file, or the one built into the cache folder: its moments read tile by tile
    // as a 5-channel texture, with its slope offset. Otherwise the pyramid is `value`, whole.
    TextureHandle* moments = nullptr;
    Vec2 slope_offset;
};
class EnvironmentHandle : public texsys::WholeMap<EnvironmentMap> {
  public:
    // An environment pyramid file, or the one built into the cache folder: its parts (faces,
    // then polar caps) read tile by tile, each a file of the cache's. Otherwise the map is
    // `value`, whole.
    std::string file;
    detail::TiledEnvShape shape;
    TextureSystem::EnvironmentShape shape_of{};  // what environment_shape() returns
    std::vector<std::unique_ptr<TextureHandle>> parts;
    // The file read whole (TextureSystem::environment_map()), while someone holds it.
    std::mutex whole_mutex;
    std::weak_ptr<const EnvironmentMap> whole;

    // The error of a part's read that failed (a truncated tile), if any.
    std::optional<Error> read_error() {
        for (const auto& part : parts)
            if (part->read_failed) {
                std::lock_guard lock(part->read_error_mutex);
                return *part->read_error;
            }
        return std::nullopt;
    }
};

namespace {

// The tiles of one lookup on one file: the thread's micro-cache first, then the shared cache.
// Every tile asked for stays pinned (in ThreadTiles::recent) until the lookup ends, when all but
// the last kMicroCacheTiles are let go, and with them the thread's tiles at hand.
class LookupTiles final : public detail::TileSource {
  public:
    LookupTiles(texsys::TileCache& cache, texsys::ThreadTiles& thread, TextureHandle& file)
        : cache_(cache), thread_(thread), file_(file) {}
    ~LookupTiles() {
        auto& recent = thread_.recent;
        const std::size_t keep = TextureSystem::kMicroCacheTiles;
        if (recent.size() > keep) {
            recent.erase(recent.begin(), recent.end() - keep);
            thread_.let_go();
        }
    }
    LookupTiles(const LookupTiles&) = delete;
    LookupTiles& operator=(const LookupTiles&) = delete;

    // The thread's tiles at hand on the file, for TiledTexels.
    detail::TiledTexels::Slots& slots() const { return thread_.slots_for(file_.id); }

    const float* tile(int level, int tx, int ty) const override {
        const texsys::TileKey key{file_.id, static_cast<std::uint32_t>(level),
                                  static_cast<std::uint32_t>(tx), static_cast<std::uint32_t>(ty)};
        auto& recent = thread_.recent;
        for (auto it = recent.rbegin(); it != recent.rend(); ++it)
            if (it->first == key) return it->second->texels.get();
        texsys::TilePtr tile =
            cache_.get(key, file_.tile_floats(level, tx, ty),
                       [&](float* texels) { file_.read_tile(level, tx, ty, texels); });
        recent.emplace_back(key, std::move(tile));
        return recent.back().second->texels.get();
    }

  private:
    texsys::TileCache& cache_;
    texsys::ThreadTiles& thread_;
    TextureHandle& file_;
};

// The tiles of one lookup on an environment map read tile by tile: a LookupTiles on each part.
class EnvLookupTiles {
  public:
    EnvLookupTiles(texsys::TileCache& cache, texsys::ThreadTiles& thread, EnvironmentHandle& env) {
        for (std::size_t i = 0; i < env.parts.size(); ++i) {
            const LookupTiles& part = tiles_[i].emplace(cache, thread, *env.parts[i]);
            sources_[i] = {&part, &part.slots()};
        }
    }
    const auto& sources() const { return sources_; }

  private:
    static constexpr int kParts = detail::TiledEnvironment::kMaxParts;
    std::array<std::optional<LookupTiles>, kParts> tiles_;
    std::array<detail::TiledEnvironment::Part, kParts> sources_{};
};

// The texels of a pyramid held whole (MipPyramid) or read tile by tile (TiledTexels), which name
// their members alike, for read_texels().
template <class Texels>
class TexelsReader final : public detail::TexelReader {
  public:
    explicit TexelsReader(const Texels& texels) : texels_(texels) {}
    int level_count() const override { return texels_.level_count(); }
    int width(int l) const override { return texels_.width(l); }
    int height(int l) const override { return texels_.height(l); }
    int channels() const override { return texels_.channels(); }
    const float* texel(int l, int x, int y) const override { return texels_.texel(l, x, y); }

  private:
    const Texels& texels_;
};

// A name → entry table that many threads read and a few add to.
template <class Entry>
class FileTable {
  public:
    // The entry of `name` and whether it was just added.
    std::pair<Entry*, bool> find_or_add(std::string_view name,
                                        const std::function<std::unique_ptr<Entry>()>& make) {
        {
            std::shared_lock lock(mutex_);
            if (auto it = entries_.find(std::string(name)); it != entries_.end())
                return {it->second.get(), false};
        }
        std::unique_lock lock(mutex_);
        auto [it, added] = entries_.try_emplace(std::string(name));
        if (added) it->second = make();
        return {it->second.get(), added};
    }
    std::size_t size() const {
        std::shared_lock lock(mutex_);
        return entries_.size();
    }

  private:
    mutable std::shared_mutex mutex_;
    std::unordered_map<std::string, std::unique_ptr<Entry>> entries_;
};

constexpr std::string_view kUdim = "<UDIM>";

class TextureSystemImpl final : public TextureSystem {
  public:
    // `options` with the cache folder resolved: cache_dir the folder pyramids are built into, or
    // empty (in memory); default_cache: it is the default folder, whose failures are warnings.
    TextureSystemImpl(const TextureSystemOptions& options, bool default_cache,
                      std::optional<Error> warning)
        : options_(options), default_cache_(default_cache), cache_(options.max_memory_mb << 20) {
        if (warning) warn(*warning);
    }

    TextureHandle* handle(std::string_view name) override { return handle(name, {}); }

    // The entry of `name` read as `as` (texsys/texel_access.h): a default `as` is the file's own
    // entry, any other an entry of its own, keyed by the name and what `as` says.
    TextureHandle* handle(std::string_view name, const detail::OpenAs& as) {
        std::string key(name);
        if (!(as == detail::OpenAs{})) {
            key += '\0';  // no file name holds a NUL
            key += std::to_string(as.subimage) + ',' +
                   (as.wrap_s ? to_string(*as.wrap_s) : "file") + ',' +
                   (as.wrap_t ? to_string(*as.wrap_t) : "file");
        }
        const auto found = files_.find_or_add(key, [&] {
            return std::make_unique<TextureHandle>(std::string(name), next_file_id_++);
        });
        TextureHandle* file = found.first;  // (clang 14 cannot capture a structured binding)
        std::call_once(file->opened, [&] {
            if (name.find(kUdim) != std::string_view::npos) {
                file->udim = true;
            } else {
                file->open(options_, as, default_cache_);
                if (file->pyramid) hold_whole(pyramid_bytes(*file->pyramid));
                if (file->warning) warn(*file->warning);
            }
        });
        return file;
    }

    // texsys/texel_access.h's read_texels().
    Status read_texels(TextureHandle* file,
                       const std::function<void(const detail::TexelReader&)>& read) {
        if (file->udim) return Error{"'" + file->name + "' is a UDIM set, not one texture"};
        if (file->error) return *file->error;
        on_texels(file, [&](const auto& texels) { read(TexelsReader(texels)); });
        if (file->read_failed) {
            std::lock_guard lock(file->read_error_mutex);
            return *file->read_error;
        }
        return {};
    }

    Result<TextureInfo> info(TextureHandle* file) override {
        if (file->udim) file = udim_tile(file, 1001);
        if (file->error) return *file->error;
        return file->info;
    }

    Status texture(TextureHandle* file, const TextureCoords& coords, const LookupOptions& options,
                   std::span<float> out, std::span<const float> missing) override {
        TextureCoords c = coords;
        if (file->udim) {
            const float u = std::floor(c.s), v = std::floor(c.t);
            if (!(u >= 0 && u < 10 && v >= 0 && v < 1000))
                return missing_or(Error{"no UDIM tile of '" + file->name + "' at (" +
                                        std::to_string(c.s) + ", " + std::to_string(c.t) + ")"},
                                  file->error_reported, out, missing);
            file = udim_tile(file, 1001 + static_cast<int>(u) + 10 * static_cast<int>(v));
            c.s -= u;
            c.t -= v;
        }
        if (file->error) return missing_or(*file->error, file->error_reported, out, missing);
        float result[MipPyramid::kMaxChannels];
        on_texels(file, [&](const auto& texels) { texture_lookup(texels, c, options, result); });
        if (file->read_failed) {
            std::lock_guard lock(file->read_error_mutex);
            return missing_or(*file->read_error, file->error_reported, out, missing);
        }
        write_channels(result, file->info.channels, out);
        return {};
    }

    Status environment(EnvironmentHandle* env, Vec3 r, Vec3 dr_dx, Vec3 dr_dy,
                       const EnvLookupOptions& options, std::span<float> out,
                       std::span<const float> missing) override {
        return environment_on(env, out, missing, [&](const auto& map, float* result) {
            environment_lookup(map, r, dr_dx, dr_dy, options, result);
        });
    }

    Status environment(EnvironmentHandle* env, const EnvFootprint& footprint,
                       const LookupOptions& options, std::span<float> out,
                       std::span<const float> missing) override {
        return environment_on(env, out, missing, [&](const auto& map, float* result) {
            environment_lookup(map, footprint, options, result);
        });
    }

    Status environment_sample(EnvironmentHandle* env, Vec3 r, std::span<float> out) override {
        return environment_on(env, out, {}, [&](const auto& map, float* result) {
            environment_bilinear(map, r, 0, result);
        });
    }

    Result<EnvironmentShape> environment_shape(EnvironmentHandle* env) override {
        if (env->error) return *env->error;
        return env->shape_of;
    }

    EnvironmentHandle* environment_handle(std::string_view name) override {
        return open_whole(environments_, name, [&](EnvironmentHandle& entry) {
            open_environment(entry, std::string(name));
        });
    }

    Status bump(BumpHandle* entry, const TextureCoords& coords, const BumpLookupOptions& options,
                SlopeStatistics* statistics) override {
        if (entry->error) {
            if (!entry->error_reported.exchange(true)) report(*entry->error);
            return *entry->error;
        }
        if (!entry->moments) {
            *statistics = bump_lookup(*entry->value, coords, options);
            return {};
        }
        float moments[5];
        if (Status s = texture(entry->moments, coords, options, moments, {}); !s) {
            if (!entry->error_reported.exchange(true)) report(s.error());
            return s;
        }
        *statistics = slope_statistics(moments, entry->slope_offset, options);
        return {};
    }

    BumpHandle* bump_handle(std::string_view name) override {
        return open_whole(bumps_, name,
                          [&](BumpHandle& entry) { open_bump(entry, std::string(name)); });
    }

    Result<TextureInfo> info(BumpHandle* entry) override {
        if (entry->error) return *entry->error;
        if (entry->moments) return info(entry->moments);
        const MipPyramid& m = entry->value->moments();
        return TextureInfo{m.width(0), m.height(0), m.channels(), m.level_count(),
                           false,      m.wrap_s(),  m.wrap_t()};
    }

    Result<TextureHandle*> add_image(std::string_view name, const Image& image, WrapMode wrap_s,
                                     WrapMode wrap_t) override {
        if (image.empty())
            return Error{"texture system: the image '" + std::string(name) + "' is empty"};
        if (image.channels < 1 || image.channels > MipPyramid::kMaxChannels)
            return Error{"texture system: the image '" + std::string(name) + "' has " +
                         std::to_string(image.channels) + " channels (1 to " +
                         std::to_string(MipPyramid::kMaxChannels) + " can be filtered)"};
        auto [file, added] = files_.find_or_add(name, [&] {
            return std::make_unique<TextureHandle>(std::string(name), next_file_id_++);
        });
        if (!added) return name_taken(name);
        std::call_once(file->opened, [&, file = file] {
            MipPyramidOptions options;
            options.wrap_s = wrap_s;
            options.wrap_t = wrap_t;
            options.downsample = options_.downsample;
            file->pyramid = std::make_shared<const MipPyramid>(MipPyramid::build(image, options));
            file->info = {image.width, image.height, image.channels, file->pyramid->level_count(),
                          false,       wrap_s,       wrap_t};
            hold_whole(pyramid_bytes(*file->pyramid));
        });
        return file;
    }

    Result<BumpHandle*> add_bump(std::string_view name, BumpPyramid pyramid) override {
        return add_whole(bumps_, name, std::move(pyramid));
    }

    Result<EnvironmentHandle*> add_environment(std::string_view name, EnvironmentMap map) override {
        return add_whole(environments_, name, std::move(map));
    }

    Result<std::shared_ptr<const MipPyramid>> pyramid(TextureHandle* file) override {
        if (file->udim) return Error{"'" + file->name + "' is a UDIM set, not one pyramid"};
        if (file->error) return *file->error;
        if (file->pyramid) return file->pyramid;
        // Kept while a caller holds it, so that two materials on one file upload it once.
        std::lock_guard lock(file->whole_mutex);
        if (std::shared_ptr<const MipPyramid> held = file->whole.lock()) return held;
        Result<MipPyramid> whole = file->read_whole();
        if (!whole) return whole.error();
        auto held = std::make_shared<const MipPyramid>(std::move(*whole));
        file->whole = held;
        return held;
    }

    Result<std::shared_ptr<const BumpPyramid>> bump_pyramid(BumpHandle* entry) override {
        if (entry->error) return *entry->error;
        if (!entry->moments) return entry->value;
        Result<std::shared_ptr<const MipPyramid>> moments = pyramid(entry->moments);
        if (!moments) return moments.error();
        std::vector<Image> levels;
        for (int l = 0; l < (*moments)->level_count(); ++l)
            levels.push_back((*moments)->level_image(l));
        Result<BumpPyramid> whole = BumpPyramid::from_moment_levels(
            levels, entry->slope_offset, (*moments)->wrap_s(), (*moments)->wrap_t());
        if (!whole) return whole.error();
        return std::make_shared<const BumpPyramid>(std::move(*whole));
    }

    Result<std::shared_ptr<const EnvironmentMap>> environment_map(
        EnvironmentHandle* entry) override {
        if (entry->error) return *entry->error;
        if (entry->value) return entry->value;
        // Kept while a caller holds it, as pyramid() keeps a texture read whole.
        std::lock_guard lock(entry->whole_mutex);
        if (std::shared_ptr<const EnvironmentMap> held = entry->whole.lock()) return held;
        Result<EnvironmentMap> whole = load_environment_pyramid(entry->file);
        if (!whole) return whole.error();
        auto held = std::make_shared<const EnvironmentMap>(std::move(*whole));
        entry->whole = held;
        return held;
    }

    TextureSystemStats stats() const override {
        const texsys::Accounting& a = *cache_.accounting();
        TextureSystemStats s;
        s.files = files_.size() + environments_.size() + bumps_.size();
        s.tiles_loaded = a.loaded;
        s.tile_hits = a.hits;
        s.tile_misses = a.misses;
        s.bytes_resident = a.resident;
        s.peak_bytes = a.peak;
        s.bytes_in_memory = bytes_in_memory_;
        return s;
    }

    std::vector<Error> take_errors() override {
        std::lock_guard lock(errors_mutex_);
        return std::exchange(errors_, {});
    }

    std::vector<Error> take_warnings() override {
        std::lock_guard lock(errors_mutex_);
        return std::exchange(warnings_, {});
    }

  private:
    // Calls read(texels) with an opened file's texels: its pyramid in memory (a MipPyramid), or its
    // tiles through the cache (a TiledTexels), pinned until read() returns.
    template <class Read>
    void on_texels(TextureHandle* file, const Read& read) {
        if (file->pyramid) return read(*file->pyramid);
        const LookupTiles tiles(cache_, thread_tiles_.local(), *file);
        read(detail::TiledTexels(file->shape, tiles, tiles.slots()));
    }

    // The file of UDIM tile `number` of the set `set`.
    TextureHandle* udim_tile(TextureHandle* set, int number) {
        std::lock_guard lock(set->udim_mutex);
        auto [it, added] = set->udim_tiles.try_emplace(number, nullptr);
        if (added) {
            std::string name = set->name;
            name.replace(name.find(kUdim), kUdim.size(), std::to_string(number));
            it->second = handle(name);
        }
        return it->second;
    }

    // An environment lookup on `env`, lookup(map, result) on its map in memory or read through
    // tiles: its channels to out, or the error (with `missing`, the missing colour instead).
    template <class Lookup>
    Status environment_on(EnvironmentHandle* env, std::span<float> out,
                          std::span<const float> missing, const Lookup& lookup) {
        if (env->error) return missing_or(*env->error, env->error_reported, out, missing);
        float result[MipPyramid::kMaxChannels];
        if (env->value) {
            lookup(*env->value, result);
        } else {
            {
                const EnvLookupTiles tiles(cache_, thread_tiles_.local(), *env);
                lookup(detail::TiledEnvironment(env->shape, tiles.sources()), result);
            }
            if (std::optional<Error> failed = env->read_error())
                return missing_or(*failed, env->error_reported, out, missing);
        }
        write_channels(result, env->shape_of.channels, out);
        return {};
    }

    // Opens environment map `name`: an environment pyramid file tile by tile; any other file's
    // pyramids built, kept whole or, with a cache folder, written there once and read tile by
    // tile (in later runs, without building them again).
    void open_environment(EnvironmentHandle& entry, const std::string& name) {
        if (is_environment_pyramid_file(name)) return open_stored_environment(entry, name);
        // Only into a cache folder given (see texture_system.h, "Bounded memory").
        const fs::path cached =
            options_.cache_dir.empty() || default_cache_
                ? fs::path()
                : cached_pyramid_file(name, options_, WrapMode::repeat, WrapMode::clamp, "env");
        std::error_code ec;
        if (!cached.empty() && fs::exists(cached, ec))
            return open_stored_environment(entry, cached.string());
        EnvImageOptions load;
        load.image.encoding = options_.color;
        Result<EnvironmentMap> map = load_environment({fs::path(name)}, load);
        if (!map) return void(entry.error = map.error());
        if (cached.empty()) {
            entry.value = std::make_shared<const EnvironmentMap>(std::move(*map));
            return held_whole(entry);
        }
        const int tile = std::clamp(options_.tile_size, 16, 1024);
        if (Status saved = save_environment_pyramid(*map, cached, tile); !saved)
            return void(entry.error = Error{"cannot cache the environment pyramids of '" + name +
                                            "': " + saved.error().message});
        open_stored_environment(entry, cached.string());
    }

    // The environment pyramid file `file` (envmap/env_pyramid_file.h), its parts read tile by
    // tile.
    void open_stored_environment(EnvironmentHandle& entry, const std::string& file) {
        Result<detail::TiledEnvShape> shape = detail::environment_pyramid_shape(
            file, std::countr_zero(static_cast<unsigned>(options_.tile_size)));
        if (!shape) return void(entry.error = shape.error());
        for (std::size_t p = 0; p < shape->parts.size(); ++p) {
            auto part = std::make_unique<TextureHandle>(file, next_file_id_++);
            part->open_part(static_cast<int>(p), shape->parts[p], options_);
            if (part->error) return void(entry.error = part->error);
            entry.parts.push_back(std::move(part));
        }
        entry.file = file;
        entry.shape = std::move(*shape);
        // The mean colour from each face's 1×1 level, read now (outside the cache).
        entry.shape_of = {entry.shape.layout, entry.shape.texel_scale(), entry.shape.channels()};
        for (int f = 0; f < entry.shape.face_count(); ++f) {
            TextureHandle& part = *entry.parts[f];
            float texel[texel_stride(MipPyramid::kMaxChannels)];
            part.read_tile(part.info.levels - 1, 0, 0, texel);
            if (part.read_failed) return void(entry.error = *part.read_error);
            add_face_mean(texel, entry.shape.face_count(), entry.shape_of);
        }
    }

    // Opens bump map `name`: a bump pyramid file tile by tile; a normal map decoded and its pyramid
    // built, kept whole or, with a cache folder, written there once and read tile by tile.
    void open_bump(BumpHandle& entry, const std::string& name) {
        if (bump_pyramid_file_offset(name)) return open_stored_bump(entry, name, name);
        const fs::path cached =
            options_.cache_dir.empty()
                ? fs::path()
                : cached_pyramid_file(name, options_, WrapMode::repeat, WrapMode::repeat, "bump");
        std::error_code ec;
        if (!cached.empty() && fs::exists(cached, ec))
            return open_stored_bump(entry, cached.string(), name);
        Result<Image> slopes = load_slope_map(name);
        Result<BumpPyramid> pyramid =
            slopes ? BumpPyramid::build(*slopes) : Result<BumpPyramid>(slopes.error());
        if (!pyramid) return void(entry.error = pyramid.error());
        if (cached.empty()) {
            entry.value = std::make_shared<const BumpPyramid>(std::move(*pyramid));
            return held_whole(entry);
        }
        const int tile = std::clamp(options_.tile_size, 16, 1024);
        if (Status saved = save_bump_pyramid(*pyramid, cached, tile); !saved) {
            if (!default_cache_)
                return void(entry.error = Error{"cannot cache the bump pyramid of '" + name +
                                                "': " + saved.error().message});
            warn(Error{"texture system: cannot cache the bump pyramid of '" + name +
                       "' (held in memory instead): " + saved.error().message});
            entry.value = std::make_shared<const BumpPyramid>(std::move(*pyramid));
            return held_whole(entry);
        }
        open_stored_bump(entry, cached.string(), name);
    }

    // The bump map `name` read from `file`, a bump pyramid file, as a tiled texture of moments.
    void open_stored_bump(BumpHandle& entry, const std::string& file, const std::string& name) {
        TextureHandle* moments = handle(file);
        Result<TextureInfo> info = this->info(moments);
        if (!info) return void(entry.error = info.error());
        if (!info->tiled || info->channels != 5 || !moments->slope_offset)
            return void(entry.error = Error{"cannot read '" + name +
                                            "': not a tiled bump pyramid of 5 moment channels"});
        entry.moments = moments;
        entry.slope_offset = *moments->slope_offset;
    }

    // The entry of `name` in `table`, opened by `open` on first use.
    template <class Entry, class Open>
    Entry* open_whole(FileTable<Entry>& table, std::string_view name, const Open& open) {
        auto [entry, added] = table.find_or_add(name, [] { return std::make_unique<Entry>(); });
        std::call_once(entry->opened, [&, entry = entry] { open(*entry); });
        return entry;
    }

    // A new entry `name` in `table` holding `map`.
    template <class Entry, class Map>
    Result<Entry*> add_whole(FileTable<Entry>& table, std::string_view name, Map map) {
        auto [entry, added] = table.find_or_add(name, [] { return std::make_unique<Entry>(); });
        if (!added) return name_taken(name);
        std::call_once(entry->opened, [&, entry = entry] {
            entry->value = std::make_shared<const Map>(std::move(map));
            held_whole(*entry);
        });
        return entry;
    }

    static Error name_taken(std::string_view name) {
        return Error{"texture system: the name '" + std::string(name) + "' is already in use"};
    }

    // What is known of an entry whose map is held whole: its texels (stats().bytes_in_memory),
    // and an environment map's shape (environment_shape()).
    void held_whole(EnvironmentHandle& entry) {
        const EnvironmentMap& map = *entry.value;
        entry.shape_of = {map.layout(), map.texel_scale(), map.channels()};
        for (int f = 0; f < map.face_count(); ++f) {
            const MipPyramid& face = map.face(f);
            add_face_mean(face.texel(face.max_level(), 0, 0), map.face_count(), entry.shape_of);
            hold_whole(pyramid_bytes(face));
        }
    }
    // One face's 1×1 texel's share of the map's mean colour (EnvironmentShape::mean).
    static void add_face_mean(const float* texel, int faces, EnvironmentShape& shape) {
        for (int c = 0; c < shape.channels; ++c)
            shape.mean[c] += texel[c] / static_cast<float>(faces);
    }
    void held_whole(BumpHandle& entry) { hold_whole(pyramid_bytes(entry.value->moments())); }
    // Texels held whole from now on: bytes_in_memory, and resident with the tiles.
    void hold_whole(std::size_t bytes) {
        bytes_in_memory_ += bytes;
        cache_.accounting()->add(bytes);
    }

    static std::size_t pyramid_bytes(const MipPyramid& pyramid) {
        std::size_t texels = 0;
        for (int l = 0; l < pyramid.level_count(); ++l)
            texels += static_cast<std::size_t>(pyramid.width(l)) * pyramid.height(l);
        return texels * pyramid.stride() * sizeof(float);
    }

    static void write_channels(const float* result, int channels, std::span<float> out) {
        for (std::size_t k = 0; k < out.size(); ++k)
            out[k] = k < static_cast<std::size_t>(channels) ? result[k] : 0.0f;
    }

    // A lookup that failed with `error`: the missing colour and success, the error reported once,
    // if the caller gave one; else the error.
    Status missing_or(const Error& error, std::atomic<bool>& reported, std::span<float> out,
                      std::span<const float> missing) {
        if (missing.empty()) return error;
        for (std::size_t k = 0; k < out.size(); ++k) out[k] = k < missing.size() ? missing[k] : 0;
        if (!reported.exchange(true)) report(error);
        return {};
    }

    void report(const Error& error) {
        std::lock_guard lock(errors_mutex_);
        errors_.push_back(error);
    }
    void warn(const Error& warning) {
        std::lock_guard lock(errors_mutex_);
        warnings_.push_back(warning);
    }

    const TextureSystemOptions options_;
    const bool default_cache_;
    texsys::TileCache cache_;
    texsys::PerThreadTiles thread_tiles_;
    std::atomic<std::uint32_t> next_file_id_{0};
    std::atomic<std::size_t> bytes_in_memory_{0};
    FileTable<TextureHandle> files_;
    FileTable<EnvironmentHandle> environments_;
    FileTable<BumpHandle> bumps_;
    std::mutex errors_mutex_;
    std::vector<Error> errors_, warnings_;
};

}  // namespace

TextureHandle* detail::texture_handle(TextureSystem& system, std::string_view name,
                                      const OpenAs& as) {
    return static_cast<TextureSystemImpl&>(system).handle(name, as);
}

Status detail::read_texels(TextureSystem& system, TextureHandle* file,
                           const std::function<void(const TexelReader&)>& read) {
    return static_cast<TextureSystemImpl&>(system).read_texels(file, read);
}

Result<std::unique_ptr<TextureSystem>> TextureSystem::create(const TextureSystemOptions& options) {
    if (options.max_memory_mb < 1)
        return Error{"texture system: max_memory_mb must be at least 1 (got 0)"};
    if (options.tile_size < 8 || options.tile_size > 1024 ||
        !std::has_single_bit(static_cast<unsigned>(options.tile_size)))
        return Error{"texture system: tile_size must be a power of two from 8 to 1024 (got " +
                     std::to_string(options.tile_size) + ")"};
    if (!options.cache_dir.empty() && options.build_in_memory)
        return Error{"texture system: cache_dir '" + options.cache_dir.string() +
                     "' and build_in_memory: give one of them"};
    TextureSystemOptions resolved = options;
    const bool default_cache = options.cache_dir.empty() && !options.build_in_memory;
    if (default_cache) resolved.cache_dir = default_texture_cache_dir();
    std::optional<Error> warning;
    if (!resolved.cache_dir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(resolved.cache_dir, ec);
        if (ec || !std::filesystem::is_directory(resolved.cache_dir)) {
            const std::string why =
                "cannot use the " + std::string(default_cache ? "default " : "") +
                "cache folder '" + resolved.cache_dir.string() +
                "': " + (ec ? ec.message() : std::string("it is not a directory"));
            if (!default_cache) return Error{"texture system: " + why};
            warning = Error{"texture system: " + why + " (pyramids are built in memory)"};
            resolved.cache_dir.clear();
        }
    } else if (default_cache) {
        warning = Error{
            "texture system: neither XDG_CACHE_HOME nor HOME is set: no default cache folder "
            "(pyramids are built in memory)"};
    }
    return std::unique_ptr<TextureSystem>(
        std::make_unique<TextureSystemImpl>(resolved, default_cache, std::move(warning)));
}

std::filesystem::path default_texture_cache_dir() {
    // The XDG Base Directory rule: a relative XDG_CACHE_HOME is invalid and ignored.
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    if (xdg != nullptr && *xdg != '\0' && std::filesystem::path(xdg).is_absolute())
        return std::filesystem::path(xdg) / "footprint";
    const char* home = std::getenv("HOME");
    if (home != nullptr && *home != '\0')
        return std::filesystem::path(home) / ".cache" / "footprint";
    return {};
}

}  // namespace footprint
