// Leader lines and anchor dots: solid triangles in pixel coordinates, one
// draw call per frame (contract in pin_lines.h).
#include "kiosk/app/pin_lines.h"

#include <GLES3/gl3.h>

#include <cmath>

#include "kiosk/render/renderer.h"

namespace body::kiosk {

namespace {

const char* kVertex = R"(#version 300 es
layout(location = 0) in vec2 a_pos;
layout(location = 1) in vec4 a_color;
uniform vec2 u_screen;
out vec4 v_color;
void main() {
    v_color = a_color;
    gl_Position = vec4(a_pos.x / u_screen.x * 2.0 - 1.0, 1.0 - a_pos.y / u_screen.y * 2.0, 0.0, 1.0);
}
)";

const char* kFragment = R"(#version 300 es
precision mediump float;
in vec4 v_color;
out vec4 o_color;
void main() { o_color = v_color; }
)";

struct Vertex {
    float x, y, r, g, b, a;
};

// A segment as a quad `width` pixels wide.
void segment(std::vector<Vertex>& out, glm::vec2 a, glm::vec2 b, float width, const glm::vec4& c) {
    const glm::vec2 d = b - a;
    const float len = glm::length(d);
    if (len <= 0.0f) return;
    const glm::vec2 n = glm::vec2(-d.y, d.x) / len * (width * 0.5f);
    const glm::vec2 p[4] = {a + n, b + n, b - n, a - n};
    for (int i : {0, 1, 2, 0, 2, 3}) out.push_back(Vertex{p[i].x, p[i].y, c.r, c.g, c.b, c.a});
}

// A dot as an octagon of radius r.
void dot(std::vector<Vertex>& out, glm::vec2 centre, float r, const glm::vec4& c) {
    for (int i = 0; i < 8; ++i) {
        const float a0 = 0.7853982f * static_cast<float>(i), a1 = 0.7853982f * static_cast<float>(i + 1);
        const glm::vec2 p0 = centre + r * glm::vec2(std::cos(a0), std::sin(a0));
        const glm::vec2 p1 = centre + r * glm::vec2(std::cos(a1), std::sin(a1));
        for (const glm::vec2& p : {centre, p0, p1}) out.push_back(Vertex{p.x, p.y, c.r, c.g, c.b, c.a});
    }
}

}  // namespace

struct PinLines::State {
    GLuint program = 0, vao = 0, vbo = 0;
    GLint u_screen = -1;
    std::vector<Vertex> vertices;
};

PinLines::PinLines() = default;
PinLines::~PinLines() = default;

Status PinLines::init() {
    auto s = std::make_unique<State>();
    auto program = render::link_program(kVertex, kFragment, "pin lines");
    if (!program) return program.error();
    s->program = program.value();
    s->u_screen = glGetUniformLocation(s->program, "u_screen");
    glGenVertexArrays(1, &s->vao);
    glGenBuffers(1, &s->vbo);
    glBindVertexArray(s->vao);
    glBindBuffer(GL_ARRAY_BUFFER, s->vbo);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(0));
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(2 * sizeof(float)));
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glBindVertexArray(0);
    shutdown();
    s_ = std::move(s);
    return ok_status();
}

void PinLines::shutdown() {
    if (!s_) return;
    glDeleteProgram(s_->program);
    glDeleteVertexArrays(1, &s_->vao);
    glDeleteBuffers(1, &s_->vbo);
    s_.reset();
}

void PinLines::draw(const std::vector<PinView>& pins, float scale, unsigned framebuffer, int width, int height) {
    if (!s_) return;
    State& s = *s_;
    s.vertices.clear();
    const glm::vec4 halo(1.0f, 1.0f, 1.0f, 0.9f), ink(0.12f, 0.11f, 0.10f, 1.0f);
    for (const PinView& p : pins) {
        if (!p.shown || !p.label) continue;
        const glm::vec2 end = leader_end(*p.label, p.anchor_px);
        segment(s.vertices, p.anchor_px, end, 4.0f * scale,
                halo);  // a light edge keeps the line visible on dark models
        segment(s.vertices, p.anchor_px, end, 2.0f * scale, ink);
        dot(s.vertices, p.anchor_px, 6.0f * scale, halo);
        dot(s.vertices, p.anchor_px, 4.0f * scale, ink);
    }
    if (s.vertices.empty()) return;
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(s.program);
    glUniform2f(s.u_screen, static_cast<float>(width), static_cast<float>(height));
    glBindVertexArray(s.vao);
    glBindBuffer(GL_ARRAY_BUFFER, s.vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(s.vertices.size() * sizeof(Vertex)), s.vertices.data(),
                 GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(s.vertices.size()));
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

}  // namespace body::kiosk
