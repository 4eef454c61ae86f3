#pragma once
// The renderer's GLSL programs: one per shader pair of kiosk/shaders/, with the
// vertex attribute locations below, uniform locations looked up once and
// cached. The renderer's table and the batch programs are linked at their
// first use (Frame::use), so a start links only what its first frame draws.
#include <GLES3/gl3.h>

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "shared/error.h"

namespace body::render {

// Vertex attribute locations (mesh.vert, wireframe.vert).
inline constexpr GLuint kPosition = 0, kNormal = 1, kMorph = 2;
inline constexpr GLuint kWireVertex = 3;  // `wireframe`: the index buffer read as a vertex attribute
inline constexpr GLuint kNormalCode = 4;  // 8:8 octahedral normal codes (mesh.vert decodes them)

struct Program {
    GLuint id = 0;
    // What link_on_first_use() links while id is 0: kiosk/shaders/ names and
    // "#define" lines. A failed link is logged once and not tried again.
    std::string vert, frag, defines;
    bool link_failed = false;
    bool drawn = false;          // used by a frame already (its shader variants compiled)
    bool clip_distance = false;  // writes gl_ClipDistance[0] (kiosk/shaders/clip_vertex.glsl)
    // The Frame::serial whose per-frame uniforms (projection, view ray; the
    // lights) this program holds: set once a frame, not once a model.
    uint64_t frame_uniforms = 0, frame_lights = 0;
    std::map<std::string, GLint, std::less<>> locations;  // looked up without a std::string per call
    GLint loc(const char* name);
};

// The program table. The `lines` paper fill draws with `baseline`; a selected
// model with `smooth`.
struct Programs {
    Program baseline;   // mesh.vert + baseline.frag
    Program smooth;     // mesh.vert + smooth.frag
    Program hatching;   // mesh.vert + hatching.frag (both hatching styles)
    Program xray;       // mesh.vert + xray.frag
    Program lines;      // lines.vert + lines.frag (the edges of `lines`)
    Program wireframe;  // wireframe.vert + wireframe.frag
    // The same reading the positions straight from the model's position
    // buffer through a buffer texture (BODY_WIRE_BUFFER; styles/wireframe.cpp):
    // always linked at its first use, where the driver offers
    // GL_EXT_texture_buffer.
    Program wireframe_buffer;
};

// A program linked at its first use: only its shader pair and defines now.
Program deferred_program(std::string vert, std::string frag, std::string defines = {});
// Links `p` from its shader pair unless linked already; false (the reason
// logged once) when it cannot be linked.
bool link_on_first_use(Program& p);
// The table with every program deferred to its first use.
void defer_programs(Programs& programs, const char* defines = nullptr);
// Links every program of the table but wireframe_buffer (deferred: not every
// driver offers it); on an error the ones linked are deleted.
// `defines` ("#define NAME 1\n" lines) select a variant, e.g. the cut plane's
// clipped programs (kiosk/render/styles/cut_cap.cpp).
Status link_programs(Programs& programs, const char* defines = nullptr);
// One program of kiosk/shaders/ (the cut plane's cap), with optional `defines`.
Result<Program> link_shader_pair(const std::string& vert, const std::string& frag, const char* defines = nullptr);
void delete_programs(Programs& programs);

}  // namespace body::render
