// The authoring mode (`bodyview --author`): a desktop window that composes,
// styles and labels an exhibit and saves its scene.json (kiosk/author/).
#include "kiosk/author/author_run.h"
#include "kiosk/modes/modes.h"

namespace body::kiosk {

int run_author_mode(platform::Surface& surface, const ViewOptions& o, const scene::Scene&) {
    // The scene was checked before the surface opened; read again with its save path.
    auto start = author::open_for_authoring(o.author_inputs);
    if (!start) return report(start.error());
    author::AuthorRunOptions ao;
    ao.replay = o.replay;
    ao.screenshot = o.screenshot;
    ao.preview_screenshot = o.preview_screenshot;
    ao.frames = o.frames;
    ao.renderer = o.renderer;
    ao.stats = o.kiosk_stats;
    return author::run_author(surface, start.value(), ao);
}

}  // namespace body::kiosk
