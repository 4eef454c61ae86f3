// Procedural tonal art map. References: Praun et al. 2001 "Real-time hatching"
// (SIGGRAPH), tone matching per mip level and stroke nesting; Webb et al. 2002
// "Fine tone control in hardware hatching" (the tone targets used here).
//
// Phases: a shared stroke sequence (deterministic LCG) in unit-square
// coordinates; per level, strokes are drawn (toroidally, so the tile repeats)
// until the tone's target darkness is reached, tones drawn on top of each
// other; levels smaller than 8 texels are box-filtered from the level above.
#include "kiosk/render/tonal_art_map.h"

#include <algorithm>
#include <cmath>

namespace body::render {
namespace {

struct Stroke {
    float x, y;     // start, unit square
    float length;   // unit square
    float slope;    // small deviation from the axis
    bool vertical;  // cross-hatching stroke
    float ink;      // 0..1 opacity
};

class Lcg {
public:
    explicit Lcg(uint32_t seed) : s_(seed) {}
    float next() {
        s_ = s_ * 1664525u + 1013904223u;
        return static_cast<float>(s_ >> 8) / 16777216.0f;
    }

private:
    uint32_t s_;
};

// Target mean darkness of tone k (k = 0 lightest).
double target_darkness(int tone, int tones) { return 0.07 + 0.63 * tone / std::max(1, tones - 1); }

Stroke make_stroke(Lcg& rng, bool vertical) {
    Stroke s;
    s.x = rng.next();
    s.y = rng.next();
    s.length = 0.10f + 0.12f * rng.next();
    s.slope = (rng.next() - 0.5f) * 0.16f;
    s.vertical = vertical;
    s.ink = 0.55f + 0.35f * rng.next();
    return s;
}

// Draws a one-texel-wide antialiased stroke into `d` (darkness, size x size),
// wrapping; returns the darkness it added (sum over the texels it touched).
double draw_stroke(std::vector<float>& d, int size, const Stroke& s) {
    double added = 0;
    const float n = static_cast<float>(size);
    const int steps = std::max(2, static_cast<int>(s.length * n));
    for (int i = 0; i < steps; ++i) {
        float t = static_cast<float>(i) / n;
        // Taper the ends like a pen stroke.
        float u = static_cast<float>(i) / static_cast<float>(steps - 1);
        float a = s.ink * std::min(1.0f, std::min(u, 1.0f - u) * 8.0f + 0.25f);
        float along = s.x * n + t * n;
        float across = s.y * n + s.slope * t * n;
        int ia = static_cast<int>(std::floor(along));
        int ic = static_cast<int>(std::floor(across));
        float frac = across - static_cast<float>(ic);
        for (int k = 0; k < 2; ++k) {
            float w = k == 0 ? 1.0f - frac : frac;
            int col = ((ia % size) + size) % size;
            int row = (((ic + k) % size) + size) % size;
            int x = s.vertical ? row : col;
            int y = s.vertical ? col : row;
            float& px = d[static_cast<size_t>(y) * static_cast<size_t>(size) + static_cast<size_t>(x)];
            const float before = px;
            px = px + a * w * (1.0f - px);
            added += static_cast<double>(px - before);
        }
    }
    return added;
}

double mean(const std::vector<float>& d) {
    double sum = 0;
    for (float v : d) sum += v;
    return d.empty() ? 0.0 : sum / static_cast<double>(d.size());
}

std::vector<uint8_t> to_bytes(const std::vector<float>& d) {
    std::vector<uint8_t> out(d.size());
    for (size_t i = 0; i < d.size(); ++i)
        out[i] = static_cast<uint8_t>(std::lround(255.0f * (1.0f - std::clamp(d[i], 0.0f, 1.0f))));
    return out;
}

// One level: all tones, drawn with the shared stroke sequence until each target.
// The mean darkness is tracked incrementally (a full pass over the level per
// stroke made the 256-texel map cost most of the kiosk's start-up); the exact
// mean is taken only near the target, so the strokes drawn are the same.
std::vector<std::vector<uint8_t>> draw_level(int size, int tones) {
    std::vector<std::vector<uint8_t>> out;
    std::vector<float> d(static_cast<size_t>(size) * static_cast<size_t>(size), 0.0f);
    const double texels = static_cast<double>(d.size());
    double running = 0;  // sum of d, up to rounding
    Lcg horizontal(12345u), vertical(67890u);
    for (int tone = 0; tone < tones; ++tone) {
        const double target = target_darkness(tone, tones);
        const bool cross = tone >= tones / 2;
        int guard = 0;
        auto below_target = [&] {
            if (running / texels < target - 1e-4) return true;
            running = mean(d) * texels;  // resynchronise near the target
            return running / texels < target;
        };
        while (below_target() && guard++ < 100000) {
            // Past the middle, alternate cross strokes with more parallel ones.
            bool v = cross && (guard % 2 == 0);
            running += draw_stroke(d, size, make_stroke(v ? vertical : horizontal, v));
        }
        out.push_back(to_bytes(d));
    }
    return out;
}

std::vector<uint8_t> downsample(const std::vector<uint8_t>& src, int size) {
    int half = size / 2;
    std::vector<uint8_t> out(static_cast<size_t>(half) * static_cast<size_t>(half));
    for (int y = 0; y < half; ++y)
        for (int x = 0; x < half; ++x) {
            auto at = [&](int xx, int yy) {
                return static_cast<int>(
                    src[static_cast<size_t>(yy) * static_cast<size_t>(size) + static_cast<size_t>(xx)]);
            };
            int sum = at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1);
            out[static_cast<size_t>(y) * static_cast<size_t>(half) + static_cast<size_t>(x)] =
                static_cast<uint8_t>((sum + 2) / 4);
        }
    return out;
}

}  // namespace

double TonalArtMap::darkness(int tone) const {
    if (levels.empty() || tone < 0 || tone >= tones) return 0.0;
    const auto& t = levels[0][static_cast<size_t>(tone)];
    double sum = 0;
    for (uint8_t v : t) sum += 255 - v;
    return t.empty() ? 0.0 : sum / (255.0 * static_cast<double>(t.size()));
}

TonalArtMap make_tonal_art_map(int size, int tones) {
    TonalArtMap tam;
    tam.size = size;
    tam.tones = tones;
    for (int s = size; s >= 1; s /= 2) {
        if (s >= 8) {
            tam.levels.push_back(draw_level(s, tones));
        } else {
            std::vector<std::vector<uint8_t>> level;
            for (int t = 0; t < tones; ++t)
                level.push_back(downsample(tam.levels.back()[static_cast<size_t>(t)], s * 2));
            tam.levels.push_back(std::move(level));
        }
    }
    return tam;
}

}  // namespace body::render
