// EGL context creation for OpenGL ES 3.0 (Khronos EGL 1.5, EGL_EXT_platform_base,
// EGL_MESA_platform_surfaceless, EGL_KHR_platform_gbm).
#include "platform/egl_context.h"

#include <cstring>
#include <vector>

namespace body::platform {

std::string egl_error_string(EGLint error) {
    switch (error) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
        case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    }
    return "EGL error " + std::to_string(error);
}

bool egl_has_extension(const char* list, const char* name) {
    if (!list) return false;
    size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

namespace {

Error egl_failure(const char* what) {
    return runtime_error(std::string("EGL: ") + what + " failed (" + egl_error_string(eglGetError()) + ")");
}

EGLDisplay get_display(EGLenum platform, void* native_display) {
    if (platform == 0) return eglGetDisplay(static_cast<EGLNativeDisplayType>(native_display));
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!egl_has_extension(client, "EGL_EXT_platform_base")) return EGL_NO_DISPLAY;
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display) return EGL_NO_DISPLAY;
    return get_platform_display(platform, native_display, nullptr);
}

}  // namespace

Result<std::unique_ptr<EglContext>> EglContext::open(EGLenum platform, void* native_display, EGLint surface_bits,
                                                     EGLint native_visual) {
    auto ctx = std::make_unique<EglContext>();
    ctx->display_ = get_display(platform, native_display);
    if (ctx->display_ == EGL_NO_DISPLAY) return runtime_error("EGL: no display for this platform");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(ctx->display_, &major, &minor)) {
        ctx->display_ = EGL_NO_DISPLAY;
        return egl_failure("eglInitialize");
    }
    if (!eglBindAPI(EGL_OPENGL_ES_API)) return egl_failure("eglBindAPI(GLES)");

    std::vector<EGLint> attribs = {
        EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT,   EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
        EGL_DEPTH_SIZE,      surface_bits ? 24 : 0};
    attribs.insert(attribs.end(), {EGL_SURFACE_TYPE, surface_bits});
    // A stencil buffer for the cut plane's caps (kiosk/render/styles/cut_cap.h);
    // a display without one still runs, its cut sections left open.
    if (surface_bits) attribs.insert(attribs.end(), {EGL_STENCIL_SIZE, 8});
    attribs.push_back(EGL_NONE);
    EGLint count = 0;
    eglChooseConfig(ctx->display_, attribs.data(), nullptr, 0, &count);
    if (count <= 0 && surface_bits) {
        attribs.resize(attribs.size() - 3);
        attribs.push_back(EGL_NONE);
        eglChooseConfig(ctx->display_, attribs.data(), nullptr, 0, &count);
    }
    if (count <= 0) return runtime_error("EGL: no GLES 3 config with RGB888 and depth");
    std::vector<EGLConfig> configs(static_cast<size_t>(count));
    eglChooseConfig(ctx->display_, attribs.data(), configs.data(), count, &count);
    ctx->config_ = configs[0];
    if (native_visual != 0) {
        bool found = false;
        for (EGLint i = 0; i < count && !found; ++i) {
            EGLint id = 0;
            if (eglGetConfigAttrib(ctx->display_, configs[static_cast<size_t>(i)], EGL_NATIVE_VISUAL_ID, &id) &&
                id == native_visual) {
                ctx->config_ = configs[static_cast<size_t>(i)];
                found = true;
            }
        }
        if (!found) return runtime_error("EGL: no config matches the scan-out format");
    }
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
    ctx->context_ = eglCreateContext(ctx->display_, ctx->config_, EGL_NO_CONTEXT, context_attribs);
    if (ctx->context_ == EGL_NO_CONTEXT) return egl_failure("eglCreateContext(GLES 3.0)");
    return ctx;
}

Result<std::unique_ptr<EglContext>> EglContext::open_first_device() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    // EGL_EXT_device_base is the older name of enumeration + query together
    // (NVIDIA's driver through libglvnd lists only that one).
    if (!egl_has_extension(client, "EGL_EXT_platform_device") ||
        !(egl_has_extension(client, "EGL_EXT_device_enumeration") || egl_has_extension(client, "EGL_EXT_device_base")))
        return runtime_error("EGL: no device platform (EGL_EXT_platform_device, EGL_EXT_device_enumeration)");
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (!query_devices) return runtime_error("EGL: eglQueryDevicesEXT missing");
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!query_devices(16, devices, &count) || count <= 0) return runtime_error("EGL: no EGL device");
    Error last = runtime_error("EGL: no EGL device");
    for (EGLint i = 0; i < count; ++i) {
        auto ctx = open(EGL_PLATFORM_DEVICE_EXT, devices[i], 0, 0);
        if (!ctx) {
            last = ctx.error();
            continue;
        }
        if (!egl_has_extension(eglQueryString(ctx.value()->display_, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
            last = runtime_error("EGL: device " + std::to_string(i) + " lacks EGL_KHR_surfaceless_context");
            continue;
        }
        if (auto s = ctx.value()->make_current(); !s) {
            last = s.error();
            continue;
        }
        return ctx;
    }
    return last;
}

EglContext::~EglContext() {
    if (display_ == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    // No eglTerminate: the EGLDisplay is shared by every context on the same
    // platform in this process, and terminating it would kill the others.
}

Status EglContext::create_window_surface(void* native_window) {
    // EGLNativeWindowType differs per window system (a pointer for GBM, an XID
    // for X11), so the caller hands over an opaque pointer.
    surface_ = eglCreateWindowSurface(display_, config_, reinterpret_cast<EGLNativeWindowType>(native_window), nullptr);
    if (surface_ == EGL_NO_SURFACE) return egl_failure("eglCreateWindowSurface");
    return ok_status();
}

Status EglContext::replace_window_surface(void* native_window) {
    const EGLSurface old = surface_;
    if (auto s = create_window_surface(native_window); !s) {
        surface_ = old;
        return s;
    }
    if (auto s = make_current(); !s) {
        eglDestroySurface(display_, surface_);
        surface_ = old;
        return s;
    }
    if (old != EGL_NO_SURFACE) eglDestroySurface(display_, old);
    return ok_status();
}

Status EglContext::create_pbuffer_surface(int width, int height) {
    const EGLint attribs[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
    surface_ = eglCreatePbufferSurface(display_, config_, attribs);
    if (surface_ == EGL_NO_SURFACE) return egl_failure("eglCreatePbufferSurface");
    return ok_status();
}

Status EglContext::make_current() {
    if (!eglMakeCurrent(display_, surface_, surface_, context_)) return egl_failure("eglMakeCurrent");
    return ok_status();
}

Status EglContext::swap_buffers() {
    if (!eglSwapBuffers(display_, surface_)) return egl_failure("eglSwapBuffers");
    return ok_status();
}

}  // namespace body::platform
