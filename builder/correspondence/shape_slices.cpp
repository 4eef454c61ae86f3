// Shape-based intermediate slices (contract in shape_slices.h).
//
// References:
//   G. T. Herman, J. Zheng, C. A. Bucholtz, "Shape-based interpolation", IEEE
//     CG&A 12(3), 1992 (the mean of signed distance fields between slices).
//   S. P. Raya, J. K. Udupa, "Shape-based interpolation of multidimensional
//     objects", IEEE TMI 9(1), 1990.
//   P. F. Felzenszwalb, D. P. Huttenlocher, "Distance transforms of sampled
//     functions", Theory of Computing 8, 2012 (the squared Euclidean transform).
#include "builder/correspondence/shape_slices.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "builder/contours/repair.h"
#include "builder/slicing/marching_squares.h"

namespace body {
namespace {

using Polygons = std::span<const std::span<const Vec2>>;

// Cell (i, j) has its centre at origin + (i, j) * cell.
struct Raster {
    Vec2 origin{0.0, 0.0};
    double cell = 0.0;
    size_t width = 0, height = 0;
    size_t size() const { return width * height; }
    Vec2 centre(size_t i, size_t j) const { return origin + Vec2(double(i), double(j)) * cell; }
};

// The joint box of both slices with two empty cells around it, `cells` along its longer side.
bool make_raster(Polygons lower, Polygons upper, int cells, Raster& r) {
    Vec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (Polygons side : {lower, upper})
        for (std::span<const Vec2> poly : side)
            for (const Vec2& p : poly) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
    if (!(extent > 0) || !std::isfinite(extent)) return false;
    r.cell = extent / double(cells - 1);
    r.origin = lo - Vec2(2.0 * r.cell);
    r.width = size_t(std::ceil((hi.x - lo.x) / r.cell)) + 5;
    r.height = size_t(std::ceil((hi.y - lo.y) / r.cell)) + 5;
    return true;
}

// Even-odd inside of the cells' centres, row by row.
std::vector<uint8_t> inside_mask(Polygons polys, const Raster& r) {
    std::vector<uint8_t> mask(r.size(), 0);
    std::vector<double> xs;
    for (size_t j = 0; j < r.height; ++j) {
        const double y = r.origin.y + double(j) * r.cell;
        xs.clear();
        for (std::span<const Vec2> poly : polys)
            for (size_t k = 0, n = poly.size(); k < n; ++k) {
                const Vec2 a = poly[k], b = poly[(k + 1) % n];
                if ((a.y > y) != (b.y > y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
            }
        std::sort(xs.begin(), xs.end());
        for (size_t k = 0; k + 1 < xs.size(); k += 2) {
            const double from = std::ceil((xs[k] - r.origin.x) / r.cell);
            const double to = std::ceil((xs[k + 1] - r.origin.x) / r.cell);
            for (auto i = size_t(std::max(from, 0.0)); i < size_t(std::clamp(to, 0.0, double(r.width))); ++i)
                mask[j * r.width + i] = 1;
        }
    }
    return mask;
}

// Felzenszwalb-Huttenlocher: d[q] = min_p (q - p)^2 + f[p] over a line of n values.
void distance_1d(const double* f, size_t n, double* d, std::vector<size_t>& v, std::vector<double>& z) {
    v.assign(n, 0);
    z.assign(n + 1, 0.0);
    size_t k = 0;
    z[0] = -std::numeric_limits<double>::infinity();
    z[1] = std::numeric_limits<double>::infinity();
    for (size_t q = 1; q < n; ++q) {
        // z[0] is minus infinity, so the loop stops at k = 0 at the latest.
        auto meet = [&](size_t p) {
            const double pp = double(p), qq = double(q);
            return ((f[q] + qq * qq) - (f[p] + pp * pp)) / (2.0 * qq - 2.0 * pp);
        };
        double s = meet(v[k]);
        while (s <= z[k]) s = meet(v[--k]);
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = std::numeric_limits<double>::infinity();
    }
    k = 0;
    for (size_t q = 0; q < n; ++q) {
        while (z[k + 1] < double(q)) ++k;
        const double dq = double(q) - double(v[k]);
        d[q] = dq * dq + f[v[k]];
    }
}

// Squared distance in cells from each cell to the nearest cell whose mask equals `target`.
std::vector<double> squared_distance(const std::vector<uint8_t>& mask, uint8_t target, const Raster& r) {
    constexpr double kFar = 1e20;
    std::vector<double> g(r.size()), out(r.width);
    std::vector<size_t> v;
    std::vector<double> z;
    // Along columns the input is 0 or far: the transform is the squared
    // distance to the nearest target cell of the column (the same integers
    // as distance_1d's), found by two scans of all columns at once, row by row.
    constexpr double kNone = -1.0;
    std::vector<double> last(r.width, kNone);  // per column: the row of the latest target seen
    for (size_t j = 0; j < r.height; ++j)
        for (size_t i = 0; i < r.width; ++i) {
            const size_t k = j * r.width + i;
            if (mask[k] == target) last[i] = double(j);
            const double d = double(j) - last[i];
            g[k] = last[i] == kNone ? kFar : d * d;
        }
    std::fill(last.begin(), last.end(), kNone);
    for (size_t j = r.height; j-- > 0;)
        for (size_t i = 0; i < r.width; ++i) {
            const size_t k = j * r.width + i;
            if (mask[k] == target) last[i] = double(j);
            const double d = last[i] - double(j);
            if (last[i] != kNone) g[k] = std::min(g[k], d * d);
        }
    for (size_t j = 0; j < r.height; ++j) {
        distance_1d(&g[j * r.width], r.width, out.data(), v, z);
        std::copy(out.begin(), out.begin() + long(r.width), g.begin() + long(j * r.width));
    }
    return g;
}

// Signed distance in cells (negative inside) from the cells' mask.
std::vector<double> signed_field(const std::vector<uint8_t>& mask, const Raster& r) {
    const std::vector<double> to_out = squared_distance(mask, 0, r), to_in = squared_distance(mask, 1, r);
    std::vector<double> sd(r.size());
    for (size_t k = 0; k < r.size(); ++k) sd[k] = mask[k] ? 0.5 - std::sqrt(to_out[k]) : std::sqrt(to_in[k]) - 0.5;
    return sd;
}

// Regions of cells whose mask equals `value` (4- or 8-connected); `border`
// counts those reaching the raster's edge.
size_t count_regions(const std::vector<uint8_t>& mask, uint8_t value, bool eight, const Raster& r, size_t& border) {
    std::vector<uint8_t> seen(r.size(), 0);
    std::vector<size_t> todo;
    size_t regions = 0;
    border = 0;
    const long W = long(r.width), H = long(r.height);
    for (size_t start = 0; start < r.size(); ++start) {
        if (seen[start] || mask[start] != value) continue;
        ++regions;
        bool edge = false;
        todo.assign(1, start);
        seen[start] = 1;
        while (!todo.empty()) {
            const size_t c = todo.back();
            todo.pop_back();
            const long x = long(c % r.width), y = long(c / r.width);
            edge = edge || x == 0 || y == 0 || x == W - 1 || y == H - 1;
            for (long dy = -1; dy <= 1; ++dy)
                for (long dx = -1; dx <= 1; ++dx) {
                    if ((dx == 0 && dy == 0) || (!eight && dx != 0 && dy != 0)) continue;
                    const long nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= W || ny >= H) continue;
                    const size_t n = size_t(ny * W + nx);
                    if (!seen[n] && mask[n] == value) seen[n] = 1, todo.push_back(n);
                }
        }
        border += edge;
    }
    return regions;
}

struct Topology {
    size_t solids = 0, holes = 0;
};
Topology topology(const std::vector<uint8_t>& mask, const Raster& r) {
    size_t border = 0;
    Topology t;
    t.solids = count_regions(mask, 1, false, r, border);
    t.holes = count_regions(mask, 0, true, r, border);
    t.holes -= border;
    return t;
}

// Whether the mean field's zero set changes the hole count against both slices.
bool topology_changes_between(Polygons lower, Polygons upper) {
    Raster r;
    if (!make_raster(lower, upper, kShapeDetectCells, r)) return false;
    const std::vector<uint8_t> a = inside_mask(lower, r), b = inside_mask(upper, r);
    const std::vector<double> fa = signed_field(a, r), fb = signed_field(b, r);
    std::vector<uint8_t> mid(r.size());
    for (size_t k = 0; k < r.size(); ++k) mid[k] = fa[k] + fb[k] < 0.0;
    // The mid section first: it usually matches the lower slice, and then the upper is not counted.
    auto same = [](Topology x, Topology y) { return x.solids == y.solids && x.holes == y.holes; };
    const Topology tm = topology(mid, r);
    return tm.solids > 0 && !same(tm, topology(a, r)) && !same(tm, topology(b, r));
}

// Whether polys[i] lies inside an odd number of the others (a hole under
// even-odd inside): its first point tested against each.
bool is_hole(Polygons polys, size_t i) {
    const Vec2 p = polys[i][0];
    bool inside = false;
    for (size_t j = 0; j < polys.size(); ++j) {
        if (j == i) continue;
        std::span<const Vec2> q = polys[j];
        for (size_t k = 0, n = q.size(); k < n; ++k) {
            const Vec2 a = q[k], b = q[(k + 1) % n];
            if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
        }
    }
    return inside;
}

// The solids of `polys` that meet the other slice's region grown by one cell
// (`other_grown`): by a cell inside them or a cell holding one of their
// points, so specks under a cell count too. Solids over nothing are ends (caps),
// not branches.
size_t meeting_solids(Polygons polys, const std::vector<uint8_t>& other_grown, const Raster& r) {
    size_t count = 0;
    for (size_t i = 0; i < polys.size(); ++i) {
        if (is_hole(polys, i)) continue;
        bool meets = false;
        for (const Vec2& p : polys[i]) {
            const Vec2 c = (p - r.origin) / r.cell + Vec2(0.5);
            const auto x = size_t(std::clamp(c.x, 0.0, double(r.width - 1)));
            const auto y = size_t(std::clamp(c.y, 0.0, double(r.height - 1)));
            if ((meets = other_grown[y * r.width + x] != 0)) break;
        }
        if (!meets) {
            const std::span<const Vec2> one[1] = {polys[i]};
            const std::vector<uint8_t> own = inside_mask(one, r);
            for (size_t k = 0; k < r.size() && !meets; ++k) meets = own[k] && other_grown[k];
        }
        count += meets;
    }
    return count;
}

// The mask grown by one cell (8 neighbours).
std::vector<uint8_t> grown(const std::vector<uint8_t>& mask, const Raster& r) {
    std::vector<uint8_t> out(mask);
    for (size_t j = 0; j < r.height; ++j)
        for (size_t i = 0; i < r.width; ++i) {
            if (!mask[j * r.width + i]) continue;
            for (size_t y = j ? j - 1 : 0; y <= std::min(j + 1, r.height - 1); ++y)
                for (size_t x = i ? i - 1 : 0; x <= std::min(i + 1, r.width - 1); ++x) out[y * r.width + x] = 1;
        }
    return out;
}

// Where a branch or a piece of its own lies between the slices: the height
// fraction of the section to insert, negative when none (contract in the header).
double branch_fraction(Polygons lower, Polygons upper) {
    Raster r;
    if (!make_raster(lower, upper, kShapeBranchCells, r)) return -1.0;
    const std::vector<uint8_t> a = inside_mask(lower, r), b = inside_mask(upper, r);
    if (meeting_solids(lower, grown(b, r), r) != meeting_solids(upper, grown(a, r), r)) return 0.5;
    size_t border = 0;
    const size_t sa = count_regions(a, 1, false, r, border), sb = count_regions(b, 1, false, r, border);
    const std::vector<double> fa = signed_field(a, r), fb = signed_field(b, r);
    std::vector<uint8_t> mid(r.size());
    for (double t : {0.5, 0.25, 0.75}) {
        for (size_t k = 0; k < r.size(); ++k) mid[k] = (1.0 - t) * fa[k] + t * fb[k] < 0.0;
        const size_t sm = count_regions(mid, 1, false, r, border);
        if (sm > 0 && sm != sa && sm != sb) return t;
    }
    return -1.0;
}

}  // namespace

ShapeSlice shape_slice_between(Polygons lower, Polygons upper, bool at_branches) {
    ShapeSlice out;
    if (lower.empty() || upper.empty()) return out;
    if (!topology_changes_between(lower, upper)) {
        out.t = at_branches ? branch_fraction(lower, upper) : -1.0;
        if (out.t < 0.0) return out;
        out.at_branch = true;
    }
    const double t = out.t;
    std::vector<std::vector<Vec2>>& rings = out.rings;
    Raster r;
    make_raster(lower, upper, kShapeTraceCells, r);
    const std::vector<double> fa = signed_field(inside_mask(lower, r), r), fb = signed_field(inside_mask(upper, r), r);
    // Inside (blended distance below zero) as values above the level 1; the
    // border cells are outside, like the tracer's pixels beyond the grid (0).
    std::vector<float> field(r.size());
    for (size_t k = 0; k < r.size(); ++k) field[k] = float(1.0 - ((1.0 - t) * fa[k] + t * fb[k]));
    trace_field_isolines(field, r.width, r.height, 1.0f, rings);
    const double min_area2 = 4.0 * r.cell * r.cell;  // twice the area: 2 square cells
    std::erase_if(rings, [&](std::vector<Vec2>& ring) {
        for (Vec2& p : ring) p = r.origin + p * r.cell;
        // Steps of 1/128 cell and nearly straight runs would give caps and
        // bands slivers of no area.
        clean_contour(ring, 0.01 * r.cell);
        return ring.size() < 3 || std::abs(signed_area2(ring.data(), ring.size())) < min_area2;
    });
    return out;
}

std::vector<std::vector<Vec2>> shape_mid_slice(Polygons lower, Polygons upper) {
    ShapeSlice s = shape_slice_between(lower, upper, false);
    if (s.t != 0.5) return {};
    return std::move(s.rings);
}

}  // namespace body
