#include "shared/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "shared/input_file.h"

namespace body {

Status write_file_atomically(const std::string& path, const std::function<std::string(std::ostream&)>& write) {
    const std::string temp = path + ".tmp-" + std::to_string(::getpid());
    std::string reason;
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) return runtime_error(path + ": cannot create file: " + std::strerror(errno));
        reason = write(out);
        out.flush();
        if (reason.empty() && !out) reason = "write failed (disk full?)";
    }
    if (reason.empty() && std::rename(temp.c_str(), path.c_str()) != 0)
        reason = std::string("cannot rename temporary file: ") + std::strerror(errno);
    if (!reason.empty()) {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        return runtime_error(path + ": " + reason);
    }
    return ok_status();
}

Status write_file_atomically(const std::string& path, std::span<const uint8_t> bytes) {
    return write_file_atomically(path, [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        return std::string();
    });
}

Result<std::string> read_file(const std::string& path) {
    if (auto regular = check_regular_file(path); !regular) return regular.error();
    std::ifstream in(path, std::ios::binary);
    if (!in) return input_error(path + ": cannot open: " + std::strerror(errno));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) return input_error(path + ": read failed");
    return buffer.str();
}

}  // namespace body
