#include "platform/platform.h"

namespace body::platform {

std::vector<Backend> compiled_backends() {
    std::vector<Backend> out;
#ifdef BODY_WITH_GLFW
    out.push_back(Backend::Glfw);
#endif
#ifdef BODY_WITH_DRM
    out.push_back(Backend::Drm);
#endif
    out.push_back(Backend::Headless);
    return out;
}

const char* backend_name(Backend backend) {
    switch (backend) {
        case Backend::Auto: return "auto";
        case Backend::Headless: return "headless";
        case Backend::Glfw: return "glfw";
        case Backend::Drm: return "drm";
    }
    return "?";
}

Result<Backend> parse_backend(const std::string& name) {
    for (Backend b : {Backend::Auto, Backend::Headless, Backend::Glfw, Backend::Drm})
        if (name == backend_name(b)) return b;
    return input_error("unknown platform '" + name + "' (expected auto, glfw, drm or headless)");
}

}  // namespace body::platform
