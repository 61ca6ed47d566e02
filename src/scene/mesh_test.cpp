#include "scene/mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/test_shared_data.h"
#include "core/test_temp_dir.h"
#include "image/color.h"
#include "image/image_io.h"

namespace footprint {
namespace {

namespace fs = std::filesystem;

using test::shared_data_dir;

using test::TempDir;

void write_file(const fs::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary);
    out << text;
}

std::string read_file(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string base64(const std::string& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                           (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                           static_cast<unsigned char>(bytes[i + 2]);
        for (int k = 3; k >= 0; --k) out += table[(v >> (6 * k)) & 63];
    }
    if (i + 1 == bytes.size()) {
        const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == bytes.size()) {
        const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                           (static_cast<unsigned char>(bytes[i + 1]) << 8);
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += table[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

// A 2×2 RGB PNG holding exactly the 8-bit codes given (written as linear, so no encoding).
void write_png_codes(const fs::path& file, const std::vector<int>& codes) {
    Image img(2, 2, 3);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = codes[i] / 255.0f;
    ImageSaveOptions options;
    options.encoding = ColorEncoding::linear;
    ASSERT_TRUE(save_image(img, file, options).ok());
}

const std::vector<int> kBaseCodes = {0, 64, 128, 255, 10, 20, 30, 40, 50, 200, 100, 7};
const std::vector<int> kNormalCodes = {128, 128, 255, 255, 128, 128, 0, 128, 128, 128, 0, 128};

void expect_near(Vec3d a, Vec3d b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

// ---------------------------------------------------------------------------------------------
// OBJ

constexpr const char* kQuadObj = R"(mtllib quad.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
v 2 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
usemtl red
f 1/1/1 2/2/1 3/3/1 4/4/1
usemtl textured
f 2/1/1 5/2/1 6/3/1
)";

constexpr const char* kQuadMtl = R"(newmtl red
Kd 0.5 0.25 0.125
newmtl textured
Kd 1 1 1
map_Kd tex.png
)";

TEST(MeshObj, LoadsPositionsUvsNormalsAndMaterials) {
    TempDir dir;
    write_file(dir / "quad.obj", kQuadObj);
    write_file(dir / "quad.mtl", kQuadMtl);
    Image tex(2, 2, 3, 0.25f);
    tex.at(1, 0, 0) = 1.0f;
    ASSERT_TRUE(save_image(tex, dir / "tex.png").ok());  // sRGB-encoded

    Result<MeshAsset> asset = load_mesh(dir / "quad.obj", {});
    ASSERT_TRUE(asset.ok()) << asset.error().message;
    ASSERT_EQ(asset->meshes.size(), 2u);
    EXPECT_EQ(asset->triangle_count(), 3u);

    const TriangleMesh& red = asset->meshes[0];
    EXPECT_EQ(red.name, "red");
    EXPECT_EQ(red.triangles.size(), 2u);
    EXPECT_EQ(red.positions.size(), 4u);
    ASSERT_TRUE(red.has_normals());
    ASSERT_TRUE(red.has_uvs());
    EXPECT_FALSE(red.has_tangents());
    for (std::size_t i = 0; i < red.positions.size(); ++i) {
        expect_near(red.normals[i], {0, 0, 1}, 1e-12);
        // In this file vt equals the position's (x, y): v up, as in OBJ.
        EXPECT_NEAR(red.uvs[i].x, red.positions[i].x, 1e-12);
        EXPECT_NEAR(red.uvs[i].y, red.positions[i].y, 1e-12);
    }
    EXPECT_FLOAT_EQ(red.material.base_color.x, 0.5f);
    EXPECT_FLOAT_EQ(red.material.base_color.y, 0.25f);
    EXPECT_FLOAT_EQ(red.material.base_color.z, 0.125f);
    EXPECT_FALSE(red.material.has_base_color_texture());
    EXPECT_FALSE(red.material.has_normal_texture());
    EXPECT_FALSE(red.material.metallic_roughness);  // OBJ: the scene's model

    const TriangleMesh& textured = asset->meshes[1];
    EXPECT_EQ(textured.triangles.size(), 1u);
    ASSERT_TRUE(textured.material.has_base_color_texture());
    const Image& t = *textured.material.base_color_texture;
    ASSERT_EQ(t.width, 2);
    ASSERT_EQ(t.height, 2);
    EXPECT_NEAR(t.at(0, 0, 0), 0.25f, 0.01f);  // decoded back to linear
    EXPECT_NEAR(t.at(1, 0, 0), 1.0f, 1e-6f);
}

TEST(MeshObj, TransformScalesThenRotatesThenTranslates) {
    TempDir dir;
    write_file(dir / "tri.obj",
               "v 0 0 0\nv 1 -1 0\nv 0 0 1\nvn 1 1 0\nvn 1 1 0\nvn 1 1 0\nf 1//1 2//2 3//3\n");
    MeshTransform xf;
    xf.scale = {2, 1, 1};
    xf.rotate_deg = {0, 0, 90};  // (x, y, z) → (−y, x, z)
    xf.translate = {1, 2, 3};
    Result<MeshAsset> asset = load_mesh(dir / "tri.obj", xf);
    ASSERT_TRUE(asset.ok()) << asset.error().message;
    const TriangleMesh& m = asset->meshes.at(0);
    ASSERT_EQ(m.positions.size(), 3u);
    // Find each vertex by its original index through the triangle.
    const auto& tri = m.triangles.at(0);
    expect_near(m.positions[tri[0]], {1, 2, 3}, 1e-6);
    expect_near(m.positions[tri[1]], {2, 4, 3}, 1e-6);  // S: (2,−1,0), R: (1,2,0)
    expect_near(m.positions[tri[2]], {1, 2, 4}, 1e-6);  // (0,0,1) stays
    // Normal: R·S⁻¹·n = R·(0.5, 1, 0) = (−1, 0.5, 0), normalised.
    const Vec3d expected = normalize(Vec3d{-1, 0.5, 0});
    for (const Vec3d& n : m.normals) expect_near(n, expected, 1e-6);
    // The normal was perpendicular to the triangle and stays so.
    const Vec3d e1 = m.positions[tri[1]] - m.positions[tri[0]];
    const Vec3d e2 = m.positions[tri[2]] - m.positions[tri[0]];
    EXPECT_NEAR(dot(e1, expected), 0, 1e-6);
    EXPECT_NEAR(dot(e2, expected), 0, 1e-6);
}

TEST(MeshObj, MirroringKeepsTheFrontSide) {
    TempDir dir;
    write_file(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    MeshTransform xf;
    xf.scale = {-1, 1, 1};
    Result<MeshAsset> asset = load_mesh(dir / "tri.obj", xf);
    ASSERT_TRUE(asset.ok()) << asset.error().message;
    const TriangleMesh& m = asset->meshes.at(0);
    const auto& t = m.triangles.at(0);
    const Vec3d ng =
        cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    EXPECT_GT(ng.z, 0);  // the front still faces +z (mirroring x does not turn it)
}

// ---------------------------------------------------------------------------------------------
// glTF

struct GltfBuilder {
    std::string bin;
    std::vector<std::string> views, accessors;

    template <class T>
    int add(const std::vector<T>& data, int component_type, const std::string& type, int count) {
        while (bin.size() % 4) bin.push_back('\0');
        const std::size_t offset = bin.size();
        bin.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(T));
        views.push_back(R"({"buffer":0,"byteOffset":)" + std::to_string(offset) +
                        R"(,"byteLength":)" + std::to_string(data.size() * sizeof(T)) + "}");
        accessors.push_back(R"({"bufferView":)" + std::to_string(views.size() - 1) +
                            R"(,"componentType":)" + std::to_string(component_type) +
                            R"(,"count":)" + std::to_string(count) + R"(,"type":")" + type +
                            R"("})");
        return static_cast<int>(accessors.size() - 1);
    }

    static std::string join(const std::vector<std::string>& v) {
        std::string s;
        for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + v[i];
        return s;
    }

    // The document; `embed` puts the buffer in a data URI, otherwise it has no uri (GLB).
    std::string json(const std::string& body, bool embed) const {
        std::string buffer = R"({"byteLength":)" + std::to_string(bin.size());
        if (embed)
            buffer += R"(,"uri":"data:application/octet-stream;base64,)" + base64(bin) + "\"";
        buffer += "}";
        return R"({"asset":{"version":"2.0"},)" + body + R"(,"bufferViews":[)" + join(views) +
               R"(],"accessors":[)" + join(accessors) + R"(],"buffers":[)" + buffer + "]}";
    }

    std::string glb(const std::string& body) const {
        std::string js = json(body, false);
        while (js.size() % 4) js.push_back(' ');
        std::string b = bin;
        while (b.size() % 4) b.push_back('\0');
        auto u32 = [](std::uint32_t v) {
            return std::string(reinterpret_cast<const char*>(&v), 4);
        };
        const std::uint32_t total = 12 + 8 + static_cast<std::uint32_t>(js.size()) + 8 +
                                    static_cast<std::uint32_t>(b.size());
        return "glTF" + u32(2) + u32(total) + u32(static_cast<std::uint32_t>(js.size())) +
               u32(0x4E4F534A) + js + u32(static_cast<std::uint32_t>(b.size())) + u32(0x004E4942) +
               b;
    }
};

constexpr int kFloat = 5126, kU8 = 5121, kU16 = 5123, kU32 = 5125;

// A unit quad in z = 0 under a node hierarchy (translate (0,0,5), then scale 2), plus a points
// primitive (skipped) and a node outside the scene (ignored). Indices of `index_type`.
struct QuadGltf {
    GltfBuilder b;
    std::string body;

    QuadGltf(int index_type, std::vector<std::uint32_t> index = {0, 1, 2, 0, 2, 3}, float x0 = 0) {
        const int pos =
            b.add(std::vector<float>{x0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, kFloat, "VEC3", 4);
        const int nrm =
            b.add(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 4);
        // glTF (s, t) with t down the image: the bottom vertices have t = 1.
        const int uv =
            b.add(std::vector<float>{0, 1, 1, 1, 1, 0, 0.25f, 0.125f}, kFloat, "VEC2", 4);
        const int tan = b.add(std::vector<float>{1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, -1},
                              kFloat, "VEC4", 4);
        int idx = 0;
        const int n = static_cast<int>(index.size());
        if (index_type == kU8) {
            idx = b.add(std::vector<std::uint8_t>(index.begin(), index.end()), kU8, "SCALAR", n);
        } else if (index_type == kU16) {
            idx = b.add(std::vector<std::uint16_t>(index.begin(), index.end()), kU16, "SCALAR", n);
        } else {
            idx = b.add(index, kU32, "SCALAR", n);
        }
        const auto s = [](int i) { return std::to_string(i); };
        body = R"("scene":0,"scenes":[{"nodes":[0]}],)"
               R"("nodes":[{"children":[1],"translation":[0,0,5]},{"mesh":0,"scale":[2,2,2]},)"
               R"({"mesh":0,"translation":[100,0,0]}],)"
               R"("meshes":[{"name":"quad","primitives":[)"
               R"({"attributes":{"POSITION":)" +
               s(pos) + R"(,"NORMAL":)" + s(nrm) + R"(,"TEXCOORD_0":)" + s(uv) + R"(,"TANGENT":)" +
               s(tan) + R"(},"indices":)" + s(idx) +
               R"(,"material":0},)"
               R"({"attributes":{"POSITION":)" +
               s(pos) +
               R"(},"mode":0}]}],)"
               R"("materials":[{"name":"mat","pbrMetallicRoughness":{"baseColorFactor":)"
               R"([0.5,0.25,1,1],"baseColorTexture":{"index":0},"metallicFactor":0.25,)"
               R"("roughnessFactor":0.75,"metallicRoughnessTexture":{"index":1}},)"
               R"("normalTexture":{"index":1,"scale":0.5}}],)"
               R"("textures":[{"source":0},{"source":1}],)";
    }

    // Writes base.png next to the file and the normal map as a data URI.
    std::string images(const TempDir& dir) const {
        write_png_codes(dir / "base.png", kBaseCodes);
        write_png_codes(dir / "normal_tmp.png", kNormalCodes);
        const std::string normal = base64(read_file(dir / "normal_tmp.png"));
        fs::remove(dir / "normal_tmp.png");
        return R"("images":[{"uri":"base.png"},{"uri":"data:image/png;base64,)" + normal + "\"}]";
    }
};

void check_quad(const MeshAsset& asset) {
    ASSERT_EQ(asset.meshes.size(), 1u);  // points skipped, the node outside the scene ignored
    const TriangleMesh& m = asset.meshes[0];
    EXPECT_EQ(m.name, "quad");
    ASSERT_EQ(m.positions.size(), 4u);
    ASSERT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
    EXPECT_EQ(m.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
    // Node transform: p' = 2·p + (0, 0, 5).
    expect_near(m.positions[0], {0, 0, 5}, 1e-12);
    expect_near(m.positions[1], {2, 0, 5}, 1e-12);
    expect_near(m.positions[2], {2, 2, 5}, 1e-12);
    expect_near(m.positions[3], {0, 2, 5}, 1e-12);
    ASSERT_TRUE(m.has_normals() && m.has_uvs() && m.has_tangents());
    for (const Vec3d& n : m.normals) expect_near(n, {0, 0, 1}, 1e-12);
    // uv = (s, 1 − t): v up.
    EXPECT_NEAR(m.uvs[0].x, 0, 1e-7);
    EXPECT_NEAR(m.uvs[0].y, 0, 1e-7);
    EXPECT_NEAR(m.uvs[2].x, 1, 1e-7);
    EXPECT_NEAR(m.uvs[2].y, 1, 1e-7);
    EXPECT_NEAR(m.uvs[3].x, 0.25, 1e-7);
    EXPECT_NEAR(m.uvs[3].y, 0.875, 1e-7);
    expect_near(m.tangents[0].xyz, {1, 0, 0}, 1e-12);
    EXPECT_EQ(m.tangents[0].w, 1);
    EXPECT_EQ(m.tangents[3].w, -1);

    const MeshMaterial& mat = m.material;
    EXPECT_EQ(mat.name, "mat");
    EXPECT_FLOAT_EQ(mat.base_color.x, 0.5f);
    EXPECT_FLOAT_EQ(mat.base_color.y, 0.25f);
    EXPECT_FLOAT_EQ(mat.base_color.z, 1.0f);
    EXPECT_FLOAT_EQ(mat.normal_scale, 0.5f);
    ASSERT_TRUE(mat.has_base_color_texture());
    ASSERT_TRUE(mat.has_normal_texture());
    const Image& base = *mat.base_color_texture;
    const Image& normal = *mat.normal_texture;
    ASSERT_EQ(base.width, 2);
    ASSERT_EQ(base.height, 2);
    ASSERT_EQ(base.channels, 3);
    ASSERT_EQ(normal.channels, 3);
    for (std::size_t i = 0; i < base.pixels.size(); ++i) {
        EXPECT_FLOAT_EQ(base.pixels[i], srgb_to_linear(kBaseCodes[i] / 255.0f)) << i;
        EXPECT_FLOAT_EQ(normal.pixels[i], kNormalCodes[i] / 255.0f) << i;
    }
    // Metallic-roughness: the factors, and the texture as data (here the normal map's image).
    EXPECT_TRUE(mat.metallic_roughness);
    EXPECT_FLOAT_EQ(mat.metallic, 0.25f);
    EXPECT_FLOAT_EQ(mat.roughness, 0.75f);
    ASSERT_NE(mat.metallic_roughness_texture, nullptr);
    EXPECT_EQ(mat.metallic_roughness_texture->pixels, normal.pixels);
}

TEST(MeshGltf, LoadsEmbeddedBufferNodesMaterialsAndTextures) {
    for (int type : {kU8, kU16, kU32}) {
        SCOPED_TRACE(type);
        TempDir dir;
        QuadGltf q(type);
        write_file(dir / "quad.gltf", q.b.json(q.body + q.images(dir), true));
        Result<MeshAsset> asset = load_mesh(dir / "quad.gltf");
        ASSERT_TRUE(asset.ok()) << asset.error().message;
        check_quad(*asset);
    }
}

TEST(MeshGltf, LoadsGlb) {
    TempDir dir;
    QuadGltf q(kU16);
    write_file(dir / "quad.GLB", q.b.glb(q.body + q.images(dir)));
    Result<MeshAsset> asset = load_mesh(dir / "quad.GLB");
    ASSERT_TRUE(asset.ok()) << asset.error().message;
    check_quad(*asset);
}

TEST(MeshGltf, UserTransformAppliesAfterTheNodes) {
    TempDir dir;
    QuadGltf q(kU16);
    write_file(dir / "quad.gltf", q.b.json(q.body + q.images(dir), true));
    MeshTransform xf;
    xf.translate = {10, 0, 0};
    xf.scale = {1, 1, 0.5};
    Result<MeshAsset> asset = load_mesh(dir / "quad.gltf", xf);
    ASSERT_TRUE(asset.ok()) << asset.error().message;
    expect_near(asset->meshes.at(0).positions[2], {12, 2, 2.5}, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST(MeshErrors, MissingFileNamesTheFile) {
    for (const char* name : {"no_such_mesh.obj", "no_such_mesh.gltf", "no_such_mesh.glb"}) {
        Result<MeshAsset> r = load_mesh(name);
        ASSERT_FALSE(r.ok());
        EXPECT_TRUE(contains(r.error().message, name)) << r.error().message;
        EXPECT_TRUE(contains(r.error().message, "no such file")) << r.error().message;
    }
}

TEST(MeshErrors, GarbageContentNamesTheFile) {
    TempDir dir;
    for (const char* name : {"garbage.gltf", "garbage.glb", "garbage.obj"}) {
        write_file(dir / name, "this is not a mesh {{{\n");
        Result<MeshAsset> r = load_mesh(dir / name);
        ASSERT_FALSE(r.ok()) << name;
        EXPECT_TRUE(contains(r.error().message, name)) << r.error().message;
    }
    write_file(dir / "empty.obj", "# nothing here\nv 0 0 0\n");
    Result<MeshAsset> r = load_mesh(dir / "empty.obj");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error().message, "empty.obj")) << r.error().message;
    EXPECT_TRUE(contains(r.error().message, "no triangles")) << r.error().message;
}

TEST(MeshErrors, UnsupportedExtensionAndBadTransform) {
    TempDir dir;
    write_file(dir / "mesh.ply", "ply\n");
    Result<MeshAsset> r = load_mesh(dir / "mesh.ply");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error().message, "mesh.ply")) << r.error().message;
    EXPECT_TRUE(contains(r.error().message, "unsupported extension")) << r.error().message;

    write_file(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    MeshTransform xf;
    xf.scale = {1, 0, 1};
    r = load_mesh(dir / "tri.obj", xf);
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error().message, "tri.obj")) << r.error().message;
}

TEST(MeshErrors, OutOfRangeIndicesNameTheFile) {
    TempDir dir;
    write_file(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    Result<MeshAsset> r = load_mesh(dir / "bad.obj");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error().message, "bad.obj")) << r.error().message;

    QuadGltf q(kU16, {0, 1, 7});
    write_file(dir / "bad.gltf", q.b.json(q.body + q.images(dir), true));
    r = load_mesh(dir / "bad.gltf");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error().message, "bad.gltf")) << r.error().message;
    EXPECT_TRUE(contains(r.error().message, "index 7 out of range")) << r.error().message;
}

TEST(MeshErrors, NonFinitePositionNamesTheFile) {
    TempDir dir;
    QuadGltf q(kU16, {0, 1, 2, 0, 2, 3}, std::nanf(""));
    write_file(dir / "nan.gltf", q.b.json(q.body + q.images(dir), true));
    Result<MeshAsset> r = load_mesh(dir / "nan.gltf");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error().message, "nan.gltf")) << r.error().message;
    EXPECT_TRUE(contains(r.error().message, "non-finite")) << r.error().message;
}

TEST(MeshErrors, MissingTextureNamesTheFiles) {
    TempDir dir;
    write_file(dir / "quad.obj", kQuadObj);
    write_file(dir / "quad.mtl", kQuadMtl);  // tex.png is not there
    Result<MeshAsset> r = load_mesh(dir / "quad.obj");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error().message, "quad.obj")) << r.error().message;
    EXPECT_TRUE(contains(r.error().message, "tex.png")) << r.error().message;
}

TEST(MeshErrors, NonFiniteObjValuesNameTheFileTheLineAndTheValue) {
    struct Case {
        const char* line;
        const char* value;
        const char* keyword;
    };
    const Case cases[] = {
        {"v nan 0 0", "'nan'", "'v' value 1"},
        {"v inf 0 0", "'inf'", "'v' value 1"},
        {"v 0 -inf 0", "'-inf'", "'v' value 2"},
        {"v 0 0 1e999", "'1e999'", "'v' value 3"},  // overflows a double
        {"v 0 0 zero", "'zero'", "'v' value 3"},
        {"vn 0 NaN 1", "'NaN'", "'vn' value 2"},
        {"vt Infinity 0", "'Infinity'", "'vt' value 1"},
    };
    TempDir dir;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.line);
        // Line 4 holds the bad value; the face uses it (v) or not (vn, vt): either way it is read.
        write_file(dir / "bad.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\n") + c.line +
                                        "\nvt 0 0\nvn 0 0 1\nf 1 2 3\n");
        const Result<MeshAsset> r = load_mesh(dir / "bad.obj");
        ASSERT_FALSE(r.ok());
        const std::string& message = r.error().message;
        EXPECT_TRUE(contains(message, "cannot read '" + (dir / "bad.obj").string() + "'"))
            << message;
        EXPECT_TRUE(contains(message, "line 4")) << message;
        EXPECT_TRUE(contains(message, c.keyword)) << message;
        EXPECT_TRUE(contains(message, std::string("is ") + c.value + ", not a finite number"))
            << message;
    }
    // Signs, exponents, comments, tabs, CRLF and vertex colours are fine.
    write_file(dir / "good.obj",
               "v +0 0 0 # origin\r\nv\t1e0 0 0 0.5 0.5 0.5\nv 0 1.0E+0 -0\nvt .5 1.\nf 1 2 3\n");
    const Result<MeshAsset> good = load_mesh(dir / "good.obj");
    ASSERT_TRUE(good.ok()) << good.error().message;
    expect_near(good->meshes.at(0).positions[1], {1, 0, 0}, 0);
}

TEST(MeshErrors, NonFiniteGltfValuesNameTheAttributeAndTheElement) {
    TempDir dir;
    QuadGltf q(kU16, {0, 1, 2, 0, 2, 3}, std::numeric_limits<float>::infinity());
    write_file(dir / "inf.gltf", q.b.json(q.body + q.images(dir), true));
    const Result<MeshAsset> r = load_mesh(dir / "inf.gltf");
    ASSERT_FALSE(r.ok());
    const std::string& message = r.error().message;
    EXPECT_TRUE(contains(message, "inf.gltf")) << message;
    EXPECT_TRUE(contains(message,
                         "(POSITION of mesh 'quad'): element 0 holds the non-finite "
                         "value inf"))
        << message;
}

TEST(MeshErrors, MissingGltfTextureNamesTheFileAndItsMaterial) {
    TempDir dir;
    QuadGltf q(kU16);
    std::string images = q.images(dir);
    fs::remove(dir / "base.png");
    write_file(dir / "quad.gltf", q.b.json(q.body + images, true));
    Result<MeshAsset> r = load_mesh(dir / "quad.gltf");
    ASSERT_FALSE(r.ok());
    std::string message = r.error().message;
    EXPECT_TRUE(contains(message, "cannot read '" + (dir / "quad.gltf").string() + "'")) << message;
    EXPECT_TRUE(contains(message, "baseColorTexture of material 'mat' (texture 0)")) << message;
    EXPECT_TRUE(contains(message, "image 0 'base.png': file not found (resolved to '" +
                                      (dir / "base.png").string() + "')"))
        << message;
    EXPECT_FALSE(contains(message, "was not decoded")) << message;  // not "(-1×-1, -1 channels"

    // A URI's %20 is a space in the file name.
    const std::size_t at = images.find("base.png");
    images.replace(at, 8, "my%20base.png");
    write_file(dir / "quad.gltf", q.b.json(q.body + images, true));
    r = load_mesh(dir / "quad.gltf");
    ASSERT_FALSE(r.ok());
    message = r.error().message;
    EXPECT_TRUE(contains(message, "(resolved to '" + (dir / "my base.png").string() + "')"))
        << message;
}

TEST(MeshErrors, MetallicRoughnessFactorsOutsideTheGltfRangeNameTheMaterial) {
    TempDir dir;
    QuadGltf q(kU16);
    std::string body = q.body;
    body.replace(body.find("\"roughnessFactor\":0.75"), 22, "\"roughnessFactor\":1.50");
    write_file(dir / "quad.gltf", q.b.json(body + q.images(dir), true));
    const Result<MeshAsset> r = load_mesh(dir / "quad.gltf");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error().message, "roughnessFactor of material 'mat' is 1.5"))
        << r.error().message;
    EXPECT_TRUE(contains(r.error().message, "glTF allows [0, 1]")) << r.error().message;
}

// ---------------------------------------------------------------------------------------------
// Shared data (skipped when absent)

void expect_bounds(const MeshAsset& asset, Vec3d lo, Vec3d hi, double tol) {
    Vec3d a{1e300, 1e300, 1e300}, b{-1e300, -1e300, -1e300};
    for (const TriangleMesh& m : asset.meshes)
        for (const Vec3d& p : m.positions) {
            a = {std::min(a.x, p.x), std::min(a.y, p.y), std::min(a.z, p.z)};
            b = {std::max(b.x, p.x), std::max(b.y, p.y), std::max(b.z, p.z)};
        }
    expect_near(a, lo, tol);
    expect_near(b, hi, tol);
}

TEST(MeshSharedData, SpotObj) {
    const fs::path dir = shared_data_dir() / "meshes" / "spot";
    if (!fs::exists(dir / "spot_triangulated.obj")) GTEST_SKIP() << test::missing_shared_data(dir);
    Result<MeshAsset> asset = load_mesh(dir / "spot_triangulated.obj");
    ASSERT_TRUE(asset.ok()) << asset.error().message;
    ASSERT_EQ(asset->meshes.size(), 1u);  // no materials: one group
    const TriangleMesh& m = asset->meshes[0];
    EXPECT_EQ(m.triangles.size(), 5856u);
    EXPECT_TRUE(m.has_uvs());
    EXPECT_FALSE(m.has_normals());   // the file has no vn
    for (const Vec2d& uv : m.uvs) {  // the unit square, up to a small overshoot in the file
        EXPECT_GE(uv.x, -0.1);
        EXPECT_LE(uv.x, 1.1);
        EXPECT_GE(uv.y, -0.1);
        EXPECT_LE(uv.y, 1.1);
    }
    expect_bounds(*asset, {-0.471552, -0.736784, -0.668909}, {0.471552, 0.953646, 1.049}, 1e-6);
    // The OBJ names no material; its texture comes with it and loads as an image.
    Result<Image> tex = load_image(dir / "spot_texture.png");
    ASSERT_TRUE(tex.ok()) << tex.error().message;
    EXPECT_EQ(tex->width, 1024);
    EXPECT_EQ(tex->height, 1024);
}

TEST(MeshSharedData, FlightHelmetGltf) {
    const fs::path file = shared_data_dir() / "meshes" / "FlightHelmet" / "FlightHelmet.gltf";
    if (!fs::exists(file)) GTEST_SKIP() << test::missing_shared_data(file);
    Result<MeshAsset> asset = load_mesh(file);
    ASSERT_TRUE(asset.ok()) << asset.error().message;
    ASSERT_EQ(asset->meshes.size(), 6u);
    EXPECT_EQ(asset->triangle_count(), 94722u);
    expect_bounds(*asset, {-0.203642711, -2.14242937e-05, -0.171545789},
                  {0.162940636, 0.716000438, 0.200029165}, 1e-6);
    for (const TriangleMesh& m : asset->meshes) {
        SCOPED_TRACE(m.name);
        EXPECT_TRUE(m.has_normals());
        EXPECT_TRUE(m.has_uvs());
        EXPECT_TRUE(m.has_tangents());
        ASSERT_TRUE(m.material.has_base_color_texture());
        ASSERT_TRUE(m.material.has_normal_texture());
        EXPECT_GT(m.material.base_color_texture->width, 0);
        EXPECT_GT(m.material.normal_texture->width, 0);
        // A normal map's texels point mostly out of the surface: blue ≳ 0.5 on average.
        const Image& nt = *m.material.normal_texture;
        ASSERT_GE(nt.channels, 3);
        double blue = 0;
        for (std::size_t i = 0; i < nt.pixel_count(); ++i) blue += nt.pixels[i * nt.channels + 2];
        EXPECT_GT(blue / static_cast<double>(nt.pixel_count()), 0.5);
    }
    // Every part is metallic-roughness, with a texture (roughness in G, metallic in B).
    for (const TriangleMesh& m : asset->meshes) {
        EXPECT_TRUE(m.material.metallic_roughness);
        ASSERT_NE(m.material.metallic_roughness_texture, nullptr) << m.name;
        EXPECT_GE(m.material.metallic_roughness_texture->channels, 3);
    }
    // Materials shared by meshes share their decoded images.
    EXPECT_EQ(asset->meshes[0].material.base_color_texture,
              asset->meshes[1].material.base_color_texture);
}

}  // namespace
}  // namespace footprint
