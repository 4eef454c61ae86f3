// STL/PLY to .bpm through bodygen (contract in model_convert.h).
#include "kiosk/author/model_convert.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace body::kiosk::author {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const std::string& file) {
    std::string ext = fs::path(file).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

// bodygen beside this executable (an install or a build tree), else the first on PATH.
std::string find_bodygen() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (!ec && fs::is_regular_file(self.parent_path() / "bodygen", ec))
        return (self.parent_path() / "bodygen").string();
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "";
    for (size_t at = 0; at <= dirs.size();) {
        const size_t end = std::min(dirs.find(':', at), dirs.size());
        const fs::path candidate = fs::path(dirs.substr(at, end - at)) / "bodygen";
        if (end > at && access(candidate.c_str(), X_OK) == 0) return candidate.string();
        at = end + 1;
    }
    return {};
}

}  // namespace

bool needs_conversion(const std::string& file) {
    const std::string ext = lower_extension(file);
    return ext == ".stl" || ext == ".ply";
}

Result<std::string> convert_to_bpm(const std::string& file, const std::string& models_dir) {
    const std::string bodygen = find_bodygen();
    if (bodygen.empty())
        return runtime_error(file + ": converting it needs bodygen (not found beside bodyview or on PATH)");
    std::error_code ec;
    fs::create_directories(models_dir, ec);
    if (ec) return runtime_error(models_dir + ": cannot create the models folder: " + ec.message());
    const std::string stem = fs::path(file).stem().string();
    fs::path out = fs::path(models_dir) / (stem + ".bpm");
    for (int n = 2; fs::exists(out, ec); ++n) out = fs::path(models_dir) / (stem + "-" + std::to_string(n) + ".bpm");
    const fs::path log = out.string() + ".log";

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    std::vector<std::string> args{bodygen, "lod", file, "-o", out.string(), "--quiet"};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, bodygen.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    int status = 0;
    if (spawned == 0) waitpid(pid, &status, 0);
    std::string why;
    if (std::ifstream in(log); in) std::getline(in, why);
    fs::remove(log, ec);
    if (spawned != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fs::remove(out, ec);
        if (why.rfind("bodygen: ", 0) == 0) why = why.substr(9);
        if (why.empty()) why = file + ": bodygen lod failed";
        return input_error(why);
    }
    return out.string();
}

}  // namespace body::kiosk::author
