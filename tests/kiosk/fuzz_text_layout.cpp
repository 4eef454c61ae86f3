// libFuzzer target for label and UI text from a bundle (any bytes as UTF-8):
// shaping, bidi, fallback, wrapping and the control-text rule never crash,
// and fit_text never returns text wider or taller than its box.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string_view>

#include "kiosk/app/text.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace body::kiosk;
    static std::unique_ptr<GlyphAtlas> atlas = [] {
        auto a = GlyphAtlas::build(BODY_FONT_FILE, 20.0f);
        if (!a) std::abort();
        return std::make_unique<GlyphAtlas>(std::move(a).value());
    }();
    if (size < 1) return 0;
    const float box_w = 8.0f + static_cast<float>(data[0]);  // 8..263 px
    const std::u32string text =
        decode_utf8(std::string_view(reinterpret_cast<const char*>(data + 1), std::min<size_t>(size - 1, 512)));
    (void)atlas->layout(text, 0.0f, 0.0f);
    for (const TextLine& l : atlas->wrap(text, box_w)) (void)atlas->layout(l.text, 0.0f, 0.0f);
    const FittedText f = fit_text(*atlas, text, box_w, 60.0f);
    if (f.width > box_w + 0.01f || f.height > 60.0f + 0.01f) std::abort();
    return 0;
}
