// The kiosk gives its free heap back once per reset, a moment after it
// (kiosk/app/idle_memory.h), and never while visitors use it.
#include "kiosk/app/idle_memory.h"

#include <gtest/gtest.h>

#include "kiosk_test_scene.h"

namespace body::kiosk {
namespace {

TEST(IdleMemory, GivesBackOnceADelayAfterEachReset) {
    long calls = 0;
    IdleMemory idle([&] { ++calls; }, 1.0);
    for (int f = 0; f <= 600; ++f) idle.frame(0, f / 60.0);  // ten seconds of use: no reset
    EXPECT_EQ(calls, 0);
    idle.frame(1, 10.0);  // the reset
    idle.frame(1, 10.5);
    EXPECT_EQ(calls, 0);  // not yet: the frames after a reset free the styles' data
    idle.frame(1, 11.0);
    EXPECT_EQ(calls, 1);
    for (int f = 0; f < 600; ++f) idle.frame(1, 11.0 + f / 60.0);
    EXPECT_EQ(calls, 1);  // once per reset
    idle.frame(2, 30.0);
    idle.frame(3, 30.5);  // another before it was due: one call, a delay after the last
    idle.frame(3, 31.2);
    EXPECT_EQ(calls, 1);
    idle.frame(3, 31.5);
    EXPECT_EQ(calls, 2);
    EXPECT_EQ(idle.given_back(), 2);
}

// Driven by a KioskApp's own idle timers: one give-back per reset the app makes.
TEST(IdleMemory, FollowsTheAppsResets) {
    KioskApp app = test::make_app();
    long calls = 0;
    IdleMemory idle([&] { ++calls; });
    for (int f = 0; f < 60 * 60; ++f) {  // one idle minute
        const double now = f / 60.0;
        app.update(now);
        idle.frame(app.resets(), now);
    }
    EXPECT_GE(app.resets(), 1);
    EXPECT_EQ(calls, app.resets());
}

}  // namespace
}  // namespace body::kiosk
