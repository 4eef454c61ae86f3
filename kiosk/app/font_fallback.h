#pragma once
// Fonts for every script, opened lazily. A FontSet lists font files (the UI
// font first, then fallbacks: Noto Sans Arabic, Noto Sans Hebrew, Noto Sans
// CJK); only the first is read at open(). A fallback file is mapped and parsed
// the first time a string needs a character the fonts read so far do not draw,
// so the kiosk's first frame pays only for the scripts it shows.
//
// Per-character choice (font_for): a letter of a script with a preferred font
// (Arabic, Hebrew, Han/Kana/Hangul) takes that font when it draws it; any other
// character stays in the font of the character before it when that font draws
// it (digits and spaces inside an Arabic word keep the Arabic font's metrics);
// otherwise the first listed font that draws it. -1 when none does.
//
// Faces per language (set_language): in a collection (.ttc) whose faces are
// named by region, as Noto Sans CJK's JP/KR/SC/TC/HK, Han characters take the
// face of the language's region (cjk_face_tags), since one character's glyph
// differs between them (直, 骨); other languages take the collection's first
// face. The chosen face is a font of its own (its own index, opened lazily).
//
// Sizes: every font is scaled to the same em size, derived from the first
// font so that its ascent-descent equals the requested pixel height.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "shared/error.h"

struct hb_font_t;

namespace body::kiosk {

// One glyph's coverage bitmap, 2x horizontally oversampled and prefiltered so
// that it samples well at fractional pen positions.
struct GlyphBitmap {
    int width = 0, height = 0;             // bitmap pixels
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // quad, pixels from the pen position, y down
    std::vector<uint8_t> coverage;         // width*height, row 0 at top
};

class FontSet {
public:
    // The UI font then every installed fallback of default_fallback_fonts().
    static std::vector<std::string> every_script(const std::string& primary);
    // Opens the first file (an error names it when it is unreadable or not a
    // TrueType/OpenType font); the others are only remembered. A fallback that
    // later fails to open is skipped, with one line on stderr.
    static Result<std::shared_ptr<FontSet>> open(const std::vector<std::string>& files);
    ~FontSet();
    FontSet(const FontSet&) = delete;
    FontSet& operator=(const FontSet&) = delete;

    size_t size() const;    // fonts listed
    size_t loaded() const;  // font files read so far
    const std::string& file(int font) const;
    int face(int font) const;  // the face index in its file

    // The language (BCP 47) whose CJK face the next font_for calls choose;
    // true when that changes the face (shaped text cached before is stale).
    bool set_language(const std::string& language);
    // The chosen face's region tag ("SC"), or "" for a collection's first face.
    const std::string& face_tag() const;

    // The font that draws `c` (rules above); `previous` is the font of the
    // character before it, or -1.
    int font_for(char32_t c, int previous);
    // HarfBuzz font of a loaded font, scaled to font units (1 unit = 1/upem em).
    hb_font_t* shaper(int font);
    // Pixels per font unit of `font` at em size `em_px`.
    float scale(int font, float em_px) const;
    // The em size that gives the first font an ascent-descent of `pixel_height`,
    // and that font's ascent and line height (ascent - descent + gap) at it.
    float em_for_pixel_height(float pixel_height) const;
    void vertical_metrics(float em_px, float& ascent, float& line_height) const;
    GlyphBitmap rasterize(int font, uint32_t glyph, float em_px) const;

private:
    FontSet();
    struct Impl;
    std::unique_ptr<Impl> p_;
};

// Installed Debian fallback fonts: fonts-noto-core (Arabic, Hebrew) and
// fonts-noto-cjk (Chinese, Japanese, Korean); missing files are left out.
std::vector<std::string> default_fallback_fonts();

// The region tags of the CJK faces `language` (BCP 47: "zh-Hans", "zh-TW",
// "ja", "ko") wants, most wanted first; empty for other languages.
std::vector<std::string> cjk_face_tags(const std::string& language);

}  // namespace body::kiosk
