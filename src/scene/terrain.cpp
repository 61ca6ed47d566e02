#include "scene/terrain.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace footprint {

namespace {

std::uint64_t mix(std::uint64_t z) {  // SplitMix64's finaliser
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// A standard normal number for point (x, y) of the finest lattice (Box–Muller of two hashes).
double lattice_gaussian(std::uint32_t seed, int x, int y) {
    const std::uint64_t key =
        mix(mix(seed) ^ (static_cast<std::uint64_t>(x) << 32 | static_cast<std::uint32_t>(y)));
    const double u1 = (static_cast<double>(key >> 11) + 0.5) * 0x1.0p-53;
    const double u2 = static_cast<double>(mix(key) >> 11) * 0x1.0p-53;
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
}

int side_samples(const TerrainShape& shape) {
    return (1 << std::clamp(shape.subdivisions, 1, kMaxTerrainSubdivisions)) + 1;
}

}  // namespace

std::vector<double> terrain_heights(const TerrainShape& shape) {
    const int n = side_samples(shape);
    const int lattice_step = (1 << kMaxTerrainSubdivisions) / (n - 1);  // the finest lattice's
    std::vector<double> h(static_cast<std::size_t>(n) * n);
    auto at = [&](int i, int j) -> double& { return h[static_cast<std::size_t>(j) * n + i]; };
    // The displacement of sample (i, j) whose neighbours are d away (the side = 1).
    auto displacement = [&](int i, int j, double d) {
        return shape.height * std::pow(d, shape.roughness) *
               lattice_gaussian(shape.seed, i * lattice_step, j * lattice_step);
    };
    for (int j : {0, n - 1})
        for (int i : {0, n - 1}) at(i, j) = displacement(i, j, 1);
    for (int step = n - 1; step > 1; step /= 2) {
        const int half = step / 2;
        const double side = static_cast<double>(step) / (n - 1);
        for (int j = half; j < n; j += step)  // square: each square's centre
            for (int i = half; i < n; i += step)
                at(i, j) = 0.25 * (at(i - half, j - half) + at(i + half, j - half) +
                                   at(i - half, j + half) + at(i + half, j + half)) +
                           displacement(i, j, side * std::numbers::sqrt2 / 2);
        for (int j = 0; j < n; j += half)  // diamond: each edge's midpoint
            for (int i = (j / half) % 2 == 0 ? half : 0; i < n; i += step) {
                double sum = 0;
                int count = 0;
                for (auto [di, dj] : {std::pair{-half, 0}, {half, 0}, {0, -half}, {0, half}}) {
                    if (i + di < 0 || i + di >= n || j + dj < 0 || j + dj >= n) continue;
                    sum += at(i + di, j + dj);
                    ++count;
                }
                at(i, j) = sum / count + displacement(i, j, side / 2);
            }
    }
    return h;
}

TriangleMesh make_terrain_mesh(const TerrainShape& shape, const std::string& name) {
    const std::vector<double> h = terrain_heights(shape);
    const int n = side_samples(shape);
    const double dx = shape.size.x / (n - 1), dz = shape.size.y / (n - 1);
    auto height = [&](int i, int j) { return h[static_cast<std::size_t>(j) * n + i]; };
    TriangleMesh mesh;
    mesh.name = name;
    mesh.material.name = name;
    const std::size_t count = static_cast<std::size_t>(n) * n;
    mesh.positions.reserve(count);
    mesh.normals.reserve(count);
    mesh.uvs.reserve(count);
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const double u = static_cast<double>(i) / (n - 1), v = static_cast<double>(j) / (n - 1);
            mesh.positions.push_back(shape.center + Vec3d{(u - 0.5) * shape.size.x, height(i, j),
                                                          (v - 0.5) * shape.size.y});
            // Central differences inside, one-sided on the border.
            const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, n - 1);
            const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, n - 1);
            const double hx = (height(i1, j) - height(i0, j)) / ((i1 - i0) * dx);
            const double hz = (height(i, j1) - height(i, j0)) / ((j1 - j0) * dz);
            mesh.normals.push_back(normalize(Vec3d{-hx, 1, -hz}));
            mesh.uvs.push_back({u, 1 - v});
        }
    }
    mesh.triangles.reserve(2 * static_cast<std::size_t>(n - 1) * (n - 1));
    for (int j = 0; j + 1 < n; ++j) {
        for (int i = 0; i + 1 < n; ++i) {
            const auto index = [&](int a, int b) { return static_cast<std::uint32_t>(b * n + a); };
            mesh.triangles.push_back({index(i, j), index(i, j + 1), index(i + 1, j)});
            mesh.triangles.push_back({index(i + 1, j), index(i, j + 1), index(i + 1, j + 1)});
        }
    }
    return mesh;
}

}  // namespace footprint
