// Connector hotplug from udev (contract in drm_hotplug.h).
#include "platform/drm_hotplug.h"

#include <climits>
#include <cstdlib>
#include <cstring>

#ifdef BODY_WITH_UDEV
#include <libudev.h>
#endif

namespace body::platform {
namespace {

#ifdef BODY_WITH_UDEV
class UdevHotplug final : public HotplugSource {
public:
    UdevHotplug(udev* context, udev_monitor* monitor, std::string card)
        : udev_(context), monitor_(monitor), card_(std::move(card)) {}
    ~UdevHotplug() override {
        udev_monitor_unref(monitor_);
        udev_unref(udev_);
    }
    int fd() const override { return udev_monitor_get_fd(monitor_); }
    bool read_hotplug() override {
        bool hotplug = false;
        // The monitor's socket is non-blocking: this ends when the queue is empty.
        while (udev_device* d = udev_monitor_receive_device(monitor_)) {
            hotplug |= is_connector_hotplug(udev_device_get_action(d), udev_device_get_property_value(d, "HOTPLUG"),
                                            udev_device_get_devnode(d), card_);
            udev_device_unref(d);
        }
        return hotplug;
    }

private:
    udev* udev_;
    udev_monitor* monitor_;
    std::string card_;
};
#endif

}  // namespace

bool is_connector_hotplug(const char* action, const char* hotplug, const char* devnode, const std::string& card) {
    if (!action || std::strcmp(action, "change") != 0) return false;
    if (!hotplug || std::strcmp(hotplug, "1") != 0) return false;
    return !devnode || card == devnode;
}

std::unique_ptr<HotplugSource> open_udev_hotplug(const std::string& card, std::string& why) {
#ifdef BODY_WITH_UDEV
    char resolved[PATH_MAX];
    const std::string path = ::realpath(card.c_str(), resolved) ? std::string(resolved) : card;
    udev* context = udev_new();
    if (!context) {
        why = "udev_new failed";
        return nullptr;
    }
    udev_monitor* monitor = udev_monitor_new_from_netlink(context, "udev");
    if (!monitor || udev_monitor_filter_add_match_subsystem_devtype(monitor, "drm", "drm_minor") < 0 ||
        udev_monitor_enable_receiving(monitor) < 0) {
        if (monitor) udev_monitor_unref(monitor);
        udev_unref(context);
        why = "no udev monitor (netlink)";
        return nullptr;
    }
    return std::make_unique<UdevHotplug>(context, monitor, path);
#else
    (void)card;
    why = "built without libudev (libudev-dev)";
    return nullptr;
#endif
}

}  // namespace body::platform
