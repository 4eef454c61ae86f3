// evdev multitouch protocol B fed fabricated kernel events: slots, tracking ids,
// SYN_DROPPED resync, device removal, and the rotation mapping.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "platform/evdev_touch.h"
#include "tests/platform/input_events.h"

namespace body::platform {
namespace {

input_event ev(uint16_t type, uint16_t code, int32_t value) {
    input_event e{};
    e.type = type;
    e.code = code;
    e.value = value;
    return e;
}
input_event syn() { return ev(EV_SYN, SYN_REPORT, 0); }

using T = InputEvent::Type;
using test::expect_events;

struct Fixture {
    MtProtocolB mt{10, 0};
    std::vector<InputEvent> out;
    Fixture() {
        TouchMapping m;
        m.min_x = m.min_y = 0;
        m.max_x = 1000;
        m.max_y = 1000;
        m.width = 1001;
        m.height = 1001;  // 1 raw unit = 1 pixel
        mt.set_mapping(m);
    }
    void feed(std::initializer_list<input_event> events) {
        for (const input_event& e : events) mt.feed(e, 1.0, out);
    }
};

TEST(MtProtocolB, TwoFingersDownMoveUp) {
    Fixture f;
    f.feed({ev(EV_ABS, ABS_MT_SLOT, 0), ev(EV_ABS, ABS_MT_TRACKING_ID, 45), ev(EV_ABS, ABS_MT_POSITION_X, 100),
            ev(EV_ABS, ABS_MT_POSITION_Y, 200), ev(EV_ABS, ABS_MT_SLOT, 1), ev(EV_ABS, ABS_MT_TRACKING_ID, 46),
            ev(EV_ABS, ABS_MT_POSITION_X, 300), ev(EV_ABS, ABS_MT_POSITION_Y, 400)});
    EXPECT_TRUE(f.out.empty());  // nothing before SYN_REPORT
    f.feed({syn()});
    expect_events(f.out, {{T::TouchDown, 45, 100.0f, 200.0f}, {T::TouchDown, 46, 300.0f, 400.0f}});
    f.out.clear();
    // Slot 1 is still selected: only X of slot 1 changes; then slot 0 lifts.
    f.feed({ev(EV_ABS, ABS_MT_POSITION_X, 310), syn()});
    expect_events(f.out, {{T::TouchMove, 46, 310.0f, 400.0f}});
    f.out.clear();
    f.feed({ev(EV_ABS, ABS_MT_SLOT, 0), ev(EV_ABS, ABS_MT_TRACKING_ID, -1), syn()});
    expect_events(f.out, {{T::TouchUp, 45}});
    EXPECT_EQ(f.mt.active_contacts(), 1);
}

TEST(MtProtocolB, ANewContactInAReusedSlotWithinOneFrameIsUpThenDown) {
    Fixture f;
    f.feed(
        {ev(EV_ABS, ABS_MT_TRACKING_ID, 7), ev(EV_ABS, ABS_MT_POSITION_X, 1), ev(EV_ABS, ABS_MT_POSITION_Y, 1), syn()});
    f.out.clear();
    f.feed({ev(EV_ABS, ABS_MT_TRACKING_ID, 8), ev(EV_ABS, ABS_MT_POSITION_X, 500), syn()});
    expect_events(f.out, {{T::TouchUp, 7}, {T::TouchDown, 8, 500.0f}});
}

TEST(MtProtocolB, SynDroppedIgnoresTheRestOfTheFrameAndResyncsFromTheDeviceState) {
    Fixture f;
    f.feed({ev(EV_ABS, ABS_MT_SLOT, 0), ev(EV_ABS, ABS_MT_TRACKING_ID, 1), ev(EV_ABS, ABS_MT_POSITION_X, 10),
            ev(EV_ABS, ABS_MT_POSITION_Y, 10), ev(EV_ABS, ABS_MT_SLOT, 1), ev(EV_ABS, ABS_MT_TRACKING_ID, 2),
            ev(EV_ABS, ABS_MT_POSITION_X, 20), ev(EV_ABS, ABS_MT_POSITION_Y, 20), syn()});
    ASSERT_EQ(f.out.size(), 2u);
    f.out.clear();
    // Overflow: a half-delivered frame, the drop, the rest of a frame, its SYN_REPORT.
    f.feed({ev(EV_ABS, ABS_MT_SLOT, 0), ev(EV_ABS, ABS_MT_POSITION_X, 999), ev(EV_SYN, SYN_DROPPED, 0),
            ev(EV_ABS, ABS_MT_POSITION_X, 555), ev(EV_ABS, ABS_MT_TRACKING_ID, -1), syn()});
    EXPECT_TRUE(f.out.empty());
    EXPECT_TRUE(f.mt.needs_resync());
    // While dropped nothing is reported against the stale state.
    f.feed({ev(EV_ABS, ABS_MT_POSITION_X, 30), syn()});
    EXPECT_TRUE(f.out.empty());
    // The device now says: slot 0 lifted, slot 1 moved, slot 2 is a new finger.
    std::vector<MtSlot> now(10);
    now[1] = MtSlot{2, 25, 20};
    now[2] = MtSlot{3, 70, 80};
    f.mt.resync(now, 2.0, f.out);
    expect_events(f.out, {{T::TouchUp, 1}, {T::TouchMove, 2, 25.0f}, {T::TouchDown, 3, 70.0f, 80.0f}});
    EXPECT_FALSE(f.mt.needs_resync());
    f.out.clear();
    // Back to normal: the next frame is relative to the resynced state.
    f.feed({ev(EV_ABS, ABS_MT_SLOT, 2), ev(EV_ABS, ABS_MT_POSITION_Y, 90), syn()});
    expect_events(f.out, {{T::TouchMove, 3, 70.0f, 90.0f}});
}

TEST(MtProtocolB, RemovedDeviceLiftsEveryFingerAndIdsDifferPerDevice) {
    MtProtocolB second(4, 1);
    std::vector<InputEvent> out;
    for (const input_event& e : {ev(EV_ABS, ABS_MT_TRACKING_ID, 5), ev(EV_ABS, ABS_MT_SLOT, 3),
                                 ev(EV_ABS, ABS_MT_TRACKING_ID, 6), ev(EV_ABS, ABS_MT_SLOT, 9),  // out of range
                                 ev(EV_ABS, ABS_MT_TRACKING_ID, 7), syn()}) {
        second.feed(e, 0.0, out);
    }
    expect_events(out, {{T::TouchDown, 65536 + 5}, {T::TouchDown, 65536 + 6}});
    out.clear();
    second.release_all(1.0, out);
    expect_events(out, {{T::TouchUp, 65536 + 5}, {T::TouchUp, 65536 + 6}});
    EXPECT_EQ(second.active_contacts(), 0);
}

TEST(TouchMapping, RotationsMapThePanelCornersToTheScreen) {
    TouchMapping m;
    m.min_x = 100;
    m.max_x = 4100;
    m.min_y = 0;
    m.max_y = 2000;
    m.width = 1281;
    m.height = 801;
    float x, y;
    // Panel top-left (min, min) and a point at (1/4, 1/2).
    struct Case {
        int rotation;
        float tl_x, tl_y, p_x, p_y;
    };
    for (const Case& c : {Case{0, 0, 0, 320, 400}, Case{90, 1280, 0, 640, 200}, Case{180, 1280, 800, 960, 400},
                          Case{270, 0, 800, 640, 600}}) {
        m.rotation = c.rotation;
        map_touch(m, 100, 0, x, y);
        EXPECT_FLOAT_EQ(x, c.tl_x) << c.rotation;
        EXPECT_FLOAT_EQ(y, c.tl_y) << c.rotation;
        map_touch(m, 1100, 1000, x, y);
        EXPECT_FLOAT_EQ(x, c.p_x) << c.rotation;
        EXPECT_FLOAT_EQ(y, c.p_y) << c.rotation;
    }
    m.rotation = 0;
    map_touch(m, -50, 99999, x, y);  // out of range clamps to the screen
    EXPECT_FLOAT_EQ(x, 0.0f);
    EXPECT_FLOAT_EQ(y, 800.0f);
    EXPECT_TRUE(parse_rotation("270"));
    EXPECT_FALSE(parse_rotation("45"));
}

// A panel whose touches land 10 % right and mirrored vertically: the matrix
// (from a calibration tool, libinput's convention) undoes it before the rotation.
TEST(TouchMapping, CalibrationMatrixIsAppliedBeforeTheRotation) {
    TouchMapping m;
    m.max_x = m.max_y = 1000;
    m.width = m.height = 1001;
    m.calibration = {1, 0, -0.1f, 0, -1, 1};
    float x, y;
    map_touch(m, 600, 250, x, y);
    EXPECT_NEAR(x, 500.0f, 1e-3f);
    EXPECT_NEAR(y, 750.0f, 1e-3f);
    m.rotation = 90;  // then turned: (u, v) -> (1 - v, u)
    map_touch(m, 600, 250, x, y);
    EXPECT_NEAR(x, 250.0f, 1e-3f);
    EXPECT_NEAR(y, 500.0f, 1e-3f);
    auto c = parse_calibration("1, 0, -0.1 0 -1 1");
    ASSERT_TRUE(c);
    EXPECT_FLOAT_EQ((*c)[2], -0.1f);
    EXPECT_FALSE(parse_calibration("1 0 0 0 1"));    // five numbers
    EXPECT_FALSE(parse_calibration("1 2 0 2 4 0"));  // singular
    EXPECT_FALSE(parse_calibration("1 0 0 0 1 0 7"));
}

TEST(EvdevInput, OpensADirectoryWithoutTouchscreens) {
    char dir[] = "/tmp/body_evdev_XXXXXX";
    ASSERT_NE(::mkdtemp(dir), nullptr);
    auto input = EvdevInput::open(EvdevOptions{dir, 800, 480, 0});
    ASSERT_TRUE(input) << input.error().message;
    std::vector<InputEvent> out;
    (*input)->poll(0.0, out);
    EXPECT_EQ((*input)->device_count(), 0u);
    EXPECT_TRUE(out.empty());
    // A node appearing later goes through the inotify path; one that is not an
    // evdev touch screen (here a plain file) is ignored, and so is its removal.
    const std::string node = std::string(dir) + "/event7";
    std::FILE* f = std::fopen(node.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fclose(f);
    (*input)->poll(1.0, out);
    EXPECT_EQ((*input)->device_count(), 0u);
    ::unlink(node.c_str());
    (*input)->poll(2.0, out);
    EXPECT_TRUE(out.empty());
    ::rmdir(dir);
    EXPECT_FALSE(EvdevInput::open(EvdevOptions{"/nonexistent/input", 800, 480, 0}));
}

// Hotplug through the same path the backends use, with a fake opener in place of
// the seat (no uinput here): a node created while running is opened at the next
// poll (the next frame, so well within the 1 s goal), one whose permissions udev
// fixes later (IN_ATTRIB) is tried again, and every descriptor handed out is
// given back to the opener's closer.
TEST(EvdevInput, AddedNodesAreOpenedAtTheNextPollThroughTheOpener) {
    char dir[] = "/tmp/body_evdev_hotplug_XXXXXX";
    ASSERT_NE(::mkdtemp(dir), nullptr);
    std::vector<std::string> opened;
    int open_fds = 0;
    EvdevOptions o{dir, 800, 480, 0};
    o.open_device = [&](const std::string& path) {
        opened.push_back(path);
        const int fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);  // not an evdev device: ignored after opening
        open_fds += fd >= 0;
        return fd;
    };
    o.close_device = [&](int fd) {
        --open_fds;
        ::close(fd);
    };
    auto input = EvdevInput::open(o);
    ASSERT_TRUE(input) << input.error().message;
    std::vector<InputEvent> out;
    (*input)->poll(0.0, out);
    EXPECT_TRUE(opened.empty());
    const std::string node = std::string(dir) + "/event4";
    std::FILE* f = std::fopen(node.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fclose(f);
    (*input)->poll(1.0 / 60.0, out);  // the next frame
    ASSERT_EQ(opened.size(), 1u);
    EXPECT_EQ(opened[0], node);
    ::chmod(node.c_str(), 0660);  // udev setting the group later: tried again
    (*input)->poll(2.0 / 60.0, out);
    EXPECT_EQ(opened.size(), 2u);
    std::fclose(std::fopen((std::string(dir) + "/js0").c_str(), "w"));  // not an event node
    (*input)->poll(3.0 / 60.0, out);
    EXPECT_EQ(opened.size(), 2u);
    EXPECT_EQ(open_fds, 0);
    EXPECT_TRUE(out.empty());
    input->reset();
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace body::platform
