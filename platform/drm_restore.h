#pragma once
// What the screen showed before the kiosk, given back on every exit path the
// process controls: the normal end and SIGINT/SIGTERM (the loop leaves, the
// surface is destroyed), a fatal error after the mode set (the same), and a
// crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT: restore_on_crash). SIGKILL
// cannot be caught: the kernel drops the DRM master and the next start sets
// its mode again.
//
// The few libdrm calls involved go through DrmOps (drm_kms.h), a table the unit
// tests replace with a fake device (tests/platform/drm_restore_test.cpp). After
// an atomic mode set the restore is one atomic commit too (use_atomic), with
// drmModeSetCrtc as the fallback when the driver refuses it.
#include <cstdint>

#include "platform/drm_kms.h"
#include "platform/drm_modeset.h"
#include "shared/error.h"

namespace body::platform {

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
    // The kiosk set its mode atomically with these ids: restore the same way.
    void use_atomic(const DrmAtomicIds& ids) {
        atomic_ = ids;
        use_atomic_ = true;
    }
    // The one flip in flight: queued (page flip with an event), then its event seen.
    void flip_queued() { flip_pending_ = true; }
    void flip_done() { flip_pending_ = false; }
    bool flip_pending() const { return flip_pending_; }
    // Waits out a pending flip, then sets the saved framebuffer, position and mode
    // on the connector (or turns the CRTC off when it was off). Once; later calls
    // and calls before mode_set() do nothing.
    Status restore();
    // The crash handler's restore: the same, always legacy (drmModeSetCrtc is
    // one ioctl; the atomic request allocates, and the heap may be what broke).
    void restore_after_crash();
    bool restored() const { return restored_; }

private:
    void wait_for_flip();
    int restore_atomic();
    int restore_legacy();

    const DrmOps& ops_;
    int fd_;
    uint32_t crtc_id_, connector_id_;
    drmModeCrtc* saved_ = nullptr;
    bool mode_set_ = false, flip_pending_ = false, restored_ = false, use_atomic_ = false;
    DrmAtomicIds atomic_;
};

// Registers `keeper` for the crash signals: their handler restores the display,
// then lets the signal do what it would have done. nullptr unregisters.
void restore_on_crash(DrmCrtcKeeper* keeper);

}  // namespace body::platform
