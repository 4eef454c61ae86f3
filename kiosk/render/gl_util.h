#pragma once
// Small helpers shared by the renderer's files: the debug-build GL error check,
// the context's version and extension list, and handing freed heap memory back
// to the system.
#include <GLES3/gl3.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <cstdio>
#include <cstring>

#ifdef BODY_GL_DEBUG
#define BODY_GL_CHECK(where)                                                                               \
    do {                                                                                                   \
        for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError())                                  \
            std::fprintf(stderr, "bodyview: GL error 0x%04x after %s\n", static_cast<unsigned>(e), where); \
    } while (0)
#else
#define BODY_GL_CHECK(where) \
    do {                     \
    } while (0)
#endif

namespace body::render {

// Whether the current context's GL ES version is at least major.minor.
inline bool gl_version_at_least(GLint major, GLint minor) {
    GLint have_major = 0, have_minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &have_major);
    glGetIntegerv(GL_MINOR_VERSION, &have_minor);
    return have_major > major || (have_major == major && have_minor >= minor);
}

// Whether the current context lists the GL extension `name`.
inline bool gl_has_extension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
        if (e && std::strcmp(e, name) == 0) return true;
    }
    return false;
}

// Gives the heap's free memory back to the system (glibc keeps large freed
// blocks resident; software drivers keep textures and compiler scratch there).
inline void trim_heap() {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

}  // namespace body::render
