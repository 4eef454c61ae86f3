// Automatic LOD: a frame-cost model fitted from reported frames, and a tiered,
// screen-area-weighted water-filling allocation of the triangle budget.
#include "kiosk/app/lod_controller.h"

#include <algorithm>
#include <cmath>

namespace body::kiosk {

namespace {

// Spends `budget` over `items` (indices into models) in proportion to weights,
// never above `cap[i]`; returns what was left.
double water_fill(const std::vector<size_t>& items, const std::vector<double>& weight, const std::vector<double>& cap,
                  std::vector<double>& give, double budget) {
    std::vector<size_t> open = items;
    while (budget > 0.5 && !open.empty()) {
        double total = 0.0;
        for (size_t i : open) total += weight[i];
        if (total <= 0.0) break;
        std::vector<size_t> still;
        double spent = 0.0;
        bool capped = false;
        for (size_t i : open) {
            const double share = budget * weight[i] / total;
            if (give[i] + share >= cap[i]) capped = true;
        }
        for (size_t i : open) {
            const double share = budget * weight[i] / total;
            if (capped) {
                // Fill only the capped ones this round so the rest is redistributed.
                if (give[i] + share >= cap[i]) {
                    spent += cap[i] - give[i];
                    give[i] = cap[i];
                } else {
                    still.push_back(i);
                }
            } else {
                give[i] += share;
                spent += share;
            }
        }
        budget -= spent;
        if (!capped) break;
        open = std::move(still);
    }
    return std::max(budget, 0.0);
}

}  // namespace

void LodController::report_frame(double frame_ms, size_t triangles_drawn) {
    if (!(frame_ms > 0.0) || !std::isfinite(frame_ms)) return;
    const double mtri = static_cast<double>(triangles_drawn) * 1e-6;
    const double a = settings_.smoothing;
    // Two frames with different loads give slope and overhead; otherwise attribute
    // the time to triangles above the current overhead estimate.
    if (have_previous_ && triangles_drawn != previous_triangles_) {
        const double dm = mtri - static_cast<double>(previous_triangles_) * 1e-6;
        const double slope = (frame_ms - previous_ms_) / dm;
        if (slope > 0.0 && std::isfinite(slope)) {
            const double overhead = std::max(0.0, frame_ms - slope * mtri);
            ms_per_mtri_ = (1.0 - a) * ms_per_mtri_ + a * slope;
            overhead_ms_ = (1.0 - a) * overhead_ms_ + a * overhead;
        }
    } else if (mtri > 0.0) {
        const double slope = std::max(frame_ms - overhead_ms_, 0.0) / mtri;
        if (slope > 0.0) ms_per_mtri_ = (1.0 - a) * ms_per_mtri_ + a * slope;
    }
    // Never predict below what was measured: correct the overhead if the model
    // under-estimates this frame.
    const double predicted = overhead_ms_ + ms_per_mtri_ * mtri;
    if (frame_ms > predicted) overhead_ms_ += frame_ms - predicted;
    have_previous_ = true;
    previous_ms_ = frame_ms;
    previous_triangles_ = triangles_drawn;
}

size_t LodController::budget() const {
    const double ms = settings_.target_ms * settings_.headroom - overhead_ms_;
    const double triangles = ms > 0.0 ? ms / ms_per_mtri_ * 1e6 : 0.0;
    return std::max(static_cast<size_t>(triangles), settings_.min_triangles);
}

std::vector<size_t> LodController::allocate(std::span<const LodModelInput> models) const {
    const size_t n = models.size();
    std::vector<double> give(n, 0.0), cap(n, 0.0), weight(n, 0.0);
    double remaining = static_cast<double>(budget());
    std::vector<size_t> tiers[3];
    for (size_t i = 0; i < n; ++i) {
        const LodModelInput& m = models[i];
        if (!m.visible || m.full_triangles == 0) continue;
        const double base = static_cast<double>(std::min(m.base_triangles, m.full_triangles));
        if (m.manual_ratio) {
            give[i] = std::max(base, std::round(static_cast<double>(m.full_triangles) * *m.manual_ratio));
        } else {
            give[i] = base;
            cap[i] = static_cast<double>(m.full_triangles);
            const double r = std::max(m.screen_radius_px, 1.0f);
            weight[i] = r * r;
            tiers[std::clamp(m.tier, 0, 2)].push_back(i);
        }
        remaining -= give[i];
    }
    for (auto& tier : tiers) {
        if (remaining <= 0.0) break;
        remaining = water_fill(tier, weight, cap, give, remaining);
    }
    std::vector<size_t> out(n, 0);
    for (size_t i = 0; i < n; ++i) out[i] = static_cast<size_t>(std::floor(give[i] + 1e-6));
    return out;
}

float lod_step(float ratio, int direction) {
    const float steps = ratio * 10.0f;
    float next = direction > 0 ? std::floor(steps + 1e-3f) + 1.0f : std::ceil(steps - 1e-3f) - 1.0f;
    return std::clamp(next, 1.0f, 10.0f) / 10.0f;
}

}  // namespace body::kiosk
