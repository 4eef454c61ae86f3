#include "builder/caps/dome_groups.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace body {
namespace {

constexpr size_t kMaxDomeGroup = 16;

double cross3(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// The group being grown: its boundary cycle and area-weighted centroid sums.
struct Growing {
    std::vector<uint32_t> cycle;
    Vec2 moment{0.0};
    double area = 0;
    size_t triangles = 0;
    Vec2 first_centroid{0.0};
};

// A lone triangle's apex is its centroid, whatever its area (a flat one the
// flips could not remove included).
Vec2 apex_of(const Growing& g) { return g.triangles == 1 ? g.first_centroid : g.moment / g.area; }

// Every fan triangle (p, q, apex) strictly counter-clockwise: cross > 1e-9
// |q - p| |apex - p|, compared squared (no square roots in the inner loop).
bool star_shaped(std::span<const Vec2> at, const std::vector<uint32_t>& cycle, const Vec2& apex) {
    for (size_t i = 0; i < cycle.size(); ++i) {
        const Vec2 p = at[cycle[i]], q = at[cycle[(i + 1) % cycle.size()]];
        const double c = cross3(p, q, apex);
        if (!(c > 0) || !(c * c > 1e-18 * glm::dot(q - p, q - p) * glm::dot(apex - p, apex - p))) return false;
    }
    return true;
}

// Adds triangle (a, b, c) across one of the cycle's edges; false (cycle
// unchanged) when it shares none, its third vertex is already on the cycle,
// or the union would not be star-shaped around the new centroid. The cycle
// is edited in place and restored on refusal (no allocation per triangle).
bool try_add(std::span<const Vec2> at, Growing& g, uint32_t a, uint32_t b, uint32_t c, double area,
             const Vec2& centroid) {
    const uint32_t tri[3] = {a, b, c};
    const size_t n = g.cycle.size();
    for (int k = 0; k < 3; ++k) {
        const uint32_t u = tri[(k + 1) % 3], v = tri[k], w = tri[(k + 2) % 3];  // cycle edge u -> v, new vertex w
        for (size_t i = 0; i < n; ++i) {
            if (g.cycle[i] != u || g.cycle[(i + 1) % n] != v) continue;
            if (std::find(g.cycle.begin(), g.cycle.end(), w) != g.cycle.end()) return false;
            const Vec2 moment = g.moment + centroid * area;
            const double total = g.area + area;
            if (!(total > 0)) return false;
            g.cycle.insert(g.cycle.begin() + long(i) + 1, w);
            if (!star_shaped(at, g.cycle, moment / total)) {
                g.cycle.erase(g.cycle.begin() + long(i) + 1);
                return false;
            }
            g.moment = moment, g.area = total, ++g.triangles;
            return true;
        }
    }
    return false;
}

}  // namespace

void dome_groups(std::span<const Vec2> at, std::span<const uint32_t> triangles, std::vector<DomeGroup>& groups,
                 std::vector<uint32_t>& cycles) {
    groups.clear();
    cycles.clear();
    const size_t count = triangles.size() / 3;
    const size_t most = std::min(kMaxDomeGroup, std::max<size_t>(1, (count + kDomeSamples - 1) / kDomeSamples));
    Growing g;
    auto close = [&] {
        if (g.cycle.empty()) return;
        groups.push_back({apex_of(g), uint32_t(cycles.size()), uint32_t(g.cycle.size())});
        cycles.insert(cycles.end(), g.cycle.begin(), g.cycle.end());
        g.cycle.clear();  // keeps its capacity for the next group
    };
    for (size_t t = 0; t < count; ++t) {
        const uint32_t a = triangles[3 * t], b = triangles[3 * t + 1], c = triangles[3 * t + 2];
        const Vec2 centroid = (at[a] + at[b] + at[c]) / 3.0;
        const double area = 0.5 * cross3(at[a], at[b], at[c]);
        if (!g.cycle.empty() && g.triangles < most && try_add(at, g, a, b, c, area, centroid)) continue;
        close();
        g.cycle.assign({a, b, c});
        g.moment = centroid * std::max(area, 0.0);
        g.area = std::max(area, 0.0);
        g.triangles = 1;
        g.first_centroid = centroid;
        if (!(area > 0)) close();  // nothing may grow from a flat triangle
    }
    close();
}

void lift_groups(std::span<const DomeGroup> groups, std::span<const uint32_t> cycles, std::span<const uint32_t> ids,
                 const std::function<Vec3(const Vec2&)>& lift, std::vector<Vec3>& positions,
                 const std::function<void(uint32_t, uint32_t, uint32_t)>& emit, std::span<const Vec2> at,
                 double piece) {
    const auto key = [](uint32_t u, uint32_t v) { return (uint64_t(u) << 32) | v; };
    // Chords: directed cycle edges whose reverse is on another cycle. Each
    // chord's inner points, from its lower local id to its higher, are made once.
    std::unordered_set<uint64_t> directed;
    std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> chain;  // (first new vertex, count)
    const bool split = piece > 0 && !at.empty();
    if (split)
        for (const DomeGroup& g : groups)
            for (uint32_t i = 0; i < g.count; ++i)
                directed.insert(key(cycles[g.first + i], cycles[g.first + (i + 1) % g.count]));
    std::vector<uint32_t> along;
    for (const DomeGroup& g : groups) {
        const uint32_t apex = uint32_t(positions.size());
        positions.push_back(lift(g.apex));
        for (uint32_t i = 0; i < g.count; ++i) {
            const uint32_t u = cycles[g.first + i], v = cycles[g.first + (i + 1) % g.count];
            along.assign({ids[u]});
            if (split && directed.count(key(v, u))) {
                const uint32_t lo = std::min(u, v), hi = std::max(u, v);
                auto [it, fresh] = chain.try_emplace(key(lo, hi), uint32_t(positions.size()), 0u);
                if (fresh) {
                    const double length = glm::length(at[hi] - at[lo]);
                    const uint32_t pieces =
                        std::min(kMaxChordPieces, std::max(2u, uint32_t(std::ceil(length / piece))));
                    it->second.second = pieces - 1;
                    for (uint32_t k = 1; k < pieces; ++k)
                        positions.push_back(lift(at[lo] + (at[hi] - at[lo]) * (double(k) / pieces)));
                }
                const auto [first, count] = it->second;
                for (uint32_t k = 0; k < count; ++k) along.push_back(u == lo ? first + k : first + count - 1 - k);
            }
            along.push_back(ids[v]);
            for (size_t k = 0; k + 1 < along.size(); ++k) emit(along[k], along[k + 1], apex);
        }
    }
}

}  // namespace body
