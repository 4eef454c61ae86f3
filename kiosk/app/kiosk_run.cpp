// The kiosk loop over the scene's models and the renderer (contract in kiosk_run.h).
#include "kiosk/app/kiosk_run.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "kiosk/app/idle_memory.h"
#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/overlay.h"
#include "kiosk/app/pin_lines.h"
#include "kiosk/app/pin_occlusion.h"
#include "kiosk/app/replay.h"
#include "kiosk/render/image.h"
#include "kiosk/scene/scene_models.h"
#include "shared/pm/large_array.h"

namespace body::kiosk {
namespace {

using Clock = std::chrono::steady_clock;
// Per frame, the time given to uploading models that arrived after the first (at least one each frame).
constexpr auto kUploadSlice = std::chrono::milliseconds(4);

// The display's density: from --display-width-mm when given, else as the surface reports it.
float display_pixels_per_mm(const platform::Surface& surface, double display_width_mm) {
    return display_width_mm > 0.0 ? static_cast<float>(surface.width() / display_width_mm) : surface.pixels_per_mm();
}

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

void log_error(const Error& e) { std::fprintf(stderr, "bodyview: %s\n", e.message.c_str()); }

// One run of the kiosk: what the frames share.
class KioskLoop {
public:
    KioskLoop(platform::Surface& surface, const scene::Scene& scene, const KioskRunOptions& options)
        : surface_(surface), scene_(scene), options_(options), models_(scene) {}

    int run();

private:
    int start();
    void start_app();
    bool feed_input(double now);
    bool bind_models(long frame, double now, size_t& triangles);
    render::View camera_view(double now) const;
    void draw_overlay(const render::FrameOptions& frame);
    bool write_screenshot(const render::FrameOptions& frame);
    void after_first_frame();
    // A model's world placement: its manifest transform, moved by the visitor.
    glm::mat4 placement(int model) const {
        return glm::translate(glm::mat4(1.0f), app_->model(model).offset) *
               models_.transform(static_cast<size_t>(model));
    }
    void yield_to_loaders(double frame_ms);
    bool check_gl(FrameReport& report);

    platform::Surface& surface_;
    const scene::Scene& scene_;
    const KioskRunOptions& options_;
    Replay replay_;
    bool replaying_ = false;
    size_t next_event_ = 0;
    double init_ms_ = 0.0, load_ms_ = 0.0, ui_ms_ = 0.0;
    size_t ok_models_ = 0;
    // Start-up is timed from before the .bpm loaders start (SceneModels starts
    // them at once: base meshes decode while the renderer compiles its shaders).
    Clock::time_point load_start_ = Clock::now();
    render::Renderer renderer_;
    SceneModels models_;
    std::unique_ptr<KioskApp> app_;
    Overlay overlay_;
    PinLines pin_lines_;          // leader lines under the overlay's pin labels
    PinOcclusion pin_occlusion_;  // the pins' occlusion queries
    std::vector<Vertex2d> pin_vertices_;
    float ui_scale_ = 1.0f;
    std::vector<platform::InputEvent> events_;
    double detail_cap_ = 1.0;  // lowered by GL_OUT_OF_MEMORY
    IdleMemory idle_memory_;   // free heap pages back to the system after each reset
};

// Reads the context's health into `report`; false when the context is lost.
bool KioskLoop::check_gl(FrameReport& report) {
    const platform::GlHealth h = options_.hooks.gl_health ? options_.hooks.gl_health() : platform::read_gl_health();
    report.gl_errors = h.errors;
    report.out_of_memory = h.out_of_memory;
    if (h.context_lost()) {
        std::fprintf(stderr, "bodyview: GPU context lost (reset status 0x%04x): exiting for a fresh start\n",
                     h.reset_status);
        return false;
    }
    if (h.out_of_memory && detail_cap_ > 1.0 / 16.0) {
        detail_cap_ *= 0.5;
        std::fprintf(stderr, "bodyview: GPU out of memory: every model now drawn at %.1f %% of its planned detail\n",
                     100.0 * detail_cap_);
    }
    return true;
}

// Replay, renderer, models, app and overlay. Returns an exit code, or -1 to go on.
int KioskLoop::start() {
    if (!options_.replay.empty()) {
        auto r = read_replay(options_.replay);
        if (!r) {
            log_error(r.error());
            return r.error().exit_code;
        }
        replay_ = std::move(r).value();
        replaying_ = true;
    } else if (options_.replay_events) {
        replay_ = *options_.replay_events;
        replaying_ = true;
    }
    if (auto s = renderer_.init(options_.renderer); !s) {
        log_error(s.error());
        return kExitRuntime;
    }
    init_ms_ = ms_since(load_start_);
    // Live, the first frame draws the models whose bases are in and the rest
    // arrive over the next frames; a replay or a screenshot waits for all of
    // them, so that its pictures do not depend on the machine's speed.
    const bool all_first = replaying_ || !options_.screenshot.empty() || options_.load_all_first;
    ok_models_ = all_first ? models_.load(renderer_, options_.load) : models_.load_ready(renderer_, options_.load);
    load_ms_ = ms_since(load_start_);
    if (ok_models_ == 0) {
        std::fprintf(stderr, "bodyview: %s: no model could be loaded\n", scene_.source.c_str());
        return kExitBadInput;
    }
    start_app();
    return -1;
}

void KioskLoop::start_app() {
    app_ = std::make_unique<KioskApp>(scene_, models_.infos(), surface_.width(), surface_.height());
    app_->set_pixels_per_mm(display_pixels_per_mm(surface_, options_.display_width_mm));
    app_->set_picker([this](int model, const Ray& ray) -> std::optional<float> {
        return models_.pick(static_cast<size_t>(model), placement(model), ray);
    });
    app_->set_many_picker([this](int model, std::span<const Ray> rays, std::span<float> nearest) {
        models_.pick_many(static_cast<size_t>(model), placement(model), rays, nearest);
    });
    (void)pin_occlusion_.init(*app_);  // else the app's own ray test
    const auto ui_start = Clock::now();
    const float ui_scale = std::max(1.0f, static_cast<float>(std::min(surface_.width(), surface_.height())) / 800.0f);
    if (auto s = overlay_.init(options_.font.empty() ? default_font_file() : options_.font, ui_scale); !s)
        std::fprintf(stderr, "bodyview: labels disabled: %s\n", s.error().message.c_str());
    ui_scale_ = ui_scale;
    ui_ms_ = ms_since(ui_start);
}

// Hands this frame's input to the app; false once the platform asked to quit.
bool KioskLoop::feed_input(double now) {
    events_.clear();
    bool keep = surface_.poll_events(events_);
    // The display may change size while running (DRM: another monitor plugged in).
    if (surface_.width() != app_->camera().width() || surface_.height() != app_->camera().height()) {
        app_->set_viewport(surface_.width(), surface_.height());
        app_->set_pixels_per_mm(display_pixels_per_mm(surface_, options_.display_width_mm));
    }
    if (options_.hooks.input) options_.hooks.input(*app_, now, events_);
    if (replaying_) {
        // Replay coordinates refer to replay.width x height; scaled to the surface.
        const float sx = static_cast<float>(surface_.width()) /
                         static_cast<float>(replay_.width > 0 ? replay_.width : surface_.width());
        const float sy = static_cast<float>(surface_.height()) /
                         static_cast<float>(replay_.height > 0 ? replay_.height : surface_.height());
        while (next_event_ < replay_.events.size() && replay_.events[next_event_].time <= now) {
            InputEvent e = replay_.events[next_event_++];
            e.x *= sx;
            e.y *= sy;
            app_->handle(e);
        }
        return keep;
    }
    for (const auto& e : events_) {
        // Quit is the loop's business; the rest, modifiers included (Shift+click
        // selects, thesis B.2), goes to the app as a replay's events do.
        if (e.type == InputEvent::Type::Quit)
            keep = false;
        else
            app_->handle(e);
    }
    return keep;
}

// Binds the app's state to the models; true when every model is at the detail planned for it.
bool KioskLoop::bind_models(long frame, double now, size_t& triangles) {
    bool at_planned_detail = true;
    triangles = 0;
    for (int i = 0; i < app_->model_count(); ++i) {
        const auto m = static_cast<size_t>(i);
        const ModelSettings& ms = app_->model(i);
        const ModelInfo& mi = app_->info(i);
        ModelBinding b;
        b.style = ms.style;
        b.visible = app_->visible(i);
        b.selected = i == app_->selected();
        b.cut = app_->cut_applies(i);
        b.transform = placement(i);
        b.lod_automatic = options_.auto_lod;
        b.lod_ratio = !options_.auto_lod  ? (ms.manual_lod ? *ms.manual_lod : 1.0)
                      : mi.full_triangles ? static_cast<double>(ms.triangles) / static_cast<double>(mi.full_triangles)
                                          : 1.0;
        b.lod_ratio = std::max(b.lod_ratio * detail_cap_, 1e-6);
        b.hold_level = frame == 0;  // the first frame shows the base meshes: on screen as soon as possible
        at_planned_detail = models_.bind(m, b, now) && at_planned_detail;
        if (b.visible) triangles += models_.triangles(m);
    }
    return at_planned_detail;
}

// The app's orbit camera as the renderer's view, with the anti burn-in drift as a pan of a few pixels.
render::View KioskLoop::camera_view(double now) const {
    Vec3f center;
    float radius = 0.0f;
    if (models_.pending() > 0)  // the bounds the whole scene will have (models still arriving)
        models_.scene_bounds([this](size_t i) { return app_->visible(static_cast<int>(i)); },
                             [this](size_t i) { return placement(static_cast<int>(i)); }, center, radius);
    else
        renderer_.scene_bounds(center, radius);
    return app_->camera().render_view(app_->drift(now), center, radius);
}

// The controls and the selected model's label card.
void KioskLoop::draw_overlay(const render::FrameOptions& frame) {
    pin_lines_.set_high_contrast(app_->high_contrast());
    overlay_.set_look(app_->high_contrast(), app_->large_text());
    overlay_.set_language(app_->language());
    pin_vertices_.clear();
    pin_lines_.append(app_->pins(), ui_scale_, pin_vertices_);
    overlay_.draw(app_->controls(), label_card(*app_), frame.framebuffer, frame.width, frame.height, pin_vertices_);
}

bool KioskLoop::write_screenshot(const render::FrameOptions& frame) {
    render::Image img;
    img.width = frame.width;
    img.height = frame.height;
    img.rgba = platform::read_pixels_rgba(frame.framebuffer, frame.width, frame.height);
    if (auto s = render::write_png(options_.screenshot, img); !s) {
        log_error(s.error());
        return false;
    }
    return true;
}

// The first picture is up: detail may decode now (and its memory be prefaulted
// beside it). A replay waits for all of it so that its frames do not depend on
// the machine's speed.
void KioskLoop::after_first_frame() {
    pm::start_background_prefault();
    models_.release_detail(replaying_);
}

// While detail streams in, the loader threads get the CPU for five times as
// long as the frame took (at most 500 ms, or until they are done): a renderer
// that runs on the CPU would otherwise starve them, and a GPU frame of ~16 ms
// still leaves ~12 frames a second during the load.
void KioskLoop::yield_to_loaders(double frame_ms) {
    const auto until =
        Clock::now() + std::chrono::microseconds(static_cast<long>(std::min(5.0 * frame_ms, 500.0) * 1e3));
    models_.wait_until(until);
}

int KioskLoop::run() {
    if (int code = start(); code >= 0) {
        renderer_.shutdown();
        return code;
    }
    const double step = 1.0 / 60.0;
    double frame_ms_sum = 0.0, first_frame_ms = -1.0, full_detail_ms = -1.0;
    long frames_counted = 0;
    int exit_code = kExitOk;
    for (long frame = 0;; ++frame) {
        const auto frame_start = Clock::now();
        const double now = replaying_ ? static_cast<double>(frame) * step : surface_.time();
        // The streamed structures are shared with their loaders: picking (in the
        // event handlers) and level changes read and write them.
        if (models_.pending() > 0 && frame > 0) models_.upload_arrived(frame_start + kUploadSlice);
        const size_t pending_drawn = models_.pending();
        auto stream_locks = models_.lock();
        const bool keep = feed_input(now);
        pin_occlusion_.before_update(*app_);
        app_->update(now);
        const bool streaming = models_.poll_streams() || models_.pending() > 0;
        size_t triangles = 0;
        const bool at_planned_detail = bind_models(frame, now, triangles);
        render::FrameOptions fo;
        fo.width = surface_.width();
        fo.height = surface_.height();
        fo.framebuffer = surface_.framebuffer();
        fo.cut = app_->cut().plane();
        fo.cut.volume_around = app_->scene().cut_plane.volume_around;
        const render::View view = camera_view(now);
        stream_locks.clear();  // drawing needs only the GL buffers
        renderer_.render(view, render::Lighting{}, fo);
        if (options_.verbose && renderer_.last_frame_stats().programs_linked > 0)
            std::fprintf(stderr, "bodyview: frame %ld linked %zu program(s)\n", frame,
                         renderer_.last_frame_stats().programs_linked);
        pin_occlusion_.after_render(*app_, view, fo, replaying_ || !options_.screenshot.empty());
        draw_overlay(fo);

        bool last = app_->exit_requested() || !keep ||
                    (replaying_ && next_event_ >= replay_.events.size() && now >= replay_.end_time) ||
                    (options_.frames > 0 && frame + 1 >= options_.frames);
        if (last && !options_.screenshot.empty() && !write_screenshot(fo)) exit_code = kExitRuntime;
        if (auto s = surface_.present(); !s) {
            log_error(s.error());
            exit_code = kExitRuntime;
            break;
        }
        const double frame_ms = ms_since(frame_start), since_start = ms_since(load_start_);
        if (first_frame_ms < 0.0) {
            first_frame_ms = since_start;
            after_first_frame();
            renderer_.warm_up_cut(render::Lighting{},
                                  fo);  // the cut plane's shaders compiled now, not at a visitor's tap
            if (options_.verbose)
                std::fprintf(
                    stderr,
                    "bodyview: first frame %.1f ms after start (renderer init %.1f ms with the loaders "
                    "starting, %zu/%zu models, %zu of them still arriving, base meshes in %.1f ms, label atlases %.1f "
                    "ms)\n",
                    first_frame_ms, init_ms_, ok_models_, scene_.models.size(), models_.pending(), load_ms_ - init_ms_,
                    ui_ms_);
        }
        if (full_detail_ms < 0.0 && !streaming && at_planned_detail) {
            full_detail_ms = since_start;
            if (options_.verbose)
                std::fprintf(stderr, "bodyview: full detail %.1f ms after start (%zu triangles drawn)\n",
                             full_detail_ms, triangles);
        }
        if (!replaying_ || options_.measure_frames_in_replay) app_->report_frame(frame_ms, triangles);
        FrameReport report{frame, now, frame_ms, triangles, app_.get()};
        report.shaped_lines = overlay_.shaped_lines();
        report.models_pending = pending_drawn;
        if (!check_gl(report)) {
            exit_code = kExitRuntime;
            last = true;
        }
        idle_memory_.frame(app_->resets(), now);
        report.heap_given_back = idle_memory_.given_back();
        if (options_.hooks.frame_done && !options_.hooks.frame_done(report)) last = true;
        frame_ms_sum += frame_ms;
        ++frames_counted;
        if (options_.verbose && frames_counted % 60 == 0)
            std::fprintf(stderr, "bodyview: %.2f ms/frame, %zu triangles, budget %zu, %zu draw calls\n",
                         frame_ms_sum / static_cast<double>(frames_counted), triangles, app_->lod_controller().budget(),
                         renderer_.last_frame_stats().draw_calls);
        if (last) break;
        if (streaming && frame > 0 && !replaying_) yield_to_loaders(frame_ms);
    }
    if (app_->exit_requested()) std::fprintf(stderr, "bodyview: admin exit\n");
    if (options_.verbose && frames_counted > 0)
        std::fprintf(stderr,
                     "bodyview: %ld frames, %.2f ms/frame mean, LOD controller %s, budget %zu triangles, "
                     "GL buffers %.1f MiB\n",
                     frames_counted, frame_ms_sum / static_cast<double>(frames_counted),
                     options_.auto_lod ? "on" : "off", app_->lod_controller().budget(),
                     static_cast<double>(renderer_.gpu_bytes()) / 1048576.0);
    overlay_.shutdown();
    pin_occlusion_.shutdown();
    renderer_.shutdown();
    return exit_code;
}

}  // namespace

int run_kiosk(platform::Surface& surface, const scene::Scene& scene, const KioskRunOptions& options) {
    return KioskLoop(surface, scene, options).run();
}

}  // namespace body::kiosk
