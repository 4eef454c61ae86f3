// ProgressiveMesh::morph_sources (the kiosk's geomorph sources, computed from
// the split records in one pass) against the definition: step the mesh down to
// the coarser level and read where every vertex's ancestor is.
#include <gtest/gtest.h>

#include <random>

#include "builder/lod/bpm_writer.h"
#include "builder/lod/simplify.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "tests/common/test_meshes.h"

namespace body::pm {
namespace {

// Where vertex v (< vertex count at `hi`) is at level `lo` <= hi, by stepping a copy.
std::vector<Vec3f> sources_by_stepping(const ProgressiveMesh& pm, size_t lo, size_t hi) {
    ProgressiveMesh m = pm;
    m.set_level(hi);
    const size_t lo_vc = m.base_vertex_count() + lo, hi_vc = m.vertex_count();
    m.set_level(lo);
    std::vector<Vec3f> at(hi_vc);
    for (size_t v = 0; v < lo_vc; ++v) at[v] = m.position(v);
    for (size_t j = lo; j < hi; ++j) at[m.split_child(j)] = at[m.split_parent(j)];  // parents come first
    return at;
}

// Random pairs of levels the order can draw (every level in refinement order,
// batch boundaries in the batched order, whose batches renumber their vertices).
void check_random_level_pairs(BpmStream::FaceOrder order) {
    lod::LodOptions options;
    options.chunk_splits = 512;
    auto bytes = lod::encode_bpm(std::vector<Mesh>{test::uv_sphere(30, 60)}, options);
    ASSERT_TRUE(bytes) << bytes.error().message;
    auto meshes = read_bpm_bytes(bytes.value(), "sphere.bpm", order);
    ASSERT_TRUE(meshes) << meshes.error().message;
    ProgressiveMesh& pm = *meshes.value()[0];
    ASSERT_GT(pm.max_level(), 1000u);
    std::mt19937 rng(7);
    std::vector<Vec3f> out;
    size_t moved_parents_seen = 0;
    for (int trial = 0; trial < 40; ++trial) {
        size_t lo = pm.drawable_below(rng() % (pm.max_level() + 1)),
               hi = pm.drawable_below(rng() % (pm.max_level() + 1));
        if (lo > hi) std::swap(lo, hi);
        if (trial == 0) lo = 0, hi = pm.max_level();
        const std::vector<Vec3f> want = sources_by_stepping(pm, lo, hi);
        pm.set_level(hi);
        const size_t begin = pm.morph_sources(lo, out);
        ASSERT_EQ(pm.level(), hi);
        ASSERT_LE(begin, pm.base_vertex_count() + lo);
        ASSERT_EQ(out.size(), pm.vertex_count() - begin);
        for (size_t v = 0; v < pm.vertex_count(); ++v) {
            const Vec3f got = v < begin ? pm.position(v) : out[v - begin];
            ASSERT_EQ(got, want[v]) << "vertex " << v << ", levels " << lo << " -> " << hi;
        }
        moved_parents_seen += pm.base_vertex_count() + lo - begin;
    }
    EXPECT_GT(moved_parents_seen, 0u) << "no pair moved an older vertex: the test covers only the easy case";
}

TEST(GeomorphSources, MatchSteppingDownForRandomLevelPairs) {
    check_random_level_pairs(BpmStream::FaceOrder::Refinement);
}

TEST(GeomorphSources, MatchSteppingDownInTheBatchedOrder) { check_random_level_pairs(BpmStream::FaceOrder::Batched); }

}  // namespace
}  // namespace body::pm
