// Randomised soak visitors (contract in soak_visitors.h).
#include "kiosk/modes/soak_visitors.h"

#include <algorithm>
#include <cmath>

#include "kiosk/app/kiosk_app.h"

namespace body::kiosk {

using Type = platform::InputEvent::Type;

SoakVisitors::SoakVisitors(uint64_t seed, double idle_seconds, double reset_seconds)
    : rng_(seed), idle_seconds_(idle_seconds), reset_seconds_(reset_seconds) {}

bool SoakVisitors::in_corner(float x, float y) const {
    const float c = 0.12f * std::min(width_, height_);
    return (x < c || x > width_ - c) && (y < c || y > height_ - c);
}

void SoakVisitors::push(double t, Type type, int id, float x, float y) {
    platform::InputEvent e;
    e.type = type;
    e.id = id;
    e.x = std::clamp(x, 0.0f, width_ - 1.0f);
    e.y = std::clamp(y, 0.0f, height_ - 1.0f);
    e.time = t;
    pending_.push_back({t, e});
}

void SoakVisitors::tap(float x, float y, double t) {
    push(t, Type::TouchDown, 1, x, y);
    push(t + uniform_d(0.05, 0.15), Type::TouchUp, 1, x, y);
}

void SoakVisitors::drag(float x0, float y0, float x1, float y1, double t, double seconds) {
    const int steps = std::max(2, static_cast<int>(seconds * 60.0));
    push(t, Type::TouchDown, 1, x0, y0);
    for (int i = 1; i <= steps; ++i) {
        const float f = static_cast<float>(i) / static_cast<float>(steps);
        push(t + seconds * f, Type::TouchMove, 1, x0 + (x1 - x0) * f, y0 + (y1 - y0) * f);
    }
    push(t + seconds + 0.02, Type::TouchUp, 1, x1, y1);
}

// Two fingers on a line through (cx, cy), their distance going from 2 r0 to 2 r1.
void SoakVisitors::pinch(float cx, float cy, float r0, float r1, double t, double seconds) {
    const float a = uniform(0.0f, 3.14159f), ca = std::cos(a), sa = std::sin(a);
    const int steps = std::max(2, static_cast<int>(seconds * 60.0));
    push(t, Type::TouchDown, 1, cx - ca * r0, cy - sa * r0);
    push(t + 0.01, Type::TouchDown, 2, cx + ca * r0, cy + sa * r0);
    for (int i = 1; i <= steps; ++i) {
        const float f = static_cast<float>(i) / static_cast<float>(steps), r = r0 + (r1 - r0) * f;
        const double ti = t + 0.01 + seconds * f;
        push(ti, Type::TouchMove, 1, cx - ca * r, cy - sa * r);
        push(ti, Type::TouchMove, 2, cx + ca * r, cy + sa * r);
    }
    push(t + seconds + 0.03, Type::TouchUp, 2, cx + ca * r1, cy + sa * r1);
    push(t + seconds + 0.04, Type::TouchUp, 1, cx - ca * r1, cy - sa * r1);
}

// One action starting at `t`; `next_action_` moves past its end.
void SoakVisitors::plan_action(const KioskApp& app, double t) {
    ++actions_;
    float x = 0, y = 0;
    do {
        x = uniform(0.15f * width_, 0.85f * width_);
        y = uniform(0.15f * height_, 0.85f * height_);
    } while (in_corner(x, y));
    const int kind = std::uniform_int_distribution<int>(0, 9)(rng_);
    if (kind <= 3) {  // a control: the common case for a visitor exploring
        std::vector<const Control*> enabled;
        for (const Control& c : app.controls())
            if (c.enabled && !in_corner(c.rect.x + c.rect.w * 0.5f, c.rect.y + c.rect.h * 0.5f)) enabled.push_back(&c);
        if (!enabled.empty()) {
            const Control* c = enabled[std::uniform_int_distribution<size_t>(0, enabled.size() - 1)(rng_)];
            float cx = c->rect.x + c->rect.w * uniform(0.3f, 0.7f), cy = c->rect.y + c->rect.h * uniform(0.3f, 0.7f);
            if (in_corner(cx, cy)) cx = c->rect.x + c->rect.w * 0.5f, cy = c->rect.y + c->rect.h * 0.5f;
            tap(cx, cy, t);
        } else {
            tap(x, y, t);
        }
        next_action_ = t + 0.2;
    } else if (kind <= 5) {  // a tap on the picture: select, deselect, focus
        tap(x, y, t);
        next_action_ = t + 0.2;
    } else if (kind <= 7) {
        const double s = uniform_d(0.3, 1.5);
        drag(x, y, x + uniform(-0.3f, 0.3f) * width_, y + uniform(-0.3f, 0.3f) * height_, t, s);
        next_action_ = t + s + 0.1;
    } else if (kind == 8) {
        const float r = 0.05f * std::min(width_, height_), s = uniform(0.5f, 3.0f);
        const double d = uniform_d(0.3, 1.0);
        pinch(x, y, r, r * s, t, d);
        next_action_ = t + d + 0.1;
    } else {
        platform::InputEvent e;
        e.type = Type::Scroll;
        e.x = x;
        e.y = y;
        e.dy = uniform(-3.0f, 3.0f);
        e.time = t;
        pending_.push_back({t, e});
        next_action_ = t + 0.1;
    }
    next_action_ += uniform_d(0.3, 3.0);
}

void SoakVisitors::plan(const KioskApp& app, double now) {
    if (now < next_action_) return;
    const double t = std::max(now, next_action_);
    if (actions_left_ == 0) {
        ++sessions_;
        actions_left_ = std::uniform_int_distribution<int>(3, 15)(rng_);
    }
    plan_action(app, t);
    if (--actions_left_ == 0) {  // the session ends: an idle period
        const double u = uniform_d(0.0, 1.0);
        const double idle = u < 0.7   ? reset_seconds_ + uniform_d(0.5, 4.0)
                            : u < 0.9 ? uniform_d(idle_seconds_ + 0.5, reset_seconds_ - 0.5)
                                      : uniform_d(0.5, idle_seconds_ - 0.5);
        next_action_ = std::max(next_action_, pending_.empty() ? t : pending_.back().time) + idle;
    }
}

void SoakVisitors::poll(const KioskApp& app, double now, std::vector<platform::InputEvent>& out) {
    width_ = static_cast<float>(app.ui_state().width);
    height_ = static_cast<float>(app.ui_state().height);
    if (pending_.empty()) plan(app, now);
    while (!pending_.empty() && pending_.front().time <= now) {
        out.push_back(pending_.front().event);
        pending_.pop_front();
    }
}

}  // namespace body::kiosk
