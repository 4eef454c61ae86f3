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

// One start's optimal path: the columns it visits in each row and its moves.
struct Path {
    std::vector<uint32_t> lo, hi;  // per row r in [0, rows]
    std::vector<uint8_t> moves;    // 0 = advance A (row), 1 = advance B (column)
    double cost = 0;               // folds * fold_weight + area
};

constexpr uint8_t kFreeStart = 2;
constexpr double kInfinite = std::numeric_limits<double>::infinity();

struct Grid {
    const Band& band;
    bool a_is_lower;
    uint32_t rows, cols;  // |A|, |B|
    // Reused scratch: costs of the previous and current row for the two
    // states (last move A / last move B), and two bits per region cell
    // telling the predecessor's state of each.
    std::vector<double> prev_a, prev_b, cur_a, cur_b;
    // The cost (folds, area) is folded into one number, folds * fold_weight +
    // area, with fold_weight above any band's total area: the same order, and
    // a branch-free inner loop.
    double fold_weight = 1;
    std::vector<uint64_t> bits;
    std::vector<size_t> row_offset;

    // A and B unrolled with an offset of one (index x + 1 holds point x, x
    // from -1): points, edge vectors and unit edge directions. The triangle
    // of a move is the same whichever contour is lower, so the inner loop
    // needs no wrapping and no branch on it.
    std::vector<Vec3> ap, ae, ad, bp, be, bd;

    Grid(const Band& b, bool lower_rows, uint32_t r, uint32_t c) : band(b), a_is_lower(lower_rows), rows(r), cols(c) {
        std::span<const Vec3> a_pts = a_is_lower ? band.lower : band.upper,
                              b_pts = a_is_lower ? band.upper : band.lower;
        unroll(a_pts, rows + 2, ap, ae, ad);
        unroll(b_pts, 2 * cols + 2, bp, be, bd);
    }
    static void unroll(std::span<const Vec3> c, size_t count, std::vector<Vec3>& p, std::vector<Vec3>& e,
                       std::vector<Vec3>& d) {
        const size_t n = c.size();
        p.resize(count);
        e.resize(count);
        d.resize(count);
        for (size_t x = 0; x < count; ++x) {
            size_t i = (x + n - 1) % n;  // point x - 1
            p[x] = c[i];
            e[x] = c[(i + 1) % n] - c[i];
            double len = glm::length(e[x]);
            d[x] = len > 0 ? e[x] / len : Vec3(0.0);
        }
    }

    // Area of advancing A from cell (r, c): triangle (A_r, A_r+1, B_c); of
    // advancing B: triangle (B_c, B_c+1, A_r).
    double area_a_of(uint32_t r, uint32_t c) const {
        return 0.5 * glm::length(glm::cross(ae[r + 1], bp[c + 1] - ap[r + 1]));
    }
    double area_b_of(uint32_t r, uint32_t c) const {
        return 0.5 * glm::length(glm::cross(be[c + 1], ap[r + 1] - bp[c + 1]));
    }
    // The same areas tabulated once per band when it has at most kTableCells
    // cells (2 doubles each): the divide and conquer visits a cell about
    // log |B| times, and the square roots were most of its time. Column c +
    // |B| holds the points of column c, and row |A| those of row 0, so the
    // table is |A| x |B| and gives the very same values.
    static constexpr size_t kTableCells = size_t(1) << 18;
    std::vector<double> table_a, table_b;
    void tabulate() {
        if (size_t(rows) * cols > kTableCells) return;
        table_a.resize(size_t(rows) * cols);
        table_b.resize(size_t(rows) * cols);
        for (uint32_t r = 0; r < rows; ++r)
            for (uint32_t c = 0; c < cols; ++c) {
                table_a[size_t(r) * cols + c] = area_a_of(r, c);
                table_b[size_t(r) * cols + c] = area_b_of(r, c);
            }
    }
    size_t cell_of(uint32_t r, uint32_t c) const {
        r -= r >= rows ? rows : 0;
        c -= c >= cols ? cols : 0;
        c -= c >= cols ? cols : 0;
        return size_t(r) * cols + c;
    }
    double area_a(uint32_t r, uint32_t c) const { return table_a.empty() ? area_a_of(r, c) : table_a[cell_of(r, c)]; }
    double area_b(uint32_t r, uint32_t c) const { return table_b.empty() ? area_b_of(r, c) : table_b[cell_of(r, c)]; }
    // Fold between A edge ea and B edge eb (either may be -1 as uint32_t: wrapped).
    uint32_t fold(uint32_t ea, uint32_t eb) const {
        return glm::dot(ad[ea + 1u], bd[eb + 1u]) < tiling_detail::kFoldCosine ? 1u : 0u;
    }
    bool bit(size_t index) const { return (bits[index >> 6] >> (index & 63)) & 1; }
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
        const double start_a = first != 1 ? 0.0 : kInfinite, start_b = first != 0 ? 0.0 : kInfinite;
        for (uint32_t c = lo; c <= hi; ++c) {
            double in_a = kInfinite, in_b = kInfinite;
            const size_t cell = base + 2 * (c - lo);
            if (r == 0 && c == k) in_a = start_a, in_b = start_b;
            const double corner = g.fold(r - 1, c - 1) ? g.fold_weight : 0.0;  // between A edge r-1 and B edge c-1
            if (r > 0 && c >= plo && c <= phi) {                               // arrive by A from (r-1, c)
                const double via_a = g.prev_a[c - plo], via_b = g.prev_b[c - plo] + corner;
                const bool from_b = via_b < via_a;
                in_a = (from_b ? via_b : via_a) + g.area_a(r - 1, c);
                g.bits[cell >> 6] |= uint64_t(from_b) << (cell & 63);
            }
            if (c > lo) {  // arrive by B from (r, c-1)
                const double via_a = g.cur_a[c - 1 - lo] + corner, via_b = g.cur_b[c - 1 - lo];
                const bool from_b = via_b < via_a;
                in_b = (from_b ? via_b : via_a) + g.area_b(r, c - 1);
                g.bits[(cell + 1) >> 6] |= uint64_t(from_b) << ((cell + 1) & 63);
            }
            g.cur_a[c - lo] = in_a;
            g.cur_b[c - lo] = in_b;
        }
        std::swap(g.prev_a, g.cur_a);
        std::swap(g.prev_b, g.cur_b);
    }
    const double end_a = g.prev_a[end - left(rows)], end_b = g.prev_b[end - left(rows)];
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

void tile_optimal(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles,
                  bool charge_corners) {
    Band band(lower, upper);
    const bool a_is_lower = lower.size() >= upper.size();
    Grid grid(band, a_is_lower, uint32_t(a_is_lower ? lower.size() : upper.size()),
              uint32_t(a_is_lower ? upper.size() : lower.size()));
    const uint32_t rows = grid.rows, cols = grid.cols;
    Aabb box;
    for (const Vec3& p : lower) box.extend(p);
    for (const Vec3& p : upper) box.extend(p);
    // Every triangle's area is below extent^2 / 2: the weight exceeds any band's area.
    grid.fold_weight = charge_corners ? double(rows + cols) * box.extent() * box.extent() + 1.0 : 0.0;

    grid.tabulate();
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
    if (charge_corners) tiling.swap_until_stable();  // corners break FKU's non-crossing argument: polish locally
    tiling.emit(triangles);
}

void tile_optimal_from(std::span<const Vec3> lower, std::span<const Vec3> upper, uint32_t i0, uint32_t j0,
                       std::vector<uint32_t>& triangles) {
    const bool a_is_lower = lower.size() >= upper.size();
    // A turned so that the start's vertex on A is A's vertex 0 (where the grid starts).
    std::span<const Vec3> a = a_is_lower ? lower : upper;
    const uint32_t shift = a_is_lower ? i0 : j0, k = a_is_lower ? j0 : i0;
    std::vector<Vec3> turned(a.begin() + shift, a.end());
    turned.insert(turned.end(), a.begin(), a.begin() + shift);
    Band turned_band(a_is_lower ? std::span<const Vec3>(turned) : lower,
                     a_is_lower ? upper : std::span<const Vec3>(turned));
    const uint32_t rows = uint32_t(a.size()), cols = uint32_t(a_is_lower ? upper.size() : lower.size());
    Grid grid(turned_band, a_is_lower, rows, cols);
    Aabb box;
    for (const Vec3& p : lower) box.extend(p);
    for (const Vec3& p : upper) box.extend(p);
    grid.fold_weight = double(rows + cols) * box.extent() * box.extent() + 1.0;
    std::vector<uint32_t> lo(rows + 1, 0), hi(rows + 1, 2 * cols);
    Path path;
    best_path(grid, k, lo, hi, path);
    std::vector<uint8_t> moves(path.moves);
    if (!a_is_lower)
        for (uint8_t& mv : moves) mv ^= 1;
    Band band(lower, upper);
    tiling_detail::CyclicTiling tiling(band, i0, j0, moves);
    tiling.split_full_fans();
    tiling.swap_until_stable();
    tiling.emit(triangles);
}

}  // namespace body
