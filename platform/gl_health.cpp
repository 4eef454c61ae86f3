// The GL context's health (contract in gl_health.h).
#include "platform/gl_health.h"

#include <EGL/egl.h>

#include <initializer_list>

namespace body::platform {
namespace {

using ResetStatusFn = GLenum (*)();

// glGetGraphicsResetStatus{,EXT,KHR}: core in GLES 3.2, an extension before.
ResetStatusFn reset_status_function() {
    static const ResetStatusFn fn = [] {
        for (const char* name :
             {"glGetGraphicsResetStatus", "glGetGraphicsResetStatusKHR", "glGetGraphicsResetStatusEXT"})
            if (auto f = reinterpret_cast<ResetStatusFn>(eglGetProcAddress(name))) return f;
        return ResetStatusFn{nullptr};
    }();
    return fn;
}

}  // namespace

GlHealth read_gl_health() {
    GlHealth h;
    // A lost context may report GL_CONTEXT_LOST for ever: bounded.
    for (int i = 0; i < 16; ++i) {
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        if (h.errors++ == 0) h.first_error = e;
        h.out_of_memory = h.out_of_memory || e == GL_OUT_OF_MEMORY;
    }
    if (ResetStatusFn fn = reset_status_function()) h.reset_status = fn();
    return h;
}

}  // namespace body::platform
