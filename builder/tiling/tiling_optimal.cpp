// Optimal tiling: the minimum-cost closed path on the toroidal graph of a
// contour pair, cost = (folded corners, area) compared lexicographically
// (tiling_internal.h). Corners are charged by keeping the last move in the
// dynamic programme's state; the cyclic corner at the start is exact because
// each start is solved once per closing state. Optimal paths for different
// starts never cross when the cost is area alone, which makes the divide and
// conquer exact; corner charges can break that exchange argument, so with
// folds present the result is exact per start but the start search is FKU's
// bound, followed by a local polish with diagonal flips.
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
#include <cassert>
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

constexpr uint8_t kFreeStart = 2;
constexpr Cost kInfinite{std::numeric_limits<uint32_t>::max() / 2, 0.0};

struct Grid {
    const Band& band;
    bool a_is_lower;
    uint32_t rows, cols;  // |A|, |B|
    // Reused scratch: costs of the previous and current row for the two
    // states (last move A / last move B), and two bits per region cell
    // telling the predecessor's state of each.
    std::vector<Cost> prev_a, prev_b, cur_a, cur_b;
    std::vector<uint64_t> bits;
    std::vector<size_t> row_offset;

    Grid(const Band& b, bool lower_rows, uint32_t r, uint32_t c) : band(b), a_is_lower(lower_rows), rows(r), cols(c) {}

    uint32_t wrap_b(uint32_t c) const { return c >= cols ? c - cols : c; }
    uint32_t wrap_a(uint32_t r) const { return r >= rows ? r - rows : r; }
    // Area of advancing A from cell (r, c), or B from it.
    double area_a(uint32_t r, uint32_t c) const {
        return a_is_lower ? band.lower_area(wrap_a(r), wrap_b(c)) : band.upper_area(wrap_b(c), wrap_a(r));
    }
    double area_b(uint32_t r, uint32_t c) const {
        return a_is_lower ? band.upper_area(wrap_a(r), wrap_b(c)) : band.lower_area(wrap_b(c), wrap_a(r));
    }
    // Fold between A edge ea and B edge eb (indices may be one below zero: wrapped).
    uint32_t fold(uint32_t ea, uint32_t eb) const {
        ea = ea == uint32_t(-1) ? rows - 1 : wrap_a(ea);
        eb = eb == uint32_t(-1) ? cols - 1 : wrap_b(eb);
        return a_is_lower ? band.fold(ea, eb) : band.fold(eb, ea);
    }
    bool bit(size_t index) const { return (bits[index >> 6] >> (index & 63)) & 1; }
    void set_bit(size_t index) { bits[index >> 6] |= uint64_t(1) << (index & 63); }
};

// Phase 1: shortest path for start k inside the region between the columns
// lo_bound[r] and hi_bound[r] of each row (Keppel's dynamic programme, with
// the last move in the state so that corners can be charged). `first` is the
// type of the path's last move, which precedes its first one cyclically: the
// path starts and must end in that state; kFreeStart leaves the corner at the
// start uncharged.
static void shortest_path(Grid& g, uint32_t k, uint8_t first, std::span<const uint32_t> lo_bound,
                          std::span<const uint32_t> hi_bound, Path& out) {
    const uint32_t rows = g.rows, end = k + g.cols;
    auto left = [&](uint32_t r) { return std::max(lo_bound[r], k); };
    auto right = [&](uint32_t r) { return std::min(hi_bound[r], end); };
    g.row_offset.resize(rows + 2);
    size_t total = 0;
    uint32_t width_max = 0;
    for (uint32_t r = 0; r <= rows; ++r) {
        g.row_offset[r] = total;
        total += right(r) - left(r) + 1;
        width_max = std::max(width_max, right(r) - left(r) + 1);
    }
    g.bits.assign((2 * total + 63) / 64, 0);
    for (auto* v : {&g.prev_a, &g.prev_b, &g.cur_a, &g.cur_b}) v->resize(width_max);

    for (uint32_t r = 0; r <= rows; ++r) {
        const uint32_t lo = left(r), hi = right(r);
        const uint32_t plo = r ? left(r - 1) : 0, phi = r ? right(r - 1) : 0;
        const size_t base = 2 * g.row_offset[r];
        for (uint32_t c = lo; c <= hi; ++c) {
            Cost in_a = kInfinite, in_b = kInfinite;
            const size_t cell = base + 2 * (c - lo);
            if (r == 0 && c == k) {
                if (first != 1) in_a = Cost{};
                if (first != 0) in_b = Cost{};
            }
            if (r > 0 && c >= plo && c <= phi) {  // arrive by A from (r-1, c)
                const double area = g.area_a(r - 1, c);
                Cost via_a = g.prev_a[c - plo], via_b = g.prev_b[c - plo];
                via_b.folds += g.fold(r - 1, c - 1);
                if (via_b < via_a)
                    in_a = via_b, g.set_bit(cell);
                else
                    in_a = via_a;
                in_a.area += area;
            }
            if (c > lo) {  // arrive by B from (r, c-1)
                const double area = g.area_b(r, c - 1);
                Cost via_a = g.cur_a[c - 1 - lo], via_b = g.cur_b[c - 1 - lo];
                via_a.folds += g.fold(r - 1, c - 1);
                if (via_b < via_a)
                    in_b = via_b, g.set_bit(cell + 1);
                else
                    in_b = via_a;
                in_b.area += area;
            }
            g.cur_a[c - lo] = in_a;
            g.cur_b[c - lo] = in_b;
        }
        std::swap(g.prev_a, g.cur_a);
        std::swap(g.prev_b, g.cur_b);
    }
    const Cost end_a = g.prev_a[end - left(rows)], end_b = g.prev_b[end - left(rows)];
    uint8_t state = first;
    if (first == kFreeStart) state = end_b < end_a ? 1 : 0;
    out.cost = state == 0 ? end_a : end_b;
    if (!(out.cost < kInfinite)) return;  // the region cannot end with this move type

    // Backtrack from (rows, end) to (0, k), recording the columns per row.
    out.lo.assign(rows + 1, std::numeric_limits<uint32_t>::max());
    out.hi.assign(rows + 1, 0);
    out.moves.clear();
    uint32_t r = rows, c = end;
    for (;;) {
        out.lo[r] = std::min(out.lo[r], c);
        out.hi[r] = std::max(out.hi[r], c);
        if (r == 0 && c == k) break;
        const size_t cell = 2 * g.row_offset[r] + 2 * (c - left(r));
        const uint8_t from = g.bit(cell + state) ? 1 : 0;
        out.moves.push_back(state);
        if (state == 0)
            --r;
        else
            --c;
        state = from;
    }
    std::reverse(out.moves.begin(), out.moves.end());
}

// The optimal path for start k, with the corner at the start charged.
static void best_path(Grid& g, uint32_t k, std::span<const uint32_t> lo_bound, std::span<const uint32_t> hi_bound,
                      Path& out) {
    // Leaving the corner at the start uncharged gives a lower bound; a path
    // whose start corner does not fold attains it and is optimal. Otherwise
    // solve once per closing state.
    shortest_path(g, k, kFreeStart, lo_bound, hi_bound, out);
    const uint8_t last = out.moves.back(), head = out.moves.front();
    if (last == head) return;
    const uint32_t fold = last == 0 ? g.fold(g.rows - 1, k) : g.fold(0, k - 1);
    if (!fold) return;
    Path other;
    shortest_path(g, k, 0, lo_bound, hi_bound, out);
    shortest_path(g, k, 1, lo_bound, hi_bound, other);
    if (other.cost < out.cost) out = std::move(other);
    assert(out.cost < kInfinite);  // every region holds a path, ending with one move type or the other
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
        best_path(grid, k, pa.lo, pb.hi, pk);
        consider(pk, k);
        between(a, pa, k, pk);
        between(k, pk, b, pb);
    }
};

}  // namespace

void tile_optimal(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles) {
    Band band(lower, upper);
    const bool a_is_lower = lower.size() >= upper.size();
    Grid grid(band, a_is_lower, uint32_t(a_is_lower ? lower.size() : upper.size()),
              uint32_t(a_is_lower ? upper.size() : lower.size()));
    const uint32_t rows = grid.rows, cols = grid.cols;

    std::vector<uint32_t> lo0(rows + 1, 0), hi0(rows + 1, cols);
    Path first;
    best_path(grid, 0, lo0, hi0, first);
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
    tiling.swap_until_stable();  // corners break FKU's non-crossing argument: polish locally
    tiling.emit(triangles);
}

}  // namespace body
