#pragma once
// UI text: UTF-8 decoding, a glyph atlas filled on demand, shaped layout
// (text_shaping.h: bidi, HarfBuzz, font fallback) into textured quads, line
// wrapping and the rule that fits a control's text to its button. No GL here:
// the atlas is a single-channel coverage bitmap the overlay uploads whenever
// generation() changes.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "kiosk/app/text_shaping.h"
#include "shared/error.h"

namespace body::kiosk {

// Decodes UTF-8; invalid or truncated sequences and overlong forms become U+FFFD.
std::u32string decode_utf8(std::string_view text);

// The font the build configured (BODY_FONT_FILE).
const char* default_font_file();

struct GlyphQuad {
    float x0, y0, x1, y1;  // pixels, y down
    float s0, t0, s1, t1;  // atlas texture coordinates in [0, 1]
    char32_t codepoint;    // the first character the glyph draws
};

struct TextLine {
    std::u32string text;
    float width = 0.0f;
};

class GlyphAtlas {
public:
    // An atlas at `pixel_height` over FontSet::every_script(font_file); only
    // that file is read now, fallbacks and glyphs when a string needs them.
    static Result<GlyphAtlas> build(const std::string& font_file, float pixel_height);
    // An atlas sharing already opened fonts (one FontSet for all sizes).
    GlyphAtlas(std::shared_ptr<FontSet> fonts, float pixel_height);
    GlyphAtlas() = default;

    int width() const { return width_; }
    int height() const { return height_; }
    const std::vector<uint8_t>& pixels() const { return pixels_; }  // width*height coverage, row 0 at top
    // Changes whenever pixels() does; epoch() whenever earlier quads' texture
    // coordinates became stale (the atlas grew or was refilled).
    uint64_t generation() const { return generation_; }
    uint64_t epoch() const { return epoch_; }
    // Shaped lines held in the cache (bounded, whatever the text seen).
    size_t shaped_lines() const { return shaped_.size() + shaped_previous_.size(); }
    float pixel_height() const { return pixel_height_; }
    float ascent() const { return ascent_; }
    float line_height() const { return line_height_; }
    FontSet& fonts() { return *fonts_; }
    // Some font of the set draws `codepoint` (may open a fallback font).
    bool has(char32_t codepoint);

    // Quads for one line with its baseline starting at (x, y), shaped and in
    // visual order; glyphs are rasterised into the atlas on first use. Returns
    // the advance width via `advance`.
    std::vector<GlyphQuad> layout(std::u32string_view text, float x, float y, float* advance = nullptr,
                                  TextDirection direction = TextDirection::Auto);
    float measure(std::u32string_view text, TextDirection direction = TextDirection::Auto);
    // Greedy wrap at line_break_opportunities() (a part longer than the width is broken).
    std::vector<TextLine> wrap(std::u32string_view text, float max_width);

private:
    struct Slot {
        int ax = 0, ay = 0, w = 0, h = 0;  // atlas pixels; w == 0: blank glyph
        float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    };
    const ShapedText& shaped(std::u32string_view text, TextDirection direction);
    const Slot& slot(int font, uint32_t glyph);
    bool place(int w, int h, int& ax, int& ay);
    void grow_or_refill();

    std::shared_ptr<FontSet> fonts_;
    float pixel_height_ = 0.0f, em_px_ = 0.0f, ascent_ = 0.0f, line_height_ = 0.0f;
    int width_ = 0, height_ = 0;
    std::vector<uint8_t> pixels_;
    int shelf_x_ = 0, shelf_y_ = 0, shelf_h_ = 0;
    uint64_t generation_ = 0, epoch_ = 0;
    std::unordered_map<uint64_t, Slot> slots_;  // font << 32 | glyph
    // Shaped lines by direction + text, in two generations: a full current one
    // becomes the previous one, and a hit there moves back. Lines used every
    // frame stay; the many one-off prefixes wrap() measures are bounded.
    std::unordered_map<std::u32string, ShapedText> shaped_, shaped_previous_;
};

// How a control's text fits a w x h box, by rule: one line at full size; else
// the larger of one line shrunk (to no less than kMinTextScale) and two or more
// lines broken at line_break_opportunities (largest scale that fits, 5 % steps);
// else, at kMinTextScale, the lines at break opportunities the box holds with
// each too-wide line cut and ended with "…" (abbreviated: "cerebel…" / "left").
// Never wider or taller than the box.
inline constexpr float kMinTextScale = 0.7f;
struct FittedText {
    std::vector<TextLine> lines;  // widths unscaled
    float scale = 1.0f;
    bool abbreviated = false;
    bool rtl = false;
    float width = 0.0f, height = 0.0f;  // scaled extent of the lines
};
FittedText fit_text(GlyphAtlas& atlas, std::u32string_view text, float w, float h);

}  // namespace body::kiosk
