// The streaming loader decodes a .bpm on the shared decoding threads: the base meshes at
// once, the detail only after release_detail(), everything in the end exactly
// as a one-shot read; failures keep what arrived and name the section.
#include "kiosk/scene/stream_loader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <thread>

#include "builder/lod/bpm_writer.h"
#include "builder/lod/simplify.h"
#include "kiosk/scene/model_part.h"
#include "shared/pm/bpm_reader.h"
#include "tests/common/test_meshes.h"

namespace body::kiosk {
namespace {

std::string temp_file(std::span<const uint8_t> bytes) {
    char name[] = "/tmp/body_stream_XXXXXX.bpm";
    const int fd = ::mkstemps(name, 4);
    EXPECT_GE(fd, 0);
    ::close(fd);
    std::ofstream(name, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return name;
}

// Two spheres (two structures), small SPLT sections: many sections after the bases.
std::vector<uint8_t> two_sphere_bpm() {
    lod::LodOptions options;
    options.chunk_splits = 256;
    const std::vector<Mesh> meshes{test::uv_sphere(40, 80), test::uv_sphere(30, 60, Vec3(3.0, 0.0, 0.0))};
    auto bytes = lod::encode_bpm(meshes, options);
    EXPECT_TRUE(bytes) << bytes.error().message;
    return bytes ? std::move(bytes).value() : std::vector<uint8_t>{};
}

TEST(StreamLoader, DecodesTheBasesThenWaitsForReleaseThenEverything) {
    const std::vector<uint8_t> bytes = two_sphere_bpm();
    ASSERT_GT(bytes.size(), 40000u);
    const std::string path = temp_file(bytes);
    auto expected = pm::read_bpm_bytes(bytes, path);
    ASSERT_TRUE(expected) << expected.error().message;
    {
        StreamLoader loader(path, 4096);
        loader.wait_for_bases();
        auto held = loader.lock();
        ASSERT_TRUE(loader.bases_ready());
        ASSERT_EQ(loader.stream().structure_count(), 2u);
        EXPECT_FALSE(loader.done());
        // At most one 4 KiB chunk past the bases before it waits.
        EXPECT_LE(loader.bytes_decoded(), bytes.size() - 8192);
        const size_t before = loader.bytes_decoded();
        held.unlock();
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        held.lock();
        EXPECT_EQ(loader.bytes_decoded(), before) << "decoded detail before release_detail()";
        held.unlock();

        loader.wait_until_done();
        held.lock();
        EXPECT_TRUE(loader.error().empty()) << loader.error();
        EXPECT_TRUE(loader.stream().complete());
        EXPECT_EQ(loader.bytes_decoded(), bytes.size());
        for (size_t s = 0; s < 2; ++s) {
            pm::ProgressiveMesh& got = loader.stream().structure(s);
            // The one-shot read sits at level 0: bring a copy to the top to compare.
            pm::ProgressiveMesh want = *expected.value()[s];
            ASSERT_EQ(got.available_level(), want.max_level());
            got.set_level(got.max_level());
            want.set_level(want.max_level());
            const auto gp = got.position_codes(), wp = want.position_codes();
            ASSERT_EQ(gp.size(), wp.size());
            EXPECT_TRUE(std::equal(gp.begin(), gp.end(), wp.begin()));
            const auto gi = got.indices(), wi = want.indices();
            ASSERT_EQ(gi.size(), wi.size());
            EXPECT_TRUE(std::equal(gi.begin(), gi.end(), wi.begin()));
        }
    }
    ::unlink(path.c_str());
}

TEST(StreamLoader, ACorruptSectionAfterTheBasesKeepsWhatArrived) {
    std::vector<uint8_t> bytes = two_sphere_bpm();
    bytes[bytes.size() * 3 / 4] ^= 0x5a;  // inside a late SPLT section
    const std::string path = temp_file(bytes);
    StreamLoader loader(path, 4096);
    loader.wait_until_done();
    auto held = loader.lock();
    EXPECT_TRUE(loader.bases_ready());
    EXPECT_NE(loader.error().find(path + ": section SPLT of structure"), std::string::npos) << loader.error();
    EXPECT_NE(loader.error().find("checksum mismatch"), std::string::npos) << loader.error();
    EXPECT_GT(loader.stream().structure(0).available_level(), 0u);
    ::unlink(path.c_str());
}

TEST(StreamLoader, ReportsAMissingFileAndATruncatedOne) {
    StreamLoader missing("/nonexistent/model.bpm");
    missing.wait_for_bases();
    {
        auto held = missing.lock();
        EXPECT_TRUE(missing.done());
        EXPECT_FALSE(missing.bases_ready());
        EXPECT_NE(missing.error().find("/nonexistent/model.bpm"), std::string::npos);
    }
    std::vector<uint8_t> bytes = two_sphere_bpm();
    bytes.resize(bytes.size() - 10);
    const std::string path = temp_file(bytes);
    StreamLoader truncated(path, 4096);
    truncated.wait_until_done();
    auto held = truncated.lock();
    EXPECT_NE(truncated.error().find("truncated"), std::string::npos) << truncated.error();
    ::unlink(path.c_str());
}

// The render thread takes the lock every frame while a pool thread decodes: it must
// get in between two slices, not when the whole file is done (a plain mutex lets
// the decoding thread re-take it slice after slice).
TEST(StreamLoader, LetsAWaitingCallerInBetweenSlices) {
    lod::LodOptions options;
    options.chunk_splits = 256;
    auto bytes = lod::encode_bpm(std::vector<Mesh>{test::uv_sphere(150, 300)}, options);
    ASSERT_TRUE(bytes) << bytes.error().message;
    ASSERT_GT(bytes->size(), 300000u);
    const std::string path = temp_file(bytes.value());
    StreamLoader loader(path, 1 << 20);  // one read: only the slices leave gaps
    loader.wait_for_bases();
    loader.release_detail();
    int taken_mid_file = 0;
    for (int i = 0; i < 8; ++i) {
        auto held = loader.lock();
        if (!loader.done()) ++taken_mid_file;
        held.unlock();
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    EXPECT_GE(taken_mid_file, 6) << "the caller only got the lock after the decoding";
    loader.wait_until_done();
    {
        auto held = loader.lock();
        EXPECT_TRUE(loader.error().empty()) << loader.error();
        EXPECT_TRUE(loader.stream().complete());
    }
    ::unlink(path.c_str());
}

TEST(StreamLoader, StopsWhileWaitingForRelease) {
    const std::vector<uint8_t> bytes = two_sphere_bpm();
    const std::string path = temp_file(bytes);
    {
        StreamLoader loader(path, 1024);
        loader.wait_for_bases();
    }  // the destructor must leave the pool while the file waits for release_detail()
    ::unlink(path.c_str());
}

// A small on-demand file: the slice that completes the base also reaches the
// wanted level (the base), so the pool thread pauses in that same step. A
// caller already blocked in wait_for_bases() must still be woken; the pause
// once returned before the wake-up and left it waiting for ever (ctest's
// time-out is this test's failure). Many rounds with the caller arriving at
// different moments, since which thread gets there first is up to the
// scheduler.
TEST(StreamLoader, AWaiterHearsOfTheBasesWhenTheSameSlicePauses) {
    lod::LodOptions options;
    options.chunk_splits = 256;
    auto bytes = lod::encode_bpm(std::vector<Mesh>{test::uv_sphere(8, 16)}, options);
    ASSERT_TRUE(bytes) << bytes.error().message;
    const std::string path = temp_file(bytes.value());
    for (int round = 0; round < 300; ++round) {
        StreamLoader loader(path, 1 << 16, 0.0, DecodePool::shared(), true);
        std::this_thread::sleep_for(std::chrono::microseconds(round % 50 * 10));
        loader.wait_for_bases();
        auto held = loader.lock();
        ASSERT_TRUE(loader.bases_ready()) << "round " << round;
        ASSERT_TRUE(loader.error().empty()) << loader.error();
    }
    ::unlink(path.c_str());
}

// Waits (bounded) until the loader paused or finished; false on time-out.
bool settle(const StreamLoader& loader) {
    return loader.wait_idle_until(std::chrono::steady_clock::now() + std::chrono::seconds(20));
}

// The levels of `got` up to its decoded level equal those of the one-shot read's:
// triangles (index prefix) and vertices (position codes).
void expect_prefix_levels(pm::ProgressiveMesh& got, pm::ProgressiveMesh want) {
    for (size_t level : {size_t(0), got.available_level() / 2, got.available_level()}) {
        ASSERT_EQ(got.set_level(level), want.set_level(level));
        const size_t n = got.triangle_count() * 3, v = got.vertex_count() * 3;
        ASSERT_EQ(n, want.triangle_count() * 3);
        EXPECT_TRUE(std::equal(got.indices().begin(), got.indices().begin() + ptrdiff_t(n), want.indices().begin()));
        EXPECT_TRUE(std::equal(got.position_codes().begin(), got.position_codes().begin() + ptrdiff_t(v),
                               want.position_codes().begin()));
    }
}

// On demand: past the bases a file decodes only as far as each structure's want
// (rounded up to a batch boundary), pauses holding that level exactly as a whole
// read gives it, and resumes when a want rises, to the same file in the end.
TEST(StreamLoader, OnDemandPausesAtTheWantedLevelAndResumes) {
    const std::vector<uint8_t> bytes = two_sphere_bpm();
    const std::string path = temp_file(bytes);
    auto expected = pm::read_bpm_bytes(bytes, path);
    ASSERT_TRUE(expected) << expected.error().message;
    {
        StreamLoader loader(path, 4096, 0.0, DecodePool::shared(), true);
        loader.wait_for_bases();
        loader.release_detail();
        ASSERT_TRUE(settle(loader));
        {
            auto held = loader.lock();
            ASSERT_TRUE(loader.paused()) << "nothing wanted past the bases";
            EXPECT_EQ(loader.stream().structure(0).available_level(), 0u);
            EXPECT_EQ(loader.stream().structure(1).available_level(), 0u);
            loader.want_splits(0, 300);  // the second structure stays at its base
        }
        ASSERT_TRUE(settle(loader));
        {
            auto held = loader.lock();
            ASSERT_TRUE(loader.paused());
            pm::ProgressiveMesh& first = loader.stream().structure(0);
            const auto bl = first.batch_levels();
            EXPECT_EQ(first.available_level(), *std::lower_bound(bl.begin(), bl.end(), 300u));
            expect_prefix_levels(first, *expected.value()[0]);
            EXPECT_LT(loader.bytes_decoded(), bytes.size() / 2);
            loader.want_splits(1, 1000);
        }
        ASSERT_TRUE(settle(loader));
        {
            auto held = loader.lock();
            ASSERT_TRUE(loader.paused());
            pm::ProgressiveMesh& second = loader.stream().structure(1);
            const auto bl = second.batch_levels();
            EXPECT_EQ(second.available_level(), *std::lower_bound(bl.begin(), bl.end(), 1000u));
            expect_prefix_levels(second, *expected.value()[1]);
        }
        loader.wait_until_done();  // lifts every want
        auto held = loader.lock();
        EXPECT_TRUE(loader.error().empty()) << loader.error();
        ASSERT_TRUE(loader.stream().complete());
        for (size_t s = 0; s < 2; ++s) {
            pm::ProgressiveMesh& got = loader.stream().structure(s);
            ASSERT_EQ(got.available_level(), got.max_level());
            expect_prefix_levels(got, *expected.value()[s]);
        }
    }
    ::unlink(path.c_str());
}

// A part's want (ModelPart::wanted_splits) decodes a file to the level the
// ratio draws and no further: the last batch boundary within the ratio's
// triangles, as a whole read draws it; the next batch would be decoded and
// never drawn (a complete batch is drawn at its boundaries only).
TEST(StreamLoader, OnDemandDecodesTheLevelTheRatioDrawsAndNoFurther) {
    const std::vector<uint8_t> bytes = two_sphere_bpm();
    const std::string path = temp_file(bytes);
    auto expected = pm::read_bpm_bytes(bytes, path);
    ASSERT_TRUE(expected) << expected.error().message;
    {
        StreamLoader loader(path, 4096, 0.0, DecodePool::shared(), true);
        loader.wait_for_bases();
        loader.release_detail();
        ASSERT_TRUE(settle(loader));
        pm::ProgressiveMesh& whole = *expected.value()[0];
        std::unique_ptr<ModelPart> part;
        {
            auto held = loader.lock();
            part = std::make_unique<ModelPart>(loader.stream().structure(0));
        }
        size_t inside_batches = 0;
        for (double ratio : {0.01, 0.05, 0.2, 0.45, 0.7, 1.0}) {
            const auto want =
                static_cast<size_t>(std::llround(static_cast<double>(whole.max_triangle_count()) * ratio));
            const size_t drawn = whole.level_for_triangles(want);  // a whole read: boundaries only
            for (int round = 0; round < 8; ++round) {              // each want decodes at most one step
                auto held = loader.lock();
                const size_t splits = part->wanted_splits(ratio);
                if (splits <= loader.stream().structure(0).available_level()) break;
                loader.want_splits(0, splits);
                held.unlock();
                ASSERT_TRUE(settle(loader));
            }
            auto held = loader.lock();
            pm::ProgressiveMesh& got = loader.stream().structure(0);
            EXPECT_EQ(got.available_level(), drawn) << "ratio " << ratio;
            EXPECT_EQ(got.level_for_triangles(want), drawn) << "ratio " << ratio;
            if (drawn < got.max_level() && whole.triangles_at(drawn) < want) ++inside_batches;
        }
        EXPECT_GE(inside_batches, 3u) << "ratios between two boundaries";
        auto held = loader.lock();
        expect_prefix_levels(loader.stream().structure(0), *expected.value()[0]);
    }
    ::unlink(path.c_str());
}

}  // namespace
}  // namespace body::kiosk
