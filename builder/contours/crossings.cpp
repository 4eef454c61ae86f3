// Crossings between the edges of closed loops: every edge's bounding box goes
// into a static box tree (median splits on the longer axis), each edge queries
// it for overlapping boxes and the exact test runs on those pairs only. For a
// stack of concentric rings the old sort-on-x sweep tested every pair of edges
// that shared an x interval (all of them near the middle); the tree tests
// O(log n) boxes per edge.
//
// References:
//   M. I. Shamos, D. Hoey, "Geometric intersection problems", FOCS 1976.
//   N. Roussopoulos, D. Leifker, "Direct spatial search on pictorial databases
//     using packed R-trees", SIGMOD 1985 (a static tree of boxes, built once).
#include <algorithm>
#include <map>

#include "builder/contours/validate.h"

namespace body {
namespace {

struct Box {
    double x0, y0, x1, y1;
    bool overlaps(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
    void add(const Box& o) {
        x0 = std::min(x0, o.x0), y0 = std::min(y0, o.y0);
        x1 = std::max(x1, o.x1), y1 = std::max(y1, o.y1);
    }
};

struct Edge {
    Box box;
    uint32_t loop, index;
};

// Node k covers edges [begin, end); children 2k+1, 2k+2 when end - begin > kLeaf.
constexpr size_t kLeaf = 8;

struct Tree {
    std::vector<Edge> edges;
    std::vector<Box> boxes;  // per node
};

void build_node(Tree& t, size_t node, size_t begin, size_t end) {
    if (t.boxes.size() <= node) t.boxes.resize(node + 1);
    Box b = t.edges[begin].box;
    for (size_t i = begin + 1; i < end; ++i) b.add(t.edges[i].box);
    t.boxes[node] = b;
    if (end - begin <= kLeaf) return;
    const bool by_x = b.x1 - b.x0 >= b.y1 - b.y0;
    const size_t mid = begin + (end - begin) / 2;
    auto center = [by_x](const Edge& e) { return by_x ? e.box.x0 + e.box.x1 : e.box.y0 + e.box.y1; };
    std::nth_element(t.edges.begin() + long(begin), t.edges.begin() + long(mid), t.edges.begin() + long(end),
                     [&](const Edge& a, const Edge& c) { return center(a) < center(c); });
    build_node(t, 2 * node + 1, begin, mid);
    build_node(t, 2 * node + 2, mid, end);
}

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

// Intersection (crossing or touching) of segments ab and cd; writes the point
// and whether they cross properly.
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2& at, bool& crosses) {
    double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
    crosses = false;
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
        double t = d1 / (d1 - d2);
        at = a + (b - a) * t;
        crosses = true;
        return true;
    }
    if (d1 == 0 && on_segment(c, d, a)) return at = a, true;
    if (d2 == 0 && on_segment(c, d, b)) return at = b, true;
    if (d3 == 0 && on_segment(a, b, c)) return at = c, true;
    if (d4 == 0 && on_segment(a, b, d)) return at = d, true;
    return false;
}

bool lower(const Vec2& p, const Vec2& q) { return p.x < q.x || (p.x == q.x && p.y < q.y); }

// Whether edges u and v meet where they should not; writes the point.
bool edges_meet(std::span<const std::span<const Vec2>> loops, const Edge& u, const Edge& v, Vec2& at, bool& crosses) {
    crosses = false;
    const auto &lu = loops[u.loop], &lv = loops[v.loop];
    const Vec2 &a = lu[u.index], &b = lu[(u.index + 1) % lu.size()];
    const Vec2 &c = lv[v.index], &d = lv[(v.index + 1) % lv.size()];
    if (u.loop == v.loop) {
        const uint32_t n = uint32_t(lu.size());
        const bool next = (u.index + 1) % n == v.index, prev = (v.index + 1) % n == u.index;
        if (next || prev) {
            // Adjacent edges meet at their shared vertex; they only fail when they fold back.
            const Vec2& shared = next ? b : a;
            const Vec2& other_u = next ? a : b;
            const Vec2& other_v = next ? d : c;
            if (orient(other_u, shared, other_v) == 0 && glm::dot(other_u - shared, other_v - shared) > 0) {
                at = shared;
                return true;
            }
            return false;
        }
    }
    return segments_meet(a, b, c, d, at, crosses);
}

}  // namespace

std::vector<Crossing> find_crossings(std::span<const std::span<const Vec2>> loops) {
    Tree t;
    for (uint32_t l = 0; l < loops.size(); ++l) {
        const auto& pts = loops[l];
        for (uint32_t i = 0; i < pts.size(); ++i) {
            const Vec2 &a = pts[i], &b = pts[(i + 1) % pts.size()];
            t.edges.push_back({{std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y)}, l, i});
        }
    }
    std::map<std::pair<size_t, size_t>, Crossing> found;
    if (t.edges.empty()) return {};
    build_node(t, 0, 0, t.edges.size());
    // Edge order after the build is the tree's; a pair is tested once, from the
    // edge with the lower position in that order.
    struct Visit {
        size_t node, begin, end;
    };
    std::vector<Visit> todo;
    for (size_t s = 0; s < t.edges.size(); ++s) {
        const Edge& u = t.edges[s];
        todo.assign(1, Visit{0, 0, t.edges.size()});
        while (!todo.empty()) {
            const auto [node, begin, end] = todo.back();
            todo.pop_back();
            if (end <= s + 1 || !t.boxes[node].overlaps(u.box)) continue;
            if (end - begin > kLeaf) {
                const size_t mid = begin + (end - begin) / 2;
                todo.push_back({2 * node + 1, begin, mid});
                todo.push_back({2 * node + 2, mid, end});
                continue;
            }
            for (size_t k = std::max(begin, s + 1); k < end; ++k) {
                const Edge& v = t.edges[k];
                Vec2 at;
                bool crosses = false;
                if (!v.box.overlaps(u.box) || !edges_meet(loops, u, v, at, crosses)) continue;
                const std::pair<size_t, size_t> key{std::min(u.loop, v.loop), std::max(u.loop, v.loop)};
                auto [it, inserted] = found.emplace(key, Crossing{true, key.first, key.second, at, crosses});
                if (!inserted && lower(at, it->second.point)) it->second.point = at;
                it->second.crosses |= crosses;
            }
        }
    }
    std::vector<Crossing> out;
    for (const auto& [key, x] : found) out.push_back(x);
    return out;
}

Crossing find_crossing(std::span<const std::span<const Vec2>> loops) {
    auto all = find_crossings(loops);
    return all.empty() ? Crossing{} : all.front();
}

}  // namespace body
