// Multiresolution tiling, after Meyers, Skinner & Sloan and the BodyGen thesis
// (section 2.5.2): simplify both contours with a filter bank, tile the coarse
// pair optimally, then add the detail back one level at a time, each new
// vertex splitting the triangle on its edge, followed by local edge swaps on
// the same (folds, area) cost until no swap lowers it.
//
// References:
// - D. Meyers, S. Skinner, K. Sloan, "Surfaces from contours", ACM TOG 11(3),
//   1992 (multiresolution tiling).
// - C. K. Chui, "An Introduction to Wavelets", 1992 (filter banks).
// - H. Fuchs, Z. M. Kedem, S. P. Uselton, CACM 20(10), 1977 (the coarse tiling,
//   tiling_optimal.cpp).
//
// Filter bank: analysis with the linear B-spline low-pass [1 2 1] / 4 and
// dyadic down-sampling; coarse vertex k sits at fine vertex 2k, so synthesis
// (the coarse positions plus the detail) gives back exactly the finer level and
// the finest level is the input itself. Odd counts keep their last vertex.
// Cost: O(m^2 log m) for the coarse pair of at most kCoarseVertices per
// contour plus, per level, a linear expansion and swaps that are local in
// practice: O(n log n) overall.
#include <algorithm>
#include <vector>

#include "builder/tiling/tiling_internal.h"

namespace body {

namespace {

using tiling_detail::Band;
using tiling_detail::Cost;
using tiling_detail::CyclicTiling;

// Contours longer than this are simplified before the optimal tiling.
constexpr size_t kCoarseVertices = 48;

// Pairs with at most this many vertex pairs get the optimal tiling through the
// multiresolution path's first spanning edge when the multiresolution one is
// left with a fold (one start of the dynamic programme, O(m n)).
constexpr double kOptimalFallbackCells = 4e6;

// Phase 1: the filter-bank pyramid; levels[0] is the input.
static std::vector<std::vector<Vec3>> analyse(std::span<const Vec3> contour) {
    std::vector<std::vector<Vec3>> levels;
    levels.emplace_back(contour.begin(), contour.end());
    while (levels.back().size() > kCoarseVertices) {
        const std::vector<Vec3>& fine = levels.back();
        const size_t n = fine.size(), half = (n + 1) / 2;
        std::vector<Vec3> coarse(half);
        for (size_t k = 0; k < half; ++k) {
            size_t c = 2 * k;
            if (c + 1 == n) {  // odd count: the last vertex has no odd partner after it
                coarse[k] = fine[c];
                continue;
            }
            coarse[k] = 0.25 * fine[(c + n - 1) % n] + 0.5 * fine[c] + 0.25 * fine[c + 1];
        }
        levels.push_back(std::move(coarse));
    }
    return levels;
}

// Phase 2: the coarse optimal tiling as a cyclic tiling of the coarse pair.
static void coarse_tiling(const Band& band, std::vector<uint8_t>& moves, uint32_t& i0, uint32_t& j0) {
    std::vector<uint32_t> tris;
    tile_optimal(band.lower, band.upper, tris);
    // Recover the moves from the emitted triangles (lower: 2 lower ids).
    const uint32_t m = uint32_t(band.lower.size());
    moves.clear();
    for (size_t t = 0; t < tris.size(); t += 3) moves.push_back(tris[t + 1] < m ? 0 : 1);
    i0 = tris[0];
    j0 = tris[2] - m;
}

// Phase 3a: synthesis step for the tiling: every move along a coarse edge that
// gained a vertex becomes two moves on the finer level.
static void refine_moves(const CyclicTiling& coarse, bool refine_lower, bool refine_upper, size_t fine_m, size_t fine_n,
                         std::vector<uint8_t>& moves, uint32_t& i0, uint32_t& j0) {
    moves.clear();
    for (size_t p = 0; p < coarse.size(); ++p) {
        uint8_t mv = coarse.mv[p];
        moves.push_back(mv);
        if (mv == 0 && refine_lower && 2 * size_t(coarse.ei[p]) + 1 < fine_m) moves.push_back(0);
        if (mv == 1 && refine_upper && 2 * size_t(coarse.ej[p]) + 1 < fine_n) moves.push_back(1);
    }
    i0 = refine_lower ? 2 * coarse.ei[0] : coarse.ei[0];
    j0 = refine_upper ? 2 * coarse.ej[0] : coarse.ej[0];
}

}  // namespace

void tile_multires(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles) {
    auto lower_levels = analyse(lower), upper_levels = analyse(upper);
    const size_t lower_depth = lower_levels.size() - 1, upper_depth = upper_levels.size() - 1;
    const size_t depth = std::max(lower_depth, upper_depth);
    // At step s (from depth down to 0) a pyramid of depth d is at level
    // max(s - (depth - d), 0): the shallower one starts refining later.
    auto level_at = [&](size_t d, size_t step) { return step + d >= depth ? step + d - depth : 0; };

    size_t ll = level_at(lower_depth, depth), ul = level_at(upper_depth, depth);
    Band band(lower_levels[ll], upper_levels[ul]);
    std::vector<uint8_t> moves;
    uint32_t i0 = 0, j0 = 0;
    coarse_tiling(band, moves, i0, j0);
    CyclicTiling tiling(band, i0, j0, moves);

    for (size_t step = depth; step-- > 0;) {
        size_t nl = level_at(lower_depth, step), nu = level_at(upper_depth, step);
        refine_moves(tiling, nl != ll, nu != ul, lower_levels[nl].size(), upper_levels[nu].size(), moves, i0, j0);
        ll = nl;
        ul = nu;
        Band fine(lower_levels[ll], upper_levels[ul]);
        band = std::move(fine);
        tiling = CyclicTiling(band, i0, j0, moves);
        tiling.swap_until_stable();
    }
    if (depth == 0) tiling.swap_until_stable();
    tiling.split_full_fans();
    // Local swaps cannot undo a fold the coarse levels committed to; where one
    // is left and the pair is small enough, the optimal path through the same
    // first spanning edge decides (one start: the search over all starts costs
    // more for the same accuracy).
    if (tiling.total().folds > 0 && depth > 0 && double(lower.size()) * double(upper.size()) <= kOptimalFallbackCells) {
        std::vector<uint32_t> optimal;
        tile_optimal_from(lower, upper, tiling.ei[0], tiling.ej[0], optimal);
        std::vector<uint8_t> optimal_moves;
        const uint32_t m = uint32_t(lower.size());
        for (size_t t = 0; t < optimal.size(); t += 3) optimal_moves.push_back(optimal[t + 1] < m ? 0 : 1);
        CyclicTiling other(band, optimal[0], optimal[2] - m, optimal_moves);
        if (other.total() < tiling.total()) {
            triangles.insert(triangles.end(), optimal.begin(), optimal.end());
            return;
        }
    }
    tiling.emit(triangles);
}

}  // namespace body
