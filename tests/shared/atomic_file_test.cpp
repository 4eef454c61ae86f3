#include "shared/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace body {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const char* name) {
    fs::path dir = fs::temp_directory_path() / (std::string("body_atomic_") + name + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(AtomicFile, WritesAndReadsBack) {
    fs::path dir = fresh_dir("ok");
    std::string path = (dir / "a.txt").string();
    ASSERT_TRUE(write_file_atomically(path, [](std::ostream& o) {
                    o << "hello";
                    return std::string();
                }).ok());
    auto text = read_file(path);
    ASSERT_TRUE(text.ok());
    EXPECT_EQ(*text, "hello");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    fs::remove_all(dir);
}

TEST(AtomicFile, FailureLeavesOldFileAndNoTemporary) {
    fs::path dir = fresh_dir("fail");
    std::string path = (dir / "a.txt").string();
    { std::ofstream(path) << "old"; }
    auto st = write_file_atomically(path, [](std::ostream& o) {
        o << "partial";
        return std::string("boom");
    });
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().message.find(path), std::string::npos);
    EXPECT_NE(st.error().message.find("boom"), std::string::npos);
    EXPECT_EQ(*read_file(path), "old");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    fs::remove_all(dir);
}

TEST(AtomicFile, MissingDirectoryIsAnErrorNamingThePath) {
    auto st = write_file_atomically("/nonexistent-dir/x/y.obj", std::span<const uint8_t>());
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().message.find("/nonexistent-dir/x/y.obj"), std::string::npos);
    EXPECT_FALSE(read_file("/nonexistent-dir/x/y.obj").ok());
}

}  // namespace
}  // namespace body
