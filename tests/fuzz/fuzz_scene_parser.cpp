// libFuzzer target for the scene manifest parser: a scene or one error line
// naming the file, never a crash.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "shared/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    auto scene = body::scene::parse_scene(text, "fuzz.json", "/nonexistent-bundle");
    if (!scene.ok()) {
        const std::string& m = scene.error().message;
        if (m.find('\n') != std::string::npos) std::abort();
    }
    return 0;
}
