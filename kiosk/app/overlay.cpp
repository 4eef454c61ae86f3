// The 2-D layer: one tiny shader (solid or atlas-coverage quads in pixel
// coordinates), batched per texture, blended over the frame.
#include "kiosk/app/overlay.h"

#include <GLES3/gl3.h>

#include <algorithm>
#include <map>
#include <tuple>

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
    uint64_t uploaded[2] = {~0ull, ~0ull};  // atlas generation in each texture
    int texture_size[2] = {0, 0};
    std::vector<Vertex> solid, text[2];
    std::map<std::tuple<std::string, float, float>, FittedText> fitted;  // control text and box -> fit
    const FittedText& fit(const std::string& utf8, float w, float h);
    void build(const std::vector<Control>& controls, const LabelCard& card);
    void upload();
};

namespace {

// `lines` of one atlas, each centred (or aligned to `align`: -1 left, 1 right) in r.
void text_lines(std::vector<Vertex>& out, GlyphAtlas& a, const std::vector<TextLine>& lines, float k, float x, float w,
                float y_baseline, int align, TextDirection dir, Colour c) {
    float y = y_baseline;
    for (const TextLine& line : lines) {
        const float lw = line.width * k;
        const float x0 = align < 0 ? x : align > 0 ? x + w - lw : x + (w - lw) * 0.5f;
        for (const GlyphQuad& q : a.layout(line.text, 0.0f, 0.0f, nullptr, dir))
            quad(out, x0 + q.x0 * k, y + q.y0 * k, x0 + q.x1 * k, y + q.y1 * k, q.s0, q.t0, q.s1, q.t1, c);
        y += a.line_height() * k;
    }
}

}  // namespace

void Overlay::State::upload() {
    GlyphAtlas* atlases[2] = {&title, &body};
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int i = 0; i < 2; ++i) {
        const GlyphAtlas& a = *atlases[i];
        if (uploaded[i] == a.generation()) continue;
        glBindTexture(GL_TEXTURE_2D, textures[i]);
        if (texture_size[i] != a.width()) {
            glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, a.width(), a.height(), 0, GL_RED, GL_UNSIGNED_BYTE,
                         a.pixels().data());
            texture_size[i] = a.width();
        } else {
            glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, a.width(), a.height(), GL_RED, GL_UNSIGNED_BYTE, a.pixels().data());
        }
        uploaded[i] = a.generation();
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

Overlay::Overlay() = default;
Overlay::~Overlay() = default;

Status Overlay::init(const std::string& font_file, float scale) {
    auto s = std::make_unique<State>();
    auto fonts = FontSet::open(FontSet::every_script(font_file));
    if (!fonts) return fonts.error();
    s->title = GlyphAtlas(fonts.value(), 30.0f * scale);
    s->body = GlyphAtlas(fonts.value(), 20.0f * scale);
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
    for (int i = 0; i < 2; ++i) {
        glBindTexture(GL_TEXTURE_2D, s->textures[i]);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
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

// fit_text is a search over scales and cuts: done once per text and box, not every frame.
const FittedText& Overlay::State::fit(const std::string& utf8, float w, float h) {
    auto key = std::make_tuple(utf8, w, h);
    if (auto it = fitted.find(key); it != fitted.end()) return it->second;
    if (fitted.size() > 512) fitted.clear();
    return fitted.emplace(std::move(key), fit_text(body, decode_utf8(utf8), w, h)).first->second;
}

void Overlay::State::build(const std::vector<Control>& controls, const LabelCard& card) {
    solid.clear();
    text[0].clear();
    text[1].clear();
    const Colour ink{0.12f, 0.11f, 0.10f, 1.0f}, faded{0.12f, 0.11f, 0.10f, 0.35f};
    for (const Control& c : controls) {
        const Rect& r = c.rect;
        const Colour fill = c.active ? Colour{0.80f, 0.88f, 0.97f, 0.92f} : Colour{1.0f, 1.0f, 1.0f, 0.85f};
        quad(solid, r.x, r.y, r.x + r.w, r.y + r.h, 0, 0, 0, 0, fill);
        const Colour edge{0.35f, 0.35f, 0.40f, 0.9f};
        quad(solid, r.x, r.y + r.h - 2, r.x + r.w, r.y + r.h, 0, 0, 0, 0, edge);
        const FittedText& f = fit(c.text, r.w - 8.0f, r.h - 6.0f);
        // Lines centred in the box; the first baseline puts the block's middle at the box's.
        const float k = f.scale, lh = body.line_height() * k;
        const float top = r.y + (r.h - static_cast<float>(f.lines.size()) * lh) * 0.5f;
        const float baseline = top + (lh + body.ascent() * 0.75f * k) * 0.5f;
        const TextDirection dir = f.rtl ? TextDirection::RightToLeft : TextDirection::LeftToRight;
        text_lines(text[1], body, f.lines, k, r.x + 4.0f, r.w - 8.0f, baseline, 0, dir, c.enabled ? ink : faded);
    }
    if (!card.visible) return;
    // Shrink the card to its text, keeping its bottom edge.
    const float pad = 16.0f;
    const std::u32string title_text = decode_utf8(card.title), body_text = decode_utf8(card.description);
    const auto title_lines = title.wrap(title_text, card.rect.w - 2 * pad);
    auto body_lines = body.wrap(body_text, card.rect.w - 2 * pad);
    const bool has_body = !card.description.empty();
    if (!has_body) body_lines.clear();
    const float needed = 2 * pad + static_cast<float>(title_lines.size()) * title.line_height() +
                         (has_body ? (static_cast<float>(body_lines.size()) + 0.3f) * body.line_height() : 0.0f);
    Rect r = card.rect;
    if (needed < r.h) {
        r.y += r.h - needed;
        r.h = needed;
    }
    // Lines that do not fit the card's height are left out whole, never cut.
    auto fitting = [](std::vector<TextLine> lines, float from, float to, float lh) {
        const auto n = static_cast<size_t>(std::max(0.0f, std::floor((to - from) / lh)));
        if (lines.size() > n) lines.resize(n);
        return lines;
    };
    const bool rtl = is_rtl_paragraph(title_text.empty() ? body_text : title_text);
    quad(solid, r.x, r.y, r.x + r.w, r.y + r.h, 0, 0, 0, 0, Colour{1.0f, 1.0f, 0.98f, 0.93f});
    const float bar_x = rtl ? r.x + r.w - 6 : r.x;  // the accent bar on the reading side
    quad(solid, bar_x, r.y, bar_x + 6, r.y + r.h, 0, 0, 0, 0, Colour{0.55f, 0.25f, 0.80f, 1.0f});
    const TextDirection dir = rtl ? TextDirection::RightToLeft : TextDirection::LeftToRight;
    const int align = rtl ? 1 : -1;
    const float title_top = r.y + pad;
    const auto titles = fitting(title_lines, title_top, r.y + r.h, title.line_height());
    text_lines(text[0], title, titles, 1.0f, r.x + pad, r.w - 2 * pad, title_top + title.ascent(), align, dir, ink);
    const float body_top =
        title_top + static_cast<float>(titles.size()) * title.line_height() + body.line_height() * 0.3f;
    const auto bodies = fitting(body_lines, body_top, r.y + r.h - pad * 0.5f, body.line_height());
    text_lines(text[1], body, bodies, 1.0f, r.x + pad, r.w - 2 * pad, body_top + body.ascent(), align, dir, ink);
}

void Overlay::draw(const std::vector<Control>& controls, const LabelCard& card, unsigned framebuffer, int width,
                   int height) {
    if (!s_) return;
    State& s = *s_;
    // Glyphs new this frame may grow an atlas and stale the quads laid out before: then once more.
    const uint64_t epochs = s.title.epoch() + s.body.epoch();
    s.build(controls, card);
    if (s.title.epoch() + s.body.epoch() != epochs) s.build(controls, card);
    s.upload();

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
    submit(s.solid, 0, s.textures[0]);  // (texture unused: untextured)
    submit(s.text[0], 1, s.textures[0]);
    submit(s.text[1], 1, s.textures[1]);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

}  // namespace body::kiosk
