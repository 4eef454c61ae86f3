#pragma once
// The display half of the DRM/KMS backend, without GBM or EGL, over DrmOps
// (drm_kms.h) so that the unit tests drive it with a fake device:
//  - picks connector, mode and CRTC (drm_select.h) and saves the CRTC for the
//    restore (drm_restore.h, on every exit path);
//  - the first present() sets the mode, atomically where the driver allows
//    (drm_modeset.h), and later ones flip with exactly one flip in flight: a
//    flip is queued only after the previous one's event was handled;
//  - connector hotplug: reprobe() re-reads the connectors and re-picks with
//    the same rule when the connector went away or its modes changed; the
//    caller resizes its buffers to width() x height() and the next present()
//    sets the mode again; with no display connected nothing is committed;
//  - seat switches: set_active(false) stops all commits, set_active(true)
//    makes the next present() a full mode set (the other VT changed it);
//  - a commit refused for want of DRM master (another process took it, direct
//    opens only) stops commits until set_master succeeds again, then a full
//    mode set.
#include <memory>
#include <string>
#include <vector>

#include "platform/drm_hotplug.h"
#include "platform/drm_modeset.h"
#include "platform/drm_restore.h"
#include "shared/error.h"

namespace body::platform {

class DrmDisplay {
public:
    DrmDisplay(const DrmOps& ops, int fd, const ModeRequest& request);
    ~DrmDisplay();  // waits out a flip in flight, restores the display
    DrmDisplay(const DrmDisplay&) = delete;
    DrmDisplay& operator=(const DrmDisplay&) = delete;

    // The first pick: an error when no connector is connected (at start the
    // kiosk needs one to size its buffers).
    Status pick();
    bool has_output() const { return has_output_; }
    int width() const { return target_.mode.hdisplay; }
    int height() const { return target_.mode.vdisplay; }
    float pixels_per_mm() const;
    const DrmTarget& target() const { return target_; }
    // "atomic", "legacy", or "" before the first mode set.
    const char* mode_setter() const { return setter_ ? setter_->kind() : ""; }

    enum class Shown { ModeSet, Flipped, Skipped };
    // Shows framebuffer `fb`: a full mode set the first time and after a
    // hotplug change, seat re-activation or regained master; a flip otherwise,
    // returning once its event arrived. Skipped: nothing was committed (seat
    // away, no display, no master); the caller keeps its own buffer and idles.
    Result<Shown> present(uint32_t fb);

    void set_active(bool active);
    bool active() const { return active_; }

    enum class Hotplug { Unchanged, Changed, Resized, NoDisplay };
    // After a hotplug event: Changed (same size, the mode is set again),
    // Resized (new size: new buffers first), NoDisplay (nothing connected; idle).
    Hotplug reprobe();
    // Drains `source` and re-probes when it reported a connector hotplug.
    Hotplug follow(HotplugSource& source) { return source.read_hotplug() ? reprobe() : Hotplug::Unchanged; }

    // The keeper, for the crash handler (restore_on_crash); null before pick().
    DrmCrtcKeeper* keeper() { return keeper_.get(); }
    // Restores now (the teardown before the framebuffers go); idempotent.
    Status restore();
    // Flips queued so far (bench and tests).
    long flips() const { return flips_; }

private:
    // Picks from `probed`: false with `why` when nothing fits.
    bool pick_from(const std::vector<DrmProbedConnector>& probed, const ModeRequest& request, std::string& why);
    Status set_mode(uint32_t fb);
    Status flip(uint32_t fb);
    Status wait_flip();
    bool master_refused(int error);

    const DrmOps& ops_;
    int fd_;
    ModeRequest request_;
    DrmTarget target_;
    std::vector<drmModeModeInfo> modes_;  // the connector's modes when picked
    uint32_t mm_width_ = 0;
    bool has_output_ = false, active_ = true, need_mode_set_ = true, master_lost_ = false;
    long flips_ = 0;
    std::unique_ptr<DrmModeSetter> setter_;
    std::unique_ptr<DrmCrtcKeeper> keeper_;
};

}  // namespace body::platform
