#pragma once
// Draws the kiosk's 2-D layer over the rendered scene with GLES 3.0: the
// finger-sized controls (ui.h) and the label card of the selected model, text
// from GlyphAtlas textures. Needs a current GLES 3 context; one instance per
// context. Pixels, origin top-left.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "kiosk/app/batch_2d.h"
#include "kiosk/app/label_card.h"
#include "kiosk/app/text.h"
#include "kiosk/app/ui.h"
#include "shared/error.h"

namespace body::kiosk {

class Overlay {
public:
    Overlay();
    ~Overlay();
    Overlay(const Overlay&) = delete;
    Overlay& operator=(const Overlay&) = delete;

    // Compiles the shader and opens the fonts (font_file first, then the
    // fallbacks for every script) for two atlases, titles and body text; glyphs
    // are rasterised and uploaded when a string first needs them.
    Status init(const std::string& font_file, float scale);
    void shutdown();
    // Draws controls and card into `framebuffer` (width x height). Control texts
    // follow fit_text (never cut off); right-to-left card text is right-aligned.
    // `under`: solid triangles drawn first, in the same draw as the controls'
    // boxes (the pins' leader lines, pin_lines.h).
    void draw(const std::vector<Control>& controls, const LabelCard& card, unsigned framebuffer, int width, int height,
              std::span<const Vertex2d> under = {});
    // The access modes (access.h) the next draws use: the high-contrast
    // palette, large text (atlases kLargeTextScale times larger, made when first needed).
    void set_look(bool high_contrast, bool large_text);
    // The UI language (BCP 47) the next draws shape for: it picks the CJK
    // font face (FontSet::set_language: Chinese in the SC face, not Japanese).
    void set_language(const std::string& language);
    // Lines of text shaped so far and held by the atlases (GlyphAtlas::shaped_lines):
    // text is shaped when a control or card first draws it, never ahead.
    size_t shaped_lines() const;

private:
    struct State;
    std::unique_ptr<State> s_;
};

}  // namespace body::kiosk
