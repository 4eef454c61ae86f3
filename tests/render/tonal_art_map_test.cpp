// The procedural tonal art map: tones ordered, nested, mip levels tone-matched.
#include "kiosk/render/tonal_art_map.h"

#include <gtest/gtest.h>

using namespace body::render;

TEST(TonalArtMap, SixTonesDarkenInOrderAndNest) {
    TonalArtMap tam = make_tonal_art_map(64, 6);
    ASSERT_EQ(tam.tones, 6);
    ASSERT_EQ(tam.levels.size(), 7u);  // 64 .. 1
    for (int t = 1; t < tam.tones; ++t) {
        EXPECT_GT(tam.darkness(t), tam.darkness(t - 1) + 0.05) << t;
        // Nesting: a darker tone only adds ink (every texel at most as light).
        const auto& a = tam.levels[0][static_cast<size_t>(t - 1)];
        const auto& b = tam.levels[0][static_cast<size_t>(t)];
        for (size_t i = 0; i < a.size(); ++i) ASSERT_LE(b[i], a[i]) << "tone " << t << " texel " << i;
    }
}

TEST(TonalArtMap, MipLevelsKeepTheTone) {
    TonalArtMap tam = make_tonal_art_map(128, 6);
    for (int t = 0; t < tam.tones; ++t) {
        for (size_t l = 1; l < tam.levels.size(); ++l) {
            const auto& px = tam.levels[l][static_cast<size_t>(t)];
            double sum = 0;
            for (uint8_t v : px) sum += 255 - v;
            double d = sum / (255.0 * static_cast<double>(px.size()));
            EXPECT_NEAR(d, tam.darkness(t), 0.08) << "tone " << t << " level " << l;
        }
    }
}

TEST(TonalArtMap, IsDeterministic) { EXPECT_EQ(make_tonal_art_map(32, 6).levels, make_tonal_art_map(32, 6).levels); }
