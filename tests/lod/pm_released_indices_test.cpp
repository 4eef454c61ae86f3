// ProgressiveMesh with its index array handed to the caller (release_indices,
// release_indices_upto, patch_indices): the caller's copy, patched at any
// moment, holds what a mesh that kept its array holds at the same level.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "builder/lod/bpm_writer.h"
#include "builder/lod/simplify.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/index_code.h"
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

// The packed code gives every entry back exactly: `entries` packed in place
// (its words a prefix of the array) and decoded from those words only.
void expect_round_trip(const std::vector<uint32_t>& entries, size_t vertex_count) {
    const size_t bits = pm::index_code_bits(vertex_count);
    std::vector<uint32_t> packed = entries;
    const size_t words = pm::pack_index_code(packed, bits);
    EXPECT_LE(words, entries.size());
    packed.resize(words);
    std::vector<uint32_t> back(entries.size(), 0xdeadbeefu);
    pm::unpack_index_code(packed, bits, back);
    EXPECT_EQ(back, entries) << "vertex_count " << vertex_count;
}

TEST(PmIndexCode, EveryEntryComesBackExactly) {
    const size_t big = pm::kMaxVertices;
    expect_round_trip({}, 1);
    expect_round_trip({0, 0, 0}, 1);  // one vertex: the long code is 1 bit wide
    expect_round_trip({1, 0, 1, 0, 0, 1}, 2);
    // The largest jumps both ways, on the first corner and the others.
    expect_round_trip({uint32_t(big - 1), 0, uint32_t(big - 1), 0, uint32_t(big - 1), 0, 0, 0, uint32_t(big - 1)}, big);
    // Differences at the short code's edge (zigzag 31 and 32) around a reference.
    expect_round_trip({100, 115, 84, 116, 100, 83, 100, 100, 100}, big);
    // More distinct values than the FIFO holds, cycled: each comes back after
    // being evicted (always a miss), then a run of 16 repeated (always a hit).
    std::vector<uint32_t> cycled;
    for (int round = 0; round < 4; ++round)
        for (uint32_t v = 0; v < 17; ++v) cycled.push_back(v * 1000);
    for (uint32_t v = 0; v < 16; ++v) cycled.push_back(v * 1000);
    cycled.push_back(16 * 1000);
    while (cycled.size() % 3) cycled.push_back(0);
    expect_round_trip(cycled, 17 * 1000);
    // Random meshes of every kind of entry: FIFO ages 0..15, short and long
    // differences, values anywhere below the count.
    std::mt19937 rng(24);
    for (size_t vertex_count : {size_t(3), size_t(1000), size_t(557330), big}) {
        std::vector<uint32_t> mixed;
        for (size_t i = 0; i < 30000; ++i) {
            const uint32_t kind = rng() % 4;
            uint32_t v = rng() % vertex_count;
            if (kind == 0 && mixed.size() >= 20) v = mixed[mixed.size() - 1 - rng() % 20];
            if (kind == 1 && !mixed.empty())
                v = uint32_t(std::clamp<int64_t>(int64_t(mixed.back()) + int64_t(rng() % 41) - 20, 0,
                                                 int64_t(vertex_count) - 1));
            mixed.push_back(v);
        }
        expect_round_trip(mixed, vertex_count);
    }
}

TEST(PmIndexCode, RefinedMeshArrayComesBackExactly) {
    const auto bytes = sphere_bpm(5);
    auto m = decode_one(bytes);
    ASSERT_TRUE(m);
    for (size_t level : {size_t(0), m->max_level() / 2, m->max_level()}) {
        m->set_level(level);
        expect_round_trip(std::vector<uint32_t>(m->indices().begin(), m->indices().end()), m->max_vertex_count());
    }
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
