#pragma once
// Display and input devices without root: the seat manager (libseat, which
// talks to seatd or logind) opens them for the session's user and takes them
// away while another VT is shown. Where no seat manager answers (or the build
// has no libseat, BODY_WITH_SEAT), devices are opened directly, which works as
// root or for members of the device's group (video for /dev/dri, input for
// /dev/input): the one-time setup is in README.md ("The kiosk as a service").
//
// active() is false while the seat is switched away (VT switch): the DRM
// surface stops flipping then and sets its mode again when it comes back.
#include <memory>
#include <string>

namespace body::platform {

class Seat {
public:
    // The seat manager's seat, or a direct-open seat when none answers (never null).
    static std::shared_ptr<Seat> open();
    virtual ~Seat() = default;
    // A file descriptor for `path` (read-write, non-blocking, close-on-exec), or -1 with errno set.
    virtual int open_device(const std::string& path) = 0;
    virtual void close_device(int fd) = 0;
    // Handles pending seat events without blocking (enable/disable on VT switches).
    virtual void dispatch() = 0;
    virtual bool active() const = 0;
    // Counts re-activations: the surface compares it to know it must set its mode again.
    virtual int activations() const = 0;
    virtual const char* kind() const = 0;  // "libseat (seat0)" or "direct"
    // Readable when seat events are pending (poll it while idle); -1 for none.
    virtual int fd() const { return -1; }
};

}  // namespace body::platform
