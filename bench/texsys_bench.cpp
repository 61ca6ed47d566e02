#include "texsys_bench.h"

#include <OpenImageIO/texture.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <stdexcept>
#include <thread>

#include "bench_texture_content.h"
#include "bench_util.h"
#include "image/image_io.h"
#include "math/vec3.h"
#include "oiio/texture_system.h"
#include "texture/mip_pyramid.h"
#include "texture/reference_filter.h"
#include "texture_system.h"

namespace footprint::bench {

namespace {

namespace fs = std::filesystem;

// ---- The files --------------------------------------------------------------------------------

// Texture i: the benchmark texture shifted by i/textures of its width, its channels turned by i.
Image texture_variant(const Image& base, int i, int textures) {
    Image image(base.width, base.height, 3);
    const int shift = base.width * i / textures;
    for (int y = 0; y < base.height; ++y)
        for (int x = 0; x < base.width; ++x)
            for (int c = 0; c < 3; ++c)
                image.at(x, y, c) = base.at((x + shift) % base.width, y, (c + i) % 3);
    return image;
}

fs::path texture_file(const fs::path& dir, int i, int size) {
    return dir / ("texsys-" + std::to_string(size) + "-" + std::to_string(i) + ".exr");
}

void write_textures(const TexsysBenchOptions& opt, const fs::path& dir, const ProgressNote& note) {
    std::optional<Image> base;
    for (int i = 0; i < opt.textures; ++i) {
        const fs::path file = texture_file(dir, i, opt.size);
        if (fs::exists(file)) continue;
        note("writing " + file.string());
        if (!base) base = make_benchmark_texture(opt.size);
        const MipPyramid pyramid = MipPyramid::build(texture_variant(*base, i, opt.textures));
        std::vector<Image> levels;
        for (int l = 0; l < pyramid.level_count(); ++l) levels.push_back(pyramid.level_image(l));
        LevelsSaveOptions save;
        save.wrap_modes = "periodic,periodic";
        if (Status s = save_image_levels(levels, file, save); !s)
            throw std::runtime_error(s.error().message);
    }
}

// ---- The frame: a plane y = 0 seen at a grazing angle
// --------------------------------------------

struct PixelLookup {
    int texture = -1;  // −1: the pixel sees the sky
    TextureCoords coords;
};

// Camera at height 1 looking along +z, pitched 10° down, 40° vertical field of view. The plane's
// strips 4 units wide along x take the textures in turn; a texture repeats every 4 units.
class GrazingPlane {
  public:
    GrazingPlane(int width, int height, int textures)
        : width_(width), height_(height), textures_(textures) {}

    PixelLookup at(int x, int y) const {
        const std::optional<Vec3> p = hit(x + 0.5f, y + 0.5f);
        const std::optional<Vec3> px = hit(x + 1.5f, y + 0.5f), py = hit(x + 0.5f, y + 1.5f);
        if (!p || !px || !py) return {};
        constexpr float kRepeat = 4, kStrip = 4;
        const int strip = static_cast<int>(std::floor(p->x / kStrip));
        PixelLookup l;
        l.texture = ((strip % textures_) + textures_) % textures_;
        l.coords = {p->x / kRepeat,           p->z / kRepeat,           (px->x - p->x) / kRepeat,
                    (px->z - p->z) / kRepeat, (py->x - p->x) / kRepeat, (py->z - p->z) / kRepeat};
        return l;
    }

  private:
    std::optional<Vec3> hit(float px, float py) const {
        constexpr float kPitch = 10.0f * 3.14159265f / 180, kTanHalf = 0.36397f;  // tan 20°
        const float aspect = static_cast<float>(width_) / static_cast<float>(height_);
        const float u = (2 * px / static_cast<float>(width_) - 1) * kTanHalf * aspect;
        const float v = (1 - 2 * py / static_cast<float>(height_)) * kTanHalf;
        // Camera frame: forward (0, −sin, cos), up (0, cos, sin), right (1, 0, 0).
        const Vec3 d{u, v * std::cos(kPitch) - std::sin(kPitch),
                     v * std::sin(kPitch) + std::cos(kPitch)};
        if (d.y >= -1e-4f) return std::nullopt;
        const float t = 1.0f / -d.y;
        return Vec3{t * d.x, 0, t * d.z};
    }
    int width_, height_, textures_;
};

std::vector<PixelLookup> frame_lookups(const TexsysBenchOptions& opt) {
    const GrazingPlane plane(opt.width, opt.height, opt.textures);
    std::vector<PixelLookup> all(static_cast<std::size_t>(opt.width) * opt.height);
    for (int y = 0; y < opt.height; ++y)
        for (int x = 0; x < opt.width; ++x) all[std::size_t(y) * opt.width + x] = plane.at(x, y);
    return all;
}

// ---- One texture system's run, in a child process
// ------------------------------------------------

// What a run renders with: lookup(thread, pixel, out) writes 3 floats.
using LookupCall = std::function<void(const PixelLookup&, float*)>;

struct RunResult {
    double cold_seconds = 0;
    double lookups_per_s = 0;  // the frames after the first
    double peak_rss_mb = 0;
    double peak_texels_mb = NAN;  // the texture system's own figure
    std::uint64_t image_hash = 0;
    std::vector<float> last_frame;
};

// Renders opt.frames frames with `threads` threads, rows dealt out in blocks of 8.
RunResult render_frames(const TexsysBenchOptions& opt, const std::vector<PixelLookup>& lookups,
                        int threads, const std::function<LookupCall()>& make_call) {
    RunResult r;
    r.last_frame.assign(lookups.size() * 3, 0.0f);
    std::size_t looked_up = 0;
    for (const PixelLookup& l : lookups) looked_up += l.texture >= 0;
    double warm_seconds = 1e300;
    for (int frame = 0; frame < opt.frames; ++frame) {
        std::atomic<int> next_block{0};
        const int blocks = (opt.height + 7) / 8;
        const double seconds =
            run_split(std::size_t(threads), threads, [&](int, std::size_t, std::size_t) {
                const LookupCall call = make_call();
                for (int b; (b = next_block++) < blocks;) {
                    for (int y = b * 8; y < std::min(opt.height, b * 8 + 8); ++y) {
                        for (int x = 0; x < opt.width; ++x) {
                            const std::size_t i = std::size_t(y) * opt.width + x;
                            if (lookups[i].texture >= 0) call(lookups[i], &r.last_frame[3 * i]);
                        }
                    }
                }
            });
        if (frame == 0)
            r.cold_seconds = seconds;
        else
            warm_seconds = std::min(warm_seconds, seconds);
    }
    // The best of the warm frames: other processes only ever slow a frame down.
    r.lookups_per_s = double(looked_up) / std::max(warm_seconds, 1e-9);
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a of the last frame's bits
    for (float v : r.last_frame) h = (h ^ std::bit_cast<std::uint32_t>(v)) * 1099511628211ull;
    r.image_hash = h;
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    r.peak_rss_mb = double(usage.ru_maxrss) / 1024.0;
    return r;
}

// OpenImageIO's default TextureOpt asks for `anisotropic` 32, which the adapter takes for
// footprint assembly's probe budget: the native run with that budget is the adapter's lookups
// without the interface.
constexpr int kOiioDefaultAnisotropic = 32;

RunResult run_ours(const TexsysBenchOptions& opt, const fs::path& dir,
                   const std::vector<PixelLookup>& lookups, int threads, int cache_mb,
                   int max_probes = LookupOptions{}.max_probes) {
    TextureSystemOptions options;
    options.max_memory_mb = std::size_t(cache_mb);
    std::unique_ptr<TextureSystem> ts = std::move(TextureSystem::create(options).value());
    std::vector<TextureHandle*> handles;
    for (int i = 0; i < opt.textures; ++i)
        handles.push_back(ts->handle(texture_file(dir, i, opt.size).string()));
    LookupOptions lookup;  // footprint assembly
    lookup.max_probes = max_probes;
    RunResult r = render_frames(opt, lookups, threads, [&]() -> LookupCall {
        return [&](const PixelLookup& l, float* out) {
            if (!ts->texture(handles[l.texture], l.coords, lookup, {out, 3}))
                throw std::runtime_error("footprint's lookup failed");
        };
    });
    r.peak_texels_mb = double(ts->stats().peak_bytes) / double(1 << 20);
    return r;
}

// The same lookups on the files' levels held in memory as MipPyramids, without a texture system:
// what the cache and its tiles cost.
RunResult run_in_memory(const TexsysBenchOptions& opt, const fs::path& dir,
                        const std::vector<PixelLookup>& lookups) {
    std::vector<MipPyramid> pyramids;
    for (int i = 0; i < opt.textures; ++i) {
        Result<std::vector<Image>> levels = load_image_levels(texture_file(dir, i, opt.size));
        if (!levels) throw std::runtime_error(levels.error().message);
        pyramids.push_back(std::move(MipPyramid::from_levels(*levels).value()));
    }
    const LookupOptions lookup;
    return render_frames(opt, lookups, 1, [&]() -> LookupCall {
        return [&](const PixelLookup& l, float* out) {
            texture_lookup(pyramids[l.texture], l.coords, lookup, out);
        };
    });
}

// The frames through OpenImageIO's interface, on `ts`: handles, each thread's info and a default
// TextureOpt (anisotropic, smart bicubic) per lookup, as a renderer calls it.
RunResult render_through(OIIO::TextureSystem* ts, const TexsysBenchOptions& opt,
                         const fs::path& dir, const std::vector<PixelLookup>& lookups,
                         int threads) {
    std::vector<OIIO::TextureSystem::TextureHandle*> handles;
    for (int i = 0; i < opt.textures; ++i)
        handles.push_back(
            ts->get_texture_handle(OIIO::ustring(texture_file(dir, i, opt.size).string())));
    return render_frames(opt, lookups, threads, [&]() -> LookupCall {
        OIIO::TextureSystem::Perthread* thread = ts->get_perthread_info();
        return [ts, thread, &handles](const PixelLookup& l, float* out) {
            OIIO::TextureOpt options;
            const TextureCoords& c = l.coords;
            if (!ts->texture(handles[l.texture], thread, options, c.s, c.t, c.dsdx, c.dtdx, c.dsdy,
                             c.dtdy, 3, out))
                throw std::runtime_error("a lookup failed: " + ts->geterror());
        };
    });
}

RunResult run_oiio(const TexsysBenchOptions& opt, const fs::path& dir,
                   const std::vector<PixelLookup>& lookups, int threads) {
    OIIO::TextureSystem* ts = OIIO::TextureSystem::create(false);
    ts->attribute("max_memory_MB", float(opt.cache_mb));
    RunResult r = render_through(ts, opt, dir, lookups, threads);
    long long used = 0;
    if (ts->getattribute("stat:cache_memory_used", OIIO::TypeDesc::INT64, &used))
        r.peak_texels_mb = double(used) / double(1 << 20);  // its figure is the current use
    OIIO::TextureSystem::destroy(ts);
    return r;
}

// footprint behind OpenImageIO's interface: the same calls as run_oiio(), on the adapter.
RunResult run_adapter(const TexsysBenchOptions& opt, const fs::path& dir,
                      const std::vector<PixelLookup>& lookups, int threads) {
    TextureSystemOptions options;
    options.max_memory_mb = std::size_t(opt.cache_mb);
    OIIO::TextureSystem* ts = oiio::create_texture_system(options);
    if (!ts) throw std::runtime_error(oiio::create_error());
    RunResult r = render_through(ts, opt, dir, lookups, threads);
    oiio::destroy_texture_system(ts);
    return r;
}

// Runs `work` in a child process; false if it failed. The parent starts no thread pool (OpenEXR's,
// oneTBB's) before its last child, so that each child starts from a single thread: a pool's
// threads do not survive fork().
bool in_child(const std::function<bool()>& work) {
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        bool ok = false;
        try {
            ok = work();
        } catch (const std::exception& e) {
            std::fprintf(stderr, "footprint-bench texsys: %s\n", e.what());
        }
        std::fflush(nullptr);
        _exit(ok ? 0 : 1);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// Runs `run` in a child process and returns what it wrote back (a JSON line, then the floats of
// the pixels `subset` names).
RunResult in_child(const std::function<RunResult()>& run, const std::vector<std::size_t>& subset,
                   const fs::path& scratch) {
    const bool ok = in_child([&] {
        const RunResult r = run();
        std::ofstream out(scratch, std::ios::binary);
        const nlohmann::json j = {{"cold_seconds", r.cold_seconds},
                                  {"lookups_per_s", r.lookups_per_s},
                                  {"peak_rss_mb", r.peak_rss_mb},
                                  {"peak_texels_mb", number_or_null(r.peak_texels_mb)},
                                  {"image_hash", r.image_hash}};
        out << j.dump() << "\n";
        for (std::size_t i : subset)
            out.write(reinterpret_cast<const char*>(&r.last_frame[3 * i]), 3 * sizeof(float));
        return bool(out);
    });
    if (!ok) throw std::runtime_error("a texsys benchmark run failed");
    std::ifstream in(scratch, std::ios::binary);
    std::string line;
    std::getline(in, line);
    const nlohmann::json j = nlohmann::json::parse(line);
    RunResult r;
    r.cold_seconds = j["cold_seconds"];
    r.lookups_per_s = j["lookups_per_s"];
    r.peak_rss_mb = j["peak_rss_mb"];
    r.peak_texels_mb = j["peak_texels_mb"].is_null() ? NAN : double(j["peak_texels_mb"]);
    r.image_hash = j["image_hash"];
    r.last_frame.resize(subset.size() * 3);
    in.read(reinterpret_cast<char*>(r.last_frame.data()), std::streamsize(r.last_frame.size() * 4));
    fs::remove(scratch);
    return r;
}

// ---- Error against the reference
// -----------------------------------------------------------------

// Every 97th lit pixel whose footprint the brute-force reference can afford (λ1 ≤ 64 texels).
std::vector<std::size_t> error_subset(const std::vector<PixelLookup>& lookups, int size) {
    std::vector<std::size_t> subset;
    std::size_t lit = 0;
    for (std::size_t i = 0; i < lookups.size(); ++i) {
        if (lookups[i].texture < 0 || lit++ % 97) continue;
        const TextureCoords& c = lookups[i].coords;
        const float s = float(size);
        const FootprintEllipse e =
            make_footprint_ellipse(Vec2{c.dsdx * s, c.dtdx * s}, Vec2{c.dsdy * s, c.dtdy * s});
        if (e.major_radius <= 64) subset.push_back(i);
    }
    return subset;
}

std::vector<float> reference_values(const TexsysBenchOptions& opt,
                                    const std::vector<PixelLookup>& lookups,
                                    const std::vector<std::size_t>& subset,
                                    const ProgressNote& note) {
    std::vector<float> ref(subset.size() * 3);
    const Image base = make_benchmark_texture(opt.size);
    for (int tex = 0; tex < opt.textures; ++tex) {
        note("reference lookups, texture " + std::to_string(tex));
        const Image image = texture_variant(base, tex, opt.textures);
        const float s = float(opt.size);
        for (std::size_t k = 0; k < subset.size(); ++k) {
            const PixelLookup& l = lookups[subset[k]];
            if (l.texture != tex) continue;
            const TextureCoords& c = l.coords;
            reference_lookup(
                image, c.s, c.t,
                make_footprint_ellipse(Vec2{c.dsdx * s, c.dtdx * s}, Vec2{c.dsdy * s, c.dtdy * s}),
                {}, &ref[3 * k]);
        }
    }
    return ref;
}

double rmse(const std::vector<float>& a, const std::vector<float>& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += double(a[i] - b[i]) * double(a[i] - b[i]);
    return a.empty() ? NAN : std::sqrt(sum / double(a.size()));
}

// The subset's footprints by size: λ1 ≤ 1 texel (magnified), ≤ 4, ≤ 16, ≤ 64.
constexpr float kClassLimits[] = {1, 4, 16, 64};
int footprint_class(const TextureCoords& c, int size) {
    const float s = float(size);
    const float l1 =
        make_footprint_ellipse(Vec2{c.dsdx * s, c.dtdx * s}, Vec2{c.dsdy * s, c.dtdy * s})
            .major_radius;
    int k = 0;
    while (k < 3 && l1 > kClassLimits[k]) ++k;
    return k;
}

// RMSE of `values` against `ref` over the subset pixels of footprint class k.
double class_rmse(const std::vector<float>& values, const std::vector<float>& ref,
                  const std::vector<PixelLookup>& lookups, const std::vector<std::size_t>& subset,
                  int size, int k) {
    std::vector<float> a, b;
    for (std::size_t i = 0; i < subset.size(); ++i) {
        if (footprint_class(lookups[subset[i]].coords, size) != k) continue;
        a.insert(a.end(), &values[3 * i], &values[3 * i + 3]);
        b.insert(b.end(), &ref[3 * i], &ref[3 * i + 3]);
    }
    return rmse(a, b);
}

}  // namespace

int run_texsys_bench(const TexsysBenchOptions& opt) {
    const ProgressNote note(opt.quiet);
    const bool temporary = opt.dir.empty();
    const fs::path dir =
        temporary ? fs::temp_directory_path() / ("footprint-texsys-" + std::to_string(getpid()))
                  : fs::path(opt.dir);
    fs::create_directories(dir);
    struct Cleanup {
        fs::path dir;
        bool remove;
        ~Cleanup() {
            std::error_code ec;
            if (remove) fs::remove_all(dir, ec);
        }
    } cleanup{dir, temporary};

    if (!in_child([&] {
            write_textures(opt, dir, note);
            return true;
        }))
        throw std::runtime_error("cannot write the texture files in " + dir.string());
    const std::vector<PixelLookup> lookups = frame_lookups(opt);
    const std::vector<std::size_t> subset = error_subset(lookups, opt.size);
    const fs::path scratch = dir / "run.bin";
    double float_pyramids_mb = 0;
    for (int l = 0, s = opt.size; s >= 1; ++l, s /= 2)
        float_pyramids_mb += double(s) * s * 16 / double(1 << 20);
    float_pyramids_mb *= opt.textures;

    struct Row {
        std::string system;
        int threads;
        RunResult r;
    };
    std::vector<Row> rows;
    // Keeps a system's best round.
    const auto keep = [&](const std::string& system, int threads, const RunResult& r) {
        for (Row& row : rows)
            if (row.system == system && row.threads == threads) {
                if (r.lookups_per_s > row.r.lookups_per_s) row.r = r;
                return;
            }
        rows.push_back({system, threads, r});
    };
    for (int round = 1; round <= opt.rounds; ++round) {
        const std::string of_round =
            opt.rounds > 1 ? ", round " + std::to_string(round) + "/" + std::to_string(opt.rounds)
                           : "";
        for (int threads : opt.thread_counts) {
            const std::string with = " " + std::to_string(threads) + " thread(s)" + of_round;
            note("footprint," + with);
            keep("footprint", threads,
                 in_child([&] { return run_ours(opt, dir, lookups, threads, opt.cache_mb); },
                          subset, scratch));
            if (opt.api == "oiio") {
                note("footprint with the adapter's probe budget," + with);
                keep("native-32", threads,
                     in_child(
                         [&] {
                             return run_ours(opt, dir, lookups, threads, opt.cache_mb,
                                             kOiioDefaultAnisotropic);
                         },
                         subset, scratch));
                note("footprint behind OpenImageIO's interface," + with);
                keep("fp-oiio", threads,
                     in_child([&] { return run_adapter(opt, dir, lookups, threads); }, subset,
                              scratch));
            }
            if (opt.with_oiio) {
                note("OpenImageIO," + with);
                keep("oiio", threads,
                     in_child([&] { return run_oiio(opt, dir, lookups, threads); }, subset,
                              scratch));
            }
        }
    }
    note("footprint, in memory");
    rows.push_back({"in-memory", 1,
                    in_child([&] { return run_in_memory(opt, dir, lookups); }, subset, scratch)});
    note("footprint, unbounded cache");
    const RunResult unbounded =
        in_child([&] { return run_ours(opt, dir, lookups, 1, 1 << 20); }, subset, scratch);
    const std::vector<float> ref = reference_values(opt, lookups, subset, note);

    std::printf(
        "footprint-bench texsys: %d textures of %d² RGB (%.0f MiB of float pyramids), "
        "cache %d MiB, %dx%d frames of a grazing plane, %d frames (the first cold), each system's "
        "best of %d "
        "rounds\n",
        opt.textures, opt.size, float_pyramids_mb, opt.cache_mb, opt.width, opt.height, opt.frames,
        opt.rounds);
    std::printf("%-10s %7s %10s %14s %12s %16s %10s\n", "system", "threads", "cold s", "Mlookups/s",
                "peak RSS MB", "peak texels MB", "RMSE");
    nlohmann::json runs = nlohmann::json::array();
    bool all_same = true;
    for (const Row& row : rows) {
        const double error = rmse(row.r.last_frame, ref);
        std::printf("%-10s %7d %10.2f %14.3f %12.0f %16.1f %10.5f\n", row.system.c_str(),
                    row.threads, row.r.cold_seconds, row.r.lookups_per_s / 1e6, row.r.peak_rss_mb,
                    row.r.peak_texels_mb, error);
        if (row.system == "footprint")
            all_same = all_same && row.r.image_hash == unbounded.image_hash;
        if (row.system == "fp-oiio")  // its threads must agree among themselves
            for (const Row& other : rows)
                if (other.system == "fp-oiio")
                    all_same = all_same && other.r.image_hash == row.r.image_hash;
        runs.push_back({{"system", row.system},
                        {"threads", row.threads},
                        {"cold_seconds", row.r.cold_seconds},
                        {"mlookups_per_s", row.r.lookups_per_s / 1e6},
                        {"peak_rss_mb", row.r.peak_rss_mb},
                        {"peak_texels_mb", number_or_null(row.r.peak_texels_mb)},
                        {"rmse", error}});
    }
    std::printf("RMSE by footprint (major radius λ1 in level-0 texels):\n%-10s %7s", "system",
                "threads");
    for (float limit : kClassLimits) std::printf("   λ1 ≤ %-4.0f", limit);
    std::printf("\n");
    for (const Row& row : rows) {
        std::printf("%-10s %7d", row.system.c_str(), row.threads);
        for (int k = 0; k < 4; ++k)
            std::printf(" %10.5f", class_rmse(row.r.last_frame, ref, lookups, subset, opt.size, k));
        std::printf("\n");
    }
    std::printf(
        "error subset: %zu pixels; footprint's images with 1 and 2 threads and with an "
        "unbounded cache (peak %.0f MiB of texels) are %s%s\n",
        subset.size(), unbounded.peak_texels_mb,
        all_same ? "identical, bit for bit" : "NOT identical",
        opt.api == "oiio" ? " (and so are those behind OpenImageIO's interface, among themselves)"
                          : "");
    const auto rate = [&](const std::string& system, int threads) {
        for (const Row& row : rows)
            if (row.system == system && row.threads == threads) return row.r.lookups_per_s;
        return double(NAN);
    };
    for (int threads : opt.thread_counts) {
        const double oiio = rate("oiio", threads), ours = rate("footprint", threads),
                     adapter = rate("fp-oiio", threads), same_budget = rate("native-32", threads);
        if (opt.with_oiio)
            std::printf("%d thread(s): footprint %.2f× OpenImageIO's lookups/s", threads,
                        ours / oiio);
        if (opt.with_oiio && opt.api == "oiio")
            std::printf("; behind OpenImageIO's interface %.2f×", adapter / oiio);
        if (opt.api == "oiio")
            std::printf("; the interface costs %.1f %% against the native API with its budget",
                        100 * (1 - adapter / same_budget));
        std::printf("\n");
    }
    if (!opt.json_path.empty()) {
        const nlohmann::json j = {{"benchmark", "texsys"},
                                  {"textures", opt.textures},
                                  {"size", opt.size},
                                  {"cache_mb", opt.cache_mb},
                                  {"float_pyramids_mb", float_pyramids_mb},
                                  {"frame", {opt.width, opt.height}},
                                  {"frames", opt.frames},
                                  {"rounds", opt.rounds},
                                  {"error_subset", subset.size()},
                                  {"bit_identical", all_same},
                                  {"unbounded_peak_texels_mb", unbounded.peak_texels_mb},
                                  {"api", opt.api},
                                  {"oiio_version", OIIO_VERSION_STRING},
                                  {"runs", runs}};
        write_json(opt.json_path, j);
    }
    return all_same ? 0 : 1;
}

}  // namespace footprint::bench
