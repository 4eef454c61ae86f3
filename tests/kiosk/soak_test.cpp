// The soak's parts without GL: the verdict on logged minutes (leaks, descriptors,
// threads, GL errors, p99 drift fail it) and the randomised visitors (sessions
// that reach attract and reset, touches outside the admin corner).
#include "kiosk/modes/soak.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "kiosk/modes/soak_visitors.h"
#include "kiosk_test_scene.h"

namespace body::kiosk {
namespace {

// `n` steady minutes: 100 MiB, 5 fds, 4 threads, p99 20 ms.
std::vector<SoakMinute> steady(int n) {
    std::vector<SoakMinute> out;
    for (int i = 1; i <= n; ++i) out.push_back({i, 100.0, 3600, 10.0, 20.0, 0, 5, 4});
    return out;
}

TEST(SoakVerdict, SteadyRunPasses) {
    const SoakVerdict v = soak_verdict(steady(30));
    EXPECT_TRUE(v.ok) << (v.failures.empty() ? "" : v.failures.front());
    EXPECT_TRUE(v.failures.empty());
}

TEST(SoakVerdict, GrowthBeyondOneMibPerHourAfterWarmupFails) {
    auto m = steady(65);
    // 3 MiB per hour from minute 5 on: 3 MiB over the hour, 1 + 1 allowed.
    for (auto& x : m) x.rss_mib += 3.0 * std::max(0, x.minute - 5) / 60.0 + 0.1;
    EXPECT_FALSE(soak_verdict(m).ok);
    // Growth inside the warm-up only (the first 5 minutes) is allowed.
    auto w = steady(65);
    for (auto& x : w) x.rss_mib += 3.0 * std::min(x.minute, 4);
    EXPECT_TRUE(soak_verdict(w).ok);
}

TEST(SoakVerdict, GlErrorsDescriptorsAndThreadsFail) {
    auto gl = steady(3);
    gl[2].gl_errors = 1;
    EXPECT_FALSE(soak_verdict(gl).ok);
    auto fds = steady(12);
    fds.back().fds = 6;
    EXPECT_FALSE(soak_verdict(fds).ok);
    auto threads = steady(12);
    threads.back().threads = 5;
    EXPECT_FALSE(soak_verdict(threads).ok);
    EXPECT_FALSE(soak_verdict(steady(1)).ok);  // nothing to compare
}

TEST(SoakVerdict, P99DriftIsJudgedOnlyWithTwoWindowsAfterWarmup) {
    auto m = steady(25);
    for (auto& x : m)
        if (x.minute > 15) x.p99_ms = 23.0;  // +15 %
    EXPECT_FALSE(soak_verdict(m).ok);
    m.back().p99_ms = m.front().p99_ms;
    auto shorter = steady(20);  // 5 warm-up + 10 + 10 fits; 19 would not
    for (auto& x : shorter) x.p99_ms = x.minute > 15 ? 21.9 : 20.0;
    EXPECT_TRUE(soak_verdict(shorter).ok);  // +9.5 %
    auto short_run = steady(19);
    short_run.back().p99_ms = 40.0;
    EXPECT_TRUE(soak_verdict(short_run).ok);
}

// Ten simulated minutes at 60 Hz: the visitors begin sessions, the app reaches
// attract and reset between them, and no touch lands in a corner.
TEST(SoakVisitors, SessionsEndInAttractAndReset) {
    KioskApp app = test::make_app();
    app.update(0.0);
    SoakVisitors visitors(7, 5.0, 10.0);  // the test scene's timers
    std::vector<platform::InputEvent> events;
    long attracts = 0, touches = 0;
    KioskMode last = app.mode();
    for (int f = 0; f < 60 * 600; ++f) {
        const double now = f / 60.0;
        events.clear();
        visitors.poll(app, now, events);
        for (const auto& e : events) {
            if (e.type == platform::InputEvent::Type::TouchDown) {
                ++touches;
                const bool corner = (e.x < 96 || e.x > 1280 - 96) && (e.y < 96 || e.y > 800 - 96);
                EXPECT_FALSE(corner) << e.x << "," << e.y;
            }
            app.handle(e);
        }
        app.update(now);
        attracts += app.mode() == KioskMode::Attract && last != KioskMode::Attract;
        last = app.mode();
    }
    EXPECT_FALSE(app.exit_requested());
    EXPECT_GE(visitors.sessions(), 10);
    EXPECT_GT(visitors.actions(), 3 * visitors.sessions());
    EXPECT_GE(touches, visitors.actions() / 2);
    EXPECT_GE(attracts, visitors.sessions() / 2);
    EXPECT_GE(app.resets(), visitors.sessions() / 3);
}

}  // namespace
}  // namespace body::kiosk
