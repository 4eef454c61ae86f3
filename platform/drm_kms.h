#pragma once
// Every kernel call the DRM/KMS backend makes for its display (not for its
// buffers: GBM and AddFB stay in drm_surface.cpp), as one table of plain
// functions: libdrm by default (real_drm_ops()), a fake device in the unit
// tests (tests/platform/drm_fake.h). Return values follow libdrm: 0 or a
// non-negative count on success, negative with errno set on failure.
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "platform/drm_select.h"

namespace body::platform {

// One (object, property, value) triple of an atomic request.
struct DrmAtomicProp {
    uint32_t object = 0, property = 0;
    uint64_t value = 0;
};

// A connector as probed: the description the selection reads (drm_select.h)
// and the kernel's mode records in the same order.
struct DrmProbedConnector {
    DrmConnector desc;
    std::vector<drmModeModeInfo> modes;
    uint32_t mm_width = 0;  // physical width; 0 when the display reports none
};

struct DrmOps {
    drmModeCrtc* (*get_crtc)(int fd, uint32_t crtc_id);
    void (*free_crtc)(drmModeCrtc* crtc);
    int (*set_crtc)(int fd, uint32_t crtc_id, uint32_t fb_id, uint32_t x, uint32_t y, uint32_t* connectors, int count,
                    drmModeModeInfo* mode);
    // poll(2) for POLLIN: > 0 readable, 0 timed out, < 0 error.
    int (*wait_readable)(int fd, int timeout_ms);
    int (*handle_event)(int fd, drmEventContext* context);
    // Atomic mode setting (after kmscube's drm-atomic.c).
    int (*set_client_cap)(int fd, uint64_t capability, uint64_t value);
    // The id of `object`'s property `name` (type: DRM_MODE_OBJECT_*), 0 when it has none.
    uint32_t (*property_id)(int fd, uint32_t object, uint32_t type, const char* name);
    // The primary plane that can scan out on `crtc_id`, 0 when none (needs universal planes).
    uint32_t (*primary_plane)(int fd, uint32_t crtc_id);
    int (*create_blob)(int fd, const void* data, size_t size, uint32_t* blob_id);
    int (*destroy_blob)(int fd, uint32_t blob_id);
    int (*atomic_commit)(int fd, const DrmAtomicProp* props, size_t count, uint32_t flags, void* user_data);
    // Legacy page flip.
    int (*page_flip)(int fd, uint32_t crtc_id, uint32_t fb_id, uint32_t flags, void* user_data);
    // Takes DRM master back after another process had it (direct opens only:
    // the seat manager handles master for libseat).
    int (*set_master)(int fd);
    // Every connector of the device, as it is now.
    std::vector<DrmProbedConnector> (*probe)(int fd);
};
// libdrm itself.
const DrmOps& real_drm_ops();

}  // namespace body::platform
