// Contour repairs: point clean-up (duplicates, near duplicates, collinear
// points, zero-width spikes) and the union of crossing contours (Clipper).
//
// References:
//   A. Johnson, Clipper 6 (libpolyclipping): Vatti's clipping algorithm with
//     integer coordinates; B. R. Vatti, "A generic solution to polygon
//     clipping", CACM 35(7), 1992.
#include "builder/contours/repair.h"

#include <algorithm>
#include <clipper.hpp>
#include <cmath>
#include <unordered_map>

namespace body {
namespace {

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + ab * t));
}

enum class Removal { None, Collinear, Spike };

// Whether b (between a and c) can go, and how far the boundary moves then.
Removal removable(const Vec2& a, const Vec2& b, const Vec2& c, double noise, double& moved) {
    if (a == c) return moved = glm::length(b - a), Removal::Spike;  // out and back to the same point
    const Vec2 ac = c - a;
    const double len = glm::length(ac);  // > 0: a != c
    if (std::abs(ac.x * (b.y - a.y) - ac.y * (b.x - a.x)) / len > noise) return Removal::None;
    moved = segment_distance(b, a, c);
    const double t = glm::dot(b - a, ac) / (len * len);
    return t >= 0.0 && t <= 1.0 ? Removal::Collinear : Removal::Spike;
}

// Keeps the first of each run of points within `noise` of each other (cyclically).
void remove_near_duplicates(std::vector<Vec2>& pts, double noise, PointRepair& r) {
    std::vector<Vec2> out;
    out.reserve(pts.size());
    for (const Vec2& p : pts) {
        if (!out.empty() && glm::length(p - out.back()) <= noise)
            r.note(p, glm::length(p - out.back()));
        else
            out.push_back(p);
    }
    while (out.size() > 1 && glm::length(out.back() - out.front()) <= noise) {
        r.note(out.back(), glm::length(out.back() - out.front()));
        out.pop_back();
    }
    if (out.size() != pts.size()) pts = std::move(out);
}

// One pass over the ring with a stack; returns whether anything went (the
// ring is left as it was when nothing did).
bool clean_pass(std::vector<Vec2>& pts, double noise, CleanupResult& r) {
    std::vector<Vec2> out;
    out.reserve(pts.size());
    bool changed = false;
    auto reduce = [&](std::vector<Vec2>& v) {
        while (v.size() >= 3) {
            double moved = 0.0;
            const Vec2 a = v[v.size() - 3], b = v[v.size() - 2], c = v.back();
            const Removal why = removable(a, b, c, noise, moved);
            if (why == Removal::None) return;
            (why == Removal::Collinear ? r.collinear : r.spike).note(b, moved);
            v.erase(v.end() - 2);
            if (v[v.size() - 2] == v.back()) v.pop_back();  // the spike's base, now twice
            changed = true;
        }
    };
    for (const Vec2& p : pts) {
        out.push_back(p);
        reduce(out);
    }
    // Across the seam: the last two points with the first, and the last with the first two.
    for (int k = 0; k < 2 && out.size() >= 3; ++k) {
        std::rotate(out.begin(), out.begin() + 1, out.end());
        const size_t before = out.size();
        reduce(out);
        if (out.size() != before) k = -1;
    }
    if (changed) pts = std::move(out);
    return changed;
}

struct KeyHash {
    size_t operator()(const ClipperLib::IntPoint& p) const {
        return std::hash<long long>()(p.X) ^ (std::hash<long long>()(p.Y) * 0x9e3779b97f4a7c15ull);
    }
};
struct KeyEq {
    bool operator()(const ClipperLib::IntPoint& a, const ClipperLib::IntPoint& b) const {
        return a.X == b.X && a.Y == b.Y;
    }
};

double extent(std::span<const Vec2> pts) {
    Vec2 lo(1e300), hi(-1e300);
    for (const Vec2& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return pts.empty() ? 0.0 : glm::length(hi - lo);
}

double perimeter(std::span<const Vec2> pts) {
    double sum = 0.0;
    for (size_t i = 0; i < pts.size(); ++i) sum += glm::length(pts[(i + 1) % pts.size()] - pts[i]);
    return sum;
}

// Largest distance from a point of `piece` to the boundary of the kept loops.
double distance_to_kept(std::span<const Vec2> piece, const std::vector<std::vector<Vec2>>& loops,
                        const std::vector<bool>& kept) {
    double worst = 0.0;
    for (const Vec2& p : piece) {
        double best = 1e300;
        for (size_t l = 0; l < loops.size(); ++l) {
            if (!kept[l]) continue;
            const auto& q = loops[l];
            for (size_t i = 0; i < q.size(); ++i)
                best = std::min(best, segment_distance(p, q[i], q[(i + 1) % q.size()]));
        }
        worst = std::max(worst, best);
    }
    return worst;
}

}  // namespace

size_t remove_duplicate_points(std::vector<Vec2>& pts) {
    const size_t before = pts.size();
    std::vector<Vec2> out;
    out.reserve(pts.size());
    for (const Vec2& p : pts)
        if (out.empty() || out.back() != p) out.push_back(p);
    while (out.size() > 1 && out.back() == out.front()) out.pop_back();
    pts = std::move(out);
    return before - pts.size();
}

CleanupResult clean_contour(std::vector<Vec2>& points, double noise) {
    CleanupResult r;
    remove_near_duplicates(points, noise, r.near_duplicate);
    while (points.size() >= 3 && clean_pass(points, noise, r)) {
    }
    return r;
}

RegionUnion union_regions(std::span<const std::vector<Vec2>> loops, double tolerance) {
    using namespace ClipperLib;
    double m = 0.0;
    for (const auto& l : loops)
        for (const Vec2& p : l) m = std::max({m, std::abs(p.x), std::abs(p.y)});
    // A power of two keeps the scaling exact; 2^50 leaves Clipper's 62-bit range room.
    // (The exponent is clamped so tiny or huge coordinates cannot make it overflow.)
    const double scale = m > 0 ? std::exp2(std::clamp(std::floor(50.0 - std::log2(m)), -1000.0, 1000.0)) : 1.0;
    std::unordered_map<IntPoint, Vec2, KeyHash, KeyEq> original;
    Paths paths;
    for (const auto& l : loops) {
        Path path;
        for (const Vec2& p : l) {
            IntPoint q(cInt(std::llround(p.x * scale)), cInt(std::llround(p.y * scale)));
            original.emplace(q, p);
            path.push_back(q);
        }
        paths.push_back(std::move(path));
    }
    Paths out;
    try {
        Clipper clipper;
        clipper.StrictlySimple(true);
        clipper.AddPaths(paths, ptSubject, true);
        clipper.Execute(ctUnion, out, pftNonZero, pftNonZero);
    } catch (const std::exception&) {
        RegionUnion failed;
        failed.ok = false;
        return failed;
    }
    RegionUnion result;
    for (const Path& path : out) {
        std::vector<Vec2> loop;
        for (const IntPoint& q : path) {
            auto it = original.find(q);
            loop.push_back(it != original.end() ? it->second : Vec2(double(q.X) / scale, double(q.Y) / scale));
        }
        if (loop.size() >= 3) result.loops.push_back(std::move(loop));
    }
    // Drop slivers, smallest first, while they stay within the tolerance of what is kept.
    std::vector<size_t> order(result.loops.size());
    std::vector<double> area(result.loops.size());
    for (size_t i = 0; i < order.size(); ++i) {
        order[i] = i;
        area[i] = std::abs(signed_area2(result.loops[i].data(), result.loops[i].size())) / 2;
    }
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return area[a] < area[b]; });
    std::vector<bool> kept(result.loops.size(), true);
    size_t left = kept.size();
    for (size_t i : order) {
        const auto& piece = result.loops[i];
        if (area[i] > tolerance * perimeter(piece)) continue;
        kept[i] = false;
        const double d = left > 1 ? distance_to_kept(piece, result.loops, kept) : extent(piece);
        if (d > tolerance) {
            kept[i] = true;
            continue;
        }
        --left;
        ++result.dropped;
        result.moved = std::max(result.moved, d);
    }
    std::vector<std::vector<Vec2>> keep;
    for (size_t i = 0; i < kept.size(); ++i)
        if (kept[i]) keep.push_back(std::move(result.loops[i]));
    result.loops = std::move(keep);
    // Input points the union swallowed (inside a curl) moved to the boundary.
    if (loops.size() == 1 && !result.loops.empty()) {
        std::unordered_map<IntPoint, bool, KeyHash, KeyEq> present;
        for (const auto& l : result.loops)
            for (const Vec2& p : l)
                present.emplace(IntPoint(cInt(std::llround(p.x * scale)), cInt(std::llround(p.y * scale))), true);
        std::vector<Vec2> gone;
        for (const Vec2& p : loops[0])
            if (!present.count(IntPoint(cInt(std::llround(p.x * scale)), cInt(std::llround(p.y * scale)))))
                gone.push_back(p);
        const std::vector<bool> all(result.loops.size(), true);
        if (!gone.empty()) result.moved = std::max(result.moved, distance_to_kept(gone, result.loops, all));
    }
    return result;
}

double pull_inward(std::vector<Vec2>& loop, const Vec2& point, double step) {
    const size_t n = loop.size();
    const bool ccw = signed_area2(loop.data(), n) > 0;
    double moved = 0.0;
    for (size_t i = 0; i < n; ++i) {
        if (loop[i] != point) continue;
        const Vec2 prev = loop[(i + n - 1) % n], next = loop[(i + 1) % n];
        const Vec2 u = glm::normalize(prev - point), w = glm::normalize(next - point);
        const double turn = (point.x - prev.x) * (next.y - prev.y) - (point.y - prev.y) * (next.x - prev.x);
        Vec2 dir = u + w;
        if (glm::length(dir) < 1e-9)
            dir = ccw ? Vec2(-w.y, w.x) : Vec2(w.y, -w.x);  // straight: the edge's inner normal
        else if ((turn > 0) != ccw)
            dir = -dir;  // reflex vertex: the bisector points outside
        const double d = std::min({step, glm::length(prev - point) / 4, glm::length(next - point) / 4});
        loop[i] = point + glm::normalize(dir) * d;
        moved = std::max(moved, d);
    }
    return moved;
}

}  // namespace body
