// The OpenImageIO adapter (oiio/texture_system.h). Each lookup is answered in three steps:
//   1. check the handle and the arguments: a hostile value returns false with a message before
//      anything reads it (OpenImageIO 2.4.7 itself crashes on some: docs/library.md);
//   2. footprint answers what it filters (oiio/oiio_lookups.h), with OpenImageIO's meaning;
//   3. anything else goes to the OpenImageIO TextureSystem the adapter owns (the delegate), with
//      the same arguments.
// Every other call of the interface (metadata, texels, UDIM queries, attributes, 3D textures,
// shadows) is the delegate's: it reads the files as OpenImageIO reads them.
#include "oiio/texture_system.h"

#include <OpenImageIO/imagecache.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "oiio/oiio_lookups.h"

namespace footprint::oiio {

namespace {

using OIIO::ImageSpec;
using OIIO::TextureOpt;
using OIIO::TextureOptBatch;
using OIIO::TypeDesc;
using OIIO::ustring;
using Handle = OIIO::TextureSystem::TextureHandle;
using Perthread = OIIO::TextureSystem::Perthread;
using V3fParam = OIIO::V3fParam;
namespace Tex = OIIO::Tex;

thread_local std::string t_create_error;

// What the adapter knows of a file it gave a handle for: the delegate's handle, and OpenImageIO's
// view of the file, read once through the delegate.
struct File {
    static constexpr std::uint64_t kMagic = 0x666f6f747072696eULL;  // "footprin"
    std::uint64_t magic = kMagic;
    ustring name;
    Handle* delegate = nullptr;
    bool udim = false;  // a UDIM set's name, resolved per lookup
    std::once_flag probed;
    std::atomic<bool> probed_done{false};
    detail::FileFacts facts;
    std::unique_ptr<detail::Entries> entries;  // footprint's entries of the file
    // detail::direct_entry() of the file, found on the first call with default options.
    std::once_flag direct_found;
    std::atomic<bool> direct_done{false};
    footprint::TextureHandle* direct = nullptr;
};

class Adapter final : public OIIO::TextureSystem {
  public:
    explicit Adapter(const TextureSystemOptions& options)
        : options_(options), delegate_(OIIO::TextureSystem::create(/*shared=*/false)) {
        options_.color = ColorEncoding::linear;  // values as stored, as OpenImageIO returns them
        // footprint MIP-maps a file without levels; the delegate does too, so that a lookup
        // reads the same levels whichever answers it (docs/library.md).
        delegate_->attribute("automip", 1);
        delegate_->attribute("max_memory_MB", static_cast<float>(options_.max_memory_mb));
    }
    ~Adapter() override {
        for (Perthread* info : retired_) delegate_->destroy_thread_info(info);
        OIIO::TextureSystem::destroy(delegate_, /*teardown_imagecache=*/true);
    }
    Adapter(const Adapter&) = delete;
    Adapter& operator=(const Adapter&) = delete;
    // OpenImageIO's TextureSystem hides its operator delete (its objects are destroyed through
    // TextureSystem::destroy()); the adapter is destroyed as its own type.
    static void operator delete(void* p) { ::operator delete(p); }

    // ---- Attributes: kept by the delegate (OpenImageIO's names, types and defaults).
    // max_memory_MB also bounds footprint's cache when it is set before the first lookup.
    bool attribute(OIIO::string_view name, TypeDesc type, const void* val) override {
        if (name == "max_memory_MB" && type == TypeDesc::FLOAT) {
            std::lock_guard lock(footprint_mutex_);
            if (!footprint_)
                options_.max_memory_mb = static_cast<std::size_t>(
                    std::clamp(*static_cast<const float*>(val), 1.0f, 1e7f));
        }
        const bool set = delegate_->attribute(name, type, val);
        read_settings();
        return set;
    }
    bool attribute(OIIO::string_view name, int val) override {
        return attribute(name, TypeDesc::INT, &val);
    }
    bool attribute(OIIO::string_view name, float val) override {
        return attribute(name, TypeDesc::FLOAT, &val);
    }
    bool attribute(OIIO::string_view name, double val) override {
        const float f = static_cast<float>(val);
        return attribute(name, TypeDesc::FLOAT, &f);
    }
    bool attribute(OIIO::string_view name, OIIO::string_view val) override {
        const std::string text(val);
        const char* c = text.c_str();
        return attribute(name, TypeDesc::STRING, &c);
    }
    bool getattribute(OIIO::string_view name, TypeDesc type, void* val) const override {
        return delegate_->getattribute(name, type, val);
    }
    bool getattribute(OIIO::string_view name, int& val) const override {
        return delegate_->getattribute(name, val);
    }
    bool getattribute(OIIO::string_view name, float& val) const override {
        return delegate_->getattribute(name, val);
    }
    bool getattribute(OIIO::string_view name, double& val) const override {
        return delegate_->getattribute(name, val);
    }
    bool getattribute(OIIO::string_view name, char** val) const override {
        return delegate_->getattribute(name, val);
    }
    bool getattribute(OIIO::string_view name, std::string& val) const override {
        return delegate_->getattribute(name, val);
    }
    TypeDesc getattributetype(OIIO::string_view name) const override {
        return delegate_->getattributetype(name);
    }

    // ---- Per-thread info (the delegate's) and handles (the adapter's Files).
    Perthread* get_perthread_info(Perthread* thread_info) override {
        return delegate_->get_perthread_info(thread_info);
    }
    // OpenImageIO 2.4.7's destroy_thread_info() leaves a null in its image cache's list of
    // per-thread infos, which getstats() and reset_stats() then dereference: a crash. So a
    // destroyed info is kept, handed out again by the next create_thread_info(), and given back
    // to the delegate with the adapter.
    Perthread* create_thread_info() override {
        {
            std::lock_guard lock(retired_mutex_);
            if (!retired_.empty()) {
                Perthread* reused = retired_.back();
                retired_.pop_back();
                return reused;
            }
        }
        return delegate_->create_thread_info();
    }
    void destroy_thread_info(Perthread* thread_info) override {
        if (!thread_info) return;
        std::lock_guard lock(retired_mutex_);
        if (std::find(retired_.begin(), retired_.end(), thread_info) == retired_.end())
            retired_.push_back(thread_info);
    }
    Handle* get_texture_handle(ustring filename, Perthread* thread_info) override {
        return reinterpret_cast<Handle*>(file(filename, thread_info));
    }
    bool good(Handle* handle) override {
        File* f = from_handle(handle);
        return f && delegate_->good(f->delegate);
    }
    ustring filename_from_handle(Handle* handle) override {
        File* f = from_handle(handle);
        return f ? f->name : ustring();
    }

    // ---- 2D texture lookups.
    bool texture(ustring filename, TextureOpt& options, float s, float t, float dsdx, float dtdx,
                 float dsdy, float dtdy, int nchannels, float* result, float* dresultds,
                 float* dresultdt) override {
        Perthread* thread_info = get_perthread_info(nullptr);
        return texture(get_texture_handle(filename, thread_info), thread_info, options, s, t, dsdx,
                       dtdx, dsdy, dtdy, nchannels, result, dresultds, dresultdt);
    }

    bool texture(Handle* handle, Perthread* thread_info, TextureOpt& options, float s, float t,
                 float dsdx, float dtdx, float dsdy, float dtdy, int nchannels, float* result,
                 float* dresultds, float* dresultdt) override {
        File* f = from_handle(handle);
        if (!f) {
            count(&Counts::texture_others);
            return refuse("texture(): not a texture handle of this system", nchannels, result,
                          dresultds, dresultdt);
        }
        static constexpr const char* names[] = {"s", "t", "dsdx", "dtdx", "dsdy", "dtdy"};
        const float coords[] = {s, t, dsdx, dtdx, dsdy, dtdy};
        // Most calls of a renderer: OpenImageIO's default options on a plain texture, the
        // values in range, as many channels as the file has or fewer, no derivatives. They skip
        // the checks and the routing that find footprint assembly for them (oiio_lookups.h).
        if (detail::direct_options(options) && !dresultds && !dresultdt && result &&
            nchannels > 0 && detail::values_in_range(coords, 6)) {
            const detail::Settings now = settings();
            footprint::TextureHandle* entry = direct_entry(*f, thread_info);
            if (entry && nchannels <= f->facts.nchannels && !now.flip_t &&
                std::max(f->facts.width, f->facts.height) <= now.max_mip_res) {
                std::string error;
                const std::optional<bool> answered = detail::direct_texture(
                    footprint(), entry, f->facts.width, f->facts.height, options,
                    {s, t, dsdx, dtdx, dsdy, dtdy}, nchannels, result, error);
                if (answered) {
                    count(&Counts::texture_answered);
                    if (!*answered) append_error(error);
                    return *answered;
                }
            }
        }
        if (std::string why = check_call(*f, thread_info, options, names, coords, 6, nchannels,
                                         result, dresultds, dresultdt);
            !why.empty()) {
            count(&Counts::texture_others);
            return refuse("texture(): " + why + " (texture '" + f->name.string() + "')", nchannels,
                          result, dresultds, dresultdt);
        }
        // A UDIM set is resolved to its tile as OpenImageIO resolves it.
        File* tile = f;
        float ts = s, tt = t;
        if (f->udim) {
            Handle* resolved = delegate_->resolve_udim(f->delegate, thread_info, s, t);
            tile =
                resolved ? file(delegate_->filename_from_handle(resolved), thread_info) : nullptr;
            ts -= std::floor(ts);
            tt -= std::floor(tt);
        }
        if (tile) {
            std::string error;
            const std::optional<bool> answered = detail::footprint_texture(
                footprint(), *tile->entries, facts(*tile, thread_info), settings(), options,
                {ts, tt, dsdx, dtdx, dsdy, dtdy}, nchannels, result, dresultds, dresultdt, error);
            if (answered) {
                count(&Counts::texture_answered);
                if (!*answered) append_error(error);
                return *answered;
            }
        }
        count(&Counts::texture_others);
        const bool ok = delegate_->texture(f->delegate, thread_info, options, s, t, dsdx, dtdx,
                                           dsdy, dtdy, nchannels, result, dresultds, dresultdt);
        if (!ok) explain_missing(tile ? *tile : *f, thread_info, "texture");
        return ok;
    }

    bool texture(ustring filename, TextureOptBatch& options, Tex::RunMask mask, const float* s,
                 const float* t, const float* dsdx, const float* dtdx, const float* dsdy,
                 const float* dtdy, int nchannels, float* result, float* dresultds,
                 float* dresultdt) override {
        Perthread* thread_info = get_perthread_info(nullptr);
        return texture(get_texture_handle(filename, thread_info), thread_info, options, mask, s, t,
                       dsdx, dtdx, dsdy, dtdy, nchannels, result, dresultds, dresultdt);
    }

    bool texture(Handle* handle, Perthread* thread_info, TextureOptBatch& options,
                 Tex::RunMask mask, const float* s, const float* t, const float* dsdx,
                 const float* dtdx, const float* dsdy, const float* dtdy, int nchannels,
                 float* result, float* dresultds, float* dresultdt) override {
        return each_lane("texture", handle, {s, t, dsdx, dtdx, dsdy, dtdy}, options, mask,
                         nchannels, result, dresultds, dresultdt,
                         [&](int i, TextureOpt& opt, float* r, float* ds, float* dt) {
                             return texture(handle, thread_info, opt, s[i], t[i], dsdx[i], dtdx[i],
                                            dsdy[i], dtdy[i], nchannels, r, ds, dt);
                         });
    }

    // The multi-point calls OpenImageIO deprecated in 1.8: their points one by one.
    bool texture(ustring filename, OIIO::TextureOptions& options, OIIO::Runflag* runflags,
                 int beginactive, int endactive, OIIO::VaryingRef<float> s,
                 OIIO::VaryingRef<float> t, OIIO::VaryingRef<float> dsdx,
                 OIIO::VaryingRef<float> dtdx, OIIO::VaryingRef<float> dsdy,
                 OIIO::VaryingRef<float> dtdy, int nchannels, float* result, float* dresultds,
                 float* dresultdt) override {
        Perthread* thread_info = get_perthread_info(nullptr);
        return texture(get_texture_handle(filename, thread_info), thread_info, options, runflags,
                       beginactive, endactive, s, t, dsdx, dtdx, dsdy, dtdy, nchannels, result,
                       dresultds, dresultdt);
    }
    bool texture(Handle* handle, Perthread* thread_info, OIIO::TextureOptions& options,
                 OIIO::Runflag* runflags, int beginactive, int endactive, OIIO::VaryingRef<float> s,
                 OIIO::VaryingRef<float> t, OIIO::VaryingRef<float> dsdx,
                 OIIO::VaryingRef<float> dtdx, OIIO::VaryingRef<float> dsdy,
                 OIIO::VaryingRef<float> dtdy, int nchannels, float* result, float* dresultds,
                 float* dresultdt) override {
        bool ok = true;
        for (int i = beginactive; i < endactive; ++i) {
            if (!runflags[i]) continue;
            TextureOpt opt(options, i);
            const std::size_t at = static_cast<std::size_t>(i) * nchannels;
            ok &= texture(handle, thread_info, opt, s[i], t[i], dsdx[i], dtdx[i], dsdy[i], dtdy[i],
                          nchannels, result + at, dresultds ? dresultds + at : nullptr,
                          dresultdt ? dresultdt + at : nullptr);
        }
        return ok;
    }

    // ---- Environment lookups.
    bool environment(ustring filename, TextureOpt& options, V3fParam R, V3fParam dRdx,
                     V3fParam dRdy, int nchannels, float* result, float* dresultds,
                     float* dresultdt) override {
        Perthread* thread_info = get_perthread_info(nullptr);
        return environment(get_texture_handle(filename, thread_info), thread_info, options, R, dRdx,
                           dRdy, nchannels, result, dresultds, dresultdt);
    }

    bool environment(Handle* handle, Perthread* thread_info, TextureOpt& options, V3fParam R,
                     V3fParam dRdx, V3fParam dRdy, int nchannels, float* result, float* dresultds,
                     float* dresultdt) override {
        File* f = from_handle(handle);
        if (!f) {
            count(&Counts::environment_others);
            return refuse("environment(): not a texture handle of this system", nchannels, result,
                          dresultds, dresultdt);
        }
        const Imath::V3f r = R.cast<Imath::V3f>(), rx = dRdx.cast<Imath::V3f>(),
                         ry = dRdy.cast<Imath::V3f>();
        static constexpr const char* names[] = {"R.x",    "R.y",    "R.z",    "dRdx.x", "dRdx.y",
                                                "dRdx.z", "dRdy.x", "dRdy.y", "dRdy.z"};
        const float values[] = {r.x, r.y, r.z, rx.x, rx.y, rx.z, ry.x, ry.y, ry.z};
        std::string why = check_call(*f, thread_info, options, names, values, 9, nchannels, result,
                                     dresultds, dresultdt);
        if (why.empty() && r.length2() == 0) why = "the direction R is zero";
        if (!why.empty()) {
            count(&Counts::environment_others);
            return refuse("environment(): " + why + " (environment '" + f->name.string() + "')",
                          nchannels, result, dresultds, dresultdt);
        }
        std::string error;
        const std::optional<bool> answered = detail::footprint_environment(
            footprint(), *f->entries, facts(*f, thread_info), options, r, rx, ry, nchannels, result,
            dresultds, dresultdt, error);
        if (answered) {
            count(&Counts::environment_answered);
            if (!*answered) append_error(error);
            return *answered;
        }
        count(&Counts::environment_others);
        const bool ok = delegate_->environment(f->delegate, thread_info, options, R, dRdx, dRdy,
                                               nchannels, result, dresultds, dresultdt);
        if (!ok) explain_missing(*f, thread_info, "environment");
        return ok;
    }

    bool environment(ustring filename, TextureOptBatch& options, Tex::RunMask mask, const float* R,
                     const float* dRdx, const float* dRdy, int nchannels, float* result,
                     float* dresultds, float* dresultdt) override {
        Perthread* thread_info = get_perthread_info(nullptr);
        return environment(get_texture_handle(filename, thread_info), thread_info, options, mask, R,
                           dRdx, dRdy, nchannels, result, dresultds, dresultdt);
    }

    bool environment(Handle* handle, Perthread* thread_info, TextureOptBatch& options,
                     Tex::RunMask mask, const float* R, const float* dRdx, const float* dRdy,
                     int nchannels, float* result, float* dresultds, float* dresultdt) override {
        constexpr int W = Tex::BatchWidth;
        return each_lane("environment", handle, {R, dRdx, dRdy}, options, mask, nchannels, result,
                         dresultds, dresultdt,
                         [&](int i, TextureOpt& opt, float* r, float* ds, float* dt) {
                             const auto lane = [&](const float* v) {
                                 return Imath::V3f(v[i], v[i + W], v[i + 2 * W]);
                             };
                             return environment(handle, thread_info, opt, lane(R), lane(dRdx),
                                                lane(dRdy), nchannels, r, ds, dt);
                         });
    }

    bool environment(ustring filename, OIIO::TextureOptions& options, OIIO::Runflag* runflags,
                     int beginactive, int endactive, OIIO::VaryingRef<Imath::V3f> R,
                     OIIO::VaryingRef<Imath::V3f> dRdx, OIIO::VaryingRef<Imath::V3f> dRdy,
                     int nchannels, float* result, float* dresultds, float* dresultdt) override {
        Perthread* thread_info = get_perthread_info(nullptr);
        return environment(get_texture_handle(filename, thread_info), thread_info, options,
                           runflags, beginactive, endactive, R, dRdx, dRdy, nchannels, result,
                           dresultds, dresultdt);
    }
    bool environment(Handle* handle, Perthread* thread_info, OIIO::TextureOptions& options,
                     OIIO::Runflag* runflags, int beginactive, int endactive,
                     OIIO::VaryingRef<Imath::V3f> R, OIIO::VaryingRef<Imath::V3f> dRdx,
                     OIIO::VaryingRef<Imath::V3f> dRdy, int nchannels, float* result,
                     float* dresultds, float* dresultdt) override {
        bool ok = true;
        for (int i = beginactive; i < endactive; ++i) {
            if (!runflags[i]) continue;
            TextureOpt opt(options, i);
            const std::size_t at = static_cast<std::size_t>(i) * nchannels;
            ok &= environment(handle, thread_info, opt, R[i], dRdx[i], dRdy[i], nchannels,
                              result + at, dresultds ? dresultds + at : nullptr,
                              dresultdt ? dresultdt + at : nullptr);
        }
        return ok;
    }

    // ---- What footprint does not filter: the delegate's, on its own handle.
    bool texture3d(ustring filename, TextureOpt& options, V3fParam P, V3fParam dPdx, V3fParam dPdy,
                   V3fParam dPdz, int nchannels, float* result, float* dresultds, float* dresultdt,
                   float* dresultdr) override {
        return delegate_->texture3d(filename, options, P, dPdx, dPdy, dPdz, nchannels, result,
                                    dresultds, dresultdt, dresultdr);
    }
    bool texture3d(Handle* handle, Perthread* thread_info, TextureOpt& options, V3fParam P,
                   V3fParam dPdx, V3fParam dPdy, V3fParam dPdz, int nchannels, float* result,
                   float* dresultds, float* dresultdt, float* dresultdr) override {
        File* f = from_handle(handle);
        if (!f)
            return refuse("texture3d(): not a texture handle of this system", nchannels, result,
                          dresultds, dresultdt);
        return delegate_->texture3d(f->delegate, thread_info, options, P, dPdx, dPdy, dPdz,
                                    nchannels, result, dresultds, dresultdt, dresultdr);
    }
    bool texture3d(ustring filename, TextureOptBatch& options, Tex::RunMask mask, const float* P,
                   const float* dPdx, const float* dPdy, const float* dPdz, int nchannels,
                   float* result, float* dresultds, float* dresultdt, float* dresultdr) override {
        return delegate_->texture3d(filename, options, mask, P, dPdx, dPdy, dPdz, nchannels, result,
                                    dresultds, dresultdt, dresultdr);
    }
    bool texture3d(Handle* handle, Perthread* thread_info, TextureOptBatch& options,
                   Tex::RunMask mask, const float* P, const float* dPdx, const float* dPdy,
                   const float* dPdz, int nchannels, float* result, float* dresultds,
                   float* dresultdt, float* dresultdr) override {
        File* f = from_handle(handle);
        if (!f)
            return refuse("texture3d(): not a texture handle of this system", 0, nullptr, nullptr,
                          nullptr);
        return delegate_->texture3d(f->delegate, thread_info, options, mask, P, dPdx, dPdy, dPdz,
                                    nchannels, result, dresultds, dresultdt, dresultdr);
    }
    bool texture3d(ustring filename, OIIO::TextureOptions& options, OIIO::Runflag* runflags,
                   int beginactive, int endactive, OIIO::VaryingRef<Imath::V3f> P,
                   OIIO::VaryingRef<Imath::V3f> dPdx, OIIO::VaryingRef<Imath::V3f> dPdy,
                   OIIO::VaryingRef<Imath::V3f> dPdz, int nchannels, float* result,
                   float* dresultds, float* dresultdt, float* dresultdr) override {
        OIIO_PRAGMA_WARNING_PUSH
        OIIO_GCC_PRAGMA(GCC diagnostic ignored "-Wdeprecated-declarations")
        return delegate_->texture3d(filename, options, runflags, beginactive, endactive, P, dPdx,
                                    dPdy, dPdz, nchannels, result, dresultds, dresultdt, dresultdr);
        OIIO_PRAGMA_WARNING_POP
    }
    bool texture3d(Handle* handle, Perthread* thread_info, OIIO::TextureOptions& options,
                   OIIO::Runflag* runflags, int beginactive, int endactive,
                   OIIO::VaryingRef<Imath::V3f> P, OIIO::VaryingRef<Imath::V3f> dPdx,
                   OIIO::VaryingRef<Imath::V3f> dPdy, OIIO::VaryingRef<Imath::V3f> dPdz,
                   int nchannels, float* result, float* dresultds, float* dresultdt,
                   float* dresultdr) override {
        File* f = from_handle(handle);
        if (!f)
            return refuse("texture3d(): not a texture handle of this system", 0, nullptr, nullptr,
                          nullptr);
        OIIO_PRAGMA_WARNING_PUSH
        OIIO_GCC_PRAGMA(GCC diagnostic ignored "-Wdeprecated-declarations")
        return delegate_->texture3d(f->delegate, thread_info, options, runflags, beginactive,
                                    endactive, P, dPdx, dPdy, dPdz, nchannels, result, dresultds,
                                    dresultdt, dresultdr);
        OIIO_PRAGMA_WARNING_POP
    }

    bool shadow(ustring filename, TextureOpt& options, V3fParam P, V3fParam dPdx, V3fParam dPdy,
                float* result, float* dresultds, float* dresultdt) override {
        return delegate_->shadow(filename, options, P, dPdx, dPdy, result, dresultds, dresultdt);
    }
    bool shadow(Handle* handle, Perthread* thread_info, TextureOpt& options, V3fParam P,
                V3fParam dPdx, V3fParam dPdy, float* result, float* dresultds,
                float* dresultdt) override {
        File* f = from_handle(handle);
        if (!f)
            return refuse("shadow(): not a texture handle of this system", 1, result, dresultds,
                          dresultdt);
        return delegate_->shadow(f->delegate, thread_info, options, P, dPdx, dPdy, result,
                                 dresultds, dresultdt);
    }
    bool shadow(ustring filename, TextureOptBatch& options, Tex::RunMask mask, const float* P,
                const float* dPdx, const float* dPdy, float* result, float* dresultds,
                float* dresultdt) override {
        return delegate_->shadow(filename, options, mask, P, dPdx, dPdy, result, dresultds,
                                 dresultdt);
    }
    bool shadow(Handle* handle, Perthread* thread_info, TextureOptBatch& options, Tex::RunMask mask,
                const float* P, const float* dPdx, const float* dPdy, float* result,
                float* dresultds, float* dresultdt) override {
        File* f = from_handle(handle);
        if (!f)
            return refuse("shadow(): not a texture handle of this system", 0, nullptr, nullptr,
                          nullptr);
        return delegate_->shadow(f->delegate, thread_info, options, mask, P, dPdx, dPdy, result,
                                 dresultds, dresultdt);
    }
    bool shadow(ustring filename, OIIO::TextureOptions& options, OIIO::Runflag* runflags,
                int beginactive, int endactive, OIIO::VaryingRef<Imath::V3f> P,
                OIIO::VaryingRef<Imath::V3f> dPdx, OIIO::VaryingRef<Imath::V3f> dPdy, float* result,
                float* dresultds, float* dresultdt) override {
        OIIO_PRAGMA_WARNING_PUSH
        OIIO_GCC_PRAGMA(GCC diagnostic ignored "-Wdeprecated-declarations")
        return delegate_->shadow(filename, options, runflags, beginactive, endactive, P, dPdx, dPdy,
                                 result, dresultds, dresultdt);
        OIIO_PRAGMA_WARNING_POP
    }
    bool shadow(Handle* handle, Perthread* thread_info, OIIO::TextureOptions& options,
                OIIO::Runflag* runflags, int beginactive, int endactive,
                OIIO::VaryingRef<Imath::V3f> P, OIIO::VaryingRef<Imath::V3f> dPdx,
                OIIO::VaryingRef<Imath::V3f> dPdy, float* result, float* dresultds,
                float* dresultdt) override {
        File* f = from_handle(handle);
        if (!f)
            return refuse("shadow(): not a texture handle of this system", 0, nullptr, nullptr,
                          nullptr);
        OIIO_PRAGMA_WARNING_PUSH
        OIIO_GCC_PRAGMA(GCC diagnostic ignored "-Wdeprecated-declarations")
        return delegate_->shadow(f->delegate, thread_info, options, runflags, beginactive,
                                 endactive, P, dPdx, dPdy, result, dresultds, dresultdt);
        OIIO_PRAGMA_WARNING_POP
    }

    // ---- Files: names, metadata, texels and UDIM sets, as OpenImageIO reads them.
    std::string resolve_filename(const std::string& filename) const override {
        return delegate_->resolve_filename(filename);
    }
    bool get_texture_info(ustring filename, int subimage, ustring dataname, TypeDesc datatype,
                          void* data) override {
        if (subimage_refused("get_texture_info", filename, subimage)) return false;
        return delegate_->get_texture_info(filename, subimage, dataname, datatype, data);
    }
    bool get_texture_info(Handle* handle, Perthread* thread_info, int subimage, ustring dataname,
                          TypeDesc datatype, void* data) override {
        File* f = from_handle(handle);
        if (!f) return refuse("get_texture_info(): not a texture handle of this system");
        if (subimage_refused("get_texture_info", *f, thread_info, subimage)) return false;
        return delegate_->get_texture_info(f->delegate, thread_info, subimage, dataname, datatype,
                                           data);
    }
    bool get_imagespec(ustring filename, int subimage, ImageSpec& spec) override {
        if (subimage_refused("get_imagespec", filename, subimage)) return false;
        return delegate_->get_imagespec(filename, subimage, spec);
    }
    bool get_imagespec(Handle* handle, Perthread* thread_info, int subimage,
                       ImageSpec& spec) override {
        File* f = from_handle(handle);
        if (!f) return refuse("get_imagespec(): not a texture handle of this system");
        if (subimage_refused("get_imagespec", *f, thread_info, subimage)) return false;
        return delegate_->get_imagespec(f->delegate, thread_info, subimage, spec);
    }
    const ImageSpec* imagespec(ustring filename, int subimage) override {
        if (subimage_refused("imagespec", filename, subimage)) return nullptr;
        return delegate_->imagespec(filename, subimage);
    }
    const ImageSpec* imagespec(Handle* handle, Perthread* thread_info, int subimage) override {
        File* f = from_handle(handle);
        if (!f) {
            refuse("imagespec(): not a texture handle of this system");
            return nullptr;
        }
        if (subimage_refused("imagespec", *f, thread_info, subimage)) return nullptr;
        return delegate_->imagespec(f->delegate, thread_info, subimage);
    }
    bool get_texels(ustring filename, TextureOpt& options, int miplevel, int xbegin, int xend,
                    int ybegin, int yend, int zbegin, int zend, int chbegin, int chend,
                    TypeDesc format, void* result) override {
        Perthread* thread_info = get_perthread_info(nullptr);
        return get_texels(get_texture_handle(filename, thread_info), thread_info, options, miplevel,
                          xbegin, xend, ybegin, yend, zbegin, zend, chbegin, chend, format, result);
    }
    bool get_texels(Handle* handle, Perthread* thread_info, TextureOpt& options, int miplevel,
                    int xbegin, int xend, int ybegin, int yend, int zbegin, int zend, int chbegin,
                    int chend, TypeDesc format, void* result) override {
        File* f = from_handle(handle);
        if (!f) return refuse("get_texels(): not a texture handle of this system");
        std::string why = check_options(*f, thread_info, options);
        if (why.empty())
            why =
                check_texel_range(xbegin, xend, ybegin, yend, zbegin, zend, chbegin, chend, result);
        if (!why.empty())
            return refuse("get_texels(): " + why + " (texture '" + f->name.string() + "')");
        return delegate_->get_texels(f->delegate, thread_info, options, miplevel, xbegin, xend,
                                     ybegin, yend, zbegin, zend, chbegin, chend, format, result);
    }
    bool is_udim(ustring filename) override { return delegate_->is_udim(filename); }
    bool is_udim(Handle* handle) override {
        File* f = from_handle(handle);
        return f && f->udim;
    }
    Handle* resolve_udim(ustring pattern, float s, float t) override {
        Perthread* thread_info = get_perthread_info(nullptr);
        return resolve_udim(get_texture_handle(pattern, thread_info), thread_info, s, t);
    }
    Handle* resolve_udim(Handle* handle, Perthread* thread_info, float s, float t) override {
        File* f = from_handle(handle);
        if (!f || !std::isfinite(s) || !std::isfinite(t)) return nullptr;
        Handle* tile = delegate_->resolve_udim(f->delegate, thread_info, s, t);
        if (!tile) return nullptr;
        if (tile == f->delegate) return handle;  // not a UDIM set: the file itself
        return get_texture_handle(delegate_->filename_from_handle(tile), thread_info);
    }
    void inventory_udim(ustring pattern, std::vector<ustring>& filenames, int& nutiles,
                        int& nvtiles) override {
        delegate_->inventory_udim(pattern, filenames, nutiles, nvtiles);
    }
    void inventory_udim(Handle* handle, Perthread* thread_info, std::vector<ustring>& filenames,
                        int& nutiles, int& nvtiles) override {
        File* f = from_handle(handle);
        if (!f) {
            filenames.clear();
            nutiles = nvtiles = 0;
            return;
        }
        delegate_->inventory_udim(f->delegate, thread_info, filenames, nutiles, nvtiles);
    }

    // ---- Cache control. footprint's entries of a file are not reopened: invalidate() and
    // close() reach the delegate's cache only (docs/library.md).
    void invalidate(ustring filename, bool force) override {
        delegate_->invalidate(filename, force);
    }
    void invalidate_all(bool force) override { delegate_->invalidate_all(force); }
    void close(ustring filename) override { delegate_->close(filename); }
    void close_all() override { delegate_->close_all(); }

    // ---- Errors and statistics.
    // The adapter's own messages, then the delegate's and its image cache's (where OpenImageIO
    // reports a file that fails to open when its handle is made).
    bool has_error() const override {
        return !thread_errors()[this].empty() || delegate_->has_error() ||
               delegate_->imagecache()->has_error();
    }
    std::string geterror(bool clear) const override {
        std::string& mine = thread_errors()[this];
        std::string all = mine;
        for (const std::string& theirs :
             {delegate_->geterror(clear), delegate_->imagecache()->geterror(clear)})
            if (!theirs.empty()) all += (all.empty() ? "" : "\n") + theirs;
        if (clear) mine.clear();
        return all;
    }
    std::string getstats(int level, bool icstats) const override {
        std::ostringstream out;
        out << "footprint TextureSystem (OpenImageIO interface)\n"
            << "  texture calls "
            << total(&Counts::texture_answered) + total(&Counts::texture_others)
            << ", answered by footprint " << total(&Counts::texture_answered) << "\n"
            << "  environment calls "
            << total(&Counts::environment_answered) + total(&Counts::environment_others)
            << ", answered by footprint " << total(&Counts::environment_answered) << "\n";
        {
            std::lock_guard lock(footprint_mutex_);
            if (footprint_) {
                const TextureSystemStats s = footprint_->stats();
                out << "  footprint: files " << s.files << ", tiles loaded " << s.tiles_loaded
                    << ", peak tile memory " << (s.peak_bytes >> 20) << " MiB, pyramids in memory "
                    << (s.bytes_in_memory >> 20) << " MiB\n";
            }
        }
        out << "Delegate (OpenImageIO), for the calls footprint does not answer:\n"
            << delegate_->getstats(level, icstats);
        return out.str();
    }
    void reset_stats() override {
        for (Counts& c : counts_) {
            c.texture_answered = c.texture_others = 0;
            c.environment_answered = c.environment_others = 0;
        }
        delegate_->reset_stats();
    }
    OIIO::ImageCache* imagecache() const override { return delegate_->imagecache(); }

  private:
    static constexpr int kMaxResultChannels = 64;

    File* file(ustring name, Perthread* thread_info) {
        {
            std::shared_lock lock(files_mutex_);
            if (auto it = files_.find(name); it != files_.end()) return it->second.get();
        }
        std::unique_lock lock(files_mutex_);
        std::unique_ptr<File>& entry = files_[name];
        if (!entry) {
            entry = std::make_unique<File>();
            entry->name = name;
            entry->delegate = delegate_->get_texture_handle(name, thread_info);
            entry->udim = delegate_->is_udim(entry->delegate);
            entry->entries = std::make_unique<detail::Entries>(name.string());
        }
        return entry.get();
    }

    static File* from_handle(Handle* handle) {
        File* f = reinterpret_cast<File*>(handle);
        return f && f->magic == File::kMagic ? f : nullptr;
    }

    // The entry of `f` that answers calls with default options, or null (oiio_lookups.h).
    footprint::TextureHandle* direct_entry(File& f, Perthread* thread_info) {
        if (f.direct_done.load(std::memory_order_acquire)) return f.direct;
        std::call_once(f.direct_found, [&] {
            const detail::FileFacts& known = facts(f, thread_info);
            if (!f.udim) f.direct = detail::direct_entry(footprint(), *f.entries, known);
            f.direct_done.store(true, std::memory_order_release);
        });
        return f.direct;
    }

    // OpenImageIO's view of a file, through the delegate.
    const detail::FileFacts& facts(File& f, Perthread* thread_info) {
        // Probed once; every later lookup reads the flag alone (std::call_once's own check costs
        // more than the rest of a lookup's bookkeeping).
        if (f.probed_done.load(std::memory_order_acquire)) return f.facts;
        std::call_once(f.probed, [&] {
            detail::FileFacts& facts = f.facts;
            int exists = 0;
            facts.good = delegate_->good(f.delegate) &&
                         delegate_->get_texture_info(f.delegate, thread_info, 0, ustring("exists"),
                                                     TypeDesc::INT, &exists) &&
                         exists;
            if (!facts.good) return;  // every lookup is the delegate's: it reports the error
            delegate_->get_texture_info(f.delegate, thread_info, 0, ustring("subimages"),
                                        TypeDesc::INT, &facts.subimages);
            ImageSpec spec;
            if (const ImageSpec* known = delegate_->imagespec(f.delegate, thread_info, 0))
                spec = *known;
            facts.width = spec.width;
            facts.height = spec.height;
            facts.nchannels = spec.nchannels;
            facts.alpha_channel = spec.alpha_channel;
            facts.full_pixel_range = spec.x == spec.full_x && spec.y == spec.full_y &&
                                     spec.width == spec.full_width &&
                                     spec.height == spec.full_height;
            const std::string wrapmodes = spec.get_string_attribute("wrapmodes");
            if (!wrapmodes.empty())
                TextureOpt::parse_wrapmodes(wrapmodes.c_str(), facts.swrap, facts.twrap);
            const std::string format = spec.get_string_attribute("textureformat");
            facts.latlong = format == "LatLong Environment";
            facts.cube = format == "CubeFace Environment";
            std::string up = "y";
            delegate_->getattribute("latlong_up", up);
            const std::string file_up = spec.get_string_attribute("oiio:updirection");
            if ((facts.latlong || facts.cube) && !file_up.empty()) up = file_up;
            facts.y_up = up != "z";
            facts.sample_border =
                (facts.latlong || facts.cube) && spec.get_int_attribute("oiio:sampleborder") != 0;
        });
        f.probed_done.store(true, std::memory_order_release);
        return f.facts;
    }

    detail::Settings settings() const {
        return {gray_to_rgb_.load(std::memory_order_relaxed),
                flip_t_.load(std::memory_order_relaxed),
                max_mip_res_.load(std::memory_order_relaxed)};
    }
    void read_settings() {
        int value = 0;
        if (delegate_->getattribute("gray_to_rgb", value)) gray_to_rgb_ = value != 0;
        if (delegate_->getattribute("flip_t", value)) flip_t_ = value != 0;
        if (delegate_->getattribute("max_mip_res", value)) max_mip_res_ = value;
    }

    // footprint's texture system, made on the first lookup (so that max_memory_MB set before it
    // counts); every later lookup finds it without the lock.
    footprint::TextureSystem& footprint() {
        if (footprint::TextureSystem* made = footprint_ready_.load(std::memory_order_acquire))
            return *made;
        std::lock_guard lock(footprint_mutex_);
        if (!footprint_) {
            // create() refuses only options create_texture_system() already checked.
            Result<std::unique_ptr<footprint::TextureSystem>> made =
                footprint::TextureSystem::create(options_);
            footprint_ = std::move(*made);
            footprint_ready_.store(footprint_.get(), std::memory_order_release);
        }
        return *footprint_;
    }

    // Why a lookup's handle, options and values cannot be looked up, or empty.
    std::string check_call(File& f, Perthread* thread_info, const TextureOpt& options,
                           const char* const* names, const float* values, int count, int nchannels,
                           const float* result, const float* dresultds, const float* dresultdt) {
        if (nchannels < 0 || nchannels > kMaxResultChannels)
            return "nchannels = " + std::to_string(nchannels) + " is out of range (0 to " +
                   std::to_string(kMaxResultChannels) + ")";
        if (nchannels > 0 && !result) return "the result pointer is null";
        if ((dresultds == nullptr) != (dresultdt == nullptr))
            return "dresultds and dresultdt must be given together";
        if (!detail::values_in_range(values, count))
            return detail::check_values(names, values, count);
        return check_options(f, thread_info, options);
    }
    std::string check_options(File& f, Perthread* thread_info, const TextureOpt& options) {
        const detail::FileFacts& known = facts(f, thread_info);
        return detail::check_options(options, known.good ? known.subimages : 1 << 30);
    }

    // Why get_texels() cannot read a rectangle, or empty. OpenImageIO 2.4.7 takes a reversed
    // range's negative size for a huge one (its memset runs past the buffer), reads before the
    // pixel for a negative chbegin and writes through a null result.
    static std::string check_texel_range(int xbegin, int xend, int ybegin, int yend, int zbegin,
                                         int zend, int chbegin, int chend, const void* result) {
        const int begins[] = {xbegin, ybegin, zbegin, chbegin}, ends[] = {xend, yend, zend, chend};
        const char* names[] = {"x", "y", "z", "ch"};
        for (int k = 0; k < 4; ++k)
            if (ends[k] < begins[k])
                return std::string(names[k]) + "end = " + std::to_string(ends[k]) + " is below " +
                       names[k] + "begin = " + std::to_string(begins[k]);
        if (chbegin < 0) return "chbegin = " + std::to_string(chbegin) + " is negative";
        const bool empty = xbegin == xend || ybegin == yend || zbegin == zend || chbegin == chend;
        if (!result && !empty) return "the result pointer is null";
        return {};
    }

    // A metadata call's subimage that is not one of the file's: refused with a message naming
    // the file (OpenImageIO's does not). A file OpenImageIO cannot open is left to it.
    bool subimage_refused(const char* call, File& f, Perthread* thread_info, int subimage) {
        if (subimage == 0) return false;
        const detail::FileFacts& known = facts(f, thread_info);
        if (!known.good || (subimage >= 0 && subimage < known.subimages)) return false;
        refuse(std::string(call) + "(): subimage " + std::to_string(subimage) +
               " is out of range (the file has " + std::to_string(known.subimages) +
               ") (texture '" + f.name.string() + "')");
        return true;
    }
    bool subimage_refused(const char* call, ustring filename, int subimage) {
        if (subimage == 0) return false;
        Perthread* thread_info = get_perthread_info(nullptr);
        return subimage_refused(call, *file(filename, thread_info), thread_info, subimage);
    }

    // A lookup the delegate failed on a file it could not open: OpenImageIO 2.4's lookups by
    // handle then say nothing, so the adapter names the file.
    void explain_missing(File& f, Perthread* thread_info, const char* call) {
        if (facts(f, thread_info).good || delegate_->has_error() ||
            delegate_->imagecache()->has_error())
            return;
        append_error(std::string(call) + "(): cannot open '" + f.name.string() + "'");
    }

    // A refused call: OpenImageIO's missing-texture result (fill, derivatives 0), false, and the
    // message for geterror().
    bool refuse(const std::string& why, int nchannels = 0, float* result = nullptr,
                float* dresultds = nullptr, float* dresultdt = nullptr) const {
        append_error(why);
        if (nchannels < 0 || nchannels > kMaxResultChannels) return false;
        for (int c = 0; c < nchannels; ++c) {
            if (result) result[c] = 0;
            if (dresultds) dresultds[c] = 0;
            if (dresultdt) dresultdt[c] = 0;
        }
        return false;
    }
    void append_error(const std::string& message) const {
        std::string& mine = thread_errors()[this];
        if (!mine.empty()) mine += '\n';
        mine += message;
    }
    // Errors are per thread, as OpenImageIO keeps them.
    static std::unordered_map<const Adapter*, std::string>& thread_errors() {
        thread_local std::unordered_map<const Adapter*, std::string> errors;
        return errors;
    }

    // A batch as its lanes' single lookups (OpenImageIO 2.4's own batch does the same):
    // lookup(i, lane i's options, results, derivatives or null) for each lane in `mask`, the
    // results laid out channel by channel, Tex::BatchWidth lanes each. The batch's own arguments
    // (the channel count, the arrays it reads and writes) are checked first.
    template <class Lookup>
    bool each_lane(const char* call, Handle* handle, std::initializer_list<const float*> inputs,
                   const TextureOptBatch& options, Tex::RunMask mask, int nchannels, float* result,
                   float* dresultds, float* dresultdt, const Lookup& lookup) {
        constexpr int W = Tex::BatchWidth;
        std::string why;
        if (nchannels < 0 || nchannels > kMaxResultChannels)
            why = "nchannels = " + std::to_string(nchannels) + " is out of range (0 to " +
                  std::to_string(kMaxResultChannels) + ")";
        else if (nchannels > 0 && !result)
            why = "the result pointer is null";
        else if ((dresultds == nullptr) != (dresultdt == nullptr))
            why = "dresultds and dresultdt must be given together";
        else if ((mask & Tex::RunMaskOn) != 0 &&
                 std::find(inputs.begin(), inputs.end(), nullptr) != inputs.end())
            why = "an input array is null";
        if (!why.empty()) {
            const File* f = from_handle(handle);
            return refuse(std::string(call) + "(): " + why +
                          (f ? " ('" + f->name.string() + "')" : std::string()));
        }
        bool ok = true;
        for (int i = 0; i < W; ++i) {
            if (!(mask & (Tex::RunMask(1) << i))) continue;
            TextureOpt opt = lane_options(options, i);
            float r[kMaxResultChannels], ds[kMaxResultChannels], dt[kMaxResultChannels];
            ok &= lookup(i, opt, r, dresultds ? ds : nullptr, dresultds ? dt : nullptr);
            for (int c = 0; c < nchannels; ++c) {
                result[c * W + i] = r[c];
                if (dresultds) {
                    dresultds[c * W + i] = ds[c];
                    dresultdt[c * W + i] = dt[c];
                }
            }
        }
        return ok;
    }

    static TextureOpt lane_options(const TextureOptBatch& batch, int i) {
        TextureOpt opt;
        opt.firstchannel = batch.firstchannel;
        opt.subimage = batch.subimage;
        opt.subimagename = batch.subimagename;
        opt.swrap = static_cast<TextureOpt::Wrap>(batch.swrap);
        opt.twrap = static_cast<TextureOpt::Wrap>(batch.twrap);
        opt.mipmode = static_cast<TextureOpt::MipMode>(batch.mipmode);
        opt.interpmode = static_cast<TextureOpt::InterpMode>(batch.interpmode);
        opt.anisotropic = batch.anisotropic;
        opt.conservative_filter = batch.conservative_filter;
        opt.fill = batch.fill;
        opt.missingcolor = batch.missingcolor;
        opt.sblur = batch.sblur[i];
        opt.tblur = batch.tblur[i];
        opt.swidth = batch.swidth[i];
        opt.twidth = batch.twidth[i];
        opt.rnd = batch.rnd[i];
        return opt;
    }

    TextureSystemOptions options_;
    OIIO::TextureSystem* delegate_;
    mutable std::mutex footprint_mutex_;
    std::unique_ptr<footprint::TextureSystem> footprint_;
    std::atomic<footprint::TextureSystem*> footprint_ready_{nullptr};
    std::shared_mutex files_mutex_;
    std::unordered_map<ustring, std::unique_ptr<File>> files_;
    std::atomic<bool> gray_to_rgb_{false}, flip_t_{false};
    std::atomic<int> max_mip_res_{1 << 30};
    std::mutex retired_mutex_;
    std::vector<Perthread*> retired_;  // destroyed by the host, kept for create_thread_info()
    // The call counts getstats() reports, in shards of a cache line each. A call counts once:
    // answered by footprint, or not (the delegate's, or refused). A thread holding a shard lease
    // (CountShard) is the only one to count in its shard, with a load and a store; the threads
    // beyond kCountShards share the last shard, with atomic increments. (A shared counter, or a
    // locked increment per call, costs a lookup through the interface several percent.)
    struct alignas(64) Counts {
        std::atomic<std::uint64_t> texture_answered{0}, texture_others{0};
        std::atomic<std::uint64_t> environment_answered{0}, environment_others{0};
    };
    static constexpr std::size_t kCountShards = 16;
    mutable std::array<Counts, kCountShards + 1> counts_;
    void count(std::atomic<std::uint64_t> Counts::*which) const {
        thread_local const CountShard lease;
        std::atomic<std::uint64_t>& n = counts_[lease.index].*which;
        if (lease.index < kCountShards)
            n.store(n.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
        else
            n.fetch_add(1, std::memory_order_relaxed);
    }
    // A thread's shard index, leased for the thread's life: 0 to kCountShards − 1, the thread's
    // alone in every adapter, or kCountShards, shared.
    struct CountShard {
        CountShard() {
            std::lock_guard lock(mutex());
            std::vector<std::size_t>& free = free_shards();
            if (!free.empty()) index = free.back(), free.pop_back();
        }
        ~CountShard() {
            if (index == kCountShards) return;
            std::lock_guard lock(mutex());
            free_shards().push_back(index);
        }
        std::size_t index = kCountShards;
        static std::mutex& mutex() {
            static std::mutex m;
            return m;
        }
        static std::vector<std::size_t>& free_shards() {
            static std::vector<std::size_t> free = [] {
                std::vector<std::size_t> all(kCountShards);
                for (std::size_t i = 0; i < kCountShards; ++i) all[i] = kCountShards - 1 - i;
                return all;
            }();
            return free;
        }
    };
    std::uint64_t total(std::atomic<std::uint64_t> Counts::*count) const {
        std::uint64_t sum = 0;
        for (const Counts& c : counts_) sum += (c.*count).load(std::memory_order_relaxed);
        return sum;
    }
};

}  // namespace

OIIO::TextureSystem* create_texture_system(const TextureSystemOptions& options) {
    // The options footprint's TextureSystem refuses, refused here (it is created on first use).
    Result<std::unique_ptr<footprint::TextureSystem>> checked =
        footprint::TextureSystem::create(options);
    if (!checked) {
        t_create_error = checked.error().message;
        return nullptr;
    }
    t_create_error.clear();
    return new Adapter(options);
}

void destroy_texture_system(OIIO::TextureSystem* system) {
    // OpenImageIO's TextureSystem has a private operator delete: deleted as the adapter's type.
    delete static_cast<Adapter*>(system);
}

std::string create_error() {
    return t_create_error;
}

}  // namespace footprint::oiio
