// The automatic LOD controller under a simulated frame cost: it converges to a
// triangle budget that holds the target, and spends it by tier and screen size.
#include "kiosk/app/lod_controller.h"

#include <gtest/gtest.h>

#include <numeric>

#include "kiosk/scene/model_part.h"

namespace body::kiosk {
namespace {

// A GPU that needs 2 ms plus 8 ms per million triangles.
double cost(size_t triangles) { return 2.0 + 8.0 * static_cast<double>(triangles) * 1e-6; }

size_t sum(const std::vector<size_t>& v) { return std::accumulate(v.begin(), v.end(), size_t{0}); }

TEST(LodController, ConvergesUnderTheTargetOnASceneTooHeavyForIt) {
    LodController lod;
    std::vector<LodModelInput> models(4);
    for (size_t i = 0; i < models.size(); ++i) {
        models[i].full_triangles = 1000000;
        models[i].base_triangles = 5000;
        models[i].screen_radius_px = 100.0f;
    }
    ASSERT_GT(cost(4000000), 16.7);  // full detail would take 34 ms
    std::vector<size_t> counts;
    for (int frame = 0; frame < 30; ++frame) {
        counts = lod.allocate(models);
        lod.report_frame(cost(sum(counts)), sum(counts));
    }
    // Budget = (0.9 * 16.7 - 2) / 8 ms per million = 1,628,750 triangles.
    EXPECT_NEAR(static_cast<double>(lod.budget()), 1628750.0, 2000.0);
    EXPECT_NEAR(static_cast<double>(sum(counts)), 1628750.0, 2000.0);
    EXPECT_LE(cost(sum(counts)), 16.7);
    for (size_t c : counts) EXPECT_NEAR(static_cast<double>(c), 1628750.0 / 4, 600.0);  // equal sizes, equal shares
    EXPECT_NEAR(lod.overhead_ms(), 2.0, 0.01);
    EXPECT_NEAR(lod.ms_per_mtri(), 8.0, 0.01);
}

TEST(LodController, LightScenesGetFullDetail) {
    LodController lod;
    std::vector<LodModelInput> models(2);
    for (auto& m : models) {
        m.full_triangles = 100000;
        m.base_triangles = 1000;
        m.screen_radius_px = 50.0f;
    }
    std::vector<size_t> counts;
    for (int frame = 0; frame < 10; ++frame) {
        counts = lod.allocate(models);
        lod.report_frame(cost(sum(counts)), sum(counts));
    }
    EXPECT_EQ(counts, (std::vector<size_t>{100000, 100000}));
}

TEST(LodController, SpendsBySelectionThenGroupThenScreenArea) {
    LodController lod(LodSettings{16.7, 0.9, 0.5, 10.0, 50000});  // budget (15.03 ms / 10) = 1,503,000
    ASSERT_EQ(lod.budget(), 1503000u);
    std::vector<LodModelInput> m(5);
    for (auto& x : m) {
        x.full_triangles = 1000000;
        x.base_triangles = 1000;
    }
    m[0].tier = 0, m[0].screen_radius_px = 10;   // selected, small on screen
    m[1].tier = 1, m[1].screen_radius_px = 10;   // its group
    m[2].tier = 2, m[2].screen_radius_px = 300;  // big on screen
    m[3].tier = 2, m[3].screen_radius_px = 100;  // a third of the radius: a ninth of the area
    m[4].visible = false;
    const auto c = lod.allocate(m);
    EXPECT_EQ(c[0], 1000000u);  // selection first, in full
    EXPECT_EQ(c[1], 501000u);   // then the group gets the rest: 1,503,000 - 4 bases - 999,000
    EXPECT_EQ(c[2], 1000u);     // nothing left for the others but their base meshes
    EXPECT_EQ(c[3], 1000u);
    EXPECT_EQ(c[4], 0u);
    EXPECT_EQ(sum(c), 1503000u);

    m[0].tier = m[1].tier = 2;  // no selection: by screen area, 9:1
    const auto d = lod.allocate(m);
    EXPECT_EQ(d[2], 1000000u);  // capped at full detail; the rest goes to the others
    EXPECT_GT(d[3], d[0]);
    EXPECT_EQ(d[0], d[1]);
    EXPECT_NEAR(static_cast<double>(sum(d)), 1503000.0, 3.0);
}

TEST(LodController, ManualLevelsAreKeptAndCountAgainstTheBudget) {
    LodController lod(LodSettings{16.7, 0.9, 0.5, 10.0, 50000});
    std::vector<LodModelInput> m(2);
    for (auto& x : m) {
        x.full_triangles = 1000000;
        x.base_triangles = 1000;
        x.screen_radius_px = 100;
    }
    m[0].manual_ratio = 0.3f;
    const auto c = lod.allocate(m);
    EXPECT_EQ(c[0], 300000u);
    EXPECT_EQ(c[1], 1000000u);
    m[0].manual_ratio = 1.0f;
    const auto d = lod.allocate(m);
    EXPECT_EQ(d[0], 1000000u);
    EXPECT_EQ(d[1], 503000u);
}

TEST(LodController, KeepsAFloorWhenTheOverheadAloneMissesTheTarget) {
    LodController lod;
    // A software renderer: 20 ms of fill before any triangle, then 1 ms per 10k.
    auto slow = [](size_t triangles) { return 20.0 + 100.0 * static_cast<double>(triangles) * 1e-6; };
    std::vector<LodModelInput> models(1);
    models[0].full_triangles = 1000000;
    models[0].base_triangles = 4;
    models[0].screen_radius_px = 200;
    std::vector<size_t> counts;
    for (int frame = 0; frame < 20; ++frame) {
        counts = lod.allocate(models);
        lod.report_frame(slow(counts[0]), counts[0]);
    }
    EXPECT_EQ(lod.budget(), lod.settings().min_triangles);
    EXPECT_EQ(counts[0], 50000u);
}

TEST(LodController, TenPercentSteps) {
    EXPECT_FLOAT_EQ(lod_step(1.0f, -1), 0.9f);
    EXPECT_FLOAT_EQ(lod_step(0.9f, -1), 0.8f);
    EXPECT_FLOAT_EQ(lod_step(0.85f, -1), 0.8f);
    EXPECT_FLOAT_EQ(lod_step(0.85f, 1), 0.9f);
    EXPECT_FLOAT_EQ(lod_step(0.1f, -1), 0.1f);
    EXPECT_FLOAT_EQ(lod_step(1.0f, 1), 1.0f);
    EXPECT_FLOAT_EQ(lod_step(0.03f, 1), 0.1f);
}

TEST(Geomorph, BlendsOverAboutOneHundredFiftyMilliseconds) {
    Geomorph g;
    EXPECT_FLOAT_EQ(g.factor(0.0), 1.0f);  // nothing started: the level is final
    g.start(10.0, 100, 200);
    EXPECT_FLOAT_EQ(g.factor(10.0), 0.0f);
    EXPECT_FLOAT_EQ(g.factor(10.075), 0.5f);
    EXPECT_FLOAT_EQ(g.factor(10.15), 1.0f);
    EXPECT_TRUE(g.active(10.1));
    EXPECT_FALSE(g.active(10.2));
    EXPECT_LT(g.factor(10.02), g.factor(10.04));
}

}  // namespace
}  // namespace body::kiosk
