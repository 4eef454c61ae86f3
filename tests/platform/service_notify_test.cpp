// Service notifications on a stand-in socket: READY=1 after the first frame
// only, WATCHDOG=1 paced by the unit's interval and only while frames come,
// STOPPING=1 at the end; nothing at all outside systemd.
#include "platform/service_notify.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "notify_listener.h"

namespace body::platform {
namespace {

class ServiceNotify : public ::testing::Test {
protected:
    void SetUp() override {
        path_ = (std::filesystem::temp_directory_path() / ("body_notify_" + std::to_string(::getpid()))).string();
        listener_ = std::make_unique<test::NotifyListener>(path_);
        ASSERT_TRUE(listener_->bound());
        ::setenv("NOTIFY_SOCKET", path_.c_str(), 1);
        ::setenv("WATCHDOG_USEC", "2000000", 1);  // 2 s: a ping every 0.5 s of frames
        ::setenv("WATCHDOG_PID", std::to_string(::getpid()).c_str(), 1);
    }
    void TearDown() override {
        ::unsetenv("NOTIFY_SOCKET");
        ::unsetenv("WATCHDOG_USEC");
        ::unsetenv("WATCHDOG_PID");
    }
    std::string path_;
    std::unique_ptr<test::NotifyListener> listener_;
};

TEST_F(ServiceNotify, ReadyAfterTheFirstFrameThenWatchdogWhileFramesCome) {
    ServiceNotifier n;
    ASSERT_TRUE(n.active());
    EXPECT_DOUBLE_EQ(n.watchdog_seconds(), 2.0);
    EXPECT_TRUE(listener_->drain().empty());  // nothing before a frame
    n.frame_presented(10.0);
    auto first = listener_->drain();
    ASSERT_EQ(first.size(), 1u);
    EXPECT_EQ(first[0].rfind("READY=1", 0), 0u) << first[0];
    // Frames at 60 Hz for 2 s: a ping every 0.5 s.
    for (int f = 1; f <= 120; ++f) n.frame_presented(10.0 + f / 60.0);
    auto pings = listener_->drain();
    EXPECT_EQ(pings.size(), 4u);
    for (const auto& p : pings) EXPECT_EQ(p, "WATCHDOG=1");
    // The loop hangs: no frame, no ping, however long (systemd will restart it).
    EXPECT_TRUE(listener_->drain().empty());
    n.stopping();
    auto last = listener_->drain();
    ASSERT_EQ(last.size(), 1u);
    EXPECT_EQ(last[0], "STOPPING=1");
}

TEST_F(ServiceNotify, WatchdogOfAnotherProcessIsIgnored) {
    ::setenv("WATCHDOG_PID", "1", 1);
    ServiceNotifier n;
    EXPECT_TRUE(n.active());
    EXPECT_EQ(n.watchdog_seconds(), 0.0);
    for (int f = 0; f < 600; ++f) n.frame_presented(f / 60.0);
    EXPECT_EQ(listener_->drain().size(), 1u);  // READY only
}

TEST_F(ServiceNotify, OutsideSystemdNothingIsSent) {
    ::unsetenv("NOTIFY_SOCKET");
    ServiceNotifier n;
    EXPECT_FALSE(n.active());
    for (int f = 0; f < 600; ++f) n.frame_presented(f / 60.0);
    n.stopping();
    EXPECT_TRUE(listener_->drain().empty());
    EXPECT_FALSE(notify_service("READY=1"));
}

}  // namespace
}  // namespace body::platform
