// Backend names, selection (auto) and helpers shared by every backend.
#include "platform/platform.h"

#include <GLES3/gl3.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "platform/log.h"

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

namespace {
LogLevel g_log_level = LogLevel::Info;
}  // namespace

void set_log_level(LogLevel level) { g_log_level = level; }
LogLevel log_level() { return g_log_level; }

Result<LogLevel> parse_log_level(const std::string& text) {
    if (text == "error") return LogLevel::Error;
    if (text == "warning") return LogLevel::Warning;
    if (text == "info") return LogLevel::Info;
    if (text == "debug") return LogLevel::Debug;
    return input_error("--log-level: expected error, warning, info or debug, got '" + text + "'");
}

Result<std::pair<int, int>> parse_size(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w <= 0 || h <= 0 ||
        w > 16384 || h > 16384)
        return input_error("bad size '" + text + "' (expected WIDTHxHEIGHT, e.g. 1280x800)");
    return std::pair<int, int>{w, h};
}

#ifndef BODY_WITH_GLFW
Result<std::unique_ptr<Surface>> create_glfw_surface(const SurfaceOptions&) {
    return runtime_error("glfw: this bodyview was built without GLFW (BODY_WITH_GLFW=OFF)");
}
#endif
#ifndef BODY_WITH_DRM
Result<std::unique_ptr<Surface>> create_drm_surface(const SurfaceOptions&) {
    return runtime_error("drm: this bodyview was built without DRM/KMS (BODY_WITH_DRM=OFF)");
}
#endif

namespace {

bool display_server_present() {
    const char* x = std::getenv("DISPLAY");
    const char* w = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (w && *w);
}

bool drm_card_opens() {
    for (int i = 0; i < 10; ++i) {
        std::string path = "/dev/dri/card" + std::to_string(i);
        int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
        if (fd >= 0) {
            ::close(fd);
            return true;
        }
    }
    return false;
}

}  // namespace

std::string default_software_rasterizer_threads() {
    ::setenv("LP_NUM_THREADS", "0", 0);  // 0: keeps a value the user set
    return std::getenv("LP_NUM_THREADS");
}

Result<std::unique_ptr<Surface>> create_surface(const SurfaceOptions& options) {
    default_software_rasterizer_threads();
    switch (options.backend) {
        case Backend::Headless: return create_headless_surface(options);
        case Backend::Glfw: return create_glfw_surface(options);
        case Backend::Drm: return create_drm_surface(options);
        case Backend::Auto: break;
    }
    std::string tried;
#ifdef BODY_WITH_GLFW
    if (display_server_present()) {
        auto s = create_glfw_surface(options);
        if (s) return s;
        tried = s.error().message + "; ";
    } else {
        tried = "glfw: no DISPLAY or WAYLAND_DISPLAY; ";
    }
#else
    (void)display_server_present;
#endif
#ifdef BODY_WITH_DRM
    if (drm_card_opens()) {
        auto s = create_drm_surface(options);
        if (s) return s;
        tried += s.error().message;
    } else {
        tried += "drm: no /dev/dri/card* can be opened";
    }
#else
    (void)drm_card_opens;
#endif
    return runtime_error("no display: " + tried + " (use --platform headless for offscreen rendering)");
}

std::vector<uint8_t> read_pixels_rgba(unsigned framebuffer, int width, int height) {
    std::vector<uint8_t> rows(static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    // GL's first row is the bottom one; flip to top-first.
    const size_t stride = static_cast<size_t>(width) * 4;
    std::vector<uint8_t> line(stride);
    for (int y = 0; y < height / 2; ++y) {
        uint8_t* a = rows.data() + static_cast<size_t>(y) * stride;
        uint8_t* b = rows.data() + static_cast<size_t>(height - 1 - y) * stride;
        std::copy(a, a + stride, line.data());
        std::copy(b, b + stride, a);
        std::copy(line.data(), line.data() + stride, b);
    }
    return rows;
}

}  // namespace body::platform
