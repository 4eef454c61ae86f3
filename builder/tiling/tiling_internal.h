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

}  // namespace body::tiling_detail

namespace body {

// The methods, each in its own file; inputs already validated (>= 3 finite points each).
void tile_optimal(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles);
void tile_multires(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles);

}  // namespace body
