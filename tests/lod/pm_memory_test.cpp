// What a progressive mesh keeps (the memory contract of progressive_mesh.h and
// split_replay.h): the connectivity replay holds the vertices that arrived, not
// the file's full detail; a complete structure keeps its split records, codes
// and index array within fixed bytes per split, vertex and triangle, and less
// once it hands its arrays to a renderer; a structure parked part-way holds
// split records and decoding state for what arrived, not for its full detail,
// and decodes to the same mesh. Sizes only, no timing.
#include <gtest/gtest.h>

#include <algorithm>
#include <span>
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

// A file in many SPLT sections, fed in small pieces until `stop` says so.
template <class Stop>
void feed_until(pm::BpmStream& stream, std::span<const uint8_t> bytes, size_t& at, Stop stop) {
    constexpr size_t kPiece = 97;  // not a section size: sections complete mid-piece
    while (at < bytes.size() && !(stream.structure_count() == 1 && stop(stream.structure(0)))) {
        const size_t n = std::min(kPiece, bytes.size() - at);
        ASSERT_TRUE(stream.feed(bytes.subspan(at, n)).ok());
        at += n;
    }
}

TEST(PmMemory, StructureParkedPartWayHoldsWhatArrived) {
    const std::vector<Mesh> meshes = {test::icosphere(5)};
    lod::LodOptions options;
    options.chunk_splits = 256;
    auto bytes = lod::encode_bpm(meshes, options);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    const std::span<const uint8_t> all(*bytes);
    pm::BpmStream stream("sphere.bpm");
    size_t at = 0;
    // Parked at about a tenth of the splits, then just before the last section.
    feed_until(stream, all, at, [](const pm::ProgressiveMesh& m) { return m.available_level() * 10 >= m.max_level(); });
    const pm::ProgressiveMesh& m = stream.structure(0);
    const size_t early_level = m.available_level(), early = m.heap_bytes();
    ASSERT_GT(m.max_level(), 5000u);
    ASSERT_LT(early_level * 5, m.max_level());
    feed_until(stream, all, at,
               [](const pm::ProgressiveMesh& s) { return s.available_level() + 256 >= s.max_level(); });
    const size_t late_level = m.available_level(), late = m.heap_bytes();
    ASSERT_LT(late_level, m.max_level());
    // The renderer's arrays are sized at INFO (8 bytes a vertex, 12 a
    // triangle, full detail); the rest follows the splits decoded, with at
    // most doubling's slack.
    const size_t renderer = 8 * m.max_vertex_count() + 12 * m.max_triangle_count() + 4096;
    ASSERT_GT(late, renderer);
    const double per_split_late = double(late - renderer) / double(late_level);
    EXPECT_LE(double(early), double(renderer) + 2.5 * per_split_late * double(early_level))
        << "a tenth decoded holds about a tenth of the decoding state (" << early << " bytes at level " << early_level
        << ", " << late << " at " << late_level << ")";
}

TEST(PmMemory, GrowingWithTheSectionsDecodesTheSameMeshInTheSameBytes) {
    const std::vector<Mesh> meshes = {test::icosphere(4)};
    lod::LodOptions options;
    options.chunk_splits = 100;
    auto bytes = lod::encode_bpm(meshes, options);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    auto whole = pm::read_bpm_bytes(*bytes, "sphere.bpm");  // every section at once
    ASSERT_TRUE(whole.ok()) << whole.error().message;
    pm::BpmStream stream("sphere.bpm");
    size_t at = 0;
    feed_until(stream, *bytes, at, [](const pm::ProgressiveMesh&) { return false; });
    ASSERT_TRUE(stream.finish().ok());
    pm::ProgressiveMesh& a = *whole->front();
    pm::ProgressiveMesh& b = stream.structure(0);
    ASSERT_EQ(b.available_level(), b.max_level());
    ASSERT_EQ(a.max_level(), b.max_level());
    for (size_t level : {size_t(0), a.max_level() / 3, a.max_level()}) {
        a.set_level(level);
        b.set_level(level);
        ASSERT_EQ(a.level(), b.level());
        const size_t n = a.triangle_count() * 3, v = a.vertex_count() * 3;
        EXPECT_TRUE(std::equal(a.indices().begin(), a.indices().begin() + ptrdiff_t(n), b.indices().begin()));
        EXPECT_TRUE(std::equal(a.position_codes().begin(), a.position_codes().begin() + ptrdiff_t(v),
                               b.position_codes().begin()));
        EXPECT_EQ(a.error_at(level), b.error_at(level));
    }
    // The whole read sizes its arrays to the file's counts at once
    // (expect_whole_file), the stream grows them: both end at the same sizes.
    EXPECT_EQ(a.heap_bytes(), b.heap_bytes());
}

}  // namespace
}  // namespace body
