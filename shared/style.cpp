// Style names (contract in style.h).
#include "shared/style.h"

namespace body {

const char* style_name(Style style) {
    switch (style) {
        case Style::Smooth: return "smooth";
        case Style::Wireframe: return "wireframe";
        case Style::Lines: return "lines";
        case Style::Hatching: return "hatching";
        case Style::Hatching2Tone: return "hatching-2tone";
        case Style::Baseline: return "baseline";
    }
    return "?";
}

std::optional<Style> parse_style(const std::string& name) {
    for (Style s : kAllStyles)
        if (name == style_name(s)) return s;
    return std::nullopt;
}

}  // namespace body
