#pragma once
// Randomised visitors for the soak (soak.h): sessions of gestures and control
// taps, each followed by an idle period. A session is 3..15 actions 0.3..3 s
// apart: a tap on the picture (picks or deselects), a one-finger drag (orbit, or
// moves a selected object), a two-finger pinch (zoom), a wheel turn, or a tap
// on an enabled control (style, group style, LOD -/+/auto, isolate, a group
// toggle, language, home). Idle periods: 70 % past `reset_seconds` (attract,
// then reset), 20 % between `idle_seconds` and the reset (attract only), 10 %
// shorter. Touches never land in the screen's corners (the admin gesture lives
// in one). The same seed gives the same visitors for the same frame times.
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "platform/platform.h"

namespace body::kiosk {

class KioskApp;

class SoakVisitors {
public:
    SoakVisitors(uint64_t seed, double idle_seconds, double reset_seconds);

    // Appends the events due at `now` (stamped `now`); plans the next action
    // from the app's controls and screen size when nothing is pending.
    void poll(const KioskApp& app, double now, std::vector<platform::InputEvent>& out);

    long sessions() const { return sessions_; }  // sessions begun
    long actions() const { return actions_; }    // actions begun

private:
    struct Timed {
        double time;
        platform::InputEvent event;
    };
    void plan(const KioskApp& app, double now);
    void plan_action(const KioskApp& app, double t);
    void tap(float x, float y, double t);
    void drag(float x0, float y0, float x1, float y1, double t, double seconds);
    void pinch(float cx, float cy, float r0, float r1, double t, double seconds);
    void push(double t, platform::InputEvent::Type type, int id, float x, float y);
    bool in_corner(float x, float y) const;
    float uniform(float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng_); }
    double uniform_d(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }

    std::mt19937_64 rng_;
    double idle_seconds_, reset_seconds_;
    std::deque<Timed> pending_;  // in time order
    double next_action_ = 0.5;   // time the next action starts
    int actions_left_ = 0;       // in the current session; 0: the next action starts a session
    float width_ = 0, height_ = 0;
    long sessions_ = 0, actions_ = 0;
};

}  // namespace body::kiosk
