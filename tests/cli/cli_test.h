#pragma once
// Runs the built binaries as a user would and captures exit code and output.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace body::test {

struct RunResult {
    int exit_code = -1;
    std::string output;  // stdout and stderr together
};

inline std::string bin(const char* name) { return std::string(BODY_BINARY_DIR) + "/bin/" + name; }

inline RunResult run(const std::string& command) {
    RunResult r;
    std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
    int status = ::pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

}  // namespace body::test
