// Saving and restoring the CRTC around the kiosk (contract in drm_restore.h).
#include "platform/drm_restore.h"

#include <poll.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <string>

namespace body::platform {
namespace {

int poll_readable(int fd, int timeout_ms) {
    pollfd p{fd, POLLIN, 0};
    return ::poll(&p, 1, timeout_ms);
}

const DrmOps kRealOps = {drmModeGetCrtc, drmModeFreeCrtc, drmModeSetCrtc, poll_readable, drmHandleEvent};

std::atomic<DrmCrtcKeeper*> g_crash_keeper{nullptr};
constexpr int kCrashSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

void on_crash(int signal) {
    // One attempt only: a crash inside the restore must not loop.
    if (DrmCrtcKeeper* keeper = g_crash_keeper.exchange(nullptr)) (void)keeper->restore();
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

}  // namespace

const DrmOps& real_drm_ops() { return kRealOps; }

DrmCrtcKeeper::DrmCrtcKeeper(const DrmOps& ops, int fd, uint32_t crtc_id, uint32_t connector_id)
    : ops_(ops), fd_(fd), crtc_id_(crtc_id), connector_id_(connector_id) {}

DrmCrtcKeeper::~DrmCrtcKeeper() {
    (void)restore();
    if (saved_) ops_.free_crtc(saved_);  // never set: nothing to restore, still ours to free
}

bool DrmCrtcKeeper::save() {
    if (saved_) ops_.free_crtc(saved_);
    saved_ = ops_.get_crtc(fd_, crtc_id_);
    return saved_ != nullptr;
}

void DrmCrtcKeeper::wait_for_flip() {
    drmEventContext context{};
    context.version = 2;
    context.page_flip_handler = [](int, unsigned, unsigned, unsigned, void* data) {
        static_cast<DrmCrtcKeeper*>(data)->flip_done();
    };
    // The flip's event carries the user data it was queued with; whatever it is,
    // the one flip in flight is over once an event has been handled.
    for (int waited = 0; flip_pending_ && waited < kFlipWaitMs; waited += 50) {
        const int r = ops_.wait_readable(fd_, 50);
        if (r < 0 && errno != EINTR) break;
        if (r > 0) {
            ops_.handle_event(fd_, &context);
            flip_pending_ = false;
        }
    }
}

Status DrmCrtcKeeper::restore() {
    if (!mode_set_ || restored_) return ok_status();
    restored_ = true;
    wait_for_flip();
    int rc = 0;
    if (saved_ && saved_->mode_valid && saved_->buffer_id)
        rc = ops_.set_crtc(fd_, crtc_id_, saved_->buffer_id, saved_->x, saved_->y, &connector_id_, 1, &saved_->mode);
    else  // it was off (or unknown): off again
        rc = ops_.set_crtc(fd_, crtc_id_, 0, 0, 0, nullptr, 0, nullptr);
    if (saved_) ops_.free_crtc(saved_);
    saved_ = nullptr;
    if (rc != 0) return runtime_error("drm: restoring the display failed (" + std::string(std::strerror(errno)) + ")");
    return ok_status();
}

void restore_on_crash(DrmCrtcKeeper* keeper) {
    g_crash_keeper.store(keeper);
    for (int s : kCrashSignals) std::signal(s, keeper ? on_crash : SIG_DFL);
}

}  // namespace body::platform
