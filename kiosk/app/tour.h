#pragma once
// Tours (scene.json `tours`, shared/scene/SCENE.md) as pure logic, no GL: the
// easing curves, the camera pose between two steps, and the player's state
// machine. KioskApp applies a step's scene state (visibility, styles,
// selection) when the player enters it and sets the camera from pose_at().
//
// Player: start() enters step 0. A step first moves (its `duration`, eased),
// then holds (its `hold`); playing, it then enters the next step. After the
// last step the tour stays there (`finished()`), or starts over when it loops
// (the attract mode). pause() freezes the clock; next()/previous() enter a step
// at once (and keep the pause); leave() ends the tour. Times are seconds.
#include "kiosk/app/camera.h"
#include "shared/scene/scene.h"

namespace body::kiosk {

// f(0) = 0, f(1) = 1, monotonic; t is clamped to [0, 1].
float ease(scene::Easing easing, float t);

// The pose a fraction `t` (already eased) of the way from `a` to `b`: target and
// distance linearly, polar linearly, azimuth the shorter way round.
CameraPose interpolate_pose(const CameraPose& a, const CameraPose& b, float t);

// The pose a step aims at: each value the step gives, the rest from `from`.
// A step distance of 0 means `home.distance`.
CameraPose step_pose(const scene::TourCamera& camera, const CameraPose& from, const CameraPose& home);

class TourPlayer {
public:
    // Enters step 0 of a tour with `steps` steps (>= 1).
    void start(int tour, int steps, bool loop, double now);
    void leave();
    void pause(double now);
    void resume(double now);
    void next(double now);
    void previous(double now);
    // Advances the clock; true when a new step was entered since the last call
    // (start, next, previous and the automatic advance all count).
    bool update(double now, const scene::Tour& tour);

    bool active() const { return tour_ >= 0; }
    bool paused() const { return paused_; }
    bool looping() const { return loop_; }
    bool finished() const;  // holding the last step of a tour that does not loop
    int tour() const { return tour_; }
    int step() const { return step_; }
    // Seconds into the current step (frozen while paused).
    double elapsed() const { return elapsed_; }
    // The eased fraction of the current step's move, in [0, 1].
    float progress(const scene::Tour& tour) const;

private:
    void enter(int step, double now);

    int tour_ = -1, step_ = 0, steps_ = 0;
    bool loop_ = false, paused_ = false, entered_ = false;
    double elapsed_ = 0.0, last_ = 0.0;
    double finished_at_ = 1e30;  // the last step's duration + hold, from the last update()
};

}  // namespace body::kiosk
