#pragma once
// A bounding-volume hierarchy over axis-aligned boxes, for the nearest hit of
// a ray (the kiosk's picking over thousands of models).
//
// Contract:
// - bvh_build(): `lo[i]`, `hi[i]` are item i's box (lo <= hi per axis; an item
//   with lo > hi on any axis is left out of the tree). Items are split
//   at the median of their centres on the longest axis of the centres' box;
//   leaves hold at most kBvhLeaf items. O(n log n); the tree is the caller's.
// - bvh_refit(): the same items with new boxes (a model moved): the topology is
//   kept and every node's box recomputed bottom up, O(n). The count must match
//   the build's; rebuild when items are added or removed, or when an item left
//   out (empty box) gets a box.
// - bvh_nearest(): the item whose exact hit along `ray` is nearest. `hit(item)`
//   returns the ray distance to the item's surface or nullopt; it is called
//   only for items whose own box (and its leaf's) the ray enters before the
//   best distance so far,
//   children nearer first, so the surface of item i must lie inside its box.
//   Returns the item (-1: none; equal distances: the lowest item) and writes
//   its distance to `distance`.
// - bvh_entered(): every item whose own box the ray enters before `before`,
//   with the distance at which it enters (0 when the origin is inside), in
//   no particular order; for batching many rays by item (the kiosk's pin
//   occlusion: each model walked once for all the rays that reach it).
// - `ray.direction` need not be unit length; distances are in its units.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

constexpr uint32_t kBvhLeaf = 4;

struct BvhNode {
    glm::vec3 lo{0.0f}, hi{0.0f};
    uint32_t first = 0;  // leaf: first of `count` entries of Bvh::items; inner: left child (right = first + 1)
    uint32_t count = 0;  // 0: inner node
};

struct Bvh {
    std::vector<BvhNode> nodes;               // nodes[0] the root; children after their parent
    std::vector<uint32_t> items;              // item indices, grouped by leaf
    std::vector<glm::vec3> item_lo, item_hi;  // their boxes, in the order of `items`
};

void bvh_build(Bvh& bvh, std::span<const glm::vec3> lo, std::span<const glm::vec3> hi);
void bvh_refit(Bvh& bvh, std::span<const glm::vec3> lo, std::span<const glm::vec3> hi);

using BvhHit = std::function<std::optional<float>(uint32_t item)>;
int bvh_nearest(const Bvh& bvh, const Ray& ray, const BvhHit& hit, float& distance);

using BvhEntered = std::function<void(uint32_t item, float enter)>;
void bvh_entered(const Bvh& bvh, const Ray& ray, float before, const BvhEntered& entered);

// The distance at which `ray` enters box [lo, hi] (0 when it starts inside), or nullopt.
std::optional<float> ray_box(const Ray& ray, const glm::vec3& inv_direction, const glm::vec3& lo, const glm::vec3& hi);

}  // namespace body
