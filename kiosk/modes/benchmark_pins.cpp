// `--benchmark`'s pinned-label table (benchmark.h, issue 27): the kiosk frame
// (the model drawn from a KioskApp's turning camera, then the overlay) with
// eight pins and their labels against the same frame without them, timed in
// alternating pairs in one run. The pins' cost is all of it: the app's per
// frame projection and layout, the occlusion queries against the frame's
// depth buffer (PinOcclusion, as the kiosk loop's: answers read a frame later
// without stalling), the leader lines and the labels' quads and text. A second
// line gives where the wall time goes, phase by phase (app update = layout and
// taking the answers; render = the frame and the pins' queries).
#include <GLES3/gl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/label_card.h"
#include "kiosk/app/overlay.h"
#include "kiosk/app/pin_lines.h"
#include "kiosk/app/pin_occlusion.h"
#include "kiosk/modes/benchmark.h"
#include "kiosk/scene/ray_hits.h"

namespace body::kiosk {

namespace {

constexpr int kPins = 8;

// The model's current level on the CPU, for picking.
struct CpuMesh {
    std::vector<Vec3f> positions;
    std::vector<uint32_t> indices;

    // Möller-Trumbore, both sides, as the kiosk's picker.
    std::optional<float> hit(const Ray& ray) const {
        float best = 1e30f;
        for (size_t i = 0; i + 2 < indices.size(); i += 3) {
            const glm::vec3 a = positions[indices[i]], b = positions[indices[i + 1]], c = positions[indices[i + 2]];
            const glm::vec3 e1 = b - a, e2 = c - a, pv = glm::cross(ray.direction, e2);
            const float det = glm::dot(e1, pv);
            if (std::abs(det) < 1e-12f) continue;
            const float inv = 1.0f / det;
            const glm::vec3 tv = ray.origin - a;
            const float u = glm::dot(tv, pv) * inv;
            if (u < 0.0f || u > 1.0f) continue;
            const glm::vec3 qv = glm::cross(tv, e1);
            const float v = glm::dot(ray.direction, qv) * inv;
            if (v < 0.0f || u + v > 1.0f) continue;
            const float t = glm::dot(e2, qv) * inv;
            if (t > 0.0f && t < best) best = t;
        }
        return best < 1e30f ? std::optional<float>(best) : std::nullopt;
    }
};

// A source whose arrays the renderer holds (a complete .bpm hands over its
// indices and vertex data at release_arrays) is read back from the renderer's
// buffers: the level that is drawn.
CpuMesh cpu_mesh(const render::Renderer& renderer, render::ModelId id, ModelSource& source) {
    CpuMesh m;
    const render::MeshData d = source.mesh();
    const size_t nv = d.vertex_count == SIZE_MAX ? d.positions.size() : d.vertex_count;
    if (d.positions.size() >= nv)
        m.positions.assign(d.positions.begin(), d.positions.begin() + static_cast<long>(nv));
    else
        (void)renderer.read_positions(id, m.positions);
    const size_t ni = d.index_count == SIZE_MAX ? d.indices.size() : d.index_count;
    if (d.indices.size() >= ni) {
        m.indices.assign(d.indices.begin(), d.indices.begin() + static_cast<long>(ni));
    } else {  // a progressive mesh handed its indices to the renderer
        renderer.read_indices(id, ni, [&](std::span<const uint32_t> ix) { m.indices.assign(ix.begin(), ix.end()); });
    }
    source.release_arrays();
    // Corners past the positions (a failed read-back) would read out of bounds.
    const auto past = [&](uint32_t v) { return v >= m.positions.size(); };
    if (std::any_of(m.indices.begin(), m.indices.end(), past)) m.indices.clear();
    return m;
}

// Where the wall time goes, summed over the timed frames: [without, with] x phase.
enum { kUpdate, kRender, kLines, kOverlay, kFinish, kPhases };
using PhaseTimes = double[2][kPhases];

void print_phases(const PhaseTimes& ms) {
    std::printf(
        "wall ms summed over the timed frames, without / with pins: app update %.1f / %.1f, render %.1f / %.1f, "
        "leader lines built %.1f / %.1f, overlay (with the lines) %.1f / %.1f, glFinish %.1f / %.1f\n",
        ms[0][kUpdate], ms[1][kUpdate], ms[0][kRender], ms[1][kRender], ms[0][kLines], ms[1][kLines], ms[0][kOverlay],
        ms[1][kOverlay], ms[0][kFinish], ms[1][kFinish]);
}

scene::Scene bench_scene(bool pins) {
    scene::Scene s;
    s.source = "benchmark";
    scene::Model m;
    m.name = "model";
    m.file = m.name;  // never read: the model is already in the renderer
    m.labels.push_back(scene::LabelText{"en", "Model", ""});
    s.models.push_back(m);
    s.kiosk.pins = pins;
    s.kiosk.idle_seconds = 86400.0f;  // no attract mode, no reset: the camera is turned by hand
    s.kiosk.reset_seconds = 86400.0f;
    return s;
}

// Pins where rays on a ring around the model's centre, seen from the start camera, hit it.
scene::Scene bench_pins_scene(const CpuMesh& mesh, const std::vector<ModelInfo>& info, Vec3f center, float radius,
                              const render::FrameOptions& frame) {
    scene::Scene with_scene = bench_scene(true);
    KioskApp probe(bench_scene(false), info, frame.width, frame.height);
    const glm::vec4 clip = probe.camera().projection() * probe.camera().view() * glm::vec4(center, 1.0f);
    const glm::vec2 px((clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(frame.width),
                       (0.5f - clip.y / clip.w * 0.5f) * static_cast<float>(frame.height));
    const float r = probe.camera().screen_radius(center, radius);
    for (int k = 0; k < 64 && static_cast<int>(with_scene.models[0].pins.size()) < kPins; ++k) {
        const float a = 0.7853982f * static_cast<float>(k % 8), d = r * (0.2f + 0.1f * static_cast<float>(k / 8));
        const Ray ray = probe.camera().ray(px.x + d * std::cos(a), px.y + d * std::sin(a));
        const auto t = mesh.hit(ray);
        if (!t) continue;
        const glm::vec3 p = ray.origin + ray.direction * *t;
        scene::Pin pin;
        pin.anchor = {p.x, p.y, p.z};
        scene::LabelText text;
        text.language = "en";
        text.title = std::to_string(with_scene.models[0].pins.size() + 1);
        text.title.insert(0, "Pin ");
        pin.labels.push_back(std::move(text));
        with_scene.models[0].pins.push_back(pin);
    }
    return with_scene;
}

}  // namespace

Status compare_pins(render::Renderer& renderer, render::ModelId id, ModelSource& source,
                    const render::FrameOptions& frame, int min_pairs, double seconds) {
    const CpuMesh mesh = cpu_mesh(renderer, id, source);
    if (mesh.indices.empty()) return runtime_error("pins table: the model's triangles could not be read for picking");
    Vec3f center;
    float radius = 0.0f;
    renderer.bounds(id, center, radius);
    const std::vector<ModelInfo> info{
        ModelInfo{true, center, radius, mesh.indices.size() / 3, mesh.indices.size() / 3}};
    KioskApp::Picker picker = [&](int, const Ray& ray) { return mesh.hit(ray); };

    const scene::Scene with_scene = bench_pins_scene(mesh, info, center, radius, frame);
    KioskApp with(with_scene, info, frame.width, frame.height),
        without(bench_scene(false), info, frame.width, frame.height);
    with.set_picker(picker);
    without.set_picker(picker);
    // As the kiosk's (SceneModels::pick_many): the pins' rays through the model in one walk.
    const KioskApp::ManyPicker many = [&](int, std::span<const Ray> rays, std::span<float> nearest) {
        nearest_hits(
            mesh.indices, [&](uint32_t v) { return mesh.positions[v]; }, rays, nearest);
    };
    with.set_many_picker(many);  // (the frames without pins cast no rays)
    PinOcclusion occlusion;      // the kiosk's occlusion path; the pickers then serve taps only
    const bool queries = occlusion.init(with);

    Overlay overlay;
    if (auto s = overlay.init(default_font_file(), 1.0f); !s) return s;
    PinLines lines;
    std::vector<Vertex2d> line_vertices;

    double now = 0.0;
    size_t shown = 0, placed = 0, frames_with = 0;
    struct Timed {
        double wall, cpu;
    };
    PhaseTimes phase_ms = {};
    bool timing = false;
    const auto time_frame = [&](KioskApp& app, bool pins) {
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpu_now_ms();
        auto mark = t0;
        const auto lap = [&](int phase) {
            const auto t = std::chrono::steady_clock::now();
            if (timing) phase_ms[pins][phase] += std::chrono::duration<double, std::milli>(t - mark).count();
            mark = t;
        };
        if (pins) occlusion.before_update(app);
        app.update(now);
        lap(kUpdate);
        const render::View view = app.camera().render_view(app.drift(now), center, radius);
        renderer.render(view, render::Lighting{}, frame);
        if (pins) occlusion.after_render(app, view, frame, false);
        lap(kRender);
        line_vertices.clear();
        if (pins) lines.append(app.pins(), 1.0f, line_vertices);
        lap(kLines);
        overlay.draw(app.controls(), label_card(app), frame.framebuffer, frame.width, frame.height, line_vertices);
        lap(kOverlay);
        glFinish();
        lap(kFinish);
        if (pins) {
            ++frames_with;
            for (const PinView& p : app.pins()) {
                shown += p.shown;
                placed += p.label.has_value();
            }
        }
        return Timed{std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(),
                     cpu_now_ms() - c0};
    };
    // Both cameras turn alike, 0.6 degrees a 60 Hz frame (4x the attract mode), so occlusion is re-tested as the kiosk
    // would.
    const auto advance = [&] {
        now += 1.0 / 60.0;
        with.camera().rotate(0.0105f, 0.0f);
        without.camera().rotate(0.0105f, 0.0f);
    };
    for (int i = 0; i < 2; ++i) {  // warm-up
        advance();
        (void)time_frame(without, false);
        (void)time_frame(with, true);
    }
    shown = placed = frames_with = 0;
    timing = true;
    advance();
    std::vector<Timed> base{time_frame(without, false)}, pinned;
    const auto start = std::chrono::steady_clock::now();
    const auto spent = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    while (pinned.size() < static_cast<size_t>(std::max(min_pairs, 1)) || (spent() < seconds && pinned.size() < 400)) {
        pinned.push_back(time_frame(with, true));
        advance();
        base.push_back(time_frame(without, false));
    }
    std::vector<double> wall, cpu, with_ms, without_ms;
    double sum_with = 0.0, sum_without = 0.0;
    for (size_t i = 0; i < pinned.size(); ++i) {
        wall.push_back(pinned[i].wall / (0.5 * (base[i].wall + base[i + 1].wall)));
        cpu.push_back(pinned[i].cpu / (0.5 * (base[i].cpu + base[i + 1].cpu)));
        with_ms.push_back(pinned[i].wall);
        without_ms.push_back(base[i].wall);
        sum_with += pinned[i].wall;
        sum_without += base[i].wall;
    }
    const double ratio = median(wall), mean_ratio = sum_with / sum_without;
    const double n = static_cast<double>(std::max<size_t>(frames_with, 1));
    std::printf(
        "\npins and labels (issue 27): the kiosk frame (model + overlay) with %zu pins vs without, camera turning;\n"
        "ratio: median of pair ratios (as above); mean_ratio: total time with / without; occlusion by %s\n",
        with_scene.models[0].pins.size(),
        queries ? "the GPU's queries each frame" : "the CPU's ray casts at most every 0.2 s (no queries)");
    std::printf("%-10s %9s %11s %6s %10s %9s %11s %11s %5s %s\n", "triangles", "median_ms", "baseline_ms", "ratio",
                "mean_ratio", "cpu_ratio", "pins_shown", "labels_laid", "pairs", "goal");
    std::printf("%-10zu %9.2f %11.2f %6.3f %10.3f %9.3f %11.1f %11.1f %5zu <= 1.1x %s\n", mesh.indices.size() / 3,
                median(with_ms), median(without_ms), ratio, mean_ratio, median(cpu), static_cast<double>(shown) / n,
                static_cast<double>(placed) / n, pinned.size(), ratio <= 1.1 && mean_ratio <= 1.1 ? "ok" : "MISSED");
    print_phases(phase_ms);
    std::fflush(stdout);
    overlay.shutdown();
    occlusion.shutdown();
    return ok_status();
}

}  // namespace body::kiosk
