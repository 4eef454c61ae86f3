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

#include <cstdio>
#include <filesystem>

#define STBTT_STATIC
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

namespace body::kiosk {

namespace {

constexpr int kOversampleX = 2;

struct Font {
    std::string file;
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
    const int offset = stbtt_GetFontOffsetForIndex(data, 0);  // a collection's first face
    if (offset < 0 || !stbtt_InitFont(&f.info, data, offset)) return false;
    hb_blob_t* blob = hb_blob_create(static_cast<const char*>(f.map), static_cast<unsigned>(f.size),
                                     HB_MEMORY_MODE_READONLY, nullptr, nullptr);
    hb_face_t* face = hb_face_create(blob, 0);
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

}  // namespace

struct FontSet::Impl {
    std::vector<Font> fonts;
};

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

int FontSet::font_for(char32_t c, int previous) {
    auto& fonts = p_->fonts;
    const int n = static_cast<int>(fonts.size());
    if (const char* tag = preferred_tag(c)) {
        for (int i = 0; i < n; ++i) {
            if (fonts[static_cast<size_t>(i)].file.find(tag) == std::string::npos) continue;
            if (draws(fonts[static_cast<size_t>(i)], c)) return i;
        }
    } else if (previous >= 0 && previous < n && draws(fonts[static_cast<size_t>(previous)], c)) {
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
