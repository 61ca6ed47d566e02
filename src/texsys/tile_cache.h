// texsys/tile_cache.h — the texture system's shared tile cache and each thread's view of it
// (private to the texture system).
//
// TileCache maps a tile's key to its texels, loads a tile on its first request (once, whichever
// threads ask for it at the same time) and evicts least-recently-used tiles when the cached texels
// exceed its budget. A tile lives as long as someone holds it: the cache, or a thread that pinned
// it (ThreadTiles). Tiles count themselves in Accounting from allocation to release, so
// bytes_resident is what is really held, pinned tiles evicted from the cache included.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "texture/tiled_texels.h"

namespace footprint::texsys {

// Which tile: a file of the texture system, a MIP level, a tile column and row.
struct TileKey {
    std::uint32_t file = 0;
    std::uint32_t level = 0;
    std::uint32_t tx = 0, ty = 0;
    bool operator==(const TileKey&) const = default;
};
struct TileKeyHash {
    std::size_t operator()(const TileKey& k) const {
        std::uint64_t h = (std::uint64_t(k.file) << 40) ^ (std::uint64_t(k.level) << 34) ^
                          (std::uint64_t(k.ty) << 17) ^ k.tx;
        h ^= h >> 29;
        h *= 0xbf58476d1ce4e5b9ull;
        return static_cast<std::size_t>(h ^ (h >> 32));
    }
};

// What the tiles hold, shared by the cache and every tile (which may outlive the cache).
struct Accounting {
    std::atomic<std::size_t> resident{0}, peak{0};
    std::atomic<std::size_t> loaded{0}, hits{0}, misses{0};
    void add(std::size_t bytes);
    void remove(std::size_t bytes) { resident.fetch_sub(bytes, std::memory_order_relaxed); }
};

struct Tile {
    Tile(std::size_t floats, std::shared_ptr<Accounting> accounting);
    ~Tile();
    Tile(const Tile&) = delete;
    Tile& operator=(const Tile&) = delete;

    std::unique_ptr<float[]> texels;
    std::size_t bytes;
    std::once_flag loaded;
    std::shared_ptr<Accounting> accounting;
};
using TilePtr = std::shared_ptr<Tile>;

class TileCache {
  public:
    explicit TileCache(std::size_t max_bytes);

    // The tile of `key`, `floats` floats, filled by load(texels) on its first request.
    TilePtr get(const TileKey& key, std::size_t floats, const std::function<void(float*)>& load);

    const std::shared_ptr<Accounting>& accounting() const { return accounting_; }

  private:
    struct Entry {
        TilePtr tile;
        std::list<TileKey>::iterator recency;
    };
    // Under mutex_: drops the least recently used tiles beyond the budget into `evicted`, for the
    // caller to release after the lock.
    void evict_beyond_budget(std::vector<TilePtr>& evicted);

    std::size_t max_bytes_;
    std::shared_ptr<Accounting> accounting_ = std::make_shared<Accounting>();
    std::mutex mutex_;
    std::unordered_map<TileKey, Entry, TileKeyHash> entries_;
    std::list<TileKey> recency_;  // most recently used first
    std::size_t cached_bytes_ = 0;
};

// One thread's tiles of one texture system: the micro-cache, the most recent tiles last, which
// also pins every tile of the lookup in progress (a lookup's taps point into them); and the tiles
// at hand of its last lookups through tiles, for each of its last few files (an environment map's
// faces and caps are a file each), which point into tiles of `recent`: kept for the next lookup
// on that file until one of those is let go (let_go()).
struct ThreadTiles {
    std::vector<std::pair<TileKey, TilePtr>> recent;

    // The tiles at hand on `file`: those of its last lookup while none was let go since, else
    // none (the slots of the file least recently given a new set).
    detail::TiledTexels::Slots& slots_for(std::uint32_t file) {
        FileSlots* entry = &files_[last_];  // most lookups are on the file of the last one
        if (entry->file != file) {
            entry = nullptr;
            for (std::size_t i = 0; i < files_.size() && !entry; ++i)
                if (files_[i].file == file) entry = &files_[last_ = i];
        }
        if (!entry) {
            entry = &files_[last_ = next_victim_];
            next_victim_ = (next_victim_ + 1) % files_.size();
            entry->file = file;
            entry->generation = generation_ - 1;
        }
        if (entry->generation != generation_) {
            entry->slots.clear();
            entry->generation = generation_;
        }
        return entry->slots;
    }
    // Tiles of `recent` were let go: every file's tiles at hand may point into them.
    void let_go() { ++generation_; }

  private:
    struct FileSlots {
        std::uint32_t file = ~std::uint32_t(0);
        std::uint64_t generation = 0;
        detail::TiledTexels::Slots slots;
    };
    std::array<FileSlots, 12> files_;
    std::size_t last_ = 0, next_victim_ = 0;
    std::uint64_t generation_ = 1;
};

// Each thread's ThreadTiles of one texture system, owned by the system: they, and the tiles they
// pin, are freed with it, whichever threads made them. A thread's set stays until then (it is
// a cache: a later thread may be given a finished one's).
class PerThreadTiles {
  public:
    PerThreadTiles();
    // The calling thread's.
    ThreadTiles& local();

  private:
    const std::uint64_t id_;  // never reused (see local())
    tbb::enumerable_thread_specific<ThreadTiles> tiles_;
};

}  // namespace footprint::texsys
