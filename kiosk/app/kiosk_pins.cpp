// KioskApp's pinned labels: anchors (the manifest's, or each model's default
// pin), their place on screen each frame, occlusion by ray casts through the
// app's picker, and the open pin (behaviour in kiosk_app.h, layout in pins.h).
//
// The default pin of a model without pins is its most visible point: the
// surface point the start camera sees at the centre of the model's silhouette
// (the ray from the home eye through the centre of the model's bounding
// sphere); when that ray misses (a ring, a crescent), rays on rings of a
// quarter, a half and three quarters of the projected radius, eight each, are
// tried in order and the first hit is taken.
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

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
    pin_occluded_.assign(pins_.size(), 0);
}

// Whether model `m` can hold a surface point on `ray` nearer than `before`:
// false when the ray misses the sphere around its bounds (ModelInfo's radius
// is the box's half diagonal over sqrt 3), or enters it only past `before`.
// Spares the batched picker's triangle walk for models nowhere near the line of sight.
bool KioskApp::may_occlude(int m, const Ray& ray, float before) const {
    const float r = info_[static_cast<size_t>(m)].radius * 1.7320508f * 1.01f;
    const glm::vec3 oc = ray.origin - model_center(m);
    const float b = glm::dot(oc, ray.direction), c = glm::dot(oc, oc) - r * r;
    if (c <= 0.0f) return true;  // the eye inside the sphere
    const float disc = b * b - c;
    return b < 0.0f && disc >= 0.0f && -b - std::sqrt(disc) < before;
}

// Occluded: another surface (of any visible model, its own included) lies on
// the ray from the eye before the anchor, by more than 1% of the distance.
void KioskApp::test_pin_occlusion() {
    const glm::vec3 eye = camera_.eye();
    std::vector<Ray> rays(pins_.size());
    std::vector<float> dist(pins_.size(), 0.0f);
    for (size_t i = 0; i < pins_.size(); ++i) {
        const glm::vec3 p = glm::vec3(placement(pins_[i].model) * glm::vec4(pins_[i].anchor, 1.0f));
        dist[i] = glm::length(p - eye);
        pin_occluded_[i] = 0;
        if (dist[i] > 0.0f) rays[i] = Ray{eye, (p - eye) / dist[i]};
    }
    if (many_picker_) {  // each model once, with the rays of every pin it may hide
        std::vector<Ray> batch;
        std::vector<size_t> which;
        std::vector<float> nearest;
        for (int m = 0; m < model_count(); ++m) {
            if (!visible(m)) continue;
            batch.clear();
            which.clear();
            for (size_t i = 0; i < pins_.size(); ++i) {
                if (pin_occluded_[i] || dist[i] <= 0.0f || !may_occlude(m, rays[i], dist[i] * 0.99f)) continue;
                batch.push_back(rays[i]);
                which.push_back(i);
            }
            if (batch.empty()) continue;
            nearest.assign(batch.size(), INFINITY);
            many_picker_(m, batch, nearest);
            for (size_t k = 0; k < batch.size(); ++k)
                if (nearest[k] < dist[which[k]] * 0.99f) pin_occluded_[which[k]] = 1;
        }
        return;
    }
    for (size_t i = 0; i < pins_.size(); ++i) {
        if (dist[i] <= 0.0f) continue;
        // The nearest surface on the line of sight, through the picking hierarchy (kiosk_pick.cpp).
        float t = 0.0f;
        if (pick_ray(rays[i], t) >= 0 && t < dist[i] * 0.99f) pin_occluded_[i] = 1;
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
    if (key != pin_tested_key_ && (stopped || now - pin_tested_at_ >= kOcclusionInterval)) {
        test_pin_occlusion();
        pin_tested_key_ = key;
        pin_tested_at_ = now;
    }
    pin_last_key_ = std::move(key);
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
