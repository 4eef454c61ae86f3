// Smooth between-slice interpolation (contract in slice_interpolation.h).
//
// The tiling already pairs points on neighbouring slices: each edge of a band
// joining the two slices (a rung) is a correspondence. Each rung becomes a
// cubic Hermite curve whose end tangents are Catmull-Rom slopes taken from
// the rung continuing it above and below its ends, so a rung and its
// continuation meet with one tangent at the traced point (C1 across the
// slice), while the traced points and contour edges themselves stay where
// they are.
//
// References:
//   E. Catmull, R. Rom, "A class of local interpolating splines", Computer
//     Aided Geometric Design, 1974 (the tangents).
//   D. Meyers, S. Skinner, K. Sloan, "Surfaces from contours", ACM TOG 11(3),
//     1992 (surface fitting as the fourth sub-problem after tiling).
#include "builder/fairing/slice_interpolation.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "shared/edge_key.h"
#include "shared/mesh_intersect.h"

namespace body {
namespace {

constexpr int kNoSlice = -1;

// The slice a vertex lies on (exact height), or kNoSlice.
int slice_of(double z, std::span<const double> slice_z) {
    auto it = std::lower_bound(slice_z.begin(), slice_z.end(), z);
    return it != slice_z.end() && *it == z ? int(it - slice_z.begin()) : kNoSlice;
}

struct Rung {
    uint32_t lo = 0, hi = 0;  // vertex on the lower slice, on the upper one
    bool band = false;        // used by a band triangle: it is split
    bool curved = true;       // every triangle using it is a band triangle
    int count = 0;            // its points (at most `rings`)
    uint32_t first = 0;       // its `count` points, from lo to hi
};

struct Work {
    std::span<const double> slice_z;
    int rings = 0;           // the most points a rung gets
    double tolerance = 0.0;  // of the curve from its polyline, per unit of slice gap (0: every rung gets `rings`)
    double least = 0.0;      // stack units: the bound is max(tolerance x gap, least)
    std::vector<int> slice;  // per input vertex
    std::unordered_map<uint64_t, uint32_t> rung_of;  // edge_key -> rung
    std::vector<Rung> rungs;
    std::vector<Vec3> straight;  // positions with every rung on its straight line
};

constexpr uint32_t kNoRung = UINT32_MAX;

// The rung on edge (a, b) that is split, or kNoRung.
uint32_t split_rung(const Work& w, uint32_t a, uint32_t b) {
    auto it = w.rung_of.find(edge_key(a, b));
    return it != w.rung_of.end() && w.rungs[it->second].band ? it->second : kNoRung;
}

bool is_band(const Work& w, const uint32_t* t) {
    const int s0 = w.slice[t[0]], s1 = w.slice[t[1]], s2 = w.slice[t[2]];
    if (s0 == kNoSlice || s1 == kNoSlice || s2 == kNoSlice) return false;
    return std::max({s0, s1, s2}) - std::min({s0, s1, s2}) == 1;
}

// Phase 1: rungs, the edges joining adjacent slices, and which are split.
void find_rungs(Work& w, std::span<const uint32_t> indices) {
    w.rung_of.reserve(indices.size() / 2);
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const bool band = is_band(w, &indices[t]);
        for (int e = 0; e < 3; ++e) {
            uint32_t a = indices[t + e], b = indices[t + (e + 1) % 3];
            const int sa = w.slice[a], sb = w.slice[b];
            if (sa == kNoSlice || sb == kNoSlice || std::abs(sa - sb) != 1) continue;
            if (sa > sb) std::swap(a, b);
            auto [it, fresh] = w.rung_of.try_emplace(edge_key(a, b), uint32_t(w.rungs.size()));
            if (fresh) w.rungs.push_back({a, b});
            Rung& r = w.rungs[it->second];
            r.band = r.band || band;
            r.curved = r.curved && band;
        }
    }
}

// A crease or corner between bands: a band triangle at the vertex turns more
// than this from their mean normal. Curves there would bulge off the flat
// sides they join (a cube's edges), so rungs ending there stay straight.
constexpr double kSharpCos = 0.866;  // 30 degrees

// A rung's curve slopes (d(x, y)/dz) at its lower and upper end.
struct EndSlopes {
    Vec2 lo{0.0}, hi{0.0};
};

// The slopes turned into the tangent plane of the bands at each end with
// bands on both sides (`two_sided`; the area-weighted normal of its band
// triangles): a slope can point off the surface where the tiling fans one
// point to many. A slope that the plane would make nearly horizontal is left
// as it was. Rungs at sharp vertices are marked straight.
void in_tangent_plane(Work& w, std::span<const Vec3> positions, std::span<const uint32_t> indices,
                      std::span<const uint8_t> two_sided, std::vector<EndSlopes>& slope) {
    std::vector<Vec3> normal(positions.size(), Vec3(0.0));
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        if (!is_band(w, &indices[t])) continue;
        const Vec3 n = glm::cross(positions[indices[t + 1]] - positions[indices[t]],
                                  positions[indices[t + 2]] - positions[indices[t]]);
        for (int c = 0; c < 3; ++c) normal[indices[t + size_t(c)]] += n;
    }
    std::vector<uint8_t> sharp(positions.size(), 0);  // bytes: with vector<bool>, clang 14 at -O2 lost the marks
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        if (!is_band(w, &indices[t])) continue;
        const Vec3 n = glm::cross(positions[indices[t + 1]] - positions[indices[t]],
                                  positions[indices[t + 2]] - positions[indices[t]]);
        const double ln = glm::length(n);
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = indices[t + size_t(c)];
            const double lv = glm::length(normal[v]);
            if (ln > 0 && lv > 0 && glm::dot(n, normal[v]) < kSharpCos * ln * lv) sharp[v] = 1;
        }
    }
    auto turn = [&](uint32_t v, Vec2& m) {
        const double length = glm::length(normal[v]);
        if (!(length > 0) || !two_sided[v]) return;
        const Vec3 n = normal[v] / length, d(m, 1.0);
        const Vec3 in_plane = d - glm::dot(d, n) * n;
        if (in_plane.z > 0.25) m = Vec2(in_plane) / in_plane.z;
    };
    for (size_t r = 0; r < w.rungs.size(); ++r) {
        Rung& rung = w.rungs[r];
        if (sharp[rung.lo] || sharp[rung.hi]) rung.curved = false;
        if (!rung.band) continue;
        turn(rung.lo, slope[r].lo);
        turn(rung.hi, slope[r].hi);
    }
}

// Phase 2: each rung's Catmull-Rom slopes at its ends, from its own chord and
// the chord of the rung continuing it past that end (of the rungs on the far
// side of the end vertex, the one whose chord slope is nearest its own),
// weighted for uneven spacing. A rung and its continuation meet with one
// tangent when each continues the other; where the tiling fans one point to
// many, each rung keeps its own direction (the mean of all of them would bend
// rungs that run straight, a cylinder's diagonals). An end with no rung beyond
// it (a structure's end, a branch) takes the parabola's end slope, 2 x chord
// slope - the other end's slope, when the other end has one, so the curve
// keeps bending towards the end instead of running straight into it.
std::vector<EndSlopes> slopes(Work& w, std::span<const Vec3> positions, std::span<const uint32_t> indices) {
    const size_t n = positions.size();
    // Band rungs by their lower end (those going up from a vertex) and by their upper end (CSR).
    std::vector<uint32_t> up_start(n + 1, 0), down_start(n + 1, 0);
    for (const Rung& r : w.rungs)
        if (r.band) ++up_start[r.lo + 1], ++down_start[r.hi + 1];
    for (size_t v = 0; v < n; ++v) up_start[v + 1] += up_start[v], down_start[v + 1] += down_start[v];
    std::vector<uint32_t> up(up_start[n]), down(down_start[n]);
    {
        std::vector<uint32_t> up_fill(up_start.begin(), up_start.end() - 1),
            down_fill(down_start.begin(), down_start.end() - 1);
        for (uint32_t r = 0; r < w.rungs.size(); ++r)
            if (w.rungs[r].band) up[up_fill[w.rungs[r].lo]++] = r, down[down_fill[w.rungs[r].hi]++] = r;
    }
    auto gap = [&](const Rung& r) { return positions[r.hi].z - positions[r.lo].z; };
    auto chord = [&](const Rung& r) { return (Vec2(positions[r.hi]) - Vec2(positions[r.lo])) / gap(r); };
    // The rung among `beyond` whose chord slope is nearest `c` (UINT32_MAX: none).
    auto continuing = [&](std::span<const uint32_t> beyond, const Vec2& c) {
        uint32_t best = UINT32_MAX;
        double best_d = 0;
        for (uint32_t u : beyond) {
            const Vec2 d = chord(w.rungs[u]) - c;
            const double d2 = glm::dot(d, d);
            if (best == UINT32_MAX || d2 < best_d) best = u, best_d = d2;
        }
        return best;
    };
    std::vector<EndSlopes> slope(w.rungs.size());
    std::vector<uint8_t> two_sided(n, 0);
    for (uint32_t v = 0; v < n; ++v) two_sided[v] = up_start[v + 1] > up_start[v] && down_start[v + 1] > down_start[v];
    for (size_t i = 0; i < w.rungs.size(); ++i) {
        const Rung& r = w.rungs[i];
        if (!r.band) continue;
        const Vec2 c = chord(r);
        const double h = gap(r);
        slope[i] = {c, c};  // the chord's at a one-sided end, until the end condition below
        const uint32_t d = continuing({&down[down_start[r.lo]], &down[down_start[r.lo + 1]]}, c);
        if (d != UINT32_MAX) {
            const double hd = gap(w.rungs[d]);
            slope[i].lo = (hd * c + h * chord(w.rungs[d])) / (h + hd);
        }
        const uint32_t u = continuing({&up[up_start[r.hi]], &up[up_start[r.hi + 1]]}, c);
        if (u != UINT32_MAX) {
            const double hu = gap(w.rungs[u]);
            slope[i].hi = (h * chord(w.rungs[u]) + hu * c) / (h + hu);
        }
        if (d != UINT32_MAX && u == UINT32_MAX) slope[i].hi = 2.0 * c - slope[i].lo;
        if (u != UINT32_MAX && d == UINT32_MAX) slope[i].lo = 2.0 * c - slope[i].hi;
    }
    in_tangent_plane(w, positions, indices, two_sided, slope);
    return slope;
}

// Phase 3a: each rung's point count. The Hermite curve leaves its chord by
// at most (4/27) h (|m0'| + |m1'|) (m' = end slope - chord slope, h the gap);
// n evenly spaced points leave about that / (n + 1)^2 between the curve and
// their polyline. A curved rung takes the fewest n <= rings that bring this
// under max(tolerance x h, least); a straight one none.
void choose_counts(Work& w, std::span<const Vec3> positions, std::span<const EndSlopes> slope) {
    for (size_t i = 0; i < w.rungs.size(); ++i) {
        Rung& r = w.rungs[i];
        r.count = r.band ? w.rings : 0;
        if (!(w.tolerance > 0 || w.least > 0) || !r.band) continue;
        r.count = 0;
        if (!r.curved) continue;
        const Vec3 a = positions[r.lo], b = positions[r.hi];
        const double h = b.z - a.z;
        const Vec2 chord = (Vec2(b) - Vec2(a)) / h;
        const double leave = (4.0 / 27.0) * (glm::length(slope[i].lo - chord) + glm::length(slope[i].hi - chord));
        const double n = std::ceil(std::sqrt(leave / std::max(w.tolerance, w.least / h))) - 1.0;
        r.count = n <= 0 ? 0 : n >= double(w.rings) ? w.rings : int(n);
    }
}

// Phase 3b: each split rung's points, on its curve (`positions`) and on its
// straight line (`w.straight`).
void place_points(Work& w, std::vector<Vec3>& positions, std::span<const EndSlopes> slope) {
    size_t split = 0;
    for (const Rung& r : w.rungs) split += r.band ? size_t(r.count) : 0;
    positions.reserve(positions.size() + split);
    w.straight.reserve(positions.capacity());
    w.straight = positions;
    for (size_t i = 0; i < w.rungs.size(); ++i) {
        Rung& r = w.rungs[i];
        if (!r.band) continue;
        r.first = uint32_t(positions.size());
        const Vec3 a = positions[r.lo], b = positions[r.hi];
        const double h = b.z - a.z;
        for (int k = 1; k <= r.count; ++k) {
            const double t = double(k) / double(r.count + 1);
            const double z = a.z + t * h;
            const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
            const double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
            const Vec2 curve = h00 * Vec2(a) + h10 * h * slope[i].lo + h01 * Vec2(b) + h11 * h * slope[i].hi;
            const Vec2 line = Vec2(a) + t * (Vec2(b) - Vec2(a));
            w.straight.emplace_back(line, z);
            positions.emplace_back(r.curved ? curve : line, z);
        }
    }
}

// Point k (0 = `from`, count + 1 = the other end) along split rung `rung` from `from`.
uint32_t along(const Work& w, uint32_t rung, uint32_t from, int k) {
    if (k == 0) return from;
    const Rung& r = w.rungs[rung];
    if (k == r.count + 1) return from == r.lo ? r.hi : r.lo;
    return r.first + uint32_t(from == r.lo ? k - 1 : r.count - k);
}

// A band triangle (p, q on one slice, r on the other) as a strip from the
// base (p, q) to the apex r: the two rungs' points merged by their fraction
// of the way to the apex, a point level with the other side's next one making
// a quad split along its shorter diagonal (equal counts: quads only), else a
// triangle to the lower of the two next points.
void strip(const Work& w, uint32_t p, uint32_t q, uint32_t r, std::vector<uint32_t>& out) {
    const uint32_t pr = split_rung(w, p, r), qr = split_rung(w, q, r);
    const int a = w.rungs[pr].count, b = w.rungs[qr].count;
    int i = 0, j = 0;  // the points reached on each side (0: the base)
    while (i < a || j < b) {
        const uint32_t p0 = along(w, pr, p, i), q0 = along(w, qr, q, j);
        const uint32_t p1 = along(w, pr, p, i + 1), q1 = along(w, qr, q, j + 1);
        const long next_p = long(i + 1) * (b + 1), next_q = long(j + 1) * (a + 1);  // (i+1)/(a+1) vs (j+1)/(b+1)
        if (i < a && j < b && next_p == next_q) {
            if (glm::length(w.straight[p0] - w.straight[q1]) <= glm::length(w.straight[q0] - w.straight[p1]))
                out.insert(out.end(), {p0, q0, q1, p0, q1, p1});
            else
                out.insert(out.end(), {p0, q0, p1, q0, q1, p1});
            ++i, ++j;
        } else if (j == b || (i < a && next_p < next_q)) {
            out.insert(out.end(), {p0, q0, p1});
            ++i;
        } else {
            out.insert(out.end(), {p0, q0, q1});
            ++j;
        }
    }
    out.insert(out.end(), {along(w, pr, p, a), along(w, qr, q, b), r});
}

// Whether `p` lies in the closed triangle (a, b, c) of normal `n` (its plane's).
bool in_closed_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n, double slack) {
    return glm::dot(glm::cross(b - a, p - a), n) >= -slack && glm::dot(glm::cross(c - b, p - b), n) >= -slack &&
           glm::dot(glm::cross(a - c, p - c), n) >= -slack;
}

// A triangle that is not a band triangle with split rungs on its sides (on
// their straight lines): its boundary with those points, ear-clipped in its
// plane. An ear has positive area and no other boundary point in it or on its
// diagonal (points on a straight side would lie on it).
void fan(const Work& w, const uint32_t* t, std::vector<uint32_t>& out) {
    std::vector<uint32_t> poly;
    for (int e = 0; e < 3; ++e) {
        const uint32_t a = t[e], b = t[(e + 1) % 3];
        poly.push_back(a);
        const uint32_t rung = split_rung(w, a, b);
        if (rung == kNoRung) continue;
        for (int k = 1; k <= w.rungs[rung].count; ++k) poly.push_back(along(w, rung, a, k));
    }
    const auto& P = w.straight;
    const Vec3 n = glm::cross(P[t[1]] - P[t[0]], P[t[2]] - P[t[0]]);
    const double floor = 1e-9 * glm::dot(n, n);
    while (poly.size() > 3) {
        const size_t m = poly.size();
        size_t best = m;
        double best_area = floor;
        for (size_t i = 0; i < m; ++i) {
            const Vec3 &a = P[poly[(i + m - 1) % m]], &b = P[poly[i]], &c = P[poly[(i + 1) % m]];
            const double area = glm::dot(glm::cross(b - a, c - a), n);
            if (area <= best_area) continue;
            bool empty = true;
            for (size_t j = 0; j < m && empty; ++j)
                if (j != i && j != (i + 1) % m && j != (i + m - 1) % m)
                    empty = !in_closed_triangle(P[poly[j]], a, b, c, n, floor);
            if (empty) best = i, best_area = area;
        }
        if (best == m) break;  // cannot happen for a triangle's boundary; keep what is left as a fan
        out.insert(out.end(), {poly[(best + m - 1) % m], poly[best], poly[(best + 1) % m]});
        poly.erase(poly.begin() + long(best));
    }
    for (size_t i = 1; i + 1 < poly.size(); ++i) out.insert(out.end(), {poly[0], poly[i], poly[i + 1]});
}

// Phase 4: the new triangles; `parent` receives each one's input triangle.
std::vector<uint32_t> retriangulate(const Work& w, std::span<const uint32_t> indices, std::vector<uint32_t>& parent) {
    std::vector<uint32_t> out;
    out.reserve(indices.size() * size_t(2 * w.rings + 1));
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const uint32_t* tri = &indices[t];
        if (is_band(w, tri)) {
            // The apex is the vertex alone on its slice.
            for (int e = 0; e < 3; ++e) {
                const uint32_t p = tri[(e + 1) % 3], q = tri[(e + 2) % 3], r = tri[e];
                if (w.slice[p] == w.slice[q]) {
                    strip(w, p, q, r, out);
                    break;
                }
            }
            parent.resize(out.size() / 3, uint32_t(t / 3));
            continue;
        }
        bool split = false;
        for (int e = 0; e < 3; ++e) split = split || split_rung(w, tri[e], tri[(e + 1) % 3]) != kNoRung;
        if (split)
            fan(w, tri, out);
        else
            out.insert(out.end(), tri, tri + 3);
        parent.resize(out.size() / 3, uint32_t(t / 3));
    }
    return out;
}

// Triangles whose boxes, at the positions of the moment, share a cell of a
// uniform grid with a query's box: a superset of those whose boxes overlap a
// query's. Only the triangles listed in the slabs the queries reach are looked
// at (a rung's points keep their heights, so the slabs hold in every state);
// no box is kept: a round computes the few it looks at, and marks the queries'
// cells in a bitmap over their hull.
class NearTriangles {
public:
    NearTriangles(std::span<const uint32_t> indices, std::span<const Vec3> positions, std::span<const double> slice_z)
        : indices_(indices), slice_z_(slice_z) {
        const size_t n = indices.size() / 3;
        Aabb all;
        std::vector<uint32_t> slab(positions.size());
        for (size_t v = 0; v < positions.size(); ++v) {
            all.extend(positions[v]);
            slab[v] = slab_of(positions[v].z);
        }
        origin_ = all.min;
        start_.assign(slice_z.size() + 2, 0);
        auto slabs = [&](uint32_t t) {
            const uint32_t* c = &indices[3 * size_t(t)];
            return std::pair(std::min({slab[c[0]], slab[c[1]], slab[c[2]]}),
                             std::max({slab[c[0]], slab[c[1]], slab[c[2]]}));
        };
        double sum = 0;
        for (size_t t = 0; t < n; ++t) {
            const auto [first, last] = slabs(uint32_t(t));
            for (uint32_t l = first; l <= last; ++l) ++start_[l + 1];
            const Aabb b = box(positions, uint32_t(t));
            const Vec3 d = b.max - b.min;
            sum += std::max({d.x, d.y, d.z});
        }
        for (size_t l = 0; l + 1 < start_.size(); ++l) start_[l + 1] += start_[l];
        members_.resize(start_.back());
        std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
        for (uint32_t t = 0; t < n; ++t) {
            const auto [first, last] = slabs(t);
            for (uint32_t l = first; l <= last; ++l) members_[fill[l]++] = t;
        }
        // At least 1e-9 of the extent: at most 1e9 cells along an axis, which int32 holds. Every
        // place a vertex can take (its curve or its straight line) lies inside `all`.
        cell_ = std::max(2.0 * sum / double(std::max<size_t>(n, 1)), 1e-9 * std::max(all.extent(), 1e-300));
    }
    // Appends the triangles sharing a cell with any of `queries` (queries
    // included; a triangle may be appended more than once).
    void near(std::span<const uint32_t> queries, std::span<const Vec3> positions, std::vector<uint32_t>& out) const {
        if (queries.empty()) return;
        Range hull{{INT32_MAX, INT32_MAX, INT32_MAX}, {INT32_MIN, INT32_MIN, INT32_MIN}};
        std::vector<Range> ranges(queries.size());
        std::vector<uint8_t> reached(start_.size() - 1, 0);
        for (size_t i = 0; i < queries.size(); ++i) {
            ranges[i] = range(positions, queries[i]);
            for (int a = 0; a < 3; ++a) {
                hull.lo[a] = std::min(hull.lo[a], ranges[i].lo[a]);
                hull.hi[a] = std::max(hull.hi[a], ranges[i].hi[a]);
            }
            const Aabb b = box(positions, queries[i]);
            for (uint32_t l = slab_of(b.min.z); l <= slab_of(b.max.z); ++l) reached[l] = 1;
        }
        uint64_t dims[3];
        for (int a = 0; a < 3; ++a) dims[a] = uint64_t(int64_t(hull.hi[a]) - hull.lo[a] + 1);
        const double bits = double(dims[0]) * double(dims[1]) * double(dims[2]);
        // The queries' cells: a bitmap over their hull, or a hash set when the hull is too large for one.
        std::vector<uint64_t> bitmap;
        std::unordered_set<uint64_t> cells;
        const bool dense = bits <= double(kMaxBitmapBits);
        if (dense) bitmap.assign(size_t((uint64_t(bits) + 63) / 64), 0);
        auto key = [&](int32_t i, int32_t j, int32_t k) {
            return (uint64_t(i - hull.lo[0]) * dims[1] + uint64_t(j - hull.lo[1])) * dims[2] + uint64_t(k - hull.lo[2]);
        };
        for (const Range& r : ranges)
            visit(r, [&](int32_t i, int32_t j, int32_t k) {
                const uint64_t c = key(i, j, k);
                if (dense)
                    bitmap[c >> 6] |= uint64_t(1) << (c & 63);
                else
                    cells.insert(c);
                return false;
            });
        for (size_t l = 0; l < reached.size(); ++l) {
            if (!reached[l]) continue;
            for (uint32_t m = start_[l]; m < start_[l + 1]; ++m) {
                const uint32_t t = members_[m];
                Range r = range(positions, t);
                bool reach = true;  // first: does it reach the queries' hull at all? Then its cells inside it.
                for (int a = 0; a < 3; ++a) {
                    reach = reach && r.lo[a] <= hull.hi[a] && hull.lo[a] <= r.hi[a];
                    r.lo[a] = std::max(r.lo[a], hull.lo[a]);
                    r.hi[a] = std::min(r.hi[a], hull.hi[a]);
                }
                if (!reach) continue;
                const bool hit = visit(r, [&](int32_t i, int32_t j, int32_t k) {
                    const uint64_t c = key(i, j, k);
                    return dense ? (bitmap[c >> 6] >> (c & 63) & 1) != 0 : cells.count(c) != 0;
                });
                if (hit) out.push_back(t);
            }
        }
    }

private:
    static constexpr uint64_t kMaxBitmapBits = uint64_t(1) << 28;  // 32 MiB
    struct Range {
        int32_t lo[3], hi[3];  // cells along x, y, z
    };
    Aabb box(std::span<const Vec3> positions, uint32_t t) const {
        Aabb b;
        for (int c = 0; c < 3; ++c) b.extend(positions[indices_[3 * size_t(t) + size_t(c)]]);
        return b;
    }
    Range range(std::span<const Vec3> positions, uint32_t t) const {
        const Aabb b = box(positions, t);
        auto at = [&](double x, double lo) { return int32_t(floor_int((x - lo) / cell_)); };
        return {{at(b.min.x, origin_.x), at(b.min.y, origin_.y), at(b.min.z, origin_.z)},
                {at(b.max.x, origin_.x), at(b.max.y, origin_.y), at(b.max.z, origin_.z)}};
    }
    // The slab of height z: its layer among the slices (mesh_intersect.h).
    uint32_t slab_of(double z) const { return uint32_t(layer_of(slice_z_, z)); }
    // Calls f(i, j, k) on each cell of r until it returns true; whether one did.
    template <class F>
    static bool visit(const Range& r, F&& f) {
        for (int32_t i = r.lo[0]; i <= r.hi[0]; ++i)
            for (int32_t j = r.lo[1]; j <= r.hi[1]; ++j)
                for (int32_t k = r.lo[2]; k <= r.hi[2]; ++k)
                    if (f(i, j, k)) return true;
        return false;
    }
    std::span<const uint32_t> indices_;
    std::span<const double> slice_z_;
    Vec3 origin_{0.0};
    double cell_ = 1;
    std::vector<uint32_t> start_, members_;  // triangles by slab (CSR)
};

// Phase 5: rungs whose curve makes triangles meet that do not meet on the
// straight mesh go back on their straight line, until none is left. The
// straight mesh lies on the input triangles, so its meeting pairs are the
// children of input triangles that meet: a pair is new when its parents are
// one triangle or do not meet (asked of the input mesh only for the pairs
// found). The first round tests only pairs with a triangle off its straight
// position; later rounds only triangles next to a rung just straightened
// (any other new pair was found before and had its rungs straightened).
size_t keep_free_of_new_crossings(Work& w, std::vector<Vec3>& positions, std::span<const uint32_t> indices,
                                  std::span<const uint32_t> parent, std::span<const uint32_t> input_indices,
                                  size_t first_new, unsigned threads) {
    std::map<std::pair<uint32_t, uint32_t>, bool> parents_meet;
    auto new_pairs = [&](const std::vector<std::pair<uint32_t, uint32_t>>& found) {
        std::vector<std::pair<uint32_t, uint32_t>> ask;
        for (auto [t1, t2] : found) {
            const uint32_t a = parent[t1], b = parent[t2];
            if (a != b && !parents_meet.count({std::min(a, b), std::max(a, b)}))
                ask.push_back({std::min(a, b), std::max(a, b)});
        }
        std::sort(ask.begin(), ask.end());
        ask.erase(std::unique(ask.begin(), ask.end()), ask.end());
        const std::vector<uint8_t> meet =
            triangle_pairs_meet(std::span<const Vec3>(positions).first(first_new), input_indices, ask);
        for (size_t k = 0; k < ask.size(); ++k) parents_meet[ask[k]] = meet[k] != 0;
        std::vector<std::pair<uint32_t, uint32_t>> out;
        for (auto [t1, t2] : found) {
            const uint32_t a = parent[t1], b = parent[t2];
            if (a == b || !parents_meet[{std::min(a, b), std::max(a, b)}]) out.push_back({t1, t2});
        }
        return out;
    };
    std::vector<uint32_t> rung_at(positions.size() - first_new, 0);
    for (uint32_t r = 0; r < w.rungs.size(); ++r)
        if (w.rungs[r].band)
            for (int k = 0; k < w.rungs[r].count; ++k) rung_at[w.rungs[r].first + uint32_t(k) - first_new] = r;
    // Triangles around each rung's points (CSR).
    std::vector<uint32_t> start(w.rungs.size() + 1, 0), around;
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= first_new) ++start[rung_at[indices[i] - first_new] + 1];
    for (size_t r = 0; r < w.rungs.size(); ++r) start[r + 1] += start[r];
    around.resize(start.back());
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= first_new) around[fill[rung_at[indices[i] - first_new]]++] = uint32_t(i / 3);
    const NearTriangles near(indices, positions, w.slice_z);

    std::vector<uint8_t> off_straight(indices.size() / 3, 0);
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= first_new && positions[indices[i]] != w.straight[indices[i]]) off_straight[i / 3] = 1;
    // The first round's search, slab by slab: a triangle between two slices
    // (a band's strip) reaches no other slab, so each slab's grid stays small.
    // It leaves out pairs on either side of a slice that meet only in its
    // plane: there both are traced points and edges, which no rung moves, so
    // such a pair meets on the straight mesh alike and is never new.
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    self_intersections_by_layer(positions, indices, off_straight, w.slice_z, pairs, threads);
    size_t straightened = 0;
    for (int round = 0; round < 64; ++round) {
        std::vector<uint32_t> moved;
        for (const auto& pair : new_pairs(pairs)) {
            for (uint32_t t : {pair.first, pair.second})
                for (int c = 0; c < 3; ++c) {
                    const uint32_t v = indices[3 * size_t(t) + size_t(c)];
                    if (v < first_new) continue;
                    Rung& r = w.rungs[rung_at[v - first_new]];
                    if (!r.curved) continue;
                    r.curved = false;
                    for (int k = 0; k < r.count; ++k)
                        positions[r.first + uint32_t(k)] = w.straight[r.first + uint32_t(k)];
                    moved.push_back(rung_at[v - first_new]);
                }
        }
        straightened += moved.size();
        if (moved.empty()) return straightened;
        // The triangles next to those rungs and everything near them, tested again.
        std::vector<uint32_t> queries, subset;
        for (uint32_t r : moved)
            queries.insert(queries.end(), around.begin() + start[r], around.begin() + start[r + 1]);
        near.near(queries, positions, subset);
        std::sort(subset.begin(), subset.end());
        subset.erase(std::unique(subset.begin(), subset.end()), subset.end());
        std::vector<uint32_t> sub_indices;
        for (uint32_t t : subset)
            sub_indices.insert(sub_indices.end(), &indices[3 * size_t(t)], &indices[3 * size_t(t)] + 3);
        // Only pairs with a triangle that moved: a pair of unmoved ones that
        // meets and is new would have been found in an earlier round and moved.
        std::sort(queries.begin(), queries.end());
        std::vector<uint8_t> moved_here(subset.size(), 0);
        for (size_t k = 0; k < subset.size(); ++k)
            moved_here[k] = std::binary_search(queries.begin(), queries.end(), subset[k]);
        pairs.clear();
        count_self_intersections_of(positions, sub_indices, moved_here, 0, &pairs);
        for (auto& pair : pairs) pair = {subset[pair.first], subset[pair.second]};
    }
    // Not settled: the straight mesh, which has no new crossing by construction.
    for (Rung& r : w.rungs)
        if (r.band && r.curved) {
            r.curved = false;
            ++straightened;
        }
    positions = w.straight;
    return straightened;
}

}  // namespace

InterpolationStats interpolate_between_slices(std::vector<Vec3>& positions, std::vector<uint32_t>& indices,
                                              std::span<const double> slice_z, int rings, double tolerance,
                                              double least, unsigned threads) {
    InterpolationStats stats;
    if (rings <= 0 || slice_z.size() < 2) return stats;
    Work w;
    w.slice_z = slice_z;
    w.rings = rings;
    w.tolerance = tolerance;
    w.least = least;
    w.slice.resize(positions.size());
    for (size_t v = 0; v < positions.size(); ++v) w.slice[v] = slice_of(positions[v].z, slice_z);
    find_rungs(w, indices);
    const size_t first_new = positions.size();
    {
        const std::vector<EndSlopes> slope = slopes(w, positions, indices);
        choose_counts(w, positions, slope);
        place_points(w, positions, slope);
    }
    std::vector<uint32_t> parent;
    const std::vector<uint32_t> input_indices = indices;
    indices = retriangulate(w, indices, parent);
    stats.straightened = keep_free_of_new_crossings(w, positions, indices, parent, input_indices, first_new, threads);
    for (const Rung& r : w.rungs) {
        stats.rungs += r.band;
        stats.curved += r.band && r.curved;
        stats.points += r.band ? size_t(r.count) : 0;
    }
    return stats;
}

}  // namespace body
