// libFuzzer target for the PLY, STL, GLB and glTF checks that run before assimp
// (builder/mesh_import/ply_check.h, stl_check.h, glb_check.h, gltf_check.h): ok or one error
// line naming the file, never a crash or a read outside the input. The glTF check reads a
// .glb only after the GLB check passed it, as mesh_import does.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "builder/mesh_import/glb_check.h"
#include "builder/mesh_import/gltf_check.h"
#include "builder/mesh_import/ply_check.h"
#include "builder/mesh_import/stl_check.h"

namespace {

void expect_one_line(const body::Status& s, const char* path) {
    if (s.ok()) return;
    const std::string& m = s.error().message;
    if (m.rfind(std::string(path) + ": ", 0) != 0 || m.find('\n') != std::string::npos) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    expect_one_line(body::check_ply_bytes(bytes, "fuzz.ply"), "fuzz.ply");
    expect_one_line(body::check_stl_bytes(bytes, "fuzz.stl"), "fuzz.stl");
    const body::Status glb = body::check_glb_bytes(bytes, "fuzz.glb");
    expect_one_line(glb, "fuzz.glb");
    if (glb.ok()) expect_one_line(body::check_gltf_bytes(bytes, true, "fuzz.glb", "/nonexistent"), "fuzz.glb");
    expect_one_line(body::check_gltf_bytes(bytes, false, "fuzz.gltf", "/nonexistent"), "fuzz.gltf");
    return 0;
}
