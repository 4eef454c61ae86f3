#pragma once
// Self-intersection count of a triangle mesh.
//
// Contract:
// - `positions` are the vertices, `indices` three per triangle (any
//   orientation); indices must be < positions.size().
// - Returns the number of unordered pairs of triangles that intersect, counting
//   touching as intersecting. Predicates are exact on the positions snapped to
//   a grid of 2^-40 of the mesh's largest dimension (points closer than that
//   step touch). Triangles that share one vertex index count only
//   if they also meet away from that vertex; triangles that share an edge count
//   only if they are coplanar and overlap (a fold). Duplicate triangles (three
//   shared indices) count as intersecting. Degenerate triangles (zero area)
//   are skipped. Adjacency is by index: vertices at equal positions with
//   different indices are not adjacent.
// - Stops once `stop_after` pairs are found (0 = count them all), so the
//   default answers "is there any?".
// - `pairs`, when given, receives the triangle index pairs found (first < second).
// - A uniform grid over the triangles' bounding boxes avoids the quadratic
//   pair search; memory is O(triangles) for typical meshes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "shared/geometry.h"

namespace body {

size_t count_self_intersections(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                size_t stop_after = 1, std::vector<std::pair<uint32_t, uint32_t>>* pairs = nullptr);

// The same count over the pairs of which at least one triangle is marked
// (`marked[t]` != 0; one entry per triangle): e.g. only the triangles that
// moved since a mesh was known to be clean.
size_t count_self_intersections_of(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                   std::span<const uint8_t> marked, size_t stop_after = 1,
                                   std::vector<std::pair<uint32_t, uint32_t>>* pairs = nullptr);

// std::floor(v) as an int, for v within int's range: the truncation, less one
// where it rounded up (a negative fraction). The same value, without the
// instruction sequence std::floor compiles to on baseline x86-64 (grid cells).
inline int floor_int(double v) {
    const int i = int(v);
    return i - int(double(i) > v);
}

// std::llround(v) (halves away from zero), without its library call (the
// snap to the exact predicates' grid): the truncation, moved one step away
// from zero where the remainder is at least a half. The remainder is exact:
// v and its truncation i share their sign and |v - i| < 1, so v - i is exact
// by Sterbenz' lemma, or is v when i = 0. Beyond 2^62 the library answers.
inline int64_t round_half_away(double v) {
    if (!(std::abs(v) < 4611686018427387904.0)) return int64_t(std::llround(v));
    const int64_t i = int64_t(v);
    const double f = v - double(i);
    return i + int64_t(f >= 0.5) - int64_t(f <= -0.5);
}

// The layer of height z among the ascending `cuts`: 0 below the first cut,
// k from cuts[k - 1] (included) to cuts[k] (excluded).
size_t layer_of(std::span<const double> cuts, double z);

// The pairs count_self_intersections_of(positions, indices, marked, 0, &pairs)
// finds, sorted, searched layer by layer along z: `cuts` are ascending
// heights that part the mesh into layers (below the first cut, between
// consecutive ones, above the last). Each layer gets a grid of its own that
// stays in cache; a triangle is listed in every layer its box reaches, so
// cuts where few triangles cross (the slices of a contour stack) pay best.
// Left out: pairs on either side of one cut, one reaching it from below (its
// highest corner on it, its lowest below) and the other at or above it. Those
// can meet only in the cut's plane, where each triangle is the hull of its
// corners on the cut, and none is listed in the layer above a cut it only
// touches from below. The snap grid is the whole mesh's, as for the count.
// `threads` > 1 searches that many layers at a time (layers are independent;
// the sorted pairs are the same for any count).
void self_intersections_by_layer(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                 std::span<const uint8_t> marked, std::span<const double> cuts,
                                 std::vector<std::pair<uint32_t, uint32_t>>& pairs, unsigned threads = 1);

// Whether each given pair of triangles (indices into `indices` / 3) meets,
// by the rules and on the snap grid of count_self_intersections over the same
// mesh (a pair it would count answers 1). For checking a few pairs without
// counting them all.
std::vector<uint8_t> triangle_pairs_meet(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                         std::span<const std::pair<uint32_t, uint32_t>> pairs);

// The pair test on its own: do triangles (a0, a1, a2) and (b0, b1, b2), sharing
// no vertex, intersect (touching included)?
bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                         const Vec3& b2);

}  // namespace body
