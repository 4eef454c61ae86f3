// The kiosk mode: a scene (or one model as a scene) shown live with gestures,
// labels and automatic LOD, or driven by --replay (kiosk/app/kiosk_run.h); under
// systemd it notifies the service manager (platform/service_notify.h).
#include "kiosk/app/kiosk_run.h"
#include "kiosk/modes/modes.h"
#include "kiosk/render/program_binary.h"
#include "platform/service_notify.h"

namespace body::kiosk {

int run_kiosk_mode(platform::Surface& surface, const ViewOptions& o, const scene::Scene& scene) {
    KioskRunOptions ko;
    ko.replay = o.replay;
    ko.screenshot = o.screenshot;
    ko.frames = o.frames;
    ko.auto_lod = o.auto_lod;
    ko.verbose = o.kiosk_stats;
    ko.renderer = o.renderer;
    ko.display_width_mm = o.display_width_mm;
    ko.load.file_colours = !o.model_path.empty();
    // Later starts load the programs' binaries instead of compiling their GLSL.
    render::set_program_binary_dir(render::default_program_binary_dir());
    // Under systemd: ready after the first frame, the watchdog fed only while frames come.
    platform::ServiceNotifier notifier;
    if (notifier.active())
        ko.hooks.frame_done = [&](const FrameReport&) {
            notifier.frame_presented(surface.time());
            return true;
        };
    const int code = run_kiosk(surface, scene, ko);
    notifier.stopping();
    return code;
}

}  // namespace body::kiosk
