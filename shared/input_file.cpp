#include "shared/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace body {

Result<uint64_t> regular_file_size(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        if (errno == ENOENT) return input_error(path + ": no such file");
        return input_error(path + ": cannot open: " + std::strerror(errno));
    }
    if (S_ISREG(st.st_mode)) return uint64_t(st.st_size);
    if (S_ISDIR(st.st_mode)) return input_error(path + ": is a directory, not a file");
    if (S_ISFIFO(st.st_mode)) return input_error(path + ": is a FIFO, not a regular file");
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return input_error(path + ": is a device, not a regular file");
    if (S_ISSOCK(st.st_mode)) return input_error(path + ": is a socket, not a regular file");
    return input_error(path + ": not a regular file");
}

Status check_regular_file(const std::string& path) {
    auto size = regular_file_size(path);
    if (!size) return size.error();
    return ok_status();
}

Status check_output_apart(const std::string& output, std::initializer_list<std::string> inputs) {
    return check_output_apart(output, std::span<const std::string>(inputs.begin(), inputs.size()));
}

Status check_output_apart(const std::string& output, std::span<const std::string> inputs) {
    namespace fs = std::filesystem;
    std::error_code ec;
    struct stat out_st {};
    const bool out_exists = ::stat(output.c_str(), &out_st) == 0;
    if (out_exists && !S_ISREG(out_st.st_mode) && !S_ISDIR(out_st.st_mode)) {
        auto what = regular_file_size(output);  // names what it is
        return input_error((what ? output + ": not a regular file" : what.error().message) + "; not writing there");
    }
    fs::path out_path = fs::weakly_canonical(fs::path(output), ec);
    if (ec) out_path = fs::absolute(fs::path(output), ec).lexically_normal();
    const std::string out_dir = out_path.string() + "/";
    for (const std::string& input : inputs) {
        if (input.empty()) continue;
        struct stat in_st {};
        const bool same_inode = out_exists && ::stat(input.c_str(), &in_st) == 0 && in_st.st_dev == out_st.st_dev &&
                                in_st.st_ino == out_st.st_ino;
        std::error_code ec2;
        const fs::path in_path = fs::weakly_canonical(fs::path(input), ec2);
        const bool same_path = !ec2 && in_path == out_path;
        const bool inside = !ec2 && in_path.string().starts_with(out_dir) &&
                            (output.ends_with("/") || (out_exists && S_ISDIR(out_st.st_mode)));
        if (same_inode || same_path) return input_error(output + ": is the input " + input + "; not overwriting it");
        if (inside) return input_error(output + ": contains the input " + input + "; not replacing it");
    }
    return ok_status();
}

namespace {
void put_hex(std::string& out, unsigned char c) {
    static const char* hex = "0123456789abcdef";
    out += "\\x";
    out += hex[c >> 4];
    out += hex[c & 15];
}
}  // namespace

std::string escape_for_message(std::string_view text, size_t max) {
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
        if (out.size() >= max) {
            out += "...";
            break;
        }
        const auto c = static_cast<unsigned char>(text[i]);
        if (c == '\\') {
            out += "\\\\";
        } else if (c < 0x20 || c >= 0x7f) {
            put_hex(out, c);
        } else {
            out += char(c);
        }
    }
    return out;
}

std::string escape_control_characters(std::string_view text) {
    std::string out;
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c == 0x7f) {
            put_hex(out, c);
        } else {
            out += ch;
        }
    }
    return out;
}

}  // namespace body
