#pragma once
// Synthetic meshes and level checks shared by the progressive-mesh tests.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "shared/mesh.h"

namespace body::test {

// Icosahedron subdivided `levels` times, projected on a sphere of `radius`.
inline Mesh icosphere(int levels, double radius = 10.0, Vec3 center = Vec3(0.0)) {
    Mesh m;
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    const double raw[12][3] = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (auto& r : raw) m.positions.push_back(glm::normalize(Vec3(r[0], r[1], r[2])));
    m.indices = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
                 3, 9,  4, 3, 4, 2, 3, 2, 6, 3, 6, 8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
            return mid[key] = uint32_t(m.positions.size() - 1);
        };
        std::vector<uint32_t> next;
        for (size_t f = 0; f < m.indices.size(); f += 3) {
            uint32_t a = m.indices[f], b = m.indices[f + 1], c = m.indices[f + 2];
            uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        m.indices = std::move(next);
    }
    for (Vec3& p : m.positions) p = center + p * radius;
    m.name = "sphere";
    return m;
}

// Torus (genus 1) with a bumpy surface so that simplification has something to keep.
inline Mesh bumpy_torus(int rings, int segments, double major = 10.0, double minor = 3.0) {
    Mesh m;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double u = 2 * M_PI * i / rings, v = 2 * M_PI * j / segments;
            const double r = minor * (1.0 + 0.1 * std::sin(5 * u) * std::cos(3 * v));
            m.positions.push_back(
                {(major + r * std::cos(v)) * std::cos(u), (major + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
        }
    auto id = [&](int i, int j) { return uint32_t((i % rings) * segments + (j % segments)); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            m.indices.insert(m.indices.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.indices.insert(m.indices.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    m.name = "torus";
    return m;
}

// Every triangle split into four at its edge midpoints, in place (the surface does
// not change: each input triangle becomes four coplanar ones).
inline Mesh subdivide_linear(const Mesh& in) {
    Mesh out;
    out.name = in.name + "_sub";
    out.positions = in.positions;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
        auto [it, inserted] = mid.emplace(std::minmax(a, b), uint32_t(out.positions.size()));
        if (inserted) out.positions.push_back((in.positions[a] + in.positions[b]) * 0.5);
        return it->second;
    };
    for (size_t f = 0; f + 2 < in.indices.size(); f += 3) {
        const uint32_t a = in.indices[f], b = in.indices[f + 1], c = in.indices[f + 2];
        const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        out.indices.insert(out.indices.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    return out;
}

// A wavy open square sheet (boundary) of n x n quads.
inline Mesh wavy_sheet(int n, double size = 20.0) {
    Mesh m;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double x = size * i / n, y = size * j / n;
            m.positions.push_back({x, y, std::sin(x * 0.4) * std::cos(y * 0.3)});
        }
    auto id = [&](int i, int j) { return uint32_t(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            m.indices.insert(m.indices.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.indices.insert(m.indices.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    m.name = "sheet";
    return m;
}

// Worst "fold": the smallest cosine between normals of two triangles sharing an edge.
inline double min_adjacent_normal_cosine(std::span<const Vec3> pos, std::span<const uint32_t> idx) {
    std::map<std::pair<uint32_t, uint32_t>, size_t> edge_face;
    double worst = 1.0;
    auto normal = [&](size_t f) {
        const Vec3 &a = pos[idx[f * 3]], &b = pos[idx[f * 3 + 1]], &c = pos[idx[f * 3 + 2]];
        return glm::normalize(glm::cross(b - a, c - a));
    };
    for (size_t f = 0; f < idx.size() / 3; ++f)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = idx[f * 3 + k], b = idx[f * 3 + (k + 1) % 3];
            auto it = edge_face.find({b, a});
            if (it != edge_face.end()) worst = std::min(worst, glm::dot(normal(f), normal(it->second)));
            edge_face[{a, b}] = f;
        }
    return worst;
}

}  // namespace body::test
