// The glyph atlas: glyphs rasterised on first use (font_fallback.h) and packed
// on shelves into a power-of-two bitmap that grows, then refills when full;
// shaped lines (text_shaping.h) are cached by text.
#include "kiosk/app/text.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace body::kiosk {

namespace {

constexpr int kFirstAtlasSize = 512, kLargestAtlasSize = 4096, kPadding = 1;
constexpr size_t kShapedCacheLimit = 1024;  // per generation: a few MiB at most

}  // namespace

std::u32string decode_utf8(std::string_view s) {
    std::u32string out;
    out.reserve(s.size());
    size_t i = 0;
    while (i < s.size()) {
        const auto b0 = static_cast<unsigned char>(s[i]);
        int len = b0 < 0x80 ? 1 : (b0 >> 5) == 0x6 ? 2 : (b0 >> 4) == 0xE ? 3 : (b0 >> 3) == 0x1E ? 4 : 0;
        if (len == 0 || i + static_cast<size_t>(len) > s.size()) {
            out.push_back(U'\uFFFD');
            ++i;
            continue;
        }
        char32_t cp = len == 1 ? b0 : len == 2 ? (b0 & 0x1F) : len == 3 ? (b0 & 0x0F) : (b0 & 0x07);
        bool ok = true;
        for (int k = 1; k < len; ++k) {
            const auto b = static_cast<unsigned char>(s[i + static_cast<size_t>(k)]);
            if ((b & 0xC0) != 0x80) {
                ok = false;
                break;
            }
            cp = (cp << 6) | (b & 0x3F);
        }
        static constexpr char32_t kMin[5] = {0, 0, 0x80, 0x800, 0x10000};
        if (!ok || cp < kMin[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
            out.push_back(U'\uFFFD');
            ++i;  // resynchronise on the next byte
            continue;
        }
        out.push_back(cp);
        i += static_cast<size_t>(len);
    }
    return out;
}

const char* default_font_file() { return BODY_FONT_FILE; }

Result<GlyphAtlas> GlyphAtlas::build(const std::string& font_file, float pixel_height) {
    auto fonts = FontSet::open(FontSet::every_script(font_file));
    if (!fonts) return fonts.error();
    return GlyphAtlas(std::move(fonts).value(), pixel_height);
}

GlyphAtlas::GlyphAtlas(std::shared_ptr<FontSet> fonts, float pixel_height)
    : fonts_(std::move(fonts)), pixel_height_(pixel_height) {
    em_px_ = fonts_->em_for_pixel_height(pixel_height);
    fonts_->vertical_metrics(em_px_, ascent_, line_height_);
    width_ = height_ = kFirstAtlasSize;
    pixels_.assign(static_cast<size_t>(width_) * static_cast<size_t>(height_), 0);
}

bool GlyphAtlas::has(char32_t codepoint) { return fonts_ && fonts_->font_for(codepoint, -1) >= 0; }

// Shelf packing: left to right on the current shelf, a new shelf below when full.
bool GlyphAtlas::place(int w, int h, int& ax, int& ay) {
    if (shelf_x_ + w + kPadding > width_) {
        shelf_y_ += shelf_h_ + kPadding;
        shelf_x_ = 0;
        shelf_h_ = 0;
    }
    if (shelf_y_ + h + kPadding > height_ || w + kPadding > width_) return false;
    ax = shelf_x_ + kPadding;
    ay = shelf_y_ + kPadding;
    shelf_x_ += w + kPadding;
    shelf_h_ = std::max(shelf_h_, h);
    return true;
}

// Doubles the bitmap (glyphs keep their pixels; texture coordinates change),
// or at the largest size starts an empty one.
void GlyphAtlas::grow_or_refill() {
    ++epoch_;
    ++generation_;
    if (width_ < kLargestAtlasSize) {
        const int old_w = width_;
        std::vector<uint8_t> old = std::move(pixels_);
        width_ *= 2;
        height_ *= 2;
        pixels_.assign(static_cast<size_t>(width_) * static_cast<size_t>(height_), 0);
        for (int y = 0; y < old_w; ++y)
            std::memcpy(&pixels_[static_cast<size_t>(y) * static_cast<size_t>(width_)],
                        &old[static_cast<size_t>(y) * static_cast<size_t>(old_w)], static_cast<size_t>(old_w));
        shelf_y_ += shelf_h_ + kPadding;  // the old shelves are full; a new one below them
        shelf_x_ = shelf_h_ = 0;
        return;
    }
    std::fill(pixels_.begin(), pixels_.end(), uint8_t{0});
    slots_.clear();
    shelf_x_ = shelf_y_ = shelf_h_ = 0;
}

const GlyphAtlas::Slot& GlyphAtlas::slot(int font, uint32_t glyph) {
    const uint64_t key = (static_cast<uint64_t>(font) << 32) | glyph;
    if (auto it = slots_.find(key); it != slots_.end()) return it->second;
    const GlyphBitmap b = fonts_->rasterize(font, glyph, em_px_);
    Slot s;
    if (b.width > 0) {
        bool ok = place(b.width, b.height, s.ax, s.ay);
        for (int tries = 0; !ok && tries < 4; ++tries) {
            grow_or_refill();
            ok = place(b.width, b.height, s.ax, s.ay);
        }
        if (ok) {
            for (int y = 0; y < b.height; ++y)
                std::memcpy(
                    &pixels_[static_cast<size_t>(s.ay + y) * static_cast<size_t>(width_) + static_cast<size_t>(s.ax)],
                    &b.coverage[static_cast<size_t>(y) * static_cast<size_t>(b.width)], static_cast<size_t>(b.width));
            s.w = b.width;
            s.h = b.height;
            s.x0 = b.x0;
            s.y0 = b.y0;
            s.x1 = b.x1;
            s.y1 = b.y1;
            ++generation_;
        }
    }
    return slots_.emplace(key, s).first->second;
}

const ShapedText& GlyphAtlas::shaped(std::u32string_view text, TextDirection direction) {
    std::u32string key(1, static_cast<char32_t>(direction));
    for (char ch : fonts_->face_tag()) key += static_cast<char32_t>(ch);  // the CJK face chooses the glyphs
    key += U'\0';
    key += text;
    if (auto it = shaped_.find(key); it != shaped_.end()) return it->second;
    if (shaped_.size() >= kShapedCacheLimit) shaped_previous_ = std::exchange(shaped_, {});
    if (auto node = shaped_previous_.extract(key)) return shaped_.insert(std::move(node)).position->second;
    return shaped_.emplace(std::move(key), shape_text(*fonts_, text, em_px_, direction)).first->second;
}

std::vector<GlyphQuad> GlyphAtlas::layout(std::u32string_view text, float x, float y, float* advance,
                                          TextDirection direction) {
    std::vector<GlyphQuad> out;
    if (!fonts_) return out;
    const ShapedText& line = shaped(text, direction);
    for (const ShapedGlyph& g : line.glyphs) {
        const Slot& s = slot(g.font, g.glyph);
        if (s.w == 0) continue;
        const float w = static_cast<float>(width_), h = static_cast<float>(height_);
        out.push_back(GlyphQuad{x + g.x + s.x0, y + g.y + s.y0, x + g.x + s.x1, y + g.y + s.y1,
                                static_cast<float>(s.ax) / w, static_cast<float>(s.ay) / h,
                                static_cast<float>(s.ax + s.w) / w, static_cast<float>(s.ay + s.h) / h,
                                g.cluster < text.size() ? text[g.cluster] : U'\uFFFD'});
    }
    if (advance) *advance = line.width;
    return out;
}

float GlyphAtlas::measure(std::u32string_view text, TextDirection direction) {
    return fonts_ ? shaped(text, direction).width : 0.0f;
}

namespace {

std::u32string_view trimmed(std::u32string_view s) {
    while (!s.empty() && (s.back() == U' ' || s.back() == U'\u3000')) s.remove_suffix(1);
    while (!s.empty() && (s.front() == U' ' || s.front() == U'\u3000')) s.remove_prefix(1);
    return s;
}

}  // namespace

std::vector<TextLine> GlyphAtlas::wrap(std::u32string_view text, float max_width) {
    std::vector<TextLine> lines;
    auto emit = [&](std::u32string_view line) {
        line = trimmed(line);
        lines.push_back(TextLine{std::u32string(line), measure(line)});
    };
    size_t para = 0;
    while (para <= text.size()) {
        const size_t end = std::min(text.find(U'\n', para), text.size());
        const std::u32string_view p = text.substr(para, end - para);
        const auto allowed = line_break_opportunities(p);
        size_t line_start = 0, last_fit = 0;  // last_fit: a break where the line so far fits
        for (size_t i = 1; i <= p.size(); ++i) {
            if (i < p.size() && !allowed[i]) continue;
            if (measure(trimmed(p.substr(line_start, i - line_start))) <= max_width) {
                last_fit = i;
                continue;
            }
            if (last_fit > line_start) {  // the line up to the last fitting break
                emit(p.substr(line_start, last_fit - line_start));
                line_start = last_fit;
                if (measure(trimmed(p.substr(line_start, i - line_start))) <= max_width) {
                    last_fit = i;
                    continue;
                }
            }
            // One part wider than the line: broken between characters.
            size_t k = line_start + 1;
            while (true) {
                while (k < i && measure(trimmed(p.substr(line_start, k + 1 - line_start))) <= max_width) ++k;
                if (k >= i) break;
                emit(p.substr(line_start, k - line_start));
                line_start = k;
                k = line_start + 1;
            }
            last_fit = i;
        }
        if (line_start < p.size() || lines.empty() || p.empty()) emit(p.substr(line_start));
        para = end + 1;
    }
    return lines;
}

namespace {

// Greedy lines that break only at opportunities; a part wider than `max_w` stays whole on its own line.
std::vector<TextLine> lines_at_breaks(GlyphAtlas& atlas, std::u32string_view text, float max_w) {
    const auto allowed = line_break_opportunities(text);
    std::vector<TextLine> lines;
    size_t start = 0, last_fit = 0;
    auto emit = [&](size_t end) {
        const std::u32string_view l = trimmed(text.substr(start, end - start));
        lines.push_back(TextLine{std::u32string(l), atlas.measure(l)});
        start = end;
    };
    for (size_t i = 1; i <= text.size(); ++i) {
        if (i < text.size() && !allowed[i]) continue;
        if (last_fit > start && atlas.measure(trimmed(text.substr(start, i - start))) > max_w) emit(last_fit);
        last_fit = i;
    }
    if (start < text.size() || lines.empty()) emit(text.size());
    return lines;
}

// The longest start of `line` that fits `max_w` with "…" after it.
TextLine abbreviated_line(GlyphAtlas& atlas, std::u32string_view line, float max_w) {
    for (size_t n = line.size(); n-- > 0;) {
        std::u32string cut(trimmed(line.substr(0, n)));
        cut += U'\u2026';
        const float width = atlas.measure(cut);
        if (width <= max_w || n == 0) return TextLine{std::move(cut), width};
    }
    return TextLine{U"\u2026", atlas.measure(U"\u2026")};
}

}  // namespace

FittedText fit_text(GlyphAtlas& atlas, std::u32string_view text, float w, float h) {
    FittedText f;
    f.rtl = is_rtl_paragraph(text);
    const float lh = atlas.line_height();
    auto extent = [&](const std::vector<TextLine>& lines, float& width) {
        width = 0.0f;
        for (const TextLine& l : lines) width = std::max(width, l.width);
        return static_cast<float>(lines.size()) * lh;
    };
    auto accept = [&](std::vector<TextLine> lines, float scale, bool abbreviated) {
        float width = 0.0f;
        const float height = extent(lines, width);
        f.lines = std::move(lines);
        f.scale = scale;
        f.abbreviated = abbreviated;
        f.width = width * scale;
        f.height = height * scale;
        return f;
    };
    const float one = atlas.measure(text);
    const float fit_one = std::min({1.0f, w / std::max(one, 1e-3f), h / lh});
    if (fit_one >= 1.0f) return accept({TextLine{std::u32string(text), one}}, 1.0f, false);
    // Two or more lines at break opportunities: the largest scale that fits, in steps of 5 %.
    for (float scale = 1.0f; scale > fit_one && scale >= kMinTextScale - 1e-4f; scale -= 0.05f) {
        auto lines = lines_at_breaks(atlas, text, w / scale);
        float width = 0.0f;
        const float height = extent(lines, width);
        if (lines.size() > 1 && width * scale <= w && height * scale <= h)
            return accept(std::move(lines), scale, false);
    }
    if (fit_one >= kMinTextScale) return accept({TextLine{std::u32string(text), one}}, fit_one, false);
    // Abbreviated: the lines at break opportunities the box holds, each too wide
    // one cut and ended with "…" (so "cerebellum-left" keeps its side); one
    // abbreviated line when there are more lines than room.
    const float scale = std::min(kMinTextScale, h / lh);
    const auto max_lines = static_cast<size_t>(std::max(1.0f, std::floor(h / (lh * scale) + 1e-4f)));
    auto lines = lines_at_breaks(atlas, text, w / scale);
    if (lines.size() > max_lines) lines = {TextLine{std::u32string(text), one}};
    for (TextLine& l : lines)
        if (l.width * scale > w) l = abbreviated_line(atlas, l.text, w / scale);
    float width = 0.0f;
    (void)extent(lines, width);
    return accept(std::move(lines), std::min(scale, w / std::max(width, 1e-3f)), true);
}

}  // namespace body::kiosk
