#pragma once
// The platform layer: one small interface over window systems and GL contexts.
// Backends: headless_* (EGL surfaceless/pbuffer + offscreen framebuffer, always
// built), glfw_* (desktop window, GLES 3 through EGL), drm_* (DRM/KMS + GBM +
// EGL on boards without a desktop). Chosen at run time with `--platform`.
//
// Contract: create_surface() returns a Surface whose GLES 3.0 context is
// current on the calling thread. Render into framebuffer() (0 for on-screen
// backends, an FBO for headless), then present(). All calls on one thread.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "shared/error.h"

namespace body::platform {

enum class Backend { Auto, Headless, Glfw, Drm };

// Backends compiled into this binary, in auto-selection order (headless last).
std::vector<Backend> compiled_backends();
const char* backend_name(Backend backend);
Result<Backend> parse_backend(const std::string& name);

// Keyboard modifiers held when an input event happened (InputEvent::modifiers).
enum Modifier : uint32_t { kModShift = 1, kModCtrl = 2, kModAlt = 4 };

// Mouse buttons as InputEvent::id numbers them.
enum class MouseButton : uint8_t { Left = 0, Right = 1, Middle = 2 };

// One input event in surface pixels (origin top-left). Backends and the evdev
// touch layer (platform/evdev_*) produce these, replay files too
// (kiosk/app/replay.h); the kiosk app consumes them as they are.
struct InputEvent {
    enum class Type : uint8_t {
        TouchDown,
        TouchMove,
        TouchUp,
        MouseDown,
        MouseUp,
        MouseMove,
        Scroll,
        Key,
        Quit,  // window closed, SIGINT/SIGTERM
        Text,  // a character typed: its Unicode codepoint in `key` (glfw's char callback)
    };
    Type type = Type::MouseMove;
    int id = 0;              // touch slot/tracking id; mouse button (0 left, 1 right, 2 middle)
    float x = 0, y = 0;      // position in pixels (touch, mouse)
    float dx = 0, dy = 0;    // scroll offsets (Scroll)
    int key = 0;             // key code (Key): ASCII for printable keys, 256 Escape
    bool pressed = false;    // Key: down (true) or up
    double time = 0;         // seconds, the same clock as Surface::time()
    uint32_t modifiers = 0;  // kMod* bits held (glfw: mouse, scroll, key); 0 for touch and headless

    MouseButton button() const {
        return id == 1 ? MouseButton::Right : id == 2 ? MouseButton::Middle : MouseButton::Left;
    }
};
inline constexpr int kKeyEscape = 256;
// Editing keys (Key events; the authoring mode's text fields and shortcuts).
inline constexpr int kKeyBackspace = 257, kKeyDelete = 258, kKeyLeft = 259, kKeyRight = 260, kKeyUp = 261,
                     kKeyDown = 262, kKeyHome = 263, kKeyEnd = 264, kKeyEnter = 265, kKeyTab = 266, kKeyF1 = 267;

struct SurfaceOptions {
    Backend backend = Backend::Auto;
    int width = 0, height = 0;  // 0: the display's preferred size (headless: 1280x800)
    bool fullscreen = true;     // glfw: fullscreen on the primary monitor, else a window
    std::string mode;           // drm: "WxH" or "WxH@Hz"; empty for the preferred mode
    std::string drm_device;     // drm: e.g. /dev/dri/card0; empty to try card0..card9
    std::string title = "bodyview";
    // glfw and drm: touchscreens are read from here (evdev, platform/evdev_touch.h,
    // hot-plugged) and delivered by poll_events() in surface pixels (glfw maps them
    // into the window, platform/evdev_window.h); `touch_rotation` is the panel's
    // rotation (0, 90, 180, 270) against the picture.
    std::string touch_directory = "/dev/input";
    int touch_rotation = 0;
    // Applied to the panel's normalised coordinates before the rotation (evdev_touch.h).
    std::array<float, 6> touch_calibration{1, 0, 0, 0, 1, 0};
};

class Surface {
public:
    virtual ~Surface() = default;
    virtual Backend backend() const = 0;
    virtual void make_current() = 0;
    // Shows the frame (swap buffers / page flip). Headless: glFinish only.
    virtual Status present() = 0;
    // Size of framebuffer() in pixels.
    virtual int width() const = 0;
    virtual int height() const = 0;
    // The GL framebuffer to draw into: 0 on screen, an offscreen FBO headless.
    virtual unsigned framebuffer() const = 0;
    // Appends pending events; returns false once the user asked to quit.
    virtual bool poll_events(std::vector<InputEvent>& out) = 0;
    // Monotonic seconds since the surface was created.
    virtual double time() const = 0;
    // The display's pixels per millimetre (DRM: the connector's size; GLFW: the
    // monitor's, scaled to the framebuffer); 0 when unknown (headless, a
    // display that reports no size). Touch targets are sized from it.
    virtual float pixels_per_mm() const { return 0.0f; }
    // Takes back a window-close request (the authoring mode's unsaved-changes
    // prompt: Cancel). Backends without a close button ignore it.
    virtual void cancel_quit() {}
};

// Mesa's llvmpipe (the software rasterizer of GPU-less machines and of CI)
// recycles a scene once its fence reads complete, which its rasterizer thread
// marks before it unlocks the fence's mutex: the fence can be freed under that
// unlock, a 4-byte write into freed memory (heap corruption after 15-60 soak
// minutes under load; bench/RESULTS.md). Rasterizing on the calling thread has
// no such race, so surfaces set LP_NUM_THREADS=0 unless the user set it, before
// any driver loads. Returns the value in effect. Other drivers ignore it.
std::string default_software_rasterizer_threads();

// Creates the surface for `options.backend`; Auto picks a display server if
// one is reachable, else DRM if /dev/dri/card* opens, else fails with a reason.
// Headless is used only when asked for.
Result<std::unique_ptr<Surface>> create_surface(const SurfaceOptions& options);

// Backend constructors (defined in the backend files; absent ones fail cleanly).
Result<std::unique_ptr<Surface>> create_headless_surface(const SurfaceOptions& options);
Result<std::unique_ptr<Surface>> create_glfw_surface(const SurfaceOptions& options);
Result<std::unique_ptr<Surface>> create_drm_surface(const SurfaceOptions& options);

// For the backend constructors: a new S after its `Status init(const SurfaceOptions&)`.
template <class S>
Result<std::unique_ptr<Surface>> init_surface(const SurfaceOptions& options) {
    auto surface = std::make_unique<S>();
    if (auto s = surface->init(options); !s) return s.error();
    return std::unique_ptr<Surface>(std::move(surface));
}

// Reads the RGBA8 pixels of the current read framebuffer, top row first.
std::vector<uint8_t> read_pixels_rgba(unsigned framebuffer, int width, int height);

// Parses "1280x800" into width/height.
Result<std::pair<int, int>> parse_size(const std::string& text);

}  // namespace body::platform
