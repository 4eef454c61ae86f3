#pragma once
// The edge mesh of the `lines` style (McGuire & Hughes 2004, "Hardware-
// determined feature edge templates"): one record per undirected edge of an
// indexed triangle mesh with the two vertices and the third vertex of each
// adjacent face, so the vertex shader can test silhouette and crease per frame.
#include <cstdint>
#include <span>
#include <vector>

namespace body::render {

inline constexpr uint32_t kNoVertex = 0xffffffffu;

// v0, v1: the edge as traversed by face (v0, v1, a); b is the third vertex of
// the face traversing it as (v1, v0, b), or kNoVertex on a boundary. Edges
// shared by more than two faces pair the first two and report the rest as
// boundaries of their own.
struct EdgeRecord {
    uint32_t v0, v1, a, b;
};

// What the GPU gets per edge: the two vertices (positions fetched from a
// texture) and the two unit face normals packed as signed 10:10:10:2 (a zero
// second normal marks a boundary), 16 bytes.
struct GpuEdge {
    uint32_t v0, v1;
    uint32_t n0, n1;
};

// `indices`: triangles (three per face); degenerate faces are skipped.
// Deterministic order (sorted by vertex pair) so frames are stable.
std::vector<EdgeRecord> build_edge_list(std::span<const uint32_t> indices);

}  // namespace body::render
