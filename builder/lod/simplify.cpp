// Quadric-error simplification recorded as vertex splits.
//
// References:
//   M. Garland, P. Heckbert, "Surface Simplification Using Quadric Error Metrics", SIGGRAPH 1997.
//   H. Hoppe, "Progressive Meshes", SIGGRAPH 1996.
//   T. Dey, H. Edelsbrunner, S. Guha, D. Nekhayev, "Topology preserving edge contraction", 1999
//     (the link condition).
//   P. Lindstrom, G. Turk, "Fast and Memory Efficient Polygonal Simplification", IEEE Visualization
//     1998 (quadrics from the current mesh rather than the accumulated input: restart_ordering).
//
// Pipeline (static phases, public entry at the bottom):
//   clean_input      drop degenerate triangles and unreferenced vertices
//   build_adjacency  per-vertex corner lists (singly linked through corners), the face across each
//                    edge (kept up to date by the collapses), boundary/non-manifold flags
//   reorder_vertices, reorder_faces  renumber for cache locality (the output keeps the input numbering)
//   init_quadrics    area-weighted plane quadrics + boundary penalty planes (ordering) and unit-weight
//                    quadrics (the stored object-space error), gathered per vertex (a range of them:
//                    two halves on two threads)
//   placement        optimal (quadric minimiser) or fallback position of a collapse
//   lossless_regions a large mesh's lossless phase in independent regions, on threads
//   collapse_loop    indexed 4-ary heap of vertices keyed by their cheapest outgoing collapse
//                    (ordering cost per unit quadric weight)
//   restart_ordering at the end of the lossless phase, ordering quadrics from the current faces
//   emit_order       vertices and faces in refinement order, index patches per split
#include "builder/lod/simplify.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <future>
#include <iterator>
#include <limits>
#include <mutex>
#include <thread>
#include <tuple>
#include <type_traits>

#include "shared/pm/bpm_container.h"
#include "shared/pm/large_array.h"
#include "shared/pm/quantize.h"

namespace body::lod {
namespace {

// A fan's scattered cache lines are requested together before the loop that uses
// them instead of one miss after another (a hint: no effect on results).
using pm::PrefaultedVector;
using pm::prefetch;

constexpr uint32_t kNone = 0xffffffffu;
constexpr uint32_t kUnknown = 0xfffffffeu;
constexpr uint8_t kLocked = 1, kFrozen = 2;
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
// the build writes every page of them, and first-touch page faults took a quarter
// of the bunny's build time on the benchmark VM (~5000 faults at 11-15 us). (An earlier
// trial of huge pages saw no gain because it measured user time only, where faults do
// not show; huge pages are slower here anyway, see shared/prefaulted_array.cpp.)
// Per vertex, what its heap key stands for, in one cache line (update_neighbour
// reads most of it for every neighbour of every collapse).
struct alignas(64) VertexKey {
    Vec3 best_pos{0.0};            // where the keyed collapse puts the merged vertex
    double second_cost = 0.0;      // (see second_target)
    uint32_t best_target = kNone;  // the target of the heap key
    // The cheapest of its other collapses (kNone: not known), so that a vertex whose
    // keyed collapse disappears is re-keyed without walking its fan again.
    uint32_t second_target = kNone;
    uint8_t best_valid = 0;  // best_pos is the placement for exactly the heap key
    uint8_t key_is_min = 0;  // the key is the cheapest collapse (not one re-ranked past illegal ones)
};

// Per corner c: the cost of idx[c] -> the next vertex of its face, computed at
// collapse number `time` (0: never); valid while both ends' last_changed
// (the collapse that last moved them or grew their quadric) is not later.
struct CornerCost {
    double cost;
    uint32_t time;
};

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
    PrefaultedVector<CornerCost> corner_cost;  // one load for both
    PrefaultedVector<uint32_t> last_changed;
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
          last_changed(m.last_changed),
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
    std::span<CornerCost> corner_cost;
    std::span<uint32_t> last_changed, face_of_input, rank, vertex_of_input, mark;

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
    uint32_t now = 1;                       // collapses so far + 1 (CornerCost::time)
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

// ---------------------------------------------------------------- phases

// Compacts the input: keeps non-degenerate triangles and the vertices they use,
// in input order (kept_vertex[i] = input index of vertex i).
void clean_input(const Mesh& mesh, Surface& s, PrefaultedVector<uint32_t>& kept_vertex) {
    const size_t n = mesh.positions.size();
    PrefaultedVector<uint32_t> remap(n, kNone);
    s.idx.reserve(mesh.indices.size());
    for (size_t f = 0; f + 2 < mesh.indices.size(); f += 3) {
        const uint32_t a = mesh.indices[f], b = mesh.indices[f + 1], c = mesh.indices[f + 2];
        if (a >= n || b >= n || c >= n || a == b || b == c || a == c) continue;
        remap[a] = remap[b] = remap[c] = 0;
        s.idx.insert(s.idx.end(), {a, b, c});
    }
    kept_vertex.reserve(n);
    s.pos.reserve(n);
    for (size_t v = 0; v < n; ++v) {
        if (remap[v] == kNone) continue;
        remap[v] = uint32_t(kept_vertex.size());
        kept_vertex.push_back(uint32_t(v));
        s.pos.push_back(mesh.positions[v]);
    }
    for (uint32_t& v : s.idx) v = remap[v];
}

void build_adjacency(Surface& s) {
    const size_t n = s.pos.size(), corners = s.idx.size(), faces = corners / 3;
    s.head.assign(n, kNone);
    s.next.assign(corners, kNone);
    s.fcount.assign(n, 0);
    for (size_t c = corners; c-- > 0;) {
        uint32_t v = s.idx[c];
        s.next[c] = s.head[v];
        s.head[v] = uint32_t(c);
        ++s.fcount[v];
    }
    s.face_alive.assign(faces, 1);
    s.live_faces = faces;
    // Edge multiplicity from the fans: the faces around a that also contain b are
    // the faces of edge {a, b} (no sort over all corners; the same flags). Each fan
    // is walked once into a local list that all its corners then scan.
    s.edge_boundary.assign(corners, 0);
    s.across.assign(corners, kUnknown);
    s.boundary.assign(n, 0);
    s.locked.assign(n, 0);
    struct FanCorner {
        uint32_t after, before, face, corner;
    };
    std::vector<FanCorner> fan;
    for (uint32_t a = 0; a < n; ++a) {
        fan.clear();
        for (uint32_t d = s.head[a]; d != kNone; d = s.next[d]) {
            const uint32_t f = d - d % 3;
            fan.push_back({s.idx[f + (d % 3 + 1) % 3], s.idx[f + (d % 3 + 2) % 3], f, d});
        }
        for (const FanCorner& c : fan) {  // edge a -> c.after
            const uint32_t b = c.after;
            uint32_t count = 0;
            bool same_direction = false;  // another face also runs a -> b
            uint32_t other = kNone;       // the face running b -> a
            for (const FanCorner& d : fan) {
                if (d.after != b && d.before != b) continue;
                ++count;
                if (d.after == b && d.face != c.face) same_direction = true;
                if (d.before == b) other = d.face / 3;
            }
            if (count == 2 && !same_direction) s.across[c.corner] = other;
            if (count == 1) {
                s.across[c.corner] = kNone;
                s.edge_boundary[c.corner] = 1;
                s.boundary[a] = s.boundary[b] = 1;
            } else if (count > 2 || same_direction) {
                s.locked[a] = s.locked[b] = kLocked;  // non-manifold edge: never move its ends
            }
        }
    }
    s.alive.assign(n, 1);
}

// The plane of face f: unit normal, offset and twice the area (false: degenerate).
template <class S>
bool face_plane(const S& s, size_t f, Vec3& nrm, double& d, double& len) {
    const uint32_t* t = &s.idx[f * 3];
    const Vec3 &p0 = s.pos[t[0]], &p1 = s.pos[t[1]], &p2 = s.pos[t[2]];
    nrm = glm::cross(p1 - p0, p2 - p0);
    len = glm::length(nrm);
    if (!(len > 0.0)) return false;
    nrm /= len;
    d = -glm::dot(nrm, p0);
    return true;
}

// The boundary-preserving plane through edge k of face f (normal `nrm`), perpendicular to
// the face: unit weight in `unit`, boundary_weight x edge length^2 in `weighted`.
template <class S>
bool boundary_planes(const S& s, size_t f, int k, const Vec3& nrm, double boundary_weight, Quadric& weighted,
                     Quadric& unit) {
    const uint32_t* t = &s.idx[f * 3];
    const Vec3 &a = s.pos[t[k]], &b = s.pos[t[(k + 1) % 3]];
    const Vec3 edge = b - a;
    Vec3 bn = glm::cross(edge, nrm);
    const double bl = glm::length(bn);
    if (!(bl > 0.0)) return false;
    bn /= bl;
    const double bd = -glm::dot(bn, a);
    weighted = Quadric::plane(bn, bd, boundary_weight * glm::dot(edge, edge));
    unit = Quadric::plane(bn, bd, 1.0);
    return true;
}

// The ordering and error quadrics of every vertex from the input faces. Gathered per
// vertex over its corner list (the input's face order, which reorder_faces keeps), face
// planes recomputed at each corner: each vertex's sums are written once, in Morton
// order, where adding each face to its three vertices' sums in face order cost a
// scattered read-modify-write of six quadrics per face (the input's face order is
// unrelated to the vertex order; the 1.1M-triangle bunny's took 210-239 ms that way,
// 131-166 ms this way, the bunny's ~10 ms either way). The per-vertex
// summation order is the same (area plane, then the face's boundary edges at that vertex
// in edge order), so the sums are the same bit for bit.
void init_quadrics(Surface& s, double boundary_weight, uint32_t first, uint32_t end) {
    for (uint32_t v = first; v < end; ++v) {
        Quadric q, e;
        for (uint32_t c = s.head[v]; c != kNone; c = s.next[c]) {
            const uint32_t f = c / 3, at = c % 3;
            Vec3 nrm;
            double d = 0.0, len = 0.0;
            if (!face_plane(s, f, nrm, d, len)) continue;
            q.add(Quadric::plane(nrm, d, 0.5 * len));
            e.add(Quadric::plane(nrm, d, 1.0));
            // The face's edges at v (v -> next and previous -> v), in edge order.
            const int out = int(at), in = int(at + 2) % 3;
            for (const int k : {std::min(out, in), std::max(out, in)}) {
                Quadric pen, upen;
                if (!s.edge_boundary[f * 3 + k] || !boundary_planes(s, f, k, nrm, boundary_weight, pen, upen)) continue;
                q.add(pen);
                e.add(upen);
            }
        }
        s.q[v] = q;
        s.e[v] = e;
    }
}

// The ordering quadrics again, from the live faces (restart_ordering); face by face (the
// corner lists are no longer in face order).
void rebuild_ordering_quadrics(State& s, double boundary_weight) {
    const size_t faces = s.idx.size() / 3;
    std::fill(s.q.begin(), s.q.end(), Quadric{});
    for (size_t f = 0; f < faces; ++f) {
        if (!s.face_alive[f]) continue;
        Vec3 nrm;
        double d = 0.0, len = 0.0;
        if (!face_plane(s, f, nrm, d, len)) continue;
        const uint32_t* t = &s.idx[f * 3];
        const Quadric area = Quadric::plane(nrm, d, 0.5 * len);
        for (int k = 0; k < 3; ++k) s.q[t[k]].add(area);
        for (int k = 0; k < 3; ++k) {
            Quadric pen, upen;
            if (!s.edge_boundary[f * 3 + k] || !boundary_planes(s, f, k, nrm, boundary_weight, pen, upen)) continue;
            s.q[t[k]].add(pen);
            s.q[t[(k + 1) % 3]].add(pen);
        }
    }
}

// Renumbers the vertices along a Morton curve over the bounding box (10 bits per
// axis, ties by input number) so that a neighbourhood's vertices share cache lines;
// many inputs (subdivided meshes, merged OBJ objects) append vertices in an order
// unrelated to the surface. The flags and normals move with their vertex (the quadrics are built after).
void reorder_vertices(Surface& s, PrefaultedVector<Vec3>& normals) {
    const size_t n = s.pos.size();
    const Aabb box = mesh_bounds(s.pos);
    const Vec3 extent = box.max - box.min;
    auto cell = [](double t) {  // t in [0, 1] -> 0 .. 1023
        return uint64_t(std::clamp(t * 1024.0, 0.0, 1023.0));
    };
    auto spread = [](uint64_t x) {  // 10 bits -> every third bit of 30
        x = (x | (x << 16)) & 0x030000FFull;
        x = (x | (x << 8)) & 0x0300F00Full;
        x = (x | (x << 4)) & 0x030C30C3ull;
        x = (x | (x << 2)) & 0x09249249ull;
        return x;
    };
    PrefaultedVector<uint64_t> keys(n);
    for (size_t v = 0; v < n; ++v) {
        const Vec3 d = s.pos[v] - box.min;
        const uint64_t x = cell(extent.x > 0.0 ? d.x / extent.x : 0.0), y = cell(extent.y > 0.0 ? d.y / extent.y : 0.0),
                       z = cell(extent.z > 0.0 ? d.z / extent.z : 0.0);
        keys[v] = (spread(x) | spread(y) << 1 | spread(z) << 2) << 32 | v;
    }
    std::sort(keys.begin(), keys.end());
    s.rank.resize(n);
    s.vertex_of_input.resize(n);
    for (size_t i = 0; i < n; ++i) {
        s.rank[i] = uint32_t(keys[i]);
        s.vertex_of_input[s.rank[i]] = uint32_t(i);
    }
    auto permute = [&](auto& values) {
        std::remove_reference_t<decltype(values)> out(n);
        for (size_t i = 0; i < n; ++i) out[i] = values[s.rank[i]];
        values.swap(out);
    };
    permute(s.pos);
    permute(normals);
    permute(s.boundary);
    permute(s.locked);
    permute(s.alive);
    permute(s.fcount);
    for (uint32_t& v : s.idx) v = s.vertex_of_input[v];
}

// Renumbers the faces by their smallest vertex (stable), so that a fan's faces lie
// close together in every per-face and per-corner array: the input's face order
// may be unrelated to its vertex order (bunny: the next face's vertices lie ~700
// vertices away), and the collapse loop is bound by memory latency. Runs after the
// quadrics (their sums keep the input's order); the output does not depend on face
// numbers (emit_order restores the input order through face_of_input).
void reorder_faces(Surface& s) {
    const size_t n = s.pos.size(), faces = s.idx.size() / 3;
    PrefaultedVector<uint32_t> start(n + 1, 0);
    for (size_t f = 0; f < faces; ++f) ++start[std::min({s.idx[f * 3], s.idx[f * 3 + 1], s.idx[f * 3 + 2]}) + 1];
    for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    s.face_of_input.resize(faces);
    PrefaultedVector<uint32_t> idx(s.idx.size());
    PrefaultedVector<uint8_t> edge_boundary(s.idx.size());
    PrefaultedVector<uint32_t> across(s.idx.size());
    for (size_t f = 0; f < faces; ++f) {
        const uint32_t g = start[std::min({s.idx[f * 3], s.idx[f * 3 + 1], s.idx[f * 3 + 2]})]++;
        s.face_of_input[f] = g;
        for (int k = 0; k < 3; ++k) {
            idx[g * 3 + k] = s.idx[f * 3 + k];
            edge_boundary[g * 3 + k] = s.edge_boundary[f * 3 + k];
            across[g * 3 + k] = s.across[f * 3 + k];
        }
    }
    s.idx.swap(idx);
    s.edge_boundary.swap(edge_boundary);
    for (uint32_t& g : across)
        if (g < kUnknown) g = s.face_of_input[g];
    s.across.swap(across);
    // The corner lists in the input's order, as build_adjacency made them: the order
    // of a fan's walk decides which of a split's faces comes first in the output.
    s.head.assign(n, kNone);
    for (size_t f = faces; f-- > 0;)
        for (uint32_t k = 3; k-- > 0;) {
            const uint32_t c = s.face_of_input[f] * 3 + k;
            s.next[c] = s.head[s.idx[c]];
            s.head[s.idx[c]] = c;
        }
}

// Live corners of v, compacting dead ones out of its list on the way.
void live_corners(State& s, uint32_t v, std::vector<uint32_t>& out) {
    out.clear();
    uint32_t* link = &s.head[v];
    while (*link != kNone) {
        const uint32_t c = *link;
        if (!s.face_alive[c / 3]) {
            *link = s.next[c];
            continue;
        }
        out.push_back(c);
        link = &s.next[c];
    }
}

void ring_of(State& s, uint32_t v, std::vector<uint32_t>& ring) {
    ring.clear();
    uint32_t* link = &s.head[v];
    while (*link != kNone) {
        const uint32_t c = *link;
        if (!s.face_alive[c / 3]) {
            *link = s.next[c];  // drop corners of removed faces on the way
            continue;
        }
        const uint32_t f = c / 3 * 3;
        for (int k = 0; k < 3; ++k)
            if (s.idx[f + k] != v) ring.push_back(s.idx[f + k]);
        link = &s.next[c];
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
}

// The weight of a quadric: the sum of its planes' weights (trace of A, each plane's
// normal being a unit vector) -- the area it has accumulated.
double weight(const Quadric& q) { return q.a00 + q.a11 + q.a22; }

Vec3 placement_raw(const State& s, uint32_t from, uint32_t to, double& cost, bool* optimum);

// Where the collapse from -> to puts the merged vertex (see simplify.h), and its
// ordering cost there: Q_from + Q_to per unit of their weight, i.e. the area-weighted
// mean squared distance to the accumulated planes. Ranking by the plain sum (area x
// distance^2) lets a vertex that has swallowed a large flat neighbourhood outrank
// collapses that move the surface farther; per unit weight the order follows the
// distance, which is what the Hausdorff error of a level measures.
Vec3 placement(const State& s, uint32_t from, uint32_t to, double& cost, bool* optimum = nullptr) {
    const Vec3 p = placement_raw(s, from, to, cost, optimum);
    const double w = weight(s.q[from]) + weight(s.q[to]);
    if (w > 0.0) cost /= w;
    return p;
}

// placement() before the division by the weight.
Vec3 placement_raw(const State& s, uint32_t from, uint32_t to, double& cost, bool* optimum) {
    const Vec3& pv = s.pos[to];
    if (!s.settings.optimal || s.boundary[from] || s.boundary[to] || s.locked[to]) {
        cost = std::max(s.q[from].eval(pv) + s.q[to].eval(pv), 0.0);
        return pv;
    }
    Quadric sum = s.q[from];
    sum.add(s.q[to]);
    const Vec3& pu = s.pos[from];
    const Vec3 mid = (pu + pv) * 0.5;
    Vec3 p;
    if (sum.minimiser(p)) {
        p = glm::clamp(p, s.settings.box_min, s.settings.box_max);
        const Vec3 d = p - mid, e = pv - pu;
        if (glm::dot(d, d) <= glm::dot(e, e)) {  // within an edge length of the midpoint
            cost = std::max(sum.eval(p), 0.0);
            if (optimum) *optimum = true;
            return p;
        }
    }
    // The fallback for a rank-deficient sum: the cheapest point of the edge (the
    // quadric restricted to the edge is a parabola in t). Where the edge lies in the
    // quadric's null space (a flat or crease region: every point costs the same up to
    // rounding) the midpoint, so that equal costs do not let one vertex swallow its
    // neighbourhood; else the parabola's minimum clamped to the edge.
    const Vec3 e = pv - pu;
    const double ax = sum.a00 * e.x + sum.a01 * e.y + sum.a02 * e.z;
    const double ay = sum.a01 * e.x + sum.a11 * e.y + sum.a12 * e.z;
    const double az = sum.a02 * e.x + sum.a12 * e.y + sum.a22 * e.z;
    const double curv = e.x * ax + e.y * ay + e.z * az, tr = sum.a00 + sum.a11 + sum.a22;
    if (!(curv > 1e-9 * tr * glm::dot(e, e))) {
        cost = std::max(sum.eval(mid), 0.0);
        return mid;
    }
    const double gx = sum.a00 * pu.x + sum.a01 * pu.y + sum.a02 * pu.z + sum.b0;
    const double gy = sum.a01 * pu.x + sum.a11 * pu.y + sum.a12 * pu.z + sum.b1;
    const double gz = sum.a02 * pu.x + sum.a12 * pu.y + sum.a22 * pu.z + sum.b2;
    const double t = std::clamp(-(gx * e.x + gy * e.y + gz * e.z) / curv, 0.0, 1.0);
    cost = std::max(s.q[from].eval(pv) + s.q[to].eval(pv), 0.0);
    Vec3 best = pv;
    for (const Vec3& c : {pu, mid, pu + e * t}) {
        const double k = std::max(sum.eval(c), 0.0);
        if (k < cost) cost = k, best = c;
    }
    return best;
}

// placement(), reusing (and, for the vertex just merged, recording) symmetric optima.
Vec3 placement_cached(State& s, uint32_t from, uint32_t to, double& cost, bool* symmetric = nullptr) {
    if (to == s.sym_v)
        for (const auto& e : s.sym)
            if (e.to == from) {
                cost = e.cost;
                if (symmetric) *symmetric = true;
                return e.pos;
            }
    bool optimum = false;
    const Vec3 p = placement(s, from, to, cost, &optimum);
    if (from == s.sym_v && optimum) s.sym.push_back({to, cost, p});
    if (symmetric) *symmetric = optimum;
    return p;
}

double collapse_cost(const State& s, uint32_t from, uint32_t to) {
    double cost = 0.0;
    (void)placement(s, from, to, cost);
    return cost;
}

// Re-keys `u` by its cheapest outgoing collapse (or drops it when it has none).
void update_vertex(State& s, uint32_t u) {
    if (!s.alive[u] || s.locked[u]) {
        s.heap.erase(u);
        return;
    }
    // Walk u's faces (each neighbour comes up once or twice); the minimum with ties
    // broken by vertex number does not depend on the walk order.
    double best = std::numeric_limits<double>::infinity(), second = best;
    uint32_t target = kNone, second_target = kNone;
    Vec3 best_p{0.0};
    bool best_cached = false;
    // Interior fans: the cost of u -> (the vertex after u in face of corner c) is kept
    // per corner and reused while neither end has changed since (placement is a pure
    // function of both ends' positions and quadrics).
    const bool cache = !s.boundary[u];
    // An optimum just computed for u -> x is also the cost of x -> u: it goes to the
    // corner of x before u (u's fan holds it), so a later update of x need not solve
    // it again while neither end changes.
    const bool twins = cache;
    s.fresh.clear();
    s.twins.clear();
    // The live corners first (the walk is a chain of dependent loads), their faces and
    // cost cache entries requested on the way; then each neighbour's data requested
    // together; then the costs, in walk order.
    live_corners(s, u, s.walk);
    for (const uint32_t c : s.walk) {
        prefetch(&s.idx[c]);
        prefetch(&s.corner_cost[c]);
    }
    for (const uint32_t c : s.walk) {
        const uint32_t f = c / 3 * 3, at = c - f;
        const uint32_t x = s.idx[f + (at == 2 ? 0 : at + 1)];
        prefetch(&s.last_changed[x]);
        prefetch(&s.rank[x]);
        prefetch(&s.pos[x]);
        prefetch(&s.q[x]);
        prefetch(reinterpret_cast<const char*>(&s.q[x] + 1) - 1);
        prefetch(&s.boundary[x]);  // placement's checks
        prefetch(&s.locked[x]);
    }
    for (const uint32_t c : s.walk) {
        const uint32_t f = c / 3 * 3, at = c - f;
        // In a consistently oriented fan every neighbour follows u in exactly one
        // face; only a boundary fan has a neighbour that merely precedes it.
        const uint32_t after_u = f + (at == 2 ? 0 : at + 1), before_u = f + (at == 0 ? 2 : at - 1);
        for (const uint32_t corner : {after_u, before_u}) {
            if (corner == before_u && cache) break;
            const uint32_t x = s.idx[corner];
            if (x == u || (s.locked[x] & kFrozen)) continue;
            double cost = 0.0;
            Vec3 p{0.0};
            const uint32_t t = s.corner_cost[c].time;
            const bool cached = cache && t != 0 && t >= s.last_changed[u] && t >= s.last_changed[x];
            if (cached) {
                cost = s.corner_cost[c].cost;
            } else {
                bool symmetric = false;
                p = placement_cached(s, u, x, cost, &symmetric);
                if (cache) s.corner_cost[c] = {cost, s.now};
                if (twins && symmetric) s.fresh.push_back({x, cost, p});
            }
            if (twins) s.twins.push_back(before_u);
            if (cost < best || (cost == best && (target == kNone || s.rank[x] < s.rank[target]))) {
                if (target != x) second = best, second_target = target;
                best = cost, target = x, best_p = p, best_cached = cached;
            } else if (x != target && (cost < second || (cost == second && (second_target == kNone ||
                                                                            s.rank[x] < s.rank[second_target])))) {
                second = cost, second_target = x;
            }
        }
    }
    for (const uint32_t c : s.twins) {
        const uint32_t w = s.idx[c];
        for (const auto& e : s.fresh)
            if (e.to == w) {
                s.corner_cost[c] = {e.cost, s.now};
                break;
            }
    }
    // A cost from the corner cache comes without its position: that is placed when
    // the vertex is popped (most keys are set again before).
    s.key[u].best_target = target;
    s.key[u].best_pos = best_p;
    s.key[u].best_valid = !best_cached;
    s.key[u].second_target = second_target;
    s.key[u].second_cost = second;
    s.key[u].key_is_min = 1;
    if (target == kNone)
        s.heap.erase(u);
    else
        s.heap.set(u, best);
}

// After u collapsed onto v, neighbour x of v only gained or changed its edge to v;
// a full update is needed only when its cheapest collapse went to u or v.
void update_neighbour(State& s, uint32_t x, uint32_t u, uint32_t v) {
    if (!s.heap.contains(x) || s.key[x].best_target == kNone) {
        update_vertex(s, x);
        return;
    }
    const uint32_t w = s.key[x].second_target;
    const double w_cost = s.key[x].second_cost;
    if (w == u || w == v) s.key[x].second_target = kNone;  // that collapse changed: the runner-up is not known
    const bool lost = s.key[x].best_target == u || s.key[x].best_target == v;
    // The keyed collapse changed: its successor is the better of the runner-up (the
    // cheapest of the others, none of which changed) and the new x -> v.
    if (lost && (w == kNone || w == u || w == v)) {
        update_vertex(s, x);
        return;
    }
    double c = 0.0;
    const Vec3 p = placement_cached(s, x, v, c);
    if (lost) {
        if (c < w_cost || (c == w_cost && s.rank[v] < s.rank[w])) {
            s.key[x].best_target = v;
            s.key[x].best_pos = p;
            s.key[x].best_valid = 1;
            s.heap.set(x, c);
        } else {
            s.key[x].best_target = w;
            s.key[x].best_valid = 0;  // placed when popped
            s.key[x].second_target = kNone;
            s.heap.set(x, w_cost);
        }
        return;
    }
    const double key = s.heap.key(x);
    if (c < key || (c == key && s.rank[v] < s.rank[s.key[x].best_target])) {
        // The old key is the cheapest of the others only when it was the cheapest of all.
        s.key[x].second_target = s.key[x].key_is_min ? s.key[x].best_target : kNone;
        s.key[x].second_cost = key;
        s.key[x].best_target = v;
        s.key[x].best_pos = p;
        s.key[x].best_valid = 1;
        s.heap.set(x, c);
    } else if (s.key[x].second_target != kNone &&
               (c < s.key[x].second_cost ||
                (c == s.key[x].second_cost && s.rank[v] < s.rank[s.key[x].second_target]))) {
        s.key[x].second_target = v;
        s.key[x].second_cost = c;
    }
}

bool third_vertex(const State& s, uint32_t face, uint32_t u, uint32_t v, uint32_t& out) {
    const uint32_t* t = &s.idx[face * 3];
    bool has_v = false;
    for (int k = 0; k < 3; ++k) {
        if (t[k] == v)
            has_v = true;
        else if (t[k] != u)
            out = t[k];
    }
    return has_v;
}

// Unit normal of face f with vertices u and v placed at p.
Vec3 face_normal(const State& s, uint32_t f, uint32_t u, uint32_t v, const Vec3& p) {
    const uint32_t* t = &s.idx[f * 3];
    Vec3 r[3];
    for (int k = 0; k < 3; ++k) r[k] = t[k] == u || t[k] == v ? p : s.pos[t[k]];
    const Vec3 n = glm::cross(r[1] - r[0], r[2] - r[0]);
    const double l = glm::length(n);
    return l > 0.0 ? n / l : Vec3(0.0);
}

// The live face traversing edge b -> a (the neighbour of a face with edge a -> b).
uint32_t face_across(const State& s, uint32_t a, uint32_t b) {
    for (uint32_t c = s.head[b]; c != kNone; c = s.next[c]) {
        const uint32_t f = c / 3;
        if (!s.face_alive[f]) continue;
        if (s.idx[f * 3 + (c % 3 + 1) % 3] == a) return f;
    }
    return kNone;
}

// The live corners of a and of b (a != b: their lists share no link), both lists
// walked in one loop: each walk is a chain of dependent loads, and two chains
// interleaved take about the time of one. Compacts dead corners out as live_corners.
void live_corners_of_both(State& s, uint32_t a, std::vector<uint32_t>& out_a, uint32_t b,
                          std::vector<uint32_t>& out_b) {
    out_a.clear();
    out_b.clear();
    uint32_t* link_a = &s.head[a];
    uint32_t* link_b = &s.head[b];
    for (;;) {
        const uint32_t ca = *link_a, cb = *link_b;
        if (ca == kNone && cb == kNone) break;
        if (ca != kNone) {
            if (!s.face_alive[ca / 3]) {
                *link_a = s.next[ca];
            } else {
                out_a.push_back(ca);
                prefetch(&s.idx[ca]);  // topology_allowed's third_vertex
                link_a = &s.next[ca];
            }
        }
        if (cb != kNone) {
            if (!s.face_alive[cb / 3]) {
                *link_b = s.next[cb];
            } else {
                out_b.push_back(cb);
                prefetch(&s.idx[cb]);
                link_b = &s.next[cb];
            }
        }
    }
}

// The distinct neighbours of v in walk order (marked instead of sorted), from its live
// corners: each gets mark `stamp`; returns how many of them carried mark `other` before.
size_t mark_ring(State& s, uint32_t v, const std::vector<uint32_t>& corners, std::vector<uint32_t>& ring,
                 uint32_t stamp, uint32_t other) {
    ring.clear();
    size_t common = 0;
    for (const uint32_t c : corners) {
        const uint32_t f = c / 3 * 3;
        for (int k = 0; k < 3; ++k) {
            const uint32_t x = s.idx[f + k];
            if (x == v || s.mark[x] == stamp) continue;
            common += s.mark[x] == other;
            s.mark[x] = stamp;
            ring.push_back(x);
            prefetch(&s.pos[x]);  // geometry_allowed, then the updates after the collapse
            prefetch(&s.q[x]);
            prefetch(reinterpret_cast<const char*>(&s.q[x] + 1) - 1);
            s.heap.prefetch_entry(x);
        }
    }
    return common;
}

// Checks topology of the collapse u -> v (u disappears). Fills s.cu and s.cv with u's
// and v's live corners (geometry_allowed and apply_collapse use them); `shared` gets
// the faces removed.
bool topology_allowed(State& s, uint32_t u, uint32_t v, uint32_t shared[2], uint32_t& shared_count) {
    live_corners_of_both(s, u, s.cu, v, s.cv);
    shared_count = 0;
    uint32_t opposite[2] = {kNone, kNone};
    for (uint32_t c : s.cu) {
        uint32_t a = kNone;
        if (third_vertex(s, c / 3, u, v, a)) {
            if (shared_count == 2) return false;  // non-manifold edge
            opposite[shared_count] = a;
            shared[shared_count++] = c / 3;
        }
    }
    if (shared_count == 0) return false;  // no longer an edge
    // A boundary vertex may only slide along its boundary edge; an interior one over an interior edge.
    if (s.boundary[u] ? shared_count != 1 : shared_count != 2) return false;
    // Link condition: the common neighbours of u and v are exactly the opposite vertices.
    s.stamp += 2;
    mark_ring(s, u, s.cu, s.ring_u, s.stamp - 1, kNone);
    if (mark_ring(s, v, s.cv, s.ring_v, s.stamp, s.stamp - 1) != shared_count) return false;
    // Opposite vertices lose a face; keep their fans valid (no structure collapses to nothing).
    for (uint32_t i = 0; i < shared_count; ++i) {
        const uint32_t a = opposite[i];
        if (s.fcount[a] <= (s.boundary[a] ? 1u : 3u)) return false;
    }
    const uint32_t merged = s.fcount[u] + s.fcount[v] - 2 * shared_count;
    if (merged > pm::kMaxPatchFan || merged < (s.boundary[v] ? 1u : 3u)) return false;
    return true;
}

// Whether the triangle t (normal n = cross(t1 - t0, t2 - t0), longest squared edge l2)
// has no area in the .bpm: its vertices' 16-bit codes collinear. Quantization moves a
// point by at most half a step per axis, so a triangle whose height over its longest
// edge exceeds two step diagonals keeps its area (the common case: no division); a
// thinner one is quantized as the writer does.
bool flat_on_grid(const Vec3 t[3], const Vec3& n, double l2, const LoopSettings& grid) {
    if (glm::dot(n, n) > grid.grid_reach2 * l2) return false;
    int64_t q[3][3];
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) q[i][k] = pm::quantize16(t[i][k], grid.grid_lo[k], grid.grid_hi[k]);
    const int64_t ax = q[1][0] - q[0][0], ay = q[1][1] - q[0][1], az = q[1][2] - q[0][2];
    const int64_t bx = q[2][0] - q[0][0], by = q[2][1] - q[0][1], bz = q[2][2] - q[0][2];
    return ay * bz - az * by == 0 && az * bx - ax * bz == 0 && ax * by - ay * bx == 0;
}

// Checks geometry of the collapse u -> v with the merged vertex at `target`: no
// face of u's fan (nor of v's, when v moves) may flip, fold or become a sliver, here
// or on the file's 16-bit grid. (A face without area in the file stays so until the
// next collapse there: a contour rebuild of the bunny had an optimal placement 2.8e-5
// from a neighbour with a grid step of ~3e-5, both on the same codes; a jittered
// subdivided mesh has faces whose codes come out collinear. Faces that already had
// no area in the file may keep it.)
// Called right after topology_allowed(u, v) accepted: its fans s.cu and s.cv.
bool geometry_allowed(State& s, uint32_t u, uint32_t v, const Vec3& target, const uint32_t shared[2],
                      uint32_t shared_count) {
    auto& fan = s.fan;
    fan = s.cu;
    if (target != s.pos[v]) {  // (s.cv: v's live corners, from topology_allowed)
        fan.insert(fan.end(), s.cv.begin(), s.cv.end());
    }
    auto removed = [&](uint32_t f) { return f == shared[0] || (shared_count == 2 && f == shared[1]); };
    // Unit normals before/after, kept for the fold guard below (as face_normal computes them).
    auto& fan_old = s.fan_old;
    auto& fan_new = s.fan_new;
    fan_old.resize(fan.size());
    fan_new.resize(fan.size());
    auto unit = [](const Vec3& n) {
        const double l = glm::length(n);
        return l > 0.0 ? n / l : Vec3(0.0);
    };
    for (size_t i = 0; i < fan.size(); ++i) {
        const uint32_t f = fan[i] / 3;
        fan_old[i] = fan_new[i] = Vec3(0.0);
        if (removed(f)) continue;
        const uint32_t* t = &s.idx[f * 3];
        Vec3 p[3], r[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = s.pos[t[k]];
            r[k] = t[k] == u || t[k] == v ? target : p[k];
        }
        prefetch(&s.across[f * 3 + (fan[i] % 3 + 1) % 3]);  // the fold guard's neighbour lookup
        const Vec3 n0 = glm::cross(p[1] - p[0], p[2] - p[0]);
        const Vec3 n1 = glm::cross(r[1] - r[0], r[2] - r[0]);
        // Flip and fold guard: a face may turn by at most kMaxTurn per collapse.
        if (!(glm::dot(n0, n1) > kMinTurnCos * std::sqrt(glm::dot(n0, n0) * glm::dot(n1, n1)))) return false;
        const double l2 = std::max({glm::dot(r[1] - r[0], r[1] - r[0]), glm::dot(r[2] - r[1], r[2] - r[1]),
                                    glm::dot(r[0] - r[2], r[0] - r[2])});
        if (glm::dot(n1, n1) <= 1e-12 * l2 * l2) return false;
        if (flat_on_grid(r, n1, l2, s.settings)) {
            const double l2_before = std::max({glm::dot(p[1] - p[0], p[1] - p[0]), glm::dot(p[2] - p[1], p[2] - p[1]),
                                               glm::dot(p[0] - p[2], p[0] - p[2])});
            if (!flat_on_grid(p, n0, l2_before, s.settings)) return false;
        }
        fan_old[i] = unit(n0);
        fan_new[i] = unit(n1);
    }
    // Fold guard: a moved face must not end up (nearly) back to back with a
    // neighbour unless it already was. Neighbours across the fan edges are other
    // faces of the fan; across the edge opposite the moving vertex, one lookup
    // (its face's corners, then their positions, requested for the whole fan first).
    for (size_t i = 0; i < fan.size(); ++i) {
        const uint32_t g = s.across[fan[i] / 3 * 3 + (fan[i] % 3 + 1) % 3];
        if (g < kUnknown) prefetch(&s.idx[g * 3]);
    }
    for (size_t i = 0; i < fan.size(); ++i) {
        const uint32_t g = s.across[fan[i] / 3 * 3 + (fan[i] % 3 + 1) % 3];
        if (g < kUnknown)
            for (int k = 0; k < 3; ++k) prefetch(&s.pos[s.idx[g * 3 + k]]);
    }
    for (size_t i = 0; i < fan.size(); ++i) {
        const uint32_t f = fan[i] / 3, k = fan[i] % 3;
        if (fan_new[i] == Vec3(0.0)) continue;
        const uint32_t x = s.idx[f * 3 + (k + 1) % 3], y = s.idx[f * 3 + (k + 2) % 3];
        const uint32_t known = s.across[f * 3 + (k + 1) % 3];
        const uint32_t g = known == kUnknown ? face_across(s, x, y) : known;
        if (g != kNone && !removed(g)) {
            const Vec3 ng = face_normal(s, g, u, v, target);
            const double after = glm::dot(fan_new[i], ng), before = glm::dot(fan_old[i], ng);
            if (after < kFoldCos && after < before) return false;
        }
        // Nearly every pair is far from folded: test the angle first, adjacency after
        // (a removed face's zero normal never passes the angle test).
        for (size_t j = i + 1; j < fan.size(); ++j) {
            const double after = glm::dot(fan_new[i], fan_new[j]);
            if (!(after < kFoldCos)) continue;
            const uint32_t* t = &s.idx[fan[j] / 3 * 3];
            if (t[0] != x && t[1] != x && t[2] != x && t[0] != y && t[1] != y && t[2] != y) continue;
            if (after < glm::dot(fan_old[i], fan_old[j])) return false;
        }
    }
    return true;
}

// Face f (with edge u-v) is removed by the collapse u -> v: the faces across its
// two other edges (at the third vertex) become neighbours of each other.
void relink_across(State& s, uint32_t f, uint32_t u, uint32_t v) {
    uint32_t g[2] = {kUnknown, kUnknown}, n = 0;
    for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t a = s.idx[f * 3 + k], b = s.idx[f * 3 + (k + 1) % 3];
        if ((a == u && b == v) || (a == v && b == u)) continue;
        g[n++] = s.across[f * 3 + k];
    }
    for (uint32_t i = 0; i < 2; ++i) {
        const uint32_t h = g[i], other = g[1 - i];
        if (h >= kUnknown) continue;
        for (uint32_t k = 0; k < 3; ++k)
            if (s.across[h * 3 + k] == f) s.across[h * 3 + k] = other;
    }
}

// The object-space error of the collapse u -> v with the merged vertex at `target`.
double collapse_error(const State& s, uint32_t u, uint32_t v, const Vec3& target) {
    return std::sqrt(std::max(0.0, s.e[u].eval_sum(s.e[v], target)));
}

// The region phase's cap on the stored error (see lossless_regions); none otherwise.
bool error_allowed(const State& s, uint32_t u, uint32_t v, const Vec3& target) {
    return s.error_cap == std::numeric_limits<double>::infinity() || collapse_error(s, u, v, target) <= s.error_cap;
}

void apply_collapse(State& s, uint32_t u, uint32_t v, const Vec3& target, const uint32_t shared[2],
                    uint32_t shared_count) {
    Collapse rec{};
    rec.from = u;
    rec.to = v;
    rec.removed_count = shared_count;
    rec.removed[0] = shared[0];
    rec.removed[1] = shared_count == 2 ? shared[1] : kNone;
    rec.patch_begin = uint32_t(s.patch_faces.size());
    // The merged fan is u's and v's: update_vertex(v) below reads their cost cache entries.
    for (const uint32_t c : s.cu) prefetch(&s.corner_cost[c]);
    for (const uint32_t c : s.cv) prefetch(&s.corner_cost[c]);
    const double err = collapse_error(s, u, v, target);
    rec.to_before = s.pos[v];
    rec.to_after = target;
    s.pos[v] = target;
    ++s.now;
    s.last_changed[v] = s.now;
    s.running_error = std::max(s.running_error, err);
    rec.error = s.running_error;
    for (uint32_t i = 0; i < shared_count; ++i) {
        const uint32_t f = shared[i];
        relink_across(s, f, u, v);
        s.face_alive[f] = 0;
        for (int k = 0; k < 3; ++k) --s.fcount[s.idx[f * 3 + k]];
        --s.live_faces;
    }
    // (The opposite vertices' lists keep the removed corners until their next walk
    // drops them: every walk skips dead faces.)
    // Move u's surviving corners onto v (s.cu holds u's live corners from the check).
    for (uint32_t c : s.cu) {
        if (!s.face_alive[c / 3]) continue;
        s.idx[c] = v;
        s.patch_faces.push_back(c / 3);
        s.next[c] = s.head[v];
        s.head[v] = c;
        ++s.fcount[v];
    }
    s.head[u] = kNone;
    s.fcount[u] = 0;
    s.alive[u] = 0;
    rec.patch_end = uint32_t(s.patch_faces.size());
    s.collapses.push_back(rec);
    s.q[v].add(s.q[u]);
    s.e[v].add(s.e[u]);
    // The costs of collapses from v and from its neighbours (towards v) changed.
    s.heap.erase(u);
    if (!s.boundary[u]) {
        // Around an interior u every edge keeps a face, so v's ring is the union of the
        // two rings topology_allowed marked (s.ring_v, then s.ring_u's others) without u and v.
        s.touched.clear();
        for (const uint32_t x : s.ring_v)
            if (x != u) s.touched.push_back(x);
        for (const uint32_t x : s.ring_u)
            if (x != v && s.mark[x] == s.stamp - 1) s.touched.push_back(x);
    } else {
        ring_of(s, v, s.touched);
    }
    // What update_neighbour reads first (mark_ring requested the heap positions).
    for (const uint32_t x : s.touched) {
        s.heap.prefetch_item(x);
        prefetch(&s.key[x]);
    }
    s.sym_v = v;
    s.sym.clear();
    update_vertex(s, v);
    for (uint32_t x : s.touched) update_neighbour(s, x, u, v);
    s.sym_v = kNone;
}

// The end of the lossless phase (the cheapest collapse would move the surface by more
// than kLosslessDistance): the mesh is still the input surface, but each vertex's
// ordering quadric is now the sum of whatever flat or straight neighbourhood it happened
// to swallow (a linearly subdivided mesh: whole coplanar patches), which skews the
// order and the placements from here on. The current faces' planes describe the same
// surface, so the ordering quadrics start again from them, as if the simplification
// began on this mesh (Lindstrom & Turk's observation that the current mesh's planes
// suffice, used once). The error quadrics keep accumulating from the input: the stored
// error stays a bound against the input surface. Runs at most once.
void restart_ordering(State& s) {
    s.restarted = true;
    // A lossless phase that removed less than a quarter of the faces (the bunny: 0.3%)
    // left nearly every quadric as it was built; a restart would only cost a second
    // heap build.
    if (s.live_faces * 4 > s.idx.size() / 3 * 3) return;
    rebuild_ordering_quadrics(s, s.settings.boundary_weight);
    for (CornerCost& c : s.corner_cost) c.time = 0;
    s.sym_v = kNone;
    for (uint32_t v = 0; v < uint32_t(s.pos.size()); ++v) update_vertex(s, v);
}

// (cost, target's rank, target, half-edge only): u's collapses in the order they are
// tried when its keyed one is not taken.
using CollapseOptions = std::vector<std::tuple<double, uint32_t, uint32_t, bool>>;

// One step of the greedy loop on the heap's top vertex u: its keyed collapse when legal,
// else its collapses in cost order while they stay no dearer than the next vertex (a
// placement rejected by the geometry checks comes back as the half-edge collapse at
// its own cost, re-ranked); u is re-keyed past them or, without a legal one, leaves the
// heap. True when a collapse was applied.
bool collapse_top(State& s, CollapseOptions& options) {
    const uint32_t u = s.heap.top();
    // apply_collapse's first loads (the error quadrics), requested while the checks run.
    if (const uint32_t v = s.key[u].best_target; v != kNone) {
        for (const uint32_t w : {u, v}) {
            prefetch(&s.e[w]);
            prefetch(reinterpret_cast<const char*>(&s.e[w] + 1) - 1);
        }
    }
    const double limit = s.heap.second_key();
    // The next vertex to be popped is most often the runner-up now: its first
    // loads are requested while this one collapses.
    if (const uint32_t w = s.heap.second(); w != kNone) {
        prefetch(&s.head[w]);
        prefetch(&s.key[w]);
        prefetch(&s.pos[w]);
    }
    // Fast path: the keyed collapse is usually the cheapest and legal.
    if (const uint32_t v = s.key[u].best_target; v != kNone) {
        // The key and position are current unless the key was set from a
        // re-ranked option below (best_valid cleared): recompute then.
        double cost = s.heap.key(u);
        const Vec3 target = s.key[u].best_valid ? s.key[u].best_pos : placement(s, u, v, cost);
        uint32_t shared[2], shared_count = 0;
        if (cost == s.heap.key(u) && topology_allowed(s, u, v, shared, shared_count) &&
            geometry_allowed(s, u, v, target, shared, shared_count) && error_allowed(s, u, v, target)) {
            apply_collapse(s, u, v, target, shared, shared_count);
            return true;
        }
    }
    ring_of(s, u, s.ring_u);
    options.clear();
    for (uint32_t x : s.ring_u)
        if (!(s.locked[x] & kFrozen)) options.push_back({collapse_cost(s, u, x), s.rank[x], x, false});
    std::sort(options.begin(), options.end());
    for (size_t i = 0; i < options.size();) {
        const auto [cost, rank, v, half_edge] = options[i];
        if (cost > limit) {
            s.key[u].best_target = v;
            s.key[u].best_valid = 0;
            s.key[u].second_target = kNone;  // the key is not the cheapest collapse
            s.key[u].key_is_min = 0;
            s.heap.set(u, cost);  // cheaper work elsewhere first
            return false;
        }
        uint32_t shared[2], shared_count = 0;
        if (!topology_allowed(s, u, v, shared, shared_count)) {
            ++i;
            continue;
        }
        double unused = 0.0;
        const Vec3 target = half_edge ? s.pos[v] : placement(s, u, v, unused);
        if (geometry_allowed(s, u, v, target, shared, shared_count) && error_allowed(s, u, v, target)) {
            apply_collapse(s, u, v, target, shared, shared_count);
            return true;
        }
        if (half_edge || target == s.pos[v]) {
            ++i;
            continue;
        }
        // The safe fallback: the half-edge collapse (v where it is), at its cost.
        const Vec3& pv = s.pos[v];
        const double w = weight(s.q[u]) + weight(s.q[v]);
        options[i] = {std::max(s.q[u].eval(pv) + s.q[v].eval(pv), 0.0) / (w > 0.0 ? w : 1.0), rank, v, true};
        std::sort(options.begin() + ptrdiff_t(i), options.end());
    }
    s.heap.erase(u);  // no legal collapse: back when its neighbourhood changes
    return false;
}

// The lossless phase region by region, the regions in parallel: the vertices split
// into `regions` runs of the Morton order (compact pieces of the surface), a band two
// edges wide around every cut frozen, each region simplified on its own heap until its
// cheapest collapse would lose something. A collapse inside a region reads and writes
// only that region's vertices, faces and corners (a vertex outside the band has no
// neighbour in the band's inner ring, so its faces, its ring's faces and their
// neighbours all lie in its region, and collapses keep it so), so the regions do not
// depend on each other: the result is the same for any number of threads and any
// schedule, and the regions' collapses are recorded one region after the other. The
// band and what the regions could not collapse go on in the global loop.
// The order differs from the global heap's near the cuts, and a region's heap can let a
// vertex that has swallowed a large flat area take a crease that the area-weighted
// ordering cost dilutes (measured: stored errors up to 1.1e-4 where the global order
// stays below 1e-6); so a collapse here must also keep its stored error under the
// lossless distance (error_cap).
// Measured on the 1.1M-triangle bunny (4 regions, 19.5k of its 557k vertices in the band,
// the regions take it to 106k faces): simplification 3.6-3.7 -> 2.3 s wall on this 2-core
// VM (2.6 s of CPU on one thread: the regions are more cache-local than one heap; two
// threads run each region ~1.5x slower than one does alone, the VM's memory being shared);
// Hausdorff at 10 % and 2 % unchanged, bytes per split 7.48 -> 7.41.
struct RegionResult {
    PrefaultedVector<Collapse> collapses;
    PrefaultedVector<uint32_t> patch_faces;
    size_t removed_faces = 0;
};

void simplify_region(State& w, uint32_t lo, uint32_t hi, size_t budget, double base_error, RegionResult& out) {
    w.heap.reset(w.rank);
    w.sym_v = kNone;
    w.running_error = base_error;
    // At most one collapse per vertex of the region (the records move to `out` after).
    w.collapses.clear();
    w.collapses.reserve(hi - lo);
    w.patch_faces.clear();
    w.patch_faces.reserve(size_t(hi - lo) * 5);
    for (uint32_t v = lo; v < hi; ++v) update_vertex(w, v);
    const size_t start = w.live_faces;
    CollapseOptions options;
    while (!w.heap.empty() && w.heap.key(w.heap.top()) <= w.settings.lossless_cost &&
           start - w.live_faces + 2 <= budget)
        collapse_top(w, options);
    out.removed_faces = start - w.live_faces;
    out.collapses = std::move(w.collapses);
    out.patch_faces = std::move(w.patch_faces);
}

void lossless_regions(Surface& m, State& s, size_t target_faces, uint32_t regions, unsigned threads) {
    const uint32_t n = uint32_t(s.pos.size());
    const size_t faces = s.idx.size() / 3;
    auto region_of = [&](uint32_t v) { return uint32_t(uint64_t(v) * regions / n); };
    {
        PrefaultedVector<uint8_t> cut(n, 0);  // on a face that spans two regions
        for (size_t f = 0; f < faces; ++f) {
            const uint32_t* t = &s.idx[f * 3];
            const uint32_t r = region_of(t[0]);
            if (region_of(t[1]) != r || region_of(t[2]) != r) cut[t[0]] = cut[t[1]] = cut[t[2]] = 1;
        }
        for (size_t f = 0; f < faces; ++f) {
            const uint32_t* t = &s.idx[f * 3];
            if (cut[t[0]] | cut[t[1]] | cut[t[2]])
                for (int k = 0; k < 3; ++k) s.locked[t[k]] |= kFrozen;
        }
    }
    const size_t budget = (s.live_faces - std::min(s.live_faces, target_faces)) / regions;
    std::vector<RegionResult> results(regions);
    std::atomic<uint32_t> next_region{0};
    std::mutex mutex;
    std::exception_ptr failure;
    // What the workers start from (read only while they run) and end with.
    const State& from = s;
    uint32_t end_now = s.now, end_stamp = s.stamp;
    // A worker: one State (heap, scratch) for each region it takes.
    auto work = [&] {
        try {
            State w(m);
            w.error_cap = w.settings.lossless_distance;
            w.now = from.now;
            w.stamp = from.stamp;
            w.live_faces = from.live_faces;
            w.restarted = true;  // (never consulted: the region loop stops at the lossless cost)
            for (uint32_t r; (r = next_region.fetch_add(1)) < regions;) {
                const uint32_t lo = uint32_t(uint64_t(r) * n / regions), hi = uint32_t(uint64_t(r + 1) * n / regions);
                simplify_region(w, lo, hi, budget, from.running_error, results[r]);
            }
            // Corner costs and marks carry the worker's counters: the global loop goes on past all of them.
            std::lock_guard guard(mutex);
            end_now = std::max(end_now, w.now);
            end_stamp = std::max(end_stamp, w.stamp);
        } catch (...) {
            std::lock_guard guard(mutex);
            if (!failure) failure = std::current_exception();
            next_region = regions;
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < std::min(threads, regions); ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    s.now = end_now;
    s.stamp = end_stamp;
    for (const RegionResult& r : results) {
        const uint32_t offset = uint32_t(s.patch_faces.size());
        for (Collapse c : r.collapses) {
            c.patch_begin += offset;
            c.patch_end += offset;
            s.running_error = std::max(s.running_error, c.error);
            c.error = s.running_error;
            s.collapses.push_back(c);
        }
        s.patch_faces.insert(s.patch_faces.end(), r.patch_faces.begin(), r.patch_faces.end());
        s.live_faces -= r.removed_faces;
    }
    for (uint8_t& l : s.locked) l &= uint8_t(~kFrozen);
}

// The number of regions of the parallel lossless phase: one per region_faces faces, at
// most 8, none under twice that (see LodOptions). From the mesh and the options alone,
// so the output does not depend on the machine.
uint32_t lossless_region_count(size_t faces, size_t region_faces) {
    region_faces = std::max<size_t>(region_faces, 1);
    if (faces / 2 < region_faces) return 1;
    return uint32_t(std::min<size_t>(8, faces / region_faces));
}

// The threads a build may use (LodOptions::threads; 0: one per hardware thread).
unsigned thread_count(const LodOptions& lod) {
    return lod.threads ? lod.threads : std::max(1u, std::thread::hardware_concurrency());
}

// Greedy: take the vertex with the cheapest outgoing collapse; try its collapses in
// cost order while they stay no dearer than the next vertex; the first legal one
// is applied. A vertex without a legal collapse waits until its neighbourhood changes.
// Why a heap and not meshoptimizer-style threshold sweeps (measured 2026-11-25, then
// dropped): sweeping the vertices in Morton order, collapsing every one keyed under the
// 1/32 quantile of the candidates (1/128 and 1/256 alike), cut the 1.1M-triangle build
// from 4.27 to 3.2 s but not the bunny's, and lost accuracy: bunny 10 % Hausdorff
// 0.00549 -> 0.00595, 1.1M 10 % 1.000 -> 1.011x the better of meshopt/VTK on our grid
// (the order among near-zero costs changes which lossless triangulation a level gets).
// Also measured and dropped: ordering the lossless phase by vertex rank alone (costs
// under lossless_cost read as 0, so the phase sweeps in Morton order): 1.1M-triangle
// `bodygen lod` 4.7-4.9 -> 4.1 s user, but bunny 10 % Hausdorff 0.749 -> 0.819x the
// better of meshopt/VTK and the 1.1M 10 % level's stored error 3.8e-7 -> 1.5e-4; and
// deciding the re-key after a rejected keyed collapse from the runner-up alone (no
// re-evaluation of u's other collapses): same bytes, no measurable gain.
void collapse_loop(Surface& m, State& s, size_t target_faces, const LodOptions& lod) {
    const uint32_t n = uint32_t(s.pos.size());
    CollapseOptions options;
    const uint32_t regions = lossless_region_count(s.live_faces, lod.region_faces);
    if (regions > 1) lossless_regions(m, s, target_faces, regions, thread_count(lod));
    for (int pass = 0; pass < 16 && s.live_faces > target_faces; ++pass) {
        s.heap.reset(s.rank);
        std::fill(s.key.begin(), s.key.end(), VertexKey{});
        s.sym_v = kNone;
        for (uint32_t v = 0; v < n; ++v) update_vertex(s, v);
        size_t done = 0;
        while (!s.heap.empty() && s.live_faces > target_faces) {
            if (!s.restarted && s.heap.key(s.heap.top()) > s.settings.lossless_cost) {
                restart_ordering(s);
                if (s.heap.empty()) break;
            }
            if (collapse_top(s, options)) ++done;
        }
        // Collapses rejected earlier may have become legal as their neighbourhoods changed.
        if (done == 0) break;
    }
}

// Area-weighted vertex normals, here rather than shared/mesh.h so that they are
// computed without floating-point contraction (same bytes on every platform).
void area_weighted_normals(std::span<const Vec3> pos, std::span<const uint32_t> idx, std::span<Vec3> n) {
    std::fill(n.begin(), n.end(), Vec3(0.0));
    for (size_t f = 0; f + 2 < idx.size(); f += 3) {
        const Vec3 c = glm::cross(pos[idx[f + 1]] - pos[idx[f]], pos[idx[f + 2]] - pos[idx[f]]);
        for (int k = 0; k < 3; ++k) n[idx[f + k]] += c;
    }
    for (Vec3& v : n) {
        const double l = glm::length(v);
        v = l > 0.0 ? v / l : Vec3(0.0, 0.0, 1.0);
    }
}

// (Measured 2026-11-26 and dropped: the vertex and face numbering, then the indices
// beside the positions and splits, on two threads: 1.1M-triangle bunny 0.11-0.14 ->
// 0.08-0.10 s, the bunny 1.5 -> 2-3 ms.)
ProgressiveBuild emit_order(const State& s, const PrefaultedVector<Vec3>& normals) {
    ProgressiveBuild pm;
    const size_t n = s.pos.size(), faces = s.idx.size() / 3, splits = s.collapses.size();
    PrefaultedVector<uint32_t> vid(n, kNone), fid(faces, kNone);
    uint32_t next_v = 0, next_f = 0;
    for (const uint32_t v : s.vertex_of_input)
        if (s.alive[v]) vid[v] = next_v++;
    pm.base_vertices = next_v;
    for (const uint32_t f : s.face_of_input)
        if (s.face_alive[f]) fid[f] = next_f++;
    pm.base_faces = next_f;
    for (size_t j = 0; j < splits; ++j) {
        const Collapse& c = s.collapses[splits - 1 - j];
        vid[c.from] = next_v++;
        for (uint32_t i = 0; i < c.removed_count; ++i) fid[c.removed[i]] = next_f++;
    }
    pm.positions.resize(next_v);
    pm.normals.resize(next_v);
    for (size_t v = 0; v < n; ++v) {
        if (vid[v] == kNone) continue;
        pm.positions[vid[v]] = s.pos[v];
        pm.normals[vid[v]] = normals[v];
    }
    pm.indices.resize(size_t(next_f) * 3);
    for (size_t f = 0; f < faces; ++f) {
        if (fid[f] == kNone) continue;
        for (int k = 0; k < 3; ++k) pm.indices[fid[f] * 3 + k] = vid[s.idx[f * 3 + k]];
    }
    pm.splits.resize(splits);
    pm.patch_begin.assign(splits + 1, 0);
    pm.patch_faces.reserve(s.patch_faces.size());
    for (size_t j = 0; j < splits; ++j) {
        const Collapse& c = s.collapses[splits - 1 - j];
        pm.splits[j] = {vid[c.to], c.removed_count, c.error, c.to_after, c.to_before};
        for (uint32_t i = c.patch_begin; i < c.patch_end; ++i) pm.patch_faces.push_back(fid[s.patch_faces[i]]);
        pm.patch_begin[j + 1] = uint32_t(pm.patch_faces.size());
    }
    return pm;
}

}  // namespace

Result<ProgressiveBuild> build_progressive_mesh(const Mesh& mesh, const LodOptions& options) {
    Surface m;
    PrefaultedVector<uint32_t> kept;
    clean_input(mesh, m, kept);
    if (m.idx.empty()) return input_error("lod: mesh '" + mesh.name + "' has no non-degenerate triangles");
    if (m.pos.size() > pm::kMaxVertices || m.idx.size() / 3 > pm::kMaxFaces)
        return input_error("lod: mesh '" + mesh.name + "' has more than " + std::to_string(pm::kMaxVertices) +
                           " vertices or " + std::to_string(pm::kMaxFaces) + " triangles");
    PrefaultedVector<Vec3> normals(m.pos.size());
    if (mesh.normals.size() == mesh.positions.size()) {
        for (size_t i = 0; i < kept.size(); ++i) {
            const double l = glm::length(mesh.normals[kept[i]]);
            normals[i] = l > 0.0 ? mesh.normals[kept[i]] / l : Vec3(0, 0, 1);
        }
    } else {
        area_weighted_normals(m.pos, m.idx, normals);
    }
    const unsigned threads = thread_count(options);
    // Runs `side` on a second thread while the caller runs `here` (both in turn on one
    // thread). Measured (bench_pm, alternating in one session): the 1.1M-triangle bunny's
    // setup 0.45-0.68 -> 0.31-0.36 s, its simplification 2.32-2.33 -> 2.10-2.15 s; the
    // bunny's setup 11.2-17.3 -> 10.0-11.6 ms, within the noise of its build. The output is
    // the same bytes.
    auto beside = [threads](auto&& here, auto&& side) {
        if (threads < 2) {
            here();
            side();
            return;
        }
        std::future<void> done = std::async(std::launch::async, side);
        here();
        done.get();
    };
    const size_t n = m.pos.size(), corners = m.idx.size();
    PrefaultedVector<Collapse> collapses;
    PrefaultedVector<uint32_t> patch_faces;
    beside(
        [&] {
            build_adjacency(m);
            reorder_vertices(m, normals);
            // After both renumberings (nothing to permute), summed in the input's face order.
            reorder_faces(m);
        },
        [&] {
            // The collapse loop's own arrays meanwhile (mapping them is a good part of their cost).
            m.key.resize(n);
            m.corner_cost.assign(corners, {0.0, 0});
            m.last_changed.assign(n, 0);
            m.mark.assign(n, 0);
            m.q.resize(n);
            m.e.resize(n);
            // At most one collapse per vertex, each moving a few faces: no regrowth (copies) in the loop.
            collapses.reserve(n);
            // (Patches move 3.5-3.8 faces per collapse on the bunny and its subdivision; the
            // storage is mapped when reserved, so the margin is kept small.)
            patch_faces.reserve(n * 5);
        });
    // Each vertex's sums are its own: two halves at once give the same bits.
    beside([&] { init_quadrics(m, options.boundary_weight, 0, uint32_t(n / 2)); },
           [&] { init_quadrics(m, options.boundary_weight, uint32_t(n / 2), uint32_t(n)); });
    const Aabb box = mesh_bounds(m.pos);
    m.settings.optimal = options.optimal_placement;
    m.settings.boundary_weight = options.boundary_weight;
    m.settings.lossless_distance = kLosslessDistance * box.extent();
    m.settings.lossless_cost = m.settings.lossless_distance * m.settings.lossless_distance;
    m.settings.box_min = box.min;
    m.settings.box_max = box.max;
    Vec3 grid_step{0.0};
    for (int k = 0; k < 3; ++k) {
        m.settings.grid_lo[k] = pm::float_at_or_below(box.min[k]);
        m.settings.grid_hi[k] = pm::float_at_or_above(box.max[k]);
        grid_step[k] = pm::quantization_step(m.settings.grid_lo[k], m.settings.grid_hi[k]);
    }
    m.settings.grid_reach2 = 4.0 * glm::dot(grid_step, grid_step);

    State s(m);
    s.collapses.swap(collapses);
    s.patch_faces.swap(patch_faces);
    collapse_loop(m, s, std::max<size_t>(options.min_triangles, 1), options);
    return emit_order(s, normals);
}

Mesh extract_level(const ProgressiveBuild& pm, size_t level) {
    level = std::min(level, pm.splits.size());
    size_t faces = pm.base_faces;
    for (size_t j = 0; j < level; ++j) faces += pm.splits[j].face_count;
    Mesh m;
    m.positions.assign(pm.positions.begin(), pm.positions.begin() + ptrdiff_t(pm.base_vertices + level));
    m.indices.assign(pm.indices.begin(), pm.indices.begin() + ptrdiff_t(faces * 3));
    // Faces are stored as they are when they appear; replay the index patches.
    for (size_t j = 0; j < level; ++j) {
        const uint32_t child = uint32_t(pm.base_vertices + j), parent = pm.splits[j].parent;
        for (uint32_t i = pm.patch_begin[j]; i < pm.patch_begin[j + 1]; ++i) {
            uint32_t* t = &m.indices[size_t(pm.patch_faces[i]) * 3];
            for (int k = 0; k < 3; ++k)
                if (t[k] == parent) t[k] = child;
        }
        m.positions[parent] = pm.splits[j].parent_to;
    }
    return m;
}

}  // namespace body::lod
