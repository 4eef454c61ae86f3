#pragma once
// A fake KMS device behind DrmOps (platform/drm_kms.h) for the display tests:
// connectors to probe, one CRTC (41) with its primary plane (31), property ids,
// mode blobs, atomic and legacy commits that change what "the screen" shows,
// page flips whose events arrive at once, and DRM master. It refuses what the
// kernel refuses: a flip queued over a pending one (EBUSY, counted in
// flip_over_pending), any commit without master (EACCES), atomic without the
// cap, a TEST_ONLY commit when refuse_test_only is set.
#include <map>
#include <string>
#include <vector>

#include "platform/drm_kms.h"

namespace body::platform::fake {

struct Screen {
    uint32_t fb = 0;
    bool on = false;
    drmModeModeInfo mode{};
};

struct Kms {
    bool atomic = true;  // DRM_CLIENT_CAP_ATOMIC accepted
    bool refuse_test_only = false;
    bool refuse_atomic_restore = false;  // ALLOW_MODESET commits with the saved fb fail
    bool master = true;
    std::vector<DrmProbedConnector> connectors;
    Screen screen;  // CRTC 41
    // Every mode-setting commit (legacy set_crtc, atomic ALLOW_MODESET) and flip, in order:
    // "legacy-mode WxH fb N", "atomic-mode WxH fb N", "atomic-test", "legacy-flip fb N",
    // "atomic-flip fb N", "atomic-off", "legacy-off".
    std::vector<std::string> commits;
    std::map<uint32_t, drmModeModeInfo> blobs;  // live blobs
    uint32_t next_blob = 500;
    std::vector<void*> events;  // pending flip events (their user data)
    int flip_over_pending = 0;  // flips refused because one was in flight
    int set_master_calls = 0;
    int hold_events = 0;  // the next this many waits for an event time out
};
extern Kms g_kms;

const DrmOps& ops();
drmModeModeInfo mode(int width, int height, int hz, bool preferred = false);
// A connected HDMI connector 33 reaching CRTC 41 with `modes`, 500 mm wide.
DrmProbedConnector connector(uint32_t id, bool connected, std::vector<drmModeModeInfo> modes);
// The console's 1920x1080 framebuffer 7 on CRTC 41, HDMI 33 connected with 1920x1080 (preferred) and 1280x720.
void reset();
// How many commits in g_kms.commits start with `prefix`.
int count(const std::string& prefix);

}  // namespace body::platform::fake
