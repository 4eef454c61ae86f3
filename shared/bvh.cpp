// Bounding-volume hierarchy over boxes: median split build, bottom-up refit and
// a front-to-back nearest-hit walk (the contract is in bvh.h).
//
// References:
//   T. L. Kay, J. T. Kajiya, "Ray tracing complex scenes", SIGGRAPH 1986 (the
//     slab test of a ray against a box).
//   I. Wald, S. Boulos, P. Shirley, "Ray tracing deformable scenes using
//     dynamic bounding volume hierarchies", ACM TOG 2007 (refitting instead of
//     rebuilding when items move).
#include "shared/bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace body {
namespace {

bool valid(const glm::vec3& lo, const glm::vec3& hi) { return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z; }

// Node `node` covers items[begin, end): its box, then a split or a leaf.
void build_node(Bvh& bvh, size_t node, uint32_t begin, uint32_t end, std::span<const glm::vec3> lo,
                std::span<const glm::vec3> hi) {
    if (end - begin <= kBvhLeaf) {
        bvh.nodes[node].first = begin;
        bvh.nodes[node].count = end - begin;
        return;
    }
    glm::vec3 clo(std::numeric_limits<float>::max()), chi(-std::numeric_limits<float>::max());
    const auto centre = [&](uint32_t i) { return (lo[i] + hi[i]) * 0.5f; };
    for (uint32_t k = begin; k < end; ++k) {
        clo = glm::min(clo, centre(bvh.items[k]));
        chi = glm::max(chi, centre(bvh.items[k]));
    }
    const glm::vec3 ext = chi - clo;
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(bvh.items.begin() + begin, bvh.items.begin() + mid, bvh.items.begin() + end,
                     [&](uint32_t a, uint32_t b) { return centre(a)[axis] < centre(b)[axis]; });
    const size_t left = bvh.nodes.size();
    bvh.nodes.resize(left + 2);
    bvh.nodes[node].first = static_cast<uint32_t>(left);
    bvh.nodes[node].count = 0;
    build_node(bvh, left, begin, mid, lo, hi);
    build_node(bvh, left + 1, mid, end, lo, hi);
}

}  // namespace

void bvh_refit(Bvh& bvh, std::span<const glm::vec3> lo, std::span<const glm::vec3> hi) {
    bvh.item_lo.resize(bvh.items.size());
    bvh.item_hi.resize(bvh.items.size());
    for (size_t k = 0; k < bvh.items.size(); ++k) {
        bvh.item_lo[k] = lo[bvh.items[k]];
        bvh.item_hi[k] = hi[bvh.items[k]];
    }
    // Children come after their parents: walking backwards meets them first.
    for (size_t n = bvh.nodes.size(); n-- > 0;) {
        BvhNode& node = bvh.nodes[n];
        glm::vec3 a(std::numeric_limits<float>::max()), b(-std::numeric_limits<float>::max());
        if (node.count > 0) {
            for (uint32_t k = node.first; k < node.first + node.count; ++k) {
                const uint32_t i = bvh.items[k];
                if (!valid(lo[i], hi[i])) continue;  // emptied since the build: no longer reachable
                a = glm::min(a, lo[i]);
                b = glm::max(b, hi[i]);
            }
        } else {
            for (uint32_t c = node.first; c < node.first + 2; ++c) {
                a = glm::min(a, bvh.nodes[c].lo);
                b = glm::max(b, bvh.nodes[c].hi);
            }
        }
        node.lo = a;  // empty: lo > hi, which no ray enters
        node.hi = b;
    }
}

void bvh_build(Bvh& bvh, std::span<const glm::vec3> lo, std::span<const glm::vec3> hi) {
    bvh.nodes.clear();
    bvh.items.clear();
    for (size_t i = 0; i < lo.size(); ++i) {
        if (valid(lo[i], hi[i])) bvh.items.push_back(static_cast<uint32_t>(i));
    }
    if (bvh.items.empty()) return;
    bvh.nodes.reserve(2 * (bvh.items.size() / kBvhLeaf + 1));
    bvh.nodes.resize(1);
    build_node(bvh, 0, 0, static_cast<uint32_t>(bvh.items.size()), lo, hi);
    bvh_refit(bvh, lo, hi);
}

std::optional<float> ray_box(const Ray& ray, const glm::vec3& inv_direction, const glm::vec3& lo, const glm::vec3& hi) {
    if (!valid(lo, hi)) return std::nullopt;
    float t0 = 0.0f, t1 = std::numeric_limits<float>::max();
    for (int a = 0; a < 3; ++a) {
        if (ray.direction[a] == 0.0f) {  // parallel to the slab: inside it or never
            if (ray.origin[a] < lo[a] || ray.origin[a] > hi[a]) return std::nullopt;
            continue;
        }
        float n = (lo[a] - ray.origin[a]) * inv_direction[a], f = (hi[a] - ray.origin[a]) * inv_direction[a];
        if (n > f) std::swap(n, f);
        t0 = std::max(t0, n);
        t1 = std::min(t1, f);
        if (t0 > t1) return std::nullopt;
    }
    return t0;
}

int bvh_nearest(const Bvh& bvh, const Ray& ray, const BvhHit& hit, float& distance) {
    distance = std::numeric_limits<float>::max();
    if (bvh.nodes.empty()) return -1;
    const glm::vec3 inv = 1.0f / ray.direction;  // inf on a zero component; ray_box skips that axis
    int best = -1;
    struct Entry {
        uint32_t node;
        float t;
    };
    std::vector<Entry> stack;
    stack.reserve(64);
    if (const auto t = ray_box(ray, inv, bvh.nodes[0].lo, bvh.nodes[0].hi)) stack.push_back({0, *t});
    while (!stack.empty()) {
        const Entry e = stack.back();
        stack.pop_back();
        if (e.t > distance) continue;  // entered only past the best hit
        const BvhNode& node = bvh.nodes[e.node];
        if (node.count > 0) {
            // The leaf's items nearest box first, so that a near hit spares the far ones.
            std::pair<float, uint32_t> order[kBvhLeaf];
            uint32_t n = 0;
            for (uint32_t k = node.first; k < node.first + node.count; ++k) {
                const auto enter = ray_box(ray, inv, bvh.item_lo[k], bvh.item_hi[k]);
                if (!enter) continue;
                uint32_t at = n++;  // insertion: a leaf holds at most kBvhLeaf items
                for (; at > 0 && order[at - 1].first > *enter; --at) order[at] = order[at - 1];
                order[at] = {*enter, k};
            }
            for (uint32_t j = 0; j < n && order[j].first <= distance; ++j) {
                const uint32_t k = order[j].second;
                const int item = static_cast<int>(bvh.items[k]);
                const auto t = hit(bvh.items[k]);
                // Ties go to the lower item, as a walk over all items in order would.
                if (t && (*t < distance || (*t == distance && item < best))) distance = *t, best = item;
            }
            continue;
        }
        const auto ta = ray_box(ray, inv, bvh.nodes[node.first].lo, bvh.nodes[node.first].hi);
        const auto tb = ray_box(ray, inv, bvh.nodes[node.first + 1].lo, bvh.nodes[node.first + 1].hi);
        // The nearer child is pushed last, so it is walked first.
        const bool a_first = ta && (!tb || *ta <= *tb);
        if (a_first) {
            if (tb) stack.push_back({node.first + 1, *tb});
            stack.push_back({node.first, *ta});
        } else {
            if (ta) stack.push_back({node.first, *ta});
            if (tb) stack.push_back({node.first + 1, *tb});
        }
    }
    return best;
}

void bvh_entered(const Bvh& bvh, const Ray& ray, float before, const BvhEntered& entered) {
    if (bvh.nodes.empty()) return;
    const glm::vec3 inv = 1.0f / ray.direction;
    const auto reaches = [&](const glm::vec3& lo, const glm::vec3& hi) {
        const auto t = ray_box(ray, inv, lo, hi);
        return t && *t < before ? t : std::nullopt;
    };
    std::vector<uint32_t> stack;
    stack.reserve(64);
    if (reaches(bvh.nodes[0].lo, bvh.nodes[0].hi)) stack.push_back(0);
    while (!stack.empty()) {
        const BvhNode& node = bvh.nodes[stack.back()];
        stack.pop_back();
        if (node.count > 0) {
            for (uint32_t k = node.first; k < node.first + node.count; ++k)
                if (const auto t = reaches(bvh.item_lo[k], bvh.item_hi[k])) entered(bvh.items[k], *t);
            continue;
        }
        for (uint32_t c = node.first; c < node.first + 2; ++c)
            if (reaches(bvh.nodes[c].lo, bvh.nodes[c].hi)) stack.push_back(c);
    }
}

}  // namespace body
