#pragma once
// Small helpers shared by the renderer's files: the debug-build GL error check
// and handing freed heap memory back to the system.
#include <GLES3/gl3.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <cstdio>

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

// Gives the heap's free memory back to the system (glibc keeps large freed
// blocks resident; software drivers keep textures and compiler scratch there).
inline void trim_heap() {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

}  // namespace body::render
