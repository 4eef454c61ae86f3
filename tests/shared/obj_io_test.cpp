#include "shared/obj_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace body {
namespace {

namespace fs = std::filesystem;

TEST(ObjIo, RoundTripsTwoNamedObjects) {
    Mesh a, b;
    a.name = "left";
    a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    a.indices = {0, 1, 2};
    b.name = "right";
    b.positions = {{2, 0, 0}, {3, 0, 0}, {2, 1, 0.25}, {3, 1, 0}};
    b.indices = {0, 1, 2, 1, 3, 2};
    std::string path = (fs::temp_directory_path() / ("body_obj_" + std::to_string(::getpid()) + ".obj")).string();
    std::vector<Mesh> meshes{a, b};
    ASSERT_TRUE(write_obj(path, meshes, {.normals = true}).ok());
    auto back = read_obj(path);
    ASSERT_TRUE(back.ok()) << back.error().message;
    ASSERT_EQ(back->size(), 2u);
    EXPECT_EQ((*back)[0].name, "left");
    EXPECT_EQ((*back)[1].name, "right");
    EXPECT_EQ((*back)[1].triangle_count(), 2u);
    EXPECT_DOUBLE_EQ((*back)[1].positions[2].z, 0.25);
    fs::remove(path);
}

// Rows spelled on threads (blocks of rows, written in order): the same bytes
// as one thread, with and without normals, for a mesh over two blocks whose
// block count is not a multiple of the threads, after a small first object.
TEST(ObjIo, ThreadedWritingGivesTheSameFile) {
    Mesh small, large;
    small.name = "small";
    small.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    small.indices = {0, 1, 2};
    large.name = "large";
    const uint32_t n = 100003;
    for (uint32_t i = 0; i < n; ++i)
        large.positions.push_back({std::sin(0.001 * i), std::cos(0.0007 * i) * 3.5, 1e-3 * i - 40.0});
    for (uint32_t i = 0; i + 2 < n; ++i) large.indices.insert(large.indices.end(), {i, i + 1, i + 2});
    const std::vector<Mesh> meshes{small, large};
    const fs::path dir = fs::temp_directory_path();
    auto text = [](const std::string& path) {
        std::ifstream f(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(f), {});
    };
    for (bool normals : {false, true}) {
        const std::string one = (dir / ("body_obj_one_" + std::to_string(::getpid()) + ".obj")).string();
        ASSERT_TRUE(write_obj(one, meshes, {.normals = normals, .threads = 1}).ok());
        const std::string serial = text(one);
        EXPECT_GT(serial.size(), 4000000u);
        for (unsigned threads : {2u, 3u}) {
            const std::string many = (dir / ("body_obj_many_" + std::to_string(::getpid()) + ".obj")).string();
            ASSERT_TRUE(write_obj(many, meshes, {.normals = normals, .threads = threads}).ok());
            EXPECT_EQ(text(many), serial) << "normals " << normals << " threads " << threads;
            fs::remove(many);
        }
        fs::remove(one);
    }
}

TEST(ObjIo, MissingAndEmptyFilesAreInputErrors) {
    auto missing = read_obj("/nonexistent.obj");
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().exit_code, kExitBadInput);
    std::string path = (fs::temp_directory_path() / ("body_empty_" + std::to_string(::getpid()) + ".obj")).string();
    { std::ofstream(path) << "# nothing\n"; }
    auto empty = read_obj(path);
    ASSERT_FALSE(empty.ok());
    EXPECT_NE(empty.error().message.find("no triangles"), std::string::npos);
    fs::remove(path);
}

}  // namespace
}  // namespace body

namespace body {
namespace {

TEST(ObjIo, UnnamedObjectTakesTheFileStem) {
    std::string path =
        (std::filesystem::temp_directory_path() / ("body_stem_" + std::to_string(::getpid()) + ".obj")).string();
    { std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"; }
    auto m = read_obj(path);
    ASSERT_TRUE(m.ok()) << m.error().message;
    EXPECT_EQ((*m)[0].name, "body_stem_" + std::to_string(::getpid()));
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace body

namespace body {
namespace {

// The reader's check takes common spellings on a fast path and sends the rest to the
// full parse: both sides of each edge of that path give the answer the full parse gives.
TEST(ObjIo, NumbersAndCornersAtTheEdgesOfThePlainSpelling) {
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n";
    for (const char* good : {"v +.5 1. -2e+3\n", "v 9e37 -0009e37 1e-9999\n", "v 1e38 2.9e38 0\n",
                             "v 1.5E2 00000000000000000000000000000000000000000001 0\n", "f 1//1 2//1 3//1\n",
                             "f -1 -2 -3\n", "f 3 2 1 1\n"}) {
        auto m = parse_obj(tri + good + "f 1 2 3\n", "t.obj");
        EXPECT_TRUE(m.ok()) << good << ": " << m.error().message;
    }
    const struct {
        const char* line;
        const char* why;
    } bad[] = {
        {"v 1e39 0 0\n", "is not a finite float"},
        {"v 0 0 -4e38\n", "is not a finite float"},
        {"v 1e 0 0\n", "is not a number"},
        {"v . 0 0\n", "is not a number"},
        {"v 1..5 0 0\n", "is not a number"},
        {"f 1 2 -0\n", "outside 1..3"},
        {"f 1 2 4\n", "outside 1..3"},
        {"f 1 2 -4\n", "outside 1..3"},
        {"f 1/ 2 3\n", "is not an index"},
        {"f 1/1/1/1 2 3\n", "more than 3 parts"},
        {"f 1//2 2 3\n", "normal index 2 is outside 1..1"},
        {"f 1 2 3x\n", "is not an index"},
    };
    for (const auto& b : bad) {
        auto m = parse_obj(tri + b.line, "t.obj");
        ASSERT_FALSE(m.ok()) << b.line;
        EXPECT_NE(m.error().message.find(b.why), std::string::npos) << b.line << ": " << m.error().message;
        EXPECT_NE(m.error().message.find("t.obj: line 5: "), std::string::npos) << m.error().message;
    }
}

}  // namespace
}  // namespace body

namespace body {
namespace {

// Coordinates are spelled exactly as printf's %.Ng spells them, at the default
// precision and others: across magnitudes, at the switch to exponent form, at
// roundings that carry into a new digit, and near halves of the last digit.
TEST(ObjIo, CoordinatesAreSpelledAsPrintfGeneral) {
    std::vector<double> values = {0.0,
                                  -0.0,
                                  1.0,
                                  0.1,
                                  -2.5e-5,
                                  1e-5,
                                  9.99999999e-5,
                                  0.0001,
                                  123456789.0,
                                  999999999.5,
                                  1234567890.0,
                                  0.1234567885,
                                  0.12345678850000001,
                                  -7.000000005,
                                  5e-324,
                                  1.7976931348623157e308};
    uint64_t state = 12345;
    for (int i = 0; i < 3000; ++i) {  // a fixed pseudo-random spread over 40 decades
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const double unit = double(state >> 11) * 0x1p-53 - 0.5;
        values.push_back(unit * std::pow(10.0, int(state % 40) - 20));
    }
    while (values.size() % 3 != 0) values.push_back(0.5);
    Mesh mesh;
    mesh.name = "numbers";
    for (size_t i = 0; i < values.size(); i += 3) mesh.positions.push_back({values[i], values[i + 1], values[i + 2]});
    const std::string path =
        (fs::temp_directory_path() / ("body_obj_g_" + std::to_string(::getpid()) + ".obj")).string();
    for (int precision : {9, 6, 15, 17}) {
        ASSERT_TRUE(write_obj(path, std::span<const Mesh>(&mesh, 1), {.precision = precision}).ok());
        std::ifstream in(path);
        std::string line;
        size_t row = 0;
        while (std::getline(in, line)) {
            if (line.rfind("v ", 0) != 0) continue;
            ASSERT_LT(row, mesh.positions.size());
            std::string expected = "v";
            for (int k = 0; k < 3; ++k) {
                char text[64];
                std::snprintf(text, sizeof(text), " %.*g", precision, mesh.positions[row][k]);
                expected += text;
            }
            EXPECT_EQ(line, expected) << "precision " << precision;
            ++row;
        }
        EXPECT_EQ(row, mesh.positions.size());
    }
    fs::remove(path);
}

}  // namespace
}  // namespace body
