#pragma once
// Internals shared by the tiling methods (not part of the public contract).
//
// A tiling of a contour pair is a closed path on the toroidal graph of
// Keppel/Fuchs-Kedem-Uselton: a node (i, j) is the spanning edge lower[i] -
// upper[j]; a "lower" move (i, j) -> (i+1, j) makes the triangle
// (L_i, L_i+1, U_j), an "upper" move (i, j) -> (i, j+1) makes (L_i, U_j+1, U_j).
// Both are counter-clockwise seen from outside when both contours run
// counter-clockwise seen from +z and upper lies above lower.
//
// Cost of a tiling: (folds, area), compared lexicographically, so that a cost
// choice never trades a fold for area. A fold is a corner of the path where
// the band turns back on itself: a lower move followed by an upper move (or
// the reverse) whose contour edges point in opposite directions (more than
// 120 degrees apart). Every cross-section of the band between the two
// contours then runs forward along one edge and back along the next, i.e. the
// band folds over itself there. Turns within one contour are the contour's
// own shape and cost nothing.
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "shared/geometry.h"

namespace body::tiling_detail {

struct Cost {
    uint32_t folds = 0;
    double area = 0.0;
    friend Cost operator+(Cost a, Cost b) { return {a.folds + b.folds, a.area + b.area}; }
    friend bool operator<(Cost a, Cost b) { return a.folds != b.folds ? a.folds < b.folds : a.area < b.area; }
};

// Corners whose edge directions have a cosine below this fold (120 degrees).
inline constexpr double kFoldCosine = -0.5;

// The pair with its edge vectors: edge k runs from point k to point k+1.
struct Band {
    std::span<const Vec3> lower, upper;
    std::vector<Vec3> lower_edge, upper_edge;
    std::vector<double> lower_len, upper_len;

    Band(std::span<const Vec3> l, std::span<const Vec3> u) : lower(l), upper(u) {
        edges(l, lower_edge, lower_len);
        edges(u, upper_edge, upper_len);
    }
    static void edges(std::span<const Vec3> c, std::vector<Vec3>& e, std::vector<double>& len) {
        const size_t n = c.size();
        e.resize(n);
        len.resize(n);
        for (size_t k = 0; k < n; ++k) {
            e[k] = c[k + 1 == n ? 0 : k + 1] - c[k];
            len[k] = glm::length(e[k]);
        }
    }

    // Triangle (L_i, L_i+1, U_j); i in [0, m), j in [0, n).
    double lower_area(size_t i, size_t j) const {
        return 0.5 * glm::length(glm::cross(lower_edge[i], upper[j] - lower[i]));
    }
    // Triangle (L_i, U_j+1, U_j).
    double upper_area(size_t i, size_t j) const {
        const Vec3 a = upper[j] - lower[i];
        return 0.5 * glm::length(glm::cross(a + upper_edge[j], a));
    }
    Cost lower_cost(size_t i, size_t j) const { return {0, lower_area(i, j)}; }
    Cost upper_cost(size_t i, size_t j) const { return {0, upper_area(i, j)}; }
    // Does the corner between lower edge i and upper edge j (in either order) fold?
    uint32_t fold(size_t i, size_t j) const {
        return glm::dot(lower_edge[i], upper_edge[j]) < kFoldCosine * lower_len[i] * upper_len[j] ? 1u : 0u;
    }
};

// Appends the triangles of the closed path that starts at spanning edge
// (i0, j0) and takes `moves` (0 = lower, 1 = upper; m lower and n upper moves).
inline void emit_path(size_t m, size_t n, size_t i0, size_t j0, std::span<const uint8_t> moves,
                      std::vector<uint32_t>& triangles) {
    size_t i = i0 % m, j = j0 % n;
    for (uint8_t mv : moves) {
        if (mv == 0) {
            size_t i1 = i + 1 == m ? 0 : i + 1;
            triangles.insert(triangles.end(), {uint32_t(i), uint32_t(i1), uint32_t(m + j)});
            i = i1;
        } else {
            size_t j1 = j + 1 == n ? 0 : j + 1;
            triangles.insert(triangles.end(), {uint32_t(i), uint32_t(m + j1), uint32_t(m + j)});
            j = j1;
        }
    }
}

// A tiling held as its cyclic sequence of spanning edges: edge p is
// (lower[ei[p]], upper[ej[p]]) and triangle p joins edge p to edge p+1 by move
// mv[p]. Flipping spanning edge p swaps moves p-1 and p (the diagonal of the
// quad made by triangles p-1 and p), the local operation of Meyers et al.
struct CyclicTiling {
    const Band* band = nullptr;
    uint32_t m = 0, n = 0;
    std::vector<uint32_t> ei, ej;
    std::vector<uint8_t> mv;

    CyclicTiling(const Band& b, uint32_t i0, uint32_t j0, std::span<const uint8_t> moves)
        : band(&b), m(uint32_t(b.lower.size())), n(uint32_t(b.upper.size())) {
        assign(i0, j0, moves);
    }
    void assign(uint32_t i0, uint32_t j0, std::span<const uint8_t> moves) {
        const size_t count = moves.size();
        mv.assign(moves.begin(), moves.end());
        ei.resize(count);
        ej.resize(count);
        uint32_t i = i0 % m, j = j0 % n;
        for (size_t p = 0; p < count; ++p) {
            ei[p] = i;
            ej[p] = j;
            if (mv[p] == 0)
                i = i + 1 == m ? 0 : i + 1;
            else
                j = j + 1 == n ? 0 : j + 1;
        }
    }
    size_t size() const { return mv.size(); }
    size_t prev(size_t p) const { return p == 0 ? mv.size() - 1 : p - 1; }
    size_t next(size_t p) const { return p + 1 == mv.size() ? 0 : p + 1; }
    Cost triangle(uint32_t i, uint32_t j, uint8_t move) const {
        return move == 0 ? band->lower_cost(i, j) : band->upper_cost(i, j);
    }
    Cost triangle(size_t p) const { return triangle(ei[p], ej[p], mv[p]); }
    // Fold at the corner between a move of type t1 from edge (i1, j1) and one of
    // type t2 from edge (i2, j2).
    uint32_t corner(uint8_t t1, uint32_t i1, uint32_t j1, uint8_t t2, uint32_t i2, uint32_t j2) const {
        if (t1 == t2) return 0;
        return t1 == 0 ? band->fold(i1, j2) : band->fold(i2, j1);
    }
    uint32_t corner(size_t p) const {  // between moves prev(p) and p
        size_t q = prev(p);
        return corner(mv[q], ei[q], ej[q], mv[p], ei[p], ej[p]);
    }
    Cost total() const {
        Cost c;
        for (size_t p = 0; p < mv.size(); ++p) c = c + triangle(p) + Cost{corner(p), 0.0};
        return c;
    }
    bool flippable(size_t p) const { return mv[prev(p)] != mv[p]; }
    // The spanning edge p would become after a flip.
    void flipped_edge(size_t p, uint32_t& i, uint32_t& j) const {
        size_t q = prev(p);
        i = ei[q];
        j = ej[q];
        if (mv[p] == 0)
            i = i + 1 == m ? 0 : i + 1;
        else
            j = j + 1 == n ? 0 : j + 1;
    }
    // Cost of triangles p-1 and p and of the three corners around them, now
    // and after flipping edge p.
    void flip_costs(size_t p, Cost& before, Cost& after) const {
        size_t q = prev(p), o = prev(q), r = next(p);
        before = triangle(q) + triangle(p) + Cost{corner(q) + corner(p) + corner(r), 0.0};
        uint32_t i, j;
        flipped_edge(p, i, j);
        const uint8_t tq = mv[p], tp = mv[q];  // the swapped moves
        uint32_t folds = corner(mv[o], ei[o], ej[o], tq, ei[q], ej[q]) + corner(tq, ei[q], ej[q], tp, i, j) +
                         corner(tp, i, j, mv[r], ei[r], ej[r]);
        after = triangle(ei[q], ej[q], tq) + triangle(i, j, tp) + Cost{folds, 0.0};
    }
    void flip(size_t p) {
        size_t q = prev(p);
        flipped_edge(p, ei[p], ej[p]);
        std::swap(mv[q], mv[p]);
    }
    // Length of the maximal cyclic run of equal moves through p.
    size_t run_length(size_t p) const {
        size_t len = 1;
        for (size_t q = next(p); q != p && mv[q] == mv[p]; q = next(q)) ++len;
        if (len == mv.size()) return len;
        for (size_t q = prev(p); mv[q] == mv[p]; q = prev(q)) ++len;
        return len;
    }
    // A run of n upper moves (or m lower moves) visits one spanning edge twice
    // and makes a non-manifold band.
    size_t run_limit(uint8_t move) const { return move == 0 ? m - 1 : n - 1; }

    // Shortens every over-long run by moving a move at either end past its
    // neighbour, taking the cheaper end. Optimal paths rarely need it (a vertex
    // fanned to the whole other contour).
    void split_full_fans() {
        for (size_t guard = 0; guard < 4 * mv.size(); ++guard) {
            size_t start = mv.size();
            for (size_t p = 0; p < mv.size(); ++p)
                if (mv[p] != mv[prev(p)] && run_length(p) > run_limit(mv[p])) {
                    start = p;
                    break;
                }
            if (start == mv.size()) return;
            size_t end = start;
            while (mv[next(end)] == mv[start]) end = next(end);
            // Flip at `start` (swap with the move before) or at next(end).
            Cost b1, a1, b2, a2;
            flip_costs(start, b1, a1);
            flip_costs(next(end), b2, a2);
            Cost d1{a1.folds + b2.folds, a1.area + b2.area}, d2{a2.folds + b1.folds, a2.area + b1.area};
            flip(d1 < d2 ? start : next(end));
        }
    }

    // Local optimisation (Meyers et al.): flip diagonals while that lowers the
    // cost, never making a fan of a whole contour; ends when no flip helps.
    void swap_until_stable() {
        constexpr double kEpsilon = 1e-12;  // relative area change that counts, so flips terminate
        const size_t count = size();
        std::vector<uint32_t> stack;
        std::vector<uint8_t> queued(count, 1);
        stack.reserve(count);
        for (size_t p = count; p-- > 0;) stack.push_back(uint32_t(p));
        while (!stack.empty()) {
            size_t p = stack.back();
            stack.pop_back();
            queued[p] = 0;
            if (!flippable(p)) continue;
            Cost before, after;
            flip_costs(p, before, after);
            bool better =
                after.folds != before.folds ? after.folds < before.folds : after.area < before.area * (1.0 - kEpsilon);
            if (!better) continue;
            flip(p);
            size_t q = prev(p);
            if (run_length(q) > run_limit(mv[q]) || run_length(p) > run_limit(mv[p])) {
                flip(p);  // flipping again restores the previous state
                continue;
            }
            for (size_t r : {prev(q), q, next(p)})
                if (!queued[r]) queued[r] = 1, stack.push_back(uint32_t(r));
        }
    }

    void emit(std::vector<uint32_t>& triangles) const {
        for (size_t p = 0; p < mv.size(); ++p) {
            uint32_t i = ei[p], j = ej[p];
            if (mv[p] == 0)
                triangles.insert(triangles.end(), {i, i + 1 == m ? 0 : i + 1, m + j});
            else
                triangles.insert(triangles.end(), {i, m + (j + 1 == n ? 0 : j + 1), m + j});
        }
    }
};

// Fold check and repair (tiling_unfold.cpp): while triangles of the band cross
// each other, flips the diagonal (or, on small bands, the pair of diagonals)
// that leaves the fewest crossings (ties: the lower cost). Returns the number
// of crossing triangle pairs left: 0 when none was found (large bands are
// screened by sections at 1/4, 1/2 and 3/4 of the way between the contours).
size_t unfold(CyclicTiling& tiling);

}  // namespace body::tiling_detail

namespace body {

// The methods, each in its own file; inputs already validated (>= 3 finite points each).
// `charge_corners` false: area alone (FKU's original cost; the fold check's
// second candidate when the (folds, area) optimum crosses itself).
void tile_optimal(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles,
                  bool charge_corners = true);
// The optimal tiling among the paths through spanning edge (lower[i0],
// upper[j0]) only: one start of the above, O(m n) instead of O(m n log n).
void tile_optimal_from(std::span<const Vec3> lower, std::span<const Vec3> upper, uint32_t i0, uint32_t j0,
                       std::vector<uint32_t>& triangles);
void tile_multires(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles);

}  // namespace body
