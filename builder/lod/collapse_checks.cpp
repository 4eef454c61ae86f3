// The checks of a collapse u -> v (simplify_state.h): topology (the link
// condition, no component below a tetrahedron or a triangle, no interior-to-boundary
// pull) and geometry (no flip, fold or sliver, here or on the .bpm's 16-bit grid).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "builder/lod/simplify_state.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/quantize.h"

namespace body::lod::detail {

static bool third_vertex(const State& s, uint32_t face, uint32_t u, uint32_t v, uint32_t& out) {
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

// Normal (not normalised) of face f with vertices u and v placed at p.
static Vec3 face_normal_raw(const State& s, uint32_t f, uint32_t u, uint32_t v, const Vec3& p) {
    const uint32_t* t = &s.idx[f * 3];
    Vec3 r[3];
    for (int k = 0; k < 3; ++k) r[k] = t[k] == u || t[k] == v ? p : s.pos[t[k]];
    return glm::cross(r[1] - r[0], r[2] - r[0]);
}

// The live face traversing edge b -> a (the neighbour of a face with edge a -> b).
static uint32_t face_across(const State& s, uint32_t a, uint32_t b) {
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
static void live_corners_of_both(State& s, uint32_t a, std::vector<uint32_t>& out_a, uint32_t b,
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
static size_t mark_ring(State& s, uint32_t v, const std::vector<uint32_t>& corners, std::vector<uint32_t>& ring,
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

// Whether a (opposite the removed faces) stays a neighbour of v after the collapse:
// a face other than the removed ones joins it to u or v. The vertex split that undoes
// the collapse names its new faces' third vertex among v's neighbours (.bpm). Always
// true on a manifold mesh; a face soup can lose the vertex from the ring.
static bool stays_neighbour(const State& s, uint32_t a, const uint32_t shared[2], uint32_t shared_count) {
    for (const std::vector<uint32_t>* corners : {&s.cu, &s.cv}) {
        for (const uint32_t c : *corners) {
            const uint32_t f = c / 3;
            if (f == shared[0] || (shared_count == 2 && f == shared[1])) continue;
            const uint32_t* t = &s.idx[size_t(f) * 3];
            if (t[0] == a || t[1] == a || t[2] == a) return true;
        }
    }
    return false;
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
        if (!stays_neighbour(s, a, shared, shared_count)) return false;
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
static bool flat_on_grid(const Vec3 t[3], const Vec3& n, double l2, const LoopSettings& grid) {
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
    // Normals before/after (not normalised: the fold guard below first tests the sign of
    // their dot products, and a fold needs a negative one), zero for the removed faces.
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
        if (glm::dot(n1, n1) <= 1e-12 * l2 * l2) return false;  // (so n1 is not zero)
        if (flat_on_grid(r, n1, l2, s.settings)) {
            const double l2_before = std::max({glm::dot(p[1] - p[0], p[1] - p[0]), glm::dot(p[2] - p[1], p[2] - p[1]),
                                               glm::dot(p[0] - p[2], p[0] - p[2])});
            if (!flat_on_grid(p, n0, l2_before, s.settings)) return false;
        }
        fan_old[i] = n0;
        fan_new[i] = n1;
    }
    // Fold guard: a moved face must not end up (nearly) back to back with a
    // neighbour unless it already was. Neighbours across the fan edges are other
    // faces of the fan; across the edge opposite the moving vertex, one lookup
    // (its face's corners, then their positions, requested for the whole fan first).
    // The angles are compared between unit normals; a non-negative dot product of the
    // unnormalised ones is far from kFoldCos (short of underflow, below 1e-300), so most
    // pairs need no normalisation: the same decisions as normalising every normal.
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
            const Vec3 ng = face_normal_raw(s, g, u, v, target);
            if (glm::dot(fan_new[i], ng) < 0.0) {
                const Vec3 unit_g = unit(ng), unit_new = unit(fan_new[i]);
                const double after = glm::dot(unit_new, unit_g), before = glm::dot(unit(fan_old[i]), unit_g);
                if (after < kFoldCos && after < before) return false;
            }
        }
        // Nearly every pair is far from folded: test the angle first, adjacency after
        // (a removed face's zero normal never passes the angle test).
        for (size_t j = i + 1; j < fan.size(); ++j) {
            if (!(glm::dot(fan_new[i], fan_new[j]) < 0.0)) continue;
            const double after = glm::dot(unit(fan_new[i]), unit(fan_new[j]));
            if (!(after < kFoldCos)) continue;
            const uint32_t* t = &s.idx[fan[j] / 3 * 3];
            if (t[0] != x && t[1] != x && t[2] != x && t[0] != y && t[1] != y && t[2] != y) continue;
            if (after < glm::dot(unit(fan_old[i]), unit(fan_old[j]))) return false;
        }
    }
    return true;
}

}  // namespace body::lod::detail
