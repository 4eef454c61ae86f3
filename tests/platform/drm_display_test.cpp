// The DRM display state machine (platform/drm_display.h) against the fake KMS
// device (drm_fake.h): atomic or legacy mode setting, the TEST_ONLY fallback,
// one flip in flight, connector hotplug through a fake udev source, seat
// switches, lost DRM master, and the restore after each of these paths.
#include "platform/drm_display.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "drm_fake.h"

namespace body::platform {
namespace {

using fake::g_kms;
using Shown = DrmDisplay::Shown;
using Hotplug = DrmDisplay::Hotplug;

// Stands in for the udev monitor: one pending event per push().
class FakeHotplug final : public HotplugSource {
public:
    void push(bool connector_hotplug = true) { pending_.push_back(connector_hotplug); }
    int fd() const override { return -1; }
    bool read_hotplug() override {
        bool any = false;
        for (bool e : pending_) any |= e;
        pending_.clear();
        return any;
    }

private:
    std::vector<bool> pending_;
};

// A display picked on the fake and shown once (framebuffer 10).
std::unique_ptr<DrmDisplay> shown_display(const ModeRequest& request = {}) {
    auto d = std::make_unique<DrmDisplay>(fake::ops(), 3, request);
    EXPECT_TRUE(d->pick());
    auto shown = d->present(10);
    EXPECT_TRUE(shown.ok());
    EXPECT_EQ(shown.ok() ? shown.value() : Shown::Skipped, Shown::ModeSet);
    return d;
}

// The console's framebuffer 7 at 1920x1080 is back on screen.
void expect_console_restored(DrmDisplay& d, const char* how) {
    ASSERT_TRUE(d.restore());
    EXPECT_EQ(g_kms.commits.back(), std::string(how) + "-mode 1920x1080 fb 7");
    EXPECT_EQ(g_kms.screen.fb, 7u);
    EXPECT_TRUE(g_kms.events.empty());
}

TEST(DrmDisplay, AtomicWhenTheDriverHasIt) {
    fake::reset();
    auto d = shown_display();
    EXPECT_STREQ(d->mode_setter(), "atomic");
    // kmscube's order: a TEST_ONLY commit, then the mode set; the mode goes as a blob.
    ASSERT_EQ(g_kms.commits, (std::vector<std::string>{"atomic-test", "atomic-test", "atomic-mode 1920x1080 fb 10"}));
    EXPECT_EQ(g_kms.screen.fb, 10u);
    EXPECT_EQ(g_kms.blobs.size(), 1u);  // the mode on screen; the probe's blob was dropped
    EXPECT_EQ(d->width(), 1920);
    EXPECT_FLOAT_EQ(d->pixels_per_mm(), 1920.0f / 500.0f);
    ASSERT_TRUE(d->present(11));
    EXPECT_EQ(g_kms.commits.back(), "atomic-flip fb 11");
    expect_console_restored(*d, "atomic");
}

TEST(DrmDisplay, LegacyWithoutTheAtomicCap) {
    fake::reset();
    g_kms.atomic = false;
    auto d = shown_display();
    EXPECT_STREQ(d->mode_setter(), "legacy");
    ASSERT_EQ(g_kms.commits, (std::vector<std::string>{"legacy-mode 1920x1080 fb 10"}));
    ASSERT_TRUE(d->present(11));
    EXPECT_EQ(g_kms.commits.back(), "legacy-flip fb 11");
    expect_console_restored(*d, "legacy");
}

TEST(DrmDisplay, ARefusedTestOnlyCommitFallsBackToLegacy) {
    fake::reset();
    g_kms.refuse_test_only = true;
    auto d = shown_display();
    EXPECT_STREQ(d->mode_setter(), "legacy");
    EXPECT_EQ(fake::count("atomic-mode"), 0);
    EXPECT_EQ(g_kms.commits.back(), "legacy-mode 1920x1080 fb 10");
    EXPECT_TRUE(g_kms.blobs.empty());  // the probe's blob did not leak
    ASSERT_TRUE(d->present(11));
    EXPECT_EQ(g_kms.commits.back(), "legacy-flip fb 11");
    expect_console_restored(*d, "legacy");
}

TEST(DrmDisplay, NeverTwoFlipsInFlight) {
    for (bool atomic : {true, false}) {
        fake::reset();
        g_kms.atomic = atomic;
        auto d = shown_display();
        for (uint32_t fb = 11; fb < 61; ++fb) {
            auto shown = d->present(fb);
            ASSERT_TRUE(shown.ok());
            EXPECT_EQ(shown.value(), Shown::Flipped);
            EXPECT_TRUE(g_kms.events.empty()) << "present() returned with its flip in flight";
        }
        EXPECT_EQ(d->flips(), 50);
        EXPECT_EQ(fake::count(atomic ? "atomic-flip" : "legacy-flip"), 50);
        EXPECT_EQ(g_kms.flip_over_pending, 0);
        expect_console_restored(*d, atomic ? "atomic" : "legacy");
    }
}

// A flip whose event is late: present() reports the timeout; the next one
// waits for that event before queueing, and the restore does too.
TEST(DrmDisplay, ALateFlipIsWaitedForBeforeTheNext) {
    fake::reset();
    auto d = shown_display();
    g_kms.hold_events = 1;
    EXPECT_FALSE(d->present(11).ok());
    EXPECT_EQ(g_kms.events.size(), 1u);  // still in flight
    ASSERT_TRUE(d->present(12));
    EXPECT_EQ(g_kms.flip_over_pending, 0);
    EXPECT_EQ(g_kms.commits.back(), "atomic-flip fb 12");
    g_kms.hold_events = 1;
    EXPECT_FALSE(d->present(13).ok());
    expect_console_restored(*d, "atomic");
    EXPECT_EQ(g_kms.flip_over_pending, 0);
}

TEST(DrmDisplay, HotplugToAnotherResolutionRepicksAndSetsTheNewMode) {
    fake::reset();
    auto d = shown_display();
    FakeHotplug udev;
    EXPECT_EQ(d->follow(udev), Hotplug::Unchanged);  // no event: no probe
    // The monitor is swapped for a 1280x800 one.
    g_kms.connectors = {fake::connector(33, true, {fake::mode(1280, 800, 60, true), fake::mode(1024, 768, 60)})};
    udev.push();
    ASSERT_EQ(d->follow(udev), Hotplug::Resized);
    EXPECT_EQ(d->width(), 1280);
    EXPECT_EQ(d->height(), 800);
    auto shown = d->present(20);  // the surface's first buffer at the new size
    ASSERT_TRUE(shown.ok());
    EXPECT_EQ(shown.value(), Shown::ModeSet);
    EXPECT_EQ(g_kms.commits.back(), "atomic-mode 1280x800 fb 20");
    EXPECT_EQ(g_kms.blobs.size(), 1u);  // the old mode's blob went with it
    ASSERT_TRUE(d->present(21));
    EXPECT_EQ(g_kms.commits.back(), "atomic-flip fb 21");
    expect_console_restored(*d, "atomic");
}

// The driver took atomic at start but refuses the mode of the new display.
TEST(DrmDisplay, AnAtomicModeSetRefusedAfterAHotplugFallsBackToLegacy) {
    fake::reset();
    auto d = shown_display();
    g_kms.connectors = {fake::connector(33, true, {fake::mode(1280, 800, 60, true)})};
    g_kms.refuse_test_only = true;
    FakeHotplug udev;
    udev.push();
    ASSERT_EQ(d->follow(udev), Hotplug::Resized);
    auto shown = d->present(20);
    ASSERT_TRUE(shown.ok());
    EXPECT_EQ(shown.value(), Shown::ModeSet);
    EXPECT_STREQ(d->mode_setter(), "legacy");
    EXPECT_EQ(g_kms.commits.back(), "legacy-mode 1280x800 fb 20");
    ASSERT_TRUE(d->present(21));
    EXPECT_EQ(g_kms.commits.back(), "legacy-flip fb 21");
    EXPECT_TRUE(g_kms.blobs.empty());       // the atomic setter took its mode blob along
    expect_console_restored(*d, "atomic");  // the keeper still restores atomically: the driver takes that
}

TEST(DrmDisplay, HotplugWithTheSameModesChangesNothing) {
    fake::reset();
    auto d = shown_display();
    FakeHotplug udev;
    udev.push();
    EXPECT_EQ(d->follow(udev), Hotplug::Unchanged);
    ASSERT_TRUE(d->present(11));
    EXPECT_EQ(g_kms.commits.back(), "atomic-flip fb 11");
}

TEST(DrmDisplay, AReplugWithOtherModesAtTheSameSizeSetsTheModeAgain) {
    fake::reset();
    auto d = shown_display();
    g_kms.connectors = {fake::connector(33, true, {fake::mode(1920, 1080, 50, true)})};
    FakeHotplug udev;
    udev.push();
    EXPECT_EQ(d->follow(udev), Hotplug::Changed);
    auto shown = d->present(11);
    ASSERT_TRUE(shown.ok());
    EXPECT_EQ(shown.value(), Shown::ModeSet);
    EXPECT_EQ(g_kms.screen.mode.vrefresh, 50u);
    expect_console_restored(*d, "atomic");
}

TEST(DrmDisplay, WithNoDisplayNothingIsCommittedUntilOneReturns) {
    fake::reset();
    auto d = shown_display();
    FakeHotplug udev;
    g_kms.connectors[0].desc.connected = false;
    udev.push();
    ASSERT_EQ(d->follow(udev), Hotplug::NoDisplay);
    const size_t commits = g_kms.commits.size();
    for (uint32_t fb = 11; fb < 15; ++fb) {
        auto shown = d->present(fb);
        ASSERT_TRUE(shown.ok());
        EXPECT_EQ(shown.value(), Shown::Skipped);
    }
    EXPECT_EQ(g_kms.commits.size(), commits);
    // Another connector comes up.
    g_kms.connectors.push_back(fake::connector(34, true, {fake::mode(1920, 1080, 60, true)}));
    udev.push();
    ASSERT_EQ(d->follow(udev), Hotplug::Resized);
    EXPECT_EQ(d->target().connector, 34u);
    auto shown = d->present(20);
    ASSERT_TRUE(shown.ok());
    EXPECT_EQ(shown.value(), Shown::ModeSet);
    EXPECT_EQ(g_kms.commits.back(), "atomic-mode 1920x1080 fb 20");
}

TEST(DrmDisplay, AConfiguredModeMissingAfterAHotplugFallsBackToThePreferredOne) {
    fake::reset();
    auto d = shown_display(ModeRequest{1280, 720, 0});
    EXPECT_EQ(d->width(), 1280);
    g_kms.connectors = {fake::connector(33, true, {fake::mode(1024, 600, 60, true)})};
    FakeHotplug udev;
    udev.push();
    ASSERT_EQ(d->follow(udev), Hotplug::Resized);
    EXPECT_EQ(d->width(), 1024);
}

TEST(DrmDisplay, SeatSwitchedAwayCommitsNothingAndSetsTheModeWhenBack) {
    for (bool atomic : {true, false}) {
        fake::reset();
        g_kms.atomic = atomic;
        auto d = shown_display();
        ASSERT_TRUE(d->present(11));
        d->set_active(false);  // libseat's disable-seat callback
        const size_t commits = g_kms.commits.size();
        for (uint32_t fb = 12; fb < 16; ++fb) {
            auto shown = d->present(fb);
            ASSERT_TRUE(shown.ok());
            EXPECT_EQ(shown.value(), Shown::Skipped);
        }
        EXPECT_EQ(g_kms.commits.size(), commits);
        // The other VT's session changed the screen meanwhile.
        g_kms.screen = fake::Screen{99, true, fake::mode(1024, 768, 60)};
        d->set_active(true);
        auto shown = d->present(16);
        ASSERT_TRUE(shown.ok());
        EXPECT_EQ(shown.value(), Shown::ModeSet);
        EXPECT_EQ(g_kms.commits.back(), std::string(atomic ? "atomic" : "legacy") + "-mode 1920x1080 fb 16");
        ASSERT_TRUE(d->present(17));
        EXPECT_EQ(g_kms.commits.back(), std::string(atomic ? "atomic" : "legacy") + "-flip fb 17");
        expect_console_restored(*d, atomic ? "atomic" : "legacy");
    }
}

// Opened directly (no seat manager): another process took DRM master.
TEST(DrmDisplay, LostMasterWaitsForItThenSetsTheMode) {
    fake::reset();
    auto d = shown_display();
    g_kms.master = false;
    auto shown = d->present(11);
    ASSERT_TRUE(shown.ok());
    EXPECT_EQ(shown.value(), Shown::Skipped);
    ASSERT_TRUE(d->present(12).ok());
    EXPECT_EQ(g_kms.set_master_calls, 1);
    g_kms.master = true;
    shown = d->present(13);
    ASSERT_TRUE(shown.ok());
    EXPECT_EQ(shown.value(), Shown::ModeSet);
    EXPECT_EQ(g_kms.commits.back(), "atomic-mode 1920x1080 fb 13");
    expect_console_restored(*d, "atomic");
}

TEST(DrmDisplay, TheDestructorRestoresAndAConsoleThatWasOffGoesOffAgain) {
    fake::reset();
    g_kms.screen = fake::Screen{};
    { auto d = shown_display(); }
    EXPECT_EQ(g_kms.commits.back(), "atomic-off");
    EXPECT_FALSE(g_kms.screen.on);
    EXPECT_TRUE(g_kms.blobs.empty());
}

TEST(DrmDisplay, ARefusedAtomicRestoreFallsBackToLegacy) {
    fake::reset();
    g_kms.refuse_atomic_restore = true;
    auto d = shown_display();
    expect_console_restored(*d, "legacy");
}

// The crash handler's restore after an atomic mode set: legacy (one ioctl, no
// allocation in a signal handler), and only once.
TEST(DrmDisplay, TheCrashRestoreIsLegacyEvenAfterAtomic) {
    fake::reset();
    auto d = shown_display();
    ASSERT_TRUE(d->present(11));
    d->keeper()->restore_after_crash();
    EXPECT_EQ(g_kms.commits.back(), "legacy-mode 1920x1080 fb 7");
    const size_t commits = g_kms.commits.size();
    ASSERT_TRUE(d->restore());
    EXPECT_EQ(g_kms.commits.size(), commits);
}

TEST(DrmDisplay, NothingIsCommittedBeforeTheFirstPresentNorRestored) {
    fake::reset();
    {
        DrmDisplay d(fake::ops(), 3, {});
        ASSERT_TRUE(d.pick());
    }
    EXPECT_TRUE(g_kms.commits.empty());
    EXPECT_EQ(g_kms.screen.fb, 7u);
}

TEST(DrmDisplay, PickFailsWithNoDisplayAtStart) {
    fake::reset();
    g_kms.connectors[0].desc.connected = false;
    DrmDisplay d(fake::ops(), 3, {});
    auto s = d.pick();
    ASSERT_FALSE(s);
    EXPECT_NE(s.error().message.find("no connected connector"), std::string::npos);
}

TEST(DrmHotplug, OnlyChangeEventsWithHotplugOnTheCardCount) {
    const std::string card = "/dev/dri/card0";
    EXPECT_TRUE(is_connector_hotplug("change", "1", "/dev/dri/card0", card));
    EXPECT_TRUE(is_connector_hotplug("change", "1", nullptr, card));
    EXPECT_FALSE(is_connector_hotplug("change", "1", "/dev/dri/card1", card));
    EXPECT_FALSE(is_connector_hotplug("change", nullptr, "/dev/dri/card0", card));
    EXPECT_FALSE(is_connector_hotplug("change", "0", "/dev/dri/card0", card));
    EXPECT_FALSE(is_connector_hotplug("add", "1", "/dev/dri/card0", card));
    EXPECT_FALSE(is_connector_hotplug(nullptr, "1", "/dev/dri/card0", card));
}

}  // namespace
}  // namespace body::platform
