#pragma once
// The platform layer: one small interface over window systems and GL contexts.
// Backends: headless_* (EGL surfaceless, always built), glfw_* (desktop),
// drm_* (DRM/KMS + GBM + EGL on boards without a desktop). Chosen at run time.
#include <memory>
#include <string>
#include <vector>

#include "shared/error.h"

namespace body::platform {

enum class Backend { Auto, Headless, Glfw, Drm };

// Backends compiled into this binary, in auto-selection order (headless last).
std::vector<Backend> compiled_backends();
const char* backend_name(Backend backend);
Result<Backend> parse_backend(const std::string& name);

}  // namespace body::platform
