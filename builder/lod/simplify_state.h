#pragma once
// The simplifier's working state, private to builder/lod (the public interface is
// simplify.h; the pipeline and its phases are listed in simplify.cpp): constants,
// quadrics, the vertex heap, the Surface the setup builds and the State one greedy
// loop works on, and the phases each file gives the others.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "builder/lod/simplify.h"
#include "shared/geometry.h"
#include "shared/mesh.h"
#include "shared/pm/large_array.h"

namespace body::lod::detail {

using pm::PrefaultedVector;
using pm::prefetch;

constexpr uint32_t kNone = 0xffffffffu;
constexpr uint32_t kUnknown = 0xfffffffeu;
constexpr uint8_t kLocked = 1, kFrozen = 2;
// kGaveUp: a vertex popped kMaxFailedPops times without a legal collapse (or
// re-keyed past illegal ones) stays where it is (as kLocked) for the rest of the
// pass. Each such pop tries the edges of its fan again, and on
// garbage (random triangles: most edges non-manifold or boundary, fans near
// pm::kMaxPatchFan) every collapse nearby brings dozens of them back: 96 s for
// 200k random faces. The cap bounds the work per vertex; on a real surface a
// vertex rarely fails even twice.
constexpr uint8_t kGaveUp = 4;
constexpr uint8_t kMaxFailedPops = 8;
constexpr double kMinTurnCos = 0.2;  // cos(78 degrees): the largest turn of a face in one collapse
constexpr double kFoldCos = -0.9;    // neighbours closer than 26 degrees to back-to-back count as folded
// A collapse whose ordering cost (mean squared distance) is below (this x the bounding-box
// diagonal)^2 loses nothing: the lossless phase (flat and straight regions, rounding noise).
constexpr double kLosslessDistance = 1e-6;

// Symmetric 4x4 quadric: A (6), b (3), c.
struct Quadric {
    double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0, b0 = 0, b1 = 0, b2 = 0, c = 0;

    static Quadric plane(const Vec3& n, double d, double w) {
        Quadric q;
        q.a00 = w * n.x * n.x;
        q.a01 = w * n.x * n.y;
        q.a02 = w * n.x * n.z;
        q.a11 = w * n.y * n.y;
        q.a12 = w * n.y * n.z;
        q.a22 = w * n.z * n.z;
        q.b0 = w * n.x * d;
        q.b1 = w * n.y * d;
        q.b2 = w * n.z * d;
        q.c = w * d * d;
        return q;
    }
    void add(const Quadric& o) {
        a00 += o.a00;
        a01 += o.a01;
        a02 += o.a02;
        a11 += o.a11;
        a12 += o.a12;
        a22 += o.a22;
        b0 += o.b0;
        b1 += o.b1;
        b2 += o.b2;
        c += o.c;
    }
    double eval(const Vec3& p) const {
        const double x = p.x, y = p.y, z = p.z;
        const double ax = a00 * x + a01 * y + a02 * z;
        const double ay = a01 * x + a11 * y + a12 * z;
        const double az = a02 * x + a12 * y + a22 * z;
        return x * ax + y * ay + z * az + 2.0 * (b0 * x + b1 * y + b2 * z) + c;
    }
    // The minimiser of this quadric, when the 3x3 system is well conditioned
    // (det >= 1e-6 trace^3: the smallest eigenvalue is not negligible).
    bool minimiser(Vec3& p) const {
        const double c00 = a11 * a22 - a12 * a12, c01 = a02 * a12 - a01 * a22, c02 = a01 * a12 - a02 * a11;
        const double c11 = a00 * a22 - a02 * a02, c12 = a01 * a02 - a00 * a12, c22 = a00 * a11 - a01 * a01;
        const double det = a00 * c00 + a01 * c01 + a02 * c02, tr = a00 + a11 + a22;
        if (!(tr > 0.0) || !(det > 1e-6 * tr * tr * tr)) return false;
        p = Vec3(-(c00 * b0 + c01 * b1 + c02 * b2) / det, -(c01 * b0 + c11 * b1 + c12 * b2) / det,
                 -(c02 * b0 + c12 * b1 + c22 * b2) / det);
        return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    }
    double eval_sum(const Quadric& o, const Vec3& p) const {
        Quadric s = *this;
        s.add(o);
        return s.eval(p);
    }
};

// Indexed 4-ary min-heap of vertices keyed by the cost of their cheapest outgoing
// half-edge collapse; ties broken by the vertex's input number (`rank`) so the order
// is the same everywhere and does not depend on the internal numbering. Keys and
// ranks live in the heap entries: a sift compares without random loads, and four
// 16-byte siblings lie in one or two cache lines (half the depth of a binary heap).
class VertexHeap {
public:
    void reset(std::span<const uint32_t> rank) {
        rank_ = rank.data();
        pos_.assign(rank.size(), kNone);
        // Every vertex at most once: the storage never grows, so items_ stays valid.
        // items_[i] = store_[shift + i] with &items_[1] on a 64-byte boundary: the four
        // children of entry i (4i + 1 .. 4i + 4, 16 bytes each) share one cache line.
        // (Addresses only: the heap and its order are the same.)
        store_.assign(rank.size() + 4, Item{});
        const size_t misalign = (reinterpret_cast<uintptr_t>(store_.data() + 1) % 64) / sizeof(Item);
        items_ = store_.data() + (4 - misalign) % 4;
        size_ = 0;
    }
    bool empty() const { return size_ == 0; }
    bool contains(uint32_t v) const { return pos_[v] != kNone; }
    void prefetch_entry(uint32_t v) const { prefetch(&pos_[v]); }
    // The entry itself (after prefetch_entry had time to arrive).
    void prefetch_item(uint32_t v) const {
        if (pos_[v] != kNone) prefetch(&items_[pos_[v]]);
    }
    uint32_t top() const { return items_[0].v; }
    // The key of a vertex in the heap.
    double key(uint32_t v) const { return items_[pos_[v]].key; }
    // The smallest key other than the top's (infinity when there is none).
    double second_key() const {
        double k = std::numeric_limits<double>::infinity();
        for (size_t c = 1; c <= kArity && c < size_; ++c) k = std::min(k, items_[c].key);
        return k;
    }
    // The vertex most likely to be the top after it (kNone when there is none).
    uint32_t second() const {
        uint32_t best = kNone;
        double k = std::numeric_limits<double>::infinity();
        for (size_t c = 1; c <= kArity && c < size_; ++c)
            if (items_[c].key < k || best == kNone) k = items_[c].key, best = items_[c].v;
        return best;
    }
    void set(uint32_t v, double key) {
        if (pos_[v] == kNone) {
            pos_[v] = uint32_t(size_);
            items_[size_++] = {key, v, rank_[v]};
            sift_up(pos_[v]);
            return;
        }
        Item& item = items_[pos_[v]];
        const bool up = key < item.key;  // only one direction can move it
        item.key = key;
        if (up)
            sift_up(pos_[v]);
        else
            sift_down(pos_[v]);
    }
    void erase(uint32_t v) {
        const uint32_t i = pos_[v];
        if (i == kNone) return;
        const Item last = items_[--size_];
        pos_[v] = kNone;
        if (last.v == v) return;
        place(i, last);
        sift_up(i);
        sift_down(pos_[last.v]);
    }

private:
    struct alignas(16) Item {
        double key;
        uint32_t v, rank;
    };
    static bool before(const Item& a, const Item& b) { return a.key < b.key || (a.key == b.key && a.rank < b.rank); }
    void place(size_t i, const Item& item) {
        items_[i] = item;
        pos_[item.v] = uint32_t(i);
    }
    static constexpr size_t kArity = 4;
    void sift_up(size_t i) {
        const Item item = items_[i];
        while (i > 0) {
            const size_t parent = (i - 1) / kArity;
            if (!before(item, items_[parent])) break;
            place(i, items_[parent]);
            i = parent;
        }
        place(i, item);
    }
    void sift_down(size_t i) {
        const Item item = items_[i];
        for (;;) {
            const size_t first = kArity * i + 1;
            if (first >= size_) break;
            size_t c = first;
            for (size_t d = first + 1; d < std::min(first + kArity, size_); ++d)
                if (before(items_[d], items_[c])) c = d;
            if (!before(items_[c], item)) break;
            place(i, items_[c]);
            i = c;
        }
        place(i, item);
    }
    const uint32_t* rank_ = nullptr;
    PrefaultedVector<uint32_t> pos_;
    PrefaultedVector<Item> store_;
    Item* items_ = nullptr;
    size_t size_ = 0;
};

struct Collapse {
    uint32_t from, to;
    uint32_t removed[2];
    uint32_t removed_count;
    uint32_t patch_begin, patch_end;
    double error;
    Vec3 to_before, to_after;  // v's position before and after the collapse
};

// The per-vertex and per-corner arrays are mapped when allocated (PrefaultedVector):
// the build writes every page of them, and first-touch page faults were a large part
// of the build's time (bench/RESULTS.md).
// Per vertex, what its heap key stands for, in one cache line (update_neighbour
// reads most of it for every neighbour of every collapse).
struct alignas(64) VertexKey {
    Vec3 best_pos{0.0};            // where the keyed collapse puts the merged vertex
    double second_cost = 0.0;      // (see second_target)
    uint32_t best_target = kNone;  // the target of the heap key
    // The cheapest of its other collapses (kNone: not known), so that a vertex whose
    // keyed collapse disappears is re-keyed without walking its fan again.
    uint32_t second_target = kNone;
    uint8_t best_valid = 0;   // best_pos is the placement for exactly the heap key
    uint8_t key_is_min = 0;   // the key is the cheapest collapse (not one re-ranked past illegal ones)
    uint8_t failed_pops = 0;  // pops that found no legal collapse (collapse_top; kMaxFailedPops)
};

// Per corner c (Surface::corner_cost): the cost of idx[c] -> the next vertex of its
// face, or kNoCost. A collapse that moves v or grows its quadric sets kNoCost on every
// corner of v's fan whose edge has an end at v (apply_collapse), so a stored cost is
// always that of the current ends: no per-vertex change stamps to compare (one cache
// line less per neighbour) and 8 bytes per corner. (A cost is >= 0, -0 or NaN, never
// kNoCost.)
constexpr double kNoCost = -1.0;

// What stays fixed through a simplification (from LodOptions and the input's bounds).
struct LoopSettings {
    bool optimal = true;              // LodOptions::optimal_placement
    double boundary_weight = 100.0;   // LodOptions::boundary_weight
    double lossless_distance = 0.0;   // kLosslessDistance x the bounding-box diagonal
    double lossless_cost = 0.0;       // ordering cost (squared distance) of a collapse that loses nothing
    Vec3 box_min{0.0}, box_max{0.0};  // the input's bounds: placements stay inside
    // The .bpm's grid: 16-bit codes over [grid_lo, grid_hi] per axis, and the squared
    // height (two step diagonals) above which a face keeps its area there (flat_on_grid).
    float grid_lo[3] = {0, 0, 0}, grid_hi[3] = {0, 0, 0};
    double grid_reach2 = 0.0;
};

// The surface being simplified: everything indexed by vertex, face or corner. The setup
// phases build it; the collapse loop works on it through State's views, one State per
// region in lossless_regions (each touches only its region's elements).
struct Surface {
    PrefaultedVector<Vec3> pos;
    PrefaultedVector<uint32_t> idx;           // 3 per face, current
    PrefaultedVector<uint8_t> face_alive;     // per face
    PrefaultedVector<uint8_t> edge_boundary;  // per corner: edge corner -> next corner has one face
    // Per corner: the live face across the edge corner -> next corner (kNone: none;
    // kUnknown: a non-manifold or inconsistently oriented edge, looked up by walking).
    PrefaultedVector<uint32_t> across;
    PrefaultedVector<uint32_t> head, next;  // corner lists
    PrefaultedVector<uint32_t> fcount;      // live faces per vertex
    // locked: kLocked (a non-manifold edge: never moves) | kFrozen (lossless_regions'
    // border band: neither end of any collapse until the regions are done).
    PrefaultedVector<uint8_t> boundary, locked, alive;
    PrefaultedVector<Quadric> q, e;  // ordering quadric, error quadric
    PrefaultedVector<VertexKey> key;
    PrefaultedVector<double> corner_cost;
    PrefaultedVector<uint32_t> face_of_input;  // input face (after clean_input) -> face here
    // Vertex v here is input vertex rank[v] (after clean_input); ties between equal
    // costs go to the lower rank, so the result does not depend on the numbering here.
    PrefaultedVector<uint32_t> rank, vertex_of_input;
    // Per vertex: the last ring that listed it (topology_allowed: stamp - 1 for u's, stamp for v's).
    PrefaultedVector<uint32_t> mark;
    size_t live_faces = 0;
    LoopSettings settings;
};

// The collapse loop's state: views of the surface's arrays (the same names) and what
// one greedy loop owns -- its heap, its collapse records, its scratch.
struct State {
    explicit State(Surface& m)
        : pos(m.pos),
          idx(m.idx),
          face_alive(m.face_alive),
          edge_boundary(m.edge_boundary),
          across(m.across),
          head(m.head),
          next(m.next),
          fcount(m.fcount),
          boundary(m.boundary),
          locked(m.locked),
          alive(m.alive),
          q(m.q),
          e(m.e),
          key(m.key),
          corner_cost(m.corner_cost),
          face_of_input(m.face_of_input),
          rank(m.rank),
          vertex_of_input(m.vertex_of_input),
          mark(m.mark),
          live_faces(m.live_faces),
          settings(m.settings) {}
    std::span<Vec3> pos;
    std::span<uint32_t> idx;
    std::span<uint8_t> face_alive, edge_boundary;
    std::span<uint32_t> across, head, next, fcount;
    std::span<uint8_t> boundary, locked, alive;
    std::span<Quadric> q, e;
    std::span<VertexKey> key;
    std::span<double> corner_cost;
    std::span<uint32_t> face_of_input, rank, vertex_of_input, mark;

    VertexHeap heap;
    // The optimum of an edge is the same in both directions (Q_u + Q_v, the midpoint and
    // the edge length are symmetric in IEEE arithmetic): after u -> v, the placements
    // v -> x computed for v's key are reused for x -> v by v's neighbours.
    // A short list (v's ring) searched linearly rather than per-vertex arrays: fewer
    // cold cache lines per collapse.
    struct SymmetricPlacement {
        uint32_t to;
        double cost;
        Vec3 pos;
    };
    uint32_t sym_v = kNone;
    std::vector<SymmetricPlacement> sym;
    std::vector<SymmetricPlacement> fresh;  // update_vertex scratch: optima computed this call
    std::vector<uint32_t> twins;            // ... and the corners before u in its faces
    PrefaultedVector<Collapse> collapses;
    PrefaultedVector<uint32_t> patch_faces;
    size_t live_faces = 0;
    double running_error = 0.0;
    LoopSettings settings;
    bool restarted = false;                                      // restart_ordering has run
    double error_cap = std::numeric_limits<double>::infinity();  // lossless_regions' cap on a collapse's error
    // scratch
    std::vector<uint32_t> cu, cv, fan, ring_u, ring_v, touched, walk;
    uint32_t stamp = 0;  // (see Surface::mark)
    std::vector<Vec3> fan_old, fan_new;
};

// ---- the phases, by file (each file's comment says what it holds)

// simplify_setup.cpp: the surface from the input, renumbered; quadrics.
void clean_input(const Mesh& mesh, Surface& s, PrefaultedVector<uint32_t>& kept_vertex);
void build_adjacency(Surface& s);
void reorder_vertices(Surface& s, PrefaultedVector<Vec3>& normals);
void init_quadrics(Surface& s, double boundary_weight, uint32_t first, uint32_t end);
void reorder_faces(Surface& s);
void rebuild_ordering_quadrics(State& s, double boundary_weight);

// collapse_checks.cpp: whether a collapse u -> v may be applied.
// Topology: fills s.cu and s.cv with u's and v's live corners (geometry_allowed and
// apply_collapse use them); `shared` gets the faces removed.
bool topology_allowed(State& s, uint32_t u, uint32_t v, uint32_t shared[2], uint32_t& shared_count);
// Geometry with the merged vertex at `target`, right after topology_allowed(u, v) accepted.
bool geometry_allowed(State& s, uint32_t u, uint32_t v, const Vec3& target, const uint32_t shared[2],
                      uint32_t shared_count);

// collapse_loop.cpp: the greedy loop (after the lossless phase's regions).
unsigned thread_count(const LodOptions& lod);
void collapse_loop(Surface& m, State& s, size_t target_faces, const LodOptions& lod);

}  // namespace body::lod::detail
