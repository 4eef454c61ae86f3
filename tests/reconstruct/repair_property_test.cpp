// Property test: stacks sliced from a real mesh (the glmark2 bunny) along the
// three axes, evenly and unevenly, with every point jittered and twisted
// zig-zags inserted, all build (no refusal) into closed, outward 2-manifolds,
// and every input point lies within the repair tolerance of the repaired
// contours. (Self-intersection and re-slicing are not asserted here: at 12
// planes the builder's branches on the bunny cross themselves even without
// any repair; see the notes of issue 23.) Kept small: it runs with the unit tests.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "builder/contours/validate.h"
#include "builder/pipeline/build_pipeline.h"
#include "builder/slicing/mesh_slicer.h"
#include "shared/obj_io.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

constexpr const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

// Jitter of `jitter` x extent on every point; `zigzags` contours get a twist
// 0.1-0.8 x the default repair tolerance wide in one edge.
void perturb(ContourStack& stack, double extent, double jitter, int zigzags, std::mt19937& rng) {
    const double tolerance = repair_tolerance(stack, RepairOptions{});
    std::uniform_real_distribution<double> unit(-1.0, 1.0), width(0.1 * tolerance, 0.8 * tolerance);
    std::vector<Contour*> all;
    for (Slice& s : stack.slices)
        for (Contour& c : s.contours) {
            for (Vec2& p : c.points) p += Vec2(unit(rng), unit(rng)) * (jitter * extent);
            if (c.points.size() >= 8) all.push_back(&c);
        }
    for (int k = 0; k < zigzags && !all.empty(); ++k) {
        auto& pts = all[size_t(rng() % all.size())]->points;
        const size_t i = size_t(rng() % pts.size());
        const Vec2 a = pts[i], b = pts[(i + 1) % pts.size()], d = b - a;
        const Vec2 n = Vec2(-d.y, d.x) / std::max(glm::length(d), 1e-300);
        const double w = width(rng);
        pts.insert(pts.begin() + long(i) + 1, {a + d * 0.6, a + d * 0.4 + n * w, a + d * 0.4 - n * w});
    }
}

TEST(RepairProperty, SlicedBunnyWithJitterAndZigZagsBuildsClosed) {
    if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << "needs " << kBunny << " (Debian package glmark2-data)";
    auto mesh = read_obj_merged(kBunny);
    ASSERT_TRUE(mesh.ok()) << mesh.error().message;
    const Aabb box = mesh_bounds(mesh->positions);
    std::mt19937 rng(23);
    for (int axis = 0; axis < 3; ++axis) {
        for (bool uneven : {false, true}) {
            SCOPED_TRACE("axis " + std::to_string(axis) + (uneven ? " uneven" : " even"));
            std::vector<double> planes = evenly_spaced_planes(box.min[axis], box.max[axis], 12);
            if (uneven)  // spacing varying by a factor of about three
                for (size_t k = 0; k < planes.size(); ++k)
                    planes[k] = box.min[axis] + (box.max[axis] - box.min[axis]) *
                                                    std::pow((double(k) + 0.5) / double(planes.size()), 1.6);
            auto sliced = slice_mesh(mesh->positions, mesh->indices, axis, planes);
            ASSERT_TRUE(sliced.ok()) << sliced.error().message;
            ContourStack stack = std::move(*sliced);
            perturb(stack, box.extent(), 2e-5, 4, rng);
            ContourStack repaired = stack;
            RepairLog log;
            auto valid = validate_contour_stack(repaired, "bunny", RepairOptions{}, log);
            ASSERT_TRUE(valid.ok()) << valid.error().message;
            EXPECT_GE(log.counts["self_intersection"] + log.counts["overlap"], 1u);
            const double tolerance = repair_tolerance(stack, RepairOptions{});
            for (size_t k = 0; k < stack.slices.size(); ++k) {
                double worst = 0.0;
                for (const Contour& c : stack.slices[k].contours)
                    for (const Vec2& p : c.points) {
                        double d = 1e300;
                        for (const Contour& r : repaired.slices[k].contours)
                            d = std::min(d, distance_to_loop(p, r.points));
                        worst = std::max(worst, d);
                    }
                EXPECT_LE(worst, tolerance) << "slice " << k;
            }
            auto built = build_structures(stack, BuildOptions{}, "bunny");
            ASSERT_TRUE(built.ok()) << built.error().message;
            for (const StructureMesh& s : *built) {
                EXPECT_TRUE(s.closed_manifold) << s.id;
                EXPECT_GT(s.volume, 0.0) << s.id;
            }
        }
    }
}

}  // namespace
}  // namespace body
