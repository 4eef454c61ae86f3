#include "shared/mesh.h"

#include <algorithm>

#include "shared/union_find.h"

namespace body {
namespace {

// The common case first: when each link vertex starts exactly one of the
// `n` link edges (a, b) and ends exactly one (an oriented fan), every degree is
// 2 and the link is a union of cycles; returns their number (1: manifold),
// or 0 when the link is not of that kind (or too large to check this way).
int oriented_link_cycles(const uint32_t* link, uint32_t n) {
    constexpr uint32_t kMax = 32;
    if (n > kMax) return 0;
    uint8_t next[kMax], ended[kMax] = {}, seen[kMax] = {};
    for (uint32_t i = 0; i < n; ++i) {
        int found = -1;
        for (uint32_t j = 0; j < n; ++j) {
            if (j != i && link[2 * j] == link[2 * i]) return 0;  // a repeated start
            if (link[2 * j] == link[2 * i + 1]) {
                if (found >= 0) return 0;
                found = int(j);
            }
        }
        if (found < 0 || ended[found]) return 0;  // an end that starts nothing, or a repeated end
        ended[found] = 1;
        next[i] = uint8_t(found);
    }
    int cycles = 0;
    for (uint32_t i = 0; i < n; ++i) {
        if (seen[i]) continue;
        ++cycles;
        for (uint32_t k = i; !seen[k]; k = next[k]) seen[k] = 1;
    }
    return cycles;
}

// A vertex is manifold when the edges opposite it in its triangles (its link)
// form a single path or cycle: every link vertex has degree <= 2 and the link is connected.
size_t count_nonmanifold_vertices(size_t vertex_count, std::span<const uint32_t> indices) {
    std::vector<uint32_t> start(vertex_count + 1, 0);
    for (uint32_t v : indices) start[v + 1] += 2;
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<uint32_t> link(start.back());
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        for (int k = 0; k < 3; ++k) {
            uint32_t v = indices[t + k], a = indices[t + (k + 1) % 3], b = indices[t + (k + 2) % 3];
            link[fill[v]++] = a;
            link[fill[v]++] = b;
        }
    }
    size_t bad = 0;
    std::vector<uint32_t> ids, degree;  // the link's distinct vertices, sorted
    UnionFind sets;
    for (size_t v = 0; v < vertex_count; ++v) {
        if (start[v] == start[v + 1]) continue;
        if (const int cycles = oriented_link_cycles(&link[start[v]], (start[v + 1] - start[v]) / 2); cycles > 0) {
            bad += cycles != 1;
            continue;
        }
        ids.assign(link.begin() + start[v], link.begin() + start[v + 1]);
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        sets.reset(ids.size());
        degree.assign(ids.size(), 0);
        auto id = [&](uint32_t x) { return uint32_t(std::lower_bound(ids.begin(), ids.end(), x) - ids.begin()); };
        for (uint32_t i = start[v]; i < start[v + 1]; i += 2) {
            uint32_t a = id(link[i]), b = id(link[i + 1]);
            degree[a]++;
            degree[b]++;
            sets.unite(a, b);
        }
        size_t components = 0;
        for (uint32_t i = 0; i < sets.size(); ++i) components += sets.find(i) == i;
        bool ok = components == 1 && std::all_of(degree.begin(), degree.end(), [](uint32_t d) { return d <= 2; });
        bad += !ok;
    }
    return bad;
}

}  // namespace

// Edges are gathered per lower vertex (a counting sort, then each vertex's few
// entries sorted by the upper one): linear and cache-friendly where a hash of
// 3F edges was the build's largest cost on million-triangle caps.
MeshTopology analyze_topology(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                              double degenerate_area) {
    MeshTopology topo;
    topo.triangles = indices.size() / 3;
    std::vector<uint8_t> used(positions.size(), 0);
    UnionFind sets(topo.triangles);
    struct EdgeEnd {
        uint32_t upper, triangle;
        int32_t direction;  // +1 for lower -> upper, -1 otherwise
    };
    std::vector<uint32_t> start(positions.size() + 1, 0);
    for (size_t t = 0; t < topo.triangles; ++t) {
        const uint32_t* tri = &indices[3 * t];
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
            topo.degenerate_triangles++;
        } else {
            Vec3 n = glm::cross(positions[tri[1]] - positions[tri[0]], positions[tri[2]] - positions[tri[0]]);
            if (0.5 * glm::length(n) <= degenerate_area) topo.degenerate_triangles++;
        }
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = tri[k], b = tri[(k + 1) % 3];
            used[a] = 1;
            if (a != b) start[std::min(a, b) + 1]++;
        }
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<EdgeEnd> ends(start.back());
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t t = 0; t < topo.triangles; ++t) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = indices[3 * t + k], b = indices[3 * t + (k + 1) % 3];
            if (a != b) ends[fill[std::min(a, b)]++] = {std::max(a, b), uint32_t(t), a < b ? 1 : -1};
        }
    }
    for (size_t v = 0; v + 1 < start.size(); ++v) {
        const auto first = ends.begin() + start[v], last = ends.begin() + start[v + 1];
        std::sort(first, last, [](const EdgeEnd& x, const EdgeEnd& y) {
            return x.upper != y.upper ? x.upper < y.upper : x.triangle < y.triangle;
        });
        for (auto e = first; e != last;) {
            auto run = e;
            int direction_sum = 0;
            size_t count = 0;
            for (; run != last && run->upper == e->upper; ++run, ++count) {
                direction_sum += run->direction;
                sets.unite(run->triangle, e->triangle);
            }
            topo.edges++;
            if (count == 1)
                topo.boundary_edges++;
            else if (count > 2)
                topo.nonmanifold_edges++;
            else if (direction_sum != 0)
                topo.misoriented_edges++;
            e = run;
        }
    }
    topo.vertices = size_t(std::count(used.begin(), used.end(), uint8_t(1)));
    for (uint32_t t = 0; t < topo.triangles; ++t) topo.components += sets.find(t) == t;
    topo.nonmanifold_vertices = count_nonmanifold_vertices(positions.size(), indices);
    topo.euler = long(topo.vertices) - long(topo.edges) + long(topo.triangles);
    return topo;
}

double mesh_volume(std::span<const Vec3> positions, std::span<const uint32_t> indices) {
    double v = 0.0;
    for (size_t t = 0; t + 2 < indices.size(); t += 3)
        v += glm::dot(positions[indices[t]], glm::cross(positions[indices[t + 1]], positions[indices[t + 2]]));
    return v / 6.0;
}

double mesh_area(std::span<const Vec3> positions, std::span<const uint32_t> indices) {
    double a = 0.0;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const Vec3& p = positions[indices[t]];
        a += glm::length(glm::cross(positions[indices[t + 1]] - p, positions[indices[t + 2]] - p));
    }
    return a * 0.5;
}

Aabb mesh_bounds(std::span<const Vec3> positions) {
    Aabb box;
    for (const Vec3& p : positions) box.extend(p);
    return box;
}

std::vector<Vec3> vertex_normals(std::span<const Vec3> positions, std::span<const uint32_t> indices) {
    std::vector<Vec3> normals(positions.size(), Vec3(0.0));
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const Vec3& p = positions[indices[t]];
        Vec3 n = glm::cross(positions[indices[t + 1]] - p, positions[indices[t + 2]] - p);
        for (int k = 0; k < 3; ++k) normals[indices[t + k]] += n;
    }
    for (Vec3& n : normals) {
        double len = glm::length(n);
        if (len > 0) n /= len;
    }
    return normals;
}

}  // namespace body
