// Edge list for feature-edge rendering. Reference: M. McGuire, J. F. Hughes,
// "Hardware-determined feature edge templates", NPAR 2004.
// Phases: bucket the face corners by their first vertex (CSR, 4 bytes per
// corner), then for each half-edge a->b look for its twin b->a among b's
// outgoing half-edges; emit each pair once (from the side with a < b) and every
// unpaired half-edge as a boundary. O(corners x valence), no sort.
#include "kiosk/render/edge_list.h"

#include <algorithm>

namespace body::render {
namespace {

struct Corners {
    std::vector<uint32_t> start;   // per vertex + 1
    std::vector<uint32_t> corner;  // corner ids (3 * face + k) grouped by vertex
};

Corners bucket_corners(std::span<const uint32_t> indices, uint32_t vertex_count) {
    Corners c;
    c.start.assign(static_cast<size_t>(vertex_count) + 1, 0);
    for (uint32_t v : indices) ++c.start[v + 1];
    for (size_t i = 1; i < c.start.size(); ++i) c.start[i] += c.start[i - 1];
    c.corner.resize(indices.size());
    std::vector<uint32_t> fill(c.start.begin(), c.start.end() - 1);
    for (size_t i = 0; i < indices.size(); ++i) c.corner[fill[indices[i]]++] = static_cast<uint32_t>(i);
    return c;
}

inline uint32_t next_of(std::span<const uint32_t> idx, uint32_t corner) {
    return idx[corner - corner % 3 + (corner % 3 + 1) % 3];
}
inline uint32_t prev_of(std::span<const uint32_t> idx, uint32_t corner) {
    return idx[corner - corner % 3 + (corner % 3 + 2) % 3];
}

bool degenerate(std::span<const uint32_t> idx, uint32_t corner) {
    uint32_t f = corner - corner % 3;
    return idx[f] == idx[f + 1] || idx[f + 1] == idx[f + 2] || idx[f] == idx[f + 2];
}

}  // namespace

std::vector<EdgeRecord> build_edge_list(std::span<const uint32_t> indices) {
    const size_t n = indices.size() - indices.size() % 3;
    std::span<const uint32_t> idx = indices.first(n);
    if (n == 0) return {};
    const uint32_t vertex_count = *std::max_element(idx.begin(), idx.end()) + 1;
    Corners c = bucket_corners(idx, vertex_count);
    std::vector<EdgeRecord> edges;
    edges.reserve(n / 2 + 16);
    for (uint32_t a = 0; a < vertex_count; ++a) {
        for (uint32_t i = c.start[a]; i < c.start[a + 1]; ++i) {
            uint32_t corner = c.corner[i];
            if (degenerate(idx, corner)) continue;
            uint32_t b = next_of(idx, corner);
            uint32_t twin_opposite = kNoVertex;
            for (uint32_t j = c.start[b]; j < c.start[b + 1]; ++j) {
                uint32_t tc = c.corner[j];
                if (!degenerate(idx, tc) && next_of(idx, tc) == a) {
                    twin_opposite = prev_of(idx, tc);
                    break;
                }
            }
            if (twin_opposite != kNoVertex && a > b) continue;  // emitted from b's side
            edges.push_back({a, b, prev_of(idx, corner), twin_opposite});
        }
    }
    return edges;
}

}  // namespace body::render
