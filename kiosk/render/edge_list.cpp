// Edge list for feature-edge rendering. Reference: M. McGuire, J. F. Hughes,
// "Hardware-determined feature edge templates", NPAR 2004.
// Phases: bucket the face corners by their first vertex (CSR, 4 bytes per
// corner), then for each half-edge a->b look for its twin b->a among b's
// outgoing half-edges; emit each pair once (from the side with a < b) and every
// unpaired half-edge as a boundary. O(corners x valence), no sort. A first walk
// counts the edges, a second (resumable) one emits them in pieces.
#include "kiosk/render/edge_list.h"

#include <algorithm>

namespace body::render {
namespace {

// start[v] .. start[v + 1]: the corners of vertex v, ascending (no fill array:
// counts are summed to bucket ends and the corners placed backwards).
void bucket_corners(std::span<const uint32_t> indices, uint32_t vertex_count, std::vector<uint32_t>& start,
                    std::vector<uint32_t>& corner) {
    start.assign(static_cast<size_t>(vertex_count) + 1, 0);
    for (uint32_t v : indices) ++start[v];
    for (size_t i = 1; i < vertex_count; ++i) start[i] += start[i - 1];
    start[vertex_count] = static_cast<uint32_t>(indices.size());
    corner.resize(indices.size());
    for (size_t i = indices.size(); i-- > 0;) corner[--start[indices[i]]] = static_cast<uint32_t>(i);
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

// The record of the half-edge at `corner` (from its vertex a), or false when it
// is degenerate or emitted from its twin's side.
bool edge_at(std::span<const uint32_t> idx, const std::vector<uint32_t>& start, const std::vector<uint32_t>& corners,
             uint32_t a, uint32_t corner, EdgeRecord& out) {
    if (degenerate(idx, corner)) return false;
    const uint32_t b = next_of(idx, corner);
    uint32_t twin_opposite = kNoVertex;
    for (uint32_t j = start[b]; j < start[b + 1]; ++j) {
        const uint32_t tc = corners[j];
        if (!degenerate(idx, tc) && next_of(idx, tc) == a) {
            twin_opposite = prev_of(idx, tc);
            break;
        }
    }
    if (twin_opposite != kNoVertex && a > b) return false;  // emitted from b's side
    out = {a, b, prev_of(idx, corner), twin_opposite};
    return true;
}

}  // namespace

EdgeStream::EdgeStream(std::span<const uint32_t> indices) : idx_(indices.first(indices.size() - indices.size() % 3)) {
    if (idx_.empty()) return;
    const uint32_t vertex_count = *std::max_element(idx_.begin(), idx_.end()) + 1;
    bucket_corners(idx_, vertex_count, start_, corner_);
    EdgeRecord e;
    for (uint32_t a = 0; a < vertex_count; ++a)
        for (uint32_t i = start_[a]; i < start_[a + 1]; ++i) count_ += edge_at(idx_, start_, corner_, a, corner_[i], e);
}

size_t EdgeStream::next(std::span<EdgeRecord> out) {
    size_t n = 0;
    const auto vertex_count = static_cast<uint32_t>(start_.empty() ? 0 : start_.size() - 1);
    for (; vertex_ < vertex_count && n < out.size(); ++vertex_) {
        slot_ = std::max(slot_, start_[vertex_]);
        for (; slot_ < start_[vertex_ + 1] && n < out.size(); ++slot_)
            n += edge_at(idx_, start_, corner_, vertex_, corner_[slot_], out[n]);
        if (slot_ < start_[vertex_ + 1]) break;  // out is full mid-vertex: resume here
    }
    return n;
}

std::vector<EdgeRecord> build_edge_list(std::span<const uint32_t> indices) {
    EdgeStream stream(indices);
    std::vector<EdgeRecord> edges(stream.count());
    const size_t n = stream.next(edges);
    edges.resize(n);
    return edges;
}

}  // namespace body::render
