// The 2-D layer: solid quads (boxes, edges) through the shared 2-D batch's
// colour-only shader in one draw, then atlas-coverage quads, one draw per
// texture (batch_2d.h).
#include "kiosk/app/overlay.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "kiosk/app/access.h"
#include "kiosk/app/batch_2d.h"

namespace body::kiosk {

struct Overlay::State {
    Batch2d batch, solid_batch;  // atlas shader; colour-only shader, made at the second draw
    int draws = 0;
    // Per text size (normal, large): the title and body atlases and their textures.
    struct Atlases {
        AtlasTexture textures[2];  // title, body
        GlyphAtlas title, body;
    };
    Atlases sizes[2];
    std::shared_ptr<FontSet> fonts;
    float scale = 1.0f;
    bool high_contrast = false;
    int size = 0;  // index into sizes
    GlyphAtlas *title_atlas = nullptr, *body_atlas = nullptr;
    std::vector<Vertex2d> solid, text[2];
    std::map<std::tuple<std::string, float, float, int>, FittedText> fitted;  // control text, box, size -> fit
    void use_size(int s);
    const FittedText& fit(const std::string& utf8, float w, float h);
    void build(const std::vector<Control>& controls, const LabelCard& card, std::span<const Vertex2d> under);
    void upload();
};

namespace {

// `lines` of one atlas, each centred (or aligned to `align`: -1 left, 1 right) in r.
void text_lines(std::vector<Vertex2d>& out, GlyphAtlas& a, const std::vector<TextLine>& lines, float k, float x,
                float w, float y_baseline, int align, TextDirection dir, Rgba c) {
    float y = y_baseline;
    for (const TextLine& line : lines) {
        const float lw = line.width * k;
        const float x0 = align < 0 ? x : align > 0 ? x + w - lw : x + (w - lw) * 0.5f;
        for (const GlyphQuad& q : a.layout(line.text, 0.0f, 0.0f, nullptr, dir))
            quad_2d(out, x0 + q.x0 * k, y + q.y0 * k, x0 + q.x1 * k, y + q.y1 * k, c, q.s0, q.t0, q.s1, q.t1);
        y += a.line_height() * k;
    }
}

}  // namespace

void Overlay::State::upload() {
    sizes[size].textures[0].upload(*title_atlas);
    sizes[size].textures[1].upload(*body_atlas);
}

// The atlases of text size `s` (0 normal, 1 large), made at first use.
void Overlay::State::use_size(int s) {
    Atlases& a = sizes[s];
    if (a.title.pixel_height() <= 0.0f) {
        const float k = s == 1 ? kLargeTextScale : 1.0f;
        a.title = GlyphAtlas(fonts, 30.0f * scale * k);
        a.body = GlyphAtlas(fonts, 20.0f * scale * k);
    }
    size = s;
    title_atlas = &a.title;
    body_atlas = &a.body;
}

Overlay::Overlay() = default;
Overlay::~Overlay() = default;

Status Overlay::init(const std::string& font_file, float scale) {
    auto s = std::make_unique<State>();
    auto fonts = FontSet::open(FontSet::every_script(font_file));
    if (!fonts) return fonts.error();
    s->fonts = fonts.value();
    s->scale = scale;
    s->use_size(0);
    if (auto b = s->batch.init("overlay"); !b) return b;
    shutdown();
    s_ = std::move(s);
    return ok_status();
}

void Overlay::shutdown() {
    if (!s_) return;
    s_->batch.shutdown();
    s_->solid_batch.shutdown();
    for (State::Atlases& a : s_->sizes)
        for (AtlasTexture& t : a.textures) t.shutdown();
    s_.reset();
}

size_t Overlay::shaped_lines() const {
    size_t n = 0;
    if (s_) {
        for (const State::Atlases& a : s_->sizes) n += a.title.shaped_lines() + a.body.shaped_lines();
    }
    return n;
}

// fit_text is a search over scales and cuts: done once per text and box, not every frame.
const FittedText& Overlay::State::fit(const std::string& utf8, float w, float h) {
    auto key = std::make_tuple(utf8, w, h, size);
    if (auto it = fitted.find(key); it != fitted.end()) return it->second;
    if (fitted.size() > 512) fitted.clear();
    return fitted.emplace(std::move(key), fit_text(*body_atlas, decode_utf8(utf8), w, h)).first->second;
}

void Overlay::State::build(const std::vector<Control>& controls, const LabelCard& card,
                           std::span<const Vertex2d> under) {
    solid.assign(under.begin(), under.end());
    text[0].clear();
    text[1].clear();
    GlyphAtlas &title = *title_atlas, &body = *body_atlas;
    const Palette& p = palette(high_contrast);
    const Rgba ink = p.ink;
    for (const Control& c : controls) {
        const Rect& r = c.rect;
        const Rgba fill = c.active ? p.active_fill : p.fill;
        quad_2d(solid, r.x, r.y, r.x + r.w, r.y + r.h, fill);
        const Rgba edge = p.edge;
        if (p.framed) {  // the top, left and right edges as well
            quad_2d(solid, r.x, r.y, r.x + r.w, r.y + 2, edge);
            quad_2d(solid, r.x, r.y + 2, r.x + 2, r.y + r.h - 2, edge);
            quad_2d(solid, r.x + r.w - 2, r.y + 2, r.x + r.w, r.y + r.h - 2, edge);
        }
        quad_2d(solid, r.x, r.y + r.h - 2, r.x + r.w, r.y + r.h, edge);
        const FittedText& f = fit(c.text, r.w - 8.0f, r.h - 6.0f);
        // Lines centred in the box; the first baseline puts the block's middle at the box's.
        const float k = f.scale, lh = body.line_height() * k;
        const float top = r.y + (r.h - static_cast<float>(f.lines.size()) * lh) * 0.5f;
        const float baseline = top + (lh + body.ascent() * 0.75f * k) * 0.5f;
        const TextDirection dir = f.rtl ? TextDirection::RightToLeft : TextDirection::LeftToRight;
        text_lines(text[1], body, f.lines, k, r.x + 4.0f, r.w - 8.0f, baseline, 0, dir,
                   !c.enabled ? p.faded
                   : c.active ? p.active_ink
                              : ink);
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
    quad_2d(solid, r.x, r.y, r.x + r.w, r.y + r.h, p.card);
    const float bar_x = rtl ? r.x + r.w - 6 : r.x;  // the accent bar on the reading side
    quad_2d(solid, bar_x, r.y, bar_x + 6, r.y + r.h, p.accent);
    const TextDirection dir = rtl ? TextDirection::RightToLeft : TextDirection::LeftToRight;
    const int align = rtl ? 1 : -1;
    const float title_top = r.y + pad;
    const auto titles = fitting(title_lines, title_top, r.y + r.h, title.line_height());
    text_lines(text[0], title, titles, 1.0f, r.x + pad, r.w - 2 * pad, title_top + title.ascent(), align, dir,
               p.card_ink);
    const float body_top =
        title_top + static_cast<float>(titles.size()) * title.line_height() + body.line_height() * 0.3f;
    const auto bodies = fitting(body_lines, body_top, r.y + r.h - pad * 0.5f, body.line_height());
    text_lines(text[1], body, bodies, 1.0f, r.x + pad, r.w - 2 * pad, body_top + body.ascent(), align, dir, p.card_ink);
}

void Overlay::draw(const std::vector<Control>& controls, const LabelCard& card, unsigned framebuffer, int width,
                   int height, std::span<const Vertex2d> under) {
    if (!s_) return;
    State& s = *s_;
    // Glyphs new this frame may grow an atlas and stale the quads laid out before: then once more.
    const uint64_t epochs = s.title_atlas->epoch() + s.body_atlas->epoch();
    s.build(controls, card, under);
    if (s.title_atlas->epoch() + s.body_atlas->epoch() != epochs) s.build(controls, card, under);
    s.upload();

    // Lines and boxes in one draw through the colour-only shader: llvmpipe shades
    // every box pixel, and the atlas shader's texture branch and uv varying cost
    // it there. That shader is made at the second draw, so the kiosk's first
    // frame compiles no more than before; the first draw's boxes go through
    // the atlas shader (at most one level apart on translucent pixels).
    if (s.draws < 2 && ++s.draws == 2)
        (void)s.solid_batch.init("overlay boxes", Batch2d::Shading::Solid);  // else: the atlas one
    Batch2d& boxes = s.solid_batch.ready() ? s.solid_batch : s.batch;
    boxes.begin(framebuffer, width, height);
    boxes.draw(s.solid);
    s.batch.begin(framebuffer, width, height);
    s.batch.draw(s.text[0], s.sizes[s.size].textures[0].id());
    s.batch.draw(s.text[1], s.sizes[s.size].textures[1].id());
    s.batch.end();
}

void Overlay::set_look(bool high_contrast, bool large_text) {
    if (!s_) return;
    s_->high_contrast = high_contrast;
    s_->use_size(large_text ? 1 : 0);
}

void Overlay::set_language(const std::string& language) {
    if (!s_) return;
    if (s_->fonts->set_language(language)) s_->fitted.clear();  // fits measured in the other face
}

}  // namespace body::kiosk
