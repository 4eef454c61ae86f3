// The authoring window's loop (contract in author_run.h).
#include "kiosk/author/author_run.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <map>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/kiosk_run.h"
#include "kiosk/app/replay.h"
#include "kiosk/app/text.h"
#include "kiosk/author/editor.h"
#include "kiosk/author/manipulation.h"
#include "kiosk/author/model_convert.h"
#include "kiosk/author/panel_draw.h"
#include "kiosk/render/image.h"
#include "kiosk/scene/scene_models.h"

namespace body::kiosk::author {

namespace fs = std::filesystem;

namespace {

// Distinct colours for models added without one (a new scene from files).
constexpr std::array<std::array<float, 3>, 6> kPalette{{{0.85f, 0.55f, 0.45f},
                                                        {0.45f, 0.65f, 0.85f},
                                                        {0.55f, 0.80f, 0.50f},
                                                        {0.90f, 0.80f, 0.45f},
                                                        {0.70f, 0.55f, 0.85f},
                                                        {0.50f, 0.80f, 0.80f}}};

bool model_file(const std::string& p) {
    std::string ext = fs::path(p).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".bpm" || ext == ".obj" || ext == ".stl" || ext == ".ply";
}

// The manipulation sphere's rotate (Alt+drag) or scale (Alt+Shift+drag) in progress:
// the model is drawn at `current` until the release makes it one command.
struct Manipulation {
    bool scale = false;
    int model = -1;
    glm::vec2 centre{0.0f};  // the sphere's centre on screen (view pixels)
    float radius_px = 1.0f;
    glm::vec2 press{0.0f};
    glm::vec3 world_centre{0.0f};
    scene::Transform start, current;
};

// A pin being dragged to another point of its model's surface.
struct PinDrag {
    int model = -1, pin = -1;
    glm::vec2 press{0.0f};
    bool moved = false;
    std::optional<std::array<float, 3>> anchor;  // where the pointer last hit the model
};

class AuthorLoop {
public:
    AuthorLoop(platform::Surface& surface, const AuthorStart& start, const AuthorRunOptions& options)
        : surface_(surface), options_(options), editor_(Document(start.scene, start.path)) {}
    int run();

private:
    Status start();
    Status load_models();
    void rebuild_app();
    void sync();
    void feed(const InputEvent& e);
    void view_event(const InputEvent& e);
    void surface_point(int model, float x, float y);
    std::optional<std::array<float, 3>> anchor_at(int model, float x, float y);
    std::optional<glm::vec2> to_view_pixels(const glm::vec3& world) const;
    bool manipulate(const InputEvent& e);
    bool drag_pin(const InputEvent& e);
    void commit_move(int model, const glm::vec3& delta, bool snap);
    void update_pin_markers();
    bool same_models_but_one(const scene::Scene& s, size_t& index, bool& added) const;
    void serve_requests();
    void preview();
    void bind(long frame, double now);
    scene::HomeCamera camera_as_start_view() const;
    glm::mat4 placement(int i) const;
    float view_shift() const { return editor_.panel_width() * 0.5f; }

    platform::Surface& surface_;
    const AuthorRunOptions& options_;
    Editor editor_;
    render::Renderer renderer_;
    scene::Scene loaded_;  // the scene models_ was loaded from (SceneModels keeps a reference)
    std::unique_ptr<SceneModels> models_;
    std::unique_ptr<KioskApp> app_;
    PanelPainter painter_;
    long seen_revision_ = -1;
    const char* synced_how_ = nullptr;  // what the last sync did (stats), cleared when reported
    double synced_ms_ = 0.0;
    Replay replay_;
    bool replaying_ = false, quit_ = false;
    size_t next_event_ = 0;
    double now_ = 0.0;
    // The 3-D view's mouse: right drag pans, a left click without a drag selects.
    bool right_down_ = false, left_down_ = false, left_moved_ = false;
    float last_x_ = 0, last_y_ = 0, down_x_ = 0, down_y_ = 0;
    uint32_t down_modifiers_ = 0;
    std::optional<Manipulation> manip_;
    std::optional<PinDrag> pin_drag_;
};

glm::mat4 AuthorLoop::placement(int i) const {
    const scene::Transform& t = manip_ && manip_->model == i
                                    ? manip_->current
                                    : editor_.document().scene().models[static_cast<size_t>(i)].transform;
    return glm::translate(glm::mat4(1.0f), app_->model(i).offset) * to_model_matrix(t);
}

Status AuthorLoop::load_models() {
    // A new renderer drops the old models' buffers with it.
    renderer_.shutdown();
    models_.reset();
    if (auto s = renderer_.init(options_.renderer); !s) return s;
    loaded_ = editor_.document().scene();
    models_ = std::make_unique<SceneModels>(loaded_);
    if (models_->load(renderer_) == 0) std::fprintf(stderr, "bodyview: author: no model could be loaded\n");
    models_->release_detail(true);  // authoring: whole files at once, frames independent of the machine
    return ok_status();
}

// The kiosk app over the document's scene; the camera and selection carry over.
void AuthorLoop::rebuild_app() {
    const scene::Scene& s = editor_.document().scene();
    std::vector<ModelInfo> infos = models_->infos();
    for (size_t i = 0; i < infos.size(); ++i) {  // loaded at the old transform: move the bounds to the new one
        const glm::mat4 change = to_model_matrix(s.models[i].transform) * glm::inverse(models_->transform(i));
        infos[i].center = glm::vec3(change * glm::vec4(infos[i].center, 1.0f));
        infos[i].radius *= s.models[i].transform.scale / loaded_.models[i].transform.scale;
    }
    std::optional<CameraPose> pose;
    if (app_) pose = app_->camera().pose();
    app_ = std::make_unique<KioskApp>(s, infos, surface_.width(), surface_.height());
    app_->set_picker([this](int model, const Ray& ray) -> std::optional<float> {
        return models_->pick(static_cast<size_t>(model), placement(model), ray);
    });
    app_->set_many_picker([this](int model, std::span<const Ray> rays, std::span<float> nearest) {
        models_->pick_many(static_cast<size_t>(model), placement(model), rays, nearest);
    });
    if (pose) app_->camera().set_pose(*pose);
    app_->select(editor_.selection().model);
}

// Whether `s` is the loaded scene with one model added or removed at `index`.
bool AuthorLoop::same_models_but_one(const scene::Scene& s, size_t& index, bool& added) const {
    const auto& now = s.models;
    const auto& was = loaded_.models;
    if (now.size() + 1 != was.size() && now.size() != was.size() + 1) return false;
    added = now.size() > was.size();
    const auto& longer = added ? now : was;
    const auto& shorter = added ? was : now;
    index = 0;
    while (index < shorter.size() && shorter[index].path == longer[index].path) ++index;
    for (size_t i = index; i < shorter.size(); ++i)
        if (shorter[i].path != longer[i + 1].path) return false;
    return true;
}

// After an edit, undo or redo: a model added or removed is uploaded or dropped
// alone (the others stay on the GPU); other file changes reload every model;
// the rest is rebound.
void AuthorLoop::sync() {
    const Document& doc = editor_.document();
    if (doc.revision() == seen_revision_) return;
    const auto began = std::chrono::steady_clock::now();
    const bool first = seen_revision_ < 0;
    seen_revision_ = doc.revision();
    const char* how = "rebound";
    const scene::Scene& s = doc.scene();
    bool same_files = s.models.size() == loaded_.models.size();
    for (size_t i = 0; same_files && i < s.models.size(); ++i) same_files = s.models[i].path == loaded_.models[i].path;
    size_t index = 0;
    bool added = false;
    if (!same_files && models_ && same_models_but_one(s, index, added)) {
        const auto at = loaded_.models.begin() + static_cast<std::ptrdiff_t>(index);
        if (added) {
            loaded_.models.insert(at, s.models[index]);
            how = "one model uploaded";
            if (auto st = models_->insert_model(index); !st)
                std::fprintf(stderr, "bodyview: author: %s: %s\n", s.models[index].name.c_str(),
                             st.error().message.c_str());
        } else {
            loaded_.models.erase(at);
            models_->erase_model(index);
            how = "one model dropped";
        }
        same_files = true;
    }
    if (!same_files || !models_) {
        how = "every model reloaded";
        if (auto st = load_models(); !st) std::fprintf(stderr, "bodyview: author: %s\n", st.error().message.c_str());
    }
    for (size_t i = 0; i < s.models.size(); ++i) models_->set_colour(i, s.models[i].colour);
    rebuild_app();
    synced_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count();
    synced_how_ = how;
    if (options_.stats && first)
        std::fprintf(stderr, "bodyview: author: %zu models loaded in %.1f ms\n", s.models.size(), synced_ms_);
    if (first) synced_how_ = nullptr;
}

scene::HomeCamera AuthorLoop::camera_as_start_view() const {
    const CameraPose& p = app_->camera().pose();
    scene::HomeCamera c = editor_.document().scene().camera;
    c.target = {p.target.x, p.target.y, p.target.z};
    float az = std::remainder(glm::degrees(p.azimuth), 360.0f);
    c.azimuth_deg = az;
    c.polar_deg = std::clamp(glm::degrees(p.polar), 1.0f, 179.0f);
    c.distance = p.distance;
    return c;
}

// The kiosk itself on the document's scene until Esc or P (in a replay: for kPreviewSeconds).
void AuthorLoop::preview() {
    KioskRunOptions ko;
    ko.renderer = options_.renderer;
    ko.font = options_.font;
    Replay fixed;
    fixed.end_time = kPreviewSeconds;
    if (replaying_) {
        ko.replay_events = &fixed;
        ko.screenshot = options_.preview_screenshot;
    }
    bool back = false;
    ko.hooks.input = [&](const KioskApp&, double, std::vector<platform::InputEvent>& events) {
        for (auto it = events.begin(); it != events.end();) {
            const bool leave =
                it->type == InputEvent::Type::Key && it->pressed && (it->key == platform::kKeyEscape || it->key == 'P');
            back = back || leave;
            it = leave ? events.erase(it) : it + 1;
        }
    };
    ko.hooks.frame_done = [&](const FrameReport&) { return !back; };
    const int code = run_kiosk(surface_, editor_.document().scene(), ko);
    if (code != kExitOk) std::fprintf(stderr, "bodyview: author: the preview ended with exit code %d\n", code);
}

void AuthorLoop::serve_requests() {
    while (auto r = editor_.take_request()) {
        switch (*r) {
            case Request::Preview: preview(); break;
            case Request::StartView: (void)editor_.set_start_view(camera_as_start_view()); break;
            case Request::Quit: quit_ = true; break;
            case Request::AddStep: {
                std::vector<std::string> visible;  // the step shows what the view shows now
                for (int i = 0; i < app_->model_count(); ++i)
                    if (app_->visible(i))
                        visible.push_back(editor_.document().scene().models[static_cast<size_t>(i)].name);
                (void)editor_.add_step(editor_.step_request_tour(), camera_as_start_view(), visible);
                break;
            }
        }
    }
}

// A world point in the view's pixels (as events reach the view: unshifted); nullopt behind the eye.
std::optional<glm::vec2> AuthorLoop::to_view_pixels(const glm::vec3& world) const {
    const OrbitCamera& cam = app_->camera();
    const glm::vec4 clip = cam.projection() * cam.view() * glm::vec4(world, 1.0f);
    if (clip.w <= 1e-6f) return std::nullopt;
    const glm::vec2 ndc(clip.x / clip.w, clip.y / clip.w);
    return glm::vec2((ndc.x * 0.5f + 0.5f) * static_cast<float>(cam.width()),
                     (0.5f - ndc.y * 0.5f) * static_cast<float>(cam.height()));
}

// Alt+drag on the selected model's sphere rotates it, Alt+Shift+drag scales it;
// Ctrl (or snap on) snaps. True when the event was the manipulation's.
bool AuthorLoop::manipulate(const InputEvent& e) {
    using T = InputEvent::Type;
    if (e.type == T::MouseDown && e.button() == MouseButton::Left && (e.modifiers & kModAlt)) {
        const int sel = app_->selected();
        if (sel < 0) return false;
        const glm::vec3 c = app_->model_center(sel);
        const float r = app_->info(sel).radius * KioskApp::kSphereFraction;
        const auto centre = to_view_pixels(c);
        if (!centre) return false;
        const Ray ray = app_->camera().ray(e.x, e.y);
        const glm::vec3 oc = ray.origin - c;  // the press must be on the sphere
        const float b = glm::dot(oc, ray.direction), disc = b * b - (glm::dot(oc, oc) - r * r);
        if (disc < 0.0f) return false;
        Manipulation m;
        m.scale = (e.modifiers & kModShift) != 0;
        m.model = sel;
        m.centre = *centre;
        m.radius_px = std::max(app_->camera().screen_radius(c, r), 4.0f);
        m.press = glm::vec2(e.x, e.y);
        m.world_centre = c;
        m.start = m.current = editor_.document().scene().models[static_cast<size_t>(sel)].transform;
        manip_ = m;
        return true;
    }
    if (!manip_) return false;
    if (e.type != T::MouseMove && e.type != T::MouseUp) return true;
    Manipulation& m = *manip_;
    const bool snap = editor_.snap() || (e.modifiers & kModCtrl);
    const glm::vec2 at(e.x, e.y);
    if (m.scale) {
        const float from = std::max(glm::length(m.press - m.centre), 4.0f);
        m.current = scaled(m.start, glm::length(at - m.centre) / from, m.world_centre, snap);
    } else {
        const glm::vec3 a = arcball_point(m.press, m.centre, m.radius_px), b = arcball_point(at, m.centre, m.radius_px);
        const glm::mat3 view = glm::mat3(app_->camera().view());  // world -> view rotation
        const glm::mat3 turn = glm::transpose(view) * rotation_between(a, b) * view;
        m.current = rotated(m.start, turn, m.world_centre, snap);
    }
    if (e.type == T::MouseUp) {
        const Manipulation done = m;
        manip_.reset();
        if (!(done.current == done.start))
            (void)editor_.set_transform(done.model, done.current, done.scale ? "scale" : "rotate");
    }
    return true;
}

// A press on a pin's marker picks it up; the release puts it where the pointer
// last hit its model (one command); a release off the model leaves it.
bool AuthorLoop::drag_pin(const InputEvent& e) {
    using T = InputEvent::Type;
    if (e.type == T::MouseDown && e.button() == MouseButton::Left && !e.modifiers) {
        const float reach = std::max(8.0f, 6.0f * editor_.panel_width() / 400.0f);
        for (const PinMarker& p : editor_.pin_markers())
            if (std::abs(p.x - view_shift() - e.x) <= reach && std::abs(p.y - e.y) <= reach) {
                pin_drag_ = PinDrag{p.model, p.pin, glm::vec2(e.x, e.y), false, std::nullopt};
                return true;
            }
        return false;
    }
    if (!pin_drag_) return false;
    if (e.type == T::MouseMove || e.type == T::MouseUp) {
        pin_drag_->moved = pin_drag_->moved || glm::length(glm::vec2(e.x, e.y) - pin_drag_->press) >= 3.0f;
        if (auto a = anchor_at(pin_drag_->model, e.x, e.y); a && pin_drag_->moved) pin_drag_->anchor = a;
    }
    if (e.type == T::MouseUp) {
        const PinDrag d = *pin_drag_;
        pin_drag_.reset();
        if (d.anchor) (void)editor_.move_pin(d.model, d.pin, *d.anchor);
    }
    return true;
}

// The Shift+drag move as one command; snapped, the translate lands on the model's grid.
void AuthorLoop::commit_move(int sel, const glm::vec3& d, bool snap) {
    editor_.select_model(sel);
    Status st = ok_status();
    if (snap) {
        scene::Transform t = editor_.document().scene().models[static_cast<size_t>(sel)].transform;
        t.translate = snap_translate({t.translate[0] + d.x, t.translate[1] + d.y, t.translate[2] + d.z},
                                     grid_step(app_->info(sel).radius));
        st = editor_.set_transform(sel, t, "move");
    } else {
        st = editor_.move_model(sel, {d.x, d.y, d.z});
    }
    if (!st) std::fprintf(stderr, "bodyview: author: %s\n", st.error().message.c_str());
}

// The view is drawn centred right of the panel (shifted by half its width):
// events reach the camera, picking and the manipulation sphere shifted back.
void AuthorLoop::view_event(const InputEvent& event) {
    using T = InputEvent::Type;
    InputEvent e = event;
    e.x -= view_shift();
    if (manipulate(e) || drag_pin(e)) return;
    if (e.type == T::MouseDown && e.button() == MouseButton::Right) {
        right_down_ = true;
        last_x_ = e.x;
        last_y_ = e.y;
        return;
    }
    if (right_down_ && (e.type == T::MouseMove || e.type == T::MouseUp)) {
        app_->camera().pan(e.x - last_x_, e.y - last_y_);
        last_x_ = e.x;
        last_y_ = e.y;
        if (e.type == T::MouseUp) right_down_ = false;
        return;
    }
    if (e.type == T::MouseDown && e.button() == MouseButton::Left) down_modifiers_ = e.modifiers;
    if (e.type == T::MouseDown && e.button() == MouseButton::Left && !(e.modifiers & kModShift)) {
        left_down_ = true;
        left_moved_ = false;
        down_x_ = e.x;
        down_y_ = e.y;
    }
    if (e.type == T::MouseMove && left_down_ && std::hypot(e.x - down_x_, e.y - down_y_) >= 3.0f) left_moved_ = true;
    app_->handle(e);
    if (e.type == T::MouseUp && e.button() == MouseButton::Left && left_down_) {
        left_down_ = false;
        if (!left_moved_) {
            const int picked = app_->pick(e.x, e.y);
            editor_.select_model(picked);
            surface_point(picked, e.x, e.y);
        }
    }
    // The manipulation sphere's move becomes one command when the drag ends.
    const int sel = app_->selected();
    if (e.type == T::MouseUp && sel >= 0 && glm::length(app_->model(sel).offset) > 0.0f)
        commit_move(sel, app_->model(sel).offset, editor_.snap() || ((e.modifiers | down_modifiers_) & kModCtrl));
}

// The point (x, y) hits on `model`, in the model file's coordinates (a pin's anchor).
std::optional<std::array<float, 3>> AuthorLoop::anchor_at(int model, float x, float y) {
    if (model < 0) return std::nullopt;
    const Ray ray = app_->camera().ray(x, y);
    auto locks = models_->lock();
    const auto t = models_->pick(static_cast<size_t>(model), placement(model), ray);
    if (!t) return std::nullopt;
    const glm::vec3 hit = ray.origin + ray.direction * *t;
    const glm::vec3 a = glm::vec3(glm::inverse(placement(model)) * glm::vec4(hit, 1.0f));
    return std::array<float, 3>{a.x, a.y, a.z};
}

void AuthorLoop::surface_point(int model, float x, float y) {
    if (auto a = anchor_at(model, x, y)) editor_.set_surface_point(model, *a);
}

// Where the pins of the selected model are on screen (window pixels), for the panel painter and drag_pin.
void AuthorLoop::update_pin_markers() {
    std::vector<PinMarker> markers;
    const int sel = app_->selected();
    const scene::Scene& s = editor_.document().scene();
    if (sel >= 0 && sel < static_cast<int>(s.models.size())) {
        const auto& pins = s.models[static_cast<size_t>(sel)].pins;
        for (size_t k = 0; k < pins.size(); ++k) {
            std::array<float, 3> a = pins[k].anchor;
            if (pin_drag_ && pin_drag_->pin == static_cast<int>(k) && pin_drag_->anchor) a = *pin_drag_->anchor;
            const glm::vec3 w = glm::vec3(placement(sel) * glm::vec4(a[0], a[1], a[2], 1.0f));
            if (auto p = to_view_pixels(w))
                markers.push_back(PinMarker{p->x + view_shift(), p->y, sel, static_cast<int>(k)});
        }
    }
    editor_.set_pin_markers(std::move(markers));
}

void AuthorLoop::feed(const InputEvent& e) {
    if (e.type == InputEvent::Type::Quit) {
        editor_.request_quit();
        if (!editor_.quit_confirmed()) surface_.cancel_quit();
        return;
    }
    if (!editor_.handle(e)) view_event(e);
}

void AuthorLoop::bind(long frame, double now) {
    const scene::Scene& s = editor_.document().scene();
    for (int i = 0; i < app_->model_count(); ++i) {
        const ModelSettings& ms = app_->model(i);
        const ModelInfo& mi = app_->info(i);
        ModelBinding b;
        b.style = ms.style;
        b.visible = app_->visible(i);
        b.selected = i == app_->selected();
        b.transform = placement(i);
        b.lod_automatic = s.models[static_cast<size_t>(i)].lod.automatic;
        b.lod_ratio =
            mi.full_triangles ? static_cast<double>(ms.triangles) / static_cast<double>(mi.full_triangles) : 1.0;
        b.lod_ratio = std::max(b.lod_ratio, 1e-6);
        b.glide = frame > 0;
        models_->bind(static_cast<size_t>(i), b, now);
    }
}

Status AuthorLoop::start() {
    if (!options_.replay.empty()) {
        auto r = read_replay(options_.replay);
        if (!r) return r.error();
        replay_ = std::move(r).value();
        replaying_ = true;
    }
    sync();
    if (!models_) return runtime_error("author: the renderer did not start");
    const float scale = std::max(1.0f, static_cast<float>(std::min(surface_.width(), surface_.height())) / 800.0f);
    if (auto s = painter_.init(options_.font.empty() ? default_font_file() : options_.font, scale); !s) return s;
    editor_.set_viewport(surface_.width(), surface_.height(), scale);
    editor_.set_measure([this](const std::string& t) { return painter_.measure(t); });
    return ok_status();
}

int AuthorLoop::run() {
    if (auto s = start(); !s) {
        std::fprintf(stderr, "bodyview: %s\n", s.error().message.c_str());
        renderer_.shutdown();
        return s.error().exit_code;
    }
    int exit_code = kExitOk;
    int width = surface_.width(), height = surface_.height();
    for (long frame = 0;; ++frame) {
        const auto frame_began = std::chrono::steady_clock::now();
        now_ = replaying_ ? static_cast<double>(frame) / 60.0 : surface_.time();
        std::vector<InputEvent> events;
        const bool open = surface_.poll_events(events);
        if (replaying_) {
            const float sx = replay_.width > 0 ? static_cast<float>(surface_.width()) / replay_.width : 1.0f;
            const float sy = replay_.height > 0 ? static_cast<float>(surface_.height()) / replay_.height : 1.0f;
            while (next_event_ < replay_.events.size() && replay_.events[next_event_].time <= now_) {
                InputEvent e = replay_.events[next_event_++];
                e.x *= sx;
                e.y *= sy;
                events.push_back(e);
            }
        }
        if (surface_.width() != width || surface_.height() != height) {  // the window was resized
            width = surface_.width();
            height = surface_.height();
            editor_.set_viewport(width, height, std::max(1.0f, static_cast<float>(std::min(width, height)) / 800.0f));
            app_->set_viewport(width, height);
        }
        for (const InputEvent& e : events) {
            feed(e);
            sync();
            serve_requests();
            sync();
        }
        if (!open && editor_.quit_confirmed()) quit_ = true;
        if (app_->selected() != editor_.selection().model) app_->select(editor_.selection().model);
        auto locks = models_->lock();
        app_->update(now_);
        update_pin_markers();
        models_->poll_streams();
        bind(frame, now_);
        locks.clear();
        render::FrameOptions fo;
        fo.width = width;
        fo.height = height;
        fo.framebuffer = surface_.framebuffer();
        Vec3f center;
        float radius = 0;
        renderer_.scene_bounds(center, radius);
        renderer_.render(app_->camera().render_view(glm::vec2(view_shift(), 0.0f), center, radius), render::Lighting{},
                         fo);
        painter_.draw(editor_, fo.framebuffer, width, height);
        const bool last = quit_ || (replaying_ && next_event_ >= replay_.events.size() && now_ >= replay_.end_time) ||
                          (options_.frames > 0 && frame + 1 >= options_.frames);
        if (last && !options_.screenshot.empty()) {
            render::Image img;
            img.width = width;
            img.height = height;
            img.rgba = platform::read_pixels_rgba(fo.framebuffer, width, height);
            if (auto s = render::write_png(options_.screenshot, img); !s) {
                std::fprintf(stderr, "bodyview: %s\n", s.error().message.c_str());
                exit_code = kExitRuntime;
            }
        }
        if (auto s = surface_.present(); !s) {
            std::fprintf(stderr, "bodyview: %s\n", s.error().message.c_str());
            exit_code = kExitRuntime;
            break;
        }
        if (options_.stats && synced_how_) {  // this frame drew an edit
            const double ms =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame_began).count();
            std::fprintf(stderr, "bodyview: author: edit applied in %.1f ms (%s), drawn in frame %ld (%.1f ms)\n",
                         synced_ms_, synced_how_, frame, ms);
            synced_how_ = nullptr;
        }
        if (last) break;
    }
    if (replaying_ && editor_.document().dirty())
        std::fprintf(stderr, "bodyview: author: the replay ended with unsaved changes\n");
    painter_.shutdown();
    app_.reset();
    models_.reset();
    renderer_.shutdown();
    return exit_code;
}

}  // namespace

Result<AuthorStart> open_for_authoring(const std::vector<std::string>& inputs) {
    if (inputs.empty()) return input_error("--author: give BUNDLE/, scene.json or model files (.bpm, .obj)");
    AuthorStart out;
    std::vector<std::string> models;
    std::error_code ec;
    for (size_t i = 0; i < inputs.size(); ++i) {
        const std::string& in = inputs[i];
        const bool dir = fs::is_directory(in, ec) || (!in.empty() && in.back() == '/');
        const bool json = fs::path(in).extension() == ".json";
        if (i == 0 && (dir || json)) {
            out.path = dir ? (fs::path(in) / "scene.json").string() : in;
            continue;
        }
        if (!model_file(in))
            return input_error(in + ": --author takes .bpm, .obj, .stl and .ply models (bodygen lod converts others)");
        if (!fs::is_regular_file(in, ec)) return input_error(in + ": no such file");
        models.push_back(in);
    }
    if (out.path.empty()) out.path = "scene.json";
    if (fs::exists(out.path, ec)) {
        auto s = scene::read_scene(out.path);
        if (!s) return s.error();
        out.scene = std::move(s).value();
    } else {
        if (models.empty()) return input_error(out.path + ": no scene there yet: add model files to start one");
        out.scene.source = out.path;
        out.scene.base_dir = fs::path(out.path).parent_path().string();
    }
    Document names(out.scene, out.path);  // for files relative to the manifest
    for (std::string file : models) {
        if (needs_conversion(file)) {  // STL/PLY: a .bpm in the scene's models/ folder (model_convert.h)
            // bodyview opens the inputs twice (checked before the window, then for it): convert once.
            static std::map<std::string, std::string> converted;
            const std::string key = fs::absolute(file).string() + "\n" + out.path;
            auto it = converted.find(key);
            if (it == converted.end() || !fs::is_regular_file(it->second, ec)) {
                auto bpm = convert_to_bpm(file, (fs::path(out.path).parent_path() / "models").string());
                if (!bpm) return bpm.error();
                it = converted.insert_or_assign(key, bpm.value()).first;
            }
            file = it->second;
        }
        const std::string stem = fs::path(file).stem().string();
        std::string name = stem;
        for (int n = 2; out.scene.model_index(name) >= 0; ++n) name = stem + "-" + std::to_string(n);
        scene::Model m;
        m.name = name;
        m.file = names.manifest_file(file);
        m.path = fs::absolute(file).string();
        m.colour = kPalette[out.scene.models.size() % kPalette.size()];
        m.labels.push_back(scene::LabelText{out.scene.kiosk.languages.front(), name, ""});
        out.scene.models.push_back(std::move(m));
    }
    if (auto s = validate_scene(out.scene); !s) return s.error();
    return out;
}

int run_author(platform::Surface& surface, const AuthorStart& start, const AuthorRunOptions& options) {
    return AuthorLoop(surface, start, options).run();
}

}  // namespace body::kiosk::author
