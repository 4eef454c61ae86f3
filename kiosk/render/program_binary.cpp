// Linked programs kept as driver binaries (contract in program_binary.h).
// File: "BVPB", u32 binary format, u32 key length, the key, the binary.
#include "kiosk/render/program_binary.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <vector>

#include "shared/atomic_file.h"
#include "shared/input_file.h"

namespace body::render {
namespace {

constexpr char kMagic[4] = {'B', 'V', 'P', 'B'};
constexpr size_t kHeader = 12;

std::string& dir_setting() {
    static std::string dir;
    return dir;
}
size_t loaded = 0;

std::string file_for(const std::string& key) {
    char name[32];
    std::snprintf(name, sizeof name, "%016zx.bin", std::hash<std::string>{}(key));
    return dir_setting() + "/" + name;
}

// The whole file, or empty (absent, unreadable, not a regular file, 64 MiB or more).
std::string read_whole(const std::string& path) {
    if (auto size = regular_file_size(path); !size || *size >= (64u << 20)) return {};
    auto bytes = read_file(path);
    return bytes ? std::move(bytes).value() : std::string();
}

uint32_t get_u32(const uint8_t* p) {
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

}  // namespace

std::string default_program_binary_dir() {
    const auto env = [](const char* name) {
        const char* v = std::getenv(name);
        return std::string(v ? v : "");
    };
    const std::string off = env("MESA_SHADER_CACHE_DISABLE");
    if (off == "1" || off == "true" || off == "y" || off == "yes") return {};
    if (const std::string mesa = env("MESA_SHADER_CACHE_DIR"); !mesa.empty()) return mesa + "/bodyview_programs";
    if (const std::string xdg = env("XDG_CACHE_HOME"); !xdg.empty()) return xdg + "/bodyview/programs";
    if (const std::string home = env("HOME"); !home.empty()) return home + "/.cache/bodyview/programs";
    return {};
}

void set_program_binary_dir(std::string dir) { dir_setting() = std::move(dir); }
const std::string& program_binary_dir() { return dir_setting(); }
size_t program_binaries_loaded() { return loaded; }

GLuint load_program_binary(const std::string& key) {
    if (dir_setting().empty()) return 0;
    const std::string file = read_whole(file_for(key));
    const auto* f = reinterpret_cast<const uint8_t*>(file.data());
    if (file.size() <= kHeader || std::memcmp(f, kMagic, 4) != 0) return 0;
    const uint32_t format = get_u32(f + 4), key_size = get_u32(f + 8);
    if (key_size != key.size() || file.size() <= kHeader + key_size ||
        std::memcmp(f + kHeader, key.data(), key_size) != 0)
        return 0;
    // A format this driver does not offer (another driver wrote it) is skipped: glProgramBinary would raise
    // GL_INVALID_ENUM, which the kiosk's frame check would count.
    GLint count = 0;
    glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &count);
    std::vector<GLint> formats(size_t(std::max(count, 0)));
    if (count > 0) glGetIntegerv(GL_PROGRAM_BINARY_FORMATS, formats.data());
    if (std::find(formats.begin(), formats.end(), GLint(format)) == formats.end()) return 0;
    const GLuint id = glCreateProgram();
    const size_t at = kHeader + key_size;
    glProgramBinary(id, format, f + at, GLsizei(file.size() - at));
    GLint ok = 0;
    glGetProgramiv(id, GL_LINK_STATUS, &ok);
    if (!ok) {  // refused (another driver version): no GL error, LINK_STATUS false
        glDeleteProgram(id);
        return 0;
    }
    ++loaded;
    return id;
}

void save_program_binary(const std::string& key, GLuint program) {
    if (dir_setting().empty()) return;
    GLint length = 0;
    glGetProgramiv(program, GL_PROGRAM_BINARY_LENGTH, &length);
    if (length <= 0) return;  // the driver offers no binary format
    std::vector<uint8_t> f(kHeader + key.size() + size_t(length));
    GLenum format = 0;
    GLsizei written = 0;
    glGetProgramBinary(program, length, &written, &format, f.data() + kHeader + key.size());
    if (written <= 0) return;
    f.resize(kHeader + key.size() + size_t(written));
    const uint32_t header[2] = {format, uint32_t(key.size())};
    std::memcpy(f.data(), kMagic, 4);
    std::memcpy(f.data() + 4, header, 8);
    std::memcpy(f.data() + kHeader, key.data(), key.size());
    std::error_code ec;
    std::filesystem::create_directories(dir_setting(), ec);
    (void)write_file_atomically(file_for(key), f);
}

}  // namespace body::render
