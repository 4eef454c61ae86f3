#pragma once
// EGL display/config/context handling shared by the headless, GLFW-less DRM and
// any other EGL-based backend; independent of the window system. Creates an
// OpenGL ES 3.0 context. All failures come back as one-line errors.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <memory>
#include <string>

#include "shared/error.h"

namespace body::platform {

class EglContext {
public:
    EglContext() = default;
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    // Opens EGL on `platform` (EGL_PLATFORM_SURFACELESS_MESA, EGL_PLATFORM_GBM_KHR,
    // or 0 for the default display with `native_display` = EGL_DEFAULT_DISPLAY)
    // and creates a GLES 3 context. `surface_bits` is EGL_WINDOW_BIT,
    // EGL_PBUFFER_BIT or 0 (no surface); `native_visual` (a GBM format) filters
    // configs when non-zero.
    static Result<std::unique_ptr<EglContext>> open(EGLenum platform, void* native_display, EGLint surface_bits,
                                                    EGLint native_visual);

    // Opens a surfaceless GLES 3 context on the first EGL device that gives one
    // (EGL_EXT_platform_device) and makes it current: for drivers that offer
    // EGL devices but not the Mesa surfaceless platform. (NVIDIA's 580 driver
    // offers both; this path was checked on it.) Needs
    // EGL_KHR_surfaceless_context on that device.
    static Result<std::unique_ptr<EglContext>> open_first_device();

    Status create_window_surface(void* native_window);  // e.g. a gbm_surface*
    // A new window surface (the display changed size), made current; the old
    // one is destroyed. On failure the old one stays current.
    Status replace_window_surface(void* native_window);
    Status create_pbuffer_surface(int width, int height);
    Status make_current();
    Status swap_buffers();

    EGLDisplay display() const { return display_; }
    EGLConfig config() const { return config_; }
    EGLContext context() const { return context_; }
    EGLSurface surface() const { return surface_; }

private:
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLConfig config_ = nullptr;
    EGLContext context_ = EGL_NO_CONTEXT;
    EGLSurface surface_ = EGL_NO_SURFACE;
};

// Whether the space-separated extension `list` (may be null) holds `name`.
bool egl_has_extension(const char* list, const char* name);

// A short name for an EGL error code ("EGL_BAD_ALLOC").
std::string egl_error_string(EGLint error);

}  // namespace body::platform
