#pragma once
// UI text: UTF-8 decoding, a glyph atlas baked with stb_truetype (DejaVu Sans by
// default, BODY_FONT_FILE) and text layout into textured quads. No GL here: the
// atlas is a single-channel coverage bitmap the renderer uploads once.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "shared/error.h"

namespace body::kiosk {

// Decodes UTF-8; invalid or truncated sequences and overlong forms become U+FFFD.
std::u32string decode_utf8(std::string_view text);

// The font the build configured (BODY_FONT_FILE).
const char* default_font_file();

struct GlyphQuad {
    float x0, y0, x1, y1;  // pixels, y down
    float s0, t0, s1, t1;  // atlas texture coordinates in [0, 1]
    char32_t codepoint;
};

struct TextLine {
    std::u32string text;
    float width = 0.0f;
};

class GlyphAtlas {
public:
    // Bakes printable ASCII, Latin-1, Latin Extended-A, Greek, a few symbols and
    // every codepoint in `extra_text` (UTF-8, e.g. all label texts) at `pixel_height`.
    static Result<GlyphAtlas> build(const std::string& font_file, float pixel_height, std::string_view extra_text = {});

    int width() const { return width_; }
    int height() const { return height_; }
    const std::vector<uint8_t>& pixels() const { return pixels_; }  // width*height coverage, row 0 at top
    float pixel_height() const { return pixel_height_; }
    float ascent() const { return ascent_; }
    float line_height() const { return line_height_; }
    bool has(char32_t codepoint) const;

    // Quads for `text` with its baseline starting at (x, y). Codepoints not in the
    // atlas use U+FFFD (or '?'). Returns the advance width via `advance`.
    std::vector<GlyphQuad> layout(std::u32string_view text, float x, float y, float* advance = nullptr) const;
    float measure(std::u32string_view text) const;
    // Greedy word wrap at spaces (a word longer than the width is broken).
    std::vector<TextLine> wrap(std::u32string_view text, float max_width) const;

private:
    struct Glyph {
        char32_t codepoint;
        float x0, y0, x1, y1;  // offsets from the pen position
        float s0, t0, s1, t1;
        float advance;
    };
    const Glyph* find(char32_t codepoint) const;

    int width_ = 0, height_ = 0;
    std::vector<uint8_t> pixels_;
    std::vector<Glyph> glyphs_;  // sorted by codepoint
    float pixel_height_ = 0.0f, ascent_ = 0.0f, line_height_ = 0.0f;
};

}  // namespace body::kiosk
