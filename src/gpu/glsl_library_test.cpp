// The GLSL library (glsl/footprint/, docs/engine.md) as an engine gets it: compute shaders that
// include only the library's files — resolved as a shading-language include would, every include
// inlined so that the guards must drop the repeats — call its functions on textures uploaded from
// footprint's own pyramids, and are compared with the CPU's lookups at the same coordinates.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <footprint/version.h>

#include "bump/bump_pyramid.h"
#include "envmap/env_footprint.h"
#include "envmap/environment_map.h"
#include "gpu/gl_objects.h"
#include "gpu/gpu_test_device.h"
#include "texture/footprint_assembly.h"
#include "texture/mip_pyramid.h"
#include "texture/texture_lookup.h"

namespace footprint {
namespace {

// A probe's bilinear weights and its level blend have 8 fractional bits on most GPUs (llvmpipe's
// float path has more): each weight is off by up to 2⁻⁹, so a probe of texels in [0, 1] by up to
// about 2·2⁻⁹ ≈ 4e-3 where neighbouring texels differ by 1 (white noise), and a blend of probes by
// no more. A transposed Jacobian or a footprint turned by 90° moves these lookups by 10 to 100
// times that (checked below, so that the tolerance resolves the method).
constexpr float kProbeTolerance = 5e-3f;
// c(N) from its definition in float, N exps summed: a few float roundings of a sum of up to 1024
// positive terms (the CPU's is double, rounded once).
constexpr float kSpacingRelativeTolerance = 2e-5f;

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// `name` ("footprint/texture.glsl") from the first of FOOTPRINT_GLSL_DIRS that holds it (the
// source tree's glsl/, then the build's generated version.glsl), each #include "…" line replaced
// by its file, every time: the include guards must keep the second copy out.
std::string resolved_library_file(const std::string& name) {
    std::string dirs = FOOTPRINT_GLSL_DIRS, text;
    for (std::size_t start = 0; start <= dirs.size();) {
        const std::size_t end = std::min(dirs.find('|', start), dirs.size());
        if (text.empty()) text = read_text(dirs.substr(start, end - start) + "/" + name);
        start = end + 1;
    }
    EXPECT_FALSE(text.empty()) << name << " not found in " << FOOTPRINT_GLSL_DIRS;
    std::string out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t hash = line.find_first_not_of(" \t");
        if (hash != std::string::npos && line.compare(hash, 8, "#include") == 0) {
            const std::size_t open = line.find('"'), close = line.find('"', open + 1);
            out += resolved_library_file(line.substr(open + 1, close - open - 1));
        } else {
            out += line + "\n";
        }
    }
    return out;
}

// A compute shader, one invocation i per lookup: `body` reads its vec4s from inputs[] and writes
// its results to outputs[], after the library files `includes` and `declarations`.
Result<gpu::Program> compile_lookup_shader(std::initializer_list<const char*> includes,
                                           const std::string& declarations,
                                           const std::string& body) {
    std::string source = "#version 450 core\nlayout(local_size_x = 1) in;\n";
    for (const char* name : includes) source += resolved_library_file(name);
    source += R"glsl(
#if !defined(FOOTPRINT_GLSL_VERSION) || FOOTPRINT_GLSL_VERSION_MAJOR * 10000 + \
    FOOTPRINT_GLSL_VERSION_MINOR * 100 + FOOTPRINT_GLSL_VERSION_PATCH != FOOTPRINT_GLSL_VERSION
#error "footprint/version.glsl's defines are missing or inconsistent"
#endif
layout(std430, binding = 0) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };
)glsl";
    source +=
        declarations + "\nvoid main() {\n    uint i = gl_GlobalInvocationID.x;\n" + body + "}\n";
    return gpu::compile_compute_program({source});
}

gpu::Buffer make_buffer(const void* data, std::size_t bytes) {
    gpu::Buffer buffer = gpu::create_buffer();
    glNamedBufferStorage(buffer.get(), static_cast<GLsizeiptr>(bytes), data,
                         GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
    return buffer;
}

// Runs `program` for `lookups` invocations; `outputs_per_lookup` vec4s come back per lookup.
std::vector<float> run_lookups(const gpu::Program& program, const std::vector<float>& inputs,
                               std::size_t lookups, int outputs_per_lookup) {
    gpu::Buffer in = make_buffer(inputs.data(), inputs.size() * sizeof(float));
    std::vector<float> out(lookups * 4 * static_cast<std::size_t>(outputs_per_lookup), -1.0f);
    gpu::Buffer result = make_buffer(out.data(), out.size() * sizeof(float));
    glUseProgram(program.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, result.get());
    glDispatchCompute(static_cast<GLuint>(lookups), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(result.get(), 0, static_cast<GLsizeiptr>(out.size() * sizeof(float)),
                            out.data());
    EXPECT_EQ(gpu::gl_error("running a library shader"), "");
    return out;
}

// Every level of `pyramid` as a trilinear-filtered RGBA32F texture of `target` (GL_TEXTURE_2D, or
// a face of a cube through `layer`), channels `first` … first + 3 of each texel (0 beyond).
void upload_levels(GLuint texture, const MipPyramid& pyramid, int first, int layer, bool cube) {
    for (int l = 0; l < pyramid.level_count(); ++l) {
        const Image level = pyramid.level_image(l);
        std::vector<float> rgba(level.pixel_count() * 4, 0.0f);
        for (std::size_t i = 0; i < level.pixel_count(); ++i)
            for (int c = 0; c < 4 && first + c < level.channels; ++c)
                rgba[4 * i + c] = level.pixels[i * level.channels + first + c];
        if (cube)
            glTextureSubImage3D(texture, l, 0, 0, layer, level.width, level.height, 1, GL_RGBA,
                                GL_FLOAT, rgba.data());
        else
            glTextureSubImage2D(texture, l, 0, 0, level.width, level.height, GL_RGBA, GL_FLOAT,
                                rgba.data());
    }
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    const GLint wrap = cube ? GL_CLAMP_TO_EDGE : GL_REPEAT;
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, wrap);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, wrap);
}

gpu::Texture upload_2d(const MipPyramid& pyramid, int first) {
    gpu::Texture texture = gpu::create_texture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.get(), pyramid.level_count(), GL_RGBA32F, pyramid.width(0),
                       pyramid.height(0));
    upload_levels(texture.get(), pyramid, first, 0, false);
    return texture;
}

Image white_noise(int width, int height, int channels, float lo, float hi, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> value(lo, hi);
    Image image(width, height, channels);
    for (float& v : image.pixels) v = value(rng);
    return image;
}

// Lookups of every size from magnified to 16× minified, anisotropic up to 12:1 in every
// direction, at random positions: (s, t, ∂s/∂x, ∂t/∂x), (∂s/∂y, ∂t/∂y, 0, 0) per lookup.
std::vector<TextureCoords> random_coords(int count, float texels, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<TextureCoords> coords;
    for (int i = 0; i < count; ++i) {
        const float major = std::exp2(-1.0f + 5.0f * unit(rng)) / texels;  // ½ … 16 texels
        const float ratio = 1.0f + 11.0f * unit(rng) * unit(rng);
        const float angle = 6.2831853f * unit(rng), skew = 0.5f * (unit(rng) - 0.5f);
        const float c = std::cos(angle), s = std::sin(angle);
        const float minor = major / ratio;
        // D = R diag(major, minor) (a slight shear): columns ∂(s,t)/∂x and ∂(s,t)/∂y.
        coords.push_back({unit(rng), unit(rng), major * c, major * s, -minor * s + skew * major * c,
                          minor * c + skew * major * s});
    }
    return coords;
}

std::vector<float> shader_inputs(const std::vector<TextureCoords>& coords) {
    std::vector<float> in;
    for (const TextureCoords& c : coords)
        in.insert(in.end(), {c.s, c.t, c.dsdx, c.dtdx, c.dsdy, c.dtdy, 0.0f, 0.0f});
    return in;
}

// RMS of the difference between two lookups' first `channels` values over all lookups.
float rms_difference(const std::vector<float>& a, const std::vector<float>& b, int stride,
                     int channels) {
    double sum = 0;
    const std::size_t n = a.size() / static_cast<std::size_t>(stride);
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < channels; ++c) {
            const double d = a[i * stride + c] - b[i * stride + c];
            sum += d * d;
        }
    return static_cast<float>(std::sqrt(sum / static_cast<double>(n * channels)));
}

// The CPU's footprint-assembly lookups (texture_lookup() with `options`) of `coords`, four
// channels each; `transform` may turn the footprint (a wrong Jacobian) first.
template <class Transform>
std::vector<float> cpu_lookups(const MipPyramid& pyramid, std::vector<TextureCoords> coords,
                               const LookupOptions& options, Transform transform) {
    std::vector<float> out;
    for (TextureCoords c : coords) {
        transform(c);
        float texel[4];
        texture_lookup(pyramid, c, options, texel);
        out.insert(out.end(), texel, texel + 4);
    }
    return out;
}

TEST(GlslLibrary, GaussianSpacingIsTheCpusForEveryProbeCount) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    Result<gpu::Program> program = compile_lookup_shader(
        {"footprint/texture.glsl"}, "",
        "    int n = int(inputs[2 * i].x);\n"
        "    outputs[i] = vec4(fp_gaussian_spacing(n), FOOTPRINT_GLSL_VERSION, "
        "FP_MAX_PROBE_COUNT, 0);\n");
    ASSERT_TRUE(program) << program.error().message;
    std::vector<float> in;
    for (int n = 0; n <= kMaxProbeCount + 2; ++n)
        in.insert(in.end(), {static_cast<float>(n), 0, 0, 0, 0, 0, 0, 0});
    const std::vector<float> out = run_lookups(*program, in, in.size() / 8, 1);
    float worst = 0;
    for (int n = 0; n <= kMaxProbeCount + 2; ++n) {
        const float expected = gaussian_spacing_factor(n), got = out[4 * n];
        worst = std::max(worst, std::abs(got - expected) / expected);
        ASSERT_NEAR(got, expected, kSpacingRelativeTolerance * expected) << "N = " << n;
    }
    std::printf("c(N): largest relative difference %.2g\n", worst);
    EXPECT_EQ(out[1], static_cast<float>(FOOTPRINT_VERSION_MAJOR * 10000 +
                                         FOOTPRINT_VERSION_MINOR * 100 + FOOTPRINT_VERSION_PATCH));
    EXPECT_EQ(out[2], static_cast<float>(kMaxProbeCount));
}

TEST(GlslLibrary, TextureIsTheCpusFootprintAssembly) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    const int size = 64;
    const MipPyramid pyramid = MipPyramid::build(white_noise(size, size, 4, 0.0f, 1.0f, 7));
    gpu::Texture texture = upload_2d(pyramid, 0);
    // Both entry points: the derivatives, and the Jacobian whose columns they are.
    Result<gpu::Program> program = compile_lookup_shader(
        {"footprint/texture.glsl"}, "uniform sampler2D u_texture;\nuniform int u_max_probes;\n",
        "    vec4 a = inputs[2 * i], b = inputs[2 * i + 1];\n"
        "    outputs[2 * i] = fp_texture(u_texture, a.xy, a.zw, b.xy, u_max_probes);\n"
        "    outputs[2 * i + 1] = fp_texture_jacobian(u_texture, a.xy, mat2(a.zw, b.xy), "
        "u_max_probes);\n");
    ASSERT_TRUE(program) << program.error().message;
    glBindTextureUnit(0, texture.get());
    const std::vector<TextureCoords> coords = random_coords(400, size, 11);
    for (const int max_probes : {30, 4}) {  // 4: lines beyond the budget raise their level
        LookupOptions options;
        options.max_probes = max_probes;
        glProgramUniform1i(program->get(), glGetUniformLocation(program->get(), "u_max_probes"),
                           max_probes);
        const std::vector<float> out =
            run_lookups(*program, shader_inputs(coords), coords.size(), 2);
        const std::vector<float> cpu = cpu_lookups(pyramid, coords, options, [](TextureCoords&) {});
        float worst = 0;
        for (std::size_t i = 0; i < coords.size(); ++i)
            for (int c = 0; c < 4; ++c) {
                worst = std::max(worst, std::abs(out[8 * i + c] - cpu[4 * i + c]));
                ASSERT_NEAR(out[8 * i + c], cpu[4 * i + c], kProbeTolerance)
                    << "lookup " << i << " channel " << c << ", max_probes " << max_probes;
                ASSERT_EQ(out[8 * i + 4 + c], out[8 * i + c])
                    << "fp_texture_jacobian, lookup " << i;
            }
        // The tolerance resolves the method: a transposed Jacobian, or the footprint turned by
        // 90° (major and minor axes swapped), is far outside it.
        const float transposed =
            rms_difference(cpu,
                           cpu_lookups(pyramid, coords, options,
                                       [](TextureCoords& c) { std::swap(c.dtdx, c.dsdy); }),
                           4, 4);
        const float turned = rms_difference(
            cpu,
            cpu_lookups(pyramid, coords, options,
                        [](TextureCoords& c) { c = {c.s, c.t, -c.dtdx, c.dsdx, -c.dtdy, c.dsdy}; }),
            4, 4);
        std::printf(
            "fp_texture, max_probes %d: largest difference %.2g; a transposed J moves the "
            "lookups by %.2g RMS, a turned footprint by %.2g\n",
            max_probes, worst, transposed, turned);
        EXPECT_GT(transposed, 5 * kProbeTolerance);
        EXPECT_GT(turned, 5 * kProbeTolerance);
    }
}

TEST(GlslLibrary, BumpIsTheCpusSlopeStatistics) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    const int size = 32;
    BumpPyramidOptions bump_options;
    bump_options.micro_roughness = {0.01f, 0.002f, 0.005f};
    Result<BumpPyramid> bumps =
        BumpPyramid::build(white_noise(size, size, 2, -0.4f, 0.6f, 5), bump_options);
    ASSERT_TRUE(bumps) << bumps.error().message;
    gpu::Texture moments0 = upload_2d(bumps->moments(), 0),
                 moments1 = upload_2d(bumps->moments(), 4);
    Result<gpu::Program> program = compile_lookup_shader(
        {"footprint/bump.glsl"},
        "uniform sampler2D u_moments0, u_moments1;\nuniform vec2 u_offset;\n",
        "    vec4 a = inputs[2 * i], b = inputs[2 * i + 1];\n"
        "    FpSlopeStats s = fp_bump(u_moments0, u_moments1, a.xy, a.zw, b.xy, u_offset, 30);\n"
        "    outputs[2 * i] = vec4(s.mean, s.k.x, s.k.z);\n"
        "    outputs[2 * i + 1] = vec4(s.k.y, fp_roughness_factor(s.k));\n");
    ASSERT_TRUE(program) << program.error().message;
    glProgramUniform1i(program->get(), glGetUniformLocation(program->get(), "u_moments0"), 0);
    glProgramUniform1i(program->get(), glGetUniformLocation(program->get(), "u_moments1"), 1);
    glProgramUniform2f(program->get(), glGetUniformLocation(program->get(), "u_offset"),
                       bumps->slope_offset().x, bumps->slope_offset().y);
    glBindTextureUnit(0, moments0.get());
    glBindTextureUnit(1, moments1.get());
    const std::vector<TextureCoords> coords = random_coords(300, size, 3);
    const std::vector<float> out = run_lookups(*program, shader_inputs(coords), coords.size(), 2);
    // Moments of slopes within ±0.6: the probes' weights move each by up to 0.6·kProbeTolerance,
    // K_b = M2 − μμᵀ by about twice that.
    const float tolerance = 1.2f * kProbeTolerance;
    float worst = 0, spread = 0;
    for (std::size_t i = 0; i < coords.size(); ++i) {
        const SlopeStatistics cpu = bump_lookup(*bumps, coords[i], BumpLookupOptions{});
        const float* stats = &out[8 * i];  // μ1, μ2, k11, k22, k12, d1, d2, d3
        const float got[5] = {stats[0], stats[1], stats[2], stats[4], stats[3]};
        const float expected[5] = {cpu.mean.x, cpu.mean.y, cpu.covariance.xx, cpu.covariance.xy,
                                   cpu.covariance.yy};
        for (int k = 0; k < 5; ++k) {
            worst = std::max(worst, std::abs(got[k] - expected[k]));
            ASSERT_NEAR(got[k], expected[k], tolerance) << "lookup " << i << ", statistic " << k;
        }
        // B Bᵀ = K_b: d1² + d2² = k11, d2 d3 = k12, d3² = k22.
        const float d1 = stats[5], d2 = stats[6], d3 = stats[7];
        EXPECT_NEAR(d1 * d1 + d2 * d2, got[2], 1e-5f);
        EXPECT_NEAR(d2 * d3, got[3], 1e-5f);
        EXPECT_NEAR(d3 * d3, got[4], 1e-5f);
        spread = std::max(spread, cpu.covariance.xx);
    }
    std::printf("fp_bump: largest difference %.2g (largest k11 %.3g)\n", worst, spread);
    EXPECT_GT(spread, 10 * tolerance);  // the roughness is there to be compared
}

TEST(GlslLibrary, EnvironmentCubeIsTheCpusCubeLookup) {
    FOOTPRINT_GPU_DEVICE_OR_SKIP();
    const int size = 32;
    std::array<Image, 6> faces;
    for (int f = 0; f < 6; ++f) faces[f] = white_noise(size, size, 4, 0.0f, 1.0f, 20 + f);
    Result<EnvironmentMap> map = EnvironmentMap::from_cube_faces(faces);
    ASSERT_TRUE(map) << map.error().message;
    gpu::Texture cube = gpu::create_texture(GL_TEXTURE_CUBE_MAP);
    glTextureStorage2D(cube.get(), map->face(0).level_count(), GL_RGBA32F, size, size);
    for (int f = 0; f < 6; ++f) upload_levels(cube.get(), map->face(f), 0, f, true);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    // dir, ∂dir/∂x, ∂dir/∂y, rough1, rough2, κ: 16 floats, four vec4s per lookup.
    Result<gpu::Program> program = compile_lookup_shader(
        {"footprint/environment.glsl"}, "uniform samplerCube u_cube;\n",
        "    vec4 a = inputs[4 * i], b = inputs[4 * i + 1], c = inputs[4 * i + 2];\n"
        "    vec4 d = inputs[4 * i + 3];\n"
        "    outputs[i] = fp_environment_cube(u_cube, a.xyz, vec3(a.w, b.xy), vec3(b.zw, c.x), "
        "c.yzw,\n"
        "                                     d.xyz, d.w, 30);\n");
    ASSERT_TRUE(program) << program.error().message;
    glBindTextureUnit(0, cube.get());
    std::mt19937 rng(17);
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto random_vector = [&](float scale) {
        return Vec3{scale * normal(rng), scale * normal(rng), scale * normal(rng)};
    };
    std::vector<float> in, cpu;
    const float kappa = 2.0f;
    for (int i = 0; i < 300; ++i) {
        const Vec3 r = random_vector(1.0f);
        const float spread = std::exp2(-7.0f + 5.0f * unit(rng));  // ¼ … 8 texels of a 32² face
        Vec3 dx = random_vector(spread), dy = random_vector(spread * unit(rng) * unit(rng));
        const bool rough = i % 2 == 1;
        Vec3 rough1 = rough ? random_vector(0.3f * spread) : Vec3{},
             rough2 = rough ? random_vector(0.1f * spread) : Vec3{};
        in.insert(in.end(), {r.x, r.y, r.z, dx.x, dx.y, dx.z, dy.x, dy.y, dy.z, rough1.x, rough1.y,
                             rough1.z, rough2.x, rough2.y, rough2.z, kappa});
        const EnvFootprint footprint = compute_env_footprint(
            EnvLayout::cube, map->texel_scale(), r, dx, dy, rough1, rough2, {kappa, Mat3{}});
        float texel[4];
        environment_lookup(*map, footprint, LookupOptions{}, texel);
        cpu.insert(cpu.end(), texel, texel + 4);
    }
    const std::vector<float> out = run_lookups(*program, in, cpu.size() / 4, 1);
    float worst = 0;
    for (std::size_t i = 0; i < cpu.size() / 4; ++i)
        for (int c = 0; c < 4; ++c) {
            worst = std::max(worst, std::abs(out[4 * i + c] - cpu[4 * i + c]));
            EXPECT_NEAR(out[4 * i + c], cpu[4 * i + c], kProbeTolerance)
                << "lookup " << i << " channel " << c;
        }
    std::printf("fp_environment_cube: largest difference %.2g\n", worst);
}

}  // namespace
}  // namespace footprint
