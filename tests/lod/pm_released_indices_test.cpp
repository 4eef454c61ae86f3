// ProgressiveMesh with its index array handed to the caller (release_indices,
// release_indices_upto, patch_indices): the caller's copy, patched at any
// moment, holds what a mesh that kept its array holds at the same level.
#include <gtest/gtest.h>

#include <vector>

#include "builder/lod/bpm_writer.h"
#include "builder/lod/simplify.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "tests/lod/lod_test_util.h"

namespace body {
namespace {

using pm::ProgressiveMesh;

using Order = pm::BpmStream::FaceOrder;

std::unique_ptr<ProgressiveMesh> decode_one(const std::vector<uint8_t>& bytes, Order order = Order::Refinement) {
    auto r = pm::read_bpm_bytes(bytes, "test.bpm", order);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() && !r->empty() ? std::move(r->front()) : nullptr;
}

std::vector<uint8_t> sphere_bpm(int subdivisions) {
    const std::vector<Mesh> meshes = {test::icosphere(subdivisions)};
    auto bytes = lod::encode_bpm(meshes, {});
    EXPECT_TRUE(bytes.ok()) << (bytes.ok() ? "" : bytes.error().message);
    return bytes.ok() ? *bytes : std::vector<uint8_t>{};
}

// The caller's copy brought to the mesh's level, through the pending range
// only (entries outside it must not need writing).
void patch(ProgressiveMesh& m, std::vector<uint32_t>& copy) {
    const pm::DirtyRange r = m.pending_index_range();
    if (r.empty()) {
        m.patch_indices({}, 0);
        return;
    }
    ASSERT_LE(r.end, copy.size());
    m.patch_indices(std::span<uint32_t>(copy).subspan(r.begin, r.end - r.begin), r.begin);
    EXPECT_TRUE(m.pending_index_range().empty());
}

// Both orders: in the batched one (the kiosk's) a level inside a batch is
// moved to the batch boundary below it.
void expect_patched_copy_matches(Order order) {
    const auto bytes = sphere_bpm(3);
    auto kept = decode_one(bytes, order), given = decode_one(bytes, order);
    ASSERT_TRUE(kept && given);
    ASSERT_GT(kept->max_level(), 50u);
    // Start both at a middle level, then hand the array over.
    const size_t start = kept->max_level() / 2;
    kept->set_level(start);
    given->set_level(start);
    std::vector<uint32_t> copy(given->indices().begin(), given->indices().end());
    ASSERT_EQ(copy.size(), 3 * given->max_triangle_count());
    std::vector<uint16_t> codes(given->position_codes().begin(), given->position_codes().end());
    ASSERT_EQ(codes.size(), 3 * given->max_vertex_count());
    ASSERT_TRUE(given->release_indices());
    ASSERT_TRUE(given->release_vertex_data());
    EXPECT_TRUE(given->vertex_data_released());
    EXPECT_TRUE(given->position_codes().empty());
    EXPECT_TRUE(given->normal_codes().empty());
    EXPECT_TRUE(given->indices_released());
    EXPECT_TRUE(given->indices().empty());
    EXPECT_TRUE(given->pending_index_range().empty());

    uint32_t seed = 777;
    for (int step = 0; step < 300; ++step) {
        seed = seed * 1664525u + 1013904223u;
        const size_t level = (seed >> 8) % (kept->max_level() + 1);
        kept->set_level(level);
        given->set_level(level);
        EXPECT_EQ(given->level(), given->drawable_below(level));
        EXPECT_EQ(given->level() == level, order == Order::Refinement || level == given->drawable_below(level));
        // Several moves between two patches now and then: one pass from the
        // copy's level to the last one.
        if (step % 3 == 2) continue;
        patch(*given, copy);
        const std::vector<uint32_t> want(kept->indices().begin(), kept->indices().end());
        ASSERT_EQ(copy, want) << "level " << level << " step " << step;
        // The positions likewise, through their pending range only.
        const pm::DirtyRange r = given->pending_vertex_range();
        if (!r.empty())
            given->patch_position_codes(std::span<uint16_t>(codes).subspan(r.begin * 3, (r.end - r.begin) * 3),
                                        r.begin);
        else
            given->patch_position_codes({}, 0);
        EXPECT_TRUE(given->pending_vertex_range().empty());
        ASSERT_EQ(codes, std::vector<uint16_t>(kept->position_codes().begin(), kept->position_codes().end()))
            << "level " << level << " step " << step;
        ASSERT_EQ(given->vertex_count(), kept->vertex_count());
        ASSERT_EQ(given->triangle_count(), kept->triangle_count());
    }
    // A copy not brought along is visibly different (the test can fail).
    std::vector<uint32_t> stale = copy;
    kept->set_level(0);
    given->set_level(0);
    EXPECT_NE(stale, std::vector<uint32_t>(kept->indices().begin(), kept->indices().end()));
    patch(*given, stale);
    EXPECT_EQ(stale, std::vector<uint32_t>(kept->indices().begin(), kept->indices().end()));
}

TEST(PmReleasedIndices, PatchedCopyMatchesAMeshKeepingItsArray) { expect_patched_copy_matches(Order::Refinement); }
TEST(PmReleasedIndices, PatchedCopyMatchesInBatchedOrder) { expect_patched_copy_matches(Order::Batched); }

TEST(PmReleasedIndices, ReleasedAPieceAtATimeWhileCopied) {
    const auto bytes = sphere_bpm(5);  // 20K triangles: an array of whole pages
    auto kept = decode_one(bytes), given = decode_one(bytes);
    ASSERT_TRUE(kept && given);
    const std::vector<uint32_t> want(kept->indices().begin(), kept->indices().end());
    std::vector<uint32_t> copy(want.size());
    constexpr size_t kPiece = 1000;  // not a page multiple
    for (size_t first = 0; first < copy.size(); first += kPiece) {
        const size_t n = std::min(kPiece, copy.size() - first);
        // Entries not yet copied are intact after the earlier pieces were released.
        std::copy_n(given->indices().begin() + ptrdiff_t(first), n, copy.begin() + ptrdiff_t(first));
        ASSERT_TRUE(given->release_indices_upto(first + n));
        if (first + n < copy.size()) {
            ASSERT_FALSE(given->indices_released());
        }
    }
    EXPECT_TRUE(given->indices_released());
    EXPECT_TRUE(given->indices().empty());
    EXPECT_EQ(copy, want);
    // And the copy follows the levels.
    kept->set_level(kept->max_level() / 3);
    given->set_level(kept->max_level() / 3);
    patch(*given, copy);
    EXPECT_EQ(copy, std::vector<uint32_t>(kept->indices().begin(), kept->indices().end()));
}

TEST(PmReleasedIndices, PackedArrayFillsTheCopyAtTheLevelReachedSince) {
    const auto bytes = sphere_bpm(4);
    auto kept = decode_one(bytes), given = decode_one(bytes);
    ASSERT_TRUE(kept && given);
    given->set_level(given->max_level());
    ASSERT_TRUE(given->pack_indices());
    EXPECT_TRUE(given->indices_packed());
    EXPECT_TRUE(given->indices_released());
    EXPECT_TRUE(given->indices().empty());
    // Moves before the fill: the fill writes the array of the level reached.
    const size_t level = given->max_level() / 3;
    given->set_level(given->max_level() / 2);
    given->set_level(level);
    kept->set_level(level);
    std::vector<uint32_t> copy(3 * given->max_triangle_count(), 0xdeadbeefu);
    given->fill_indices(copy);
    EXPECT_FALSE(given->indices_packed());
    EXPECT_TRUE(given->pending_index_range().empty());
    EXPECT_EQ(copy, std::vector<uint32_t>(kept->indices().begin(), kept->indices().end()));
    // Patched as a released array afterwards.
    given->set_level(given->max_level());
    kept->set_level(kept->max_level());
    patch(*given, copy);
    EXPECT_EQ(copy, std::vector<uint32_t>(kept->indices().begin(), kept->indices().end()));
}

TEST(PmReleasedIndices, MovesOfParentsArePending) {
    // Some split moves its parent (optimal placement), so positions change
    // between levels and the pending vertex range is not empty.
    const auto bytes = sphere_bpm(3);
    auto m = decode_one(bytes);
    ASSERT_TRUE(m);
    m->set_level(m->max_level());
    const std::vector<uint16_t> full(m->position_codes().begin(), m->position_codes().end());
    ASSERT_TRUE(m->release_indices());
    ASSERT_TRUE(m->release_vertex_data());
    m->set_level(0);
    EXPECT_FALSE(m->pending_vertex_range().empty());
    EXPECT_FALSE(m->pending_index_range().empty());
    std::vector<uint16_t> codes = full;
    const pm::DirtyRange r = m->pending_vertex_range();
    m->patch_position_codes(std::span<uint16_t>(codes).subspan(r.begin * 3, (r.end - r.begin) * 3), r.begin);
    EXPECT_NE(codes, full);
    // Back up: the XORs undo themselves.
    m->set_level(m->max_level());
    const pm::DirtyRange back = m->pending_vertex_range();
    m->patch_position_codes(std::span<uint16_t>(codes).subspan(back.begin * 3, (back.end - back.begin) * 3),
                            back.begin);
    EXPECT_EQ(codes, full);
}

TEST(PmReleasedIndices, NotReleasedWhileSplitsAreStillStreaming) {
    const auto bytes = sphere_bpm(3);
    pm::BpmStream stream("<stream>", pm::BpmStream::FaceOrder::Refinement);
    // Everything up to the middle of the file: the base arrives, not every split.
    ASSERT_TRUE(stream.feed(std::span<const uint8_t>(bytes).first(bytes.size() * 3 / 4)).ok());
    ASSERT_EQ(stream.structure_count(), 1u);
    ProgressiveMesh& m = stream.structure(0);
    ASSERT_TRUE(m.base_ready());
    ASSERT_LT(m.available_level(), m.max_level());
    EXPECT_FALSE(m.release_indices());
    EXPECT_FALSE(m.release_indices_upto(3));
    EXPECT_FALSE(m.release_vertex_data());
    EXPECT_FALSE(m.indices_released());
    EXPECT_FALSE(m.vertex_data_released());
    // Nothing freed: the array still holds every decoded triangle (it grows with them).
    EXPECT_GE(m.indices().size(), 3 * m.triangles_at(m.available_level()));
}

}  // namespace
}  // namespace body
