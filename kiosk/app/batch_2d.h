#pragma once
// The kiosk's one 2-D pipeline, shared by every screen layer (overlay.h,
// pin_lines.h, the author's panel_draw.h): solid or glyph-coverage triangles
// in pixel coordinates (origin top-left), blended over the frame with no depth
// test. Callers fill Vertex2d arrays (quad_2d, or triangles of their own with
// u = v = 0) and submit them between begin() and end(), one draw call each;
// a GlyphAtlas goes up as an R8 texture through AtlasTexture whenever its
// pixels changed. Needs a current GLES 3 context; one instance per context;
// shutdown() (not the destructor) frees the GL objects.
#include <cstdint>
#include <span>
#include <vector>

#include "kiosk/app/text.h"
#include "shared/error.h"

namespace body::kiosk {

struct Rgba {
    float r, g, b, a;
};

struct Vertex2d {
    float x, y, u, v, r, g, b, a;
};

// Two triangles covering [x0, x1] x [y0, y1], texture coordinates [s0, s1] x [t0, t1].
void quad_2d(std::vector<Vertex2d>& out, float x0, float y0, float x1, float y1, Rgba c, float s0 = 0.0f,
             float t0 = 0.0f, float s1 = 0.0f, float t1 = 0.0f);
// One untextured corner.
inline void vertex_2d(std::vector<Vertex2d>& out, float x, float y, Rgba c) {
    out.push_back(Vertex2d{x, y, 0.0f, 0.0f, c.r, c.g, c.b, c.a});
}

// A GlyphAtlas's pixels as a GL texture (linear, clamped), uploaded again only
// when the atlas's generation changed (re-specified when its size did).
class AtlasTexture {
public:
    void upload(const GlyphAtlas& atlas);
    unsigned id() const { return texture_; }
    void shutdown();

private:
    unsigned texture_ = 0;
    uint64_t uploaded_ = ~0ull;
    int width_ = 0, height_ = 0;
};

class Batch2d {
public:
    // Atlas: solid and atlas-coverage draws. Solid: solid draws only (the
    // texture argument of draw() ignored), a shader that interpolates the
    // colour alone.
    enum class Shading { Atlas, Solid };
    // `name` names the program in a link error.
    Status init(const char* name, Shading shading = Shading::Atlas);
    void shutdown();
    bool ready() const { return program_ != 0; }
    // Binds `framebuffer` (width x height) and the blended 2-D state.
    void begin(unsigned framebuffer, int width, int height);
    // One draw of `vertices` (triangles): coverage from `texture`'s red
    // channel times the vertex alpha, or solid for texture 0.
    void draw(std::span<const Vertex2d> vertices, unsigned texture = 0);
    // Restores the 3-D state (depth test and writes on, blending off).
    void end();

private:
    unsigned program_ = 0, vao_ = 0, vbo_ = 0;
    int u_screen_ = -1, u_textured_ = -1, u_atlas_ = -1;
};

}  // namespace body::kiosk
