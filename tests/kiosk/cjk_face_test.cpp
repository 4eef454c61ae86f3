// The CJK face per language: Chinese text is drawn by the Simplified Chinese
// face of the Noto CJK collection, not its first (Japanese) face. 直 and 骨 are
// shaped differently in the two regions' standards, so their bitmaps tell the
// faces apart.
#include <gtest/gtest.h>

#include <filesystem>

#include "kiosk/app/font_fallback.h"
#include "kiosk/app/text_shaping.h"

namespace body::kiosk {
namespace {

TEST(CjkFaceTags, ByLanguageScriptAndRegion) {
    using V = std::vector<std::string>;
    EXPECT_EQ(cjk_face_tags("zh-Hans"), V{"SC"});
    EXPECT_EQ(cjk_face_tags("zh"), V{"SC"});
    EXPECT_EQ(cjk_face_tags("zh_CN"), V{"SC"});
    EXPECT_EQ(cjk_face_tags("zh-Hant"), V{"TC"});
    EXPECT_EQ(cjk_face_tags("zh-TW"), V{"TC"});
    EXPECT_EQ(cjk_face_tags("zh-Hant-HK"), (V{"HK", "TC"}));
    EXPECT_EQ(cjk_face_tags("ja"), V{"JP"});
    EXPECT_EQ(cjk_face_tags("ko-KR"), V{"KR"});
    EXPECT_TRUE(cjk_face_tags("en").empty());
    EXPECT_TRUE(cjk_face_tags("zu").empty());  // not "zh"
}

class CjkFace : public ::testing::Test {
protected:
    void SetUp() override {
        if (!std::filesystem::exists(BODY_FONT_FILE)) GTEST_SKIP() << "needs fonts-dejavu-core";
        bool cjk = false;
        for (const auto& f : default_fallback_fonts()) cjk |= f.find("CJK") != std::string::npos;
        if (!cjk) GTEST_SKIP() << "needs fonts-noto-cjk";
        auto f = FontSet::open(FontSet::every_script(BODY_FONT_FILE));
        ASSERT_TRUE(f) << f.error().message;
        fonts = f.value();
    }
    // The one glyph `c` shapes to in the current language: its font and bitmap.
    GlyphBitmap drawn(char32_t c, int* font = nullptr) {
        const std::u32string text(1, c);
        const ShapedText t = shape_text(*fonts, text, 48.0f);
        EXPECT_EQ(t.glyphs.size(), 1u);
        if (t.glyphs.empty()) return {};
        if (font) *font = t.glyphs[0].font;
        return fonts->rasterize(t.glyphs[0].font, t.glyphs[0].glyph, 48.0f);
    }
    static bool same(const GlyphBitmap& a, const GlyphBitmap& b) {
        return a.width == b.width && a.height == b.height && a.coverage == b.coverage;
    }
    std::shared_ptr<FontSet> fonts;
};

TEST_F(CjkFace, ChineseTakesTheSimplifiedFaceNotTheJapanese) {
    for (char32_t c : {U'直', U'骨'}) {
        EXPECT_TRUE(fonts->set_language("ja") || fonts->face_tag() == "JP");
        int ja_font = -1, zh_font = -1;
        const GlyphBitmap ja = drawn(c, &ja_font);
        ASSERT_GT(ja.width, 0);
        EXPECT_TRUE(fonts->set_language("zh-Hans"));
        EXPECT_EQ(fonts->face_tag(), "SC");
        const GlyphBitmap zh = drawn(c, &zh_font);
        ASSERT_GT(zh.width, 0);
        EXPECT_EQ(fonts->file(zh_font), fonts->file(ja_font));  // one collection, two faces
        EXPECT_NE(fonts->face(zh_font), fonts->face(ja_font));
        EXPECT_FALSE(same(ja, zh)) << "U+" << std::hex << static_cast<unsigned>(c) << " drawn the Japanese way";
        // Korean and Traditional Chinese take faces of their own too.
        EXPECT_TRUE(fonts->set_language("zh-Hant"));
        int tc_font = -1;
        (void)drawn(c, &tc_font);
        EXPECT_NE(fonts->face(tc_font), fonts->face(zh_font));
        EXPECT_NE(fonts->face(tc_font), fonts->face(ja_font));
    }
}

TEST_F(CjkFace, OtherLanguagesKeepTheFirstFaceAndFacesAreOpenedOnce) {
    int first = -1;
    (void)drawn(U'直', &first);
    EXPECT_EQ(fonts->face(first), 0);         // no language: the collection's first face
    EXPECT_FALSE(fonts->set_language("en"));  // same faces as none
    fonts->set_language("zh-Hans");
    int a = -1, b = -1;
    (void)drawn(U'直', &a);
    const size_t fonts_after_first = fonts->size();
    fonts->set_language("en");
    fonts->set_language("zh-CN");
    (void)drawn(U'骨', &b);
    EXPECT_EQ(a, b);  // the SC face's index stays, so atlas slots stay valid
    EXPECT_EQ(fonts->size(), fonts_after_first);
    // A Japanese kana keeps the collection (the SC face draws kana too), in the chosen face.
    const ShapedText mixed = shape_text(*fonts, U"直か", 20.0f);
    ASSERT_EQ(mixed.glyphs.size(), 2u);
    EXPECT_EQ(mixed.glyphs[0].font, a);
    EXPECT_EQ(mixed.glyphs[1].font, a);
}

}  // namespace
}  // namespace body::kiosk
