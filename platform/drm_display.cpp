// Output selection, mode setting, flips, hotplug and seat state over DrmOps
// (contract in drm_display.h).
#include "platform/drm_display.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "platform/log.h"
#include "platform/quit_signal.h"

namespace body::platform {
namespace {

bool same_modes(const std::vector<drmModeModeInfo>& a, const std::vector<drmModeModeInfo>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a[i], &b[i], sizeof a[i]) != 0) return false;
    return true;
}

void info(const std::string& line) {
    if (log_enabled(LogLevel::Info)) std::fprintf(stderr, "bodyview: drm: %s\n", line.c_str());
}

}  // namespace

DrmDisplay::DrmDisplay(const DrmOps& ops, int fd, const ModeRequest& request) : ops_(ops), fd_(fd), request_(request) {}

DrmDisplay::~DrmDisplay() { (void)restore(); }

float DrmDisplay::pixels_per_mm() const {
    return mm_width_ > 0 ? static_cast<float>(width()) / static_cast<float>(mm_width_) : 0.0f;
}

bool DrmDisplay::pick_from(const std::vector<DrmProbedConnector>& probed, const ModeRequest& request,
                           std::string& why) {
    std::vector<DrmConnector> list;
    for (const auto& p : probed) list.push_back(p.desc);
    auto sel = select_drm_output(list, request);
    if (!sel) {
        why = sel.error().message;
        return false;
    }
    const DrmProbedConnector& c = probed[sel->connector];
    target_.connector = c.desc.id;
    target_.crtc = sel->crtc;
    target_.mode = c.modes[sel->mode];
    modes_ = c.modes;
    mm_width_ = c.mm_width;
    has_output_ = true;
    return true;
}

Status DrmDisplay::pick() {
    std::string why;
    if (!pick_from(ops_.probe(fd_), request_, why)) return runtime_error(why);
    keeper_ = std::make_unique<DrmCrtcKeeper>(ops_, fd_, target_.crtc, target_.connector);
    if (!keeper_->save())
        std::fprintf(stderr, "bodyview: drm: cannot read CRTC %u; it is turned off at exit\n", target_.crtc);
    return ok_status();
}

// Lost master (EACCES/EPERM): another process drives the display now.
bool DrmDisplay::master_refused(int error) {
    if (error != EACCES && error != EPERM) return false;
    if (!master_lost_) std::fprintf(stderr, "bodyview: drm: not DRM master any more; waiting to get it back\n");
    master_lost_ = true;
    return true;
}

Status DrmDisplay::set_mode(uint32_t fb) {
    if (auto s = wait_flip(); !s) return s;  // the kernel refuses a mode set over a pending flip
    if (!setter_) {
        std::string why;
        setter_ = choose_mode_setter(ops_, fd_, target_, fb, why);
        info(std::string("mode setting: ") + setter_->kind() + (why.empty() ? "" : " (" + why + ")"));
    }
    Status s = setter_->set_mode(target_, fb);
    if (!s && std::strcmp(setter_->kind(), "atomic") == 0 && errno != EACCES && errno != EPERM) {
        // The driver took atomic before and refuses it now (another mode, another connector).
        std::fprintf(stderr, "bodyview: %s; trying legacy mode setting\n", s.error().message.c_str());
        setter_ = make_legacy_mode_setter(ops_, fd_);
        s = setter_->set_mode(target_, fb);
    }
    if (!s) return s;
    if (keeper_) {
        keeper_->mode_set();
        if (const DrmAtomicIds* ids = setter_->atomic_ids()) keeper_->use_atomic(*ids);
    }
    need_mode_set_ = false;
    return ok_status();
}

// Handles events until the flip in flight (if any) has completed.
Status DrmDisplay::wait_flip() {
    drmEventContext context{};
    context.version = 2;
    context.page_flip_handler = [](int, unsigned, unsigned, unsigned, void* data) {
        static_cast<DrmCrtcKeeper*>(data)->flip_done();
    };
    while (keeper_->flip_pending()) {
        const int r = ops_.wait_readable(fd_, 1000);
        if (r < 0 && errno == EINTR) {
            if (quit_requested()) break;  // the keeper waits for the flip before restoring
            continue;
        }
        if (r <= 0) return runtime_error("drm: page flip timed out");
        ops_.handle_event(fd_, &context);
    }
    return ok_status();
}

// Queues the flip and waits for its event; a flip still pending from an
// earlier timeout is waited for first, so two are never in flight.
Status DrmDisplay::flip(uint32_t fb) {
    if (auto s = wait_flip(); !s) return s;
    if (auto s = setter_->queue_flip(fb, keeper_.get()); !s) return s;
    ++flips_;
    keeper_->flip_queued();
    return wait_flip();
}

Result<DrmDisplay::Shown> DrmDisplay::present(uint32_t fb) {
    if (!active_ || !has_output_ || !keeper_) return Shown::Skipped;
    if (master_lost_) {
        if (ops_.set_master(fd_) != 0) return Shown::Skipped;
        info("DRM master regained; setting the mode again");
        master_lost_ = false;
        need_mode_set_ = true;
    }
    const bool full = need_mode_set_;
    Status s = full ? set_mode(fb) : flip(fb);
    if (!s) {
        if (master_refused(errno)) return Shown::Skipped;
        return s.error();
    }
    return full ? Shown::ModeSet : Shown::Flipped;
}

void DrmDisplay::set_active(bool active) {
    if (active && !active_) need_mode_set_ = true;
    active_ = active;
}

DrmDisplay::Hotplug DrmDisplay::reprobe() {
    const DrmTarget before = target_;
    const bool had_output = has_output_;
    std::vector<DrmProbedConnector> probed = ops_.probe(fd_);
    if (had_output) {
        for (const auto& p : probed)
            if (p.desc.id == before.connector && p.desc.connected && same_modes(p.modes, modes_))
                return Hotplug::Unchanged;
    }
    std::string why;
    bool found = pick_from(probed, request_, why);
    if (!found && request_.width > 0) {
        // The configured mode is not on the new display: its default rather than nothing.
        std::fprintf(stderr, "bodyview: %s; using the display's preferred mode\n", why.c_str());
        found = pick_from(probed, ModeRequest{}, why);
    }
    if (!found) {
        if (had_output) std::fprintf(stderr, "bodyview: %s; idle until a display is connected\n", why.c_str());
        has_output_ = false;
        return Hotplug::NoDisplay;
    }
    need_mode_set_ = true;
    info("display changed: connector " + std::to_string(target_.connector) + " at " + std::to_string(width()) + "x" +
         std::to_string(height()));
    const bool resized =
        !had_output || before.mode.hdisplay != target_.mode.hdisplay || before.mode.vdisplay != target_.mode.vdisplay;
    return resized ? Hotplug::Resized : Hotplug::Changed;
}

Status DrmDisplay::restore() {
    if (!keeper_) return ok_status();
    return keeper_->restore();
}

}  // namespace body::platform
