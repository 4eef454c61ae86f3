// Branching by nearest-branch partition of the single contour.
//
// References:
//   H. N. Christiansen, T. W. Sederberg, "Conversion of complex contour line
//     definitions into polygonal element mosaics", SIGGRAPH 1978 (composite
//     contours at branches).
//   D. Meyers, S. Skinner, K. Sloan, "Surfaces from contours", ACM TOG 11(3),
//     1992 (splitting the pre-branch contour along the branches' bisector,
//     here approximated by the nearest-branch partition and straight chords
//     that cut each side branch's arc off the main branch's piece).
//   BodyGen/BodyView thesis, section 2.6 (the overlapping method it replaces).
#include <algorithm>
#include <cmath>

#include "builder/branching/branching.h"

namespace body {
namespace {

struct Run {
    size_t start = 0, length = 0;
    uint32_t owner = 0;
};

Vec2 closest_on_polygon(const Vec2& p, std::span<const Vec2> poly) {
    double best = 1e300;
    Vec2 out = poly[0];
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i], ab = poly[(i + 1) % poly.size()] - a;
        const double l2 = glm::dot(ab, ab);
        const double t = l2 > 0 ? std::clamp(glm::dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
        const Vec2 q = a + ab * t;
        const double d = glm::length(q - p);
        if (d < best) best = d, out = q;
    }
    return out;
}

double distance_to_polygon(const Vec2& p, std::span<const Vec2> poly) {
    return glm::length(closest_on_polygon(p, poly) - p);
}

// Moves a chord point onto the bisector between two branches (equal distance
// to both), so that a chord runs along the gap between them (Meyers' medial
// axis, approximated point by point).
// Points only move across the straight chord (along `normal`), so the chord
// stays a graph over its straight line: its points keep their order and cannot
// collapse onto each other.
Vec2 onto_bisector(Vec2 p, const Vec2& normal, std::span<const Vec2> side, std::span<const Vec2> main) {
    for (int iteration = 0; iteration < 16; ++iteration) {
        const Vec2 qs = closest_on_polygon(p, side), qm = closest_on_polygon(p, main);
        const double ds = glm::length(qs - p), dm = glm::length(qm - p);
        const double gap = ds - dm;  // > 0: closer to the main branch, move towards the side branch
        const Vec2 target = gap > 0 ? qs : qm;
        const double len = glm::length(target - p);
        if (len <= 0 || std::abs(gap) <= 1e-9 * (ds + dm)) break;
        const Vec2 move = (target - p) * (0.5 * std::abs(gap) / len);
        p += normal * glm::dot(move, normal);
    }
    return p;
}

// Phase 1: each vertex goes to its nearest branch.
std::vector<uint32_t> nearest_owner(std::span<const uint32_t> single, std::span<const std::span<const Vec2>> branches,
                                    const std::vector<Vec3>& positions) {
    std::vector<uint32_t> owner(single.size(), 0);
    for (size_t i = 0; i < single.size(); ++i) {
        const Vec2 p(positions[single[i]]);
        double best = 1e300;
        for (uint32_t b = 0; b < branches.size(); ++b) {
            const double d = distance_to_polygon(p, branches[b]);
            if (d < best) best = d, owner[i] = b;
        }
    }
    return owner;
}

std::vector<Run> runs_of(const std::vector<uint32_t>& owner) {
    const size_t n = owner.size();
    size_t start = 0;
    while (start < n && owner[start] == owner[(start + n - 1) % n]) ++start;
    std::vector<Run> runs;
    if (start == n) return {Run{0, n, owner[0]}};
    for (size_t k = 0; k < n;) {
        Run r{(start + k) % n, 0, owner[(start + k) % n]};
        while (k < n && owner[(start + k) % n] == r.owner) ++r.length, ++k;
        runs.push_back(r);
    }
    return runs;
}

// Per-vertex owners back from runs.
std::vector<uint32_t> owners_of(const std::vector<Run>& runs, size_t n) {
    std::vector<uint32_t> owner(n, 0);
    for (const Run& r : runs)
        for (size_t k = 0; k < r.length; ++k) owner[(r.start + k) % n] = r.owner;
    return owner;
}

size_t count_of(const std::vector<uint32_t>& owner, uint32_t b) {
    return size_t(std::count(owner.begin(), owner.end(), b));
}

// Phase 2: every side branch (all but `main`) keeps only its longest arc, the
// other arcs go to the main branch. The main branch keeps at least one vertex
// (taken from the longest side arc if it had none). A side branch without an
// arc gets the main-branch vertices nearest to it (about its radius in steps),
// as long as the main branch keeps one; the branches still without an arc are
// returned: they bud off a chord in phase 3b.
std::vector<uint32_t> settle_runs(std::vector<uint32_t>& owner, std::span<const uint32_t> single,
                                  std::span<const std::span<const Vec2>> branches, const std::vector<Vec3>& positions,
                                  uint32_t main, double step) {
    const size_t n = owner.size();
    std::vector<Run> runs = runs_of(owner);
    std::vector<size_t> best(branches.size(), SIZE_MAX);
    for (size_t r = 0; r < runs.size(); ++r) {
        size_t& b = best[runs[r].owner];
        if (b == SIZE_MAX || runs[r].length > runs[b].length) b = r;
    }
    for (size_t r = 0; r < runs.size(); ++r)
        if (runs[r].owner != main && best[runs[r].owner] != r) runs[r].owner = main;
    if (std::none_of(runs.begin(), runs.end(), [&](const Run& r) { return r.owner == main; })) {
        // Every vertex is nearer a side branch: the longest side arc gives up
        // its last vertex (or, when every arc is one vertex, its only one).
        size_t longest = 0;
        for (size_t r = 1; r < runs.size(); ++r)
            if (runs[r].length > runs[longest].length) longest = r;
        if (runs[longest].length > 1) {
            --runs[longest].length;
            runs.push_back(Run{(runs[longest].start + runs[longest].length) % n, 1, main});
        } else {
            runs[longest].owner = main;
        }
    }
    owner = owners_of(runs, n);
    std::vector<uint32_t> buds;
    for (uint32_t b = 0; b < branches.size(); ++b) {
        if (b == main || std::find(owner.begin(), owner.end(), b) != owner.end()) continue;
        size_t main_left = count_of(owner, main);
        if (main_left < 2) {
            buds.push_back(b);
            continue;
        }
        size_t nearest = SIZE_MAX;
        double best_d = 1e300;
        for (size_t i = 0; i < n; ++i) {
            if (owner[i] != main) continue;
            const double d = distance_to_polygon(Vec2(positions[single[i]]), branches[b]);
            if (d < best_d) best_d = d, nearest = i;
        }
        double perimeter = 0;
        for (size_t i = 0; i < branches[b].size(); ++i)
            perimeter += glm::length(branches[b][(i + 1) % branches[b].size()] - branches[b][i]);
        const long half = std::max(0L, std::lround(perimeter / 6.28318530718 / std::max(step, 1e-300)));
        owner[nearest] = b;
        --main_left;
        for (long k = 1; k <= half && main_left > 1; ++k) {
            const size_t after = (nearest + size_t(k)) % n, before = (nearest + n - size_t(k) % n) % n;
            if (owner[after] == main && main_left > 1) owner[after] = b, --main_left;
            if (owner[before] == main && main_left > 1) owner[before] = b, --main_left;
        }
        // Keep the carved run contiguous.
        std::vector<Run> carved = runs_of(owner);
        size_t keep = SIZE_MAX;
        for (size_t r = 0; r < carved.size(); ++r)
            if (carved[r].owner == b && (keep == SIZE_MAX || carved[r].length > carved[keep].length)) keep = r;
        for (size_t r = 0; r < carved.size(); ++r)
            if (carved[r].owner == b && r != keep) carved[r].owner = main;
        owner = owners_of(carved, n);
    }
    return buds;
}

// Is `p` (seen from above) on the segment from `s` to some vertex of `poly`?
// The band tiling a piece with its branch makes triangles of two adjacent piece
// vertices and one branch vertex; a chord vertex there between a contour vertex
// and a branch vertex (common on voxel grids) would give a flat triangle.
bool on_a_fan_segment(const Vec2& p, const Vec2& s, std::span<const Vec2> poly, double tolerance) {
    const Vec2 sp = p - s;
    if (glm::length(sp) <= tolerance) return true;
    for (const Vec2& w : poly) {
        const Vec2 d = w - s;
        const double len2 = glm::dot(d, d);
        if (len2 <= 0) continue;
        const double along = glm::dot(sp, d);
        if (along <= 0 || along >= len2) continue;
        if (std::abs(d.x * sp.y - d.y * sp.x) <= tolerance * std::sqrt(len2)) return true;
    }
    return false;
}

// Moves a new vertex `p` across `normal` (a tenth of a step, then further,
// alternating sides) until it is off every fan segment from its contour
// neighbours `anchors` to the vertices of the branches it is tiled with.
Vec2 off_fan_segments(const Vec2& p, const Vec2& normal, std::span<const Vec2> anchors, std::span<const Vec2> side,
                      std::span<const Vec2> main, double step) {
    const double tolerance = 1e-3 * step;
    auto clear = [&](const Vec2& q) {
        for (const Vec2& s : anchors)
            if (on_a_fan_segment(q, s, side, tolerance) || on_a_fan_segment(q, s, main, tolerance)) return false;
        return true;
    };
    if (clear(p)) return p;
    for (int attempt = 1; attempt <= 8; ++attempt) {
        const double offset = 0.1 * step * double((attempt + 1) / 2) * (attempt % 2 ? 1.0 : -1.0);
        const Vec2 q = p + normal * offset;
        if (clear(q)) return q;
    }
    return p;
}

}  // namespace

const char* branching_method_name(BranchingMethod method) {
    return method == BranchingMethod::Partition ? "partition" : "overlap";
}

Result<std::vector<std::vector<uint32_t>>> partition_contour(std::span<const uint32_t> single,
                                                             std::span<const std::span<const Vec2>> branches,
                                                             double chord_z, std::vector<Vec3>& positions) {
    const size_t n = single.size();
    if (branches.size() < 2) return input_error("partition: needs at least two branches");
    if (n < 3) return input_error("partition: the contour has fewer than 3 vertices");
    for (const auto& branch : branches)
        if (branch.size() < 3) return input_error("partition: a branch has fewer than 3 vertices");
    double perimeter = 0;
    for (size_t i = 0; i < n; ++i) perimeter += glm::length(positions[single[(i + 1) % n]] - positions[single[i]]);
    const double step = std::max(perimeter / double(n), 1e-300);
    // The main branch (largest area) keeps what the side branches do not cut off.
    uint32_t main = 0;
    double main_area = -1;
    for (uint32_t b = 0; b < branches.size(); ++b) {
        const double a = std::abs(signed_area2(branches[b].data(), branches[b].size()));
        if (a > main_area) main_area = a, main = b;
    }
    std::vector<uint32_t> owner = nearest_owner(single, branches, positions);
    const std::vector<uint32_t> buds = settle_runs(owner, single, branches, positions, main, step);
    const std::vector<Run> runs = runs_of(owner);

    // Phase 3: each side arc is cut off by a chord from its end back to its
    // start, lifted to chord_z (at least one interior vertex, so the cut leaves
    // the slice plane), its interior points moved onto the bisector between the
    // side branch and the main branch, and off the fan segments of its ends.
    std::vector<std::vector<uint32_t>> pieces(branches.size());
    std::vector<std::vector<uint32_t>> chords(runs.size());  // arc end -> arc start, interior vertices
    for (size_t r = 0; r < runs.size(); ++r) {
        if (runs[r].owner == main) continue;
        const Vec2 from(positions[single[(runs[r].start + runs[r].length) % n]]);
        const Vec2 to(positions[single[runs[r].start % n]]);
        const int k = std::max(2, int(std::lround(glm::length(to - from) / step)));
        const Vec2 along = to - from;
        const double along_len = glm::length(along);
        const Vec2 normal = along_len > 0 ? Vec2(-along.y, along.x) / along_len : Vec2(0.0, 1.0);
        const auto& side = branches[runs[r].owner];
        for (int t = 1; t < k; ++t) {
            Vec2 p = onto_bisector(from + along * (double(t) / k), normal, side, branches[main]);
            std::vector<Vec2> anchors;
            if (t == 1) anchors.push_back(from);
            if (t == k - 1) anchors.push_back(to);
            p = off_fan_segments(p, normal, anchors, side, branches[main], step);
            chords[r].push_back(uint32_t(positions.size()));
            positions.emplace_back(p.x, p.y, chord_z);
        }
    }

    // Phase 4: side piece = its arc (up to the next run's first vertex) + its
    // chord; the main piece = main arcs with every side arc replaced by its chord
    // walked the other way.
    std::vector<uint32_t>& main_piece = pieces[main];
    for (size_t r = 0; r < runs.size(); ++r) {
        const Run& run = runs[r];
        if (run.owner == main) {
            for (size_t k = 0; k < run.length; ++k) main_piece.push_back(single[(run.start + k) % n]);
            continue;
        }
        std::vector<uint32_t>& piece = pieces[run.owner];
        for (size_t k = 0; k <= run.length; ++k) piece.push_back(single[(run.start + k) % n]);
        piece.insert(piece.end(), chords[r].begin(), chords[r].end());
        main_piece.push_back(single[run.start % n]);
        main_piece.insert(main_piece.end(), chords[r].rbegin(), chords[r].rend());
    }

    // Phase 3b: a branch left without an arc (the contour has too few vertices
    // for all of them) buds off the main piece: on the main piece's edge u -> v
    // off the slice plane (a chord edge) nearest to it, a new vertex q at chord_z
    // a quarter of the edge inside the main piece; the main piece walks
    // u -> q -> v and the bud's piece is the triangle u, v, q, so every edge
    // still pairs up.
    std::vector<bool> on_contour(positions.size(), false);
    std::vector<Vec2> single_xy;
    for (uint32_t id : single) on_contour[id] = true, single_xy.emplace_back(positions[id]);
    const double turn = signed_area2(single_xy.data(), single_xy.size()) < 0 ? -1.0 : 1.0;  // pieces' inside: left
    for (uint32_t b : buds) {
        const size_t m = main_piece.size();
        size_t at = SIZE_MAX;
        double best = 1e300;
        for (size_t i = 0; i < m; ++i) {
            const uint32_t u = main_piece[i], v = main_piece[(i + 1) % m];
            if (u < on_contour.size() && v < on_contour.size() && on_contour[u] && on_contour[v]) continue;
            const double d = distance_to_polygon(0.5 * (Vec2(positions[u]) + Vec2(positions[v])), branches[b]) -
                             1e-6 * glm::length(Vec2(positions[v]) - Vec2(positions[u]));  // ties: the longer edge
            if (d < best) best = d, at = i;
        }
        if (at == SIZE_MAX) return input_error("partition: no chord to bud a branch from");
        const uint32_t u = main_piece[at], v = main_piece[(at + 1) % m];
        const Vec2 pu(positions[u]), pv(positions[v]), mid = 0.5 * (pu + pv), uv = pv - pu;
        const double len = glm::length(uv);
        const Vec2 left = turn * (len > 0 ? Vec2(-uv.y, uv.x) / len : Vec2(0.0, 1.0));
        Vec2 q = mid + left * (0.25 * (len > 1e-3 * step ? len : step));
        const Vec2 anchors[] = {pu, pv};
        q = off_fan_segments(q, Vec2(uv.x, uv.y) / std::max(len, 1e-300), anchors, branches[b], branches[main], step);
        const uint32_t qi = uint32_t(positions.size());
        positions.emplace_back(q.x, q.y, chord_z);
        main_piece.insert(main_piece.begin() + std::ptrdiff_t(at + 1), qi);
        pieces[b] = {u, v, qi};
    }
    for (const auto& piece : pieces)
        if (piece.size() < 3) return input_error("partition: a branch piece has fewer than 3 vertices");
    return pieces;
}

}  // namespace body
