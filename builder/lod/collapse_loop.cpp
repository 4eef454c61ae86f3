// The greedy collapse loop (simplify_state.h): placements and their costs, the
// heap keys, applying a collapse, the restart of the ordering quadrics, and the
// lossless phase of a large mesh in regions on threads.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>
#include <tuple>
#include <vector>

#include "builder/lod/simplify_state.h"

namespace body::lod::detail {

// Live corners of v, compacting dead ones out of its list on the way.
static void live_corners(State& s, uint32_t v, std::vector<uint32_t>& out) {
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

static void ring_of(State& s, uint32_t v, std::vector<uint32_t>& ring) {
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
static double weight(const Quadric& q) { return q.a00 + q.a11 + q.a22; }

static Vec3 placement_raw(const State& s, uint32_t from, uint32_t to, double& cost, bool* optimum);

// Where the collapse from -> to puts the merged vertex (see simplify.h), and its
// ordering cost there: Q_from + Q_to per unit of their weight, i.e. the area-weighted
// mean squared distance to the accumulated planes. Ranking by the plain sum (area x
// distance^2) lets a vertex that has swallowed a large flat neighbourhood outrank
// collapses that move the surface farther; per unit weight the order follows the
// distance, which is what the Hausdorff error of a level measures.
static Vec3 placement(const State& s, uint32_t from, uint32_t to, double& cost, bool* optimum = nullptr) {
    const Vec3 p = placement_raw(s, from, to, cost, optimum);
    const double w = weight(s.q[from]) + weight(s.q[to]);
    if (w > 0.0) cost /= w;
    return p;
}

// placement() before the division by the weight.
static Vec3 placement_raw(const State& s, uint32_t from, uint32_t to, double& cost, bool* optimum) {
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
static Vec3 placement_cached(State& s, uint32_t from, uint32_t to, double& cost, bool* symmetric = nullptr) {
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

static double collapse_cost(const State& s, uint32_t from, uint32_t to) {
    double cost = 0.0;
    (void)placement(s, from, to, cost);
    return cost;
}

// Re-keys `u` by its cheapest outgoing collapse (or drops it when it has none).
static void update_vertex(State& s, uint32_t u) {
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
            const double stored = s.corner_cost[c];
            const bool cached = cache && stored != kNoCost;
            if (cached) {
                cost = stored;
            } else {
                bool symmetric = false;
                p = placement_cached(s, u, x, cost, &symmetric);
                if (cache) s.corner_cost[c] = cost;
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
                s.corner_cost[c] = e.cost;
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
static void update_neighbour(State& s, uint32_t x, uint32_t u, uint32_t v) {
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

// Face f (with edge u-v) is removed by the collapse u -> v: the faces across its
// two other edges (at the third vertex) become neighbours of each other.
static void relink_across(State& s, uint32_t f, uint32_t u, uint32_t v) {
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
static double collapse_error(const State& s, uint32_t u, uint32_t v, const Vec3& target) {
    return std::sqrt(std::max(0.0, s.e[u].eval_sum(s.e[v], target)));
}

// The region phase's cap on the stored error (see lossless_regions); none otherwise.
static bool error_allowed(const State& s, uint32_t u, uint32_t v, const Vec3& target) {
    return s.error_cap == std::numeric_limits<double>::infinity() || collapse_error(s, u, v, target) <= s.error_cap;
}

static void apply_collapse(State& s, uint32_t u, uint32_t v, const Vec3& target, const uint32_t shared[2],
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
    // v moves and its quadric grows: every stored cost with an end at v (the corner at v
    // and the one before it, in each face of v's fan, now u's and v's) is out of date.
    for (const std::vector<uint32_t>* corners : {&s.cu, &s.cv})
        for (const uint32_t c : *corners) {
            const uint32_t f = c / 3 * 3, at = c - f;
            s.corner_cost[c] = kNoCost;
            s.corner_cost[f + (at == 0 ? 2 : at - 1)] = kNoCost;
        }
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
static void restart_ordering(State& s) {
    s.restarted = true;
    // A lossless phase that removed less than a quarter of the faces (the bunny: 0.3%)
    // left nearly every quadric as it was built; a restart would only cost a second
    // heap build.
    if (s.live_faces * 4 > s.idx.size() / 3 * 3) return;
    rebuild_ordering_quadrics(s, s.settings.boundary_weight);
    std::fill(s.corner_cost.begin(), s.corner_cost.end(), kNoCost);
    for (uint32_t v = 0; v < uint32_t(s.locked.size()); ++v) {  // new costs, new placements: tried again
        s.locked[v] &= uint8_t(~kGaveUp);
        s.key[v].failed_pops = 0;
    }
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
static bool collapse_top(State& s, CollapseOptions& options) {
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
            // Passed over illegal collapses to get here (they are tried again at the next pop).
            if (i > 0 && ++s.key[u].failed_pops >= kMaxFailedPops) {
                s.locked[u] |= kGaveUp;
                s.heap.erase(u);
            }
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
    s.heap.erase(u);  // no legal collapse: back when its neighbourhood changes, a few times
    if (++s.key[u].failed_pops >= kMaxFailedPops) s.locked[u] |= kGaveUp;
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
// ordering cost dilutes; so a collapse here must also keep its stored error under the
// lossless distance (error_cap). Figures: bench/RESULTS.md.
struct RegionResult {
    PrefaultedVector<Collapse> collapses;
    PrefaultedVector<uint32_t> patch_faces;
    size_t removed_faces = 0;
};

static void simplify_region(State& w, uint32_t lo, uint32_t hi, size_t budget, double base_error, RegionResult& out) {
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

static void lossless_regions(Surface& m, State& s, size_t target_faces, uint32_t regions, unsigned threads) {
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
    uint32_t end_stamp = s.stamp;
    // A worker: one State (heap, scratch) for each region it takes.
    auto work = [&] {
        try {
            State w(m);
            w.error_cap = w.settings.lossless_distance;
            w.stamp = from.stamp;
            w.live_faces = from.live_faces;
            w.restarted = true;  // (never consulted: the region loop stops at the lossless cost)
            for (uint32_t r; (r = next_region.fetch_add(1)) < regions;) {
                const uint32_t lo = uint32_t(uint64_t(r) * n / regions), hi = uint32_t(uint64_t(r + 1) * n / regions);
                simplify_region(w, lo, hi, budget, from.running_error, results[r]);
            }
            // Marks carry the worker's counter: the global loop goes on past all of them.
            std::lock_guard guard(mutex);
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
    // The regions' error cap made some vertices fail there: they start afresh.
    for (uint32_t v = 0; v < uint32_t(s.locked.size()); ++v) {
        s.locked[v] &= uint8_t(~(kFrozen | kGaveUp));
        s.key[v].failed_pops = 0;
    }
}

// The number of regions of the parallel lossless phase: one per region_faces faces, at
// most 8, none under twice that (see LodOptions). From the mesh and the options alone,
// so the output does not depend on the machine.
static uint32_t lossless_region_count(size_t faces, size_t region_faces) {
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
// A heap rather than threshold sweeps: the order among near-zero costs decides which
// lossless triangulation a level gets, and sweeps lost accuracy (bench/RESULTS.md).
void collapse_loop(Surface& m, State& s, size_t target_faces, const LodOptions& lod) {
    const uint32_t n = uint32_t(s.pos.size());
    CollapseOptions options;
    const uint32_t regions = lossless_region_count(s.live_faces, lod.region_faces);
    if (regions > 1) lossless_regions(m, s, target_faces, regions, thread_count(lod));
    const size_t start_faces = s.live_faces, to_remove = start_faces > target_faces ? start_faces - target_faces : 0;
    size_t pops = 0;
    const auto report = [&] {
        if (lod.progress) lod.progress(std::min(start_faces - s.live_faces, to_remove), to_remove);
    };
    for (int pass = 0; pass < 16 && s.live_faces > target_faces; ++pass) {
        s.heap.reset(s.rank);
        std::fill(s.key.begin(), s.key.end(), VertexKey{});
        for (uint8_t& l : s.locked) l &= uint8_t(~kGaveUp);  // a new pass tries every vertex again
        s.sym_v = kNone;
        for (uint32_t v = 0; v < n; ++v) update_vertex(s, v);
        size_t done = 0;
        while (!s.heap.empty() && s.live_faces > target_faces) {
            if (!s.restarted && s.heap.key(s.heap.top()) > s.settings.lossless_cost) {
                restart_ordering(s);
                if (s.heap.empty()) break;
            }
            if (collapse_top(s, options)) ++done;
            if (++pops % 65536 == 0) report();
        }
        // Collapses rejected earlier may have become legal as their neighbourhoods changed.
        if (done == 0) break;
    }
    report();
}

// Area-weighted vertex normals, here rather than shared/mesh.h so that they are
// computed without floating-point contraction (same bytes on every platform).

}  // namespace body::lod::detail
