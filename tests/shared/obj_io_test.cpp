#include "shared/obj_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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
