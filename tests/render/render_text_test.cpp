// The kiosk's 2-D layer in every script on llvmpipe: controls, group buttons
// and a label card in Latin, Cyrillic, Greek, Arabic, Hebrew, Chinese and
// Japanese against golden/text_<script>.png (BODY_UPDATE_GOLDENS=1 rewrites
// them). Right-to-left languages draw the mirrored layout. Chinese is drawn by
// the Noto CJK collection's SC face: the Japanese face's glyphs fail its golden.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "kiosk/app/label_card.h"
#include "kiosk/app/overlay.h"
#include "kiosk/app/pin_lines.h"
#include "kiosk/render/image.h"
#include "render_fixture.h"

namespace body {
namespace {

using kiosk::Control;
using kiosk::LabelCard;
using kiosk::UiState;

struct Script {
    const char* name;
    const char* language;
    const char* title;
    const char* description;
    std::vector<std::string> groups;
};

const Script kScripts[] = {
    {"latin",
     "en",
     "Hippocampus",
     "Forms new memories and links them to emotions and senses (since 2003).",
     {"frontal-left", "temporal-right", "cerebellum-left"}},
    {"cyrillic",
     "ru",
     "Гиппокамп",
     "Формирует новые воспоминания и связывает их с эмоциями и чувствами.",
     {"лобная-левая", "височная-правая", "мозжечок"}},
    {"greek",
     "el",
     "Ιππόκαμπος",
     "Σχηματίζει νέες αναμνήσεις και τις συνδέει με τα συναισθήματα.",
     {"μετωπιαίος", "κροταφικός", "παρεγκεφαλίδα"}},
    {"arabic",
     "ar",
     "الحُصين",
     "يكوّن ذكريات جديدة ويربطها بالعواطف والحواس منذ 2003.",
     {"الفص الجبهي", "الفص الصدغي", "المخيخ"}},
    {"hebrew",
     "he",
     "היפוקמפוס",
     "יוצר זיכרונות חדשים ומקשר אותם לרגשות, שלב 12 מתוך 30.",
     {"אונה מצחית", "אונה רקתית", "המוח הקטן"}},
    {"chinese",
     "zh-Hans",
     "海马体",
     "海马体负责形成新的记忆，并把记忆与情绪和感觉联系起来。",
     {"额叶（左）", "颞叶（右）", "小脑"}},
    {"japanese",
     "ja",
     "海馬",
     "海馬は新しい記憶をつくり、感情や感覚と結びつけます。",
     {"前頭葉（左）", "側頭葉（右）", "小脳"}},
};

void PrintTo(const Script& s, std::ostream* os) { *os << s.name; }

class TextGolden : public ::testing::TestWithParam<Script> {};

TEST_P(TextGolden, MatchesGolden) {
    if (!std::filesystem::exists(BODY_FONT_FILE)) GTEST_SKIP() << "needs fonts-dejavu-core";
    const Script& sc = GetParam();
    const int w = 800, h = 500;
    test::RenderFixture f(w, h);
    if (!f.ok()) GTEST_SKIP() << f.why();
    kiosk::Overlay overlay;
    ASSERT_TRUE(overlay.init(BODY_FONT_FILE, 1.0f).ok());
    overlay.set_language(sc.language);  // Chinese in the collection's SC face, Japanese in its JP face
    UiState s;
    s.width = w;
    s.height = h;
    s.language = sc.language;
    s.has_selection = s.selection_has_group = true;
    s.style_name = "hatching";
    s.group_style_name = "lines";
    s.group_names = sc.groups;
    s.group_visible = {true, false, true};
    LabelCard card;
    card.visible = true;
    card.rect = kiosk::label_card_rect(s);
    card.title = sc.title;
    card.description = sc.description;
    const render::FrameOptions o = f.frame();
    (void)f.draw(render::View{});  // the background
    overlay.draw(kiosk::layout_controls(s), card, o.framebuffer, w, h);
    render::Image img;
    img.width = w;
    img.height = h;
    img.rgba = platform::read_pixels_rgba(o.framebuffer, w, h);
    overlay.shutdown();

    const std::string path = std::string(BODY_GOLDEN_DIR) + "/text_" + sc.name + ".png";
    if (std::getenv("BODY_UPDATE_GOLDENS")) {
        ASSERT_TRUE(render::write_png(path, img).ok());
        return;
    }
    auto golden = render::read_png(path);
    ASSERT_TRUE(golden.ok()) << golden.error().message << " (regenerate with BODY_UPDATE_GOLDENS=1)";
    // Text is thin: a strict block threshold, so that a wrong glyph, order or font shows.
    const auto d = test::compare(golden.value(), img, 16);
    if (d.bad_block_fraction > 0.001) {
        const auto actual = std::filesystem::temp_directory_path() / ("text_" + std::string(sc.name) + ".actual.png");
        (void)render::write_png(actual.string(), img);
        ADD_FAILURE() << sc.name << ": " << d.bad_block_fraction * 100 << "% blocks differ (actual: " << actual << ")";
    }
}

// A pin's leader line and dot (pin_lines.h) go through the overlay's solid
// draw: drawn from the pin to its label, alike on the first draw (atlas
// shader) and the later ones (colour-only shader), and nothing of them for a
// hidden pin.
TEST(OverlayUnder, LeaderLinesLieUnderThePinLabels) {
    if (!std::filesystem::exists(BODY_FONT_FILE)) GTEST_SKIP() << "needs fonts-dejavu-core";
    const int w = 400, h = 300;
    test::RenderFixture f(w, h);
    if (!f.ok()) GTEST_SKIP() << f.why();
    kiosk::Overlay overlay;
    ASSERT_TRUE(overlay.init(BODY_FONT_FILE, 1.0f).ok());
    kiosk::PinView pin;
    pin.shown = true;
    pin.anchor_px = {100.0f, 200.0f};
    pin.label = kiosk::Rect{200.0f, 60.0f, 120.0f, 50.0f};
    Control label;
    label.id = kiosk::ControlId::Pin;
    label.rect = *pin.label;
    label.text = "Pin";
    const render::FrameOptions o = f.frame();
    const auto frame = [&](bool shown) {
        pin.shown = shown;
        std::vector<kiosk::Vertex2d> under;
        kiosk::PinLines().append({pin}, 1.0f, under);
        EXPECT_EQ(under.empty(), !shown);
        (void)f.draw(render::View{});  // the background
        overlay.draw({label}, LabelCard{}, o.framebuffer, w, h, under);
        render::Image img;
        img.width = w;
        img.height = h;
        img.rgba = platform::read_pixels_rgba(o.framebuffer, w, h);
        return img;
    };
    const auto luma = [](const render::Image& img, int x, int y) {
        const uint8_t* p = img.at(x, y);
        return (p[0] + p[1] + p[2]) / 3;
    };
    const render::Image first = frame(true), second = frame(true), hidden = frame(false);
    const int bg = luma(hidden, 150, 150);  // on the line's way, with no line there
    for (const render::Image* img : {&first, &second}) {
        EXPECT_LT(luma(*img, 100, 200), bg - 40);  // the dark dot on the anchor
        // Half way along the line to the label's nearest corner (200, 110).
        EXPECT_LT(luma(*img, 150, 155), bg - 40);
    }
    EXPECT_EQ(luma(hidden, 100, 200), bg);
    EXPECT_EQ(test::compare(first, second).bad_block_fraction, 0.0);
    overlay.shutdown();
}

INSTANTIATE_TEST_SUITE_P(EveryScript, TextGolden, ::testing::ValuesIn(kScripts),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace body
