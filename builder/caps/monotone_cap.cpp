// Polygon with holes -> triangles in O(n log n): a plane sweep splits the
// region into y-monotone pieces, each triangulated in linear time.
//
// References:
//   M. de Berg, O. Cheong, M. van Kreveld, M. Overmars, "Computational
//     Geometry: Algorithms and Applications", 3rd ed., Springer 2008, ch. 3
//     (MakeMonotone with helpers; TriangulateMonotonePolygon with a stack).
//   D. T. Lee, F. P. Preparata, "Location of a point in a planar subdivision
//     and its applications", SIAM J. Comput. 6(3), 1977 (monotone splitting).
// Ties in y are broken by x then by index ("above" is a strict total order),
// which is the textbook's symbolic tilt of horizontal edges.
#include "builder/caps/monotone_cap.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

namespace body {
namespace {

double cross3(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// The region as one vertex array: every loop oriented with the interior on
// its left (outer ccw, holes cw); next/prev stay within a loop.
struct Region {
    std::vector<Vec2> at;
    std::vector<uint32_t> next, prev;
    bool above(uint32_t a, uint32_t b) const {
        const Vec2 p = at[a], q = at[b];
        if (p.y != q.y) return p.y > q.y;
        if (p.x != q.x) return p.x < q.x;
        return a < b;
    }
};

Region make_region(std::span<const std::span<const Vec2>> loops) {
    Region r;
    for (size_t k = 0; k < loops.size(); ++k) {
        const auto& loop = loops[k];
        const uint32_t first = uint32_t(r.at.size()), n = uint32_t(loop.size());
        r.at.insert(r.at.end(), loop.begin(), loop.end());
        const bool ccw = signed_area2(loop.data(), loop.size()) > 0;
        const bool forward = (k == 0) == ccw;
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t after = first + (i + 1) % n, before = first + (i + n - 1) % n;
            r.next.push_back(forward ? after : before);
            r.prev.push_back(forward ? before : after);
        }
    }
    return r;
}

// Phase 1: the sweep (top to bottom) adding diagonals that leave y-monotone
// pieces. The status holds the edges (v, next v) with the interior on their
// right, left to right; an edge is named by its first vertex.
class MonotoneSweep {
public:
    explicit MonotoneSweep(const Region& r) : r_(r), status_(EdgeLess{&r}), helper_(r.at.size()) {}

    bool run(std::vector<std::pair<uint32_t, uint32_t>>& diagonals) {
        std::vector<uint32_t> order(r_.at.size());
        for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return r_.above(a, b); });
        merge_.assign(r_.at.size(), 0);
        for (uint32_t v : order) {
            if (!handle(v, diagonals)) return false;
        }
        return true;
    }

private:
    struct EdgeLess {
        using is_transparent = void;
        const Region* r;
        uint32_t top(uint32_t e) const { return r->above(e, r->next[e]) ? e : r->next[e]; }
        Vec2 upper(uint32_t e) const { return r->at[top(e)]; }
        Vec2 lower(uint32_t e) const { return r->above(e, r->next[e]) ? r->at[r->next[e]] : r->at[e]; }
        // <0: p left of e, >0: right of it (e directed downwards).
        double side(uint32_t e, const Vec2& p) const { return cross3(upper(e), lower(e), p); }
        bool operator()(uint32_t a, uint32_t b) const {
            if (a == b) return false;
            // Decide with the edge whose upper end came later (it lies within the other's span).
            const bool a_later = r->above(top(b), top(a));
            const uint32_t later = a_later ? a : b, other = a_later ? b : a;
            double s = side(other, upper(later));
            if (s == 0) s = side(other, lower(later));
            if (s == 0) s = later < other ? -1 : 1;
            const bool later_left = s < 0;
            return a_later ? later_left : !later_left;
        }
        bool operator()(uint32_t e, const Vec2& p) const { return side(e, p) > 0; }
        bool operator()(const Vec2& p, uint32_t e) const { return side(e, p) < 0; }
    };
    bool handle(uint32_t v, std::vector<std::pair<uint32_t, uint32_t>>& diagonals) {
        const uint32_t p = r_.prev[v], n = r_.next[v];
        const bool p_below = r_.above(v, p), n_below = r_.above(v, n);
        const bool convex = cross3(r_.at[p], r_.at[v], r_.at[n]) > 0;
        auto connect_if_merge = [&](uint32_t e) {
            if (merge_[helper_[e]]) diagonals.emplace_back(v, helper_[e]);
        };
        if (p_below && n_below) {
            if (!convex) {  // split: joined to the helper of the edge to its left
                auto left = left_of(v);
                if (!left) return false;
                diagonals.emplace_back(v, helper_[*left]);
                helper_[*left] = v;
            }
            helper_[v] = v;  // start or split: its edge (v, next) enters
            status_.insert(v);
            return true;
        }
        if (!p_below && !n_below) {  // end or merge: the edge (prev, v) leaves
            if (status_.find(p) == status_.end()) return false;
            connect_if_merge(p);
            status_.erase(p);
            if (!convex) {
                merge_[v] = 1;
                auto left = left_of(v);
                if (!left) return false;
                connect_if_merge(*left);
                helper_[*left] = v;
            }
            return true;
        }
        if (!p_below) {  // regular, interior to the right: (prev, v) leaves, (v, next) enters
            if (status_.find(p) == status_.end()) return false;
            connect_if_merge(p);
            status_.erase(p);
            helper_[v] = v;
            status_.insert(v);
            return true;
        }
        auto left = left_of(v);  // regular, interior to the left
        if (!left) return false;
        connect_if_merge(*left);
        helper_[*left] = v;
        return true;
    }

    std::optional<uint32_t> left_of(uint32_t v) const {
        auto it = status_.lower_bound(r_.at[v]);
        if (it == status_.begin()) return std::nullopt;
        return *std::prev(it);
    }

    const Region& r_;
    std::set<uint32_t, EdgeLess> status_;
    std::vector<uint32_t> helper_;
    std::vector<uint8_t> merge_;
};

// Phase 2: the pieces as vertex cycles (interior on the left), walking the
// boundary and both directions of every diagonal; at a vertex the walk takes
// the outgoing edge next clockwise from the one it came in on.
bool extract_pieces(const Region& r, const std::vector<std::pair<uint32_t, uint32_t>>& diagonals,
                    std::vector<std::vector<uint32_t>>& pieces) {
    const uint32_t n = uint32_t(r.at.size());
    // Outgoing edges per vertex (CSR): the boundary edge, then the diagonals.
    std::vector<uint32_t> begin(n + 1, 0);
    for (uint32_t v = 0; v < n; ++v) begin[v + 1] = 1;
    for (const auto& [a, b] : diagonals) ++begin[a + 1], ++begin[b + 1];
    for (uint32_t v = 0; v < n; ++v) begin[v + 1] += begin[v];
    std::vector<uint32_t> out(begin[n]), fill(begin.begin(), begin.end() - 1);
    for (uint32_t v = 0; v < n; ++v) out[fill[v]++] = r.next[v];
    for (const auto& [a, b] : diagonals) out[fill[a]++] = b, out[fill[b]++] = a;
    for (uint32_t v = 0; v < n; ++v) {
        if (begin[v + 1] - begin[v] < 2) continue;
        const Vec2 c = r.at[v];
        std::sort(out.begin() + begin[v], out.begin() + begin[v + 1], [&](uint32_t a, uint32_t b) {
            return std::atan2(r.at[a].y - c.y, r.at[a].x - c.x) < std::atan2(r.at[b].y - c.y, r.at[b].x - c.x);
        });
    }
    std::vector<uint8_t> used(out.size(), 0);
    auto slot_of = [&](uint32_t from, uint32_t to) -> uint32_t {
        for (uint32_t s = begin[from]; s < begin[from + 1]; ++s)
            if (out[s] == to) return s;
        return UINT32_MAX;
    };
    for (uint32_t start = 0; start < n; ++start) {
        for (uint32_t s0 = begin[start]; s0 < begin[start + 1]; ++s0) {
            if (used[s0]) continue;
            std::vector<uint32_t> piece;
            uint32_t from = start, s = s0;
            while (!used[s]) {
                used[s] = 1;
                piece.push_back(from);
                const uint32_t to = out[s];
                const uint32_t deg = begin[to + 1] - begin[to];
                uint32_t next_slot = begin[to];
                if (deg > 1) {
                    // Incoming from `from`: its reverse sits at slot k (sorted by angle); take k - 1 cyclically.
                    const uint32_t k = slot_of(to, from);
                    if (k == UINT32_MAX) {
                        // Arrived by a boundary edge: place `from` among the sorted directions.
                        const Vec2 c = r.at[to];
                        const double a = std::atan2(r.at[from].y - c.y, r.at[from].x - c.x);
                        uint32_t j = begin[to];
                        while (j < begin[to + 1] && std::atan2(r.at[out[j]].y - c.y, r.at[out[j]].x - c.x) < a) ++j;
                        next_slot = j == begin[to] ? begin[to + 1] - 1 : j - 1;
                    } else {
                        next_slot = k == begin[to] ? begin[to + 1] - 1 : k - 1;
                    }
                }
                from = to, s = next_slot;
            }
            if (from != start || piece.size() < 3) return false;
            pieces.push_back(std::move(piece));
        }
    }
    return true;
}

// Phase 3: one y-monotone piece -> triangles (counter-clockwise).
bool triangulate_piece(const Region& r, const std::vector<uint32_t>& piece, std::vector<uint32_t>& triangles) {
    const size_t k = piece.size();
    size_t top = 0, bottom = 0;
    for (size_t i = 1; i < k; ++i) {
        if (r.above(piece[i], piece[top])) top = i;
        if (r.above(piece[bottom], piece[i])) bottom = i;
    }
    // Forward from the top (ccw) runs down the left chain.
    std::vector<std::pair<uint32_t, bool>> sorted;  // vertex, on the left chain
    sorted.reserve(k);
    for (size_t i = 0; i < k; ++i) {
        const size_t steps_from_top = (i + k - top) % k, steps_to_bottom = (bottom + k - top) % k;
        sorted.emplace_back(piece[i], steps_from_top > 0 && steps_from_top < steps_to_bottom);
    }
    std::sort(sorted.begin(), sorted.end(), [&](const auto& a, const auto& b) { return r.above(a.first, b.first); });
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
        if (cross3(r.at[a], r.at[b], r.at[c]) < 0) std::swap(b, c);
        triangles.insert(triangles.end(), {a, b, c});
    };
    std::vector<std::pair<uint32_t, bool>> stack{sorted[0], sorted[1]};
    for (size_t j = 2; j + 1 < k; ++j) {
        const auto u = sorted[j];
        if (u.second != stack.back().second) {
            for (size_t s = 0; s + 1 < stack.size(); ++s) emit(u.first, stack[s].first, stack[s + 1].first);
            const auto last = stack.back();
            stack = {last, u};
            continue;
        }
        auto last = stack.back();
        stack.pop_back();
        while (!stack.empty()) {
            const double c = cross3(r.at[stack.back().first], r.at[last.first], r.at[u.first]);
            if (!(u.second ? c > 0 : c < 0)) break;
            emit(u.first, last.first, stack.back().first);
            last = stack.back();
            stack.pop_back();
        }
        stack.push_back(last);
        stack.push_back(u);
    }
    const uint32_t b = sorted[k - 1].first;
    for (size_t s = 0; s + 1 < stack.size(); ++s) emit(b, stack[s].first, stack[s + 1].first);
    return true;
}

}  // namespace

bool triangulate_monotone(std::span<const std::span<const Vec2>> loops, std::vector<uint32_t>& triangles) {
    const Region r = make_region(loops);
    std::vector<std::pair<uint32_t, uint32_t>> diagonals;
    MonotoneSweep sweep(r);
    if (!sweep.run(diagonals)) return false;
    std::vector<std::vector<uint32_t>> pieces;
    if (!extract_pieces(r, diagonals, pieces)) return false;
    size_t expected = 0;
    for (const auto& piece : pieces) expected += piece.size() - 2;
    const size_t begin = triangles.size();
    triangles.reserve(begin + 3 * expected);
    for (const auto& piece : pieces)
        if (!triangulate_piece(r, piece, triangles)) return false;
    return triangles.size() - begin == 3 * expected;
}

}  // namespace body
