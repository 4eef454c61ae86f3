// KioskApp's tours, idle countdown and their controls (behaviour in
// kiosk_app.h; the player and interpolation in tour.h, the layout in
// tour_controls.h).
#include <algorithm>
#include <cmath>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/label_card.h"
#include "kiosk/app/tour_controls.h"

namespace body::kiosk {

void KioskApp::start_tour(int tour, double now, bool loop) {
    if (tour < 0 || tour >= static_cast<int>(scene_.tours.size())) return;
    tour_.start(tour, static_cast<int>(scene_.tours[static_cast<size_t>(tour)].steps.size()), loop, now);
    update_tour(now);
    relayout();
}

void KioskApp::pause_tour(double now) {
    tour_.pause(now);
    relayout();
}

// Goes on from where the camera is now: the step's move starts again from there.
void KioskApp::resume_tour(double now) {
    if (!tour_.active()) return;
    const bool again = tour_.finished();
    tour_.resume(now);
    if (!again) {
        tour_from_ = camera_.pose();
        tour_moving_ = true;
    }
    update_tour(now);
    relayout();
}

void KioskApp::next_tour_step(double now) {
    tour_.next(now);
    update_tour(now);
    relayout();
}

void KioskApp::previous_tour_step(double now) {
    tour_.previous(now);
    update_tour(now);
    relayout();
}

void KioskApp::leave_tour() {
    if (!tour_.active()) return;
    tour_.leave();
    tour_visible_.clear();
    tour_moving_ = tour_cut_moving_ = false;
    if (tour_cut_) cut_.off();
    tour_cut_ = false;
    if (selected_ >= 0 && !visible(selected_)) selected_ = -1;
    relayout();
}

std::string KioskApp::tour_caption() const {
    if (!tour_.active()) return {};
    const scene::TourStep& s = scene_.tours[static_cast<size_t>(tour_.tour())].steps[static_cast<size_t>(tour_.step())];
    const scene::LabelText* t = scene_.text(s.caption, language_);
    return t ? t->title : std::string();
}

// A step's cut plane (SCENE.md steps[].cut): where it moves to, or off for
// the one an earlier step set; a tour that never sets one leaves the
// visitor's alone. The move itself follows the camera's (update_tour).
void KioskApp::apply_tour_cut(const scene::TourStep& s) {
    tour_cut_from_ = TourCutPose{cut_.on(), cut_.normal(), cut_.offset(), cut_.axis()};
    tour_cut_moving_ = false;
    if (s.cut) {
        const scene::TourCut& c = *s.cut;
        const bool preset = c.axis >= 0 && c.axis < 3;
        const glm::vec3 n =
            preset ? cut_.axis_normal(static_cast<CutAxis>(c.axis)) : glm::vec3(c.normal[0], c.normal[1], c.normal[2]);
        const float r = cut_.radius();
        tour_cut_to_ = TourCutPose{true, glm::normalize(n), std::clamp(c.offset, -r, r),
                                   preset ? std::optional<CutAxis>(static_cast<CutAxis>(c.axis)) : std::nullopt};
        tour_cut_moving_ = tour_cut_ = true;
    } else if (tour_cut_) {
        tour_cut_to_ = TourCutPose{};
        tour_cut_to_.axis = cut_.axis();
        tour_cut_moving_ = true;
    }
    if (tour_cut_moving_ && !tour_cut_from_.on) tour_cut_from_.axis = tour_cut_to_.axis;
}

// The plane `p` (eased) of the way through the step's move.
void KioskApp::move_tour_cut(float p) {
    if (!tour_cut_moving_) return;
    const TourCutPose c = interpolate_cut(tour_cut_from_, tour_cut_to_, p, cut_.radius());
    if (c.on) {
        cut_.set_fixed(c.normal, c.offset, c.axis);
    } else {
        cut_.off();
        tour_cut_ = false;
    }
    if (p >= 1.0f) tour_cut_moving_ = false;
}

// A step's scene state: visibility (names of models or groups), styles, selection.
void KioskApp::enter_tour_step(double now) {
    const scene::TourStep& s = scene_.tours[static_cast<size_t>(tour_.tour())].steps[static_cast<size_t>(tour_.step())];
    const auto named = [&](int model, const std::string& name) {
        return scene_.models[static_cast<size_t>(model)].name == name ||
               scene_.models[static_cast<size_t>(model)].group == name;
    };
    tour_visible_.clear();
    if (s.visible) {
        tour_visible_.assign(models_.size(), 0);
        for (int i = 0; i < model_count(); ++i) {
            for (const std::string& n : *s.visible) tour_visible_[static_cast<size_t>(i)] |= named(i, n) ? 1 : 0;
        }
    }
    for (const auto& [name, style] : s.styles) {
        for (size_t g = 0; g < scene_.groups.size(); ++g) {
            if (scene_.groups[g].name == name) set_group_style(static_cast<int>(g), style);
        }
        const int m = scene_.model_index(name);
        if (m >= 0) set_model_style(m, style);
    }
    apply_tour_cut(s);
    selected_ = s.select.empty() ? -1 : scene_.model_index(s.select);
    if (selected_ >= 0 && !visible(selected_)) selected_ = -1;
    open_pin_ = -1;
    tour_from_ = camera_.pose();
    tour_to_ = step_pose(s.camera, tour_from_, home_pose_);
    tour_moving_ = true;
    (void)now;
}

void KioskApp::update_tour(double now) {
    if (!tour_.active()) return;
    const scene::Tour& t = scene_.tours[static_cast<size_t>(tour_.tour())];
    if (tour_.update(now, t)) enter_tour_step(now);
    // A visitor watching a playing tour is not idle.
    if (!tour_.looping() && !tour_.paused() && !tour_.finished()) last_input_ = std::max(last_input_, now);
    if (tour_.paused()) return;
    const float p = tour_.progress(t);
    move_tour_cut(p);
    if (!tour_moving_) return;
    camera_.set_pose(interpolate_pose(tour_from_, tour_to_, p));
    if (p >= 1.0f) tour_moving_ = false;
}

// A visitor moving the camera takes it over: their tour pauses.
void KioskApp::tour_gesture(const Gesture& g) {
    const bool moves = g.kind == GestureKind::Orbit || g.kind == GestureKind::Zoom || g.kind == GestureKind::Pan;
    if (moves && tour_.active() && !tour_.looping()) tour_.pause(now_);
}

// `c` lives in controls_, which every action below lays out anew: read it first.
bool KioskApp::activate_tour(const Control& c, double now) {
    const int group = c.group;
    switch (c.id) {
        case ControlId::TourStart: start_tour(group, now); return true;
        case ControlId::TourPrevious: previous_tour_step(now); return true;
        case ControlId::TourPause:
            if (tour_.paused() || tour_.finished()) {
                resume_tour(now);
            } else {
                pause_tour(now);
            }
            return true;
        case ControlId::TourNext: next_tour_step(now); return true;
        case ControlId::TourLeave: leave_tour(); return true;
        case ControlId::Pin:
            if (group >= 0 && group < static_cast<int>(pins_.size())) {
                select(pins_[static_cast<size_t>(group)].model);
                open_pin_ = selected_ >= 0 ? group : -1;
            }
            return true;
        default: return false;  // the caption and the countdown do nothing (the touch itself cancels the countdown)
    }
}

std::optional<int> KioskApp::countdown() const {
    const scene::KioskSettings& k = scene_.kiosk;
    if (k.countdown_seconds <= 0.0f || !visited_ || reset_done_) return std::nullopt;
    const double idle = now_ - last_input_;
    const double from = std::max<double>(k.idle_seconds, k.reset_seconds - k.countdown_seconds);
    if (idle < from || idle >= k.reset_seconds || !ui_touches_.empty() || gestures_.touches() > 0) return std::nullopt;
    return static_cast<int>(std::ceil(static_cast<double>(k.reset_seconds) - idle));
}

void KioskApp::add_tour_and_pin_controls() {
    const UiState ui = ui_state();
    TourUiState st;
    for (const scene::Tour& t : scene_.tours) {
        const scene::LabelText* title = scene_.text(t.title, language_);
        st.tour_titles.push_back(title ? title->title : t.name);
    }
    st.playing = tour_.active();
    st.paused = tour_.paused() || tour_.finished();
    st.attract = tour_.looping();
    st.caption = tour_caption();
    st.countdown = countdown();
    add_tour_controls(ui, st, controls_);
    if (pins_.empty()) return;
    // Pins avoid every control and the open label card.
    std::vector<Rect> obstacles;
    for (const Control& c : controls_) obstacles.push_back(c.rect);
    if (selected_ >= 0) obstacles.push_back(label_card_rect(ui));
    const float b = button_size(ui);
    const float h = std::max(min_target_px(ui), std::floor(0.75f * b));
    std::vector<PinRequest> requests;
    std::vector<size_t> index;
    for (size_t i = 0; i < pins_.size(); ++i) {
        pins_[i].label.reset();
        if (!pins_[i].shown) continue;
        // Width from the text's length (the overlay shrinks text that does not fit).
        const float chars = static_cast<float>(pins_[i].title.size());
        const float w = std::clamp(std::floor(chars * 0.16f * b + 0.4f * b), b, 4.0f * b);
        requests.push_back(PinRequest{pins_[i].anchor_px, glm::vec2(w, h)});
        index.push_back(i);
    }
    const Rect screen{0.0f, 0.0f, static_cast<float>(ui.width), static_cast<float>(ui.height)};
    const auto placed = layout_pins(requests, obstacles, screen, std::floor(0.5f * b), 4.0f);
    for (size_t k = 0; k < placed.size(); ++k) {
        PinView& p = pins_[index[k]];
        p.label = placed[k];
        if (!placed[k]) continue;
        Control c;
        c.id = ControlId::Pin;
        c.group = static_cast<int>(index[k]);
        c.rect = *placed[k];
        c.text = p.title;
        c.active = static_cast<int>(index[k]) == open_pin();
        controls_.push_back(std::move(c));
    }
}

}  // namespace body::kiosk
