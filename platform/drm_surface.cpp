// DRM/KMS backend: the device through the seat, a GBM surface with EGL on it,
// and the display state (selection, atomic or legacy mode setting, one flip in
// flight, connector hotplug, seat switches, the restore on every exit path) in
// DrmDisplay (platform/drm_display.h). On a hotplug that changes the display's
// size the GBM and EGL surfaces are made again at the new size; width() and
// height() follow, and the kiosk loop resizes its viewport from them. Touch:
// the panels under SurfaceOptions::touch_directory through the evdev layer
// (platform/evdev_touch.h, hot-plugged), in display pixels, from poll_events().
#include <GLES3/gl3.h>
#include <fcntl.h>
#include <gbm.h>
#include <poll.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <initializer_list>

#include "platform/drm_display.h"
#include "platform/drm_hotplug.h"
#include "platform/egl_context.h"
#include "platform/evdev_touch.h"
#include "platform/log.h"
#include "platform/platform.h"
#include "platform/quit_signal.h"
#include "platform/seat.h"

namespace body::platform {
namespace {

// Waits until one of `fds` (-1 entries ignored) is readable or `timeout_ms`
// passed: the idle wait while nothing can be shown, instead of a busy loop.
void wait_for_any(std::initializer_list<int> fds, int timeout_ms) {
    pollfd p[4];
    nfds_t n = 0;
    for (int fd : fds)
        if (fd >= 0 && n < 4) p[n++] = pollfd{fd, POLLIN, 0};
    ::poll(p, n, timeout_ms);
}

class DrmSurface final : public Surface {
public:
    ~DrmSurface() override { teardown(); }

    Status init(const SurfaceOptions& options) {
        options_ = options;
        auto request = parse_mode_request(options.mode);
        if (!request) return request.error();
        seat_ = Seat::open();
        if (log_enabled(LogLevel::Info)) std::fprintf(stderr, "bodyview: drm: devices through %s\n", seat_->kind());
        if (auto s = open_device(options.drm_device); !s) return s;
        display_ = std::make_unique<DrmDisplay>(real_drm_ops(), fd_, request.value());
        activations_ = seat_->activations();
        if (auto s = display_->pick(); !s) return s;

        gbm_ = gbm_create_device(fd_);
        if (!gbm_) return runtime_error("drm: gbm_create_device failed on " + device_);
        if (auto s = create_gbm_surface(); !s) return s;
        auto egl = EglContext::open(EGL_PLATFORM_GBM_KHR, gbm_, EGL_WINDOW_BIT, GBM_FORMAT_XRGB8888);
        if (!egl) return runtime_error("drm: " + egl.error().message);
        egl_ = std::move(egl.value());
        if (auto s = egl_->create_window_surface(gbm_surface_); !s) return s;
        if (auto s = egl_->make_current(); !s) return s;

        install_quit_handlers();
        start_ = std::chrono::steady_clock::now();
        // First frame: clear, swap, set the mode on that buffer.
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        restore_on_crash(display_->keeper());
        if (auto s = present(); !s) return s;
        if (log_enabled(LogLevel::Info))
            std::fprintf(stderr, "bodyview: drm: %dx%d, %s mode setting\n", width(), height(), display_->mode_setter());
        std::string why;
        hotplug_ = open_udev_hotplug(device_, why);
        if (!hotplug_) std::fprintf(stderr, "bodyview: drm: display hotplug not watched (%s)\n", why.c_str());
        open_touch(options);
        return ok_status();
    }

    Backend backend() const override { return Backend::Drm; }
    void make_current() override { (void)egl_->make_current(); }
    int width() const override { return surface_width_; }
    int height() const override { return surface_height_; }
    float pixels_per_mm() const override { return display_->pixels_per_mm(); }
    unsigned framebuffer() const override { return 0; }
    double time() const override {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    bool poll_events(std::vector<InputEvent>& out) override {
        if (quit_requested()) {
            InputEvent quit;
            quit.type = InputEvent::Type::Quit;
            quit.time = time();
            out.push_back(quit);
            return false;
        }
        seat_->dispatch();
        // Switched away and back since the last frame counts as away: the mode is set again.
        if (seat_->activations() != activations_) display_->set_active(false);
        activations_ = seat_->activations();
        display_->set_active(seat_->active());
        if (hotplug_ && display_->follow(*hotplug_) == DrmDisplay::Hotplug::Resized) resize_surfaces();
        if (touch_ && seat_->active()) touch_->poll(time(), out);
        return true;
    }

    // Swap, then show the new front buffer through the display (a mode set or
    // one flip, waited for), then release the previous buffer. When nothing
    // can be shown (another VT has the seat, no display connected, no DRM
    // master) the frame is dropped and the loop idles until the seat, udev or
    // a timeout wakes it.
    Status present() override {
        if (auto s = egl_->swap_buffers(); !s) return s;
        gbm_bo* next = gbm_surface_lock_front_buffer(gbm_surface_);
        if (!next) return runtime_error("drm: no free GBM buffer");
        auto fb = framebuffer_for(next);
        if (!fb) {
            gbm_surface_release_buffer(gbm_surface_, next);
            return fb.error();
        }
        auto shown = display_->present(fb.value());
        if (!shown || shown.value() == DrmDisplay::Shown::Skipped) {
            gbm_surface_release_buffer(gbm_surface_, next);
            if (!shown) return shown.error();
            wait_for_any({seat_->fd(), hotplug_ ? hotplug_->fd() : -1}, kIdleWaitMs);
            return ok_status();
        }
        if (front_) gbm_surface_release_buffer(gbm_surface_, front_);
        front_ = next;
        return ok_status();
    }

private:
    static constexpr int kIdleWaitMs = 250;

    Status create_gbm_surface() {
        surface_width_ = display_->width();
        surface_height_ = display_->height();
        gbm_surface_ =
            gbm_surface_create(gbm_, static_cast<uint32_t>(surface_width_), static_cast<uint32_t>(surface_height_),
                               GBM_FORMAT_XRGB8888, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
        if (!gbm_surface_) return runtime_error("drm: gbm_surface_create failed");
        return ok_status();
    }

    // The display re-picked at a new size (hotplug): new GBM and EGL surfaces
    // (the next present() sets the mode on them) and touch mapped to the new
    // size. A failure keeps the old surfaces (the frames are then shown at the
    // old size, or refused, until the next hotplug).
    void resize_surfaces() {
        gbm_surface* old = gbm_surface_;
        const int old_w = surface_width_, old_h = surface_height_;
        Status s = create_gbm_surface();
        if (s) s = egl_->replace_window_surface(gbm_surface_);
        if (!s) {
            std::fprintf(stderr, "bodyview: drm: resizing to %dx%d failed: %s\n", display_->width(), display_->height(),
                         s.error().message.c_str());
            if (gbm_surface_ != old && gbm_surface_) gbm_surface_destroy(gbm_surface_);
            gbm_surface_ = old;
            surface_width_ = old_w;
            surface_height_ = old_h;
            return;
        }
        if (front_) gbm_surface_release_buffer(old, front_);
        front_ = nullptr;
        gbm_surface_destroy(old);
        touch_.reset();
        open_touch(options_);
    }

    // Touchscreens through evdev, in display pixels. Absent or unreadable
    // devices are not an error: one line, and a panel plugged in later is found.
    void open_touch(const SurfaceOptions& options) {
        std::shared_ptr<Seat> seat = seat_;
        auto input = EvdevInput::open(EvdevOptions{options.touch_directory, surface_width_, surface_height_,
                                                   options.touch_rotation, options.touch_calibration,
                                                   [seat](const std::string& path) { return seat->open_device(path); },
                                                   [seat](int fd) { seat->close_device(fd); }});
        if (!input) {
            std::fprintf(stderr, "bodyview: drm: no touch input (%s)\n", input.error().message.c_str());
            return;
        }
        touch_ = std::move(input).value();
    }

    Status open_device(const std::string& requested) {
        std::vector<std::string> candidates;
        if (!requested.empty()) {
            candidates.push_back(requested);
        } else {
            for (int i = 0; i < 10; ++i) candidates.push_back("/dev/dri/card" + std::to_string(i));
        }
        std::string last = "no /dev/dri/card* device";
        for (const auto& path : candidates) {
            int fd = seat_->open_device(path);
            if (fd < 0) {
                if (errno != ENOENT || !requested.empty()) last = path + ": " + std::strerror(errno);
                continue;
            }
            drmModeRes* res = drmModeGetResources(fd);
            if (res) {
                drmModeFreeResources(res);
                fd_ = fd;
                device_ = path;
                return ok_status();
            }
            last = path + ": not a KMS device";
            seat_->close_device(fd);
        }
        return runtime_error("drm: cannot open a display device (" + last + ")");
    }

    static void destroy_fb(gbm_bo* bo, void* data) {
        auto* holder = static_cast<std::pair<int, uint32_t>*>(data);
        if (holder->second) drmModeRmFB(holder->first, holder->second);
        delete holder;
        (void)bo;
    }

    Result<uint32_t> framebuffer_for(gbm_bo* bo) {
        if (auto* existing = static_cast<std::pair<int, uint32_t>*>(gbm_bo_get_user_data(bo))) return existing->second;
        uint32_t fb = 0;
        uint32_t handles[4] = {gbm_bo_get_handle(bo).u32, 0, 0, 0};
        uint32_t strides[4] = {gbm_bo_get_stride(bo), 0, 0, 0};
        uint32_t offsets[4] = {0, 0, 0, 0};
        if (drmModeAddFB2(fd_, gbm_bo_get_width(bo), gbm_bo_get_height(bo), GBM_FORMAT_XRGB8888, handles, strides,
                          offsets, &fb, 0) != 0)
            return runtime_error("drm: drmModeAddFB2 failed (" + std::string(std::strerror(errno)) + ")");
        gbm_bo_set_user_data(bo, new std::pair<int, uint32_t>(fd_, fb), destroy_fb);
        return fb;
    }

    // The display first (before our framebuffers go), then GL, GBM and the device.
    void teardown() {
        if (display_) {
            restore_on_crash(nullptr);
            if (auto s = display_->restore(); !s) std::fprintf(stderr, "bodyview: %s\n", s.error().message.c_str());
        }
        hotplug_.reset();
        if (front_ && gbm_surface_) gbm_surface_release_buffer(gbm_surface_, front_);
        front_ = nullptr;
        egl_.reset();
        if (gbm_surface_) gbm_surface_destroy(gbm_surface_);
        if (gbm_) gbm_device_destroy(gbm_);
        gbm_surface_ = nullptr;
        gbm_ = nullptr;
        display_.reset();
        touch_.reset();
        if (fd_ >= 0) seat_->close_device(fd_);
        fd_ = -1;
        remove_quit_handlers();
    }

    int fd_ = -1;
    std::string device_;
    SurfaceOptions options_;
    int surface_width_ = 0, surface_height_ = 0;  // the GBM surface's size (the mode's when it was made)
    std::unique_ptr<DrmDisplay> display_;
    std::unique_ptr<HotplugSource> hotplug_;
    std::shared_ptr<Seat> seat_;
    int activations_ = 0;  // the seat's activations at the last frame
    gbm_device* gbm_ = nullptr;
    gbm_surface* gbm_surface_ = nullptr;
    gbm_bo* front_ = nullptr;
    std::unique_ptr<EglContext> egl_;
    std::chrono::steady_clock::time_point start_;
    std::unique_ptr<EvdevInput> touch_;
};

}  // namespace

Result<std::unique_ptr<Surface>> create_drm_surface(const SurfaceOptions& options) {
    return init_surface<DrmSurface>(options);
}

}  // namespace body::platform
