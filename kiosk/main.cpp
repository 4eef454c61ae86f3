// bodyview: the fullscreen GLES 3 kiosk viewer. Parses the command line once,
// opens the surface and runs the first mode of the table whose condition the
// options meet; each mode is a file in kiosk/modes/ over the one scene path.
#include <cstdio>
#include <string>
#include <vector>

#include "body/version.h"
#include "kiosk/modes/modes.h"
#include "kiosk/modes/service_config.h"
#include "platform/log.h"
#include "platform/platform.h"
#include "shared/cli_args.h"
#include "shared/error.h"

namespace {

using namespace body;
using body::kiosk::Mode;
using body::kiosk::ViewOptions;

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "bodyview %s - shows anatomy models on a touch screen (OpenGL ES 3.0)\n\n"
                 "usage: bodyview [options] [BUNDLE/]\n"
                 "       bodyview --headless --size 1280x800 --model X.bpm --style S --lod R --screenshot out.png\n"
                 "       bodyview --headless --benchmark [--model X.bpm]\n"
                 "       bodyview --author (BUNDLE/ | scene.json | MODELS...)   compose and save a scene\n\noptions:\n"
                 "  --platform P      auto|glfw|drm|headless (compiled here:",
                 BODY_VERSION_STRING);
    for (auto b : platform::compiled_backends()) std::fprintf(out, " %s", platform::backend_name(b));
    std::fprintf(out,
                 ")\n"
                 "  --headless        same as --platform headless\n"
                 "  --size WxH        window/offscreen size (headless default 1280x800)\n"
                 "  --windowed        glfw: a window instead of fullscreen\n"
                 "  --mode WxH[@Hz]   drm: display mode (default: the preferred one)\n"
                 "  --device PATH     drm: /dev/dri/cardN (default: the first that works)\n"
                 "  --rotate DEG      touch panel rotation against the display: 0|90|180|270 (default 0)\n"
                 "  --model FILE      a .bpm progressive mesh or .obj file, shown as a scene of one model\n"
                 "  --contours STACK  review a contour stack's correspondence: click a link to cut it, two\n"
                 "                    contours to join them, x excludes the selected one, s saves the\n"
                 "                    overrides into STACK's \"links\", o shows the built surface\n"
                 "  --scene FILE      a scene manifest (scene.json); BUNDLE/ means BUNDLE/scene.json\n"
                 "  --style S         smooth|wireframe|lines|hatching|hatching-2tone (overrides the scene)\n"
                 "  --lod R           level of detail, ratio of the full triangles in (0,1] (default 1)\n"
                 "  --select NAME     screenshot: select a model (transparent purple + manipulation sphere);\n"
                 "                    with --model also one of its structures' names, or all\n"
                 "  --xray            fade everything not selected\n"
                 "  --view AZ,POLAR   camera azimuth and polar angle in degrees (default 20,75)\n"
                 "  --line-width PX   silhouette width in pixels (default 2)\n"
                 "  --ssaa N          headless: render N times larger and downsample the screenshot\n"
                 "  --buffer-access A auto|in-place|staged: how GL buffers are patched (auto: staged\n"
                 "                    on NVIDIA and AMD, whose drivers draw a buffer mapped for writing\n"
                 "                    from host memory for a while; in place elsewhere)\n"
                 "  --screenshot PNG  render one frame, write it as PNG and exit\n"
                 "  --frames N        kiosk: exit after N frames\n"
                 "  --replay FILE     kiosk: play scripted touch/mouse input (kiosk/app/replay.h), then exit\n"
                 "  --no-auto-lod     kiosk: keep the manifest's LOD (the automatic LOD controller off)\n"
                 "  --soak MINUTES    kiosk loop under randomised visitors for MINUTES (headless unless\n"
                 "                    --platform says otherwise); logs RSS, frame times, GL errors, fds\n"
                 "                    and threads every minute; exit 1 when a soak goal fails (soak.h)\n"
                 "  --kiosk-stats     kiosk: print time to first frame / full detail and frame times\n"
                 "  --benchmark       time every style at LOD 100/40/10%% against a flat baseline\n"
                 "  --bench-triangles N  size of the generated benchmark model (default 1000000; the\n"
                 "                    nearest count a subdivision of the bunny or a sphere gives)\n"
                 "  --bench-frames N  at least N timed pairs per style and LOD, more up to 3 s (default 9)\n"
                 "  --bench-seconds S time per style and LOD beyond those pairs (default 3; 0: N pairs only)\n"
                 "  --bench-only cut  the cut-plane table alone (pins: the pinned-label table;\n"
                 "                    order: the draw-order table of a .bpm model)\n"
                 "  --config FILE     options from FILE (the service's /etc/bodyview/bodyview.conf;\n"
                 "                    kiosk/modes/service_config.h); the command line wins\n"
                 "  --touch-calibration \"A B C D E F\"  touch: 2x3 matrix applied to the panel's\n"
                 "                    normalised coordinates before the rotation (libinput's convention)\n"
                 "  --display-width-mm W  the screen's width in mm, when the display reports none or a\n"
                 "                    wrong one: no touch target is smaller than 9 mm on it\n"
                 "  --log-level L     error|warning|info|debug (default info; debug = --kiosk-stats)\n"
                 "  --author          the authoring window: side panel, undo/redo, Ctrl+S saves scene.json,\n"
                 "                    P previews the kiosk; keys with ? (kiosk/author/editor.h)\n"
                 "  --preview-screenshot PNG  author with --replay: the preview's last frame\n"
                 "  --help            this text\n  --version         print the version\n\n"
                 "A model that cannot be loaded is skipped with a one-line error (nothing drawn).\n"
                 "exit codes: 0 ok, 1 runtime failure, 2 bad usage or bad input\n");
}

// The modes, first match wins; each lives in kiosk/modes/<name>.cpp.
const Mode kModes[] = {
    {"author", [](const ViewOptions& o) { return o.author; }, kiosk::run_author_mode},
    {"contours", [](const ViewOptions& o) { return !o.contours_path.empty(); }, kiosk::run_contour_review_mode},
    {"benchmark", [](const ViewOptions& o) { return o.benchmark; }, kiosk::run_benchmark_mode},
    {"screenshot", [](const ViewOptions& o) { return !o.screenshot.empty() && o.replay.empty(); },
     kiosk::run_screenshot_mode},
    {"soak", [](const ViewOptions& o) { return o.soak_minutes > 0.0; }, kiosk::run_soak_mode},
    {"kiosk", [](const ViewOptions&) { return true; }, kiosk::run_kiosk_mode},
};

int run(const CliArgs& args) {
    auto options = kiosk::parse_view_options(args);
    if (!options) return kiosk::report(options.error());
    const ViewOptions& o = options.value();
    platform::set_log_level(o.log_level);
    // The scene is read before the surface opens: a bad manifest is reported as such on any machine.
    scene::Scene scene;
    if (!o.benchmark && o.contours_path.empty()) {
        auto s = kiosk::scene_to_show(o);
        if (!s) return kiosk::report(s.error());
        scene = std::move(s.value());
    }
    auto surface = platform::create_surface(o.surface);
    if (!surface) return kiosk::report(surface.error());
    for (const Mode& m : kModes)
        if (m.chosen(o)) return m.run(*surface.value(), o, scene);
    return kExitBadInput;  // unreachable: the last mode takes everything
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> argv_list(argv + 1, argv + argc);
    for (const auto& a : argv_list) {
        if (a == "--help" || a == "-h") {
            print_help(stdout);
            return kExitOk;
        }
        if (a == "--version") {
            std::printf("bodyview %s\n", BODY_VERSION_STRING);
            return kExitOk;
        }
    }
    if (argv_list.empty()) {
        print_help(stderr);
        return kExitBadInput;
    }
    auto with_config = kiosk::apply_config_file(argv_list, kiosk::view_value_options(), kiosk::view_flag_options());
    if (!with_config) return kiosk::report(with_config.error());
    auto args = CliArgs::parse(with_config.value(), kiosk::view_value_options(), kiosk::view_flag_options());
    if (!args) return kiosk::report(args.error());
    return run(args.value());
}
