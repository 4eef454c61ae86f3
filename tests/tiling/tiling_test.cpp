// tile_band: the contract's properties for every method (each contour edge
// used once in the right direction, closed consistently oriented band, no
// fold, outward normals) and minimum area against brute force.
#include "builder/tiling/tiling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "builder/tiling/tiling_internal.h"
#include "shared/mesh_intersect.h"

namespace {

using body::TilingMethod;
using body::Vec3;

std::vector<Vec3> ellipse(size_t n, double a, double b, double z, double cx = 0, double cy = 0, double phase = 0,
                          double rot = 0) {
    std::vector<Vec3> c(n);
    for (size_t k = 0; k < n; ++k) {
        double t = phase + 2 * M_PI * double(k) / double(n);
        double x = a * std::cos(t), y = b * std::sin(t);
        c[k] = {cx + x * std::cos(rot) - y * std::sin(rot), cy + x * std::sin(rot) + y * std::cos(rot), z};
    }
    return c;
}

// A star-shaped contour with `spikes` lobes (non-convex).
std::vector<Vec3> star(size_t n, int spikes, double r0, double r1, double z, double phase = 0) {
    std::vector<Vec3> c(n);
    for (size_t k = 0; k < n; ++k) {
        double t = phase + 2 * M_PI * double(k) / double(n);
        double r = r0 + r1 * std::cos(spikes * t);
        c[k] = {r * std::cos(t), r * std::sin(t), z};
    }
    return c;
}

struct Checked {
    uint32_t folds = 0;
    double area = 0;
};

// Asserts the band contract and returns its fold count and area.
Checked check_band(const std::vector<Vec3>& lower, const std::vector<Vec3>& upper, TilingMethod method) {
    std::vector<uint32_t> tris;
    auto status = body::tile_band(lower, upper, method, tris);
    EXPECT_TRUE(status.ok());
    const uint32_t m = uint32_t(lower.size()), n = uint32_t(upper.size());
    EXPECT_EQ(tris.size(), 3u * (m + n));
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t t = 0; t + 2 < tris.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = tris[t + e], b = tris[t + (e + 1) % 3];
            EXPECT_LT(a, m + n);
            ++directed[{a, b}];
        }
    for (uint32_t i = 0; i < m; ++i) {  // lower edges forward, once
        EXPECT_EQ((directed[{i, (i + 1) % m}]), 1) << "lower edge " << i;
        EXPECT_EQ((directed[{(i + 1) % m, i}]), 0) << "lower edge " << i;
    }
    for (uint32_t j = 0; j < n; ++j) {  // upper edges backward, once
        EXPECT_EQ((directed[{m + (j + 1) % n, m + j}]), 1) << "upper edge " << j;
        EXPECT_EQ((directed[{m + j, m + (j + 1) % n}]), 0) << "upper edge " << j;
    }
    for (auto& [e, count] : directed) {  // every other edge shared by two triangles, opposite ways
        bool contour = (e.first < m && e.second < m) || (e.first >= m && e.second >= m);
        if (contour) continue;
        EXPECT_EQ(count, 1) << e.first << "-" << e.second;
        EXPECT_EQ((directed[{e.second, e.first}]), 1) << e.first << "-" << e.second;
    }
    // The methods emit triangles in path order: recover the cyclic path and
    // charge it with the shared cost (folded corners, area).
    body::tiling_detail::Band band(lower, upper);
    std::vector<uint8_t> moves;
    for (size_t t = 0; t + 2 < tris.size(); t += 3) moves.push_back(tris[t + 1] < m ? 0 : 1);
    body::tiling_detail::CyclicTiling path(band, tris[0], tris[2] - m, moves);
    std::vector<uint32_t> again;
    path.emit(again);
    EXPECT_EQ(again, tris);  // the recovered path is the emitted one
    auto cost = path.total();
    Checked out{cost.folds, cost.area};
    return out;
}

// Pairs of band triangles that cross each other (a fold through the band).
size_t crossings(const std::vector<Vec3>& lower, const std::vector<Vec3>& upper, const std::vector<uint32_t>& tris) {
    std::vector<Vec3> points(lower);
    points.insert(points.end(), upper.begin(), upper.end());
    return body::count_self_intersections(points, tris, 0);
}

class TilingMethods : public ::testing::TestWithParam<TilingMethod> {};

// A pair whose minimum-area tiling (FKU's cost alone) folds: its triangles
// cross each other; so does the minimum of (folded corners, area). The band
// tile_band returns must not.
TEST_P(TilingMethods, NonFoldingChoiceWhereMinimumAreaFolds) {
    const std::vector<Vec3> lower{{2.6, 3.3, 0}, {-1.1, -0.6, 0}, {-3.5, -0.1, 0}, {4.1, -2.1, 0}};
    const std::vector<Vec3> upper{{-4.9, -4.8, 1}, {3.9, -4.0, 1}, {-2.1, -0.4, 1}, {-1.2, -1.2, 1}};
    std::vector<uint32_t> area_only, charged;
    body::tile_optimal(lower, upper, area_only, false);
    body::tile_optimal(lower, upper, charged, true);
    EXPECT_GT(crossings(lower, upper, area_only), 0u);
    EXPECT_GT(crossings(lower, upper, charged), 0u);
    std::vector<uint32_t> tris;
    ASSERT_TRUE(body::tile_band(lower, upper, GetParam(), tris).ok());
    EXPECT_EQ(crossings(lower, upper, tris), 0u);
    check_band(lower, upper, GetParam());  // and still a closed, consistently oriented band
}

// Random jagged pairs: no band crosses itself.
TEST_P(TilingMethods, JaggedBandsDoNotCrossThemselves) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 1000; ++trial) {
        const size_t m = 3 + rng() % 6, n = 3 + rng() % 6;
        // Odd trials: a small upper contour shifted off the centre of a ring-like lower one.
        const bool shifted = trial % 2 == 1;
        std::vector<Vec3> c[2];
        for (int k = 0; k < 2; ++k) {
            const size_t count = k ? n : m;
            const double off = shifted && k ? 6 : 1, r0 = shifted ? (k ? 0.5 : 4) : 1, dr = shifted ? 1 : 5;
            const double phase = 2 * M_PI * u(rng), cx = off * (u(rng) - 0.5), cy = off * (u(rng) - 0.5);
            for (size_t i = 0; i < count; ++i) {
                const double t = phase + 2 * M_PI * (double(i) + 0.8 * u(rng)) / double(count), r = r0 + dr * u(rng);
                c[k].push_back({cx + r * std::cos(t), cy + r * std::sin(t), 0.3 * k});
            }
        }
        std::vector<uint32_t> tris;
        ASSERT_TRUE(body::tile_band(c[0], c[1], GetParam(), tris).ok());
        EXPECT_EQ(crossings(c[0], c[1], tris), 0u) << "trial " << trial;
    }
}

TEST_P(TilingMethods, CylinderIsFaithfulAndOutward) {
    auto lower = ellipse(40, 10, 10, 0), upper = ellipse(40, 10, 10, 1);
    auto r = check_band(lower, upper, GetParam());
    EXPECT_EQ(r.folds, 0u);
    // Every triangle faces radially outward.
    std::vector<uint32_t> tris;
    ASSERT_TRUE(body::tile_band(lower, upper, GetParam(), tris).ok());
    std::vector<Vec3> all(lower);
    all.insert(all.end(), upper.begin(), upper.end());
    for (size_t t = 0; t < tris.size(); t += 3) {
        Vec3 a = all[tris[t]], b = all[tris[t + 1]], c = all[tris[t + 2]];
        Vec3 nrm = glm::cross(b - a, c - a), centre = (a + b + c) / 3.0;
        EXPECT_GT(nrm.x * centre.x + nrm.y * centre.y, 0.0);
    }
    // The straight cylinder's band is the lateral surface of 40 quads.
    EXPECT_NEAR(r.area, 40 * 2 * 10 * std::sin(M_PI / 40) * 1.0, 1e-9);
}

TEST_P(TilingMethods, VeryDifferentCounts) {
    check_band(ellipse(500, 10, 6, 0), ellipse(7, 9, 7, 2), GetParam());
    check_band(ellipse(3, 9, 7, 0), ellipse(300, 10, 6, 2), GetParam());
}

TEST_P(TilingMethods, ShiftedTwistedAndNonConvex) {
    auto r1 = check_band(ellipse(60, 10, 4, 0), ellipse(45, 10, 4, 1, 3, -2, 1.3, 0.7), GetParam());
    EXPECT_EQ(r1.folds, 0u);
    auto r2 = check_band(star(120, 5, 10, 3, 0), star(90, 5, 9, 3.5, 1.5, 0.2), GetParam());
    EXPECT_EQ(r2.folds, 0u);
    check_band(star(200, 7, 10, 4, 0), ellipse(31, 6, 6, 1.0), GetParam());
}

TEST_P(TilingMethods, RejectsBadInput) {
    std::vector<uint32_t> tris;
    std::vector<Vec3> two = {{0, 0, 0}, {1, 0, 0}};
    auto s = body::tile_band(two, ellipse(5, 1, 1, 1), GetParam(), tris);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("lower"), std::string::npos);
    auto bad = ellipse(5, 1, 1, 1);
    bad[3].y = NAN;
    s = body::tile_band(ellipse(5, 1, 1, 0), bad, GetParam(), tris);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("upper contour point 3"), std::string::npos);
}

// Minimum (folds, area) over every closed path, by enumeration (tiny inputs).
// With `manifold`, paths that fan one vertex to the whole other contour (a
// cyclic run of n upper or m lower moves) are excluded.
body::tiling_detail::Cost brute_force(const std::vector<Vec3>& lower, const std::vector<Vec3>& upper, bool manifold,
                                      size_t* optimum_crossings = nullptr) {
    body::tiling_detail::Band band(lower, upper);
    const size_t m = lower.size(), n = upper.size();
    body::tiling_detail::Cost best{~0u, 0};
    for (size_t j0 = 0; j0 < n; ++j0)
        for (uint32_t mask = 0; mask < (1u << (m + n)); ++mask) {
            if (size_t(__builtin_popcount(mask)) != n) continue;  // bit set = upper move
            if (manifold) {
                const size_t total = m + n;
                auto bit = [&](size_t s) { return int((mask >> (s % total)) & 1u); };
                size_t longest[2] = {0, 0};
                for (size_t s = 0; s < total; ++s) {
                    if (bit(s) == bit(s + total - 1)) continue;  // not the start of a run
                    size_t len = 1;
                    while (len < total && bit(s + len) == bit(s)) ++len;
                    longest[bit(s)] = std::max(longest[bit(s)], len);
                }
                if (longest[1] >= n || longest[0] >= m) continue;
            }
            std::vector<uint8_t> moves(m + n);
            for (size_t k = 0; k < m + n; ++k) moves[k] = (mask >> k) & 1;
            const body::tiling_detail::CyclicTiling path(band, 0, uint32_t(j0), moves);
            auto c = path.total();
            if (c < best) {
                best = c;
                if (optimum_crossings) {
                    std::vector<uint32_t> tris;
                    path.emit(tris);
                    *optimum_crossings = crossings(lower, upper, tris);
                }
            }
        }
    return best;
}

std::vector<Vec3> random_contour(std::mt19937& rng, size_t n, double z) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec3> c(n);
    double phase = 2 * M_PI * u(rng), cx = 2 * u(rng) - 1, cy = 2 * u(rng) - 1;
    for (size_t k = 0; k < n; ++k) {
        double t = phase + 2 * M_PI * (double(k) + 0.8 * u(rng)) / double(n), r = 3 + 2 * u(rng);
        c[k] = {cx + r * std::cos(t), cy + r * std::sin(t), z};
    }
    return c;
}

// A smooth random closed curve: a circle of radius ~4 with a few random
// Fourier modes, sampled unevenly.
std::vector<Vec3> smooth_contour(std::mt19937& rng, size_t n, double z) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double amp[4], ph[4];
    for (int f = 0; f < 4; ++f) amp[f] = 0.6 * u(rng) / (f + 1), ph[f] = 2 * M_PI * u(rng);
    double phase = 2 * M_PI * u(rng), cx = u(rng) - 0.5, cy = u(rng) - 0.5;
    std::vector<Vec3> c(n);
    for (size_t k = 0; k < n; ++k) {
        double t = phase + 2 * M_PI * (double(k) + 0.5 * u(rng)) / double(n), r = 4;
        for (int f = 0; f < 4; ++f) r += amp[f] * std::cos((f + 2) * t + ph[f]);
        c[k] = {cx + r * std::cos(t), cy + r * std::sin(t), z};
    }
    return c;
}

// Area alone (no folds): FKU's divide and conquer is exact.
TEST(TilingOptimal, MatchesBruteForceWithoutFolds) {
    std::mt19937 rng(5);
    int repaired = 0, compared = 0;
    for (int trial = 0; trial < 30; ++trial) {
        size_t m = 3 + rng() % 5, n = 3 + rng() % 5;
        auto lower = smooth_contour(rng, m, 0), upper = smooth_contour(rng, n, 1 + 0.5 * (rng() % 3));
        auto expected = brute_force(lower, upper, true), unconstrained = brute_force(lower, upper, false);
        if (expected.folds != 0) continue;
        ++compared;
        auto got = check_band(lower, upper, TilingMethod::Optimal);
        EXPECT_EQ(got.folds, 0u) << "trial " << trial;
        if (!(unconstrained < expected) && !(expected < unconstrained)) {  // the optimum is a manifold band
            EXPECT_NEAR(got.area, expected.area, 1e-9 * expected.area) << "trial " << trial;
        } else {  // repaired by a local flip: no better than the manifold optimum, and close to it
            ++repaired;
            EXPECT_GE(got.area, expected.area * (1 - 1e-9)) << "trial " << trial;
            EXPECT_LE(got.area, expected.area * 1.25) << "trial " << trial;
        }
        auto multi = check_band(lower, upper, TilingMethod::Multires);  // coarse enough to be optimal too
        EXPECT_NEAR(multi.area, got.area, 1e-9 * got.area) << "trial " << trial;
    }
    EXPECT_GT(compared, 20);
    EXPECT_LT(repaired, 8);
}

// Jagged contours: folded corners are unavoidable in places; never more than
// the minimum, and the area stays close to the minimum for that fold count
// (where that minimum's triangles cross each other, a crossing-free band).
TEST(TilingOptimal, JaggedAgainstBruteForce) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 40; ++trial) {
        size_t m = 3 + rng() % 5, n = 3 + rng() % 5;
        auto lower = random_contour(rng, m, 0), upper = random_contour(rng, n, 1 + 0.5 * (rng() % 3));
        size_t optimum_crossings = 0;
        auto expected = brute_force(lower, upper, true, &optimum_crossings);
        for (auto method : {TilingMethod::Optimal, TilingMethod::Multires}) {
            auto got = check_band(lower, upper, method);
            if (optimum_crossings > 0) {  // the optimum folds through itself: the fold check takes another band
                std::vector<uint32_t> tris;
                ASSERT_TRUE(body::tile_band(lower, upper, method, tris).ok());
                EXPECT_EQ(crossings(lower, upper, tris), 0u) << "trial " << trial;
                EXPECT_GE(got.area, expected.area * (1 - 1e-9)) << "trial " << trial;
                continue;
            }
            EXPECT_EQ(got.folds, expected.folds) << "trial " << trial;
            EXPECT_GE(got.area, expected.area * (1 - 1e-9)) << "trial " << trial;
            EXPECT_LE(got.area, expected.area * 1.1) << "trial " << trial;
        }
    }
}

// Multires stays close to the optimum on larger pairs.
TEST(TilingMultires, NearOptimalArea) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 6; ++trial) {
        auto lower = smooth_contour(rng, 100 + rng() % 100, 0), upper = smooth_contour(rng, 60 + rng() % 100, 1.5);
        auto opt = check_band(lower, upper, TilingMethod::Optimal);
        auto multi = check_band(lower, upper, TilingMethod::Multires);
        EXPECT_LE(multi.folds, opt.folds) << "trial " << trial;
        EXPECT_LE(multi.area, opt.area * 1.05) << "trial " << trial;
        std::printf("trial %d: optimal %.4f (%u folds) multires %.4f (%u folds)\n", trial, opt.area,
                    unsigned(opt.folds), multi.area, unsigned(multi.folds));
    }
}

// Jagged pairs large enough to be simplified: multires never ends with more
// folds than the optimal tiling (it falls back to it when a fold is left).
TEST(TilingMultires, JaggedNoMoreFoldsThanOptimal) {
    std::mt19937 rng(13);
    for (int trial = 0; trial < 4; ++trial) {
        auto lower = random_contour(rng, 90 + rng() % 40, 0), upper = random_contour(rng, 70 + rng() % 40, 1.0);
        auto opt = check_band(lower, upper, TilingMethod::Optimal);
        auto multi = check_band(lower, upper, TilingMethod::Multires);
        EXPECT_LE(multi.folds, opt.folds) << "trial " << trial;
    }
}

INSTANTIATE_TEST_SUITE_P(Both, TilingMethods, ::testing::Values(TilingMethod::Optimal, TilingMethod::Multires),
                         [](const auto& info) { return std::string(body::tiling_method_name(info.param)); });

}  // namespace
