// python/footprint_python.cpp — the `footprint` Python module (pybind11): the texture system's
// lookups on NumPy arrays, the renderer, the image metrics.
//
//   import footprint
//   ts = footprint.TextureSystem(max_memory_mb=256)
//   rgb = ts.texture("albedo.exr", s, t, dsdx, dtdx, dsdy, dtdy, filter="fa")   # N × C float32
//   sky = ts.environment("sky.hdr", r, dr_dx, dr_dy)                              # r: N × 3
//   image = footprint.render("scene.json", filter="fa-rough", spp=1)             # H × W × 3
//   image = footprint.render("scene.json", textures=ts)        # its maps through ts's cache
//   footprint.metrics(image, reference)                  # rmse, psnr, ssim, flip
//   footprint.save_image("out.exr", image)               # linear light
//   footprint.load_image("in.png")                       # linear light
//
// Lookups release the GIL and run on the calling thread. An argument out of range or unknown is
// a ValueError worded as the command line words it ("width 8 is out of range (16 to 16384)");
// every other error a RuntimeError with the library's message ("cannot read 'albedo.exr': …").
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <string>

#include <footprint/version.h>

#include "cli_options.h"
#include "command_util.h"
#include "image/image_io.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "texture_system.h"

namespace py = pybind11;

namespace footprint {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

[[noreturn]] void raise(const Error& error) {
    throw std::runtime_error(error.message);
}

LookupOptions lookup_options(const std::string& filter) {
    std::optional<TextureFilter> parsed = parse_texture_filter(filter);
    if (!parsed)
        throw py::value_error("filter '" + filter +
                              "': expected nearest, bilinear, trilinear, fa, ewa or sat");
    LookupOptions options;
    options.filter = *parsed;
    return options;
}

// The length every argument array shares (each 1-D, or a scalar or one value: broadcast, as
// NumPy does; empty arrays make no lookup).
py::ssize_t common_length(std::initializer_list<const FloatArray*> arrays) {
    py::ssize_t n = -1;  // the length of the arrays not broadcast, once one is seen
    for (const FloatArray* a : arrays) {
        if (a->ndim() > 1) throw py::value_error("lookup arguments must be 1-D arrays or scalars");
        const py::ssize_t size = a->ndim() == 0 ? 1 : a->shape(0);
        if (size == 1) continue;
        if (n >= 0 && size != n)
            throw py::value_error("lookup arguments have different lengths: " + std::to_string(n) +
                                  " and " + std::to_string(size));
        n = size;
    }
    return n < 0 ? 1 : n;
}
float at(const FloatArray& a, py::ssize_t i) {
    return a.data()[a.size() == 1 ? 0 : i];
}

// Rows i of an N × 3 array (or one 3-vector for all).
Vec3 row3(const FloatArray& a, py::ssize_t i) {
    const float* p = a.data() + (a.ndim() == 1 ? 0 : 3 * i);
    return {p[0], p[1], p[2]};
}
py::ssize_t rows3(const FloatArray& a, const char* name) {
    if (!((a.ndim() == 1 && a.shape(0) == 3) || (a.ndim() == 2 && a.shape(1) == 3)))
        throw py::value_error(std::string(name) + " must be a 3-vector or an N × 3 array");
    return a.ndim() == 1 ? 1 : a.shape(0);
}

class PyTextureSystem {
  public:
    // Options TextureSystem::create() refuses are a ValueError with its message (a negative
    // max_memory_mb, which its unsigned option cannot hold, worded as it words 0).
    PyTextureSystem(long long max_memory_mb, int tile_size, const std::string& cache_dir) {
        TextureSystemOptions options;
        options.max_memory_mb = static_cast<std::size_t>(std::max(max_memory_mb, 0LL));
        options.tile_size = tile_size;
        options.cache_dir = cache_dir;
        Result<std::unique_ptr<TextureSystem>> made = TextureSystem::create(options);
        if (!made) {
            std::string message = made.error().message;
            const std::size_t got = message.rfind("(got 0)");
            if (max_memory_mb < 0 && got != std::string::npos)
                message.replace(got, 7, "(got " + std::to_string(max_memory_mb) + ")");
            throw py::value_error(message);
        }
        ts_ = std::move(*made);
    }

    // The system itself, for render() to hold its scene's maps in.
    const std::shared_ptr<TextureSystem>& system() const { return ts_; }

    int channels_of(const std::string& name) {
        Result<TextureInfo> info = ts_->info(name);
        if (!info) raise(info.error());
        return info->channels;
    }

    FloatArray texture(const std::string& name, const FloatArray& s, const FloatArray& t,
                       const FloatArray& dsdx, const FloatArray& dtdx, const FloatArray& dsdy,
                       const FloatArray& dtdy, const std::string& filter) {
        const LookupOptions options = lookup_options(filter);
        const py::ssize_t n = common_length({&s, &t, &dsdx, &dtdx, &dsdy, &dtdy});
        const int channels = channels_of(name);
        FloatArray out({n, static_cast<py::ssize_t>(channels)});
        float* values = out.mutable_data();
        TextureHandle* handle = ts_->handle(name);
        Status status;
        {
            py::gil_scoped_release unlocked;
            for (py::ssize_t i = 0; i < n && status; ++i) {
                const TextureCoords c{at(s, i),    at(t, i),    at(dsdx, i),
                                      at(dtdx, i), at(dsdy, i), at(dtdy, i)};
                status = ts_->texture(handle, c, options,
                                      {values + i * channels, static_cast<std::size_t>(channels)});
            }
        }
        if (!status) raise(status.error());
        return out;
    }

    FloatArray environment(const std::string& name, const FloatArray& r, const FloatArray& dr_dx,
                           const FloatArray& dr_dy, const std::string& filter) {
        const EnvLookupOptions options(lookup_options(filter));
        const py::ssize_t n = rows3(r, "r");
        if (rows3(dr_dx, "dr_dx") != n || rows3(dr_dy, "dr_dy") != n)
            throw py::value_error("r, dr_dx and dr_dy must have the same number of rows");
        Result<TextureSystem::EnvironmentShape> shape = ts_->environment_shape(name);
        if (!shape) raise(shape.error());
        const int channels = shape->channels;
        FloatArray out({n, static_cast<py::ssize_t>(channels)});
        float* values = out.mutable_data();
        Status status;
        {
            py::gil_scoped_release unlocked;
            for (py::ssize_t i = 0; i < n && status; ++i)
                status =
                    ts_->environment(name, row3(r, i), row3(dr_dx, i), row3(dr_dy, i), options,
                                     {values + i * channels, static_cast<std::size_t>(channels)});
        }
        if (!status) raise(status.error());
        return out;
    }

    py::dict stats() const {
        const TextureSystemStats s = ts_->stats();
        py::dict d;
        d["files"] = s.files;
        d["tiles_loaded"] = s.tiles_loaded;
        d["tile_hits"] = s.tile_hits;
        d["tile_misses"] = s.tile_misses;
        d["bytes_resident"] = s.bytes_resident;
        d["peak_bytes"] = s.peak_bytes;
        d["bytes_in_memory"] = s.bytes_in_memory;
        return d;
    }

  private:
    std::shared_ptr<TextureSystem> ts_;
};

FloatArray to_array(const Image& image) {
    FloatArray out({static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width),
                    static_cast<py::ssize_t>(image.channels)});
    std::memcpy(out.mutable_data(), image.pixels.data(), image.pixels.size() * sizeof(float));
    return out;
}

Image to_image(const FloatArray& a, const char* name) {
    if (a.ndim() != 2 && a.ndim() != 3)
        throw py::value_error(std::string(name) + " must be an H × W or H × W × C array");
    const int channels = a.ndim() == 3 ? static_cast<int>(a.shape(2)) : 1;
    Image image(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), channels);
    std::memcpy(image.pixels.data(), a.data(), image.pixels.size() * sizeof(float));
    return image;
}

FloatArray render_scene(const std::string& scene, const std::string& filter, int spp,
                        std::optional<int> width, int threads, const PyTextureSystem* textures) {
    // The arguments `footprint render` checks, checked alike: ValueError, in Python's names.
    Result<FilterMode> mode = parse_render_filter(filter, "filter");
    if (!mode) throw py::value_error(mode.error().message);
    std::optional<std::string> problem = range_problem("spp", spp, kRenderSpp);
    if (!problem && width) problem = range_problem("width", *width, kImageWidths);
    if (!problem) problem = range_problem("threads", threads, kRenderThreads, "0: all cores");
    if (problem) throw py::value_error(*problem);
    Result<NamedScene> named = resolve_scene(scene, width);
    if (!named) raise(named.error());
    SceneDesc& desc = named->desc;
    if (width && desc.width != *width) {  // a scene file: keep its aspect ratio
        desc.height =
            std::max(1, static_cast<int>(std::lround(double(*width) * desc.height / desc.width)));
        desc.width = *width;
    }
    Result<RenderScene> prepared =
        prepare_render_scene(desc, textures ? textures->system() : nullptr);
    if (!prepared) raise(prepared.error());
    RenderOptions options;
    options.filter = *mode;
    options.spp = spp;
    options.threads = threads;
    Image image;
    {
        py::gil_scoped_release unlocked;
        image = render(*prepared, options);
    }
    if (Status s = prepared->take_texture_errors(); !s) raise(s.error());
    return to_array(image);
}

py::dict metrics(const FloatArray& a, const FloatArray& b, double peak) {
    MetricsOptions options;
    options.peak = peak;
    const Image image_a = to_image(a, "a"), image_b = to_image(b, "b");
    Result<ImageComparison> c = compare_images(image_a, image_b, options);
    if (!c) raise(c.error());
    Result<FlipResult> f = flip(image_a, image_b);  // b the reference; HDR-FLIP above 1
    if (!f) raise(f.error());
    py::dict d;
    d["rmse"] = c->rmse;
    d["psnr"] = c->psnr;
    d["ssim"] = c->ssim;
    d["flip"] = f->mean;
    d["pixels"] = c->pixels;
    return d;
}

FloatArray load(const std::string& file) {
    Result<Image> image = load_image(file);
    if (!image) raise(image.error());
    return to_array(*image);
}

void save(const std::string& file, const FloatArray& a) {
    if (Status saved = save_image(to_image(a, "image"), file); !saved) raise(saved.error());
}

}  // namespace
}  // namespace footprint

PYBIND11_MODULE(footprint, m) {
    using namespace footprint;
    m.doc() = "footprint: anisotropic texture filtering by footprint assembly";
    m.def("version", [] { return std::string(footprint::version()); });

    py::class_<PyTextureSystem>(m, "TextureSystem",
                                "Filtered lookups of texture files by name through a bounded cache")
        .def(py::init<long long, int, std::string>(), py::arg("max_memory_mb") = 1024,
             py::arg("tile_size") = 64, py::arg("cache_dir") = "")
        .def("texture", &PyTextureSystem::texture, py::arg("name"), py::arg("s"), py::arg("t"),
             py::arg("dsdx"), py::arg("dtdx"), py::arg("dsdy"), py::arg("dtdy"),
             py::arg("filter") = "fa",
             "N lookups (1-D arrays or scalars, broadcast): an N × channels float32 array")
        .def("environment", &PyTextureSystem::environment, py::arg("name"), py::arg("r"),
             py::arg("dr_dx"), py::arg("dr_dy"), py::arg("filter") = "fa",
             "N directions with ray differentials (N × 3): an N × channels float32 array")
        .def("channels", &PyTextureSystem::channels_of, py::arg("name"))
        .def("stats", &PyTextureSystem::stats);

    m.def("render", &render_scene, py::arg("scene"), py::arg("filter") = "fa-rough",
          py::arg("spp") = 1, py::arg("width") = py::none(), py::arg("threads") = 0,
          py::arg("textures") = py::none(),
          "A scene file (.json) or demo scene rendered: an H × W × 3 float32 array, linear light; "
          "its maps read through `textures` (a TextureSystem) or a new one");
    m.def("load_image", &load, py::arg("file"),
          "An image file as an H × W × C float32 array in linear light (load_image)");
    m.def("save_image", &save, py::arg("file"), py::arg("image"),
          "An H × W [× C] array written by the file's extension (save_image; atomic)");
    m.def("metrics", &metrics, py::arg("a"), py::arg("b"), py::arg("peak") = 1.0,
          "RMSE, PSNR, SSIM and mean FLIP (HDR-FLIP where a value is above 1) of a against the "
          "reference b (H × W [× C] arrays, linear light)");
}
