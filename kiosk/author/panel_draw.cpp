// The editor's 2-D layer (contract in panel_draw.h): solid and atlas-coverage
// quads in pixel coordinates through the kiosk's 2-D batch (app/batch_2d.h),
// in two layers (panel, then help and prompt).
#include "kiosk/author/panel_draw.h"

#include <algorithm>

#include "kiosk/app/batch_2d.h"
#include "kiosk/app/text.h"

namespace body::kiosk::author {

namespace {

constexpr Rgba kInk{0.10f, 0.10f, 0.12f, 1.0f}, kFaded{0.10f, 0.10f, 0.12f, 0.5f}, kPanel{0.93f, 0.93f, 0.95f, 0.96f},
    kBox{1, 1, 1, 1}, kActive{0.78f, 0.86f, 0.98f, 1.0f}, kEdge{0.55f, 0.55f, 0.62f, 1.0f},
    kHeading{0.84f, 0.84f, 0.88f, 1.0f}, kSelect{0.55f, 0.70f, 0.98f, 0.6f};

void quad(std::vector<Vertex2d>& out, const Rect& r, Rgba c, float s0 = 0, float t0 = 0, float s1 = 0, float t1 = 0) {
    quad_2d(out, r.x, r.y, r.x + r.w, r.y + r.h, c, s0, t0, s1, t1);
}

struct Layer {
    std::vector<Vertex2d> solid, text;
};

}  // namespace

struct PanelPainter::State {
    Batch2d batch;
    AtlasTexture texture;
    GlyphAtlas atlas;  // glyphs drawn in when first laid out (app/text.h)
    std::string font;
    float pixel_height = 16.0f;
    Layer layers[2];

    void build(Editor& e, int width, int height);

    // Text from its left edge, vertically centred in `r`, clipped at the right; returns the pen's x.
    float text(Layer& l, const std::string& utf8, const Rect& r, float left, Rgba c) {
        const float y = r.y + (r.h + atlas.ascent() * 0.75f) * 0.5f;
        float advance = 0;
        for (const GlyphQuad& q : atlas.layout(decode_utf8(utf8), r.x + left, y, &advance)) {
            if (q.x1 > r.x + r.w - 2.0f) break;
            quad(l.text, Rect{q.x0, q.y0, q.x1 - q.x0, q.y1 - q.y0}, c, q.s0, q.t0, q.s1, q.t1);
        }
        return r.x + left + advance;
    }

    void row(Layer& l, const PanelRow& r, Editor& e);
    void box(Layer& l, const std::vector<std::string>& lines, int width, int height);
};

void PanelPainter::State::row(Layer& l, const PanelRow& r, Editor& e) {
    const float pad = 6.0f + 14.0f * static_cast<float>(r.indent);
    switch (r.kind) {
        case RowKind::Button:
            quad(l.solid, r.rect, kBox);
            quad(l.solid, Rect{r.rect.x, r.rect.y + r.rect.h - 2, r.rect.w, 2}, kEdge);
            text(l, r.text, r.rect, std::max(4.0f, (r.rect.w - atlas.measure(decode_utf8(r.text))) * 0.5f), kInk);
            break;
        case RowKind::Heading:
            quad(l.solid, r.rect, kHeading);
            text(l, r.text, r.rect, 6.0f, kInk);
            break;
        case RowKind::Status: text(l, r.text, r.rect, 6.0f, kFaded); break;
        case RowKind::TreeGroup:
        case RowKind::TreeModel:
        case RowKind::TreeTour:
        case RowKind::TreeStep:
            if (r.active) quad(l.solid, r.rect, kActive);
            text(l, r.text, r.rect, pad, kInk);
            break;
        case RowKind::Field: {
            text(l, r.text, Rect{r.rect.x, r.rect.y, r.value_rect.x - r.rect.x, r.rect.h}, pad, kInk);
            quad(l.solid, r.value_rect, r.editable ? kBox : kHeading);
            const PanelRow* f = e.focused_row();
            const bool focused = f && f->rect.y == r.rect.y;
            if (!focused) {
                text(l, r.value, r.value_rect, 4.0f, kInk);
                break;
            }
            quad(l.solid, Rect{r.value_rect.x - 1, r.value_rect.y - 1, r.value_rect.w + 2, 2}, kEdge);
            const TextField& t = e.field();
            const float x0 = r.value_rect.x + 4.0f;
            const float b = atlas.measure(decode_utf8(t.text().substr(0, t.selection_begin())));
            const float en = atlas.measure(decode_utf8(t.text().substr(0, t.selection_end())));
            if (en > b) quad(l.solid, Rect{x0 + b, r.value_rect.y + 2, en - b, r.value_rect.h - 4}, kSelect);
            const float c = atlas.measure(decode_utf8(t.text().substr(0, t.cursor())));
            quad(l.solid, Rect{x0 + c, r.value_rect.y + 2, 1.5f, r.value_rect.h - 4}, kInk);
            text(l, t.text(), r.value_rect, 4.0f, kInk);
            break;
        }
    }
}

void PanelPainter::State::box(Layer& l, const std::vector<std::string>& lines, int width, int height) {
    const float lh = atlas.line_height() * 1.3f;
    float w = 0;
    for (const std::string& s : lines) w = std::max(w, atlas.measure(decode_utf8(s)));
    const Rect r{(static_cast<float>(width) - w) * 0.5f - 20,
                 (static_cast<float>(height) - lh * lines.size()) * 0.5f - 16, w + 40,
                 lh * static_cast<float>(lines.size()) + 32};
    quad(l.solid, r, Rgba{1, 1, 1, 0.97f});
    quad(l.solid, Rect{r.x, r.y, r.w, 3}, kEdge);
    for (size_t i = 0; i < lines.size(); ++i)
        text(l, lines[i], Rect{r.x, r.y + 16 + lh * static_cast<float>(i), r.w, lh}, 20.0f, kInk);
}

PanelPainter::PanelPainter() = default;
PanelPainter::~PanelPainter() = default;

Status PanelPainter::init(const std::string& font_file, float scale) {
    auto s = std::make_unique<State>();
    s->font = font_file;
    s->pixel_height = 16.0f * scale;
    auto atlas = GlyphAtlas::build(font_file, s->pixel_height);
    if (!atlas) return atlas.error();
    if (auto b = s->batch.init("author panel"); !b) return b;
    s->atlas = std::move(atlas).value();
    shutdown();
    s_ = std::move(s);
    return ok_status();
}

void PanelPainter::shutdown() {
    if (!s_) return;
    s_->batch.shutdown();
    s_->texture.shutdown();
    s_.reset();
}

float PanelPainter::measure(const std::string& utf8) const { return s_ ? s_->atlas.measure(decode_utf8(utf8)) : 0.0f; }

void PanelPainter::State::build(Editor& e, int width, int height) {
    for (Layer& l : layers) l.solid.clear(), l.text.clear();
    Layer& base = layers[0];
    for (const PinMarker& p : e.pin_markers()) {  // a square per pin of the selection: drag it to move the pin
        const float h = 5.0f * pixel_height / 16.0f;
        quad(base.solid, Rect{p.x - h - 1, p.y - h - 1, 2 * h + 2, 2 * h + 2}, kInk);
        quad(base.solid, Rect{p.x - h, p.y - h, 2 * h, 2 * h}, Rgba{1.0f, 0.85f, 0.2f, 1.0f});
    }
    quad(base.solid, Rect{0, 0, e.panel_width(), static_cast<float>(height)}, kPanel);
    for (const PanelRow& r : e.rows())
        if (r.rect.y + r.rect.h >= 0 && r.rect.y <= static_cast<float>(height)) row(base, r, e);
    if (e.help_visible()) box(layers[1], help_lines(), width, height);
    if (e.prompt_visible())
        box(layers[1], {"Unsaved changes.", "S  save and quit", "D  quit without saving", "Esc  go back"}, width,
            height);
}

void PanelPainter::draw(Editor& e, unsigned framebuffer, int width, int height) {
    if (!s_) return;
    State& s = *s_;
    // Glyphs new this frame may grow the atlas and stale the quads laid out before: then once more.
    const uint64_t epoch = s.atlas.epoch();
    s.build(e, width, height);
    if (s.atlas.epoch() != epoch) s.build(e, width, height);
    s.texture.upload(s.atlas);

    s.batch.begin(framebuffer, width, height);
    for (const Layer& l : s.layers) {
        s.batch.draw(l.solid);
        s.batch.draw(l.text, s.texture.id());
    }
    s.batch.end();
}

}  // namespace body::kiosk::author
