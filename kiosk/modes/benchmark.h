#pragma once
// `bodyview --headless --benchmark`: per style and LOD, the median frame time
// and its ratio to a minimal baseline drawn in the same run (the same buffers,
// the flat-colour shader): the median, first and third quartile of the ratios
// of style frames to the baseline frames around them, in wall and CPU time and,
// where the driver offers GL_EXT_disjoint_timer_query, in GPU time; plus peak
// RSS above the empty-context baseline and above the empty scene (the renderer
// initialised and every style drawn once on one triangle before the model is
// loaded: the driver's fixed cost apart).
#include <string>
#include <vector>

#include "kiosk/render/renderer.h"
#include "kiosk/scene/model_source.h"
#include "platform/platform.h"
#include "shared/error.h"

namespace body::kiosk {

struct BenchmarkOptions {
    std::string model;                  // .bpm/.obj; empty: a generated ~1M-triangle model
    size_t target_triangles = 1000000;  // for the generated model
    int frames = 9;                 // at least this many timed style/baseline pairs per cell (after 2 warm-up pairs)
    double seconds_per_cell = 3.0;  // then more pairs until a cell (style x LOD) has taken this long ...
    size_t max_pairs = 200;         // ... or has this many
    bool cut_only = false;          // --bench-only cut: the cut-plane table alone, after the model loads
    bool pins_only = false;         // --bench-only pins: the pinned-label table alone, at full detail
    bool order_only = false;        // --bench-only order: the draw-order table alone, after the model loads
    render::RendererOptions renderer = {};  // --buffer-access
};

// Prints the table to stdout. The surface's context must be current.
Status run_benchmark(platform::Surface& surface, const BenchmarkOptions& options);

// The generated benchmark model (benchmark_model.cpp): the bunny subdivided, or
// a bumpy icosphere where the bunny is not installed, nearest `target_triangles`.
Result<ModelSource> generated_model(size_t target_triangles);
// How many 1-to-4 subdivisions take a mesh of `triangles` nearest (by ratio) to `target`.
int subdivisions_toward(size_t triangles, size_t target);

// The draw-order table (benchmark_order.cpp), run after the memory figures:
// for a .bpm, per LOD 100/40/10 %, the level drawn by the kiosk (model `id`
// of `source`) against the same triangles as a meshoptimizer-ordered static
// mesh, timed in alternating pairs in the baseline style, plus
// meshopt_analyzeVertexCache/Fetch figures of both and of the file's
// refinement order.
Status compare_with_static(render::Renderer& renderer, render::ModelId id, ModelSource& source,
                           const std::string& bpm_path, const render::View& camera, const render::FrameOptions& frame,
                           int min_pairs, double seconds);

// The pinned-label table (benchmark_pins.cpp), run last at full detail: the kiosk frame (model
// `id` of `source` drawn from a turning KioskApp camera, then the overlay)
// with eight pins and labels against the same frame without, in alternating
// pairs; median pair ratio and the ratio of the totals (goal <= 1.1x).
Status compare_pins(render::Renderer& renderer, render::ModelId id, ModelSource& source,
                    const render::FrameOptions& frame, int min_pairs, double seconds);
// The cut-plane table (benchmark_cut.cpp), run at full detail after the
// memory figures: per style and for the model selected under x-ray, the view
// with the cut plane through the model and its cap against the same view
// without it, in alternating pairs (goal <= 1.3x), and the plane without caps.
Status compare_cut_plane(render::Renderer& renderer, render::ModelId id, const render::View& camera,
                         const render::FrameOptions& frame, int min_pairs, double seconds);

// Frames of `r` until model `id` draws its level from the ordered copy the
// kiosk draws a level that stays from (kiosk/render/level_order.h), at most
// `seconds`; whether it does (false at once for a model never ordered: small,
// static). `order_ms`, when given, is raised to the largest
// FrameStats::level_order_ms of those frames.
bool settle_level(render::Renderer& r, render::ModelId id, const render::View& camera,
                  const render::FrameOptions& frame, double seconds = 30.0, double* order_ms = nullptr);
// Wall milliseconds of one frame of `r` (glFinish included): the tables' one timer.
double frame_ms(render::Renderer& r, const render::View& camera, const render::FrameOptions& frame);
// CPU milliseconds this process has used, all threads (a software rasterizer's included).
double cpu_now_ms();
// The median of `values`; 0 when empty.
double median(std::vector<double> values);

// Peak and current resident set size of this process in KiB (/proc/self/status).
long peak_rss_kib();
long current_rss_kib();

}  // namespace body::kiosk
