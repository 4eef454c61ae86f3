// What a progressive mesh keeps (the memory contract of progressive_mesh.h and
// split_replay.h): the connectivity replay holds the vertices that arrived, not
// the file's full detail; a complete structure keeps its split records, codes
// and index array within fixed bytes per split, vertex and triangle, and less
// once it hands its arrays to a renderer. Sizes only, no timing.
#include <gtest/gtest.h>

#include <vector>

#include "builder/lod/bpm_writer.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "shared/pm/split_replay.h"
#include "tests/lod/lod_test_util.h"

namespace body {
namespace {

TEST(PmMemory, ReplayHoldsTheVerticesThatArrivedNotItsCapacity) {
    pm::SplitReplay replay;
    replay.reset(200000, 400000);  // a file's full detail, announced by its INFO
    EXPECT_EQ(replay.vertices_held(), 0u);
    const std::vector<uint32_t> tetra = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};
    replay.add_faces(0, tetra);
    EXPECT_GE(replay.vertices_held(), 4u);
    EXPECT_LE(replay.vertices_held(), 64u) << "a base of 4 vertices";
    std::vector<uint32_t> corners, scratch, moved;
    replay.corners_of(3, corners);
    EXPECT_EQ(corners, (std::vector<uint32_t>{5, 7, 10}));
    // Splits that move no corner still give each child its (empty) region.
    for (uint32_t child = 4; child < 1000; ++child) ASSERT_TRUE(replay.apply_mask(0, child, 0, scratch, moved));
    EXPECT_GE(replay.vertices_held(), 1000u);
    EXPECT_LE(replay.vertices_held(), 2000u) << "grown geometrically with the arrivals, not to the capacity";
    replay.corners_of(999, corners);
    EXPECT_TRUE(corners.empty());
    replay.corners_of(150000, corners);  // not arrived: no corners, nothing read out of bounds
    EXPECT_TRUE(corners.empty());
    replay.corners_of(0, corners);
    EXPECT_EQ(corners, (std::vector<uint32_t>{0, 3, 6}));
}

TEST(PmMemory, CompleteStructureKeepsBoundedBytesPerSplitAndLessOnceHandedOver) {
    const std::vector<Mesh> meshes = {test::icosphere(5)};
    auto bytes = lod::encode_bpm(meshes, {});
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    auto read = pm::read_bpm_bytes(*bytes, "sphere.bpm");
    ASSERT_TRUE(read.ok()) << read.error().message;
    pm::ProgressiveMesh& m = *read->front();
    ASSERT_EQ(m.available_level(), m.max_level());
    const size_t splits = m.max_level(), vertices = m.max_vertex_count(), triangles = m.max_triangle_count();
    ASSERT_GT(splits, 5000u);
    // Split records (parent, patches, moves, counts) at most 40 bytes a split,
    // codes 8 a vertex, the index array 12 a triangle: no decoding state left
    // (the replay alone would add over 40 bytes a vertex).
    const size_t records = 40 * splits + 4096;
    EXPECT_LE(m.heap_bytes(), records + 8 * vertices + 12 * triangles);
    const size_t with_arrays = m.heap_bytes();
    ASSERT_TRUE(m.release_indices());
    EXPECT_LE(m.heap_bytes() + 12 * triangles, with_arrays) << "the index array is freed";
    ASSERT_TRUE(m.release_vertex_data());
    EXPECT_LE(m.heap_bytes(), records) << "codes freed: the split records are what is left";
}

TEST(PmMemory, StructureStillDecodingHoldsItsReplay) {
    // The bound above is not met by accident: before its last split a
    // structure keeps the decoding state the complete one frees.
    const std::vector<Mesh> meshes = {test::icosphere(5)};
    auto bytes = lod::encode_bpm(meshes, {});
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    pm::BpmStream stream("sphere.bpm");
    ASSERT_TRUE(stream.feed(std::span<const uint8_t>(*bytes).first(bytes->size() - 64)).ok());
    ASSERT_EQ(stream.structure_count(), 1u);
    const pm::ProgressiveMesh& m = stream.structure(0);
    ASSERT_LT(m.available_level(), m.max_level());
    EXPECT_GT(m.heap_bytes(), 40 * m.max_level() + 8 * m.max_vertex_count() + 12 * m.max_triangle_count() + 4096);
}

}  // namespace
}  // namespace body
