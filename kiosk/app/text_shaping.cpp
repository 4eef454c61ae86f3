// One line through FriBidi and HarfBuzz (contract in text_shaping.h).
#include "kiosk/app/text_shaping.h"

#include <fribidi.h>
#include <hb.h>
#include <unicode/ubrk.h>

#include <algorithm>
#include <memory>

namespace body::kiosk {

namespace {

struct Run {
    size_t start = 0, length = 0;
    int font = 0;
    FriBidiLevel level = 0;
};

const FriBidiChar* as_fribidi(std::u32string_view s) { return reinterpret_cast<const FriBidiChar*>(s.data()); }

// Embedding levels of every character (rules P2-I2 with bracket pairs).
std::vector<FriBidiLevel> bidi_levels(std::u32string_view text, TextDirection direction, bool& rtl) {
    const auto n = static_cast<FriBidiStrIndex>(text.size());
    std::vector<FriBidiCharType> types(text.size());
    std::vector<FriBidiBracketType> brackets(text.size());
    std::vector<FriBidiLevel> levels(text.size(), 0);
    fribidi_get_bidi_types(as_fribidi(text), n, types.data());
    fribidi_get_bracket_types(as_fribidi(text), n, types.data(), brackets.data());
    FriBidiParType base = direction == TextDirection::LeftToRight   ? FRIBIDI_PAR_LTR
                          : direction == TextDirection::RightToLeft ? FRIBIDI_PAR_RTL
                                                                    : FRIBIDI_PAR_ON;
    if (fribidi_get_par_embedding_levels_ex(types.data(), brackets.data(), n, &base, levels.data()) == 0)
        std::fill(levels.begin(), levels.end(), FriBidiLevel{0});
    rtl = FRIBIDI_IS_RTL(base);
    return levels;
}

// Maximal runs of one level and one font; characters no font draws become U+FFFD.
std::vector<Run> itemize(FontSet& fonts, std::u32string& text, const std::vector<FriBidiLevel>& levels) {
    std::vector<Run> runs;
    int previous = -1;
    for (size_t i = 0; i < text.size(); ++i) {
        int font = fonts.font_for(text[i], previous);
        if (font < 0) {
            text[i] = U'\uFFFD';
            font = fonts.font_for(text[i], previous);
            if (font < 0) font = previous >= 0 ? previous : 0;  // drawn as the font's missing-glyph box
        }
        if (runs.empty() || runs.back().font != font || runs.back().level != levels[i])
            runs.push_back(Run{i, 0, font, levels[i]});
        ++runs.back().length;
        previous = font;
    }
    return runs;
}

// Rule L2: from the highest level down to the lowest odd one, reverse every
// maximal sequence of runs at that level or higher.
void visual_order(std::vector<Run>& runs) {
    int highest = 0, lowest_odd = 255;
    for (const Run& r : runs) {
        highest = std::max(highest, static_cast<int>(r.level));
        if (r.level % 2) lowest_odd = std::min(lowest_odd, static_cast<int>(r.level));
    }
    for (int level = highest; level >= lowest_odd && level > 0; --level) {
        for (size_t i = 0; i < runs.size();) {
            if (runs[i].level < level) {
                ++i;
                continue;
            }
            size_t j = i;
            while (j < runs.size() && runs[j].level >= level) ++j;
            std::reverse(runs.begin() + static_cast<std::ptrdiff_t>(i), runs.begin() + static_cast<std::ptrdiff_t>(j));
            i = j;
        }
    }
}

}  // namespace

ShapedText shape_text(FontSet& fonts, std::u32string_view line, float em_px, TextDirection direction) {
    ShapedText out;
    if (line.empty()) {
        out.rtl = direction == TextDirection::RightToLeft;
        return out;
    }
    std::u32string text(line);
    const auto levels = bidi_levels(text, direction, out.rtl);
    auto runs = itemize(fonts, text, levels);
    visual_order(runs);
    hb_buffer_t* buffer = hb_buffer_create();
    float pen = 0.0f;
    for (const Run& r : runs) {
        hb_buffer_clear_contents(buffer);
        // The whole line is the context, so joining across run edges is right.
        hb_buffer_add_utf32(buffer, reinterpret_cast<const uint32_t*>(text.data()), static_cast<int>(text.size()),
                            static_cast<unsigned>(r.start), static_cast<int>(r.length));
        hb_buffer_set_direction(buffer, r.level % 2 ? HB_DIRECTION_RTL : HB_DIRECTION_LTR);
        hb_buffer_guess_segment_properties(buffer);
        hb_shape(fonts.shaper(r.font), buffer, nullptr, 0);
        unsigned count = 0;
        const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buffer, &count);
        const hb_glyph_position_t* pos = hb_buffer_get_glyph_positions(buffer, &count);
        const float s = fonts.scale(r.font, em_px);
        for (unsigned k = 0; k < count; ++k) {  // HarfBuzz gives glyphs in visual order for either direction
            ShapedGlyph g;
            g.font = r.font;
            g.glyph = info[k].codepoint;
            g.cluster = info[k].cluster;
            g.x = pen + static_cast<float>(pos[k].x_offset) * s;
            g.y = -static_cast<float>(pos[k].y_offset) * s;
            g.advance = static_cast<float>(pos[k].x_advance) * s;
            pen += g.advance;
            out.glyphs.push_back(g);
        }
    }
    hb_buffer_destroy(buffer);
    out.width = pen;
    return out;
}

bool is_rtl_paragraph(std::u32string_view text) {
    std::vector<FriBidiCharType> types(text.size());
    fribidi_get_bidi_types(as_fribidi(text), static_cast<FriBidiStrIndex>(text.size()), types.data());
    return FRIBIDI_IS_RTL(fribidi_get_par_direction(types.data(), static_cast<FriBidiStrIndex>(text.size())));
}

bool is_rtl_language(const std::string& language) {
    const std::string code = language.substr(0, language.find_first_of("-_"));
    for (const char* rtl : {"ar", "he", "iw", "fa", "ur", "yi", "ps", "sd", "ug", "dv", "ckb"})
        if (code == rtl) return true;
    return false;
}

std::vector<bool> line_break_opportunities(std::u32string_view t) {
    std::vector<bool> allowed(t.size(), false);
    // ICU works on UTF-16: each unit remembers the character it belongs to.
    std::vector<UChar> u16;
    std::vector<size_t> index_of;
    u16.reserve(t.size());
    for (size_t i = 0; i < t.size(); ++i) {
        const char32_t c = t[i] <= 0x10FFFF && (t[i] < 0xD800 || t[i] > 0xDFFF) ? t[i] : U'\uFFFD';
        if (c > 0xFFFF) {
            u16.push_back(static_cast<UChar>(0xD7C0 + (c >> 10)));
            u16.push_back(static_cast<UChar>(0xDC00 | (c & 0x3FF)));
            index_of.insert(index_of.end(), {i, i});
        } else {
            u16.push_back(static_cast<UChar>(c));
            index_of.push_back(i);
        }
    }
    UErrorCode err = U_ZERO_ERROR;
    // One iterator per thread: opening one loads the rules, setting its text is cheap.
    thread_local std::unique_ptr<UBreakIterator, void (*)(UBreakIterator*)> it(
        ubrk_open(UBRK_LINE, "", nullptr, 0, &err), ubrk_close);
    err = U_ZERO_ERROR;
    if (!it || u16.empty()) return allowed;
    ubrk_setText(it.get(), u16.data(), static_cast<int32_t>(u16.size()), &err);
    if (U_FAILURE(err)) return allowed;
    for (int32_t b = ubrk_first(it.get()); b != UBRK_DONE; b = ubrk_next(it.get()))
        if (b > 0 && static_cast<size_t>(b) < u16.size()) allowed[index_of[static_cast<size_t>(b)]] = true;
    return allowed;
}

}  // namespace body::kiosk
