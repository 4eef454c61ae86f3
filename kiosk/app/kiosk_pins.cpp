// KioskApp's pinned labels: anchors (the manifest's, or each model's default
// pin), their place on screen each frame, occlusion by ray casts through the
// app's picker where no renderer answers it (pin_occlusion.h), and the open
// pin (behaviour in kiosk_app.h, layout in pins.h).
//
// The default pin of a model without pins is its most visible point: the
// surface point the start camera sees at the centre of the model's silhouette
// (the ray from the home eye through the centre of the model's bounding
// sphere); when that ray misses (a ring, a crescent), rays on rings of a
// quarter, a half and three quarters of the projected radius, eight each, are
// tried in order and the first hit is taken.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <tuple>

#include "kiosk/app/kiosk_app.h"

namespace body::kiosk {

namespace {

// Occlusion is tested at most this often while the camera keeps moving, and
// as soon as it stops (ray casts against every triangle are too dear per frame).
constexpr double kOcclusionInterval = 0.2;

}  // namespace

glm::mat4 KioskApp::placement(int model) const {
    return glm::translate(glm::mat4(1.0f), models_[static_cast<size_t>(model)].offset) *
           to_model_matrix(scene_.models[static_cast<size_t>(model)].transform);
}

int KioskApp::open_pin() const {
    if (open_pin_ < 0 || open_pin_ >= static_cast<int>(pins_.size())) return -1;
    return pins_[static_cast<size_t>(open_pin_)].model == selected_ ? open_pin_ : -1;
}

void KioskApp::find_pin_anchors() {
    pin_anchors_found_ = true;
    pins_.clear();
    OrbitCamera home = camera_;
    home.set_pose(home_pose_);
    for (int m = 0; m < model_count(); ++m) {
        if (!info(m).loaded) continue;
        const scene::Model& sm = scene_.models[static_cast<size_t>(m)];
        for (size_t k = 0; k < sm.pins.size(); ++k) {
            PinView p;
            p.model = m;
            p.pin = static_cast<int>(k);
            p.anchor = glm::vec3(sm.pins[k].anchor[0], sm.pins[k].anchor[1], sm.pins[k].anchor[2]);
            pins_.push_back(p);
        }
        if (!sm.pins.empty()) continue;
        const glm::vec3 c = model_center(m);
        const glm::vec4 clip = home.projection() * home.view() * glm::vec4(c, 1.0f);
        if (clip.w <= 0.0f) continue;
        const glm::vec2 px((clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(home.width()),
                           (0.5f - clip.y / clip.w * 0.5f) * static_cast<float>(home.height()));
        const float r = home.screen_radius(c, info(m).radius);
        std::optional<glm::vec3> hit;
        for (int ring = 0; ring < 4 && !hit; ++ring) {
            for (int k = 0; k < (ring ? 8 : 1) && !hit; ++k) {
                const float a = 0.7853982f * static_cast<float>(k), d = 0.25f * static_cast<float>(ring) * r;
                const Ray ray = home.ray(px.x + d * std::cos(a), px.y + d * std::sin(a));
                if (const auto t = hit_distance(m, ray)) hit = ray.origin + ray.direction * *t;
            }
        }
        if (!hit) continue;
        PinView p;
        p.model = m;
        p.anchor = glm::vec3(glm::inverse(placement(m)) * glm::vec4(*hit, 1.0f));
        pins_.push_back(p);
    }
    pin_occluded_.assign(pins_.size(), pin_occlusion_by_renderer_ ? 1 : 0);
}

// Occluded: another surface (of any visible model, its own included) lies on
// the ray from the eye before the anchor, by more than 1% of the distance.
// One walk serves both pickers: the box hierarchy (kiosk_pick.cpp) lists, per
// pin's ray, the models whose box it enters before the anchor; the models are
// then taken nearest entry first, each once with the rays of every pin it may
// still hide (a batched picker walks its triangles once for them all; the
// single picker is asked ray by ray), so a pin hidden by a near model is not
// cast again through the models behind it.
void KioskApp::test_pin_occlusion() {
    const glm::vec3 eye = camera_.eye();
    std::vector<Ray> rays(pins_.size());
    std::vector<float> before(pins_.size(), 0.0f);
    for (size_t i = 0; i < pins_.size(); ++i) {
        const glm::vec3 p = glm::vec3(placement(pins_[i].model) * glm::vec4(pins_[i].anchor, 1.0f));
        const float dist = glm::length(p - eye);
        pin_occluded_[i] = 0;
        before[i] = dist * 0.99f;
        if (dist > 0.0f) rays[i] = Ray{eye, (p - eye) / dist};
    }
    refresh_pick_tree();
    struct Reach {
        float model_enter;  // the model's nearest entry over every ray that reaches it
        uint32_t model;
        size_t pin;
    };
    std::vector<Reach> reach;
    std::vector<float> enter(info_.size(), INFINITY);
    for (size_t i = 0; i < pins_.size(); ++i) {
        if (before[i] <= 0.0f) continue;
        bvh_entered(pick_tree_, rays[i], before[i], [&](uint32_t m, float t) {
            if (!visible(static_cast<int>(m))) return;
            reach.push_back(Reach{0.0f, m, i});
            enter[m] = std::min(enter[m], t);
        });
    }
    for (Reach& r : reach) r.model_enter = enter[r.model];
    std::sort(reach.begin(), reach.end(), [](const Reach& a, const Reach& b) {
        return std::tie(a.model_enter, a.model, a.pin) < std::tie(b.model_enter, b.model, b.pin);
    });
    std::vector<Ray> batch;
    std::vector<size_t> which;
    std::vector<float> nearest;
    for (size_t at = 0; at < reach.size();) {
        const uint32_t m = reach[at].model;
        batch.clear();
        which.clear();
        for (; at < reach.size() && reach[at].model == m; ++at) {
            if (pin_occluded_[reach[at].pin]) continue;
            batch.push_back(rays[reach[at].pin]);
            which.push_back(reach[at].pin);
        }
        if (batch.empty()) continue;
        nearest.assign(batch.size(), INFINITY);
        if (many_picker_) {
            many_picker_(static_cast<int>(m), batch, nearest);
        } else {
            for (size_t k = 0; k < batch.size(); ++k)
                if (const auto t = hit_distance(static_cast<int>(m), batch[k])) nearest[k] = *t;
        }
        for (size_t k = 0; k < batch.size(); ++k)
            if (nearest[k] < before[which[k]]) pin_occluded_[which[k]] = 1;
    }
}

void KioskApp::update_pins(double now) {
    if (!scene_.kiosk.pins) return;
    if (!pin_anchors_found_) find_pin_anchors();
    // What occlusion depends on: the camera, the visibility and the models' offsets.
    std::vector<float> key{camera_.pose().target.x, camera_.pose().target.y, camera_.pose().target.z,
                           camera_.pose().azimuth,  camera_.pose().polar,    camera_.pose().distance};
    for (int m = 0; m < model_count(); ++m) {
        key.push_back(visible(m) ? 1.0f : 0.0f);
        for (int a = 0; a < 3; ++a) key.push_back(models_[static_cast<size_t>(m)].offset[a]);
    }
    const bool stopped = key == pin_last_key_;
    if (!pin_occlusion_by_renderer_ && key != pin_tested_key_ &&
        (stopped || now - pin_tested_at_ >= kOcclusionInterval)) {
        test_pin_occlusion();
        pin_tested_key_ = key;
        pin_tested_at_ = now;
    }
    pin_last_key_ = std::move(key);
    place_pins();
}

void KioskApp::set_pin_occlusion(std::span<const char> hidden, bool refresh) {
    if (hidden.size() != pins_.size()) return;
    pin_occluded_.assign(hidden.begin(), hidden.end());
    if (!refresh || !scene_.kiosk.pins) return;
    place_pins();
    relayout();
}

// Each pin's point on screen, text and whether it shows, from the current occlusion.
void KioskApp::place_pins() {
    const glm::mat4 vp = camera_.projection() * camera_.view();
    const glm::vec2 drift_px = drift(now_);
    for (size_t i = 0; i < pins_.size(); ++i) {
        PinView& p = pins_[i];
        const scene::Model& sm = scene_.models[static_cast<size_t>(p.model)];
        const scene::LabelText* t = p.pin >= 0 ? scene_.text(sm.pins[static_cast<size_t>(p.pin)].labels, language_)
                                               : &scene_.label(sm, language_);
        p.title = t ? t->title : sm.name;
        p.description = t ? t->description : std::string();
        const glm::vec4 clip = vp * placement(p.model) * glm::vec4(p.anchor, 1.0f);
        p.shown = false;
        if (clip.w <= 0.0f) continue;
        p.anchor_px = glm::vec2((clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(camera_.width()) + drift_px.x,
                                (0.5f - clip.y / clip.w * 0.5f) * static_cast<float>(camera_.height()) + drift_px.y);
        const bool on_screen = p.anchor_px.x >= 0 && p.anchor_px.y >= 0 &&
                               p.anchor_px.x < static_cast<float>(camera_.width()) &&
                               p.anchor_px.y < static_cast<float>(camera_.height());
        p.shown = on_screen && visible(p.model) && !pin_occluded_[i];
    }
}

}  // namespace body::kiosk
