#pragma once
// Shaping one line of text for any script: FriBidi (the Unicode bidirectional
// algorithm) resolves embedding levels, the line splits into runs of one level
// and one font (FontSet::font_for), HarfBuzz shapes each run (Arabic joining,
// marks, ligatures, mirrored brackets in right-to-left runs) and the runs are
// placed in visual order (rule L2). Also the line-break opportunities the
// wrapper uses: ICU's UAX #14 line breaking (CJK breaks between characters,
// never before closing punctuation; after a hyphen between letters).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "kiosk/app/font_fallback.h"

namespace body::kiosk {

enum class TextDirection { Auto, LeftToRight, RightToLeft };

struct ShapedGlyph {
    int font = 0;
    uint32_t glyph = 0;    // glyph id in that font
    uint32_t cluster = 0;  // index in the text of the first character it draws
    float x = 0, y = 0;    // pen position plus offset, pixels (y down) from the line's start
    float advance = 0;
};

struct ShapedText {
    std::vector<ShapedGlyph> glyphs;  // visual order, left to right
    float width = 0;
    bool rtl = false;  // the paragraph direction
};

// Shapes `line` (no line breaks) at em size `em_px`. Characters no font draws
// are shaped as U+FFFD (or dropped when no font has that either).
ShapedText shape_text(FontSet& fonts, std::u32string_view line, float em_px,
                      TextDirection direction = TextDirection::Auto);

// The paragraph direction by the first strong character (rules P2-P3); false when there is none.
bool is_rtl_paragraph(std::u32string_view text);
// Languages written right to left (ISO 639-1 codes, region suffix ignored: "ar", "he-IL").
bool is_rtl_language(const std::string& language);

// allowed[i]: a line may start at text[i] (UAX #14 by ICU; never at i = 0, and
// never inside a paragraph when ICU's data is missing).
std::vector<bool> line_break_opportunities(std::u32string_view text);

}  // namespace body::kiosk
