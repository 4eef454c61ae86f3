// Optimal tiling: the minimum-cost closed path on the toroidal graph of a
// contour pair, cost = (folded triangles, area) compared lexicographically.
//
// References:
// - E. Keppel, "Approximating complex surfaces by triangulation of contour
//   lines", IBM J. Res. Dev. 19(1), 1975 (the toroidal graph).
// - H. Fuchs, Z. M. Kedem, S. P. Uselton, "Optimal surface reconstruction from
//   planar contours", CACM 20(10), 1977 (shortest paths for every start,
//   divide and conquer over the starts since optimal paths do not cross:
//   O(m n log n)).
// - BodyGen/BodyView thesis, section 2.5.1.
//
// Rows are the longer contour "A" with its start fixed at vertex 0; columns
// are the shorter contour "B" unrolled twice, so the path for start k runs from
// (0, k) to (|A|, k + |B|). The path for the middle start is searched only
// between the paths of its neighbours, recursively. A path that fans one
// vertex to the whole other contour (a non-manifold band) is repaired by the
// cheapest local flip afterwards.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "builder/tiling/tiling_internal.h"

namespace body {

namespace {

using tiling_detail::Band;
using tiling_detail::Cost;

// One start's optimal path: the columns it visits in each row and its moves.
struct Path {
    std::vector<uint32_t> lo, hi;  // per row r in [0, rows]
    std::vector<uint8_t> moves;    // 0 = advance A (row), 1 = advance B (column)
    Cost cost;
};

struct Grid {
    const Band& band;
    bool a_is_lower;
    uint32_t rows, cols;  // |A|, |B|
    // Reused scratch.
    std::vector<Cost> prev, cur;
    std::vector<uint64_t> from_b;  // one bit per region cell: reached by a B move
    std::vector<size_t> row_offset;

    uint32_t wrap_b(uint32_t c) const { return c >= cols ? c - cols : c; }
    uint32_t wrap_a(uint32_t r) const { return r >= rows ? r - rows : r; }
    // Cost of advancing A from cell (r, c), or B from it.
    Cost cost_a(uint32_t r, uint32_t c) const {
        return a_is_lower ? band.lower_cost(wrap_a(r), wrap_b(c)) : band.upper_cost(wrap_b(c), wrap_a(r));
    }
    Cost cost_b(uint32_t r, uint32_t c) const {
        return a_is_lower ? band.upper_cost(wrap_a(r), wrap_b(c)) : band.lower_cost(wrap_b(c), wrap_a(r));
    }
};

// Phase 1: shortest path for start k inside the region between the columns
// lo_bound[r] and hi_bound[r] of each row (Keppel's dynamic programme).
static void shortest_path(Grid& g, uint32_t k, std::span<const uint32_t> lo_bound, std::span<const uint32_t> hi_bound,
                          Path& out) {
    const uint32_t rows = g.rows, end = k + g.cols;
    auto left = [&](uint32_t r) { return std::max(lo_bound[r], k); };
    auto right = [&](uint32_t r) { return std::min(hi_bound[r], end); };
    g.row_offset.resize(rows + 2);
    size_t total = 0;
    for (uint32_t r = 0; r <= rows; ++r) {
        g.row_offset[r] = total;
        total += right(r) - left(r) + 1;
    }
    g.from_b.assign((total + 63) / 64, 0);
    uint32_t width_max = 0;
    for (uint32_t r = 0; r <= rows; ++r) width_max = std::max(width_max, right(r) - left(r) + 1);
    g.prev.resize(width_max);
    g.cur.resize(width_max);

    for (uint32_t r = 0; r <= rows; ++r) {
        const uint32_t lo = left(r), hi = right(r);
        const uint32_t plo = r ? left(r - 1) : 0, phi = r ? right(r - 1) : 0;
        const size_t base = g.row_offset[r];
        for (uint32_t c = lo; c <= hi; ++c) {
            Cost best{std::numeric_limits<uint32_t>::max(), 0.0};
            bool via_b = false;
            if (r == 0 && c == k) best = Cost{};
            if (r > 0 && c >= plo && c <= phi) best = g.prev[c - plo] + g.cost_a(r - 1, c);
            if (c > lo) {
                Cost h = g.cur[c - 1 - lo] + g.cost_b(r, c - 1);
                if (h < best) best = h, via_b = true;
            }
            g.cur[c - lo] = best;
            if (via_b) {
                size_t bit = base + (c - lo);
                g.from_b[bit >> 6] |= uint64_t(1) << (bit & 63);
            }
        }
        std::swap(g.prev, g.cur);
    }
    out.cost = g.prev[end - left(rows)];

    // Backtrack from (rows, end) to (0, k), recording the columns per row.
    out.lo.assign(rows + 1, std::numeric_limits<uint32_t>::max());
    out.hi.assign(rows + 1, 0);
    out.moves.clear();
    uint32_t r = rows, c = end;
    for (;;) {
        out.lo[r] = std::min(out.lo[r], c);
        out.hi[r] = std::max(out.hi[r], c);
        if (r == 0 && c == k) break;
        size_t bit = g.row_offset[r] + (c - left(r));
        if ((g.from_b[bit >> 6] >> (bit & 63)) & 1) {
            out.moves.push_back(1);
            --c;
        } else {
            out.moves.push_back(0);
            --r;
        }
    }
    std::reverse(out.moves.begin(), out.moves.end());
}

struct Search {
    Grid& grid;
    Path best;
    uint32_t best_start = 0;

    void consider(const Path& p, uint32_t k) {
        if (p.cost < best.cost) {
            best = p;
            best_start = k;
        }
    }

    // Phase 2: divide and conquer over the starts strictly between a and b.
    void between(uint32_t a, const Path& pa, uint32_t b, const Path& pb) {
        if (b - a < 2) return;
        uint32_t k = a + (b - a) / 2;
        Path pk;
        shortest_path(grid, k, pa.lo, pb.hi, pk);
        consider(pk, k);
        between(a, pa, k, pk);
        between(k, pk, b, pb);
    }
};

}  // namespace

void tile_optimal(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles) {
    Band band(lower, upper);
    const bool a_is_lower = lower.size() >= upper.size();
    Grid grid{band,
              a_is_lower,
              uint32_t(a_is_lower ? lower.size() : upper.size()),
              uint32_t(a_is_lower ? upper.size() : lower.size()),
              {},
              {},
              {},
              {}};
    const uint32_t rows = grid.rows, cols = grid.cols;

    std::vector<uint32_t> lo0(rows + 1, 0), hi0(rows + 1, cols);
    Path first;
    shortest_path(grid, 0, lo0, hi0, first);
    Path last = first;  // the path for start |B| is the first one shifted by |B|
    for (uint32_t& v : last.lo) v += cols;
    for (uint32_t& v : last.hi) v += cols;

    Search search{grid, first, 0};
    search.between(0, first, cols, last);

    // Map A/B moves back to lower/upper and emit.
    std::vector<uint8_t> moves(search.best.moves);
    if (!a_is_lower)
        for (uint8_t& mv : moves) mv ^= 1;
    const size_t i0 = a_is_lower ? 0 : search.best_start, j0 = a_is_lower ? search.best_start : 0;
    tiling_detail::CyclicTiling tiling(band, uint32_t(i0), uint32_t(j0), moves);
    tiling.split_full_fans();
    tiling.emit(triangles);
}

}  // namespace body
