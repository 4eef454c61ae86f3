// The one UI word table (kiosk/app/ui_words.h): every control word in every
// language of the table, English where a column is empty, the key for an
// unknown word, and ui_text/tour_text reading the same table.
#include "kiosk/app/ui_words.h"

#include <gtest/gtest.h>

#include "kiosk/app/tour_controls.h"
#include "kiosk/app/ui.h"

namespace body::kiosk {
namespace {

TEST(UiWords, EveryControlAndCutWordIsTranslatedIntoEveryLanguage) {
    for (const char* key :
         {"home", "style", "group", "lod", "isolate", "cut", "move", "fixed", "coronal", "sagittal", "off"}) {
        ASSERT_TRUE(has_ui_word(key)) << key;
        const std::string en = ui_word(key, "en");
        EXPECT_FALSE(en.empty()) << key;
        for (std::string_view language : {"ru", "el", "ar", "he", "zh", "ja"})
            EXPECT_NE(ui_word(key, language), en) << key << " " << language;  // another script
    }
    EXPECT_EQ(ui_word("home", "ja"), "ホーム");
    EXPECT_EQ(ui_word("sagittal", "el"), "οβελιαίο");
    EXPECT_EQ(ui_word("cut", "de"), "Schnitt");
}

TEST(UiWords, AnEmptyColumnFallsBackToEnglishAndAnUnknownKeyToItself) {
    EXPECT_EQ(ui_word("leave", "de"), "Beenden");
    EXPECT_EQ(ui_word("leave", "ru"), "Leave");  // no Russian tour words yet
    EXPECT_EQ(ui_word("home", "xx"), "Home");
    EXPECT_EQ(ui_word("no such word", "de"), "no such word");
    EXPECT_FALSE(has_ui_word("no such word"));
}

TEST(UiWords, UiTextAndTourTextReadTheOneTable) {
    for (std::string_view language : kUiLanguages) {
        const std::string l(language);
        EXPECT_EQ(ui_text("isolate", l), ui_word("isolate", language));
        EXPECT_EQ(tour_text("still", l), ui_word("still", language));
        EXPECT_EQ(tour_text("axial", l), ui_text("axial", l));
    }
}

}  // namespace
}  // namespace body::kiosk
