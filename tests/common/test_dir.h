#pragma once
// A scratch directory per test: TMP/<prefix>_<pid>_<test name>, removed first so
// a crashed earlier run leaves nothing behind, then created empty.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace body::test {

inline std::filesystem::path fresh_test_dir(const std::string& prefix) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()) + "_" +
                                                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace body::test
