#pragma once
// Mode setting and page flips behind one small interface, two ways: atomic
// (drm_modeset_atomic.cpp, after kmscube's drm-atomic.c: one request sets
// connector, CRTC and primary plane together, a TEST_ONLY commit checks it
// first) when the driver accepts DRM_CLIENT_CAP_ATOMIC, legacy otherwise
// (drm_modeset_legacy.cpp: drmModeSetCrtc, drmModePageFlip). All kernel calls
// go through DrmOps (drm_kms.h). The caller keeps at most one flip in flight
// (drm_display.h); a flip's event carries `user_data`.
#include <cstdint>
#include <memory>

#include "platform/drm_kms.h"
#include "shared/error.h"

namespace body::platform {

// What is shown where: the connector, the CRTC driving it, and its mode.
struct DrmTarget {
    uint32_t connector = 0, crtc = 0;
    drmModeModeInfo mode{};
};

// The property ids of one connector/CRTC/primary-plane triple (atomic only).
struct DrmAtomicIds {
    uint32_t plane = 0;
    uint32_t connector_crtc_id = 0;
    uint32_t crtc_mode_id = 0, crtc_active = 0;
    uint32_t plane_fb_id = 0, plane_crtc_id = 0;
    uint32_t src_x = 0, src_y = 0, src_w = 0, src_h = 0;
    uint32_t crtc_x = 0, crtc_y = 0, crtc_w = 0, crtc_h = 0;
};

// Looks the ids up for `target`; false names nothing: some id is missing.
bool find_atomic_ids(const DrmOps& ops, int fd, const DrmTarget& target, DrmAtomicIds& ids);

// The request of a full mode set (kmscube's drm_atomic_commit with a mode):
// `fb` scanned out whole at `width` x `height` from (x, y) on `crtc` through
// `connector`, mode blob `mode_blob`. With fb == 0: connector, CRTC and plane off.
// Returns the number of props written into `out` (at most kMaxAtomicProps).
inline constexpr size_t kMaxAtomicProps = 14;
size_t atomic_mode_props(const DrmAtomicIds& ids, uint32_t connector, uint32_t crtc, uint32_t mode_blob, uint32_t fb,
                         uint32_t x, uint32_t y, uint32_t width, uint32_t height, DrmAtomicProp* out);

class DrmModeSetter {
public:
    virtual ~DrmModeSetter() = default;
    virtual const char* kind() const = 0;  // "atomic" or "legacy"
    // A full mode set of `target` showing `fb`; blocks until it is on screen.
    virtual Status set_mode(const DrmTarget& target, uint32_t fb) = 0;
    // Queues `fb` for the next vertical blank with a flip event (non-blocking).
    virtual Status queue_flip(uint32_t fb, void* user_data) = 0;
    // Atomic: the ids the display restore uses (DrmCrtcKeeper::use_atomic); legacy: nullptr.
    virtual const DrmAtomicIds* atomic_ids() const { return nullptr; }
};

// Atomic when the driver has it and a TEST_ONLY commit of `target` showing
// `fb` passes; otherwise nullptr and `why` says what was missing.
std::unique_ptr<DrmModeSetter> make_atomic_mode_setter(const DrmOps& ops, int fd, const DrmTarget& target, uint32_t fb,
                                                       std::string& why);
std::unique_ptr<DrmModeSetter> make_legacy_mode_setter(const DrmOps& ops, int fd);

// Atomic when make_atomic_mode_setter gives one, else legacy (with `why` filled).
std::unique_ptr<DrmModeSetter> choose_mode_setter(const DrmOps& ops, int fd, const DrmTarget& target, uint32_t fb,
                                                  std::string& why);

}  // namespace body::platform
