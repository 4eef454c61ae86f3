#pragma once
// Draws the editor (editor.h) over the 3-D view with GLES 3.0: the side panel's
// rows, the focused field's selection and cursor, the help overlay and the
// unsaved-changes prompt. Text comes from the kiosk's glyph atlas (app/text.h),
// whose glyphs are rasterised on first use and uploaded when it changed. Needs a current GLES 3
// context; pixels, origin top-left.
#include <memory>
#include <string>

#include "kiosk/author/editor.h"
#include "shared/error.h"

namespace body::kiosk::author {

class PanelPainter {
public:
    PanelPainter();
    ~PanelPainter();
    PanelPainter(const PanelPainter&) = delete;
    PanelPainter& operator=(const PanelPainter&) = delete;

    // `extra_text`: text whose glyphs are rasterised up front (names, labels).
    Status init(const std::string& font_file, float scale, const std::string& extra_text);
    void shutdown();
    // Width of `utf8` in pixels as drawn.
    float measure(const std::string& utf8) const;
    void draw(Editor& editor, unsigned framebuffer, int width, int height);

private:
    struct State;
    std::unique_ptr<State> s_;
};

}  // namespace body::kiosk::author
