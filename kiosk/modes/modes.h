#pragma once
// bodyview's programs, one file each in kiosk/modes/, all over the one scene
// path (kiosk/scene/scene_models.h). main.cpp picks the first mode whose
// `chosen` accepts the options. Each returns a process exit code.
#include "kiosk/modes/view_options.h"
#include "platform/platform.h"

namespace body::kiosk {

struct Mode {
    const char* name;
    bool (*chosen)(const ViewOptions& options);
    // `scene`: what scene_to_show() gave (read before the surface opened; empty for the benchmark).
    int (*run)(platform::Surface& surface, const ViewOptions& options, const scene::Scene& scene);
};

// --benchmark: every style at LOD 100/40/10% against a flat baseline (benchmark.cpp).
int run_benchmark_mode(platform::Surface& surface, const ViewOptions& options, const scene::Scene& scene);
// --screenshot without --replay: one frame of the scene or model to a PNG (screenshot.cpp).
int run_screenshot_mode(platform::Surface& surface, const ViewOptions& options, const scene::Scene& scene);
// --soak MINUTES: the kiosk loop under randomised visitors, resources logged and judged (soak.cpp).
int run_soak_mode(platform::Surface& surface, const ViewOptions& options, const scene::Scene& scene);
// --author: the authoring window (author.cpp, kiosk/author/).
int run_author_mode(platform::Surface& surface, const ViewOptions& options, const scene::Scene& scene);
// --contours STACK: review and override the contour correspondence (contour_review.cpp).
int run_contour_review_mode(platform::Surface& surface, const ViewOptions& options, const scene::Scene& scene);
// Otherwise: the kiosk, live or driven by --replay (kiosk.cpp).
int run_kiosk_mode(platform::Surface& surface, const ViewOptions& options, const scene::Scene& scene);

// Prints "bodyview: <message>" on stderr and returns the error's exit code.
int report(const Error& error);

}  // namespace body::kiosk
