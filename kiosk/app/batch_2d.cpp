// The shared 2-D batch (contract in batch_2d.h): one tiny shader, one vertex
// buffer streamed per draw.
#include "kiosk/app/batch_2d.h"

#include <GLES3/gl3.h>

#include "kiosk/render/renderer.h"

namespace body::kiosk {

namespace {

const char* kVertex = R"(#version 300 es
layout(location = 0) in vec2 a_pos;
layout(location = 1) in vec2 a_uv;
layout(location = 2) in vec4 a_color;
uniform vec2 u_screen;
out vec2 v_uv;
out vec4 v_color;
void main() {
    v_uv = a_uv;
    v_color = a_color;
    gl_Position = vec4(a_pos.x / u_screen.x * 2.0 - 1.0, 1.0 - a_pos.y / u_screen.y * 2.0, 0.0, 1.0);
}
)";

const char* kFragment = R"(#version 300 es
precision mediump float;
uniform sampler2D u_atlas;
uniform int u_textured;
in vec2 v_uv;
in vec4 v_color;
out vec4 o_color;
void main() {
    float a = u_textured == 1 ? texture(u_atlas, v_uv).r : 1.0;
    o_color = vec4(v_color.rgb, v_color.a * a);
}
)";

// Solid colour only (pin_lines.h): no texture coordinates interpolated.
const char* kSolidVertex = R"(#version 300 es
layout(location = 0) in vec2 a_pos;
layout(location = 2) in vec4 a_color;
uniform vec2 u_screen;
out vec4 v_color;
void main() {
    v_color = a_color;
    gl_Position = vec4(a_pos.x / u_screen.x * 2.0 - 1.0, 1.0 - a_pos.y / u_screen.y * 2.0, 0.0, 1.0);
}
)";

const char* kSolidFragment = R"(#version 300 es
precision mediump float;
in vec4 v_color;
out vec4 o_color;
void main() { o_color = v_color; }
)";

}  // namespace

void quad_2d(std::vector<Vertex2d>& out, float x0, float y0, float x1, float y1, Rgba c, float s0, float t0, float s1,
             float t1) {
    const Vertex2d v[6] = {{x0, y0, s0, t0, c.r, c.g, c.b, c.a}, {x1, y0, s1, t0, c.r, c.g, c.b, c.a},
                           {x1, y1, s1, t1, c.r, c.g, c.b, c.a}, {x0, y0, s0, t0, c.r, c.g, c.b, c.a},
                           {x1, y1, s1, t1, c.r, c.g, c.b, c.a}, {x0, y1, s0, t1, c.r, c.g, c.b, c.a}};
    out.insert(out.end(), v, v + 6);
}

void AtlasTexture::upload(const GlyphAtlas& atlas) {
    if (uploaded_ == atlas.generation()) return;
    if (texture_ == 0) {
        GLuint t = 0;
        glGenTextures(1, &t);
        texture_ = t;
    }
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (width_ != atlas.width() || height_ != atlas.height()) {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, atlas.width(), atlas.height(), 0, GL_RED, GL_UNSIGNED_BYTE,
                     atlas.pixels().data());
        width_ = atlas.width();
        height_ = atlas.height();
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, atlas.width(), atlas.height(), GL_RED, GL_UNSIGNED_BYTE,
                        atlas.pixels().data());
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    uploaded_ = atlas.generation();
}

void AtlasTexture::shutdown() {
    if (texture_ != 0) {
        const GLuint t = texture_;
        glDeleteTextures(1, &t);
    }
    *this = AtlasTexture{};
}

Status Batch2d::init(const char* name, Shading shading) {
    shutdown();
    const bool solid = shading == Shading::Solid;
    auto program = render::link_program(solid ? kSolidVertex : kVertex, solid ? kSolidFragment : kFragment, name);
    if (!program) return program.error();
    program_ = program.value();
    u_screen_ = glGetUniformLocation(program_, "u_screen");
    u_textured_ = glGetUniformLocation(program_, "u_textured");
    u_atlas_ = glGetUniformLocation(program_, "u_atlas");
    GLuint vao = 0, vbo = 0;
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    vao_ = vao;
    vbo_ = vbo;
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex2d), reinterpret_cast<void*>(0));
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex2d), reinterpret_cast<void*>(2 * sizeof(float)));
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex2d), reinterpret_cast<void*>(4 * sizeof(float)));
    for (GLuint i = 0; i < 3; ++i) glEnableVertexAttribArray(i);
    glBindVertexArray(0);
    return ok_status();
}

void Batch2d::shutdown() {
    if (program_ == 0) return;
    const GLuint vao = vao_, vbo = vbo_;
    glDeleteProgram(program_);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &vbo);
    program_ = vao_ = vbo_ = 0;
}

void Batch2d::begin(unsigned framebuffer, int width, int height) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(program_);
    glUniform2f(u_screen_, static_cast<float>(width), static_cast<float>(height));
    if (u_atlas_ >= 0) glUniform1i(u_atlas_, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
}

void Batch2d::draw(std::span<const Vertex2d> vertices, unsigned texture) {
    if (vertices.empty()) return;
    if (u_textured_ >= 0) glUniform1i(u_textured_, texture != 0 ? 1 : 0);
    if (texture != 0) glBindTexture(GL_TEXTURE_2D, texture);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size_bytes()), vertices.data(), GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size()));
}

void Batch2d::end() {
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

}  // namespace body::kiosk
