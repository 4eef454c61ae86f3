// Atomic mode setting and flips (contract in drm_modeset.h); the sequence is
// kmscube's drm-atomic.c: client caps, property ids of connector, CRTC and
// primary plane, a mode blob, TEST_ONLY, then ALLOW_MODESET; flips are
// NONBLOCK | PAGE_FLIP_EVENT commits of the plane's framebuffer.
#include <cerrno>
#include <cstring>
#include <string>

#include "platform/drm_modeset.h"

namespace body::platform {
namespace {

std::string errno_text() { return std::strerror(errno); }

class AtomicModeSetter final : public DrmModeSetter {
public:
    AtomicModeSetter(const DrmOps& ops, int fd, const DrmTarget& target, const DrmAtomicIds& ids)
        : ops_(ops), fd_(fd), target_(target), ids_(ids) {}
    ~AtomicModeSetter() override {
        if (blob_) ops_.destroy_blob(fd_, blob_);
    }
    const char* kind() const override { return "atomic"; }
    const DrmAtomicIds* atomic_ids() const override { return &ids_; }

    // Checks (TEST_ONLY) and then commits the full mode set; the mode blob of
    // the previous mode is dropped once the new one is on screen.
    Status set_mode(const DrmTarget& target, uint32_t fb) override {
        DrmAtomicIds ids = ids_;
        if ((target.connector != target_.connector || target.crtc != target_.crtc) &&
            !find_atomic_ids(ops_, fd_, target, ids))
            return runtime_error("drm: atomic: the new connector or CRTC lacks a property");
        uint32_t blob = 0;
        if (ops_.create_blob(fd_, &target.mode, sizeof target.mode, &blob) != 0)
            return runtime_error("drm: atomic: creating the mode blob failed (" + errno_text() + ")");
        DrmAtomicProp props[kMaxAtomicProps];
        const size_t n = atomic_mode_props(ids, target.connector, target.crtc, blob, fb, 0, 0, target.mode.hdisplay,
                                           target.mode.vdisplay, props);
        const uint32_t flags = DRM_MODE_ATOMIC_ALLOW_MODESET;
        if (ops_.atomic_commit(fd_, props, n, flags | DRM_MODE_ATOMIC_TEST_ONLY, nullptr) != 0 ||
            ops_.atomic_commit(fd_, props, n, flags, nullptr) != 0) {
            const std::string why = errno_text();
            ops_.destroy_blob(fd_, blob);
            return runtime_error("drm: atomic mode set failed (" + why + ")");
        }
        if (blob_) ops_.destroy_blob(fd_, blob_);
        blob_ = blob;
        target_ = target;
        ids_ = ids;
        return ok_status();
    }

    Status queue_flip(uint32_t fb, void* user_data) override {
        const DrmAtomicProp props[] = {{ids_.plane, ids_.plane_fb_id, fb},
                                       {ids_.plane, ids_.plane_crtc_id, target_.crtc}};
        if (ops_.atomic_commit(fd_, props, 2, DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT, user_data) != 0)
            return runtime_error("drm: atomic page flip failed (" + errno_text() + ")");
        return ok_status();
    }

private:
    const DrmOps& ops_;
    int fd_;
    DrmTarget target_;
    DrmAtomicIds ids_;
    uint32_t blob_ = 0;  // the mode on screen
};

}  // namespace

bool find_atomic_ids(const DrmOps& ops, int fd, const DrmTarget& target, DrmAtomicIds& ids) {
    ids.plane = ops.primary_plane(fd, target.crtc);
    if (!ids.plane) return false;
    auto plane = [&](const char* name) { return ops.property_id(fd, ids.plane, DRM_MODE_OBJECT_PLANE, name); };
    ids.connector_crtc_id = ops.property_id(fd, target.connector, DRM_MODE_OBJECT_CONNECTOR, "CRTC_ID");
    ids.crtc_mode_id = ops.property_id(fd, target.crtc, DRM_MODE_OBJECT_CRTC, "MODE_ID");
    ids.crtc_active = ops.property_id(fd, target.crtc, DRM_MODE_OBJECT_CRTC, "ACTIVE");
    ids.plane_fb_id = plane("FB_ID");
    ids.plane_crtc_id = plane("CRTC_ID");
    ids.src_x = plane("SRC_X");
    ids.src_y = plane("SRC_Y");
    ids.src_w = plane("SRC_W");
    ids.src_h = plane("SRC_H");
    ids.crtc_x = plane("CRTC_X");
    ids.crtc_y = plane("CRTC_Y");
    ids.crtc_w = plane("CRTC_W");
    ids.crtc_h = plane("CRTC_H");
    for (uint32_t id : {ids.connector_crtc_id, ids.crtc_mode_id, ids.crtc_active, ids.plane_fb_id, ids.plane_crtc_id,
                        ids.src_x, ids.src_y, ids.src_w, ids.src_h, ids.crtc_x, ids.crtc_y, ids.crtc_w, ids.crtc_h})
        if (id == 0) return false;
    return true;
}

size_t atomic_mode_props(const DrmAtomicIds& ids, uint32_t connector, uint32_t crtc, uint32_t mode_blob, uint32_t fb,
                         uint32_t x, uint32_t y, uint32_t width, uint32_t height, DrmAtomicProp* out) {
    size_t n = 0;
    auto add = [&](uint32_t object, uint32_t property, uint64_t value) { out[n++] = {object, property, value}; };
    const bool on = fb != 0;
    add(connector, ids.connector_crtc_id, on ? crtc : 0);
    add(crtc, ids.crtc_mode_id, on ? mode_blob : 0);
    add(crtc, ids.crtc_active, on ? 1 : 0);
    add(ids.plane, ids.plane_fb_id, fb);
    add(ids.plane, ids.plane_crtc_id, on ? crtc : 0);
    if (!on) return n;
    // Source rectangle in 16.16 fixed point, destination in pixels.
    add(ids.plane, ids.src_x, uint64_t{x} << 16);
    add(ids.plane, ids.src_y, uint64_t{y} << 16);
    add(ids.plane, ids.src_w, uint64_t{width} << 16);
    add(ids.plane, ids.src_h, uint64_t{height} << 16);
    add(ids.plane, ids.crtc_x, 0);
    add(ids.plane, ids.crtc_y, 0);
    add(ids.plane, ids.crtc_w, width);
    add(ids.plane, ids.crtc_h, height);
    return n;
}

std::unique_ptr<DrmModeSetter> make_atomic_mode_setter(const DrmOps& ops, int fd, const DrmTarget& target, uint32_t fb,
                                                       std::string& why) {
    // Atomic implies universal planes; the primary plane is only listed with them.
    if (ops.set_client_cap(fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1) != 0 ||
        ops.set_client_cap(fd, DRM_CLIENT_CAP_ATOMIC, 1) != 0) {
        why = "the driver has no atomic mode setting";
        return nullptr;
    }
    DrmAtomicIds ids;
    if (!find_atomic_ids(ops, fd, target, ids)) {
        why = "no primary plane or a missing property on connector, CRTC or plane";
        return nullptr;
    }
    uint32_t blob = 0;
    if (ops.create_blob(fd, &target.mode, sizeof target.mode, &blob) != 0) {
        why = "creating the mode blob failed (" + errno_text() + ")";
        return nullptr;
    }
    DrmAtomicProp props[kMaxAtomicProps];
    const size_t n = atomic_mode_props(ids, target.connector, target.crtc, blob, fb, 0, 0, target.mode.hdisplay,
                                       target.mode.vdisplay, props);
    const int rc = ops.atomic_commit(fd, props, n, DRM_MODE_ATOMIC_TEST_ONLY | DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr);
    if (rc != 0) why = "the TEST_ONLY commit was refused (" + errno_text() + ")";
    ops.destroy_blob(fd, blob);
    if (rc != 0) return nullptr;
    return std::make_unique<AtomicModeSetter>(ops, fd, target, ids);
}

std::unique_ptr<DrmModeSetter> choose_mode_setter(const DrmOps& ops, int fd, const DrmTarget& target, uint32_t fb,
                                                  std::string& why) {
    if (auto atomic = make_atomic_mode_setter(ops, fd, target, fb, why)) return atomic;
    // The atomic cap stays on: legacy calls work under it.
    return make_legacy_mode_setter(ops, fd);
}

}  // namespace body::platform
