// libFuzzer target for the OBJ reader (our line checks, then tinyobjloader):
// meshes or one error line naming the file, never a crash; every accepted
// vertex finite and every index inside its mesh.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "shared/obj_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    auto meshes = body::parse_obj(text, "fuzz.obj");
    if (!meshes.ok()) {
        const std::string& m = meshes.error().message;
        if (m.rfind("fuzz.obj: ", 0) != 0 || m.find('\n') != std::string::npos) std::abort();
        return 0;
    }
    for (const body::Mesh& mesh : *meshes) {
        for (const body::Vec3& p : mesh.positions)
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) std::abort();
        for (uint32_t i : mesh.indices)
            if (i >= mesh.positions.size()) std::abort();
    }
    return 0;
}
