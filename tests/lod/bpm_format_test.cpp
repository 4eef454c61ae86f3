// The split predictions of the .bpm format (shared/pm/prediction.h, FORMAT.md
// "Predictions"): the plane through the parent (version 4), the child's normal from
// its faces after the split, the moved parent's prediction (version 7), and what a
// file with or without normals decodes to.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "builder/lod/bpm_writer.h"
#include "builder/lod/simplify.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/draw_order.h"
#include "shared/pm/prediction.h"
#include "shared/pm/progressive_mesh.h"
#include "shared/pm/quantize.h"
#include "tests/lod/lod_test_util.h"

namespace body {
namespace {

// A ring of k vertices around v = (1000, 2000, 3000) on the plane through v with
// normal n (quantized space), counter-clockwise seen from n: q holds v (vertex 0),
// then the ring (vertices 1 .. k).
struct PlaneFan {
    std::vector<uint16_t> q;
    std::vector<uint32_t> ring;
};
PlaneFan plane_fan(uint32_t k, const double n[3], double radius) {
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double z[3] = {n[0] / len, n[1] / len, n[2] / len};
    // Tangents: x = a unit vector orthogonal to z, y = z cross x.
    double x[3] = {z[1], -z[0], 0.0};
    if (std::fabs(z[2]) > 0.9) x[0] = 1.0, x[1] = 0.0, x[2] = -z[0] / z[2];
    const double lx = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (double& c : x) c /= lx;
    const double y[3] = {z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]};
    PlaneFan f;
    f.q = {1000, 2000, 3000};
    for (uint32_t t = 0; t < k; ++t) {
        const double a = 2.0 * M_PI * t / k;
        for (int c = 0; c < 3; ++c)
            f.q.push_back(uint16_t(std::lround(f.q[size_t(c)] + radius * (std::cos(a) * x[c] + std::sin(a) * y[c]))));
        f.ring.push_back(t + 1);
    }
    return f;
}

TEST(BpmFormat, PlaneNormalFollowsTheOctahedralNormal) {
    const int32_t unit[3] = {1, 1, 1};
    int64_t n[3];
    const uint8_t up[2] = {128, 128};  // (u, w) = (1, 1) / 255: about +z
    pm::plane_normal(up, unit, n);
    EXPECT_EQ(n[2], 253);
    EXPECT_EQ(n[0], 1);
    const uint8_t down[2] = {255, 255};  // folded corner: -z
    pm::plane_normal(down, unit, n);
    EXPECT_LT(n[2], -250);
    // The weights scale each axis (object -> quantized space).
    const int32_t w[3] = {256, 128, 1};
    const uint8_t x_axis[2] = {254, 128};  // (u, w, z) = (253, 1, 1)
    pm::plane_normal(x_axis, w, n);
    EXPECT_EQ(n[0], 253 * 256);
    EXPECT_EQ(n[1], 1 * 128);
    EXPECT_EQ(n[2], 1);
}

TEST(BpmFormat, FlatRingPredictsTheAxisAlongTheNormalExactly) {
    // Tilted planes: the coordinate along the dominant axis of any point on the
    // plane is predicted within rounding from the other two.
    const double normals[][3] = {{0, 0, 1}, {0.3, -0.2, 1}, {1, 0.5, 0.2}, {-0.4, -1, 0.3}};
    for (const auto& nd : normals) {
        const PlaneFan f = plane_fan(8, nd, 400.0);
        // The plane's normal as the decoder has it: scaled to integers.
        const int64_t plane[3] = {std::llround(nd[0] * 1000), std::llround(nd[1] * 1000), std::llround(nd[2] * 1000)};
        pm::FanPrediction pred{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        pm::predict_fan(f.q.data(), f.ring.data(), 8, 2, 3, f.q.data(), plane, pred);
        ASSERT_LT(pred.axis, 3u);
        uint32_t a, b;
        pm::plane_axes(pred.axis, a, b);
        EXPECT_NE(a, pred.axis);
        EXPECT_NE(b, pred.axis);
        EXPECT_LT(a, b);
        // The ring lies on the plane (to rounding): the shift of the plane's axis is small.
        EXPECT_LE(pred.axis_shift, 1u) << nd[0] << " " << nd[1] << " " << nd[2];
        for (uint32_t t = 1; t <= 8; ++t) {
            const uint16_t* p = &f.q[t * 3];
            const uint16_t predicted = pm::plane_coordinate(pred, f.q.data(), p, 0, 4);
            EXPECT_NEAR(int(predicted), int(p[pred.axis]), 2) << "ring vertex " << t;
        }
        // Off the plane by the offset: offset / (scale * N_axis) along the axis.
        const uint16_t on = pm::plane_coordinate(pred, f.q.data(), f.q.data(), 0, 4);
        EXPECT_EQ(on, f.q[pred.axis]);
        const int64_t n_axis = plane[pred.axis];
        const uint16_t off = pm::plane_coordinate(pred, f.q.data(), f.q.data(), 4 * 10 * n_axis, 4);
        EXPECT_EQ(int(off), int(f.q[pred.axis]) + 10);
    }
}

TEST(BpmFormat, ParentPredictionIsTheVersion7Blend) {
    // v + (v - c) / 8 + (C_p - v) / 2, rounded by the arithmetic shift of (5 v - c + 4 C_p + 4).
    EXPECT_EQ(pm::parent_position(1000, 900, 1200), 1113);  // 1112.5
    EXPECT_EQ(pm::parent_position(1000, 1000, 1000), 1000);
    EXPECT_EQ(pm::parent_position(1000, 1080, 1000), 990);
    // Below 0 it wraps around like every 16-bit prediction (floor(-96 / 8) = -12).
    EXPECT_EQ(pm::parent_position(0, 100, 0), 65524);
    EXPECT_EQ(pm::parent_position(65535, 65535, 65535), 65535);
}

TEST(BpmFormat, NoPlaneWithoutANormal) {
    const double nd[3] = {0, 0, 1};
    const PlaneFan f = plane_fan(6, nd, 300.0);
    pm::FanPrediction pred{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    pm::predict_fan(f.q.data(), f.ring.data(), 6, 0, 2, f.q.data(), nullptr, pred);
    EXPECT_EQ(pred.axis, 3u);
    const int64_t zero[3] = {0, 0, 0};
    pm::predict_fan(f.q.data(), f.ring.data(), 6, 0, 2, f.q.data(), zero, pred);
    EXPECT_EQ(pred.axis, 3u);
    // The old predictions are unchanged: the child at the midpoint of v and its ring's centroid.
    uint32_t sum[3] = {0, 0, 0};
    for (uint32_t t = 0; t <= 2; ++t)
        for (int c = 0; c < 3; ++c) sum[c] += f.q[(t + 1) * 3 + size_t(c)];
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(int(pred.child[c]), (int(f.q[size_t(c)]) + int(std::lround(sum[c] / 3.0))) / 2, 1);
}

TEST(BpmFormat, ChildNormalIsTheNormalOfItsFacesAfterTheSplit) {
    // The child and its loop on a plane: the predicted octahedral normal is the
    // plane's (the orientation of the fan: counter-clockwise seen from the normal).
    const double normals[][3] = {{0, 0, 1}, {0.5, 0.2, 1}, {-1, 0.3, -0.6}, {0.1, -1, 0.2}};
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};  // a cube: no axis scaling
    int32_t weight[3];
    pm::normal_axis_weights(lo, hi, weight);
    EXPECT_EQ(weight[0], 256);
    EXPECT_EQ(weight[2], 256);
    for (const auto& nd : normals) {
        const PlaneFan f = plane_fan(7, nd, 500.0);
        pm::FanPrediction pred{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        const int64_t plane[3] = {0, 0, 1};
        pm::predict_fan(f.q.data(), f.ring.data(), 7, 5, 3, f.q.data(), plane, pred);
        // The parent stays at v; the child (anywhere: the loop's area does not depend on it).
        uint8_t oct[2];
        pm::predict_normal(pred, f.q.data(), f.q.data(), weight, oct);
        float got[3];
        pm::oct_decode8(oct, got);
        const double len = std::sqrt(nd[0] * nd[0] + nd[1] * nd[1] + nd[2] * nd[2]);
        const double dot = (got[0] * nd[0] + got[1] * nd[1] + got[2] * nd[2]) / len;
        EXPECT_GT(dot, 0.999) << nd[0] << " " << nd[1] << " " << nd[2];
    }
    // A degenerate loop (every vertex at v) gives the neutral code.
    const std::vector<uint16_t> same(3 * 8, 7);
    const uint32_t ring[7] = {1, 2, 3, 4, 5, 6, 7};
    pm::FanPrediction pred{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    pm::predict_fan(same.data(), ring, 7, 0, 3, same.data(), nullptr, pred);
    uint8_t oct[2];
    pm::predict_normal(pred, same.data(), same.data(), weight, oct);
    EXPECT_EQ(oct[0], 128);
    EXPECT_EQ(oct[1], 128);
}

// Full round trips: the decoded normals are the builder's (to 8-bit octahedral
// precision) with the normal predictions, and a file without normals (no plane)
// still decodes every position.
TEST(BpmFormat, NormalsRoundTripThroughTheirPredictions) {
    const Mesh torus = test::bumpy_torus(40, 24);
    lod::LodOptions options;
    auto build = lod::build_progressive_mesh(torus, options);
    ASSERT_TRUE(build.ok());
    auto bytes = lod::encode_bpm(std::vector<Mesh>{torus}, options);
    ASSERT_TRUE(bytes.ok());
    auto pms = pm::read_bpm_bytes(*bytes, "torus.bpm", pm::BpmStream::FaceOrder::Refinement);  // file numbering
    ASSERT_TRUE(pms.ok()) << pms.error().message;
    pm::ProgressiveMesh& m = *(*pms)[0];
    ASSERT_TRUE(m.has_normals());
    ASSERT_EQ(m.max_vertex_count(), build->normals.size());
    for (size_t v = 0; v < build->normals.size(); ++v) {
        const Vec3 n = glm::normalize(build->normals[v]);
        const Vec3f got = m.normal(v);
        ASSERT_GT(double(got.x) * n.x + double(got.y) * n.y + double(got.z) * n.z, 0.999) << "vertex " << v;
    }
}

TEST(BpmFormat, FileWithoutNormalsDecodesEveryPosition) {
    const Mesh torus = test::bumpy_torus(36, 20);
    lod::LodOptions options;
    options.normals = false;
    auto build = lod::build_progressive_mesh(torus, options);
    ASSERT_TRUE(build.ok());
    auto bytes = lod::encode_bpm(std::vector<Mesh>{torus}, options);
    ASSERT_TRUE(bytes.ok());
    auto with = lod::encode_bpm(std::vector<Mesh>{torus}, lod::LodOptions{});
    ASSERT_TRUE(with.ok());
    EXPECT_LT(bytes->size(), with->size());  // no normal values at all
    auto pms = pm::read_bpm_bytes(*bytes, "torus.bpm", pm::BpmStream::FaceOrder::Refinement);  // file numbering
    ASSERT_TRUE(pms.ok()) << pms.error().message;
    pm::ProgressiveMesh& m = *(*pms)[0];
    EXPECT_FALSE(m.has_normals());
    // Each vertex where it appears: the base at level 0, vertex B + j at level j + 1
    // (a position that a later split moves on its grid: position_bound, FORMAT.md v6).
    m.set_level(0);
    const size_t base = m.max_vertex_count() - m.max_level();
    for (size_t v = 0; v < base; ++v)
        ASSERT_LE(glm::length(Vec3(m.position(v)) - build->positions[v]), m.quantization_bound() * 1.01)
            << "vertex " << v;
    size_t coarse = 0;
    for (size_t j = 0; j < m.max_level(); ++j) {
        m.set_level(j + 1);
        const double d = glm::length(Vec3(m.position(base + j)) - build->positions[base + j]);
        ASSERT_LE(d, m.position_bound() * 1.01) << "split " << j;
        coarse += d > m.quantization_bound() * 1.01;
    }
    // The torus's coarse levels do use grids (else this test would not test them).
    EXPECT_GT(coarse, 0u);
}

// Version 7's parent prediction round trip: with every position exact, each split
// puts its parent where the builder moved it (to the quantization), at the level
// right after it, and the torus moves most of its parents.
TEST(BpmFormat, MovedParentsRoundTripThroughTheirPrediction) {
    const Mesh torus = test::bumpy_torus(40, 24);
    for (bool normals : {true, false}) {  // with and without the plane
        lod::LodOptions options;
        options.coarse_intermediate = false;
        options.normals = normals;
        auto build = lod::build_progressive_mesh(torus, options);
        ASSERT_TRUE(build.ok());
        auto bytes = lod::encode_bpm(std::vector<Mesh>{torus}, options);
        ASSERT_TRUE(bytes.ok());
        auto pms = pm::read_bpm_bytes(*bytes, "torus.bpm", pm::BpmStream::FaceOrder::Refinement);  // file numbering
        ASSERT_TRUE(pms.ok()) << pms.error().message;
        pm::ProgressiveMesh& m = *(*pms)[0];
        ASSERT_EQ(m.max_level(), build->splits.size());
        size_t moved = 0;
        for (size_t j = 0; j < build->splits.size(); ++j) {
            const lod::VertexSplit& sp = build->splits[j];
            m.set_level(j + 1);
            ASSERT_LE(glm::length(Vec3(m.position(sp.parent)) - sp.parent_to), m.quantization_bound() * 1.01)
                << "split " << j << (normals ? "" : " (no normals)");
            moved += glm::length(sp.parent_to - sp.parent_from) > 2 * m.quantization_bound();
        }
        EXPECT_GT(moved, build->splits.size() / 2);
    }
}

TEST(BpmFormat, OlderVersionsAreRejectedWithTheirNumber) {
    auto bytes = lod::encode_bpm(std::vector<Mesh>{test::icosphere(2)}, lod::LodOptions{});
    ASSERT_TRUE(bytes.ok());
    for (uint8_t version : {4, 5, 6}) {  // 5: every position exact (no grids); 6: the parent by the child's reflection
        std::vector<uint8_t> old = *bytes;
        old[4] = version;
        old[5] = 0;
        const uint32_t crc = pm::crc32({old.data(), 12});
        std::memcpy(&old[12], &crc, 4);  // little-endian host, as the format
        auto r = pm::read_bpm_bytes(old, "old.bpm");
        ASSERT_FALSE(r.ok());
        EXPECT_EQ(r.error().message, "old.bpm: file header at byte 4: unsupported version " + std::to_string(version));
    }
}

// A level as a sorted list of its triangles, each as its three corner positions
// rotated to start at the smallest (winding kept): equal for the same mesh under
// any vertex and face numbering.
std::vector<std::array<double, 9>> triangle_set(const Mesh& m) {
    std::vector<std::array<double, 9>> out;
    for (size_t f = 0; f < m.indices.size() / 3; ++f) {
        std::array<std::array<double, 3>, 3> c;
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = m.positions[m.indices[f * 3 + size_t(k)]];
            c[size_t(k)] = {p.x, p.y, p.z};
        }
        const size_t r = size_t(std::min_element(c.begin(), c.end()) - c.begin());
        std::array<double, 9> t;
        for (size_t k = 0; k < 3; ++k)
            for (size_t a = 0; a < 3; ++a) t[k * 3 + a] = c[(r + k) % 3][a];
        out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Version 5's split order (split_order.h): every batch boundary is the same mesh as
// in the simplifier's order with its error, errors stay non-increasing, the file
// replays, and the parent numbers cost a fraction of what they did.
TEST(BpmFormat, SplitsInRoundsKeepEveryBatchBoundaryAndShrinkTheParents) {
    const Mesh torus = test::bumpy_torus(60, 40);
    lod::LodOptions by_error;
    by_error.batch_rounds = false;
    auto a = lod::build_progressive_mesh(torus, by_error);
    auto b = lod::build_progressive_mesh(torus, lod::LodOptions{});
    ASSERT_TRUE(a.ok() && b.ok());
    ASSERT_EQ(a->splits.size(), b->splits.size());
    const std::vector<uint32_t> bounds = pm::batch_levels(a->base_vertices, a->splits.size());
    ASSERT_GT(bounds.size(), 3u);
    for (uint32_t level : bounds) {
        EXPECT_EQ(triangle_set(lod::extract_level(*a, level)), triangle_set(lod::extract_level(*b, level)))
            << "level " << level;
        if (level < b->splits.size()) {
            EXPECT_EQ(a->splits[level].error, b->splits[level].error) << "level " << level;
        }
    }
    size_t moved = 0;
    for (size_t j = 0; j < b->splits.size(); ++j) {
        moved += a->splits[j].parent != b->splits[j].parent;
        if (j > 0) {
            EXPECT_LE(b->splits[j].error, b->splits[j - 1].error) << "split " << j;
        }
        EXPECT_GE(b->splits[j].error, a->splits[j].error) << "split " << j;  // never claims less than by error
    }
    EXPECT_GT(moved, b->splits.size() / 2);  // the order did change
    pm::SplitSizes sa, sb;
    auto fa = lod::encode_bpm(std::vector<Mesh>{torus}, by_error, &sa);
    auto fb = lod::encode_bpm(std::vector<Mesh>{torus}, lod::LodOptions{}, &sb);
    ASSERT_TRUE(fa.ok() && fb.ok());
    EXPECT_LT(sb.context_bits[pm::kCtxParentDelta], 0.6 * sa.context_bits[pm::kCtxParentDelta]);
    EXPECT_LT(fb->size(), fa->size());
    // Both decode to their builds' full mesh (the same surface).
    for (const auto* f : {&*fa, &*fb}) {
        auto pms = pm::read_bpm_bytes(*f, "rounds.bpm");
        ASSERT_TRUE(pms.ok()) << pms.error().message;
        pm::ProgressiveMesh& m = *(*pms)[0];
        m.set_level(m.max_level());
        EXPECT_EQ(m.triangle_count(), torus.triangle_count());
    }
}

// A forged file whose first split names a parent that does not exist yet (the SPLT
// section of a later split, whose parent was born after the base, moved in front:
// its parent step is from 0 like every chunk's first) is refused with the section,
// its byte offset and the split.
TEST(BpmFormat, ParentStepPastTheChildIsRefusedWithItsPlace) {
    lod::LodOptions options;
    options.chunk_splits = 1;
    auto build = lod::build_progressive_mesh(test::icosphere(2), options);
    ASSERT_TRUE(build.ok());
    auto bytes = lod::encode_bpm(std::vector<Mesh>{test::icosphere(2)}, options);
    ASSERT_TRUE(bytes.ok());
    size_t k = 1;
    while (k < build->splits.size() && build->splits[k].parent < build->base_vertices) ++k;
    ASSERT_LT(k, build->splits.size());
    // Offsets of the SPLT sections (one split each, in order).
    std::vector<size_t> at;
    for (size_t pos = 16; pos + 12 <= bytes->size();) {
        uint32_t tag, length;
        std::memcpy(&tag, bytes->data() + pos, 4);
        std::memcpy(&length, bytes->data() + pos + 8, 4);
        if (tag == pm::kTagSplits) at.push_back(pos);
        pos += 16 + length;
    }
    ASSERT_EQ(at.size(), build->splits.size());
    std::vector<uint8_t> forged(bytes->begin(), bytes->begin() + ptrdiff_t(at[0]));
    const size_t section = forged.size();
    forged.insert(forged.end(), bytes->begin() + ptrdiff_t(at[k]), bytes->begin() + ptrdiff_t(at[k + 1]));
    std::memset(&forged[section + 12], 0, 4);  // payload's first split: 0
    const uint32_t crc = pm::crc32({forged.data() + section, forged.size() - section - 4});
    std::memcpy(&forged[forged.size() - 4], &crc, 4);
    auto r = pm::read_bpm_bytes(forged, "forged.bpm");
    ASSERT_FALSE(r.ok());
    const std::string expected =
        "forged.bpm: section SPLT of structure 0 at byte " + std::to_string(section) + ": split 0: parent out of range";
    EXPECT_EQ(r.error().message, expected);
}

// `encode_bpm`'s size accounting (bodygen lod --sizes): the fields add up to
// exactly the SPLT sections' bytes, asking for them changes no byte, and the
// per-value estimate (each symbol at its table's cost) is what the rANS coder
// spends to within a small framing rest.
TEST(BpmFormat, SplitSizesAccountForEverySplitSectionByte) {
    const std::vector<Mesh> meshes{test::bumpy_torus(40, 24), test::icosphere(4)};
    lod::LodOptions options;
    options.chunk_splits = 700;
    pm::SplitSizes sizes;
    auto bytes = lod::encode_bpm(meshes, options, &sizes);
    ASSERT_TRUE(bytes.ok());
    auto plain = lod::encode_bpm(meshes, options);
    ASSERT_TRUE(plain.ok());
    EXPECT_EQ(*bytes, *plain);
    // Walk the sections: 16-byte header, then tag, structure, reserved, length, payload, crc.
    size_t split_bytes = 0, sections = 0;
    for (size_t at = 16; at + 12 <= bytes->size();) {
        uint32_t tag, length;
        std::memcpy(&tag, bytes->data() + at, 4);
        std::memcpy(&length, bytes->data() + at + 8, 4);
        if (tag == pm::kTagSplits) {
            split_bytes += 16 + length;
            ++sections;
        }
        at += 16 + length;
    }
    ASSERT_GT(sections, 2u);
    EXPECT_NEAR(sizes.total_bits() / 8, double(split_bytes), 1e-6);
    auto pms = pm::read_bpm_bytes(*bytes, "sizes.bpm");
    ASSERT_TRUE(pms.ok()) << pms.error().message;
    EXPECT_EQ(sizes.splits, (*pms)[0]->max_level() + (*pms)[1]->max_level());
    const double* c = sizes.context_bits;
    EXPECT_GT(c[pm::kCtxParentDelta], 0);
    EXPECT_GT(c[pm::kCtxChild0] + c[pm::kCtxChild0 + 1] + c[pm::kCtxChild0 + 2], 0);
    EXPECT_GT(c[pm::kCtxParent0] + c[pm::kCtxParent0 + 1] + c[pm::kCtxParent0 + 2], 0);
    EXPECT_GT(c[pm::kCtxNormal0] + c[pm::kCtxNormal0 + 1], 0);
    EXPECT_GT(c[pm::kCtxFanStart] + c[pm::kCtxFanLength], 0);
    EXPECT_GT(sizes.table_bits, 0);
    EXPECT_DOUBLE_EQ(sizes.header_bits, 8.0 * 36 * double(sections));
    EXPECT_GE(sizes.framing_bits, 0);
    EXPECT_LT(sizes.framing_bits, 0.02 * sizes.total_bits());
}

// Version 6: positions that a later split moves go on coarser grids. The file
// shrinks, the full level is the same to the bit, and at every level each vertex
// is within position_bound() of where the exact file puts it.
TEST(BpmFormat, IntermediatePositionsOnGridsKeepTheFullLevelExact) {
    const Mesh torus = test::bumpy_torus(48, 24);
    lod::LodOptions exact_options;
    exact_options.coarse_intermediate = false;
    auto exact = lod::encode_bpm(std::vector<Mesh>{torus}, exact_options);
    auto coarse = lod::encode_bpm(std::vector<Mesh>{torus}, lod::LodOptions{});
    ASSERT_TRUE(exact.ok() && coarse.ok());
    EXPECT_LT(coarse->size(), exact->size() * 95 / 100) << coarse->size() << " vs " << exact->size();
    auto a = pm::read_bpm_bytes(*exact, "exact.bpm", pm::BpmStream::FaceOrder::Refinement);
    auto b = pm::read_bpm_bytes(*coarse, "coarse.bpm", pm::BpmStream::FaceOrder::Refinement);
    ASSERT_TRUE(a.ok() && b.ok());
    pm::ProgressiveMesh &ma = *(*a)[0], &mb = *(*b)[0];
    ASSERT_EQ(ma.max_level(), mb.max_level());
    size_t moved = 0;
    for (size_t level = 0; level <= ma.max_level(); level += 1 + level / 8) {
        ma.set_level(level);
        mb.set_level(level);
        EXPECT_FLOAT_EQ(ma.error_at(level), mb.error_at(level));
        EXPECT_LE(ma.position_bound(), mb.position_bound() * 1.0001);
        for (size_t v = 0; v < ma.vertex_count(); ++v) {
            const double d = glm::length(Vec3(ma.position(v)) - Vec3(mb.position(v)));
            // Both within their bounds of the builder's position: the exact one within quantization.
            ASSERT_LE(d, ma.quantization_bound() + mb.position_bound()) << "level " << level << " vertex " << v;
            moved += d > 0;
        }
    }
    EXPECT_GT(moved, 0u);  // some coarse level does show a gridded position
    ma.set_level(ma.max_level());
    mb.set_level(mb.max_level());
    const auto ca = ma.position_codes(), cb = mb.position_codes();
    EXPECT_TRUE(std::equal(ca.begin(), ca.begin() + ptrdiff_t(ma.vertex_count() * 3), cb.begin()));
}

}  // namespace
}  // namespace body
