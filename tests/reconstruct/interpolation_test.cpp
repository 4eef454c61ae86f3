// Between-slice interpolation (fairing/slice_interpolation.h) through the
// pipeline: traced points and contour edges stay on the mesh bit for bit, the
// mesh stays a closed outward manifold without self-intersections, and the
// distance to a known smooth surface drops against the linear bands.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <tuple>

#include "builder/contours/validate.h"
#include "builder/fairing/slice_interpolation.h"
#include "builder/pipeline/build_pipeline.h"
#include "builder/slicing/mesh_slicer.h"
#include "shared/obj_io.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

using Key = std::tuple<double, double, double>;
Key key(const Vec3& p) { return {p.x, p.y, p.z}; }

// Every input point is a mesh vertex at exactly its position, and every input
// contour edge is a mesh edge.
void expect_contours_on_mesh(const Mesh& mesh, const ContourStack& stack) {
    std::map<Key, uint32_t> id;
    for (uint32_t v = 0; v < mesh.positions.size(); ++v) id.emplace(key(mesh.positions[v]), v);
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = mesh.indices[t + size_t(e)], b = mesh.indices[t + size_t(e + 1) % 3];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    size_t missing_points = 0, missing_edges = 0;
    for (const Slice& s : stack.slices)
        for (const Contour& c : s.contours)
            for (size_t i = 0; i < c.points.size(); ++i) {
                auto a = id.find(key(Vec3(c.points[i], s.z)));
                auto b = id.find(key(Vec3(c.points[(i + 1) % c.points.size()], s.z)));
                if (a == id.end() || b == id.end()) {
                    ++missing_points;
                    continue;
                }
                missing_edges += !edges.count({std::min(a->second, b->second), std::max(a->second, b->second)});
            }
    EXPECT_EQ(missing_points, 0u);
    EXPECT_EQ(missing_edges, 0u);
}

// Largest |distance| of the mesh's surface (6 x 6 barycentric samples per
// triangle) to a surface given by its signed distance, strictly between zlo and zhi (caps excluded).
double distance_to(const Mesh& mesh, const std::function<double(const Vec3&)>& distance, double zlo, double zhi) {
    return worst_sampled_distance(mesh, distance, [&](const Vec3& p) { return p.z > zlo && p.z < zhi; });
}

// A sheared ellipsoid ((x - shear z) / a)^2 + (y / b)^2 + z^2 = 1 sliced at
// `slices` heights in (-0.9, 0.9), `points` per contour, each contour starting
// at another angle (so the tiling's correspondence is not trivial).
ContourStack ellipsoid_stack(double a, double b, double shear, int slices, int points) {
    StackBuilder sb;
    for (int k = 0; k < slices; ++k) {
        const double z = -0.9 + 1.8 * k / (slices - 1), r = std::sqrt(1 - z * z);
        std::vector<Vec2> ring;
        for (int i = 0; i < points; ++i) {
            const double t = 2 * kPi * (i + 0.37 * k) / points;
            ring.emplace_back(shear * z + a * r * std::cos(t), b * r * std::sin(t));
        }
        sb.slice(z, {ring});
    }
    return sb.stack;
}

// First-order distance to that ellipsoid: F / |grad F|.
std::function<double(const Vec3&)> ellipsoid_distance(double a, double b, double shear) {
    return [=](const Vec3& p) {
        const double u = (p.x - shear * p.z) / a, v = p.y / b;
        const double f = u * u + v * v + p.z * p.z - 1;
        const Vec3 g(2 * u / a, 2 * v / b, 2 * p.z - 2 * u * shear / a);
        return f / glm::length(g);
    };
}

// One structure built with `rings` at most per gap, each band's count chosen
// under `tolerance` (BuildOptions::ring_tolerance).
StructureMesh build_adaptive(const ContourStack& stack, int rings, double tolerance) {
    BuildOptions options;
    options.interpolate = rings;
    options.ring_tolerance = tolerance;
    auto built = build_structures(stack, options, "test");
    EXPECT_TRUE(built.ok()) << (built.ok() ? "" : built.error().message);
    if (!built.ok() || built->size() != 1) return {};
    return std::move(built->front());
}

// The vertices strictly between zlo and zhi that are not on a slice: the points added there.
size_t ring_points(const Mesh& mesh, const ContourStack& stack, double zlo, double zhi) {
    std::set<double> slices;
    for (const Slice& s : stack.slices) slices.insert(s.z);
    size_t n = 0;
    for (const Vec3& p : mesh.positions) n += p.z > zlo && p.z < zhi && !slices.count(p.z);
    return n;
}

TEST(Interpolation, SphereKeepsEveryTracedPointAndHalvesTheError) {
    const ContourStack stack = ellipsoid_stack(1.0, 1.0, 0.0, 10, 128);
    const StructureMesh linear = build_one(stack, 0), smooth = build_one(stack, 4);
    expect_good_structure(smooth, stack, "");
    expect_contours_on_mesh(smooth.mesh, stack);
    EXPECT_EQ(smooth.components, 1u);
    EXPECT_EQ(smooth.genus, 0);
    const double zlo = stack.slices.front().z, zhi = stack.slices.back().z;
    const auto d = ellipsoid_distance(1.0, 1.0, 0.0);
    const double e_linear = distance_to(linear.mesh, d, zlo, zhi), e_smooth = distance_to(smooth.mesh, d, zlo, zhi);
    RecordProperty("linear", std::to_string(e_linear));
    RecordProperty("interpolated", std::to_string(e_smooth));
    EXPECT_LT(e_smooth, 0.5 * e_linear) << "linear " << e_linear << ", interpolated " << e_smooth;
}

TEST(Interpolation, ShearedEllipsoidFollowsTheSlantedSurface) {
    const ContourStack stack = ellipsoid_stack(1.0, 0.6, 0.5, 9, 96);
    const StructureMesh linear = build_one(stack, 0), smooth = build_one(stack, 3);
    expect_good_structure(smooth, stack, "");
    expect_contours_on_mesh(smooth.mesh, stack);
    const double zlo = stack.slices.front().z, zhi = stack.slices.back().z;
    const auto d = ellipsoid_distance(1.0, 0.6, 0.5);
    const double e_linear = distance_to(linear.mesh, d, zlo, zhi), e_smooth = distance_to(smooth.mesh, d, zlo, zhi);
    RecordProperty("linear", std::to_string(e_linear));
    RecordProperty("interpolated", std::to_string(e_smooth));
    EXPECT_LT(e_smooth, 0.5 * e_linear) << "linear " << e_linear << ", interpolated " << e_smooth;
}

TEST(Interpolation, BranchesStayClosedAndKeepTheirContours) {
    StackBuilder sb;
    sb.slice(0.0, {circle(-0.6, 0.0, 0.5, 40), circle(0.6, 0.0, 0.5, 40)})
        .slice(1.0, {circle(-0.6, 0.0, 0.52, 40), circle(0.6, 0.0, 0.52, 40)})
        .slice(2.0, {ellipse(0.0, 0.0, 1.3, 0.6, 0.0, 56)})
        .slice(3.0, {ellipse(0.0, 0.0, 1.1, 0.5, 0.2, 48)})
        .slice(4.0, {circle(-0.4, 0.1, 0.3, 24), circle(0.5, -0.1, 0.35, 24)});
    const StructureMesh linear = build_one(sb.stack, 0), smooth = build_one(sb.stack, 3);
    expect_good_structure(smooth, sb.stack, "");
    expect_contours_on_mesh(smooth.mesh, sb.stack);
    EXPECT_EQ(smooth.components, linear.components);
    EXPECT_EQ(smooth.genus, linear.genus);
    EXPECT_GT(smooth.triangles, linear.triangles);
}

// A box whose square contours carry extra points at other places on each
// slice (so the tiling fans corners to many points): its sides stay flat.
TEST(Interpolation, FlatSidesStayFlat) {
    StackBuilder sb;
    for (int k = 0; k < 6; ++k) {
        const double a = 0.2 + 0.15 * k;  // where the extra points sit along each side
        sb.slice(0.3 * k, {{{-1, -1}, {a - 1, -1}, {1, -1}, {1, a - 1}, {1, 1}, {1 - a, 1}, {-1, 1}, {-1, 1 - a}}});
    }
    const StructureMesh linear = build_one(sb.stack, 0), smooth = build_one(sb.stack, 3);
    expect_good_structure(smooth, sb.stack, "");
    auto off = [](const Mesh& m) {  // largest distance of a vertex between the end slices from the box
        double d = 0.0;
        for (const Vec3& p : m.positions)
            if (p.z > 0.0 && p.z < 1.5) d = std::max(d, std::abs(std::max(std::abs(p.x), std::abs(p.y)) - 1.0));
        return d;
    };
    EXPECT_LE(off(smooth.mesh), off(linear.mesh) + 1e-9) << "linear " << off(linear.mesh);
}

// A cylinder (four equal circles) under a dome of shrinking circles: with a
// ring tolerance the cylinder's rungs, whose curves stay near their chords,
// get no points and the dome's keep some; closed, traced points kept, the error to
// the sphere on the dome as small as with every ring.
TEST(Interpolation, FlatBandsGetFewerRingsThanCurvedOnes) {
    StackBuilder sb;
    for (int k = 0; k < 8; ++k) {
        const double z = double(k), r = k <= 3 ? 1.0 : std::sqrt(1.0 - (z - 3.0) * (z - 3.0) / 20.25);
        std::vector<Vec2> ring;
        for (int i = 0; i < 256; ++i) {
            const double t = 2 * kPi * i / 256;  // points above each other: the cylinder's rungs are its rulings
            ring.emplace_back(r * 4.5 * std::cos(t), r * 4.5 * std::sin(t));
        }
        sb.slice(z, {ring});
    }
    const StructureMesh every = build_adaptive(sb.stack, 3, 0.0), adaptive = build_adaptive(sb.stack, 3, 0.05);
    expect_good_structure(adaptive, sb.stack, "");
    expect_contours_on_mesh(adaptive.mesh, sb.stack);
    EXPECT_TRUE(adaptive.closed_manifold);
    EXPECT_EQ(adaptive.components, 1u);
    EXPECT_GT(ring_points(every.mesh, sb.stack, 0.0, 2.0), 0u);
    EXPECT_EQ(ring_points(adaptive.mesh, sb.stack, 0.0, 2.0), 0u);  // flat: no points
    EXPECT_GT(ring_points(adaptive.mesh, sb.stack, 3.0, 7.0), 0u);  // curved: points kept
    EXPECT_LT(adaptive.triangles, every.triangles);
    // On the dome, the adaptive mesh stays as close to the sphere as with every ring (within 1 % of the radius).
    const auto sphere = [](const Vec3& p) { return glm::length(p - Vec3(0, 0, 3)) - 4.5; };
    const double e_every = distance_to(every.mesh, sphere, 3.0, 7.0);
    const double e_adaptive = distance_to(adaptive.mesh, sphere, 3.0, 7.0);
    EXPECT_LT(e_adaptive, e_every + 0.01 * 4.5) << "every ring " << e_every << ", adaptive " << e_adaptive;
}

// A cylinder whose rings turn half a point spacing per slice: every rung is a
// diagonal, each point's partners above (and below) lie on either side of it.
// Each rung's slope comes from the rung continuing it (a helix of diagonals),
// so the rungs run straight and a small tolerance gives them no points; the
// mean of a point's partners is vertical and would bend every diagonal.
TEST(Interpolation, DiagonalRungsOfATwistedCylinderGetNoPoints) {
    StackBuilder sb;
    for (int k = 0; k < 6; ++k) {
        std::vector<Vec2> ring;
        for (int i = 0; i < 64; ++i) {
            const double t = 2 * kPi * (i + 0.5 * k) / 64;
            ring.emplace_back(std::cos(t), std::sin(t));
        }
        sb.slice(double(k), {ring});
    }
    const StructureMesh every = build_adaptive(sb.stack, 3, 0.0), adaptive = build_adaptive(sb.stack, 3, 0.005);
    expect_good_structure(adaptive, sb.stack, "");
    expect_contours_on_mesh(adaptive.mesh, sb.stack);
    EXPECT_TRUE(adaptive.closed_manifold);
    EXPECT_EQ(ring_points(every.mesh, sb.stack, 0.0, 5.0), 5u * 128u * 3u);  // every rung a diagonal, 3 points each
    EXPECT_EQ(ring_points(adaptive.mesh, sb.stack, 0.0, 5.0), 0u);
}

// The counts from the interpolation itself: the points it adds drop with the
// tolerance, and a tolerance too small to matter gives every rung every ring.
TEST(Interpolation, RingTolerancePointsDropWithTheTolerance) {
    const ContourStack stack = ellipsoid_stack(1.0, 0.8, 0.2, 9, 48);
    const StructureMesh linear = build_one(stack, 0);
    std::vector<double> z;
    for (const Slice& s : stack.slices) z.push_back(s.z);
    auto points = [&](double tolerance) {
        Mesh copy = linear.mesh;
        const InterpolationStats stats = interpolate_between_slices(copy.positions, copy.indices, z, 4, tolerance);
        EXPECT_TRUE(analyze_topology(copy.positions, copy.indices).closed_manifold());
        return std::pair(stats.points, 4 * stats.rungs);
    };
    const auto [every, all] = points(0.0);
    EXPECT_EQ(every, all);
    EXPECT_EQ(points(1e-9).first, all);
    const size_t fine = points(0.002).first, coarse = points(0.05).first;
    EXPECT_LE(coarse, fine);
    EXPECT_LT(coarse, all);
    EXPECT_EQ(points(1.0).first, 0u);  // a tolerance of the whole gap: the ellipsoid's curves need none
}

TEST(Interpolation, NoRingsLeaveTheMeshAsItIs) {
    const ContourStack stack = ellipsoid_stack(1.0, 0.8, 0.2, 6, 32);
    const StructureMesh linear = build_one(stack, 0);
    Mesh copy = linear.mesh;
    const std::vector<double> z = {-0.9, -0.54, -0.18, 0.18, 0.54, 0.9};
    const InterpolationStats stats = interpolate_between_slices(copy.positions, copy.indices, z, 0);
    EXPECT_EQ(stats.rungs, 0u);
    EXPECT_EQ(copy.positions, linear.mesh.positions);
    EXPECT_EQ(copy.indices, linear.mesh.indices);
}

TEST(Interpolation, RingsLieOnPlanesBetweenTheSlices) {
    const ContourStack stack = ellipsoid_stack(1.0, 1.0, 0.3, 5, 24);
    const StructureMesh smooth = build_adaptive(stack, 2, 0.0);  // every rung 2 points
    std::set<double> heights;
    for (const Vec3& p : smooth.mesh.positions)
        if (p.z >= -0.9 && p.z <= 0.9) heights.insert(p.z);
    // 5 slices and 2 rings in each of the 4 gaps; the domes add heights outside.
    EXPECT_EQ(heights.size(), 5u + 4u * 2u);
}

// The glmark2 bunny sliced at uneven spacing, built with 2 rings at most per
// gap under `tolerance`: closed, outward, the same components as the linear
// build, traced points kept, no new crossing.
void expect_sliced_bunny_sound(double tolerance) {
    constexpr const char* kBunny = "/usr/share/glmark2/models/bunny.obj";
    if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << "needs " << kBunny << " (Debian package glmark2-data)";
    auto mesh = read_obj_merged(kBunny);
    ASSERT_TRUE(mesh.ok()) << mesh.error().message;
    const Aabb box = mesh_bounds(mesh->positions);
    std::vector<double> planes(16);
    for (size_t k = 0; k < planes.size(); ++k)
        planes[k] = box.min.z + (box.max.z - box.min.z) * std::pow((double(k) + 0.5) / double(planes.size()), 1.4);
    drop_planes_through_self_intersections(mesh->positions, mesh->indices, 2, planes);
    auto sliced = slice_mesh(mesh->positions, mesh->indices, 2, planes, "bunny");
    ASSERT_TRUE(sliced.ok()) << sliced.error().message;
    ContourStack repaired = *sliced;
    RepairLog log;
    ASSERT_TRUE(validate_contour_stack(repaired, "bunny", RepairOptions{}, log).ok());
    const StructureMesh linear = build_one(*sliced, 0), smooth = build_adaptive(*sliced, 2, tolerance);
    EXPECT_TRUE(smooth.closed_manifold);
    EXPECT_GT(smooth.triangles, linear.triangles);
    EXPECT_GT(smooth.volume, 0.0);
    EXPECT_EQ(smooth.components, linear.components);
    EXPECT_NEAR(smooth.volume, linear.volume, 0.05 * linear.volume);
    expect_contours_on_mesh(smooth.mesh, repaired);
    // No crossing that the linear bands do not have: every triangle of a
    // crossing pair lies within the box of a crossing linear triangle.
    std::vector<std::pair<uint32_t, uint32_t>> linear_pairs, smooth_pairs;
    count_self_intersections(linear.mesh.positions, linear.mesh.indices, 0, &linear_pairs);
    count_self_intersections(smooth.mesh.positions, smooth.mesh.indices, 0, &smooth_pairs);
    std::vector<Aabb> crossing;
    for (const auto& [a, b] : linear_pairs)
        for (uint32_t t : {a, b}) {
            Aabb box;
            for (int c = 0; c < 3; ++c)
                box.extend(linear.mesh.positions[linear.mesh.indices[3 * size_t(t) + size_t(c)]]);
            crossing.push_back(box);
        }
    size_t elsewhere = 0;
    const double slack = 1e-9 * box.extent();
    for (const auto& [a, b] : smooth_pairs)
        for (uint32_t t : {a, b}) {
            bool inside = false;
            for (const Aabb& x : crossing) {
                bool in = true;
                for (int c = 0; c < 3; ++c) {
                    const Vec3& p = smooth.mesh.positions[smooth.mesh.indices[3 * size_t(t) + size_t(c)]];
                    in = in && glm::all(glm::greaterThanEqual(p, x.min - slack)) &&
                         glm::all(glm::lessThanEqual(p, x.max + slack));
                }
                inside = inside || in;
            }
            elsewhere += !inside;
        }
    EXPECT_EQ(elsewhere, 0u) << smooth_pairs.size() << " crossing pairs, linear " << linear_pairs.size();
}

TEST(Interpolation, SlicedBunnyStaysClosedAndKeepsItsContours) { expect_sliced_bunny_sound(0.0); }

TEST(Interpolation, SlicedBunnyWithRingToleranceStaysClosedAndKeepsItsContours) { expect_sliced_bunny_sound(0.05); }

}  // namespace
}  // namespace body
