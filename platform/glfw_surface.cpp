// GLFW backend: a desktop window (or fullscreen on the primary monitor) with an
// OpenGL ES 3.0 context created through EGL (GLFW_EGL_CONTEXT_API), so the same
// GLES code runs on desktops, under Xvfb and on boards. Mouse events map to
// MouseDown/Move/Up/Scroll, Escape and printable keys to Key.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <csignal>

#include "platform/platform.h"

namespace body::platform {
namespace {

volatile std::sig_atomic_t g_glfw_quit = 0;
void on_glfw_signal(int) { g_glfw_quit = 1; }

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
        glfwSetMouseButtonCallback(window_, [](GLFWwindow* win, int button, int action, int) {
            auto* self = static_cast<GlfwSurface*>(glfwGetWindowUserPointer(win));
            double x = 0, y = 0;
            glfwGetCursorPos(win, &x, &y);
            InputEvent e;
            e.type = action == GLFW_PRESS ? InputEvent::Type::MouseDown : InputEvent::Type::MouseUp;
            e.id = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : button == GLFW_MOUSE_BUTTON_RIGHT ? 1 : 2;
            self->push(e, x, y);
        });
        glfwSetCursorPosCallback(window_, [](GLFWwindow* win, double x, double y) {
            InputEvent e;
            e.type = InputEvent::Type::MouseMove;
            static_cast<GlfwSurface*>(glfwGetWindowUserPointer(win))->push(e, x, y);
        });
        glfwSetScrollCallback(window_, [](GLFWwindow* win, double dx, double dy) {
            InputEvent e;
            e.type = InputEvent::Type::Scroll;
            e.dx = static_cast<float>(dx);
            e.dy = static_cast<float>(dy);
            double x = 0, y = 0;
            glfwGetCursorPos(win, &x, &y);
            static_cast<GlfwSurface*>(glfwGetWindowUserPointer(win))->push(e, x, y);
        });
        glfwSetKeyCallback(window_, [](GLFWwindow* win, int key, int, int action, int) {
            if (action == GLFW_REPEAT) return;
            InputEvent e;
            e.type = InputEvent::Type::Key;
            e.key = key == GLFW_KEY_ESCAPE ? kKeyEscape : (key >= 32 && key < 127 ? key : -1);
            e.pressed = action == GLFW_PRESS;
            if (e.key >= 0) static_cast<GlfwSurface*>(glfwGetWindowUserPointer(win))->push(e, 0, 0);
        });
        std::signal(SIGINT, on_glfw_signal);
        std::signal(SIGTERM, on_glfw_signal);
        return ok_status();
    }

    Backend backend() const override { return Backend::Glfw; }
    void make_current() override { glfwMakeContextCurrent(window_); }
    Status present() override {
        glfwSwapBuffers(window_);
        return ok_status();
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
    bool poll_events(std::vector<InputEvent>& out) override {
        glfwPollEvents();
        out.insert(out.end(), pending_.begin(), pending_.end());
        pending_.clear();
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
};

}  // namespace

Result<std::unique_ptr<Surface>> create_glfw_surface(const SurfaceOptions& options) {
    auto surface = std::make_unique<GlfwSurface>();
    if (auto s = surface->init(options); !s) return s.error();
    return std::unique_ptr<Surface>(std::move(surface));
}

}  // namespace body::platform
