// Glyph atlas with stb_truetype's packer (Sean Barrett, stb_truetype.h, public
// domain): codepoints collected from fixed ranges and the scene's texts, packed
// with 2x horizontal oversampling into a square power-of-two bitmap.
#include "kiosk/app/text.h"

#include <algorithm>
#include <set>

#include "shared/atomic_file.h"

#define STBTT_STATIC
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

namespace body::kiosk {

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

Result<GlyphAtlas> GlyphAtlas::build(const std::string& font_file, float pixel_height, std::string_view extra_text) {
    auto font = read_file(font_file);
    if (!font) return font.error();
    const auto* data = reinterpret_cast<const unsigned char*>(font->data());
    stbtt_fontinfo info;
    if (stbtt_GetFontOffsetForIndex(data, 0) < 0 ||
        !stbtt_InitFont(&info, data, stbtt_GetFontOffsetForIndex(data, 0))) {
        return input_error(font_file + ": byte 0: not a TrueType font");
    }
    std::set<char32_t> wanted;
    for (char32_t c = 0x20; c < 0x7F; ++c) wanted.insert(c);
    for (char32_t c = 0xA0; c < 0x180; ++c) wanted.insert(c);
    for (char32_t c = 0x391; c < 0x3CA; ++c) wanted.insert(c);
    for (char32_t c : std::u32string_view(U"\u2013\u2014\u2018\u2019\u201C\u201D\u2022\u2026\u2212\u2302\uFFFD")) {
        wanted.insert(c);
    }
    for (char32_t c : decode_utf8(extra_text)) {
        if (c >= 0x20) wanted.insert(c);
    }
    std::vector<int> codepoints;
    for (char32_t c : wanted) {
        if (stbtt_FindGlyphIndex(&info, static_cast<int>(c)) != 0) codepoints.push_back(static_cast<int>(c));
    }

    GlyphAtlas atlas;
    atlas.pixel_height_ = pixel_height;
    std::vector<stbtt_packedchar> packed(codepoints.size());
    for (int size = 256; size <= 4096; size *= 2) {
        atlas.width_ = atlas.height_ = size;
        atlas.pixels_.assign(static_cast<size_t>(size) * static_cast<size_t>(size), 0);
        stbtt_pack_context pc;
        if (!stbtt_PackBegin(&pc, atlas.pixels_.data(), size, size, 0, 1, nullptr)) {
            return runtime_error(font_file + ": cannot start the glyph packer");
        }
        stbtt_PackSetOversampling(&pc, 2, 1);
        stbtt_pack_range range{};
        range.font_size = pixel_height;
        range.array_of_unicode_codepoints = codepoints.data();
        range.num_chars = static_cast<int>(codepoints.size());
        range.chardata_for_range = packed.data();
        const int ok = stbtt_PackFontRanges(&pc, data, 0, &range, 1);
        stbtt_PackEnd(&pc);
        if (ok) break;
        if (size == 4096) return runtime_error(font_file + ": glyphs do not fit a 4096x4096 atlas");
    }
    const float scale = stbtt_ScaleForPixelHeight(&info, pixel_height);
    int ascent = 0, descent = 0, gap = 0;
    stbtt_GetFontVMetrics(&info, &ascent, &descent, &gap);
    atlas.ascent_ = static_cast<float>(ascent) * scale;
    atlas.line_height_ = static_cast<float>(ascent - descent + gap) * scale;
    for (size_t i = 0; i < codepoints.size(); ++i) {
        float x = 0.0f, y = 0.0f;
        stbtt_aligned_quad q;
        stbtt_GetPackedQuad(packed.data(), atlas.width_, atlas.height_, static_cast<int>(i), &x, &y, &q, 0);
        atlas.glyphs_.push_back(Glyph{static_cast<char32_t>(codepoints[i]), q.x0, q.y0, q.x1, q.y1, q.s0, q.t0, q.s1,
                                      q.t1, packed[i].xadvance});
    }
    return atlas;
}

const GlyphAtlas::Glyph* GlyphAtlas::find(char32_t codepoint) const {
    auto it = std::lower_bound(glyphs_.begin(), glyphs_.end(), codepoint,
                               [](const Glyph& g, char32_t c) { return g.codepoint < c; });
    return it != glyphs_.end() && it->codepoint == codepoint ? &*it : nullptr;
}

bool GlyphAtlas::has(char32_t codepoint) const { return find(codepoint) != nullptr; }

std::vector<GlyphQuad> GlyphAtlas::layout(std::u32string_view text, float x, float y, float* advance) const {
    std::vector<GlyphQuad> out;
    const float x_start = x;
    for (char32_t c : text) {
        const Glyph* g = find(c);
        if (!g) g = find(U'\uFFFD');
        if (!g) g = find(U'?');
        if (!g) continue;
        if (g->x1 > g->x0 && c != U' ') {
            out.push_back(GlyphQuad{x + g->x0, y + g->y0, x + g->x1, y + g->y1, g->s0, g->t0, g->s1, g->t1, c});
        }
        x += g->advance;
    }
    if (advance) *advance = x - x_start;
    return out;
}

float GlyphAtlas::measure(std::u32string_view text) const {
    float w = 0.0f;
    (void)layout(text, 0.0f, 0.0f, &w);
    return w;
}

std::vector<TextLine> GlyphAtlas::wrap(std::u32string_view text, float max_width) const {
    std::vector<TextLine> lines;
    std::u32string current;
    auto flush = [&] {
        while (!current.empty() && current.back() == U' ') current.pop_back();
        lines.push_back(TextLine{current, measure(current)});
        current.clear();
    };
    size_t i = 0;
    while (i < text.size()) {
        if (text[i] == U'\n') {
            flush();
            ++i;
            continue;
        }
        size_t j = i;
        while (j < text.size() && text[j] != U' ' && text[j] != U'\n') ++j;
        std::u32string word(text.substr(i, j - i));
        const std::u32string candidate = current.empty() ? word : current + U" " + word;
        if (measure(candidate) <= max_width || (current.empty() && word.size() <= 1)) {
            current = candidate;
        } else if (!current.empty() && measure(word) <= max_width) {
            flush();
            current = word;
        } else {
            // Break an over-long word at the width.
            if (!current.empty()) flush();
            for (char32_t c : word) {
                if (!current.empty() && measure(current + c) > max_width) flush();
                current.push_back(c);
            }
        }
        i = j;
        while (i < text.size() && text[i] == U' ') ++i;
    }
    if (!current.empty() || lines.empty()) flush();
    return lines;
}

}  // namespace body::kiosk
