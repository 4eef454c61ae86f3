#pragma once
// The kiosk's memory at its idle moment: a reset (nobody has touched it for
// reset_seconds) returns it to the start state, and what the last visitor's
// session allocated has been freed by then, but the C heap keeps freed pages
// resident (glibc trims only its top, and only on some frees), across every
// thread's arena: over hours the RSS would follow the worst moment of any
// session. IdleMemory gives the heap's free pages back once per reset,
// `delay` seconds after it (the frames that follow a reset release the
// styles' data and land the glides first).
//
//   IdleMemory idle;                         // glibc's malloc_trim by default
//   per frame: idle.frame(app.resets(), now);
#include <functional>

namespace body::kiosk {

class IdleMemory {
public:
    static constexpr double kDelaySeconds = 1.0;
    // `give_back`: what returns the free pages (tests count the calls).
    explicit IdleMemory(std::function<void()> give_back = {}, double delay = kDelaySeconds);

    // Called once per frame with the app's reset count and clock; calls
    // give_back once, `delay` after a reset count it has not seen yet.
    void frame(int resets, double now);
    long given_back() const { return given_back_; }  // calls so far

private:
    std::function<void()> give_back_;
    double delay_;
    int resets_seen_ = 0;
    double due_ = -1.0;  // < 0: none due
    long given_back_ = 0;
};

}  // namespace body::kiosk
