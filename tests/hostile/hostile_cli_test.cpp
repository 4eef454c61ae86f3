// Hostile inputs through bodygen and bodyview, by class (issue 30): crashes,
// hangs, outputs left behind, inputs destroyed, inputs accepted silently,
// messages. Every refusal is exactly one line naming the file and the place,
// with exit code 2 (bad input) unless said otherwise, and leaves no output.
// The inputs are generated here; `timeout` turns a hang into a failure.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/cli_test.h"

namespace body {
namespace {

namespace fs = std::filesystem;
using test::bin;
using test::run;

class Hostile : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("body_hostile_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::string write(const std::string& name, const std::string& bytes) const {
        std::ofstream(path(name), std::ios::binary) << bytes;
        return path(name);
    }
    // Runs `args` on `tool` in the test directory under a time limit.
    test::RunResult go(const std::string& tool, const std::string& args, int seconds = 60) const {
        return run("cd '" + dir_.string() + "' && timeout " + std::to_string(seconds) + " " + bin(tool.c_str()) + " " +
                   args);
    }
    // Exactly one line, exit 2, matching `shape` (a regex).
    void expect_refused(const test::RunResult& r, const std::string& shape, int code = 2) const {
        EXPECT_EQ(r.exit_code, code) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_TRUE(std::regex_search(r.output, std::regex(shape))) << "expected /" << shape << "/ in: " << r.output;
    }
    fs::path dir_;
};

std::string circle_stack(size_t n, double radius, std::vector<double> zs) {
    std::ostringstream s;
    s.precision(17);
    s << R"({"format": "bodygen.contours", "version": 1, "structures": [{"id": "a"}], "slices": [)";
    for (size_t k = 0; k < zs.size(); ++k) {
        s << (k ? "," : "") << R"({"z": )" << zs[k] << R"(, "contours": [{"structure": "a", "points": [)";
        for (size_t i = 0; i < n; ++i) {
            const double a = 2 * M_PI * double(i) / double(n), r = radius * (1 + 0.05 * std::sin(50 * a));
            s << (i ? "," : "") << "[" << r * std::cos(a) << "," << r * std::sin(a) << "]";
        }
        s << "]}]}";
    }
    s << "]}";
    return s.str();
}

// A 348-byte NIfTI-1 header and `data`: dims, datatype uint8.
std::string nifti(int16_t nx, int16_t ny, int16_t nz, const std::string& data) {
    std::string h(352, '\0');
    auto put32 = [&](size_t at, int32_t v) { std::memcpy(&h[at], &v, 4); };
    auto put16 = [&](size_t at, int16_t v) { std::memcpy(&h[at], &v, 2); };
    auto putf = [&](size_t at, float v) { std::memcpy(&h[at], &v, 4); };
    put32(0, 348);
    const int16_t dims[8] = {3, nx, ny, nz, 1, 1, 1, 1};
    for (int i = 0; i < 8; ++i) put16(40 + 2 * size_t(i), dims[i]);
    put16(70, 2);  // DT_UINT8
    put16(72, 8);
    for (int i = 0; i < 4; ++i) putf(76 + 4 * size_t(i), 1.0f);
    putf(108, 352.0f);
    putf(112, 1.0f);  // scl_slope
    std::memcpy(&h[344], "n+1\0", 4);
    return h + data;
}

std::string gzip(const std::string& bytes) {
    std::string out(compressBound(uLong(bytes.size())) + 64, '\0');
    z_stream z{};
    deflateInit2(&z, 9, Z_DEFLATED, 31, 8, Z_DEFAULT_STRATEGY);
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
    z.avail_in = uInt(bytes.size());
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = uInt(out.size());
    deflate(&z, Z_FINISH);
    out.resize(z.total_out);
    deflateEnd(&z);
    return out;
}

const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";

// ---------------------------------------------------------------- crashes

TEST_F(Hostile, CoordinatesAndGapsOutsideTheRangeAreRefusedWithThePlace) {
    write("huge.contours.json", circle_stack(32, 1e100, {0, 1}));
    expect_refused(go("bodygen", "build huge.contours.json -o out.obj"),
                   "^bodygen: huge.contours.json: slice 0 contour 0: point 0 .* outside the coordinate range");
    write("gap.contours.json", circle_stack(32, 10, {0, 1e154}));
    expect_refused(go("bodygen", "build gap.contours.json -o out.obj"),
                   "^bodygen: gap.contours.json: slice 1: z = 1e\\+154 is outside the coordinate range");
    EXPECT_FALSE(fs::exists(path("out.obj")));
}

TEST_F(Hostile, NiftiDeclaringMoreVoxelsThanItsFileHoldsIsRefusedBeforeReading) {
#ifndef BODY_HOSTILE_IMPORT
    GTEST_SKIP() << "bodygen built without import (BODY_WITH_IMPORT=OFF)";
#endif
    write("big.nii.gz", gzip(nifti(2048, 2048, 128, std::string(4096, '\0'))));
    expect_refused(go("bodygen", "contours big.nii.gz -o out.contours.json"),
                   "^bodygen: big.nii.gz: declares 536870912 bytes of voxels, more than [0-9]+ compressed bytes");
    write("short.nii", nifti(512, 512, 512, std::string(100, '\0')));
    expect_refused(go("bodygen", "contours short.nii -o out.contours.json"), "^bodygen: short.nii: .*truncated");
    EXPECT_FALSE(fs::exists(path("out.contours.json")));
}

TEST_F(Hostile, BpmHeaderIsCheckedBeforeTheFileIsRead) {
    fs::create_symlink("/dev/zero", path("zero.bpm"));
    expect_refused(go("bodygen", "info zero.bpm", 10), "^bodygen: zero.bpm: is a device, not a regular file");
    write("zeros.bpm", std::string(1 << 20, '\0'));
    expect_refused(go("bodygen", "info zeros.bpm", 10), "^bodygen: zeros.bpm: file header at byte 0: not a .bpm");
}

TEST_F(Hostile, OversizedPictureIsAnError) {
    write("t.obj", kTriangleObj);
    expect_refused(go("bodyview", "--headless --size 16384x16384 --model t.obj --screenshot x.png"),
                   "^bodyview: --size 16384x16384 .* over the limit");
    EXPECT_FALSE(fs::exists(path("x.png")));
}

// ---------------------------------------------------------------- hangs

// 10^5 points with the default (dome) caps took minutes with quadratic caps
// and a quadratic dome; the time limit is generous, not a measurement.
TEST_F(Hostile, LargeContourBuildsWithCaps) {
    write("big.contours.json", circle_stack(100000, 100, {0, 2}));
    auto r = go("bodygen", "build big.contours.json -o out.obj --quiet", 120);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(path("out.obj")));
}

TEST_F(Hostile, FifoDirectoryAndDeviceAreNamedNotOpened) {
    ASSERT_EQ(::mkfifo(path("pipe.contours.json").c_str(), 0600), 0);
    expect_refused(go("bodygen", "build pipe.contours.json -o out.obj", 10),
                   "^bodygen: pipe.contours.json: is a FIFO, not a regular file");
    fs::create_directory(path("d.contours.json"));
    expect_refused(go("bodygen", "build d.contours.json -o out.obj", 10), "^bodygen: d.contours.json: is a directory");
    ASSERT_EQ(::mkfifo(path("pipe.obj").c_str(), 0600), 0);
    expect_refused(go("bodygen", "lod pipe.obj -o out.bpm", 10), "^bodygen: pipe.obj: is a FIFO");
    fs::create_symlink("/dev/null", path("null.obj"));
    expect_refused(go("bodygen", "lod null.obj -o out.bpm", 10), "^bodygen: null.obj: is a device");
}

TEST_F(Hostile, FifoInABundleDoesNotBlockTheKiosk) {
    fs::create_directories(path("b/models"));
    ASSERT_EQ(::mkfifo(path("b/models/pipe.bpm").c_str(), 0600), 0);
    write("b/scene.json", R"({"version": 1, "models": [{"name": "p", "file": "models/pipe.bpm"}]})");
    auto r = go("bodyview", "--headless --size 64x64 --screenshot x.png b", 20);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("pipe.bpm: is a FIFO"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("x.png")));
}

TEST_F(Hostile, EndlessRunsAreRefused) {
    write("t.obj", kTriangleObj);
    expect_refused(go("bodyview", "--headless --frames 0 --model t.obj", 10), "^bodyview: --frames must be at least 1");
    expect_refused(go("bodyview", "--headless --frames -1 --model t.obj", 10),
                   "^bodyview: --frames must be at least 1");
    write("long.replay", "0.0 move 1 10 10\n1e9 end\n");
    expect_refused(go("bodyview", "--headless --replay long.replay --model t.obj", 10),
                   "^bodyview: long.replay: line 2: time 1e9 is over the 3600 s limit");
}

// ---------------------------------------------------------------- outputs left behind, inputs destroyed

TEST_F(Hostile, NoPictureWhenNothingCouldBeShown) {
    write("bad.obj", "v 0 0 0\nf 1 2 3\n");
    auto r = go("bodyview", "--headless --size 64x64 --model bad.obj --screenshot x.png");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_FALSE(fs::exists(path("x.png")));
    fs::create_directories(path("b"));
    write("b/scene.json", R"({"version": 1, "models": [{"name": "m", "file": "../bad.obj"}]})");
    r = go("bodyview", "--headless --size 64x64 --screenshot y.png b");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_FALSE(fs::exists(path("y.png")));
}

TEST_F(Hostile, OutputNamingAnInputIsRefusedAndTheInputKept) {
    const std::string stack = circle_stack(16, 10, {0, 1});
    write("in.contours.json", stack);
    ASSERT_EQ(::link(path("in.contours.json").c_str(), path("same.obj").c_str()), 0);
    expect_refused(go("bodygen", "build in.contours.json -o same.obj"),
                   "^bodygen: same.obj: is the input in.contours.json; not overwriting it");
    write("t.obj", kTriangleObj);
    expect_refused(go("bodygen", "lod t.obj -o ./t.obj"), "^bodygen: ./t.obj: is the input t.obj");
    std::ifstream in(path("in.contours.json"));
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), stack);
    expect_refused(go("bodygen", "build in.contours.json -o x.stl"), "^bodygen: x.stl: unknown output type");
}

TEST_F(Hostile, DirectoryOutputIsReplacedWholeOrNotAtAll) {
    write("in.contours.json", circle_stack(16, 10, {0, 1}));
    fs::create_directories(path("keep"));
    write("keep/notes.txt", "mine");
    expect_refused(go("bodygen", "build in.contours.json -o keep/ --quiet"),
                   "^bodygen: keep: holds notes.txt, not only OBJ files; not replacing it");
    EXPECT_TRUE(fs::exists(path("keep/notes.txt")));
    auto r = go("bodygen", "build in.contours.json -o out/ --quiet");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(path("out/a.obj")));
    for (const auto& e : fs::directory_iterator(dir_))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(Hostile, TemporariesOfDeadProcessesAreSwept) {
    write("in.contours.json", circle_stack(16, 10, {0, 1}));
    write("out.obj.tmp-999999999", "half");
    fs::create_directories(path("out.obj.tmp-1"));  // pid 1 lives: not ours to remove
    auto r = go("bodygen", "build in.contours.json -o out.obj --quiet");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_FALSE(fs::exists(path("out.obj.tmp-999999999")));
    EXPECT_TRUE(fs::exists(path("out.obj.tmp-1")));
}

// ---------------------------------------------------------------- accepted silently

TEST_F(Hostile, NiftiHeadersOutsideTheFormatAreRefusedAtTheirByte) {
#ifndef BODY_HOSTILE_IMPORT
    GTEST_SKIP() << "bodygen built without import (BODY_WITH_IMPORT=OFF)";
#endif
    std::string good = nifti(4, 4, 4, std::string(64, '\1'));
    auto patched = [&](size_t at, const std::string& bytes) {
        std::string b = good;
        b.replace(at, bytes.size(), bytes);
        return b;
    };
    write("neg.nii", patched(42, std::string("\xfe\xff", 2)));
    expect_refused(go("bodygen", "contours neg.nii -o o.json"),
                   "^bodygen: neg.nii: header byte 42: wrong dims: dim\\[1\\] = -2");
    write("zero.nii", patched(44, std::string("\0\0", 2)));
    expect_refused(go("bodygen", "contours zero.nii -o o.json"), "^bodygen: zero.nii: header byte 44: wrong dims");
    write("magic.nii", patched(344, std::string("abc\0", 4)));
    expect_refused(go("bodygen", "contours magic.nii -o o.json"), "^bodygen: magic.nii: header byte 344: magic");
    write("size.nii", patched(0, std::string(4, '\0')));
    expect_refused(go("bodygen", "contours size.nii -o o.json"),
                   "^bodygen: size.nii: header byte 0: sizeof_hdr is 0, not 348");
    EXPECT_FALSE(fs::exists(path("o.json")));
}

TEST_F(Hostile, ObjNumbersAndFacesOutsideTheFormatAreRefusedWithTheLine) {
    const std::pair<const char*, const char*> cases[] = {
        {"v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n", "line 2: vertex coordinate 'nan' is not a finite float"},
        {"v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n", "line 2: vertex coordinate 'inf' is not a finite float"},
        {"v 0 0 0\nv 1 0 one\nv 0 1 0\nf 1 2 3\n", "line 2: vertex coordinate 'one' is not a number"},
        {"v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "line 2: vertex needs x y z, got 2 values"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 100000000000000000000\n",
         "line 4: face vertex '1e?0*' is not an index|line 4: face vertex '100000000000000000000' is not an index"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "line 4: face vertex index 4 is outside 1..3"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "line 4: face has 2 vertices, at least 3 needed"},
    };
    int k = 0;
    for (const auto& [text, shape] : cases) {
        const std::string name = "bad" + std::to_string(k++) + ".obj";
        write(name, text);
        expect_refused(go("bodygen", "lod " + name + " -o out.bpm"), "^bodygen: " + name + ": " + shape);
    }
    EXPECT_FALSE(fs::exists(path("out.bpm")));
}

TEST_F(Hostile, BpmBytesAfterEndAreRefused) {
    write("t.obj", kTriangleObj);
    ASSERT_EQ(go("bodygen", "lod t.obj -o t.bpm").exit_code, 0);
    std::ifstream in(path("t.bpm"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    write("tail.bpm", bytes + "12345");
    expect_refused(go("bodygen", "info tail.bpm"), "^bodygen: tail.bpm: byte [0-9]+: 5 bytes after the END section");
    // A reserved field set (the section checksum made right again).
    std::string reserved = bytes;
    reserved[16 + 6] = 1;
    uint32_t length = 0;
    std::memcpy(&length, &reserved[16 + 8], 4);
    const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(&reserved[16]), uInt(12 + length)));
    std::memcpy(&reserved[16 + 12 + length], &crc, 4);
    write("reserved.bpm", reserved);
    expect_refused(go("bodygen", "info reserved.bpm"), "^bodygen: reserved.bpm: .*reserved field .* not 0");
}

TEST_F(Hostile, ViewerOptionsOutsideTheirRangeAreRefused) {
    write("t.obj", kTriangleObj);
    expect_refused(go("bodyview", "--headless --line-width -3 --model t.obj --screenshot x.png"),
                   "^bodyview: --line-width must be in");
    expect_refused(go("bodyview", "--headless --size 64x64 --select nosuch --model t.obj --screenshot x.png"),
                   "^bodyview: --select 'nosuch': no model or structure of that name");
    fs::create_directories(path("r.replay"));
    expect_refused(go("bodyview", "--headless --replay r.replay --model t.obj"), "^bodyview: r.replay: is a directory");
    EXPECT_FALSE(fs::exists(path("x.png")));
}

// ---------------------------------------------------------------- messages

TEST_F(Hostile, ControlCharactersFromFilesAreEscaped) {
    write("ctl.obj", "v 0 0 0\nv 1 0 \x1b[31mred\nv 0 1 0\nf 1 2 3\n");
    auto r = go("bodygen", "lod ctl.obj -o out.bpm");
    expect_refused(r, "^bodygen: ctl.obj: line 2: vertex coordinate '\\\\x1b\\[31mred' is not a number");
    EXPECT_EQ(r.output.find('\x1b'), std::string::npos);
}

}  // namespace
}  // namespace body
