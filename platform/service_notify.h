#pragma once
// Tells the service manager how the kiosk is doing (systemd Type=notify units,
// sd_notify(3)): READY=1 once the first frame has been presented, WATCHDOG=1
// while frames keep being presented (at most every quarter of the unit's
// WatchdogSec), STOPPING=1 on the way out. A loop or GPU that hangs stops the
// pings, and systemd restarts the service. Without $NOTIFY_SOCKET (not started
// by systemd) every call does nothing.
//
// Sent through libsystemd's sd_notify where the build found it (BODY_WITH_SYSTEMD),
// else with the same datagram written here (the protocol is stable and documented
// in sd_notify(3)), so a package built without libsystemd still starts.
#include <string>

namespace body::platform {

// Sends `state` (e.g. "READY=1") to $NOTIFY_SOCKET; false when there is none or it failed.
bool notify_service(const std::string& state);

class ServiceNotifier {
public:
    // Reads $NOTIFY_SOCKET and the watchdog interval ($WATCHDOG_USEC for this $WATCHDOG_PID).
    ServiceNotifier();
    bool active() const { return active_; }
    double watchdog_seconds() const { return watchdog_seconds_; }  // 0: no watchdog

    // After each presented frame; `now` is a monotonic time in seconds.
    void frame_presented(double now);
    // On the way out (any exit the process controls).
    void stopping();
    int pings() const { return pings_; }

private:
    bool active_ = false;
    bool ready_sent_ = false;
    double watchdog_seconds_ = 0.0;
    double last_ping_ = 0.0;
    int pings_ = 0;
};

}  // namespace body::platform
