// A .bpm's INFO sections read without decoding (shared/pm/bpm_summary.h): the
// same structures as the full reader, and the same refusals.
#include "shared/pm/bpm_summary.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include "builder/lod/bpm_writer.h"
#include "shared/atomic_file.h"
#include "shared/pm/bpm_reader.h"
#include "tests/lod/lod_test_util.h"

namespace body {
namespace {

void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes, size_t count) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(count));
}

// Three structures, the last large enough that its BASE and SPLT run past the
// first 4 KiB: every INFO is found past payloads that are skipped unread.
std::vector<uint8_t> three_structures() {
    std::vector<Mesh> meshes = {test::icosphere(1, 2.0), test::bumpy_torus(40, 60),
                                test::icosphere(3, 5.0, Vec3(30.0, -4.0, 7.0))};
    auto bytes = lod::encode_bpm(meshes, lod::LodOptions{});
    EXPECT_TRUE(bytes.ok());
    return bytes.ok() ? *bytes : std::vector<uint8_t>{};
}

TEST(BpmSummary, EveryStructureAsTheFullReaderDecodesIt) {
    const std::vector<uint8_t> bytes = three_structures();
    ASSERT_GT(bytes.size(), 8192u);
    ScratchPath file(testing::TempDir() + "bpm_summary_three.bpm");
    write_bytes(file.path(), bytes, bytes.size());
    auto summary = pm::read_bpm_summary(file.path());
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    auto full = pm::read_bpm_bytes(bytes, "three.bpm");
    ASSERT_TRUE(full.ok());
    ASSERT_EQ(summary->size(), full->size());
    for (size_t i = 0; i < full->size(); ++i) {
        const pm::ProgressiveMesh& m = *(*full)[i];
        const pm::StructureSummary& s = (*summary)[i];
        EXPECT_EQ(s.base_triangles, m.base_triangle_count()) << "structure " << i;
        EXPECT_EQ(s.full_triangles, m.max_triangle_count()) << "structure " << i;
        EXPECT_EQ(s.box_min, m.bounds_min()) << "structure " << i;
        EXPECT_EQ(s.box_max, m.bounds_max()) << "structure " << i;
    }
    EXPECT_GT((*summary)[1].full_triangles, (*summary)[1].base_triangles);
}

TEST(BpmSummary, ATruncatedFileNamesTheByteWhereItEnds) {
    const std::vector<uint8_t> bytes = three_structures();
    ScratchPath file(testing::TempDir() + "bpm_summary_cut.bpm");
    write_bytes(file.path(), bytes, 10);
    auto r = pm::read_bpm_summary(file.path());
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, file.path() + ": byte 0: truncated file header");
    write_bytes(file.path(), bytes, 16 + 5);  // the file header, then 5 bytes of the first section header
    r = pm::read_bpm_summary(file.path());
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, file.path() + ": byte 16: truncated before every INFO section");
}

TEST(BpmSummary, AFifoOrADirectoryIsRefusedWithoutBlocking) {
    ScratchPath fifo(testing::TempDir() + "bpm_summary_pipe.bpm");
    ASSERT_EQ(::mkfifo(fifo.path().c_str(), 0600), 0);
    auto r = pm::read_bpm_summary(fifo.path());  // a blocking open would hang here: no writer
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, fifo.path() + ": not a regular file");
    r = pm::read_bpm_summary(testing::TempDir());
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, testing::TempDir() + ": not a regular file");
    r = pm::read_bpm_summary(testing::TempDir() + "bpm_summary_absent.bpm");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, testing::TempDir() + "bpm_summary_absent.bpm: not a regular file");
}

}  // namespace
}  // namespace body
