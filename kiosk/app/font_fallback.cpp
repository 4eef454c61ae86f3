// Lazily opened fonts (contract in font_fallback.h): files are memory-mapped,
// parsed by stb_truetype (Sean Barrett, public domain) for coverage tests and
// glyph bitmaps, and by HarfBuzz for shaping (text_shaping.cpp).
#include "kiosk/app/font_fallback.h"

#include <fcntl.h>
#include <hb-ot.h>
#include <hb.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <utility>

#define STBTT_STATIC
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

namespace body::kiosk {

namespace {

constexpr int kOversampleX = 2;

struct Font {
    std::string file;
    int face = 0;        // the face's index in a collection (.ttc); 0 in a single-face file
    bool tried = false;  // opened (or failed to) already
    bool ok = false;
    void* map = nullptr;
    size_t size = 0;
    stbtt_fontinfo info{};
    hb_font_t* hb = nullptr;
    int upem = 1000;
};

// The name part a fallback file must contain to be preferred for `c`, or null
// for characters every font may draw (Latin, Greek, Cyrillic, digits, marks).
const char* preferred_tag(char32_t c) {
    if ((c >= 0x0600 && c <= 0x06FF) || (c >= 0x0750 && c <= 0x077F) || (c >= 0x08A0 && c <= 0x08FF) ||
        (c >= 0xFB50 && c <= 0xFDFF) || (c >= 0xFE70 && c <= 0xFEFF))
        return "Arabic";
    if ((c >= 0x0590 && c <= 0x05FF) || (c >= 0xFB1D && c <= 0xFB4F)) return "Hebrew";
    if ((c >= 0x1100 && c <= 0x11FF) || (c >= 0x2E80 && c <= 0x9FFF) || (c >= 0xAC00 && c <= 0xD7AF) ||
        (c >= 0xF900 && c <= 0xFAFF) || (c >= 0xFF00 && c <= 0xFFEF) || (c >= 0x20000 && c <= 0x3FFFF))
        return "CJK";
    return nullptr;
}

bool open_font(Font& f) {
    if (f.tried) return f.ok;
    f.tried = true;
    const int fd = ::open(f.file.c_str(), O_RDONLY | O_CLOEXEC);
    struct stat st {};
    if (fd < 0 || fstat(fd, &st) != 0 || st.st_size <= 0) {
        if (fd >= 0) ::close(fd);
        return false;
    }
    f.size = static_cast<size_t>(st.st_size);
    f.map = mmap(nullptr, f.size, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (f.map == MAP_FAILED) {
        f.map = nullptr;
        return false;
    }
    const auto* data = static_cast<const unsigned char*>(f.map);
    const int offset = stbtt_GetFontOffsetForIndex(data, f.face);
    if (offset < 0 || !stbtt_InitFont(&f.info, data, offset)) return false;
    hb_blob_t* blob = hb_blob_create(static_cast<const char*>(f.map), static_cast<unsigned>(f.size),
                                     HB_MEMORY_MODE_READONLY, nullptr, nullptr);
    hb_face_t* face = hb_face_create(blob, static_cast<unsigned>(f.face));
    hb_blob_destroy(blob);
    f.upem = static_cast<int>(hb_face_get_upem(face));
    f.hb = hb_font_create(face);
    hb_face_destroy(face);
    hb_font_set_scale(f.hb, f.upem, f.upem);
    f.ok = f.upem > 0;
    return f.ok;
}

void close_font(Font& f) {
    if (f.hb) hb_font_destroy(f.hb);
    if (f.map) munmap(f.map, f.size);
    f.hb = nullptr;
    f.map = nullptr;
}

bool draws(Font& f, char32_t c) { return open_font(f) && stbtt_FindGlyphIndex(&f.info, static_cast<int>(c)) != 0; }

// The face of an opened collection whose family name ends in " <tag>" ("Noto
// Sans CJK SC"), or -1. Read from the name tables, so any collection whose
// faces are named by region works, whatever their order.
int face_named(const Font& f, const std::string& tag) {
    hb_blob_t* blob = hb_blob_create(static_cast<const char*>(f.map), static_cast<unsigned>(f.size),
                                     HB_MEMORY_MODE_READONLY, nullptr, nullptr);
    const unsigned count = hb_face_count(blob);
    int found = -1;
    for (unsigned k = 0; k < count && found < 0; ++k) {
        hb_face_t* face = hb_face_create(blob, k);
        char name[128] = {};
        unsigned len = sizeof name;
        hb_ot_name_get_utf8(face, HB_OT_NAME_ID_FONT_FAMILY, hb_language_from_string("en", -1), &len, name);
        const std::string family(name);
        if (family.size() > tag.size() && family.compare(family.size() - tag.size(), tag.size(), tag) == 0 &&
            family[family.size() - tag.size() - 1] == ' ')
            found = static_cast<int>(k);
        hb_face_destroy(face);
    }
    hb_blob_destroy(blob);
    return found;
}

}  // namespace

// The region tags of CJK collection faces for a BCP 47 language, most wanted
// first: Simplified Chinese SC, Traditional TC (Hong Kong HK, then TC),
// Japanese JP, Korean KR; none for other languages (a collection's first face).
std::vector<std::string> cjk_face_tags(const std::string& language) {
    std::string lang;
    for (char ch : language) lang += ch == '_' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    const std::string primary = lang.substr(0, lang.find('-'));
    auto has = [&](const char* subtag) {
        return (lang + "-").find(std::string("-") + subtag + "-") != std::string::npos;
    };
    if (primary == "ja") return {"JP"};
    if (primary == "ko") return {"KR"};
    if (primary != "zh") return {};
    if (has("hk") || has("mo")) return {"HK", "TC"};
    if (has("hant") || has("tw")) return {"TC"};
    return {"SC"};  // zh, zh-Hans, zh-CN, zh-SG
}

struct FontSet::Impl {
    std::vector<Font> fonts;
    size_t listed = 0;              // fonts[0, listed) are the files given; the rest are faces added by variant()
    std::vector<std::string> tags;  // cjk_face_tags of the language set
    std::string language;
    std::map<std::pair<size_t, std::string>, size_t> variants;  // (listed font, first tag) -> font
    size_t variant(size_t listed_font);
};

// The face of listed font `i` the language wants: another face of the same
// collection, added to `fonts` on first use (indices already handed out stay
// valid), or `i` itself when the file has no such face.
size_t FontSet::Impl::variant(size_t i) {
    if (tags.empty()) return i;
    const auto key = std::make_pair(i, tags.front());
    if (auto it = variants.find(key); it != variants.end()) return it->second;
    size_t out = i;
    if (open_font(fonts[i])) {
        int face = -1;
        for (size_t t = 0; t < tags.size() && face < 0; ++t) face = face_named(fonts[i], tags[t]);
        if (face > 0 && face != fonts[i].face) {
            fonts.push_back(Font{fonts[i].file, face});
            out = fonts.size() - 1;
        }
    }
    variants.emplace(key, out);
    return out;
}

FontSet::FontSet() : p_(std::make_unique<Impl>()) {}

FontSet::~FontSet() {
    for (Font& f : p_->fonts) close_font(f);
}

std::vector<std::string> default_fallback_fonts() {
    std::vector<std::string> out;
    for (const char* f : {"/usr/share/fonts/truetype/noto/NotoSansArabic-Regular.ttf",
                          "/usr/share/fonts/truetype/noto/NotoSansHebrew-Regular.ttf",
                          "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc"}) {
        std::error_code ec;
        if (std::filesystem::exists(f, ec)) out.emplace_back(f);
    }
    return out;
}

std::vector<std::string> FontSet::every_script(const std::string& primary) {
    std::vector<std::string> out{primary};
    for (auto& f : default_fallback_fonts())
        if (f != primary) out.push_back(std::move(f));
    return out;
}

Result<std::shared_ptr<FontSet>> FontSet::open(const std::vector<std::string>& files) {
    if (files.empty()) return input_error("no font file given");
    std::shared_ptr<FontSet> set(new FontSet());
    for (const std::string& f : files) set->p_->fonts.push_back(Font{f});
    set->p_->listed = files.size();
    Font& first = set->p_->fonts.front();
    if (!open_font(first)) {
        std::error_code ec;
        if (!std::filesystem::exists(first.file, ec)) return input_error(first.file + ": cannot open: no such file");
        return input_error(first.file + ": byte 0: not a TrueType/OpenType font");
    }
    return set;
}

size_t FontSet::size() const { return p_->fonts.size(); }

size_t FontSet::loaded() const {
    size_t n = 0;
    for (const Font& f : p_->fonts) n += f.ok;
    return n;
}

const std::string& FontSet::file(int font) const { return p_->fonts[static_cast<size_t>(font)].file; }

int FontSet::face(int font) const { return p_->fonts[static_cast<size_t>(font)].face; }

bool FontSet::set_language(const std::string& language) {
    if (language == p_->language) return false;
    auto tags = cjk_face_tags(language);
    p_->language = language;
    const bool changed = tags != p_->tags;
    p_->tags = std::move(tags);
    return changed;
}

const std::string& FontSet::face_tag() const {
    static const std::string none;
    return p_->tags.empty() ? none : p_->tags.front();
}

int FontSet::font_for(char32_t c, int previous) {
    auto& fonts = p_->fonts;
    const int n = static_cast<int>(p_->listed);
    if (const char* tag = preferred_tag(c)) {
        for (int i = 0; i < n; ++i) {
            if (fonts[static_cast<size_t>(i)].file.find(tag) == std::string::npos) continue;
            const size_t v = std::strcmp(tag, "CJK") == 0 ? p_->variant(static_cast<size_t>(i)) : size_t(i);
            if (draws(fonts[v], c)) return static_cast<int>(v);
            if (draws(fonts[static_cast<size_t>(i)], c)) return i;
        }
    } else if (previous >= 0 && previous < static_cast<int>(fonts.size()) &&
               draws(fonts[static_cast<size_t>(previous)], c)) {
        return previous;
    }
    for (int i = 0; i < n; ++i) {
        Font& f = fonts[static_cast<size_t>(i)];
        const bool was_tried = f.tried;
        if (draws(f, c)) return i;
        if (!was_tried && !f.ok)
            std::fprintf(stderr, "bodyview: font %s skipped: not a readable TrueType/OpenType font\n", f.file.c_str());
    }
    return -1;
}

hb_font_t* FontSet::shaper(int font) { return p_->fonts[static_cast<size_t>(font)].hb; }

float FontSet::scale(int font, float em_px) const {
    return em_px / static_cast<float>(p_->fonts[static_cast<size_t>(font)].upem);
}

float FontSet::em_for_pixel_height(float pixel_height) const {
    const Font& f = p_->fonts.front();
    // stbtt_ScaleForPixelHeight maps ascent-descent to the height; as an em size:
    return stbtt_ScaleForPixelHeight(&f.info, pixel_height) * static_cast<float>(f.upem);
}

void FontSet::vertical_metrics(float em_px, float& ascent, float& line_height) const {
    const Font& f = p_->fonts.front();
    int a = 0, d = 0, gap = 0;
    stbtt_GetFontVMetrics(&f.info, &a, &d, &gap);
    const float s = em_px / static_cast<float>(f.upem);
    ascent = static_cast<float>(a) * s;
    line_height = static_cast<float>(a - d + gap) * s;
}

GlyphBitmap FontSet::rasterize(int font, uint32_t glyph, float em_px) const {
    const Font& f = p_->fonts[static_cast<size_t>(font)];
    GlyphBitmap b;
    if (!f.ok) return b;
    const float s = stbtt_ScaleForMappingEmToPixels(&f.info, em_px);
    const int g = static_cast<int>(glyph);
    int ix0 = 0, iy0 = 0, ix1 = 0, iy1 = 0;
    stbtt_GetGlyphBitmapBoxSubpixel(&f.info, g, s * kOversampleX, s, 0, 0, &ix0, &iy0, &ix1, &iy1);
    if (ix1 <= ix0 || iy1 <= iy0) return b;  // blank (a space)
    b.width = ix1 - ix0 + kOversampleX - 1;
    b.height = iy1 - iy0;
    b.coverage.assign(static_cast<size_t>(b.width) * static_cast<size_t>(b.height), 0);
    float sub_x = 0, sub_y = 0;
    stbtt_MakeGlyphBitmapSubpixelPrefilter(&f.info, b.coverage.data(), b.width, b.height, b.width, s * kOversampleX, s,
                                           0, 0, kOversampleX, 1, &sub_x, &sub_y, g);
    b.x0 = static_cast<float>(ix0) / kOversampleX + sub_x;
    b.y0 = static_cast<float>(iy0) + sub_y;
    b.x1 = static_cast<float>(ix0 + b.width) / kOversampleX + sub_x;
    b.y1 = static_cast<float>(iy1) + sub_y;
    return b;
}

}  // namespace body::kiosk
