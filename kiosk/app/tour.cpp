// Tour easing, pose interpolation and the player (contract in tour.h).
#include "kiosk/app/tour.h"

#include <algorithm>
#include <cmath>

namespace body::kiosk {

float ease(scene::Easing easing, float t) {
    t = std::clamp(t, 0.0f, 1.0f);
    switch (easing) {
        case scene::Easing::Linear: return t;
        case scene::Easing::EaseIn: return t * t * t;
        case scene::Easing::EaseOut: return 1.0f - (1.0f - t) * (1.0f - t) * (1.0f - t);
        case scene::Easing::EaseInOut: return t * t * (3.0f - 2.0f * t);  // smoothstep
    }
    return t;
}

CameraPose interpolate_pose(const CameraPose& a, const CameraPose& b, float t) {
    constexpr float kTwoPi = 6.2831853f;
    float d = std::fmod(b.azimuth - a.azimuth, kTwoPi);
    if (d > kTwoPi * 0.5f) d -= kTwoPi;
    if (d < -kTwoPi * 0.5f) d += kTwoPi;
    CameraPose p;
    p.target = a.target + (b.target - a.target) * t;
    p.azimuth = a.azimuth + d * t;
    p.polar = a.polar + (b.polar - a.polar) * t;
    p.distance = a.distance + (b.distance - a.distance) * t;
    return p;
}

CameraPose step_pose(const scene::TourCamera& c, const CameraPose& from, const CameraPose& home) {
    CameraPose p = from;
    if (c.target) p.target = glm::vec3((*c.target)[0], (*c.target)[1], (*c.target)[2]);
    if (c.azimuth_deg) p.azimuth = glm::radians(*c.azimuth_deg);
    if (c.polar_deg) p.polar = glm::radians(*c.polar_deg);
    if (c.distance) p.distance = *c.distance > 0.0f ? *c.distance : home.distance;
    return p;
}

void TourPlayer::start(int tour, int steps, bool loop, double now) {
    tour_ = tour;
    steps_ = std::max(steps, 1);
    loop_ = loop;
    paused_ = false;
    enter(0, now);
}

void TourPlayer::leave() {
    tour_ = -1;
    paused_ = false;
    entered_ = false;
}

void TourPlayer::pause(double now) {
    if (!active() || paused_) return;
    elapsed_ += std::max(0.0, now - last_);
    last_ = now;
    paused_ = true;
}

void TourPlayer::resume(double now) {
    if (!active()) return;
    if (finished()) {
        enter(0, now);  // play again from the start
    }
    paused_ = false;
    last_ = now;
}

void TourPlayer::next(double now) {
    if (active()) enter(step_ + 1 < steps_ ? step_ + 1 : (loop_ ? 0 : step_), now);
}

void TourPlayer::previous(double now) {
    if (active()) enter(step_ > 0 ? step_ - 1 : 0, now);
}

void TourPlayer::enter(int step, double now) {
    step_ = step;
    elapsed_ = 0.0;
    last_ = now;
    entered_ = true;
}

bool TourPlayer::finished() const { return active() && !loop_ && step_ == steps_ - 1 && elapsed_ >= finished_at_; }

bool TourPlayer::update(double now, const scene::Tour& tour) {
    if (!active()) return false;
    if (!paused_) {
        elapsed_ += std::max(0.0, now - last_);
        last_ = now;
        const scene::TourStep& s = tour.steps[static_cast<size_t>(step_)];
        const double length = static_cast<double>(s.duration) + static_cast<double>(s.hold);
        if (elapsed_ >= length && (loop_ || step_ + 1 < steps_)) {
            enter(step_ + 1 < steps_ ? step_ + 1 : 0, now);
        }
    }
    finished_at_ = static_cast<double>(tour.steps.back().duration) + static_cast<double>(tour.steps.back().hold);
    const bool entered = entered_;
    entered_ = false;
    return entered;
}

float TourPlayer::progress(const scene::Tour& tour) const {
    if (!active()) return 1.0f;
    const scene::TourStep& s = tour.steps[static_cast<size_t>(step_)];
    if (s.duration <= 0.0f) return 1.0f;
    return ease(s.easing, static_cast<float>(elapsed_ / static_cast<double>(s.duration)));
}

}  // namespace body::kiosk
