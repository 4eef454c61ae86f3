// DRM/KMS backend: mode setting, GBM surface, EGL on GBM and page flipping with
// at most one flip in flight; the original CRTC is restored on exit, after
// SIGINT/SIGTERM, after a fatal error and on a crash (platform/drm_restore.h). Structure after kmscube (drm-common.c,
// drm-legacy.c). Touch: the panels under SurfaceOptions::touch_directory through the evdev layer
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

#include "platform/drm_restore.h"
#include "platform/drm_select.h"
#include "platform/egl_context.h"
#include "platform/evdev_touch.h"
#include "platform/log.h"
#include "platform/platform.h"
#include "platform/quit_signal.h"
#include "platform/seat.h"

namespace body::platform {
namespace {

std::string connector_name(const drmModeConnector* c) {
    const char* type = drmModeGetConnectorTypeName(c->connector_type);
    return std::string(type ? type : "Unknown") + "-" + std::to_string(c->connector_type_id);
}

// Describes every connector for the pure selection (drm_select.h).
std::vector<DrmConnector> describe_connectors(int fd, const drmModeRes* res) {
    std::vector<DrmConnector> out;
    for (int i = 0; i < res->count_connectors; ++i) {
        drmModeConnector* c = drmModeGetConnector(fd, res->connectors[i]);
        if (!c) continue;
        DrmConnector d;
        d.id = c->connector_id;
        d.name = connector_name(c);
        d.connected = c->connection == DRM_MODE_CONNECTED;
        for (int m = 0; m < c->count_modes; ++m)
            d.modes.push_back({c->modes[m].hdisplay, c->modes[m].vdisplay, static_cast<int>(c->modes[m].vrefresh),
                               (c->modes[m].type & DRM_MODE_TYPE_PREFERRED) != 0});
        if (c->encoder_id) {
            if (drmModeEncoder* e = drmModeGetEncoder(fd, c->encoder_id)) {
                d.current_crtc = e->crtc_id;
                drmModeFreeEncoder(e);
            }
        }
        for (int e = 0; e < c->count_encoders; ++e) {
            drmModeEncoder* enc = drmModeGetEncoder(fd, c->encoders[e]);
            if (!enc) continue;
            for (int k = 0; k < res->count_crtcs; ++k)
                if (enc->possible_crtcs & (1u << k)) d.possible_crtcs.push_back(res->crtcs[k]);
            drmModeFreeEncoder(enc);
        }
        drmModeFreeConnector(c);
        out.push_back(std::move(d));
    }
    return out;
}

class DrmSurface final : public Surface {
public:
    ~DrmSurface() override { teardown(); }

    Status init(const SurfaceOptions& options) {
        auto request = parse_mode_request(options.mode);
        if (!request) return request.error();
        seat_ = Seat::open();
        if (log_enabled(LogLevel::Info)) std::fprintf(stderr, "bodyview: drm: devices through %s\n", seat_->kind());
        if (auto s = open_device(options.drm_device); !s) return s;
        drmModeRes* res = drmModeGetResources(fd_);
        if (!res) return runtime_error("drm: " + device_ + " has no KMS resources (not a display controller?)");
        auto connectors = describe_connectors(fd_, res);
        drmModeConnector* chosen = nullptr;
        auto sel = select_drm_output(connectors, request.value());
        if (sel) chosen = drmModeGetConnector(fd_, connectors[sel->connector].id);
        drmModeFreeResources(res);
        if (!sel) return sel.error();
        if (!chosen) return runtime_error("drm: connector vanished during set-up");
        mode_ = chosen->modes[sel->mode];
        connector_id_ = chosen->connector_id;
        if (chosen->mmWidth > 0) px_per_mm_ = static_cast<float>(mode_.hdisplay) / static_cast<float>(chosen->mmWidth);
        drmModeFreeConnector(chosen);
        crtc_id_ = sel->crtc;
        keeper_ = std::make_unique<DrmCrtcKeeper>(real_drm_ops(), fd_, crtc_id_, connector_id_);
        if (!keeper_->save())
            std::fprintf(stderr, "bodyview: drm: cannot read CRTC %u; it is turned off at exit\n", crtc_id_);

        gbm_ = gbm_create_device(fd_);
        if (!gbm_) return runtime_error("drm: gbm_create_device failed on " + device_);
        gbm_surface_ = gbm_surface_create(gbm_, mode_.hdisplay, mode_.vdisplay, GBM_FORMAT_XRGB8888,
                                          GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
        if (!gbm_surface_) return runtime_error("drm: gbm_surface_create failed");
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
        if (auto s = egl_->swap_buffers(); !s) return s;
        gbm_bo* bo = gbm_surface_lock_front_buffer(gbm_surface_);
        auto fb = framebuffer_for(bo);
        if (!fb) return fb.error();
        if (drmModeSetCrtc(fd_, crtc_id_, fb.value(), 0, 0, &connector_id_, 1, &mode_) != 0)
            return runtime_error("drm: drmModeSetCrtc failed (" + std::string(std::strerror(errno)) + ")");
        keeper_->mode_set();
        restore_on_crash(keeper_.get());
        activations_ = seat_->activations();
        front_ = bo;
        open_touch(options);
        return ok_status();
    }

    Backend backend() const override { return Backend::Drm; }
    void make_current() override { (void)egl_->make_current(); }
    int width() const override { return mode_.hdisplay; }
    int height() const override { return mode_.vdisplay; }
    float pixels_per_mm() const override { return px_per_mm_; }
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
        if (touch_ && seat_->active()) touch_->poll(time(), out);
        return true;
    }

    // Swap, queue a flip of the new front buffer, wait for it (so at most one
    // flip is ever in flight), then release the previous buffer.
    // While another VT has the seat nothing reaches the display; back on ours,
    // the mode is set again on the new frame (the other session may have changed it).
    Status present() override {
        if (auto s = egl_->swap_buffers(); !s) return s;
        gbm_bo* next = gbm_surface_lock_front_buffer(gbm_surface_);
        if (!next) return runtime_error("drm: no free GBM buffer");
        if (!seat_->active()) {
            gbm_surface_release_buffer(gbm_surface_, next);
            return ok_status();
        }
        auto fb = framebuffer_for(next);
        if (!fb) return fb.error();
        if (seat_->activations() != activations_) {
            activations_ = seat_->activations();
            if (drmModeSetCrtc(fd_, crtc_id_, fb.value(), 0, 0, &connector_id_, 1, &mode_) != 0)
                return runtime_error("drm: setting the mode again failed (" + std::string(std::strerror(errno)) + ")");
            if (front_) gbm_surface_release_buffer(gbm_surface_, front_);
            front_ = next;
            return ok_status();
        }
        if (drmModePageFlip(fd_, crtc_id_, fb.value(), DRM_MODE_PAGE_FLIP_EVENT, keeper_.get()) != 0) {
            gbm_surface_release_buffer(gbm_surface_, next);
            return runtime_error("drm: drmModePageFlip failed (" + std::string(std::strerror(errno)) + ")");
        }
        keeper_->flip_queued();
        drmEventContext ev{};
        ev.version = 2;
        ev.page_flip_handler = [](int, unsigned, unsigned, unsigned, void* data) {
            static_cast<DrmCrtcKeeper*>(data)->flip_done();
        };
        while (keeper_->flip_pending()) {
            pollfd p{fd_, POLLIN, 0};
            int r = ::poll(&p, 1, 1000);
            if (r < 0 && errno == EINTR) {
                if (quit_requested()) break;  // the keeper waits for the flip before restoring
                continue;
            }
            if (r <= 0) return runtime_error("drm: page flip timed out");
            drmHandleEvent(fd_, &ev);
        }
        if (front_) gbm_surface_release_buffer(gbm_surface_, front_);
        front_ = next;
        return ok_status();
    }

private:
    // Touchscreens through evdev, in display pixels. Absent or unreadable
    // devices are not an error: one line, and a panel plugged in later is found.
    void open_touch(const SurfaceOptions& options) {
        std::shared_ptr<Seat> seat = seat_;
        auto input = EvdevInput::open(EvdevOptions{options.touch_directory, mode_.hdisplay, mode_.vdisplay,
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
        if (keeper_) {
            restore_on_crash(nullptr);
            if (auto s = keeper_->restore(); !s) std::fprintf(stderr, "bodyview: %s\n", s.error().message.c_str());
            keeper_.reset();
        }
        if (front_ && gbm_surface_) gbm_surface_release_buffer(gbm_surface_, front_);
        front_ = nullptr;
        egl_.reset();
        if (gbm_surface_) gbm_surface_destroy(gbm_surface_);
        if (gbm_) gbm_device_destroy(gbm_);
        gbm_surface_ = nullptr;
        gbm_ = nullptr;
        touch_.reset();
        if (fd_ >= 0) seat_->close_device(fd_);
        fd_ = -1;
        remove_quit_handlers();
    }

    int fd_ = -1;
    std::string device_;
    drmModeModeInfo mode_{};
    uint32_t connector_id_ = 0, crtc_id_ = 0;
    float px_per_mm_ = 0.0f;  // from the connector's reported size; 0 when it reports none
    std::unique_ptr<DrmCrtcKeeper> keeper_;
    std::shared_ptr<Seat> seat_;
    int activations_ = 0;  // the seat's activations when the mode was last set
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
