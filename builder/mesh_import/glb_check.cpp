// GLB: The Khronos Group, "glTF 2.0 Specification", section 4.4 (binary glTF
// layout). Contract in glb_check.h.
#include "builder/mesh_import/glb_check.h"

#include <cstdint>

#include "shared/atomic_file.h"

namespace body {
namespace {

uint32_t u32_at(std::string_view b, size_t at) {
    return uint32_t(uint8_t(b[at])) | uint32_t(uint8_t(b[at + 1])) << 8 | uint32_t(uint8_t(b[at + 2])) << 16 |
           uint32_t(uint8_t(b[at + 3])) << 24;
}

Status fault(const std::string& path, size_t at, const std::string& reason) {
    return input_error(path + ": GLB byte " + std::to_string(at) + ": " + reason);
}

}  // namespace

Status check_glb_bytes(std::string_view bytes, const std::string& path) {
    if (bytes.size() < 12)
        return fault(path, 0, "a 12-byte header needed, the file has " + std::to_string(bytes.size()));
    if (bytes.substr(0, 4) != "glTF") return fault(path, 0, "magic is not \"glTF\"");
    if (const uint32_t version = u32_at(bytes, 4); version != 2)
        return fault(path, 4, "version " + std::to_string(version) + ", only 2 is read");
    if (const uint32_t length = u32_at(bytes, 8); length != bytes.size())
        return fault(
            path, 8,
            "header length " + std::to_string(length) + " but the file has " + std::to_string(bytes.size()) + " bytes");
    size_t at = 12;
    for (int chunk = 0; at < bytes.size(); ++chunk) {
        if (bytes.size() - at < 8) return fault(path, at, "a chunk header needs 8 bytes");
        const uint64_t length = u32_at(bytes, at);
        const std::string_view type = bytes.substr(at + 4, 4);
        if (chunk == 0 && type != "JSON") return fault(path, at + 4, "the first chunk is not JSON");
        if (length > bytes.size() - at - 8)
            return fault(path, at, "chunk length " + std::to_string(length) + " runs past the end of the file");
        at += 8 + length;
    }
    if (at == 12) return fault(path, 12, "no JSON chunk");
    return ok_status();
}

Status check_glb_file(const std::string& path) {
    auto bytes = read_file(path);  // checks for a regular file first
    if (!bytes) return bytes.error();
    return check_glb_bytes(*bytes, path);
}

}  // namespace body
