#pragma once
// The edge mesh of the `lines` style (McGuire & Hughes 2004, "Hardware-
// determined feature edge templates"): one record per undirected edge of an
// indexed triangle mesh with the two vertices and the third vertex of each
// adjacent face, so the vertex shader can test silhouette and crease per frame.
#include <cstdint>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body::render {

inline constexpr uint32_t kNoVertex = 0xffffffffu;

// v0, v1: the edge as traversed by face (v0, v1, a); b is the third vertex of
// the face traversing it as (v1, v0, b), or kNoVertex on a boundary. Edges
// shared by more than two faces pair the first two and report the rest as
// boundaries of their own.
struct EdgeRecord {
    uint32_t v0, v1, a, b;
};

// What the GPU gets per edge, one RGBA32UI texel (16 bytes, no position
// texture to fetch from): both endpoints as 16-bit codes in a box (x0 y0 | z0 x1
// | y1 z1, low half first) and the two unit face normals as 8:8 octahedral
// codes (n0 low, n1 high; a boundary edge carries -n0 as n1). See lines.vert.
struct GpuEdge {
    uint32_t xy0, z0x1, y1z1;
    uint32_t normals;
};

// Whether the faces (v0, v1, a) and (v1, v0, b) of an edge are coplanar up to
// the rounding of their corners to a grid of `step` object units per axis (the
// renderer's 16-bit position codes; 0 on an axis that is not rounded): the
// angle between their normals is within the largest tilt that moving every
// corner by up to half a step can give the two faces. To first order a corner
// moved by d (|d| <= |step| / 2) tilts a face's normal by at most
// |step| (|e1| + |e2|) / |e1 x e2|, e1 and e2 the face's edges from any corner
// (the two shortest give the tightest bound). Such an edge is never a crease
// and is a silhouette only when seen within that angle of edge-on, where the
// faces around it carry the outline, so the `lines` style leaves it out
// (faces that were coplanar before rounding, e.g. of a linearly subdivided
// mesh, otherwise differ by rounding noise). A zero step asks for exact
// coplanarity; degenerate faces are never coplanar.
bool coplanar_within_rounding(const Vec3f& v0, const Vec3f& v1, const Vec3f& a, const Vec3f& b, const Vec3f& step);

// `indices`: triangles (three per face); degenerate faces are skipped.
// Deterministic order (by the edge's smaller vertex, then corner) so frames
// are stable.
std::vector<EdgeRecord> build_edge_list(std::span<const uint32_t> indices);

// The same records streamed in pieces, for callers that convert and upload
// them without holding the whole list (a million-triangle mesh has 27 MiB of
// records). The half-edges are bucketed by their smaller vertex one window of
// vertices at a time, so the scratch stays near `scratch_bytes` (plus 4 bytes
// per vertex of a window) whatever the mesh size. `indices` must outlive the
// stream. Records come in the order of build_edge_list.
//   EdgeStream s(indices);  s.count();  while (size_t n = s.next(chunk)) use(chunk.first(n));
class EdgeStream {
public:
    explicit EdgeStream(std::span<const uint32_t> indices, size_t scratch_bytes = size_t{2} << 20);
    // Edges in all: a whole walk of its own the first time (then restarts the
    // stream), so call it before next() or not at all.
    size_t count();
    // Writes the next up to out.size() records; 0 at the end.
    size_t next(std::span<EdgeRecord> out);
    // Back to the first record (for a second walk over the same records).
    void restart();

private:
    void bucket_window(uint32_t lo);  // fills start_/corner_ for the vertices [lo, window_end_)
    std::span<const uint32_t> idx_;
    uint32_t vertex_count_ = 0, window_vertices_ = 0;
    std::vector<uint32_t> start_;   // per window vertex + 1: first slot of its half-edges in corner_
    std::vector<uint32_t> corner_;  // corner ids (3 * face + k) of the window's half-edges by smaller vertex
    size_t count_ = 0;
    bool counted_ = false;
    uint32_t window_lo_ = 0, window_end_ = 0;  // the bucketed window
    uint32_t vertex_ = 0, slot_ = 0;           // where next() resumes
};

}  // namespace body::render
