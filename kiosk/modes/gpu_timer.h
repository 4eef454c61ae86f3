#pragma once
// The GPU time of one frame, where the driver offers GL_EXT_disjoint_timer_query
// (the benchmark's third clock beside wall and CPU time). A context must be current.
#include <EGL/egl.h>
#include <GLES3/gl3.h>
// After gl3.h: the extension prototypes build on its types.
#include <GLES2/gl2ext.h>

#include <limits>

#include "kiosk/render/gl_util.h"

namespace body::kiosk {

// On a real GPU the wall time of a frame also holds the CPU's submission and
// the glFinish round trip, the same for every style, which pull the wall ratios
// toward 1; the GPU time is what the style's shaders cost. Every backend's
// context is an EGL one, so eglGetProcAddress finds the extension's entries.
class GpuTimer {
public:
    GpuTimer() {
        if (!render::gl_has_extension("GL_EXT_disjoint_timer_query")) return;
        gen_ = reinterpret_cast<PFNGLGENQUERIESEXTPROC>(eglGetProcAddress("glGenQueriesEXT"));
        delete_ = reinterpret_cast<PFNGLDELETEQUERIESEXTPROC>(eglGetProcAddress("glDeleteQueriesEXT"));
        begin_ = reinterpret_cast<PFNGLBEGINQUERYEXTPROC>(eglGetProcAddress("glBeginQueryEXT"));
        end_ = reinterpret_cast<PFNGLENDQUERYEXTPROC>(eglGetProcAddress("glEndQueryEXT"));
        result_ = reinterpret_cast<PFNGLGETQUERYOBJECTUI64VEXTPROC>(eglGetProcAddress("glGetQueryObjectui64vEXT"));
        if (!gen_ || !delete_ || !begin_ || !end_ || !result_) return;
        gen_(1, &query_);
    }
    ~GpuTimer() {
        if (query_) delete_(1, &query_);
    }
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;

    bool available() const { return query_ != 0; }
    void begin() {
        if (!query_) return;
        GLint disjoint = 0;
        glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);  // reading it clears the flag
        begin_(GL_TIME_ELAPSED_EXT, query_);
    }
    void end() {
        if (query_) end_(GL_TIME_ELAPSED_EXT);
    }
    // After glFinish: the frame's GPU milliseconds, NaN if unknown (no timer,
    // or a disjoint event such as a clock change spoiled the measurement).
    double milliseconds() {
        if (!query_) return std::numeric_limits<double>::quiet_NaN();
        GLuint64 ns = 0;
        result_(query_, GL_QUERY_RESULT_EXT, &ns);
        GLint disjoint = 0;
        glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
        return disjoint ? std::numeric_limits<double>::quiet_NaN() : static_cast<double>(ns) * 1e-6;
    }

private:
    GLuint query_ = 0;
    PFNGLGENQUERIESEXTPROC gen_ = nullptr;
    PFNGLDELETEQUERIESEXTPROC delete_ = nullptr;
    PFNGLBEGINQUERYEXTPROC begin_ = nullptr;
    PFNGLENDQUERYEXTPROC end_ = nullptr;
    PFNGLGETQUERYOBJECTUI64VEXTPROC result_ = nullptr;
};

}  // namespace body::kiosk
