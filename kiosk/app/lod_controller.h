#pragma once
// Automatic level of detail: keeps the frame time under a target by spending a
// triangle budget across the visible models.
//
// Each frame the caller reports the frame time it measured (or, in tests, a
// simulated one) and the triangles it drew. The controller estimates the cost per
// triangle and a fixed overhead, sets the budget so the predicted frame time is
// `headroom` x the target (never below `min_triangles`), and spends it:
//   1. every visible model gets its base mesh (the coarsest level, always drawn);
//      models with a manual LOD (per model or per group) get exactly that;
//   2. the rest goes tier by tier — the selected model, then the rest of its group,
//      then everything else — and within a tier in proportion to each model's
//      projected screen area, water-filling up to each model's full detail.
// Deterministic: the same reports give the same triangle counts.
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace body::kiosk {

struct LodModelInput {
    bool visible = true;
    size_t full_triangles = 0;  // finest level
    size_t base_triangles = 0;  // coarsest level (the base mesh)
    float screen_radius_px = 0.0f;
    int tier = 2;                       // 0 selected, 1 the selected model's group, 2 the rest
    std::optional<float> manual_ratio;  // fixed LOD in (0, 1]; nullopt = automatic
};

struct LodSettings {
    double target_ms = 16.7;
    double headroom = 0.9;              // aim at this fraction of the target
    double smoothing = 0.5;             // weight of the newest cost estimate
    double initial_ms_per_mtri = 10.0;  // prior before the first report
    // Floor of the budget: when the overhead alone exceeds the target (a slow GPU,
    // a software renderer), dropping every model to its base mesh would cost the
    // picture without buying the frame time back.
    size_t min_triangles = 50000;
};

class LodController {
public:
    explicit LodController(LodSettings settings = {}) : settings_(settings) {}

    // Reports the last frame: its time and the triangles drawn in it.
    void report_frame(double frame_ms, size_t triangles_drawn);
    // Triangle counts per model for the next frame (0 for invisible models).
    std::vector<size_t> allocate(std::span<const LodModelInput> models) const;

    size_t budget() const;  // triangles the controller will spend
    double ms_per_mtri() const { return ms_per_mtri_; }
    double overhead_ms() const { return overhead_ms_; }
    const LodSettings& settings() const { return settings_; }

private:
    LodSettings settings_;
    double ms_per_mtri_ = settings_.initial_ms_per_mtri;
    double overhead_ms_ = 0.0;
    bool have_previous_ = false;
    double previous_ms_ = 0.0;
    size_t previous_triangles_ = 0;
};

// Ten 10% steps for the manual LOD buttons: the next step up or down from `ratio`.
float lod_step(float ratio, int direction);

}  // namespace body::kiosk
