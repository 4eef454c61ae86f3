// count_self_intersections / triangles_intersect: closed meshes are clean,
// crossings, folds and shared-vertex crossings are found, pairs counted once.
#include "shared/mesh_intersect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "shared/mesh.h"
#include "tests/common/test_meshes.h"

namespace {

using body::Vec3;

using body::test::uv_sphere;

void append(body::Mesh& to, const body::Mesh& from) {
    uint32_t base = uint32_t(to.positions.size());
    to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
    for (uint32_t i : from.indices) to.indices.push_back(base + i);
}

TEST(SnapRounding, RoundHalfAwayMatchesLlround) {
    // Halves (both signs, odd and even integer parts), the doubles next to them,
    // integers, the snap grid's range (up to 2^40) and beyond 2^52, where every double is an integer.
    std::vector<double> values = {0.0,
                                  -0.0,
                                  0.5,
                                  -0.5,
                                  1.5,
                                  -1.5,
                                  2.5,
                                  -2.5,
                                  0.49999999999999994,
                                  -0.49999999999999994,
                                  1099511627776.0,
                                  1099511627775.5,
                                  -1099511627775.5,
                                  4503599627370495.5,
                                  4503599627370497.0,
                                  -4503599627370497.0,
                                  1e17,
                                  -1e17};
    for (double h : {0.5, 2.5, 1e6 + 0.5, 1099511627775.5})
        for (double s : {1.0, -1.0}) {
            values.push_back(std::nextafter(s * h, 0.0));
            values.push_back(std::nextafter(s * h, s * 1e300));
        }
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> spread(-1.2e12, 1.2e12);
    std::uniform_int_distribution<int64_t> whole(-(int64_t(1) << 41), int64_t(1) << 41);
    for (int i = 0; i < 20000; ++i) {
        values.push_back(spread(rng));
        values.push_back(double(whole(rng)) + 0.5);  // exact halves
    }
    for (double v : values) EXPECT_EQ(body::round_half_away(v), int64_t(std::llround(v))) << v;
}

TEST(TrianglesIntersect, PairCases) {
    Vec3 a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);
    EXPECT_TRUE(body::triangles_intersect(a0, a1, a2, {0.2, 0.2, -1}, {0.2, 0.2, 1}, {0.3, 0.9, 0}));    // pierces
    EXPECT_FALSE(body::triangles_intersect(a0, a1, a2, {0.2, 0.2, 0.1}, {0.2, 0.5, 1}, {0.8, 0.2, 1}));  // above
    EXPECT_TRUE(body::triangles_intersect(a0, a1, a2, {0.2, 0.2, 0}, {0.2, 0.5, 1}, {0.8, 0.2, 1}));     // touches
    EXPECT_TRUE(body::triangles_intersect(a0, a1, a2, {0.1, 0.1, 0}, {2, 0.1, 0}, {0.1, 2, 0}));  // coplanar overlap
    EXPECT_FALSE(body::triangles_intersect(a0, a1, a2, {1, 1, 0}, {2, 1, 0}, {1, 2, 0}));         // coplanar apart
    EXPECT_TRUE(body::triangles_intersect(a0, a1, a2, {0.1, 0.1, 0}, {0.2, 0.1, 0}, {0.1, 0.2, 0}));  // inside
}

TEST(SelfIntersections, ClosedSphereIsClean) {
    auto m = uv_sphere(24, 48);
    EXPECT_EQ(body::count_self_intersections(m.positions, m.indices, 0), 0u);
}

TEST(SelfIntersections, OverlappingSpheresAreFoundAndCounted) {
    auto m = uv_sphere(12, 24);
    append(m, uv_sphere(12, 24, Vec3(0.5, 0.1, 0.05)));
    size_t all = body::count_self_intersections(m.positions, m.indices, 0);
    EXPECT_GT(all, 20u);
    EXPECT_EQ(body::count_self_intersections(m.positions, m.indices), 1u);
    EXPECT_EQ(body::count_self_intersections(m.positions, m.indices, 5), 5u);
    // Apart: clean.
    auto apart = uv_sphere(12, 24);
    append(apart, uv_sphere(12, 24, Vec3(2.5, 0, 0)));
    EXPECT_EQ(body::count_self_intersections(apart.positions, apart.indices, 0), 0u);
}

TEST(SelfIntersections, PushedVertexPiercesTheOtherSide) {
    auto m = uv_sphere(16, 32);
    m.positions[0] = {0, 0, -1.5};  // the north pole pulled through the south
    EXPECT_GT(body::count_self_intersections(m.positions, m.indices, 0), 0u);
}

TEST(SelfIntersections, AdjacentTriangles) {
    // Two triangles sharing edge 0-1: flat (clean), folded onto each other (hit).
    std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0.5, 0}};
    std::vector<uint32_t> flat = {0, 1, 2, 1, 0, 3};
    EXPECT_EQ(body::count_self_intersections(p, flat, 0), 0u);
    std::vector<uint32_t> folded = {0, 1, 2, 1, 0, 4};
    EXPECT_EQ(body::count_self_intersections(p, folded, 0), 1u);
    // Sharing vertex 0: a fan that crosses itself, and one that does not.
    std::vector<Vec3> q = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, -0.5}, {0.5, 0.2, 0.5}, {-1, 0, 0.2}};
    std::vector<uint32_t> crossing = {0, 1, 2, 0, 3, 4};
    EXPECT_EQ(body::count_self_intersections(q, crossing, 0), 1u);
    std::vector<uint32_t> apart = {0, 1, 2, 0, 5, 3};
    EXPECT_EQ(body::count_self_intersections(q, apart, 0), 0u);
    // Coplanar fans around a shared vertex: overlapping wedges hit, disjoint do not.
    std::vector<Vec3> r = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {-1, 0.2, 0}, {-0.2, 1, 0}};
    std::vector<uint32_t> overlap = {0, 1, 2, 0, 3, 5};
    EXPECT_EQ(body::count_self_intersections(r, overlap, 0), 1u);
    std::vector<uint32_t> side = {0, 2, 5, 0, 5, 4};
    EXPECT_EQ(body::count_self_intersections(r, side, 0), 0u);
}

// The marked count finds exactly the pairs of the full count that have a
// marked triangle, and the pair query agrees with the full count.
TEST(SelfIntersections, MarkedCountAndPairQueryAgreeWithTheFullCount) {
    body::Mesh m = uv_sphere(12, 24);
    body::Mesh other = uv_sphere(12, 24);
    for (auto& p : other.positions) p += Vec3(0.7, 0.2, 0.1);
    const size_t first_other = m.indices.size() / 3;
    append(m, other);
    std::vector<std::pair<uint32_t, uint32_t>> all, marked_pairs;
    const size_t total = body::count_self_intersections(m.positions, m.indices, 0, &all);
    ASSERT_GT(total, 0u);
    std::vector<uint8_t> marked(m.indices.size() / 3, 0);
    for (size_t t = first_other; t < marked.size(); t += 2) marked[t] = 1;  // every other triangle of the second
    body::count_self_intersections_of(m.positions, m.indices, marked, 0, &marked_pairs);
    std::vector<std::pair<uint32_t, uint32_t>> expected;
    for (auto p : all)
        if (marked[p.first] || marked[p.second]) expected.push_back(p);
    std::sort(expected.begin(), expected.end());
    std::sort(marked_pairs.begin(), marked_pairs.end());
    EXPECT_FALSE(expected.empty());
    EXPECT_LT(expected.size(), all.size());
    EXPECT_EQ(marked_pairs, expected);
    std::vector<std::pair<uint32_t, uint32_t>> asked = all;
    asked.push_back({0, 1});                                   // neighbours on the first sphere
    asked.push_back({0, uint32_t(m.indices.size() / 3 - 1)});  // far apart
    const auto meet = body::triangle_pairs_meet(m.positions, m.indices, asked);
    for (size_t k = 0; k < all.size(); ++k) EXPECT_EQ(meet[k], 1) << k;
    EXPECT_EQ(meet[all.size()], 0);
    EXPECT_EQ(meet[all.size() + 1], 0);
}

// A few triangles of a large vertex array are counted over their corners
// alone: the same pairs as the same triangles copied into their own array.
TEST(SelfIntersections, SubsetOfALargeMeshCountsLikeItsOwnCopy) {
    body::Mesh m = uv_sphere(24, 48);
    body::Mesh other = uv_sphere(12, 24);
    for (auto& p : other.positions) p += Vec3(0.7, 0.2, 0.1);
    const uint32_t first_other = uint32_t(m.indices.size() / 3);
    append(m, other);
    // Every fifth triangle of the first sphere's upper half and every fourth of the second.
    std::vector<uint32_t> subset;
    for (uint32_t t = 0; t < m.indices.size() / 3; ++t)
        if ((t < first_other && t % 5 == 0 && t > first_other / 2) || (t >= first_other && t % 4 == 0))
            subset.insert(subset.end(), &m.indices[3 * size_t(t)], &m.indices[3 * size_t(t)] + 3);
    ASSERT_LT(subset.size(), m.positions.size());  // the subset path
    std::vector<uint32_t> used = subset;
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::vector<Vec3> own_positions;
    for (uint32_t v : used) own_positions.push_back(m.positions[v]);
    std::vector<uint32_t> own;
    for (uint32_t v : subset) own.push_back(uint32_t(std::lower_bound(used.begin(), used.end(), v) - used.begin()));
    ASSERT_GE(own.size(), own_positions.size());  // the whole-array path
    std::vector<std::pair<uint32_t, uint32_t>> fast, slow;
    const size_t n = body::count_self_intersections(m.positions, subset, 0, &fast);
    EXPECT_GT(n, 0u);
    EXPECT_EQ(n, body::count_self_intersections(own_positions, own, 0, &slow));
    std::sort(fast.begin(), fast.end());
    std::sort(slow.begin(), slow.end());
    EXPECT_EQ(fast, slow);
    std::vector<uint8_t> marked(subset.size() / 3, 0);
    for (size_t t = 0; t < marked.size(); t += 2) marked[t] = 1;
    EXPECT_EQ(body::count_self_intersections_of(m.positions, subset, marked, 0),
              body::count_self_intersections_of(own_positions, own, marked, 0));
}

// Whether triangles t1 and t2 lie on either side of one of `cuts`, one
// reaching it from below (highest corner on it, lowest below) and the other at
// or above it: the pairs the layered search leaves out.
bool astride_a_cut(std::span<const Vec3> positions, std::span<const uint32_t> indices, std::span<const double> cuts,
                   uint32_t t1, uint32_t t2) {
    auto low = [&](uint32_t t) {
        return std::min(
            {positions[indices[3 * t]].z, positions[indices[3 * t + 1]].z, positions[indices[3 * t + 2]].z});
    };
    auto high = [&](uint32_t t) {
        return std::max(
            {positions[indices[3 * t]].z, positions[indices[3 * t + 1]].z, positions[indices[3 * t + 2]].z});
    };
    auto below = [&](uint32_t a, uint32_t b) {
        return low(a) < high(a) && std::binary_search(cuts.begin(), cuts.end(), high(a)) && low(b) >= high(a);
    };
    return below(t1, t2) || below(t2, t1);
}

std::vector<std::pair<uint32_t, uint32_t>> not_astride(std::span<const Vec3> positions,
                                                       std::span<const uint32_t> indices, std::span<const double> cuts,
                                                       const std::vector<std::pair<uint32_t, uint32_t>>& pairs) {
    std::vector<std::pair<uint32_t, uint32_t>> out;
    for (const auto& [t1, t2] : pairs)
        if (!astride_a_cut(positions, indices, cuts, t1, t2)) out.push_back({t1, t2});
    return out;
}

// The layered search finds the marked count's pairs, with cuts through the
// sphere's rows (every triangle touches a cut, many touch one only there),
// less the pair that meets only in a cut's plane: adjacent triangles below and
// above it along a shared line. Without cuts it finds them all.
TEST(SelfIntersections, LayeredSearchFindsTheMarkedCountsPairs) {
    body::Mesh m = uv_sphere(12, 24);
    body::Mesh other = uv_sphere(12, 24);
    for (auto& p : other.positions) p += Vec3(0.7, 0.2, 0.1);
    append(m, other);
    // Below z = 3: (0, 1, 2) with its top edge on the plane; above: (0, 3, 4) along
    // the same edge (they meet beyond vertex 0), (0, 5, 6) touching at 0 only.
    const uint32_t v = uint32_t(m.positions.size());
    for (Vec3 p : {Vec3(0, 0, 3), Vec3(1, 0, 3), Vec3(0.5, 0, 2), Vec3(2, 0, 3), Vec3(0.5, 1, 4), Vec3(-1, -1, 3.5),
                   Vec3(-1, 1, 3.5)})
        m.positions.push_back(p + Vec3(3, 0, 0));
    m.indices.insert(m.indices.end(), {v, v + 1, v + 2, v, v + 3, v + 4, v, v + 5, v + 6});
    std::vector<double> cuts;
    for (const Vec3& p : m.positions) cuts.push_back(p.z);
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    std::vector<uint8_t> marked(m.indices.size() / 3, 0);
    for (size_t t = 0; t < marked.size(); t += 3) marked[t] = 1;
    marked[marked.size() - 2] = 1;  // (0, 3, 4)
    std::vector<std::pair<uint32_t, uint32_t>> expected, layered, one_layer;
    body::count_self_intersections_of(m.positions, m.indices, marked, 0, &expected);
    std::sort(expected.begin(), expected.end());
    const uint32_t last = uint32_t(marked.size() - 1);
    ASSERT_TRUE(std::binary_search(expected.begin(), expected.end(), std::pair(last - 2, last - 1)));
    ASSERT_FALSE(std::binary_search(expected.begin(), expected.end(), std::pair(last - 2, last)));
    body::self_intersections_by_layer(m.positions, m.indices, marked, cuts, layered);
    EXPECT_FALSE(std::binary_search(layered.begin(), layered.end(), std::pair(last - 2, last - 1)));
    const auto kept = not_astride(m.positions, m.indices, cuts, expected);
    EXPECT_GT(kept.size(), 20u);
    EXPECT_EQ(layered, kept);
    body::self_intersections_by_layer(m.positions, m.indices, marked, {}, one_layer);
    EXPECT_EQ(one_layer, expected);
}

// A soup of `count` triangles, each of three distinct corners drawn from
// `points` corners (a small pool, so triangles share corners and edges).
std::vector<uint32_t> random_triangles(std::mt19937& rng, uint32_t points, size_t count) {
    std::vector<uint32_t> indices;
    std::uniform_int_distribution<uint32_t> pick(0, points - 1);
    while (indices.size() < 3 * count) {
        const uint32_t a = pick(rng), b = pick(rng), c = pick(rng);
        if (a != b && b != c && a != c) indices.insert(indices.end(), {a, b, c});
    }
    return indices;
}

// Every pair of the soup's triangles that the general pair test says meet, in
// order: all of them, and those with a marked triangle.
struct MeetingPairs {
    std::vector<std::pair<uint32_t, uint32_t>> all, marked;
};
MeetingPairs meeting_pairs(std::span<const Vec3> points, std::span<const uint32_t> indices,
                           std::span<const uint8_t> marked) {
    const uint32_t n = uint32_t(indices.size() / 3);
    std::vector<std::pair<uint32_t, uint32_t>> all;
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = i + 1; j < n; ++j) all.push_back({i, j});
    const std::vector<uint8_t> meet = body::triangle_pairs_meet(points, indices, all);
    MeetingPairs out;
    for (size_t k = 0; k < all.size(); ++k) {
        if (!meet[k]) continue;
        out.all.push_back(all[k]);
        if (marked[all[k].first] || marked[all[k].second]) out.marked.push_back(all[k]);
    }
    return out;
}

// The grid broad phase and its per-cell sweep (shared by the count and the
// layered search) against every pair asked directly: random soups over a small
// point pool (so triangles share corners and edges), points on a few heights
// that double as cuts (so pairs meet in a cut's plane, which the layered
// search leaves out when they lie on either side of it), some marked.
TEST(SelfIntersections, GridSearchesFindEveryPairOfARandomSoup) {
    size_t left_out = 0;
    for (uint32_t seed = 1; seed <= 6; ++seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        const std::vector<double> heights = {0.25, 0.5, 0.75};
        std::vector<Vec3> points;
        for (int i = 0; i < 60; ++i)
            points.push_back({u(rng), u(rng), i % 3 == 0 ? heights[size_t(i / 3) % 3] : u(rng)});
        const std::vector<uint32_t> indices = random_triangles(rng, uint32_t(points.size()), 120);
        const uint32_t n = uint32_t(indices.size() / 3);
        std::vector<uint8_t> marked(n, 0);
        for (uint32_t t = 0; t < n; ++t) marked[t] = u(rng) < 0.3;
        const auto [brute, brute_marked] = meeting_pairs(points, indices, marked);
        ASSERT_GT(brute.size(), 20u) << seed;  // the soup is tangled: the comparison means something
        std::vector<std::pair<uint32_t, uint32_t>> counted, counted_marked, layered;
        EXPECT_EQ(body::count_self_intersections(points, indices, 0, &counted), brute.size()) << seed;
        std::sort(counted.begin(), counted.end());
        EXPECT_EQ(counted, brute) << seed;
        body::count_self_intersections_of(points, indices, marked, 0, &counted_marked);
        std::sort(counted_marked.begin(), counted_marked.end());
        EXPECT_EQ(counted_marked, brute_marked) << seed;
        body::self_intersections_by_layer(points, indices, marked, heights, layered);
        const auto kept = not_astride(points, indices, heights, brute_marked);
        EXPECT_EQ(layered, kept) << seed;
        // Layers searched on several threads, more than the layers too: the same pairs.
        for (unsigned threads : {2u, 3u, 8u}) {
            std::vector<std::pair<uint32_t, uint32_t>> threaded;
            body::self_intersections_by_layer(points, indices, marked, heights, threaded, threads);
            EXPECT_EQ(threaded, kept) << seed << " threads " << threads;
        }
        left_out += brute_marked.size() - kept.size();
    }
    EXPECT_GT(left_out, 0u);  // some pairs meet only in a cut's plane
}

// Pairs on either side of a horizontal plane that both reach (one from below,
// one from above) can meet only in it, where each is a point or an edge; the
// searches decide those in 2-D. Against every pair asked by the general test:
// corners on a coarse x, y lattice and a few shared heights (no cuts), so such
// pairs often cross, overlap along a line, or touch at a point in the plane.
TEST(SelfIntersections, PairsMeetingOnlyInAHorizontalPlaneAreFound) {
    // By hand: below z = 1, (0, 1, 2) with its top edge on the plane; above,
    // (3, 4, 5) with its bottom edge crossing that edge (found), (0, 6, 7)
    // sharing corner 0 with its bottom edge along the same ray (found), and
    // (1, 8, 9) sharing corner 1 with its bottom edge leaving it the other way.
    const std::vector<Vec3> hand = {{0, 0, 1},   {2, 0, 1}, {1, 0.5, 0}, {1.5, -1, 1}, {1.5, 1, 1},
                                    {1.5, 0, 2}, {1, 0, 1}, {0, 1, 2},   {3, 0, 1},    {2, 1, 2}};
    const std::vector<uint32_t> hand_indices = {0, 1, 2, 3, 4, 5, 0, 6, 7, 1, 8, 9};
    std::vector<std::pair<uint32_t, uint32_t>> hand_pairs, hand_layered;
    body::count_self_intersections(hand, hand_indices, 0, &hand_pairs);
    std::sort(hand_pairs.begin(), hand_pairs.end());
    const std::vector<std::pair<uint32_t, uint32_t>> expected = {{0, 1}, {0, 2}};
    EXPECT_EQ(hand_pairs, expected);
    body::self_intersections_by_layer(hand, hand_indices, std::vector<uint8_t>(4, 1), {}, hand_layered);
    EXPECT_EQ(hand_layered, expected);

    size_t in_plane = 0;
    for (uint32_t seed = 1; seed <= 6; ++seed) {
        std::mt19937 rng(seed);
        std::uniform_int_distribution<int> lattice(0, 4), level(0, 3);
        std::vector<Vec3> points;
        for (int i = 0; i < 50; ++i) points.push_back({0.25 * lattice(rng), 0.25 * lattice(rng), 0.25 * level(rng)});
        const std::vector<uint32_t> indices = random_triangles(rng, uint32_t(points.size()), 100);
        const uint32_t n = uint32_t(indices.size() / 3);
        auto height = [&](uint32_t t, bool high) {
            const double z0 = points[indices[3 * t]].z, z1 = points[indices[3 * t + 1]].z,
                         z2 = points[indices[3 * t + 2]].z;
            return high ? std::max({z0, z1, z2}) : std::min({z0, z1, z2});
        };
        std::vector<uint8_t> marked(n, 0);
        for (uint32_t t = 0; t < n; ++t) marked[t] = t % 3 != 0;
        const auto [brute, brute_marked] = meeting_pairs(points, indices, marked);
        for (const auto& [t1, t2] : brute) {
            const bool flat1 = height(t1, false) == height(t1, true), flat2 = height(t2, false) == height(t2, true);
            in_plane +=
                !flat1 && !flat2 && (height(t1, true) == height(t2, false) || height(t2, true) == height(t1, false));
        }
        std::vector<std::pair<uint32_t, uint32_t>> counted, layered;
        body::count_self_intersections(points, indices, 0, &counted);
        std::sort(counted.begin(), counted.end());
        EXPECT_EQ(counted, brute) << seed;
        body::self_intersections_by_layer(points, indices, marked, {}, layered);
        EXPECT_EQ(layered, brute_marked) << seed;
    }
    EXPECT_GT(in_plane, 20u);  // the comparison covers pairs that meet only in a plane
}

}  // namespace
