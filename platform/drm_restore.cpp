// Saving and restoring the CRTC around the kiosk (contract in drm_restore.h).
#include "platform/drm_restore.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <string>

namespace body::platform {
namespace {

std::atomic<DrmCrtcKeeper*> g_crash_keeper{nullptr};
constexpr int kCrashSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

void on_crash(int signal) {
    // One attempt only: a crash inside the restore must not loop.
    if (DrmCrtcKeeper* keeper = g_crash_keeper.exchange(nullptr)) keeper->restore_after_crash();
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

}  // namespace

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

// The saved state (or "off") in one ALLOW_MODESET commit; the saved mode
// goes to the kernel as a blob, dropped again after the commit.
int DrmCrtcKeeper::restore_atomic() {
    const bool on = saved_ && saved_->mode_valid && saved_->buffer_id;
    uint32_t blob = 0;
    if (on && ops_.create_blob(fd_, &saved_->mode, sizeof saved_->mode, &blob) != 0) return -1;
    DrmAtomicProp props[kMaxAtomicProps];
    const size_t n = on ? atomic_mode_props(atomic_, connector_id_, crtc_id_, blob, saved_->buffer_id, saved_->x,
                                            saved_->y, saved_->mode.hdisplay, saved_->mode.vdisplay, props)
                        : atomic_mode_props(atomic_, connector_id_, crtc_id_, 0, 0, 0, 0, 0, 0, props);
    const int rc = ops_.atomic_commit(fd_, props, n, DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr);
    if (blob) ops_.destroy_blob(fd_, blob);
    return rc;
}

int DrmCrtcKeeper::restore_legacy() {
    if (saved_ && saved_->mode_valid && saved_->buffer_id)
        return ops_.set_crtc(fd_, crtc_id_, saved_->buffer_id, saved_->x, saved_->y, &connector_id_, 1, &saved_->mode);
    return ops_.set_crtc(fd_, crtc_id_, 0, 0, 0, nullptr, 0, nullptr);  // it was off (or unknown): off again
}

Status DrmCrtcKeeper::restore() {
    if (!mode_set_ || restored_) return ok_status();
    restored_ = true;
    wait_for_flip();
    int rc = use_atomic_ ? restore_atomic() : -1;
    if (rc != 0) rc = restore_legacy();
    if (saved_) ops_.free_crtc(saved_);
    saved_ = nullptr;
    if (rc != 0) return runtime_error("drm: restoring the display failed (" + std::string(std::strerror(errno)) + ")");
    return ok_status();
}

void DrmCrtcKeeper::restore_after_crash() {
    if (!mode_set_ || restored_) return;
    restored_ = true;
    wait_for_flip();
    (void)restore_legacy();
}

void restore_on_crash(DrmCrtcKeeper* keeper) {
    g_crash_keeper.store(keeper);
    for (int s : kCrashSignals) std::signal(s, keeper ? on_crash : SIG_DFL);
}

}  // namespace body::platform
