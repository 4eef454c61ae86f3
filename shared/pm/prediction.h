#pragma once
// The predictions a vertex split's values are coded against, made the same way
// by the writer and the reader (integer arithmetic: the same bytes everywhere):
// a fan split's child and parent positions from the ring around the parent, the
// plane through the parent along its normal, and the child's normal from its
// faces after the split.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdlib>

namespace body::pm {

// Division by a ring size n (1 .. 65) as a multiplication: x * (floor(2^24 / n) + 1) >> 24
// (x < 2^22: equal to x / n, rarely one more; this is the definition).
struct SmallReciprocals {
    uint32_t r[66];
    constexpr SmallReciprocals() : r{} {
        for (uint32_t n = 1; n < 66; ++n) r[n] = (1u << 24) / n + 1;
    }
};
inline constexpr SmallReciprocals kSmallReciprocals{};
inline uint32_t divide_small(uint32_t x, uint32_t n) { return uint32_t((uint64_t(x) * kSmallReciprocals.r[n]) >> 24); }
inline uint16_t midpoint16(uint32_t a, uint32_t b) { return uint16_t((a + b + 1) / 2); }
inline uint16_t reflect16(uint16_t about, uint16_t x) { return uint16_t(2u * about - x); }

// Predictions of a fan split's positions (quantized), from the positions at the
// level before it (`q`, 3 per vertex; `v` the parent's; ring, k, start, length as
// in SplitReplay::ordered_fan; integer arithmetic, wrap-around 16-bit results):
//   child  = midpoint(v, centroid of ring[start .. start + length])   (its future ring)
//   parent = parent_position(v, child, parent_centroid) (version 7) where
//            parent_centroid = centroid of ring[start + length .. start + k]
//            (both wings, ring[start] and ring[start + length], are in both rings)
//   shift per axis = max(0, bit_width(max - min of the ring) - 5) (version 7; 4
//            before): the low bits of both residuals are about uniform below the
//            ring's extent / 32.
// Version 4 adds a plane through v (when `plane` is given: the parent's normal in
// quantized space, plane_normal): `axis` = its component largest in magnitude (the
// lowest such), 3 when it is 0 or not given (no plane). Along `axis` the surface is
// flat to a fraction of the ring's extent, so that coordinate is coded last,
// predicted from the plane (plane_coordinate) with its own shift
//   axis_shift = max(0, bit_width(max over the ring of |plane . (ring[t] - v)|)
//                       - bit_width(|plane[axis]|) - 3)
// (about the ring's distance from the plane / 8; the parent's one less,
// kParentPlaneShiftLess). child_dot and parent_dot are
// plane . (centroid - v) for the two centroids above (the child's: rounded centroid).
// (A split that is not a fan: child = v, parent = reflection, shift 0, no plane.)
// Version 7 predicts the parent from v and its ring, nearly without the child
// (the reflection about v the versions before used missed by more: bench/RESULTS.md,
// seventeenth session): v + (v - child) / 8 + (parent_centroid - v) / 2, i.e.
// (5 v - child + 4 parent_centroid + 4) >> 3 (arithmetic shift), wrapped to 16 bits.
[[gnu::always_inline]] inline uint16_t parent_position(uint16_t v, uint16_t child, uint16_t parent_centroid) {
    return uint16_t((5 * int32_t(v) - int32_t(child) + 4 * int32_t(parent_centroid) + 4) >> 3);
}
inline constexpr uint32_t kParentPlaneShiftLess = 1;
// centroid of n vertices = divide_small(sum + n / 2, n).
struct FanPrediction {
    uint16_t child[3];
    uint16_t parent_centroid[3];
    uint32_t shift[3];
    int64_t normal[3] = {0, 0, 0};
    uint32_t axis = 3, axis_shift = 0;
    int64_t child_dot = 0, parent_dot = 0;
    int64_t child_area[3] = {0, 0, 0};  // Newell sum of the edges of ring[start .. start + length], about v
    int32_t left[3] = {0, 0, 0}, right[3] = {0, 0, 0};  // ring[start] - v, ring[start + length] - v
};
inline int64_t floor_div(int64_t a, int64_t b) {  // b > 0
    const int64_t q = a / b;
    return q - ((a % b != 0) & (a < 0));
}
// a / b rounded to nearest (halves up), b != 0.
[[gnu::always_inline]] inline int64_t round_div(int64_t a, int64_t b) {
    const int64_t sign = b >> 63;  // 0 or -1: both negated when b < 0, without a branch
    a = (a ^ sign) - sign;
    b = (b ^ sign) - sign;
    const int64_t num = 2 * a + b, den = 2 * b;
    // The same quotient with a 32-bit division when both fit (64-bit ones are slow on some CPUs).
    if (num >= 0 && num < (int64_t(1) << 31) && den < (int64_t(1) << 31)) return int64_t(uint32_t(num) / uint32_t(den));
    return floor_div(num, den);
}
// The plane normal of a vertex from its octahedral normal (8 bits per component):
// (u, w) = 2 oct - 255, z = 255 - |u| - |w|, folded like oct_decode8 when z < 0
// ((255 - |w|) sgn u, (255 - |u|) sgn w, sgn 0 = +1), not normalised; then per
// axis times `weight` (plane_axis_weights) into quantized space.
inline void plane_normal(const uint8_t oct[2], const int32_t weight[3], int64_t out[3]) {
    int32_t u = 2 * int32_t(oct[0]) - 255, w = 2 * int32_t(oct[1]) - 255;
    const int32_t z = 255 - std::abs(u) - std::abs(w);
    if (z < 0) {
        const int32_t fu = (255 - std::abs(w)) * (u < 0 ? -1 : 1), fw = (255 - std::abs(u)) * (w < 0 ? -1 : 1);
        u = fu;
        w = fw;
    }
    out[0] = int64_t(u) * weight[0];
    out[1] = int64_t(w) * weight[1];
    out[2] = int64_t(z) * weight[2];
}
void predict_fan(const uint16_t* q, const uint32_t* ring, uint32_t k, uint32_t start, uint32_t length,
                 const uint16_t v[3], const int64_t* plane, FanPrediction& out);
// The other two axes of pred.axis (< 3), ascending.
inline void plane_axes(uint32_t axis, uint32_t& a, uint32_t& b) {
    // By table: comparisons here compiled to branches that mispredicted.
    static constexpr uint32_t kFirst[3] = {1, 0, 0}, kSecond[3] = {2, 2, 1};
    a = kFirst[axis];
    b = kSecond[axis];
}
// The coordinate along pred.axis (< 3) of the point whose other two coordinates are
// those of `t`, on the plane through v with normal pred.normal moved off it by
// `offset / scale` (offset in units of normal . (x - v)):
//   v[axis] + round_div(offset - scale * (n_a (t_a - v_a) + n_b (t_b - v_b)), scale * n[axis]).
// The child's uses offset = child_dot, scale 4 (a quarter of its centroid's
// distance); the parent's (version 7) offset = 2 parent_dot - 4 normal . (child - v),
// scale 64 (a 32nd of its centroid's distance less a 16th of the child's: the
// parent stays close to the plane through v).
[[gnu::always_inline]] inline uint16_t plane_coordinate(const FanPrediction& pred, const uint16_t v[3],
                                                        const uint16_t t[3], int64_t offset, int64_t scale) {
    uint32_t a, b;
    plane_axes(pred.axis, a, b);
    const int64_t along =
        pred.normal[a] * (int32_t(t[a]) - int32_t(v[a])) + pred.normal[b] * (int32_t(t[b]) - int32_t(v[b]));
    return uint16_t(int64_t(v[pred.axis]) + round_div(offset - scale * along, scale * pred.normal[pred.axis]));
}
inline int64_t plane_dot(const FanPrediction& pred, const uint16_t v[3], const uint16_t t[3]) {
    return pred.normal[0] * (int32_t(t[0]) - int32_t(v[0])) + pred.normal[1] * (int32_t(t[1]) - int32_t(v[1])) +
           pred.normal[2] * (int32_t(t[2]) - int32_t(v[2]));
}
// The moved parent's plane prediction (version 7), one definition for the
// writer and the reader: plane_coordinate(pred, v, t, parent_plane_offset(..),
// kParentPlaneScale) with its shift parent_plane_shift(pred) (comments above).
inline constexpr int64_t kParentPlaneScale = 64;
inline int64_t parent_plane_offset(const FanPrediction& pred, const uint16_t v[3], const uint16_t child[3]) {
    return 2 * pred.parent_dot - 4 * plane_dot(pred, v, child);
}
inline uint32_t parent_plane_shift(const FanPrediction& pred) {
    return pred.axis_shift > kParentPlaneShiftLess ? pred.axis_shift - kParentPlaneShiftLess : 0;
}

// Prediction of a fan split's child normal: the area-weighted normal of the child's
// faces after the split (the closed loop parent_after, ring[start .. start + length]
// around the child; the sum of (loop[i] - c) x (loop[i+1] - c), the same for any
// point in place of c: computed about the parent's position before the split `v`,
// by Newell's method: edge (a, b) adds ((a.y - b.y)(a.z + b.z), (a.z - b.z)(a.x + b.x),
// (a.x - b.x)(a.y + b.y))), taken from quantized to object space by `axis_weight`
// (normal_axis_weights), octahedral-encoded like the writer's normals but in
// integers: with l1 = |x| + |y| + |z|, (u, v) = (x, y) or, when z < 0,
// ((l1 - |y|) sgn x, (l1 - |x|) sgn y) (sgn 0 = +1), each mapped to
// floor((255 (u + l1) + l1) / (2 l1)); a zero normal gives (128, 128).
// Before weighting, the sum is halved (arithmetic shift) until every component is below 2^12.
[[gnu::always_inline]] inline void predict_normal(const FanPrediction& pred, const uint16_t v[3],
                                                  const uint16_t parent_after[3], const int32_t axis_weight[3],
                                                  uint8_t out[2]) {
    // The child ring's edges (predict_fan) closed by right -> parent_after -> left.
    const int64_t p0 = int32_t(parent_after[0]) - int32_t(v[0]), p1 = int32_t(parent_after[1]) - int32_t(v[1]),
                  p2 = int32_t(parent_after[2]) - int32_t(v[2]);
    const int32_t *l = pred.left, *r = pred.right;
    const int64_t n[3] = {pred.child_area[0] + (r[1] - p1) * (r[2] + p2) + (p1 - l[1]) * (p2 + l[2]),
                          pred.child_area[1] + (r[2] - p2) * (r[0] + p0) + (p2 - l[2]) * (p0 + l[0]),
                          pred.child_area[2] + (r[0] - p0) * (r[1] + p1) + (p0 - l[0]) * (p1 + l[1])};
    const uint64_t top = std::max({std::abs(n[0]), std::abs(n[1]), std::abs(n[2])});
    const int scale = std::max(0, int(std::bit_width(top)) - 12);
    // |x|, |y|, |z| < 2^20 (weights <= 256): l1 < 2^22 and the quotients below fit in 32 bits.
    int32_t x = int32_t(n[0] >> scale) * axis_weight[0], y = int32_t(n[1] >> scale) * axis_weight[1],
            z = int32_t(n[2] >> scale) * axis_weight[2];
    const int32_t l1 = std::abs(x) + std::abs(y) + std::abs(z);
    if (l1 == 0) {
        out[0] = out[1] = 128;
        return;
    }
    if (z < 0) {
        const int32_t ox = (l1 - std::abs(y)) * (x < 0 ? -1 : 1), oy = (l1 - std::abs(x)) * (y < 0 ? -1 : 1);
        x = ox;
        y = oy;
    }
    const uint32_t den = 2 * uint32_t(l1);
    out[0] = uint8_t(std::min<uint32_t>((255 * uint32_t(x + l1) + uint32_t(l1)) / den, 255));
    out[1] = uint8_t(std::min<uint32_t>((255 * uint32_t(y + l1) + uint32_t(l1)) / den, 255));
}
// Per axis, the factor taking a normal from quantized to object space: the product
// of the other two extents of the box (hi - lo, in double), scaled so the largest is
// 256 and rounded to nearest, at least 1.
void normal_axis_weights(const float lo[3], const float hi[3], int32_t out[3]);
// Per axis, the factor taking a normal from object to quantized space (plane_normal):
// the extent of the box (hi - lo, in double), scaled so the largest is 256 and
// rounded to nearest, at least 1.
void plane_axis_weights(const float lo[3], const float hi[3], int32_t out[3]);

}  // namespace body::pm
