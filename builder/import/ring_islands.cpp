// Islands of a label's traced rings: rings on adjacent traced slices joined
// where their regions meet (as the mesher's region-overlap correspondence
// joins them), solids with solids and holes with holes; a group whose volume
// (ring areas x slice spacing) stays under the limit is dropped: a solid
// island would be its own mesh component, a hole one a cavity.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "builder/import/label_volume.h"

namespace body::label_import {
namespace {

struct RingRef {
    size_t slice, ring;
    double area;  // signed, in pixels: solids > 0, holes < 0
    Vec2 lo, hi;
};

// Whether point p lies inside ring r (even-odd).
bool inside(const std::vector<Vec2>& r, Vec2 p) {
    bool in = false;
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
        if ((r[i].y > p.y) != (r[j].y > p.y) && p.x < r[j].x + (p.y - r[j].y) * (r[i].x - r[j].x) / (r[i].y - r[j].y))
            in = !in;
    }
    return in;
}

bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    auto side = [](Vec2 p, Vec2 q, Vec2 r) { return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x); };
    const double d1 = side(c, d, a), d2 = side(c, d, b), d3 = side(a, b, c), d4 = side(a, b, d);
    return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

// Whether the regions of two rings meet: a vertex of one inside the other, or
// two edges crossing (only edges of `b` near `a`'s box visited).
bool rings_meet(const std::vector<Vec2>& a, const RingRef& ra, const std::vector<Vec2>& b, const RingRef& rb) {
    if (ra.hi.x < rb.lo.x || rb.hi.x < ra.lo.x || ra.hi.y < rb.lo.y || rb.hi.y < ra.lo.y) return false;
    if (inside(b, a[0]) || inside(a, b[0])) return true;
    for (size_t i = 0; i < b.size(); ++i) {
        const Vec2 p = b[i], q = b[(i + 1) % b.size()];
        if (std::max(p.x, q.x) < ra.lo.x || std::min(p.x, q.x) > ra.hi.x || std::max(p.y, q.y) < ra.lo.y ||
            std::min(p.y, q.y) > ra.hi.y)
            continue;
        if (inside(a, p)) return true;
        for (size_t j = 0; j < a.size(); ++j)
            if (segments_cross(a[j], a[(j + 1) % a.size()], p, q)) return true;
    }
    return false;
}

size_t root(std::vector<size_t>& parent, size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

}  // namespace

void drop_small_islands(std::vector<std::pair<size_t, std::vector<std::vector<Vec2>>>>& traced, size_t step,
                        double min_volume, double solid_sign) {
    std::vector<RingRef> refs;
    std::vector<size_t> first(traced.size() + 1, 0);  // refs of slice s: [first[s], first[s + 1])
    for (size_t s = 0; s < traced.size(); ++s) {
        first[s] = refs.size();
        for (size_t r = 0; r < traced[s].second.size(); ++r) {
            const auto& ring = traced[s].second[r];
            RingRef ref{s, r, 0.5 * solid_sign * signed_area2(ring.data(), ring.size()), ring[0], ring[0]};
            for (const Vec2& p : ring) ref.lo = glm::min(ref.lo, p), ref.hi = glm::max(ref.hi, p);
            refs.push_back(ref);
        }
    }
    first[traced.size()] = refs.size();
    const double thickness = static_cast<double>(step);
    // A ring that alone reaches the limit keeps its group: only smaller
    // rings are tested against their neighbours.
    auto large = [&](const RingRef& r) { return std::fabs(r.area) * thickness >= min_volume; };
    std::vector<size_t> parent(refs.size());
    std::iota(parent.begin(), parent.end(), size_t(0));
    for (size_t s = 0; s + 1 < traced.size(); ++s) {
        if (traced[s + 1].first != traced[s].first + step) continue;
        for (size_t a = first[s]; a < first[s + 1]; ++a) {
            for (size_t b = first[s + 1]; b < first[s + 2]; ++b) {
                if ((refs[a].area > 0) != (refs[b].area > 0) || (large(refs[a]) && large(refs[b]))) continue;
                if (root(parent, a) == root(parent, b)) continue;
                const auto& ra = traced[s].second[refs[a].ring];
                const auto& rb = traced[s + 1].second[refs[b].ring];
                const bool meet =
                    large(refs[a]) ? rings_meet(rb, refs[b], ra, refs[a]) : rings_meet(ra, refs[a], rb, refs[b]);
                if (meet) parent[root(parent, a)] = root(parent, b);
            }
        }
    }
    std::vector<double> volume(refs.size(), 0.0);
    for (size_t i = 0; i < refs.size(); ++i)
        volume[root(parent, i)] += large(refs[i]) ? min_volume : std::fabs(refs[i].area) * thickness;
    // The largest solid group stays whatever its volume (no label vanishes).
    size_t biggest = SIZE_MAX;
    for (size_t i = 0; i < refs.size(); ++i)
        if (refs[i].area > 0 && (biggest == SIZE_MAX || volume[root(parent, i)] > volume[biggest]))
            biggest = root(parent, i);
    std::vector<std::vector<uint8_t>> drop(traced.size());
    for (size_t s = 0; s < traced.size(); ++s) drop[s].assign(traced[s].second.size(), 0);
    for (size_t i = 0; i < refs.size(); ++i) {
        const size_t g = root(parent, i);
        if (g != biggest && volume[g] < min_volume) drop[refs[i].slice][refs[i].ring] = 1;
    }
    for (size_t s = 0; s < traced.size(); ++s) {
        auto& rings = traced[s].second;
        size_t kept = 0;
        for (size_t r = 0; r < rings.size(); ++r)
            if (!drop[s][r]) {
                if (kept != r) rings[kept] = std::move(rings[r]);
                ++kept;
            }
        rings.resize(kept);
    }
}

void drop_small_islands(const SliceFrame& f, const ImportOptions& o, double min_voxels, LabelResult& out) {
    if (out.slices.empty()) return;
    // A pixel's area in the output frame, signed: negative where the frame
    // mirrors the traced plane (solids turn clockwise there).
    const double k = static_cast<double>(out.slices.front().first);
    const Vec2 origin = f.in_plane(0.0, 0.0, k), du = f.in_plane(1.0, 0.0, k) - origin,
               dv = f.in_plane(0.0, 1.0, k) - origin;
    const double pixel = du.x * dv.y - du.y * dv.x;
    drop_small_islands(out.slices, static_cast<size_t>(o.step), min_voxels * std::fabs(pixel), pixel < 0 ? -1.0 : 1.0);
    std::erase_if(out.slices, [](const auto& s) { return s.second.empty(); });
}

}  // namespace body::label_import
