// The kiosk's behaviour: routing input to controls and gestures, selection,
// styles, LOD, attract mode, reset, anti burn-in drift and the admin exit.
#include "kiosk/app/kiosk_app.h"

#include <algorithm>
#include <cmath>

#include "kiosk/app/access.h"

namespace body::kiosk {

namespace {

constexpr Style kStyleCycle[] = {Style::Smooth, Style::Lines, Style::Hatching, Style::Hatching2Tone, Style::Wireframe};

Style next_style(Style s) {
    for (size_t i = 0; i < std::size(kStyleCycle); ++i) {
        if (kStyleCycle[i] == s) return kStyleCycle[(i + 1) % std::size(kStyleCycle)];
    }
    return Style::Smooth;
}

std::optional<float> manual(const scene::Lod& lod) {
    return lod.automatic ? std::nullopt : std::optional<float>(lod.ratio);
}

// Distance along the ray to a sphere, or nullopt.
std::optional<float> ray_sphere(const Ray& ray, const glm::vec3& center, float radius) {
    const glm::vec3 oc = ray.origin - center;
    const float b = glm::dot(oc, ray.direction);
    const float c = glm::dot(oc, oc) - radius * radius;
    const float disc = b * b - c;
    if (disc < 0.0f) return std::nullopt;
    const float s = std::sqrt(disc);
    const float t = -b - s >= 0.0f ? -b - s : -b + s;
    if (t < 0.0f) return std::nullopt;
    return t;
}

// The world normals of the cut plane's presets: the kiosk world's axes
// (cut_plane.h) or the scene's own.
std::array<glm::vec3, 3> cut_axes(const scene::Scene& s) {
    std::array<glm::vec3, 3> axes{glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0)};
    for (size_t i = 0; i < 3; ++i)
        if (const auto& a = s.cut_plane.axes[i]) axes[i] = glm::vec3((*a)[0], (*a)[1], (*a)[2]);
    return axes;
}

}  // namespace

KioskApp::KioskApp(scene::Scene scene, std::vector<ModelInfo> models, int width, int height)
    : scene_(std::move(scene)), info_(std::move(models)) {
    info_.resize(scene_.models.size());
    models_.resize(scene_.models.size());
    groups_.resize(scene_.groups.size());
    language_ = scene_.kiosk.languages.front();
    high_contrast_ = scene_.kiosk.high_contrast;
    large_text_ = scene_.kiosk.large_text;
    offered_languages_ = offered_languages(scene_.kiosk.languages);
    LodSettings lod_settings;
    lod_settings.target_ms = scene_.kiosk.frame_ms_target;
    lod_ = LodController(lod_settings);

    // Scene bounds over the models that loaded.
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const ModelInfo& m : info_) {
        if (!m.loaded) continue;
        lo = glm::min(lo, m.center - glm::vec3(m.radius));
        hi = glm::max(hi, m.center + glm::vec3(m.radius));
    }
    const bool any = lo.x <= hi.x;
    const glm::vec3 center = any ? (lo + hi) * 0.5f : glm::vec3(0.0f);
    // The smallest sphere around `center` holding every model's sphere.
    float radius = any ? 0.0f : 1.0f;
    for (const ModelInfo& m : info_) {
        if (m.loaded) radius = std::max(radius, glm::length(m.center - center) + m.radius);
    }
    camera_.set_viewport(width, height);
    camera_.configure(scene_.camera.fov_deg, radius);
    const scene::HomeCamera& hc = scene_.camera;
    home_pose_.azimuth = glm::radians(hc.azimuth_deg);
    home_pose_.polar = glm::radians(hc.polar_deg);
    if (hc.distance > 0.0f) {
        home_pose_.target = glm::vec3(hc.target[0], hc.target[1], hc.target[2]);
        home_pose_.distance = hc.distance;
    } else {
        home_pose_.target = center;
        home_pose_.distance = camera_.fit_distance(radius);
    }
    operator_ = OperatorMode(scene_.kiosk.operator_pin);
    cut_.configure(center, radius, cut_axes(scene_));
    const auto& sn = scene_.cut_plane.slice_normal;
    cut_.set_slices(sn ? glm::vec3((*sn)[0], (*sn)[1], (*sn)[2]) : cut_axes(scene_)[0], scene_.cut_plane.slices);
    reset();
    resets_ = 0;
}

bool KioskApp::cut_applies(int model) const { return cut_.group() < 0 || group_index(model) == cut_.group(); }

void KioskApp::set_viewport(int width, int height) {
    camera_.set_viewport(width, height);
    relayout();
}

int KioskApp::group_index(int model) const {
    const std::string& g = scene_.models[static_cast<size_t>(model)].group;
    if (g.empty()) return -1;
    for (size_t i = 0; i < scene_.groups.size(); ++i) {
        if (scene_.groups[i].name == g) return static_cast<int>(i);
    }
    return -1;
}

bool KioskApp::visible(int model) const {
    if (!info_[static_cast<size_t>(model)].loaded) return false;
    if (!tour_visible_.empty()) return tour_visible_[static_cast<size_t>(model)] != 0;
    const int g = group_index(model);
    return g < 0 ? !isolated_ : groups_[static_cast<size_t>(g)].visible;
}

glm::vec3 KioskApp::model_center(int model) const {
    return info_[static_cast<size_t>(model)].center + models_[static_cast<size_t>(model)].offset;
}

glm::vec2 KioskApp::drift(double now) const {
    const double two_pi = 6.283185307179586;
    return glm::vec2(kDriftPx * std::sin(two_pi * now / 97.0), kDriftPx * std::sin(two_pi * now / 131.0));
}

bool KioskApp::lod_auto() const {
    if (selected_ >= 0) return !models_[static_cast<size_t>(selected_)].manual_lod;
    return std::all_of(models_.begin(), models_.end(), [](const ModelSettings& m) { return !m.manual_lod; });
}

void KioskApp::set_pixels_per_mm(float px_per_mm) {
    px_per_mm_ = std::max(0.0f, px_per_mm);
    relayout();
}

UiState KioskApp::ui_state() const {
    UiState s;
    s.px_per_mm = px_per_mm_;
    s.width = camera_.width();
    s.height = camera_.height();
    s.language = language_;
    s.has_selection = selected_ >= 0;
    s.selection_has_group = selected_ >= 0 && group_index(selected_) >= 0;
    s.lod_auto = lod_auto();
    s.isolated = isolated_;
    if (selected_ >= 0) {
        const Style style = models_[static_cast<size_t>(selected_)].style;
        s.style_name = style_name(style);
        const int g = group_index(selected_);
        const auto& gs = g >= 0 ? groups_[static_cast<size_t>(g)].style : std::nullopt;
        s.group_style_name = style_name(gs ? *gs : style);
    }
    for (size_t i = 0; i < groups_.size(); ++i) {
        s.group_names.push_back(scene_.groups[i].name);
        s.group_visible.push_back(groups_[i].visible);
    }
    const glm::vec2 d = drift(now_);
    s.drift_x = d.x;
    s.drift_y = d.y;
    s.high_contrast = high_contrast_;
    s.large_text = large_text_;
    s.access_buttons = scene_.kiosk.access_buttons;
    s.cut_on = cut_.on();
    s.cut_editing = cut_.editing();
    s.cut_axis = cut_axis_name(cut_.axis());
    return s;
}

void KioskApp::relayout() {
    if (operator_.active()) {
        controls_ = operator_.controls(ui_state(), operator_.diagnostics(now_, lod_auto()), language_set());
        return;
    }
    controls_ = layout_controls(ui_state());
    if (scene_.kiosk.access_buttons) add_access_controls(ui_state(), controls_);  // before the pins avoid them
    add_tree();
    add_tour_and_pin_controls();
    if (scene_.kiosk.icons) add_icons(controls_);
}

size_t KioskApp::triangles_planned() const {
    size_t total = 0;
    for (int i = 0; i < model_count(); ++i) {
        if (visible(i)) total += models_[static_cast<size_t>(i)].triangles;
    }
    return total;
}

// ---- input -------------------------------------------------------------------

void KioskApp::admin_tap(float x, float y, double now) {
    const scene::AdminGesture& a = scene_.kiosk.admin;
    const float side = a.corner_size * static_cast<float>(std::min(camera_.width(), camera_.height()));
    const bool left =
        a.corner == scene::AdminGesture::Corner::TopLeft || a.corner == scene::AdminGesture::Corner::BottomLeft;
    const bool top =
        a.corner == scene::AdminGesture::Corner::TopLeft || a.corner == scene::AdminGesture::Corner::TopRight;
    const bool in_x = left ? x < side : x >= static_cast<float>(camera_.width()) - side;
    const bool in_y = top ? y < side : y >= static_cast<float>(camera_.height()) - side;
    if (!in_x || !in_y) {
        admin_taps_.clear();
        return;
    }
    admin_taps_.push_back(now);
    std::erase_if(admin_taps_, [&](double t) { return now - t > a.seconds; });
    if (static_cast<int>(admin_taps_.size()) < a.taps) return;
    if (!operator_.enabled()) {
        exit_requested_ = true;
        return;
    }
    operator_.open();
    admin_taps_.clear();
    ui_touches_.clear();
    relayout();
}

void KioskApp::handle(const InputEvent& e) {
    now_ = std::max(now_, e.time);
    last_input_ = e.time;
    reset_done_ = false;
    visited_ = true;
    if (tour_.looping()) leave_tour();  // the attract mode's tour gives way to the visitor
    mode_ = KioskMode::Interactive;
    const bool down = e.type == InputEvent::Type::TouchDown || e.type == InputEvent::Type::MouseDown;
    const bool up = e.type == InputEvent::Type::TouchUp || e.type == InputEvent::Type::MouseUp;
    const bool is_mouse = e.type == InputEvent::Type::MouseDown || e.type == InputEvent::Type::MouseUp;
    const int touch_id = is_mouse ? -1 : e.id;
    if (down) admin_tap(e.x, e.y, e.time);
    if (tree_key(e)) return;

    // A finger that went down on a control belongs to it until it lifts.
    if (down && !(is_mouse && (e.modifiers & kModShift))) {
        if (const Control* c = hit_test(controls_, e.x, e.y)) {
            ui_touches_.push_back({touch_id, c->id});
            ui_touch_group_ = c->group;
            return;
        }
    }
    for (size_t i = 0; i < ui_touches_.size(); ++i) {
        if (ui_touches_[i].first != touch_id) continue;
        if (e.type == InputEvent::Type::TouchMove || e.type == InputEvent::Type::MouseMove) return;
        if (up) {
            const ControlId id = ui_touches_[i].second;
            ui_touches_.erase(ui_touches_.begin() + static_cast<long>(i));
            const Control* c = hit_test(controls_, e.x, e.y);
            if (c && c->id == id && c->group == ui_touch_group_) activate(*c, e.time);
            return;
        }
    }
    if (operator_.active()) return;  // modal: only its controls answer
    std::vector<Gesture> gestures;
    gestures_.feed(e, gestures);
    for (const Gesture& g : gestures) {
        tour_gesture(g);
        apply_gesture(g);
    }
    relayout();
}

void KioskApp::apply_gesture(const Gesture& g) {
    switch (g.kind) {
        case GestureKind::Begin: break;
        case GestureKind::Orbit:
            if (cut_.editing())
                cut_.drag(g.dx, g.dy, camera_);
            else
                camera_.orbit(g.dx, g.dy);
            break;
        case GestureKind::Zoom: camera_.zoom(g.factor); break;
        case GestureKind::Pan:
            if (cut_.editing())
                cut_.tilt(g.dx, g.dy, camera_);
            else
                camera_.pan(g.dx, g.dy);
            break;
        case GestureKind::Tap: {
            open_pin_ = -1;
            // Thesis B.2: Shift+left click selects what it hits; Shift+left or
            // middle click away from every object deselects; a middle click on
            // an object changes nothing. Touch taps act like left clicks.
            const int m = pick(g.x, g.y);
            if (g.button != MouseButton::Middle || m < 0) select(m);
            break;
        }
        case GestureKind::DoubleTap: {
            const int m = pick(g.x, g.y);
            if (m >= 0) focus(m, g.time);
            break;
        }
        case GestureKind::DragStart: {
            dragging_object_ = false;
            if (selected_ < 0) break;
            const float r = info_[static_cast<size_t>(selected_)].radius * kSphereFraction;
            dragging_object_ = ray_sphere(camera_.ray(g.x, g.y), model_center(selected_), r).has_value();
            break;
        }
        case GestureKind::Drag: {
            if (!dragging_object_ || selected_ < 0) break;
            const float u = 2.0f * camera_.pose().distance * std::tan(camera_.fov_y() * 0.5f) /
                            static_cast<float>(camera_.height());
            glm::vec3& offset = models_[static_cast<size_t>(selected_)].offset;
            pick_tree_stale_ = true;
            if (g.button == MouseButton::Left) {  // the X-Z plane
                offset.x += g.dx * u;
                offset.z += g.dy * u;
            } else {  // the Y-Z plane
                offset.y -= g.dy * u;
                offset.z += g.dx * u;
            }
            break;
        }
        case GestureKind::DragEnd: dragging_object_ = false; break;
    }
}

void KioskApp::activate(const Control& c, double now) {
    switch (c.id) {
        case ControlId::Home: home(now); break;
        case ControlId::Language: next_language(); break;
        case ControlId::Style:
            if (selected_ >= 0) set_model_style(selected_, next_style(models_[static_cast<size_t>(selected_)].style));
            break;
        case ControlId::GroupStyle: {
            const int g = selected_ >= 0 ? group_index(selected_) : -1;
            if (g < 0) break;
            const auto& current = groups_[static_cast<size_t>(g)].style;
            set_group_style(g, next_style(current ? *current : models_[static_cast<size_t>(selected_)].style));
            break;
        }
        case ControlId::LodDown:
        case ControlId::LodUp: {
            const int dir = c.id == ControlId::LodUp ? 1 : -1;
            for (int i = 0; i < model_count(); ++i) {
                if (selected_ >= 0 && i != selected_) continue;
                ModelSettings& m = models_[static_cast<size_t>(i)];
                const float from = m.manual_lod ? *m.manual_lod
                                   : info_[static_cast<size_t>(i)].full_triangles
                                       ? static_cast<float>(m.triangles) /
                                             static_cast<float>(info_[static_cast<size_t>(i)].full_triangles)
                                       : 1.0f;
                set_model_lod(i, lod_step(from, dir));
            }
            break;
        }
        case ControlId::LodAuto:
            for (int i = 0; i < model_count(); ++i) {
                if (selected_ < 0 || i == selected_) set_model_lod(i, std::nullopt);
            }
            break;
        case ControlId::Isolate: toggle_isolate(); break;
        case ControlId::Cut: cut_.cycle(camera_, selected_ >= 0 ? group_index(selected_) : -1); break;
        case ControlId::CutAxis: cut_.next_axis(camera_); break;
        case ControlId::GroupToggle:
            if (c.group >= 0) set_group_visible(c.group, !groups_[static_cast<size_t>(c.group)].visible);
            break;
        case ControlId::TourStart:
        case ControlId::TourPrevious:
        case ControlId::TourPause:
        case ControlId::TourNext:
        case ControlId::TourLeave:
        case ControlId::TourCaption:
        case ControlId::Countdown:
        case ControlId::Pin: activate_tour(c, now); break;
        case ControlId::OperatorKey:
        case ControlId::OperatorInfo:
        case ControlId::OperatorRestart:
        case ControlId::OperatorClose:
        case ControlId::OperatorLanguage: activate_operator(c); break;
        case ControlId::Contrast: high_contrast_ = !high_contrast_; break;
        case ControlId::LargeText: large_text_ = !large_text_; break;
        case ControlId::TreeOpen:
        case ControlId::TreeSearch:
        case ControlId::TreeBackspace:
        case ControlId::TreeUp:
        case ControlId::TreeDown:
        case ControlId::TreeLetter:
        case ControlId::TreeGroup:
        case ControlId::TreeModel: activate_tree(c); break;
    }
    relayout();
}

// ---- actions -------------------------------------------------------------------

std::optional<float> KioskApp::hit_distance(int model, const Ray& ray) const {
    return picker_ ? picker_(model, ray)
                   : ray_sphere(ray, model_center(model), info_[static_cast<size_t>(model)].radius);
}

void KioskApp::select(int model) {
    selected_ = model >= 0 && model < model_count() && visible(model) ? model : -1;
    relayout();
}

void KioskApp::focus(int model, double now) {
    if (model < 0 || model >= model_count()) return;
    camera_.focus(model_center(model), info_[static_cast<size_t>(model)].radius, now);
}

void KioskApp::set_model_style(int model, Style style) { models_[static_cast<size_t>(model)].style = style; }

void KioskApp::set_group_style(int group, Style style) {
    groups_[static_cast<size_t>(group)].style = style;
    for (int i = 0; i < model_count(); ++i) {
        if (group_index(i) == group) models_[static_cast<size_t>(i)].style = style;
    }
}

void KioskApp::set_model_lod(int model, std::optional<float> ratio) {
    if (ratio) ratio = std::clamp(*ratio, 0.0f, 1.0f);
    models_[static_cast<size_t>(model)].manual_lod = ratio;
}

void KioskApp::set_group_lod(int group, std::optional<float> ratio) {
    for (int i = 0; i < model_count(); ++i) {
        if (group_index(i) == group) set_model_lod(i, ratio);
    }
}

void KioskApp::set_group_visible(int group, bool visible_now) {
    groups_[static_cast<size_t>(group)].visible = visible_now;
    if (selected_ >= 0 && !visible(selected_)) selected_ = -1;
}

void KioskApp::toggle_isolate() {
    if (isolated_) {
        for (size_t i = 0; i < groups_.size() && i < visible_before_isolate_.size(); ++i) {
            groups_[i].visible = visible_before_isolate_[i];
        }
        isolated_ = false;
        return;
    }
    const int g = selected_ >= 0 ? group_index(selected_) : -1;
    if (g < 0) return;
    visible_before_isolate_.clear();
    for (size_t i = 0; i < groups_.size(); ++i) {
        visible_before_isolate_.push_back(groups_[i].visible);
        groups_[i].visible = static_cast<int>(i) == g;
    }
    isolated_ = true;
}

void KioskApp::next_language() {
    const auto& langs = scene_.kiosk.languages;
    auto it = std::find(langs.begin(), langs.end(), language_);
    language_ = it == langs.end() || std::next(it) == langs.end() ? langs.front() : *std::next(it);
}

void KioskApp::home(double now) { camera_.fly_to(home_pose_, now); }

void KioskApp::reset() {
    leave_tour();
    operator_.close();  // staff who walked away leave no panel open
    visited_ = false;
    open_pin_ = -1;
    camera_.set_pose(home_pose_);
    for (size_t i = 0; i < groups_.size(); ++i) {
        groups_[i].visible = scene_.groups[i].visible;
        groups_[i].style = scene_.groups[i].style;
    }
    for (int i = 0; i < model_count(); ++i) {
        const scene::Model& m = scene_.models[static_cast<size_t>(i)];
        ModelSettings& s = models_[static_cast<size_t>(i)];
        const int g = group_index(i);
        const scene::Group* group = g >= 0 ? &scene_.groups[static_cast<size_t>(g)] : nullptr;
        s.style = group && group->style ? *group->style : m.style;
        s.manual_lod = group && group->lod ? manual(*group->lod) : manual(m.lod);
        s.offset = glm::vec3(0.0f);
    }
    pick_tree_stale_ = true;
    tree_ = TreeState{};
    selected_ = -1;
    dragging_object_ = false;
    isolated_ = false;
    cut_.off();
    cut_.set_axis(CutAxis::Axial, camera_);
    language_ = scene_.kiosk.languages.front();
    high_contrast_ = scene_.kiosk.high_contrast;
    large_text_ = scene_.kiosk.large_text;
    ui_touches_.clear();
    gestures_.reset();
    ++resets_;
    relayout();
}

// ---- per frame -----------------------------------------------------------------

void KioskApp::plan_lod() {
    std::vector<LodModelInput> inputs(models_.size());
    const int selected_group = selected_ >= 0 ? group_index(selected_) : -1;
    for (int i = 0; i < model_count(); ++i) {
        const ModelInfo& info = info_[static_cast<size_t>(i)];
        LodModelInput& in = inputs[static_cast<size_t>(i)];
        in.visible = visible(i);
        in.full_triangles = info.full_triangles;
        in.base_triangles = info.base_triangles;
        in.screen_radius_px = camera_.screen_radius(model_center(i), info.radius);
        in.tier = i == selected_ ? 0 : (selected_group >= 0 && group_index(i) == selected_group ? 1 : 2);
        in.manual_ratio = models_[static_cast<size_t>(i)].manual_lod;
    }
    const std::vector<size_t> counts = lod_.allocate(inputs);
    for (size_t i = 0; i < models_.size(); ++i) {
        ModelSettings& m = models_[i];
        const size_t full = info_[i].full_triangles;
        const size_t next = counts[i];
        // Small refinements wait (no geomorph churn); coarsening is never delayed.
        const bool change = next < m.triangles || static_cast<double>(next - m.triangles) > 0.02 * full ||
                            (next == full && next != m.triangles);
        if (!change || next == m.triangles) continue;
        m.triangles = next;
    }
}

void KioskApp::update(double now) {
    const double dt = std::max(0.0, now - last_update_);
    last_update_ = now;
    now_ = std::max(now_, now);
    const double idle = now - last_input_;
    if (idle >= scene_.kiosk.idle_seconds && ui_touches_.empty() && gestures_.touches() == 0) {
        mode_ = KioskMode::Attract;
        if (idle >= scene_.kiosk.reset_seconds && !reset_done_) {
            reset();
            reset_done_ = true;
        }
        const int attract_tour = scene_.tour_index(scene_.kiosk.attract_tour);
        if (attract_tour >= 0 && !tour_.active()) start_tour(attract_tour, now, true);
        if (attract_tour < 0 && !camera_.transitioning()) {
            camera_.rotate(kAttractRadiansPerSecond * static_cast<float>(dt), 0.0f);
        }
    }
    std::vector<Gesture> gestures;
    gestures_.flush(gestures);
    for (const Gesture& g : gestures) {
        tour_gesture(g);
        apply_gesture(g);
    }
    camera_.update(now);
    update_tour(now);
    update_pins(now);
    plan_lod();
    relayout();
}

}  // namespace body::kiosk
