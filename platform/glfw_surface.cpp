// GLFW backend: a desktop window (or fullscreen on the primary monitor) with an
// OpenGL ES 3.0 context created through EGL (GLFW_EGL_CONTEXT_API), so the same
// GLES code runs on desktops, under Xvfb and on boards. Mouse events map to
// MouseDown/Move/Up/Scroll, Escape, printable and editing keys to Key, typed
// characters to Text, each with the
// Shift/Ctrl/Alt modifiers held. GLFW 3.3 has no touch API: touchscreens are
// read through the evdev layer (platform/evdev_touch.h, hot-plugged) when
// /dev/input is readable and mapped into the window (platform/evdev_window.h);
// otherwise one line is logged and input is mouse only.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <csignal>
#include <cstdio>

#include "platform/evdev_touch.h"
#include "platform/evdev_window.h"
#include "platform/platform.h"

namespace body::platform {
namespace {

volatile std::sig_atomic_t g_glfw_quit = 0;
void on_glfw_signal(int) { g_glfw_quit = 1; }

uint32_t modifiers_from_glfw(int mods) {
    return ((mods & GLFW_MOD_SHIFT) ? kModShift : 0u) | ((mods & GLFW_MOD_CONTROL) ? kModCtrl : 0u) |
           ((mods & GLFW_MOD_ALT) ? kModAlt : 0u);
}

// The modifiers held now (cursor and scroll callbacks carry none).
uint32_t modifiers_held(GLFWwindow* win) {
    auto down = [win](int a, int b) { return glfwGetKey(win, a) == GLFW_PRESS || glfwGetKey(win, b) == GLFW_PRESS; };
    return (down(GLFW_KEY_LEFT_SHIFT, GLFW_KEY_RIGHT_SHIFT) ? kModShift : 0u) |
           (down(GLFW_KEY_LEFT_CONTROL, GLFW_KEY_RIGHT_CONTROL) ? kModCtrl : 0u) |
           (down(GLFW_KEY_LEFT_ALT, GLFW_KEY_RIGHT_ALT) ? kModAlt : 0u);
}

// GLFW's editing keys as platform key codes (platform.h), -1 for the rest.
int editing_key(int key) {
    switch (key) {
        case GLFW_KEY_BACKSPACE: return kKeyBackspace;
        case GLFW_KEY_DELETE: return kKeyDelete;
        case GLFW_KEY_LEFT: return kKeyLeft;
        case GLFW_KEY_RIGHT: return kKeyRight;
        case GLFW_KEY_UP: return kKeyUp;
        case GLFW_KEY_DOWN: return kKeyDown;
        case GLFW_KEY_HOME: return kKeyHome;
        case GLFW_KEY_END: return kKeyEnd;
        case GLFW_KEY_ENTER:
        case GLFW_KEY_KP_ENTER: return kKeyEnter;
        case GLFW_KEY_TAB: return kKeyTab;
        case GLFW_KEY_F1: return kKeyF1;
        default: return -1;
    }
}

// The monitor a window is on: its own when fullscreen, else the one holding the
// window's centre, else the primary.
GLFWmonitor* monitor_of(GLFWwindow* win) {
    if (GLFWmonitor* m = glfwGetWindowMonitor(win)) return m;
    int x = 0, y = 0, w = 0, h = 0, count = 0;
    glfwGetWindowPos(win, &x, &y);
    glfwGetWindowSize(win, &w, &h);
    GLFWmonitor** monitors = glfwGetMonitors(&count);
    for (int i = 0; i < count; ++i) {
        int mx = 0, my = 0;
        glfwGetMonitorPos(monitors[i], &mx, &my);
        const GLFWvidmode* mode = glfwGetVideoMode(monitors[i]);
        if (!mode) continue;
        const int cx = x + w / 2, cy = y + h / 2;
        if (cx >= mx && cy >= my && cx < mx + mode->width && cy < my + mode->height) return monitors[i];
    }
    return glfwGetPrimaryMonitor();
}

class GlfwSurface final : public Surface {
public:
    ~GlfwSurface() override {
        if (window_) glfwDestroyWindow(window_);
        glfwTerminate();
    }

    Status init(const SurfaceOptions& options) {
        if (!glfwInit()) return runtime_error("glfw: cannot initialise (no display server reachable?)");
        glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
        glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
        glfwWindowHint(GLFW_DEPTH_BITS, 24);
        GLFWmonitor* monitor = options.fullscreen ? glfwGetPrimaryMonitor() : nullptr;
        int w = options.width, h = options.height;
        if (monitor && (w <= 0 || h <= 0)) {
            const GLFWvidmode* mode = glfwGetVideoMode(monitor);
            w = mode->width;
            h = mode->height;
        }
        if (w <= 0 || h <= 0) {
            w = 1280;
            h = 800;
        }
        window_ = glfwCreateWindow(w, h, options.title.c_str(), monitor, nullptr);
        if (!window_) {
            const char* why = nullptr;
            glfwGetError(&why);
            return runtime_error(std::string("glfw: cannot create a GLES 3.0 window (") + (why ? why : "?") + ")");
        }
        glfwSetWindowUserPointer(window_, this);
        glfwMakeContextCurrent(window_);
        glfwSwapInterval(1);
        glfwSetMouseButtonCallback(window_, [](GLFWwindow* win, int button, int action, int mods) {
            auto* self = static_cast<GlfwSurface*>(glfwGetWindowUserPointer(win));
            double x = 0, y = 0;
            glfwGetCursorPos(win, &x, &y);
            InputEvent e;
            e.type = action == GLFW_PRESS ? InputEvent::Type::MouseDown : InputEvent::Type::MouseUp;
            e.id = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : button == GLFW_MOUSE_BUTTON_RIGHT ? 1 : 2;
            e.modifiers = modifiers_from_glfw(mods);
            self->push(e, x, y);
        });
        glfwSetCursorPosCallback(window_, [](GLFWwindow* win, double x, double y) {
            InputEvent e;
            e.type = InputEvent::Type::MouseMove;
            e.modifiers = modifiers_held(win);
            static_cast<GlfwSurface*>(glfwGetWindowUserPointer(win))->push(e, x, y);
        });
        glfwSetScrollCallback(window_, [](GLFWwindow* win, double dx, double dy) {
            InputEvent e;
            e.type = InputEvent::Type::Scroll;
            e.dx = static_cast<float>(dx);
            e.dy = static_cast<float>(dy);
            e.modifiers = modifiers_held(win);
            double x = 0, y = 0;
            glfwGetCursorPos(win, &x, &y);
            static_cast<GlfwSurface*>(glfwGetWindowUserPointer(win))->push(e, x, y);
        });
        glfwSetKeyCallback(window_, [](GLFWwindow* win, int key, int, int action, int mods) {
            if (action == GLFW_REPEAT) return;
            InputEvent e;
            e.type = InputEvent::Type::Key;
            e.key = key == GLFW_KEY_ESCAPE ? kKeyEscape : (key >= 32 && key < 127 ? key : editing_key(key));
            e.pressed = action == GLFW_PRESS;
            e.modifiers = modifiers_from_glfw(mods);
            if (e.key >= 0) static_cast<GlfwSurface*>(glfwGetWindowUserPointer(win))->push(e, 0, 0);
        });
        glfwSetCharCallback(window_, [](GLFWwindow* win, unsigned int codepoint) {
            InputEvent e;
            e.type = InputEvent::Type::Text;
            e.key = static_cast<int>(codepoint);
            e.pressed = true;
            e.modifiers = modifiers_held(win);
            static_cast<GlfwSurface*>(glfwGetWindowUserPointer(win))->push(e, 0, 0);
        });
        std::signal(SIGINT, on_glfw_signal);
        std::signal(SIGTERM, on_glfw_signal);
        open_touch(options);
        return ok_status();
    }

    Backend backend() const override { return Backend::Glfw; }
    void make_current() override { glfwMakeContextCurrent(window_); }
    Status present() override {
        glfwSwapBuffers(window_);
        return ok_status();
    }
    float pixels_per_mm() const override {
        GLFWmonitor* m = monitor_of(window_);
        int mm_w = 0, mm_h = 0, win_w = 0, win_h = 0;
        glfwGetMonitorPhysicalSize(m, &mm_w, &mm_h);
        const GLFWvidmode* mode = glfwGetVideoMode(m);
        glfwGetWindowSize(window_, &win_w, &win_h);
        if (mm_w <= 0 || !mode || mode->width <= 0 || win_w <= 0) return 0.0f;
        // Monitor pixels per mm, times framebuffer pixels per window unit (high-DPI).
        return static_cast<float>(mode->width) / static_cast<float>(mm_w) * static_cast<float>(width()) /
               static_cast<float>(win_w);
    }
    int width() const override {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        return w;
    }
    int height() const override {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        return h;
    }
    unsigned framebuffer() const override { return 0; }
    double time() const override { return glfwGetTime(); }
    void cancel_quit() override { glfwSetWindowShouldClose(window_, GLFW_FALSE); }
    bool poll_events(std::vector<InputEvent>& out) override {
        glfwPollEvents();
        const size_t first = out.size();
        out.insert(out.end(), pending_.begin(), pending_.end());
        pending_.clear();
        if (touch_) {
            touch_->poll(time(), out);
            if (out.size() > first) {  // where the window is now, only when there is something to map or filter
                touch_filter_.set_placement(placement());
                touch_filter_.apply(out, first);
            }
        }
        if (glfwWindowShouldClose(window_) || g_glfw_quit) {
            InputEvent q;
            q.type = InputEvent::Type::Quit;
            q.time = time();
            out.push_back(q);
            return false;
        }
        return true;
    }

private:
    // Touchscreens through evdev, mapped to the monitor the window is on. Absent
    // or unreadable devices are not an error: one line, then mouse only.
    void open_touch(const SurfaceOptions& options) {
        const GLFWvidmode* mode = glfwGetVideoMode(monitor_of(window_));
        EvdevOptions eo;
        eo.directory = options.touch_directory;
        eo.width = mode ? mode->width : width();
        eo.height = mode ? mode->height : height();
        eo.rotation = options.touch_rotation;
        eo.calibration = options.touch_calibration;
        auto input = EvdevInput::open(eo);
        if (!input) {
            std::fprintf(stderr, "bodyview: glfw: no touch input (%s); mouse only\n", input.error().message.c_str());
            return;
        }
        touch_ = std::move(input).value();
        if (touch_->device_count() == 0) {
            std::fprintf(stderr, "bodyview: glfw: no readable touchscreen in %s; mouse only until one is plugged in\n",
                         eo.directory.c_str());
        }
    }

    WindowPlacement placement() const {
        WindowPlacement p;
        int mx = 0, my = 0;
        glfwGetMonitorPos(monitor_of(window_), &mx, &my);
        glfwGetWindowPos(window_, &p.x, &p.y);
        p.x -= mx;
        p.y -= my;
        glfwGetWindowSize(window_, &p.width, &p.height);
        glfwGetFramebufferSize(window_, &p.framebuffer_width, &p.framebuffer_height);
        return p;
    }

    void push(InputEvent e, double x, double y) {
        // Window coordinates to framebuffer pixels (they differ on HiDPI screens).
        int ww = 1, wh = 1;
        glfwGetWindowSize(window_, &ww, &wh);
        e.x = static_cast<float>(x * width() / (ww > 0 ? ww : 1));
        e.y = static_cast<float>(y * height() / (wh > 0 ? wh : 1));
        e.time = time();
        pending_.push_back(e);
    }

    GLFWwindow* window_ = nullptr;
    std::vector<InputEvent> pending_;
    std::unique_ptr<EvdevInput> touch_;
    WindowTouchFilter touch_filter_;
};

}  // namespace

Result<std::unique_ptr<Surface>> create_glfw_surface(const SurfaceOptions& options) {
    return init_surface<GlfwSurface>(options);
}

}  // namespace body::platform
