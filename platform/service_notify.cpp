// Service manager notifications (contract in service_notify.h).
#include "platform/service_notify.h"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>

#ifdef BODY_WITH_SYSTEMD
#include <systemd/sd-daemon.h>
#endif

namespace body::platform {
namespace {

#ifndef BODY_WITH_SYSTEMD
// sd_notify(3)'s datagram: the state string to the AF_UNIX socket named by
// $NOTIFY_SOCKET ('@' first: the abstract namespace).
bool send_datagram(const std::string& state) {
    const char* path = std::getenv("NOTIFY_SOCKET");
    if (!path || (path[0] != '/' && path[0] != '@')) return false;
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    const size_t len = std::strlen(path);
    if (len >= sizeof addr.sun_path) return false;
    std::memcpy(addr.sun_path, path, len);
    if (addr.sun_path[0] == '@') addr.sun_path[0] = '\0';
    const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return false;
    const auto addr_len = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + len);
    const bool sent = ::sendto(fd, state.data(), state.size(), MSG_NOSIGNAL, reinterpret_cast<sockaddr*>(&addr),
                               addr_len) == static_cast<ssize_t>(state.size());
    ::close(fd);
    return sent;
}
#endif

// The watchdog interval in seconds when it is meant for this process, else 0.
double watchdog_interval() {
#ifdef BODY_WITH_SYSTEMD
    uint64_t usec = 0;
    return sd_watchdog_enabled(0, &usec) > 0 ? static_cast<double>(usec) * 1e-6 : 0.0;
#else
    const char* usec = std::getenv("WATCHDOG_USEC");
    const char* pid = std::getenv("WATCHDOG_PID");
    if (!usec || (pid && std::strtol(pid, nullptr, 10) != ::getpid())) return 0.0;
    return static_cast<double>(std::strtoull(usec, nullptr, 10)) * 1e-6;
#endif
}

}  // namespace

bool notify_service(const std::string& state) {
#ifdef BODY_WITH_SYSTEMD
    return sd_notify(0, state.c_str()) > 0;
#else
    return send_datagram(state);
#endif
}

ServiceNotifier::ServiceNotifier() {
    const char* socket = std::getenv("NOTIFY_SOCKET");
    active_ = socket && *socket;
    watchdog_seconds_ = active_ ? watchdog_interval() : 0.0;
}

void ServiceNotifier::frame_presented(double now) {
    if (!active_) return;
    if (!ready_sent_) {
        ready_sent_ = notify_service("READY=1\nSTATUS=showing the exhibit");
        last_ping_ = now;
        return;
    }
    // A quarter of the interval: two missed pings still leave time before systemd acts.
    if (watchdog_seconds_ > 0.0 && now - last_ping_ >= 0.25 * watchdog_seconds_) {
        if (notify_service("WATCHDOG=1")) ++pings_;
        last_ping_ = now;
    }
}

void ServiceNotifier::stopping() {
    if (active_) notify_service("STOPPING=1");
}

}  // namespace body::platform
