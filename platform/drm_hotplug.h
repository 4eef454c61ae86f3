#pragma once
// Connector hotplug events: the kernel's "change" uevent on the DRM card with
// HOTPLUG=1 (a monitor plugged, unplugged, or showing other modes), read from a
// udev monitor (libudev, BODY_WITH_UDEV). The DRM surface polls fd() with its
// other descriptors and, on read_hotplug(), has DrmDisplay::reprobe() re-read the
// connectors. The unit tests feed a fake source into the same path.
#include <memory>
#include <string>

namespace body::platform {

class HotplugSource {
public:
    virtual ~HotplugSource() = default;
    // Readable (POLLIN) when events are pending.
    virtual int fd() const = 0;
    // Reads every pending event without blocking; true when one was a
    // connector hotplug on the watched card.
    virtual bool read_hotplug() = 0;
};

// Whether a uevent is a connector hotplug on `card` (a /dev/dri/cardN path with
// symlinks resolved): action "change", HOTPLUG=1, device node `card` (any DRM
// node when the event names none). Null arguments are absent fields.
bool is_connector_hotplug(const char* action, const char* hotplug, const char* devnode, const std::string& card);

// A udev monitor on the drm subsystem for `card`, or nullptr with `why` (built
// without libudev, or no netlink socket): hotplug then goes unnoticed.
std::unique_ptr<HotplugSource> open_udev_hotplug(const std::string& card, std::string& why);

}  // namespace body::platform
