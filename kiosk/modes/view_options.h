#pragma once
// bodyview's command line, parsed once for every mode (kiosk/modes/): the
// surface, the renderer and what to show, with each mode's own options.
// Errors are usage errors naming the option, in the words `bodyview --help` uses.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kiosk/render/renderer.h"
#include "platform/log.h"
#include "platform/platform.h"
#include "shared/cli_args.h"
#include "shared/error.h"
#include "shared/scene/scene.h"

namespace body::kiosk {

struct ViewOptions {
    platform::SurfaceOptions surface;
    render::RendererOptions renderer;
    std::string scene_path;                           // --scene, or BUNDLE/scene.json
    std::string model_path;                           // --model
    std::string contours_path;                        // --contours: the contour review (modes/contour_review.cpp)
    std::optional<double> lod;                        // --lod: every model at this ratio
    std::optional<Style> style;                       // --style: every model in this style
    std::optional<std::string> select;                // --select
    bool xray = false;                                // --xray
    std::optional<std::pair<float, float>> view_deg;  // --view: azimuth, polar
    int ssaa = 1;
    double line_width = 2.0;
    long frames = 0;
    std::string screenshot, replay;
    bool auto_lod = true, kiosk_stats = false;
    bool benchmark = false;
    long bench_triangles = 1000000;
    long bench_frames = 9;
    double bench_seconds = 3.0;              // --bench-seconds: time spent per cell beyond the first bench_frames pairs
    std::string bench_only;                  // --bench-only: one table ("cut", "order"); empty: every table
    double soak_minutes = 0.0;               // --soak; 0: no soak
    double display_width_mm = 0.0;           // --display-width-mm; 0: as the display reports it
    bool author = false;                     // --author: the authoring window (kiosk/author/)
    std::vector<std::string> author_inputs;  // --author's BUNDLE/, scene.json and/or model files
    std::string preview_screenshot;          // --preview-screenshot: the author's preview in a replay
    platform::LogLevel log_level = platform::LogLevel::Info;
};

// Value options and flags bodyview accepts (names without "--").
const std::set<std::string>& view_value_options();
const std::set<std::string>& view_flag_options();

Result<ViewOptions> parse_view_options(const CliArgs& args);

// What to show as a scene: the manifest (--scene, BUNDLE/), or one model file
// (--model) as a scene of one model named after the file, seen from the
// default view (azimuth 20, polar 75, 35 degrees), in --style, at --lod.
Result<scene::Scene> scene_to_show(const ViewOptions& options);

}  // namespace body::kiosk
