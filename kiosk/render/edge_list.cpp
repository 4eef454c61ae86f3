// Edge list for feature-edge rendering. Reference: M. McGuire, J. F. Hughes,
// "Hardware-determined feature edge templates", NPAR 2004.
// Phases, per window of vertices: bucket the half-edges whose smaller endpoint
// lies in the window by that vertex (CSR, 4 bytes per half-edge), then for each
// half-edge a->b look for its twin b->a in the same bucket; emit each pair once
// (from the side with a < b) and every unpaired half-edge as a boundary.
// O(corners x windows + corners x valence), no sort. The walk is resumable and
// emits the edges in pieces; counting them is a walk of its own, only on request.
#include "kiosk/render/edge_list.h"

#include <algorithm>
#include <cmath>

namespace body::render {
namespace {

inline uint32_t next_of(std::span<const uint32_t> idx, uint32_t corner) {
    return idx[corner - corner % 3 + (corner % 3 + 1) % 3];
}
inline uint32_t prev_of(std::span<const uint32_t> idx, uint32_t corner) {
    return idx[corner - corner % 3 + (corner % 3 + 2) % 3];
}

// The record of the half-edge at `corner` (a = its vertex) found in the bucket
// [begin, end) of its smaller endpoint, or false when its twin emits it.
bool edge_at(std::span<const uint32_t> idx, const uint32_t* begin, const uint32_t* end, uint32_t corner,
             EdgeRecord& out) {
    const uint32_t a = idx[corner], b = next_of(idx, corner);
    uint32_t twin_opposite = kNoVertex;
    for (const uint32_t* j = begin; j != end; ++j)
        if (idx[*j] == b && next_of(idx, *j) == a) {
            twin_opposite = prev_of(idx, *j);
            break;
        }
    if (twin_opposite != kNoVertex && a > b) return false;  // emitted from b's side
    out = {a, b, prev_of(idx, corner), twin_opposite};
    return true;
}

// The unit normal of the face (p, q, r) and the bound on its tilt when each
// corner moves by up to half of `step` (see coplanar_within_rounding); false
// for a degenerate face.
bool normal_and_tilt(const Vec3f& p, const Vec3f& q, const Vec3f& r, float step_length, Vec3f& normal, float& tilt) {
    const Vec3f n = glm::cross(q - p, r - p);
    const float twice_area = glm::length(n);
    if (!(twice_area > 0.0f)) return false;
    normal = n / twice_area;
    const float a = glm::length(q - p), b = glm::length(r - q), c = glm::length(p - r);
    tilt = step_length * (a + b + c - std::max({a, b, c})) / twice_area;
    return true;
}

}  // namespace

bool coplanar_within_rounding(const Vec3f& v0, const Vec3f& v1, const Vec3f& a, const Vec3f& b, const Vec3f& step) {
    const float step_length = glm::length(step);
    Vec3f n0, n1;
    float tilt0 = 0.0f, tilt1 = 0.0f;
    if (!normal_and_tilt(v0, v1, a, step_length, n0, tilt0) || !normal_and_tilt(v1, v0, b, step_length, n1, tilt1))
        return false;
    const float angle = std::atan2(glm::length(glm::cross(n0, n1)), glm::dot(n0, n1));
    return angle <= tilt0 + tilt1;
}

void EdgeStream::bucket_window(uint32_t lo) {
    window_lo_ = lo;
    window_end_ = static_cast<uint32_t>(std::min<size_t>(size_t{lo} + window_vertices_, vertex_count_));
    const uint32_t n = window_end_ - lo;
    start_.assign(static_cast<size_t>(n) + 1, 0);
    // Per face, so a degenerate face is tested once and a corner's successor
    // needs no division; the half-edge at corner f + k runs to corner f + (k + 1) % 3.
    const uint32_t faces_end = static_cast<uint32_t>(idx_.size());
    for (uint32_t f = 0; f < faces_end; f += 3) {
        const uint32_t a = idx_[f], b = idx_[f + 1], c = idx_[f + 2];
        if (a == b || b == c || a == c) continue;
        for (const uint32_t k : {std::min(a, b), std::min(b, c), std::min(c, a)})
            if (k - lo < n) ++start_[k - lo];
    }
    for (uint32_t i = 1; i < n; ++i) start_[i] += start_[i - 1];
    start_[n] = n ? start_[n - 1] : 0;
    // Sized to the window, never doubled by growth: the old storage is freed
    // before the new arrives (its contents are all overwritten below).
    const size_t half_edges = start_[n];
    if (half_edges > corner_.capacity()) {
        std::vector<uint32_t>().swap(corner_);
        corner_.reserve(half_edges + half_edges / 16);
    }
    corner_.resize(half_edges);
    for (uint32_t f = faces_end; f > 0;) {  // backwards: each bucket ascending
        f -= 3;
        const uint32_t a = idx_[f], b = idx_[f + 1], c = idx_[f + 2];
        if (a == b || b == c || a == c) continue;
        if (const uint32_t k = std::min(c, a); k - lo < n) corner_[--start_[k - lo]] = f + 2;
        if (const uint32_t k = std::min(b, c); k - lo < n) corner_[--start_[k - lo]] = f + 1;
        if (const uint32_t k = std::min(a, b); k - lo < n) corner_[--start_[k - lo]] = f;
    }
}

EdgeStream::EdgeStream(std::span<const uint32_t> indices, size_t scratch_bytes)
    : idx_(indices.first(indices.size() - indices.size() % 3)) {
    if (idx_.empty()) return;
    vertex_count_ = *std::max_element(idx_.begin(), idx_.end()) + 1;
    // Half-edges per window ~ corners x window / vertices; at least one vertex a window.
    const size_t corner_bytes = std::max<size_t>(idx_.size() * 4, 1);
    const size_t windows = std::max<size_t>(1, (corner_bytes + scratch_bytes - 1) / std::max<size_t>(scratch_bytes, 1));
    window_vertices_ = static_cast<uint32_t>(std::max<size_t>(1, (vertex_count_ + windows - 1) / windows));
}

size_t EdgeStream::count() {
    if (counted_) return count_;
    EdgeRecord e;
    count_ = 0;
    for (uint32_t lo = 0; lo < vertex_count_; lo = window_end_) {
        bucket_window(lo);
        for (uint32_t v = 0; v < window_end_ - lo; ++v)
            for (uint32_t i = start_[v]; i < start_[v + 1]; ++i)
                count_ += edge_at(idx_, corner_.data() + start_[v], corner_.data() + start_[v + 1], corner_[i], e);
    }
    counted_ = true;
    restart();
    return count_;
}

void EdgeStream::restart() {
    window_end_ = 0;  // next() buckets the first window again
    vertex_ = 0;
    slot_ = 0;
}

size_t EdgeStream::next(std::span<EdgeRecord> out) {
    size_t n = 0;
    while (n < out.size() && vertex_ < vertex_count_) {
        if (vertex_ >= window_end_ || window_end_ == 0) {
            bucket_window(vertex_);
            slot_ = 0;
        }
        const uint32_t v = vertex_ - window_lo_;
        slot_ = std::max(slot_, start_[v]);
        const uint32_t* begin = corner_.data() + start_[v];
        const uint32_t* end = corner_.data() + start_[v + 1];
        for (; slot_ < start_[v + 1] && n < out.size(); ++slot_) n += edge_at(idx_, begin, end, corner_[slot_], out[n]);
        if (slot_ < start_[v + 1]) break;  // out is full mid-vertex: resume here
        ++vertex_;
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
