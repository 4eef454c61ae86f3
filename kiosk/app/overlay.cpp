// The 2-D layer: one tiny shader (solid or atlas-coverage quads in pixel
// coordinates), batched per texture, blended over the frame.
#include "kiosk/app/overlay.h"

#include <GLES3/gl3.h>

#include <algorithm>

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

struct Vertex {
    float x, y, u, v, r, g, b, a;
};

struct Colour {
    float r, g, b, a;
};

void quad(std::vector<Vertex>& out, float x0, float y0, float x1, float y1, float s0, float t0, float s1, float t1,
          Colour c) {
    const Vertex v[6] = {{x0, y0, s0, t0, c.r, c.g, c.b, c.a}, {x1, y0, s1, t0, c.r, c.g, c.b, c.a},
                         {x1, y1, s1, t1, c.r, c.g, c.b, c.a}, {x0, y0, s0, t0, c.r, c.g, c.b, c.a},
                         {x1, y1, s1, t1, c.r, c.g, c.b, c.a}, {x0, y1, s0, t1, c.r, c.g, c.b, c.a}};
    out.insert(out.end(), v, v + 6);
}

}  // namespace

struct Overlay::State {
    GLuint program = 0, vao = 0, vbo = 0;
    GLuint textures[2] = {0, 0};
    GLint u_screen = -1, u_textured = -1, u_atlas = -1;
    GlyphAtlas title, body;
    std::vector<Vertex> solid, text[2];
};

Overlay::Overlay() = default;
Overlay::~Overlay() = default;

Status Overlay::init(const std::string& font_file, float scale, const std::string& all_label_text) {
    auto s = std::make_unique<State>();
    auto title = GlyphAtlas::build(font_file, 30.0f * scale, all_label_text);
    if (!title) return title.error();
    auto body = GlyphAtlas::build(font_file, 20.0f * scale, all_label_text);
    if (!body) return body.error();
    s->title = std::move(title).value();
    s->body = std::move(body).value();
    auto program = render::link_program(kVertex, kFragment, "overlay");
    if (!program) return program.error();
    s->program = program.value();
    s->u_screen = glGetUniformLocation(s->program, "u_screen");
    s->u_textured = glGetUniformLocation(s->program, "u_textured");
    s->u_atlas = glGetUniformLocation(s->program, "u_atlas");
    glGenVertexArrays(1, &s->vao);
    glGenBuffers(1, &s->vbo);
    glBindVertexArray(s->vao);
    glBindBuffer(GL_ARRAY_BUFFER, s->vbo);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(0));
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(2 * sizeof(float)));
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(4 * sizeof(float)));
    for (GLuint i = 0; i < 3; ++i) glEnableVertexAttribArray(i);
    glBindVertexArray(0);
    glGenTextures(2, s->textures);
    const GlyphAtlas* atlases[2] = {&s->title, &s->body};
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int i = 0; i < 2; ++i) {
        glBindTexture(GL_TEXTURE_2D, s->textures[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, atlases[i]->width(), atlases[i]->height(), 0, GL_RED, GL_UNSIGNED_BYTE,
                     atlases[i]->pixels().data());
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    shutdown();
    s_ = std::move(s);
    return ok_status();
}

void Overlay::shutdown() {
    if (!s_) return;
    glDeleteProgram(s_->program);
    glDeleteVertexArrays(1, &s_->vao);
    glDeleteBuffers(1, &s_->vbo);
    glDeleteTextures(2, s_->textures);
    s_.reset();
}

void Overlay::draw(const std::vector<Control>& controls, const LabelCard& card, unsigned framebuffer, int width,
                   int height) {
    if (!s_) return;
    State& s = *s_;
    s.solid.clear();
    s.text[0].clear();
    s.text[1].clear();
    const Colour ink{0.12f, 0.11f, 0.10f, 1.0f}, faded{0.12f, 0.11f, 0.10f, 0.35f};
    auto text_centered = [&](int which, const std::string& utf8, const Rect& r, Colour c) {
        const GlyphAtlas& a = which == 0 ? s.title : s.body;
        const std::u32string t = decode_utf8(utf8);
        const float w = a.measure(t);
        // Too wide for the button: shrink it (down to 60%), then clip.
        const float room = r.w - 8.0f;
        const float k = w > room ? std::max(0.6f, room / w) : 1.0f;
        const float x = r.x + std::max(4.0f, (r.w - w * k) * 0.5f);
        const float y = r.y + (r.h + a.ascent() * 0.75f * k) * 0.5f;
        for (const GlyphQuad& q : a.layout(t, 0.0f, 0.0f)) {
            const float x0 = x + q.x0 * k, x1 = x + q.x1 * k;
            if (x1 > r.x + r.w - 2.0f) break;
            quad(s.text[which], x0, y + q.y0 * k, x1, y + q.y1 * k, q.s0, q.t0, q.s1, q.t1, c);
        }
    };
    for (const Control& c : controls) {
        const Rect& r = c.rect;
        const Colour fill = c.active ? Colour{0.80f, 0.88f, 0.97f, 0.92f} : Colour{1.0f, 1.0f, 1.0f, 0.85f};
        quad(s.solid, r.x, r.y, r.x + r.w, r.y + r.h, 0, 0, 0, 0, fill);
        const Colour edge{0.35f, 0.35f, 0.40f, 0.9f};
        quad(s.solid, r.x, r.y + r.h - 2, r.x + r.w, r.y + r.h, 0, 0, 0, 0, edge);
        text_centered(1, c.text, r, c.enabled ? ink : faded);
    }
    if (card.visible) {
        // Shrink the card to its text, keeping its bottom edge.
        const float pad = 16.0f;
        const auto title_lines = s.title.wrap(decode_utf8(card.title), card.rect.w - 2 * pad);
        const auto body_lines = s.body.wrap(decode_utf8(card.description), card.rect.w - 2 * pad);
        const bool has_body = !card.description.empty();
        const float needed = 2 * pad + static_cast<float>(title_lines.size()) * s.title.line_height() +
                             (has_body ? (static_cast<float>(body_lines.size()) + 0.3f) * s.body.line_height() : 0.0f);
        Rect r = card.rect;
        if (needed < r.h) {
            r.y += r.h - needed;
            r.h = needed;
        }
        quad(s.solid, r.x, r.y, r.x + r.w, r.y + r.h, 0, 0, 0, 0, Colour{1.0f, 1.0f, 0.98f, 0.93f});
        quad(s.solid, r.x, r.y, r.x + 6, r.y + r.h, 0, 0, 0, 0, Colour{0.55f, 0.25f, 0.80f, 1.0f});
        float y = r.y + pad + s.title.ascent();
        for (const TextLine& line : title_lines) {
            if (y > r.y + r.h) break;
            for (const GlyphQuad& q : s.title.layout(line.text, r.x + pad, y)) {
                quad(s.text[0], q.x0, q.y0, q.x1, q.y1, q.s0, q.t0, q.s1, q.t1, ink);
            }
            y += s.title.line_height();
        }
        y += s.body.line_height() * 0.3f - s.title.ascent() + s.body.ascent();
        for (const TextLine& line : has_body ? body_lines : std::vector<TextLine>{}) {
            if (y > r.y + r.h - pad * 0.5f) break;
            for (const GlyphQuad& q : s.body.layout(line.text, r.x + pad, y)) {
                quad(s.text[1], q.x0, q.y0, q.x1, q.y1, q.s0, q.t0, q.s1, q.t1, ink);
            }
            y += s.body.line_height();
        }
    }

    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(s.program);
    glUniform2f(s.u_screen, static_cast<float>(width), static_cast<float>(height));
    glUniform1i(s.u_atlas, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(s.vao);
    glBindBuffer(GL_ARRAY_BUFFER, s.vbo);
    auto submit = [&](const std::vector<Vertex>& v, int textured, GLuint texture) {
        if (v.empty()) return;
        glUniform1i(s.u_textured, textured);
        glBindTexture(GL_TEXTURE_2D, texture);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(Vertex)), v.data(), GL_STREAM_DRAW);
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size()));
    };
    submit(s.solid, 0, s.textures[0]);
    submit(s.text[0], 1, s.textures[0]);
    submit(s.text[1], 1, s.textures[1]);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

}  // namespace body::kiosk
