// The kiosk mode: a scene (or one model as a scene) shown live with gestures,
// labels and automatic LOD, or driven by --replay (kiosk/app/kiosk_run.h).
#include "kiosk/app/kiosk_run.h"
#include "kiosk/modes/modes.h"

namespace body::kiosk {

int run_kiosk_mode(platform::Surface& surface, const ViewOptions& o, const scene::Scene& scene) {
    KioskRunOptions ko;
    ko.replay = o.replay;
    ko.screenshot = o.screenshot;
    ko.frames = o.frames;
    ko.auto_lod = o.auto_lod;
    ko.verbose = o.kiosk_stats;
    ko.renderer = o.renderer;
    ko.load.file_colours = !o.model_path.empty();
    return run_kiosk(surface, scene, ko);
}

}  // namespace body::kiosk
