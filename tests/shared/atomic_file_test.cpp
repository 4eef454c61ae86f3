#include "shared/atomic_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <vector>

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

// A signal in the middle of a directory write (the kiosk bundle's and
// build -o DIR/'s case) removes the staged tree whole, nested files included,
// and the scratch directory of a ScratchPath too; the old directory stays.
TEST(AtomicFile, SignalDuringADirectoryWriteRemovesTheStagedTree) {
    for (int sig : {SIGINT, SIGTERM}) {
        fs::path dir = fresh_dir("signal");
        const std::string out = (dir / "bundle").string();
        fs::create_directories(out);
        { std::ofstream(out + "/old.txt") << "old"; }
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            remove_temporaries_on_signal();
            const ScratchPath scratch(out + ".work");
            fs::create_directories(scratch.path() + "/models");
            { std::ofstream(scratch.path() + "/models/m.bpm") << "scratch"; }
            (void)write_directory_atomically(
                out,
                [&](const std::string& staged) {
                    fs::create_directories(staged + "/models/deeper");
                    for (int k = 0; k < 300; ++k)  // more entries than one getdents64 buffer
                        std::ofstream(staged + "/models/m" + std::to_string(k) + ".bpm") << "data";
                    std::ofstream(staged + "/models/deeper/x") << "x";
                    ::raise(sig);
                    return ok_status();
                },
                [](const std::string&) { return std::string(); });
            ::_exit(3);  // not reached: the signal ends the process
        }
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
        EXPECT_EQ(WTERMSIG(status), sig);
        std::vector<std::string> left;
        for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
        EXPECT_EQ(left, std::vector<std::string>{"bundle"}) << "left: " << left.size() << " entries";
        std::ifstream old(out + "/old.txt");
        std::string text;
        old >> text;
        EXPECT_EQ(text, "old");
        fs::remove_all(dir);
    }
}

}  // namespace
}  // namespace body
