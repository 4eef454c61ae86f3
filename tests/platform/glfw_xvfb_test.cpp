// The glfw backend on a real X server (run under xvfb-run by ctest): it starts
// without touch devices and says so in one line, and a Shift+click the X server
// delivers arrives as a MouseDown carrying the Shift modifier.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>

#include "platform/platform.h"

// Last: Xlib defines macros (Status, None, Bool) that must not reach the headers above.
// clang-format off
#include <X11/Xlib.h>
// clang-format on

namespace body::platform {
namespace {

bool have_display() {
    const char* d = std::getenv("DISPLAY");
    return d && *d;
}

// A small window, reading touchscreens from `touch_directory`; stderr captured in `log`.
std::unique_ptr<Surface> open_window(const std::string& touch_directory, std::string& log) {
    SurfaceOptions o;
    o.backend = Backend::Glfw;
    o.fullscreen = false;
    o.width = 320;
    o.height = 240;
    o.title = "bodyview-xvfb-test";
    o.touch_directory = touch_directory;
    testing::internal::CaptureStderr();
    auto s = create_surface(o);
    log = testing::internal::GetCapturedStderr();
    if (!s) {
        ADD_FAILURE() << s.error().message;
        return nullptr;
    }
    return std::move(s).value();
}

size_t lines(const std::string& text) { return static_cast<size_t>(std::count(text.begin(), text.end(), '\n')); }

TEST(GlfwXvfb, StartsWithoutTouchDevicesAndSaysSoOnce) {
    if (!have_display()) GTEST_SKIP() << "no DISPLAY (ctest runs this under xvfb-run)";
    const auto empty = std::filesystem::temp_directory_path() / ("body-no-touch-" + std::to_string(::getpid()));
    std::filesystem::create_directories(empty);
    std::string log;
    {
        auto surface = open_window(empty.string(), log);
        ASSERT_TRUE(surface);
        EXPECT_EQ(surface->backend(), Backend::Glfw);
        EXPECT_EQ(lines(log), 1u) << log;
        EXPECT_NE(log.find("no readable touchscreen in " + empty.string()), std::string::npos) << log;
        EXPECT_NE(log.find("mouse only"), std::string::npos) << log;
        std::vector<InputEvent> events;
        EXPECT_TRUE(surface->poll_events(events));
    }
    std::filesystem::remove_all(empty);
    // A directory that cannot be watched: also one line, and the window still opens.
    auto surface = open_window("/nonexistent/input", log);
    ASSERT_TRUE(surface);
    EXPECT_EQ(lines(log), 1u) << log;
    EXPECT_NE(log.find("no touch input"), std::string::npos) << log;
    EXPECT_NE(log.find("/nonexistent/input"), std::string::npos) << log;
}

// The X window whose name is `title`, searched from `root` down.
Window find_window(Display* d, Window root, const std::string& title) {
    char* name = nullptr;
    if (XFetchName(d, root, &name) && name) {
        const bool match = title == name;
        XFree(name);
        if (match) return root;
    }
    Window parent = 0, ignored = 0, *children = nullptr;
    unsigned count = 0;
    if (!XQueryTree(d, root, &ignored, &parent, &children, &count)) return 0;
    Window found = 0;
    for (unsigned i = 0; i < count && !found; ++i) found = find_window(d, children[i], title);
    if (children) XFree(children);
    return found;
}

void send_button(Display* d, Window w, unsigned button, unsigned state) {
    XEvent e{};
    e.xbutton.type = ButtonPress;
    e.xbutton.display = d;
    e.xbutton.window = w;
    e.xbutton.root = DefaultRootWindow(d);
    e.xbutton.x = 40;
    e.xbutton.y = 30;
    e.xbutton.button = button;
    e.xbutton.state = state;
    e.xbutton.same_screen = True;
    XSendEvent(d, w, True, ButtonPressMask, &e);
    XFlush(d);
}

// Polls until a MouseDown arrives (the X server delivers asynchronously).
std::optional<InputEvent> next_mouse_down(Surface& s) {
    for (int i = 0; i < 200; ++i) {
        std::vector<InputEvent> events;
        s.poll_events(events);
        for (const InputEvent& e : events)
            if (e.type == InputEvent::Type::MouseDown) return e;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return std::nullopt;
}

TEST(GlfwXvfb, MouseButtonsCarryTheModifiersHeld) {
    if (!have_display()) GTEST_SKIP() << "no DISPLAY (ctest runs this under xvfb-run)";
    std::string log;
    auto surface = open_window("/nonexistent/input", log);
    ASSERT_TRUE(surface);
    Display* d = XOpenDisplay(nullptr);
    ASSERT_NE(d, nullptr);
    Window w = 0;
    for (int i = 0; i < 100 && !w; ++i) {
        std::vector<InputEvent> events;
        surface->poll_events(events);
        w = find_window(d, DefaultRootWindow(d), "bodyview-xvfb-test");
        if (!w) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_NE(w, 0u) << "the glfw window is not on the X server";

    send_button(d, w, Button1, ShiftMask);
    auto shift_left = next_mouse_down(*surface);
    ASSERT_TRUE(shift_left);
    EXPECT_EQ(shift_left->id, 0);
    EXPECT_EQ(shift_left->modifiers, static_cast<uint32_t>(kModShift));

    send_button(d, w, Button2, ShiftMask | ControlMask);
    auto shift_middle = next_mouse_down(*surface);
    ASSERT_TRUE(shift_middle);
    EXPECT_EQ(shift_middle->id, 2);
    EXPECT_EQ(shift_middle->modifiers, kModShift | kModCtrl);

    send_button(d, w, Button3, 0);
    auto plain_right = next_mouse_down(*surface);
    ASSERT_TRUE(plain_right);
    EXPECT_EQ(plain_right->id, 1);
    EXPECT_EQ(plain_right->modifiers, 0u);
    XCloseDisplay(d);
}

}  // namespace
}  // namespace body::platform
