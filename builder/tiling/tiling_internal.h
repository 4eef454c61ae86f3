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
// Cost of a triangle: (folds, area), compared lexicographically, so that a
// cost choice never trades a fold for area. A triangle folds when its normal
// points against the outward direction of the opposite contour at the apex
// (the edge runs backwards relative to the contour it is stitched to).
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

// Triangles whose normal makes more than this angle's cosine with the opposite
// contour's outward direction count as folded (cos 120 degrees).
inline constexpr double kFoldCosine = -0.5;

// The pair with per-vertex outward directions (unit, horizontal; zero where
// the contour has no defined tangent).
struct Band {
    std::span<const Vec3> lower, upper;
    std::vector<Vec3> lower_out, upper_out;

    Band(std::span<const Vec3> l, std::span<const Vec3> u) : lower(l), upper(u) {
        lower_out = outward(l);
        upper_out = outward(u);
    }

    static std::vector<Vec3> outward(std::span<const Vec3> c) {
        const size_t n = c.size();
        std::vector<Vec3> out(n);
        for (size_t k = 0; k < n; ++k) {
            Vec3 t = c[(k + 1) % n] - c[(k + n - 1) % n];
            Vec3 o(t.y, -t.x, 0.0);  // tangent x (+z)
            double len = glm::length(o);
            out[k] = len > 0.0 ? o / len : Vec3(0.0);
        }
        return out;
    }

    // Triangle (L_i, L_i+1, U_j); i in [0, m), j in [0, n).
    Cost lower_cost(size_t i, size_t j) const {
        const Vec3& a = lower[i];
        const Vec3& b = lower[i + 1 == lower.size() ? 0 : i + 1];
        const Vec3& c = upper[j];
        Vec3 nrm = glm::cross(b - a, c - a);
        double len = glm::length(nrm);
        return {glm::dot(nrm, upper_out[j]) < kFoldCosine * len ? 1u : 0u, 0.5 * len};
    }
    // Triangle (L_i, U_j+1, U_j).
    Cost upper_cost(size_t i, size_t j) const {
        const Vec3& a = lower[i];
        const Vec3& b = upper[j + 1 == upper.size() ? 0 : j + 1];
        const Vec3& c = upper[j];
        Vec3 nrm = glm::cross(b - a, c - a);
        double len = glm::length(nrm);
        return {glm::dot(nrm, lower_out[i]) < kFoldCosine * len ? 1u : 0u, 0.5 * len};
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
    // Cost of triangles p-1 and p now, and after flipping edge p.
    void flip_costs(size_t p, Cost& before, Cost& after) const {
        size_t q = prev(p);
        before = triangle(q) + triangle(p);
        uint32_t i, j;
        flipped_edge(p, i, j);
        after = triangle(ei[q], ej[q], mv[p]) + triangle(i, j, mv[q]);
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

}  // namespace body::tiling_detail

namespace body {

// The methods, each in its own file; inputs already validated (>= 3 finite points each).
void tile_optimal(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles);
void tile_multires(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles);

}  // namespace body
