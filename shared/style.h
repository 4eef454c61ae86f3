#pragma once
// The drawing styles (thesis section 3.4): one vocabulary for the scene
// manifest, the kiosk's controls and the renderer.
#include <cstdint>
#include <optional>
#include <string>

namespace body {

enum class Style : uint8_t {
    Smooth,         // per-pixel Blinn-Phong, key/fill/rim
    Wireframe,      // barycentric edges in the fragment shader, constant pixel width
    Lines,          // paper-white fill + silhouette/boundary/crease edges (thesis "hand-drawn 1")
    Hatching,       // 6-tone tonal art map (thesis "hand-drawn 2", Praun/Webb)
    Hatching2Tone,  // the thesis' two-texture threshold variant (Lake et al.)
    Baseline,       // one flat colour: the benchmark's minimal baseline, not offered to visitors
};
// The styles a manifest, a visitor or --style can choose.
inline constexpr Style kAllStyles[] = {Style::Smooth, Style::Wireframe, Style::Lines, Style::Hatching,
                                       Style::Hatching2Tone};
inline constexpr int kStyleCount = 5;

// "smooth", "wireframe", "lines", "hatching", "hatching-2tone", "baseline".
const char* style_name(Style style);
// One of kAllStyles by its name; nullopt for any other name ("baseline" included).
std::optional<Style> parse_style(const std::string& name);

}  // namespace body
