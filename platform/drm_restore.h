#pragma once
// What the screen showed before the kiosk, given back on every exit path the
// process controls: the normal end and SIGINT/SIGTERM (the loop leaves, the
// surface is destroyed), a fatal error after the mode set (the same), and a
// crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT: restore_on_crash). SIGKILL
// cannot be caught: the kernel drops the DRM master and the next start sets
// its mode again.
//
// The few libdrm calls involved go through DrmOps, a table the unit tests
// replace with a fake device (tests/platform/drm_restore_test.cpp).
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <cstdint>

#include "shared/error.h"

namespace body::platform {

struct DrmOps {
    drmModeCrtc* (*get_crtc)(int fd, uint32_t crtc_id);
    void (*free_crtc)(drmModeCrtc* crtc);
    int (*set_crtc)(int fd, uint32_t crtc_id, uint32_t fb_id, uint32_t x, uint32_t y, uint32_t* connectors, int count,
                    drmModeModeInfo* mode);
    // poll(2) for POLLIN: > 0 readable, 0 timed out, < 0 error.
    int (*wait_readable)(int fd, int timeout_ms);
    int (*handle_event)(int fd, drmEventContext* context);
};
// libdrm itself.
const DrmOps& real_drm_ops();

// Saves one CRTC's state before the kiosk's mode set and puts it back once.
// Tracks the one page flip allowed in flight: a restore first waits for it
// (at most kFlipWaitMs), since the kernel refuses a mode set over a pending flip.
class DrmCrtcKeeper {
public:
    static constexpr int kFlipWaitMs = 1000;
    DrmCrtcKeeper(const DrmOps& ops, int fd, uint32_t crtc_id, uint32_t connector_id);
    ~DrmCrtcKeeper();
    DrmCrtcKeeper(const DrmCrtcKeeper&) = delete;
    DrmCrtcKeeper& operator=(const DrmCrtcKeeper&) = delete;

    // Reads the CRTC as it is now; false when the driver gives nothing back.
    bool save();
    // The kiosk's mode is on screen: from now on restore() acts.
    void mode_set() { mode_set_ = true; }
    // The one flip in flight: queued (page flip with an event), then its event seen.
    void flip_queued() { flip_pending_ = true; }
    void flip_done() { flip_pending_ = false; }
    bool flip_pending() const { return flip_pending_; }
    // Waits out a pending flip, then sets the saved framebuffer, position and mode
    // on the connector (or turns the CRTC off when it was off). Once; later calls
    // and calls before mode_set() do nothing.
    Status restore();
    bool restored() const { return restored_; }

private:
    void wait_for_flip();

    const DrmOps& ops_;
    int fd_;
    uint32_t crtc_id_, connector_id_;
    drmModeCrtc* saved_ = nullptr;
    bool mode_set_ = false, flip_pending_ = false, restored_ = false;
};

// Registers `keeper` for the crash signals: their handler restores the display,
// then lets the signal do what it would have done. nullptr unregisters.
void restore_on_crash(DrmCrtcKeeper* keeper);

}  // namespace body::platform
