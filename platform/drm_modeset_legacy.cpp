// Legacy mode setting and flips (contract in drm_modeset.h), as kmscube's
// drm-legacy.c: drmModeSetCrtc for the mode, drmModePageFlip with an event.
#include <cerrno>
#include <cstring>
#include <string>

#include "platform/drm_modeset.h"

namespace body::platform {
namespace {

class LegacyModeSetter final : public DrmModeSetter {
public:
    LegacyModeSetter(const DrmOps& ops, int fd) : ops_(ops), fd_(fd) {}
    const char* kind() const override { return "legacy"; }

    Status set_mode(const DrmTarget& target, uint32_t fb) override {
        target_ = target;
        if (ops_.set_crtc(fd_, target_.crtc, fb, 0, 0, &target_.connector, 1, &target_.mode) != 0)
            return runtime_error("drm: drmModeSetCrtc failed (" + std::string(std::strerror(errno)) + ")");
        return ok_status();
    }

    Status queue_flip(uint32_t fb, void* user_data) override {
        if (ops_.page_flip(fd_, target_.crtc, fb, DRM_MODE_PAGE_FLIP_EVENT, user_data) != 0)
            return runtime_error("drm: drmModePageFlip failed (" + std::string(std::strerror(errno)) + ")");
        return ok_status();
    }

private:
    const DrmOps& ops_;
    int fd_;
    DrmTarget target_;
};

}  // namespace

std::unique_ptr<DrmModeSetter> make_legacy_mode_setter(const DrmOps& ops, int fd) {
    return std::make_unique<LegacyModeSetter>(ops, fd);
}

}  // namespace body::platform
