// Decoding on demand (BpmStream::set_wanted_splits): a stream that stops at a
// wanted level, inside a SPLT section, holds exactly the levels a whole decode
// gives up to there; raised wants resume it, again and again, to the same
// file as an uninterrupted decode, bit for bit. No timing.
#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <vector>

#include "builder/lod/bpm_writer.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "tests/lod/lod_test_util.h"

namespace body {
namespace {

// Feeds `bytes` from `at` in pieces until the stream pauses or the bytes end;
// the next feed after a pause starts at bytes_consumed().
void feed_from(pm::BpmStream& stream, std::span<const uint8_t> bytes, size_t at) {
    constexpr size_t kPiece = 997;  // not a section size
    while (at < bytes.size()) {
        const size_t n = std::min(kPiece, bytes.size() - at);
        ASSERT_TRUE(stream.feed(bytes.subspan(at, n)).ok());
        at += n;
        if (stream.paused()) return;
    }
}

// The two structures agree on every level up to `up_to`: the triangles (index
// prefix), the vertices (position and normal codes) and the errors.
void expect_same_levels(pm::ProgressiveMesh& a, pm::ProgressiveMesh& b, size_t up_to) {
    std::vector<size_t> levels = {0, up_to / 3, up_to / 2, up_to};
    for (uint32_t boundary : a.batch_levels())
        if (boundary <= up_to) levels.push_back(boundary);
    for (size_t level : levels) {
        ASSERT_EQ(a.set_level(level), b.set_level(level)) << level;
        ASSERT_EQ(a.triangle_count(), b.triangle_count());
        const size_t n = a.triangle_count() * 3, v = a.vertex_count();
        EXPECT_TRUE(std::equal(a.indices().begin(), a.indices().begin() + ptrdiff_t(n), b.indices().begin()))
            << "triangles at level " << level;
        EXPECT_TRUE(std::equal(a.position_codes().begin(), a.position_codes().begin() + ptrdiff_t(3 * v),
                               b.position_codes().begin()))
            << "vertices at level " << level;
        EXPECT_TRUE(
            std::equal(a.normal_codes().begin(), a.normal_codes().begin() + ptrdiff_t(2 * v), b.normal_codes().begin()))
            << "normals at level " << level;
        // A level's error arrives with the split after it (the last decoded level's is not known yet).
        if (level < b.available_level() || b.available_level() == b.max_level()) {
            EXPECT_EQ(a.error_at(level), b.error_at(level)) << "error at level " << level;
        }
    }
}

struct OnDemandCase {
    pm::BpmStream::FaceOrder order;
    size_t chunk_splits;  // 0: the writer's default (4,096 splits a section)
};

class PmOnDemand : public ::testing::TestWithParam<OnDemandCase> {};

TEST_P(PmOnDemand, PausedLevelsMatchTheWholeDecodeAndResumeToTheSameFile) {
    const OnDemandCase c = GetParam();
    lod::LodOptions options;
    if (c.chunk_splits) options.chunk_splits = c.chunk_splits;
    const std::vector<Mesh> meshes = {test::icosphere(5)};
    auto bytes = lod::encode_bpm(meshes, options);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    const std::span<const uint8_t> all(*bytes);
    auto whole = pm::read_bpm_bytes(all, "sphere.bpm", c.order);
    ASSERT_TRUE(whole.ok()) << whole.error().message;
    pm::ProgressiveMesh& a = *whole->front();
    const size_t max = a.max_level();
    ASSERT_GT(max, 9000u);

    pm::BpmStream stream("sphere.bpm", c.order);
    stream.set_wanted_splits_all(0);
    feed_from(stream, all, 0);
    ASSERT_TRUE(stream.paused()) << "nothing wanted past the base";
    ASSERT_EQ(stream.structure_count(), 1u);
    pm::ProgressiveMesh& b = stream.structure(0);
    ASSERT_TRUE(b.base_ready());
    EXPECT_EQ(b.available_level(), 0u);
    const size_t base_bytes = b.heap_bytes();

    // Wants inside the first sections, one resumed twice inside the same section.
    size_t previous = 0, first_pause_bytes = 0, resumes = 0;
    for (size_t want : {size_t(150), size_t(700), size_t(1500), size_t(5000)}) {
        stream.set_wanted_splits(0, want);
        ASSERT_TRUE(stream.wants_more());
        feed_from(stream, all, stream.bytes_consumed());
        ASSERT_TRUE(stream.paused()) << "want " << want;
        const size_t level = b.available_level();
        // Stopped at the want, or (batched order) the first batch boundary at or above it.
        if (c.order == pm::BpmStream::FaceOrder::Refinement) {
            EXPECT_EQ(level, want);
        } else {
            const auto bl = a.batch_levels();
            EXPECT_EQ(level, *std::lower_bound(bl.begin(), bl.end(), uint32_t(want)));
        }
        EXPECT_GT(level, previous);
        EXPECT_LT(level, max);
        previous = level;
        expect_same_levels(a, b, level);
        if (!first_pause_bytes) first_pause_bytes = b.heap_bytes();
        // Paused, it holds its drawn arrays and split records (with their doubling's
        // room), not its decoding state (the replay, the codes in the file's
        // numbering): 67-137 bytes a vertex here, 194-336 with the state.
        EXPECT_LT(b.heap_bytes(), 160 * (b.base_vertex_count() + level)) << "decoding state kept while paused";
        // Resumed from a drawn level below the decoded one, and from a level
        // inside a batch (refinement order): the state rebuilt on resuming
        // (from the drawn arrays) must lead to the decoded level itself.
        b.set_level(resumes++ % 2 == 0 ? level / 3 : 0);
    }
    const size_t sections = c.chunk_splits ? c.chunk_splits : 4096;
    EXPECT_NE(previous % sections, 0u) << "the last pause lies inside a section";
    EXPECT_GT(first_pause_bytes, base_bytes);
    // Paused near its start, it holds a fraction of what decoding the whole file holds before the end.
    pm::BpmStream nearly("sphere.bpm", c.order);
    ASSERT_TRUE(nearly.feed(all.first(all.size() - 64)).ok());
    EXPECT_LT(2 * first_pause_bytes, nearly.structure(0).heap_bytes());

    stream.set_wanted_splits_all(SIZE_MAX);
    feed_from(stream, all, stream.bytes_consumed());
    EXPECT_FALSE(stream.paused());
    ASSERT_TRUE(stream.finish().ok()) << stream.finish().error().message;
    ASSERT_EQ(b.available_level(), max);
    expect_same_levels(a, b, max);
}

INSTANTIATE_TEST_SUITE_P(Orders, PmOnDemand,
                         ::testing::Values(OnDemandCase{pm::BpmStream::FaceOrder::Batched, 0},
                                           OnDemandCase{pm::BpmStream::FaceOrder::Refinement, 0},
                                           OnDemandCase{pm::BpmStream::FaceOrder::Batched, 1000}));

TEST(PmOnDemandStream, DefaultDecodesEverythingAndAPausedStreamHoldsNoBytes) {
    const std::vector<Mesh> meshes = {test::icosphere(4)};
    auto bytes = lod::encode_bpm(meshes, {});
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    const std::span<const uint8_t> all(*bytes);
    pm::BpmStream full("sphere.bpm");
    feed_from(full, all, 0);
    EXPECT_FALSE(full.paused());
    EXPECT_TRUE(full.complete());
    pm::BpmStream held("sphere.bpm");
    held.set_wanted_splits_all(0);
    feed_from(held, all, 0);
    ASSERT_TRUE(held.paused());
    EXPECT_LT(held.bytes_consumed(), all.size() / 2) << "stopped before the splits";
    EXPECT_EQ(held.structure(0).available_level(), 0u);
    // A corrupt byte in the section is still caught when the section is read again.
    std::vector<uint8_t> bad(all.begin(), all.end());
    bad[held.bytes_consumed() + 40] ^= 0x55;
    held.set_wanted_splits_all(SIZE_MAX);
    const Status st = held.feed(std::span<const uint8_t>(bad).subspan(held.bytes_consumed()));
    EXPECT_FALSE(st.ok());
}

}  // namespace
}  // namespace body
