// Text for every script: shaping (Arabic joining), bidi order (Hebrew, numbers
// inside right-to-left text), per-character font fallback opened lazily, CJK
// line breaks, the mirrored UI, and the rule that fits every control's text.
#include "kiosk/app/text_shaping.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "kiosk/app/text.h"
#include "kiosk/app/ui.h"
#include "shared/style.h"

namespace body::kiosk {
namespace {

bool has_fallback(const char* tag) {
    for (const auto& f : default_fallback_fonts())
        if (f.find(tag) != std::string::npos) return true;
    return false;
}

class Shaping : public ::testing::Test {
protected:
    void SetUp() override {
        if (!std::filesystem::exists(BODY_FONT_FILE)) GTEST_SKIP() << "needs fonts-dejavu-core";
        auto f = FontSet::open(FontSet::every_script(BODY_FONT_FILE));
        ASSERT_TRUE(f) << f.error().message;
        fonts = f.value();
    }
    std::vector<uint32_t> clusters(std::u32string_view text, TextDirection d = TextDirection::Auto) {
        std::vector<uint32_t> out;
        for (const ShapedGlyph& g : shape_text(*fonts, text, 20.0f, d).glyphs) out.push_back(g.cluster);
        return out;
    }
    std::shared_ptr<FontSet> fonts;
};

TEST_F(Shaping, ArabicLettersJoinIntoOtherGlyphsThanTheirIsolatedForms) {
    if (!has_fallback("Arabic")) GTEST_SKIP() << "needs fonts-noto-core";
    const std::u32string word = U"بيت";  // beh, yeh, teh: initial, medial, final forms
    const ShapedText joined = shape_text(*fonts, word, 20.0f);
    ASSERT_EQ(joined.glyphs.size(), 3u);
    EXPECT_TRUE(joined.rtl);
    EXPECT_NE(fonts->file(joined.glyphs[0].font).find("Arabic"), std::string::npos);
    int differing = 0;
    for (const ShapedGlyph& g : joined.glyphs) {
        const ShapedText alone = shape_text(*fonts, word.substr(g.cluster, 1), 20.0f);
        ASSERT_EQ(alone.glyphs.size(), 1u);
        EXPECT_NE(alone.glyphs[0].glyph, 0u);
        differing += alone.glyphs[0].glyph != g.glyph;
    }
    EXPECT_EQ(differing, 3);
    // Visual order: the first letter is drawn rightmost.
    EXPECT_EQ(joined.glyphs.back().cluster, 0u);
}

TEST_F(Shaping, HebrewIsDrawnRightToLeft) {
    EXPECT_EQ(clusters(U"שלום"), (std::vector<uint32_t>{3, 2, 1, 0}));
    EXPECT_TRUE(is_rtl_paragraph(U"שלום world"));
    EXPECT_FALSE(is_rtl_paragraph(U"world שלום"));
    EXPECT_EQ(clusters(U"abc"), (std::vector<uint32_t>{0, 1, 2}));
}

TEST_F(Shaping, NumbersKeepLeftToRightOrderInsideRightToLeftText) {
    // "page 12" in Hebrew: the number stays 1 then 2, at the left end of the line.
    EXPECT_EQ(clusters(U"עמוד 12"), (std::vector<uint32_t>{5, 6, 4, 3, 2, 1, 0}));
    // A Hebrew word and a number after it inside English (rules W7, N1, I1, L2).
    EXPECT_EQ(clusters(U"page שלום 12"), (std::vector<uint32_t>{0, 1, 2, 3, 4, 10, 11, 9, 8, 7, 6, 5}));
    // The paragraph direction decides which side each run goes.
    EXPECT_EQ(clusters(U"abc שלום"), (std::vector<uint32_t>{0, 1, 2, 3, 7, 6, 5, 4}));
    EXPECT_EQ(clusters(U"abc שלום", TextDirection::RightToLeft), (std::vector<uint32_t>{7, 6, 5, 4, 3, 0, 1, 2}));
}

TEST_F(Shaping, FallbackFontsOpenOnlyWhenAStringNeedsThem) {
    if (!has_fallback("CJK")) GTEST_SKIP() << "needs fonts-noto-cjk";
    EXPECT_EQ(fonts->loaded(), 1u);
    (void)shape_text(*fonts, U"Hippocampus Гиппокамп Ιππόκαμπος", 20.0f);
    EXPECT_EQ(fonts->loaded(), 1u);  // DejaVu draws Latin, Cyrillic, Greek
    const ShapedText cjk = shape_text(*fonts, U"海马体 かいば", 20.0f);
    EXPECT_EQ(fonts->loaded(), 2u);
    for (const ShapedGlyph& g : cjk.glyphs) {
        EXPECT_NE(g.glyph, 0u);
        EXPECT_NE(fonts->file(g.font).find("CJK"), std::string::npos);  // the space stays in the CJK run
    }
    // A character every font lacks is drawn as U+FFFD by the font that has it, not as a missing-glyph box.
    const ShapedText missing = shape_text(*fonts, U"a\U0010FFFD", 20.0f);
    ASSERT_EQ(missing.glyphs.size(), 2u);
    EXPECT_NE(missing.glyphs[1].glyph, 0u);
}

TEST(LineBreaks, CjkBreaksBetweenCharactersButNotBeforeClosingPunctuation) {
    const std::u32string t = U"海马体负责记忆。「大脑」";
    const auto a = line_break_opportunities(t);
    EXPECT_TRUE(a[1]);    // between 海 and 马
    EXPECT_FALSE(a[7]);   // not before 。
    EXPECT_TRUE(a[8]);    // before 「
    EXPECT_FALSE(a[9]);   // not after 「
    EXPECT_FALSE(a[11]);  // not before 」
    const auto latin = line_break_opportunities(U"temporal-right lobe");
    EXPECT_TRUE(latin[9]);   // after the hyphen between letters
    EXPECT_TRUE(latin[15]);  // after the space
    EXPECT_FALSE(latin[3]);  // inside a word
    EXPECT_TRUE(is_rtl_language("ar"));
    EXPECT_TRUE(is_rtl_language("he-IL"));
    EXPECT_FALSE(is_rtl_language("en"));
}

TEST(LineBreaks, ChineseWrapsWithinTheWidthWithoutLosingCharacters) {
    if (!has_fallback("CJK")) GTEST_SKIP() << "needs fonts-noto-cjk";
    auto atlas = GlyphAtlas::build(BODY_FONT_FILE, 20.0f);
    ASSERT_TRUE(atlas) << atlas.error().message;
    const std::u32string text = U"海马体位于大脑颞叶内侧，负责把短期记忆转化为长期记忆。";
    const auto lines = atlas->wrap(text, 120.0f);
    ASSERT_GT(lines.size(), 2u);
    std::u32string joined;
    for (const auto& l : lines) {
        EXPECT_LE(l.width, 120.0f);
        EXPECT_NE(l.text.front(), U'，');
        EXPECT_NE(l.text.front(), U'。');
        joined += l.text;
    }
    EXPECT_EQ(joined, text);
}

// A kiosk wraps every card it shows; each wrap measures many one-off prefixes. The
// cache must stay bounded over months of visitors, and lines drawn every frame
// must survive the turnover.
TEST(ShapedCache, StaysBoundedAndKeepsTheLinesInUse) {
    if (!std::filesystem::exists(BODY_FONT_FILE)) GTEST_SKIP() << "needs fonts-dejavu-core";
    auto atlas = GlyphAtlas::build(BODY_FONT_FILE, 20.0f);
    ASSERT_TRUE(atlas) << atlas.error().message;
    const std::u32string hot = U"Home";
    const float hot_width = atlas->measure(hot);
    size_t most = 0;
    for (int card = 0; card < 3000; ++card) {
        std::u32string text = U"Region " + std::u32string(1, static_cast<char32_t>(U'A' + card % 26)) + U" ";
        for (int w = 0; w < 12; ++w)
            text += U"word" + std::u32string(1, static_cast<char32_t>(U'a' + (card + w) % 26)) + U" ";
        text += std::u32string(1, static_cast<char32_t>(0x4E00 + card));  // every card distinct
        ASSERT_FALSE(atlas->wrap(text, 90.0f).empty());
        EXPECT_EQ(atlas->measure(hot), hot_width);  // the line in use every frame
        most = std::max(most, atlas->shaped_lines());
    }
    EXPECT_GT(most, 1000u);  // the cache is used...
    EXPECT_LE(most, 2048u);  // ...and bounded (two generations of 1024)
}

TEST(MirroredUi, RightToLeftLanguagesMirrorTheControls) {
    UiState s;
    s.width = 1280;
    s.height = 800;
    s.group_names = {"limbic", "cortex"};
    s.group_visible = {true, true};
    const auto ltr = layout_controls(s);
    s.language = "ar";
    const auto rtl = layout_controls(s);
    ASSERT_EQ(ltr.size(), rtl.size());
    for (size_t i = 0; i < ltr.size(); ++i) {
        EXPECT_FLOAT_EQ(rtl[i].rect.x, 1280.0f - ltr[i].rect.x - ltr[i].rect.w) << i;
        EXPECT_FLOAT_EQ(rtl[i].rect.y, ltr[i].rect.y);
    }
    EXPECT_LT(rtl[0].rect.x, 640.0f);  // the column is on the left
    EXPECT_EQ(rtl[0].text, "الرئيسية");
}

// Every group name the AAL bundle (scripts/build-sample.sh) can have, from its group table.
std::vector<std::string> aal_group_names() {
    std::ifstream in(BODY_SOURCE_DIR "/builder/import/aal_groups.tsv");
    std::set<std::string> names{"other"};
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        const auto tab = line.find('\t');
        if (tab == std::string::npos) continue;
        const std::string g = line.substr(tab + 1);
        if (g == "group") continue;
        const auto side = g.find("{side}");
        if (side == std::string::npos) {
            names.insert(g);
            continue;
        }
        for (const char* s : {"left", "right", ""}) {
            std::string n = g.substr(0, side) + s + g.substr(side + 6);
            while (!n.empty() && n.back() == '-') n.pop_back();
            names.insert(n);
        }
    }
    return {names.begin(), names.end()};
}

TEST(ControlText, TheRuleShrinksWrapsThenAbbreviatesKeepingTheSide) {
    if (!std::filesystem::exists(BODY_FONT_FILE)) GTEST_SKIP() << "needs fonts-dejavu-core";
    auto atlas = GlyphAtlas::build(BODY_FONT_FILE, 20.0f);
    ASSERT_TRUE(atlas) << atlas.error().message;
    const float wide = atlas->measure(U"central-left");
    const FittedText whole = fit_text(*atlas, U"central-left", wide + 1.0f, 60.0f);
    EXPECT_EQ(whole.lines.size(), 1u);
    EXPECT_FLOAT_EQ(whole.scale, 1.0f);
    const FittedText shrunk = fit_text(*atlas, U"central-left", wide * 0.9f, 20.0f);  // one line's height only
    ASSERT_EQ(shrunk.lines.size(), 1u);
    EXPECT_NEAR(shrunk.scale, 0.9f, 0.01f);
    const FittedText wrapped = fit_text(*atlas, U"central-left", wide * 0.8f, 60.0f);  // wrapping keeps it larger
    ASSERT_EQ(wrapped.lines.size(), 2u);
    EXPECT_EQ(wrapped.lines[0].text, U"central-");
    EXPECT_EQ(wrapped.lines[1].text, U"left");
    EXPECT_GT(wrapped.scale, 0.8f);
    const float narrow = atlas->measure(U"cerebel") * kMinTextScale;
    const FittedText cut = fit_text(*atlas, U"cerebellum-left", narrow, 60.0f);
    EXPECT_TRUE(cut.abbreviated);
    ASSERT_EQ(cut.lines.size(), 2u);
    EXPECT_EQ(cut.lines[0].text.back(), U'\u2026');
    EXPECT_EQ(cut.lines[1].text, U"left");
    EXPECT_LE(cut.width, narrow);
}

// Draws nothing: lays every control's text out as the overlay does and checks
// that every glyph lies inside its button, and that the words are all there
// or abbreviated by the rule (both ends kept).
TEST(ControlText, EveryControlOfTheAalLayoutFitsItsButtonInEveryLanguage) {
    if (!std::filesystem::exists(BODY_FONT_FILE)) GTEST_SKIP() << "needs fonts-dejavu-core";
    const auto groups = aal_group_names();
    ASSERT_GE(groups.size(), 15u);
    int abbreviated = 0, checked = 0;
    for (auto [w, h] : {std::pair{800, 480}, {1280, 800}, {1920, 1080}}) {
        const float ui_scale = std::max(1.0f, static_cast<float>(std::min(w, h)) / 800.0f);
        auto atlas = GlyphAtlas::build(BODY_FONT_FILE, 20.0f * ui_scale);
        ASSERT_TRUE(atlas) << atlas.error().message;
        for (const char* lang : {"en", "de", "fr", "es", "ru", "el", "ar", "he", "zh", "ja"}) {
            for (size_t count : {size_t{4}, size_t{8}, size_t{15}, groups.size()}) {
                UiState s;
                s.width = w;
                s.height = h;
                s.language = lang;
                s.has_selection = s.selection_has_group = true;
                s.style_name = style_name(Style::Hatching2Tone);  // the longest style name
                s.group_style_name = style_name(Style::Wireframe);
                s.group_names.assign(groups.begin(), groups.begin() + static_cast<std::ptrdiff_t>(count));
                s.group_visible.assign(count, true);
                for (const Control& c : layout_controls(s)) {
                    const std::u32string text = decode_utf8(c.text);
                    const FittedText f = fit_text(*atlas, text, c.rect.w - 8.0f, c.rect.h - 6.0f);
                    ++checked;
                    EXPECT_LE(f.width, c.rect.w - 8.0f + 0.01f) << lang << " " << c.text;
                    EXPECT_LE(f.height, c.rect.h - 6.0f + 0.01f) << lang << " " << c.text;
                    EXPECT_GE(f.scale, kMinTextScale - 0.01f) << lang << " " << c.text;
                    std::u32string shown;
                    for (const TextLine& l : f.lines) {
                        float advance = 0;
                        for (const GlyphQuad& q : atlas->layout(l.text, 0, 0, &advance))
                            EXPECT_LE(q.x1 * f.scale, f.width + 2.0f) << lang << " " << c.text;
                        EXPECT_NEAR(advance, l.width, 0.01f);
                        shown += (shown.empty() || shown.back() == U'-' ? U"" : U" ") + l.text;
                    }
                    if (f.abbreviated) {
                        // Only a crowded group row (buttons under 80 px) needs abbreviations.
                        EXPECT_GT(count, 8u) << w << "x" << h << " " << lang << " " << c.text;
                        EXPECT_LT(c.rect.w, 80.0f) << c.text;
                        ++abbreviated;
                        // What is shown, less the ellipses, is the text's start and then characters of it in order.
                        EXPECT_NE(shown.find(U'\u2026'), std::u32string::npos) << c.text;
                        EXPECT_EQ(shown.front(), text.front()) << c.text;
                        size_t at = 0;
                        for (char32_t ch : shown) {
                            if (ch == U'\u2026' || ch == U' ') continue;
                            at = text.find(ch, at);
                            ASSERT_NE(at, std::u32string::npos) << c.text;
                            ++at;
                        }
                    } else {
                        std::u32string squeezed = text;
                        std::erase(squeezed, U' ');
                        std::erase(shown, U' ');
                        EXPECT_EQ(shown, squeezed) << lang << " " << c.text;
                    }
                }
            }
        }
    }
    EXPECT_GT(checked, 500);
    EXPECT_GT(abbreviated, 0);  // the rule was exercised (22 groups in one row)
}

}  // namespace
}  // namespace body::kiosk
