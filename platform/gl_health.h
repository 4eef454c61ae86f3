#pragma once
// The GL context's health, read once per frame by the kiosk loop: the errors
// raised since the last check (GL_OUT_OF_MEMORY among them) and whether the
// context was lost to a GPU reset (GL_EXT_robustness / GL_KHR_robustness'
// glGetGraphicsResetStatus, where the driver offers it; a context created
// without a reset notification strategy always reads "no reset").
#include <GLES3/gl3.h>

namespace body::platform {

struct GlHealth {
    int errors = 0;              // glGetError values other than GL_NO_ERROR
    bool out_of_memory = false;  // one of them was GL_OUT_OF_MEMORY
    GLenum first_error = GL_NO_ERROR;
    GLenum reset_status = GL_NO_ERROR;  // GUILTY/INNOCENT/UNKNOWN_CONTEXT_RESET: the context is gone
    bool context_lost() const { return reset_status != GL_NO_ERROR; }
};

// Drains the current context's error flags and reads its reset status.
GlHealth read_gl_health();

}  // namespace body::platform
