// Opening devices through the seat manager, or directly (contract in seat.h).
#include "platform/seat.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <map>

#ifdef BODY_WITH_SEAT
extern "C" {  // libseat.h declares C functions without a C++ guard
#include <libseat.h>
}
#endif

namespace body::platform {
namespace {

class DirectSeat final : public Seat {
public:
    int open_device(const std::string& path) override { return ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC); }
    void close_device(int fd) override { ::close(fd); }
    void dispatch() override {}
    bool active() const override { return true; }
    int activations() const override { return 1; }
    const char* kind() const override { return "direct"; }
};

#ifdef BODY_WITH_SEAT
class LibSeat final : public Seat {
public:
    static std::shared_ptr<LibSeat> open() {
        libseat_set_log_level(LIBSEAT_LOG_LEVEL_SILENT);
        auto seat = std::shared_ptr<LibSeat>(new LibSeat());
        static const libseat_seat_listener listener = {
            [](libseat*, void* self) { static_cast<LibSeat*>(self)->enable(); },
            [](libseat*, void* self) { static_cast<LibSeat*>(self)->disable(); }};
        seat->seat_ = libseat_open_seat(&listener, seat.get());
        if (!seat->seat_) return nullptr;
        // The seat is usable once enabled; a manager that never enables it is as good as none.
        for (int i = 0; i < 50 && !seat->active_; ++i)
            if (libseat_dispatch(seat->seat_, 100) < 0) break;
        if (!seat->active_) return nullptr;
        seat->name_ = std::string("libseat (") + libseat_seat_name(seat->seat_) + ")";
        return seat;
    }
    ~LibSeat() override {
        if (seat_) libseat_close_seat(seat_);
    }
    int open_device(const std::string& path) override {
        int fd = -1;
        const int id = libseat_open_device(seat_, path.c_str(), &fd);
        if (id < 0) return -1;
        // libseat's descriptor may be blocking; our readers expect O_NONBLOCK.
        ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
        ids_[fd] = id;
        return fd;
    }
    void close_device(int fd) override {
        if (auto it = ids_.find(fd); it != ids_.end()) {
            libseat_close_device(seat_, it->second);
            ids_.erase(it);
        }
        ::close(fd);
    }
    void dispatch() override { libseat_dispatch(seat_, 0); }
    bool active() const override { return active_; }
    int activations() const override { return activations_; }
    const char* kind() const override { return name_.c_str(); }
    int fd() const override { return libseat_get_fd(seat_); }

private:
    LibSeat() = default;
    void enable() {
        active_ = true;
        ++activations_;
    }
    // Another VT is shown: the devices are no longer ours until enable(). This
    // runs inside dispatch(), between frames, when the DRM surface has no flip
    // in flight (it waits for each), so the seat is given up at once; the
    // surface sees active() false and commits nothing (DrmDisplay::set_active).
    void disable() {
        active_ = false;
        libseat_disable_seat(seat_);
    }
    libseat* seat_ = nullptr;
    bool active_ = false;
    int activations_ = 0;
    std::string name_;
    std::map<int, int> ids_;  // fd -> libseat device id
};
#endif

}  // namespace

std::shared_ptr<Seat> Seat::open() {
#ifdef BODY_WITH_SEAT
    if (auto seat = LibSeat::open()) return seat;
#endif
    return std::make_shared<DirectSeat>();
}

}  // namespace body::platform
