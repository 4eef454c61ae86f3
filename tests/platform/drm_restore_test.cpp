// The display restore against a fake DRM device (DrmOps): the saved CRTC comes
// back once on the normal path, after a pending flip has completed, as "off"
// when it was off, not at all before the kiosk's mode was set, and from the
// crash handler of a process that aborts.
#include "platform/drm_restore.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <string>
#include <vector>

namespace body::platform {
namespace {

// The fake device: one CRTC whose state the calls read and write, and a log of calls.
struct FakeDrm {
    drmModeCrtc crtc{};  // what the screen shows now
    bool event_ready = false;
    std::vector<std::string> calls;
    int set_crtc_result = 0;
    int log_fd = -1;  // crash test: set_crtc also writes here (the parent reads it)
};
FakeDrm g_fake;

drmModeCrtc* fake_get_crtc(int, uint32_t id) {
    g_fake.calls.push_back("get " + std::to_string(id));
    return new drmModeCrtc(g_fake.crtc);
}
void fake_free_crtc(drmModeCrtc* c) { delete c; }
int fake_set_crtc(int, uint32_t id, uint32_t fb, uint32_t x, uint32_t y, uint32_t* connectors, int count,
                  drmModeModeInfo* mode) {
    const std::string call =
        "set " + std::to_string(id) + " fb " + std::to_string(fb) + " at " + std::to_string(x) + "," +
        std::to_string(y) + " connectors " + std::to_string(count) +
        (count ? " first " + std::to_string(connectors[0]) : "") +
        (mode ? " mode " + std::to_string(mode->hdisplay) + "x" + std::to_string(mode->vdisplay) : " no mode");
    g_fake.calls.push_back(call);
    if (g_fake.log_fd >= 0) (void)!::write(g_fake.log_fd, call.data(), call.size());
    if (g_fake.set_crtc_result == 0) {
        g_fake.crtc.buffer_id = fb;
        g_fake.crtc.mode_valid = mode != nullptr;
    }
    return g_fake.set_crtc_result;
}
int fake_wait(int, int) {
    g_fake.calls.push_back("wait");
    return g_fake.event_ready ? 1 : 0;
}
int fake_handle(int, drmEventContext*) {
    g_fake.calls.push_back("event");
    g_fake.event_ready = false;
    return 0;
}
// Only the calls a legacy restore makes; the atomic restore is in drm_display_test.cpp.
const DrmOps kFake = {.get_crtc = fake_get_crtc,
                      .free_crtc = fake_free_crtc,
                      .set_crtc = fake_set_crtc,
                      .wait_readable = fake_wait,
                      .handle_event = fake_handle,
                      .set_client_cap = nullptr,
                      .property_id = nullptr,
                      .primary_plane = nullptr,
                      .create_blob = nullptr,
                      .destroy_blob = nullptr,
                      .atomic_commit = nullptr,
                      .page_flip = nullptr,
                      .set_master = nullptr,
                      .probe = nullptr};

// The console's CRTC 41 showing framebuffer 7 at 1920x1080 on connector 33.
void console_on_screen() {
    g_fake = FakeDrm{};
    g_fake.crtc.crtc_id = 41;
    g_fake.crtc.buffer_id = 7;
    g_fake.crtc.x = 0;
    g_fake.crtc.y = 0;
    g_fake.crtc.mode_valid = 1;
    g_fake.crtc.mode.hdisplay = 1920;
    g_fake.crtc.mode.vdisplay = 1080;
}
const std::string kRestored = "set 41 fb 7 at 0,0 connectors 1 first 33 mode 1920x1080";

// The kiosk's mode set as drm_surface.cpp does it, through the fake.
void kiosk_mode_set(DrmCrtcKeeper& keeper) {
    ASSERT_TRUE(keeper.save());
    drmModeModeInfo mode{};
    mode.hdisplay = 1280;
    mode.vdisplay = 800;
    uint32_t connector = 33;
    ASSERT_EQ(fake_set_crtc(3, 41, 99, 0, 0, &connector, 1, &mode), 0);
    keeper.mode_set();
}

TEST(DrmRestore, NormalExitPutsTheSavedCrtcBackOnce) {
    console_on_screen();
    {
        DrmCrtcKeeper keeper(kFake, 3, 41, 33);
        kiosk_mode_set(keeper);
        EXPECT_EQ(g_fake.crtc.buffer_id, 99u);
        ASSERT_TRUE(keeper.restore());
        EXPECT_TRUE(keeper.restored());
        EXPECT_TRUE(keeper.restore());  // again: nothing
    }                                   // and the destructor: nothing more
    EXPECT_EQ(g_fake.crtc.buffer_id, 7u);
    ASSERT_EQ(g_fake.calls.size(), 3u);
    EXPECT_EQ(g_fake.calls[2], kRestored);
}

TEST(DrmRestore, SigtermOrFatalErrorPathRestoresThroughTheDestructor) {
    console_on_screen();
    {
        // The loop left (SIGTERM's quit, or an error returned after the mode set):
        // the surface is destroyed without an explicit restore.
        DrmCrtcKeeper keeper(kFake, 3, 41, 33);
        kiosk_mode_set(keeper);
    }
    EXPECT_EQ(g_fake.calls.back(), kRestored);
    EXPECT_EQ(g_fake.crtc.buffer_id, 7u);
}

TEST(DrmRestore, NothingIsTouchedBeforeTheModeSet) {
    console_on_screen();
    {
        DrmCrtcKeeper keeper(kFake, 3, 41, 33);
        ASSERT_TRUE(keeper.save());  // e.g. EGL failed after this
    }
    ASSERT_EQ(g_fake.calls.size(), 1u);
    EXPECT_EQ(g_fake.calls[0], "get 41");
}

TEST(DrmRestore, APendingFlipCompletesBeforeTheRestore) {
    console_on_screen();
    DrmCrtcKeeper keeper(kFake, 3, 41, 33);
    kiosk_mode_set(keeper);
    keeper.flip_queued();
    g_fake.event_ready = true;
    ASSERT_TRUE(keeper.restore());
    EXPECT_FALSE(keeper.flip_pending());
    const auto& c = g_fake.calls;
    ASSERT_GE(c.size(), 5u);
    EXPECT_EQ(c[c.size() - 3], "wait");
    EXPECT_EQ(c[c.size() - 2], "event");
    EXPECT_EQ(c.back(), kRestored);
}

TEST(DrmRestore, AFlipThatNeverCompletesDelaysTheRestoreBoundedly) {
    console_on_screen();
    DrmCrtcKeeper keeper(kFake, 3, 41, 33);
    kiosk_mode_set(keeper);
    keeper.flip_queued();  // no event will come
    ASSERT_TRUE(keeper.restore());
    EXPECT_EQ(g_fake.calls.back(), kRestored);
    long waits = std::count(g_fake.calls.begin(), g_fake.calls.end(), std::string("wait"));
    EXPECT_EQ(waits, DrmCrtcKeeper::kFlipWaitMs / 50);
}

TEST(DrmRestore, ACrtcThatWasOffIsTurnedOffAgain) {
    console_on_screen();
    g_fake.crtc.buffer_id = 0;
    g_fake.crtc.mode_valid = 0;
    DrmCrtcKeeper keeper(kFake, 3, 41, 33);
    kiosk_mode_set(keeper);
    ASSERT_TRUE(keeper.restore());
    EXPECT_EQ(g_fake.calls.back(), "set 41 fb 0 at 0,0 connectors 0 no mode");
}

TEST(DrmRestore, AFailedRestoreIsReported) {
    console_on_screen();
    DrmCrtcKeeper keeper(kFake, 3, 41, 33);
    kiosk_mode_set(keeper);
    g_fake.set_crtc_result = -1;
    errno = EACCES;
    auto s = keeper.restore();
    ASSERT_FALSE(s);
    EXPECT_NE(s.error().message.find("restoring the display failed"), std::string::npos);
}

// A kiosk that aborts after its mode set: the crash handler restores, then the
// process still dies of SIGABRT (so systemd sees the crash and restarts it).
TEST(DrmRestore, ACrashRestoresThenDiesOfTheSignal) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        ::close(fds[0]);
        console_on_screen();
        g_fake.log_fd = fds[1];
        static DrmCrtcKeeper* keeper = new DrmCrtcKeeper(kFake, 3, 41, 33);
        keeper->save();
        keeper->mode_set();
        restore_on_crash(keeper);
        std::abort();
    }
    ::close(fds[1]);
    std::string log;
    char buf[256];
    for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) log.append(buf, static_cast<size_t>(n));
    ::close(fds[0]);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), SIGABRT);
    EXPECT_EQ(log, kRestored);
}

}  // namespace
}  // namespace body::platform
