#include "texsys/tile_cache.h"

#include <algorithm>

namespace footprint::texsys {

void Accounting::add(std::size_t bytes) {
    const std::size_t now = resident.fetch_add(bytes, std::memory_order_relaxed) + bytes;
    std::size_t peak_now = peak.load(std::memory_order_relaxed);
    while (now > peak_now && !peak.compare_exchange_weak(peak_now, now)) {
    }
}

Tile::Tile(std::size_t floats, std::shared_ptr<Accounting> accounting_)
    : texels(new float[floats]), bytes(floats * sizeof(float)), accounting(std::move(accounting_)) {
    accounting->add(bytes);
}

Tile::~Tile() {
    accounting->remove(bytes);
}

TileCache::TileCache(std::size_t max_bytes) : max_bytes_(max_bytes) {}

TilePtr TileCache::get(const TileKey& key, std::size_t floats,
                       const std::function<void(float*)>& load) {
    // Under the lock only the map and the recency list: a miss allocates its tile before taking
    // it, and the tiles it evicts are released after (their texels freed), so that another thread
    // waits for neither the allocator nor the page faults of a tile that is not its own.
    TilePtr tile, fresh;
    std::vector<TilePtr> evicted;
    for (;;) {
        {
            std::lock_guard lock(mutex_);
            auto found = entries_.find(key);
            if (found != entries_.end()) {
                recency_.splice(recency_.begin(), recency_, found->second.recency);
                tile = found->second.tile;
                accounting_->hits.fetch_add(1, std::memory_order_relaxed);
            } else if (fresh) {
                tile = std::move(fresh);
                recency_.push_front(key);
                entries_.emplace(key, Entry{tile, recency_.begin()});
                cached_bytes_ += tile->bytes;
                evict_beyond_budget(evicted);
                accounting_->misses.fetch_add(1, std::memory_order_relaxed);
            }
        }
        if (tile) break;
        fresh = std::make_shared<Tile>(floats, accounting_);  // then look again
    }
    evicted.clear();
    fresh.reset();  // another thread cached the tile first
    // Outside the lock, so that a thread reading a tile from disk holds up only the threads
    // that want that tile.
    std::call_once(tile->loaded, [&] {
        load(tile->texels.get());
        accounting_->loaded.fetch_add(1, std::memory_order_relaxed);
    });
    return tile;
}

void TileCache::evict_beyond_budget(std::vector<TilePtr>& evicted) {
    // The newest tile (at the front) stays even alone beyond the budget: its lookup needs it.
    while (cached_bytes_ > max_bytes_ && recency_.size() > 1) {
        auto victim = entries_.find(recency_.back());
        cached_bytes_ -= victim->second.tile->bytes;
        evicted.push_back(std::move(victim->second.tile));
        entries_.erase(victim);
        recency_.pop_back();
    }
}

namespace {
std::atomic<std::uint64_t> next_per_thread_tiles_id{1};
}  // namespace

PerThreadTiles::PerThreadTiles() : id_(next_per_thread_tiles_id++) {}

ThreadTiles& PerThreadTiles::local() {
    // The thread's set is found in tiles_ once per change of system; most lookups follow one on
    // the same system. A note that names this id names this object: ids are never reused.
    thread_local struct {
        std::uint64_t id = 0;
        ThreadTiles* tiles = nullptr;
    } last;
    if (last.id != id_) last = {id_, &tiles_.local()};
    return *last.tiles;
}

}  // namespace footprint::texsys
