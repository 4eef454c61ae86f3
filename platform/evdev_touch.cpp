// evdev multitouch (protocol B, Documentation/input/multi-touch-protocol.rst)
// with SYN_DROPPED resync (Documentation/input/event-codes.rst) and hotplug.
#include "platform/evdev_touch.h"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "platform/log.h"

namespace body::platform {

// ---- mapping -------------------------------------------------------------------

void map_touch(const TouchMapping& m, int raw_x, int raw_y, float& x, float& y) {
    const float span_x = static_cast<float>(std::max(m.max_x - m.min_x, 1));
    const float span_y = static_cast<float>(std::max(m.max_y - m.min_y, 1));
    const float nu = static_cast<float>(raw_x - m.min_x) / span_x, nv = static_cast<float>(raw_y - m.min_y) / span_y;
    const auto& c = m.calibration;
    const float u = std::clamp(c[0] * nu + c[1] * nv + c[2], 0.0f, 1.0f);
    const float v = std::clamp(c[3] * nu + c[4] * nv + c[5], 0.0f, 1.0f);
    float sx = u, sy = v;
    switch (m.rotation) {
        case 90: sx = 1.0f - v, sy = u; break;
        case 180: sx = 1.0f - u, sy = 1.0f - v; break;
        case 270: sx = v, sy = 1.0f - u; break;
        default: break;
    }
    x = sx * static_cast<float>(m.width - 1);
    y = sy * static_cast<float>(m.height - 1);
}

Result<int> parse_rotation(const std::string& text) {
    if (text == "0" || text == "90" || text == "180" || text == "270") return std::stoi(text);
    return input_error("--rotate: expected 0, 90, 180 or 270, got '" + text + "'");
}

Result<std::array<float, 6>> parse_calibration(const std::string& text) {
    std::array<float, 6> c{};
    std::string t = text;
    std::replace(t.begin(), t.end(), ',', ' ');
    char extra = 0;
    const bool read =
        std::sscanf(t.c_str(), "%f %f %f %f %f %f %c", &c[0], &c[1], &c[2], &c[3], &c[4], &c[5], &extra) == 6;
    const bool finite = std::all_of(c.begin(), c.end(), [](float x) { return std::isfinite(x); });
    if (!read || !finite || std::abs(c[0] * c[4] - c[1] * c[3]) < 1e-6f)
        return input_error("--touch-calibration: expected six numbers 'A B C D E F' with A*E - B*D not 0, got '" +
                           text + "'");
    return c;
}

// ---- protocol B ------------------------------------------------------------------

MtProtocolB::MtProtocolB(int slot_count, int device_number)
    : reported_(static_cast<size_t>(std::clamp(slot_count, 1, kMaxSlots))),
      pending_(reported_.size()),
      device_number_(device_number) {}

int MtProtocolB::active_contacts() const {
    return static_cast<int>(
        std::count_if(reported_.begin(), reported_.end(), [](const MtSlot& s) { return s.tracking_id >= 0; }));
}

void MtProtocolB::emit_frame(double time, std::vector<InputEvent>& out) {
    for (size_t i = 0; i < reported_.size(); ++i) {
        const MtSlot& was = reported_[i];
        const MtSlot& now = pending_[i];
        InputEvent e;
        e.time = time;
        if (was.tracking_id >= 0 && was.tracking_id != now.tracking_id) {
            e.type = InputEvent::Type::TouchUp;
            e.id = contact_id(was.tracking_id);
            map_touch(mapping_, was.x, was.y, e.x, e.y);
            out.push_back(e);
        }
        if (now.tracking_id >= 0) {
            if (was.tracking_id != now.tracking_id) {
                e.type = InputEvent::Type::TouchDown;
            } else if (was.x != now.x || was.y != now.y) {
                e.type = InputEvent::Type::TouchMove;
            } else {
                continue;
            }
            e.id = contact_id(now.tracking_id);
            map_touch(mapping_, now.x, now.y, e.x, e.y);
            out.push_back(e);
        }
    }
    reported_ = pending_;
}

void MtProtocolB::feed(const input_event& ev, double time, std::vector<InputEvent>& out) {
    if (ev.type == EV_SYN && ev.code == SYN_DROPPED) {
        // The kernel buffer overflowed: this frame and the state are unknown.
        dropped_ = true;
        skipping_ = true;
        pending_ = reported_;
        return;
    }
    if (skipping_) {
        if (ev.type == EV_SYN && ev.code == SYN_REPORT) skipping_ = false;
        return;
    }
    if (ev.type == EV_SYN && ev.code == SYN_REPORT) {
        if (!dropped_) emit_frame(time, out);  // until resync the deltas would be against a stale state
        return;
    }
    if (ev.type != EV_ABS) return;
    switch (ev.code) {
        case ABS_MT_SLOT: slot_ = ev.value; break;
        case ABS_MT_TRACKING_ID:
            if (slot_ >= 0 && slot_ < slot_count())
                pending_[static_cast<size_t>(slot_)].tracking_id = ev.value < 0 ? -1 : ev.value;
            break;
        case ABS_MT_POSITION_X:
            if (slot_ >= 0 && slot_ < slot_count()) pending_[static_cast<size_t>(slot_)].x = ev.value;
            break;
        case ABS_MT_POSITION_Y:
            if (slot_ >= 0 && slot_ < slot_count()) pending_[static_cast<size_t>(slot_)].y = ev.value;
            break;
        default: break;
    }
}

void MtProtocolB::resync(std::span<const MtSlot> slots, double time, std::vector<InputEvent>& out) {
    for (size_t i = 0; i < pending_.size(); ++i) pending_[i] = i < slots.size() ? slots[i] : MtSlot{};
    dropped_ = false;
    skipping_ = false;
    emit_frame(time, out);
}

void MtProtocolB::release_all(double time, std::vector<InputEvent>& out) {
    for (MtSlot& s : pending_) s.tracking_id = -1;
    dropped_ = skipping_ = false;
    emit_frame(time, out);
}

// ---- devices -------------------------------------------------------------------

struct EvdevInput::Device {
    std::string path;
    int fd = -1;
    libevdev* dev = nullptr;
    MtProtocolB protocol;
    const EvdevInput* owner;
    Device(std::string p, int f, libevdev* d, int slots, int number, const EvdevInput* o)
        : path(std::move(p)), fd(f), dev(d), protocol(slots, number), owner(o) {}
    ~Device() {
        if (dev) libevdev_free(dev);
        if (fd >= 0) owner->close_node(fd);
    }
};

int EvdevInput::open_node(const std::string& path) const {
    return options_.open_device ? options_.open_device(path) : ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
}

void EvdevInput::close_node(int fd) const {
    if (options_.close_device)
        options_.close_device(fd);
    else
        ::close(fd);
}

Result<std::unique_ptr<EvdevInput>> EvdevInput::open(const EvdevOptions& options) {
    std::unique_ptr<EvdevInput> input(new EvdevInput());
    input->options_ = options;
    input->inotify_fd_ = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (input->inotify_fd_ < 0) return runtime_error(std::string("inotify: ") + std::strerror(errno));
    if (::inotify_add_watch(input->inotify_fd_, options.directory.c_str(), IN_CREATE | IN_ATTRIB | IN_DELETE) < 0) {
        return runtime_error(options.directory + ": cannot watch for input devices: " + std::strerror(errno));
    }
    input->scan();
    return input;
}

EvdevInput::~EvdevInput() {
    devices_.clear();
    if (inotify_fd_ >= 0) ::close(inotify_fd_);
}

size_t EvdevInput::device_count() const { return devices_.size(); }

std::vector<std::string> EvdevInput::device_paths() const {
    std::vector<std::string> out;
    for (const auto& d : devices_) out.push_back(d->path);
    return out;
}

void EvdevInput::scan() {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(options_.directory, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("event", 0) == 0) add_device(entry.path().string());
    }
}

void EvdevInput::add_device(const std::string& path) {
    for (const auto& d : devices_) {
        if (d->path == path) return;
    }
    const int fd = open_node(path);
    if (fd < 0) return;  // not (yet) readable: udev may fix permissions later (IN_ATTRIB)
    libevdev* dev = nullptr;
    if (libevdev_new_from_fd(fd, &dev) < 0) {
        close_node(fd);
        return;
    }
    const bool touch = libevdev_has_event_code(dev, EV_ABS, ABS_MT_SLOT) &&
                       libevdev_has_event_code(dev, EV_ABS, ABS_MT_POSITION_X) &&
                       libevdev_has_event_code(dev, EV_ABS, ABS_MT_POSITION_Y);
    if (!touch) {
        libevdev_free(dev);
        close_node(fd);
        return;
    }
    const int slots = libevdev_get_num_slots(dev);
    auto device = std::make_unique<Device>(path, fd, dev, slots > 0 ? slots : 10, next_number_++, this);
    TouchMapping m;
    const input_absinfo* ax = libevdev_get_abs_info(dev, ABS_MT_POSITION_X);
    const input_absinfo* ay = libevdev_get_abs_info(dev, ABS_MT_POSITION_Y);
    if (ax) m.min_x = ax->minimum, m.max_x = ax->maximum;
    if (ay) m.min_y = ay->minimum, m.max_y = ay->maximum;
    m.width = options_.width;
    m.height = options_.height;
    m.rotation = options_.rotation;
    m.calibration = options_.calibration;
    device->protocol.set_mapping(m);
    if (log_enabled(LogLevel::Info))
        std::fprintf(stderr, "bodyview: touch device %s (%s, %d slots)\n", path.c_str(), libevdev_get_name(dev), slots);
    devices_.push_back(std::move(device));
}

void EvdevInput::remove_device(size_t index, double now, std::vector<InputEvent>& out) {
    devices_[index]->protocol.release_all(now, out);
    std::fprintf(stderr, "bodyview: touch device %s removed\n", devices_[index]->path.c_str());
    devices_.erase(devices_.begin() + static_cast<long>(index));
}

void EvdevInput::read_device(size_t index, double now, std::vector<InputEvent>& out) {
    Device& d = *devices_[index];
    input_event ev;
    for (;;) {
        int rc = libevdev_next_event(d.dev, LIBEVDEV_READ_FLAG_NORMAL, &ev);
        if (rc == LIBEVDEV_READ_STATUS_SYNC) {
            // ev is SYN_DROPPED: let libevdev catch up, then diff its slot state.
            d.protocol.feed(ev, now, out);
            while (libevdev_next_event(d.dev, LIBEVDEV_READ_FLAG_SYNC, &ev) == LIBEVDEV_READ_STATUS_SYNC) {
            }
            std::vector<MtSlot> slots(static_cast<size_t>(d.protocol.slot_count()));
            for (size_t s = 0; s < slots.size(); ++s) {
                const int slot = static_cast<int>(s);
                slots[s].tracking_id = libevdev_get_slot_value(d.dev, static_cast<unsigned>(slot), ABS_MT_TRACKING_ID);
                slots[s].x = libevdev_get_slot_value(d.dev, static_cast<unsigned>(slot), ABS_MT_POSITION_X);
                slots[s].y = libevdev_get_slot_value(d.dev, static_cast<unsigned>(slot), ABS_MT_POSITION_Y);
            }
            d.protocol.resync(slots, now, out);
            continue;
        }
        if (rc == LIBEVDEV_READ_STATUS_SUCCESS) {
            d.protocol.feed(ev, now, out);
            continue;
        }
        if (rc == -EAGAIN) return;
        remove_device(index, now, out);  // -ENODEV: unplugged
        return;
    }
}

void EvdevInput::poll(double now, std::vector<InputEvent>& out) {
    if (inotify_fd_ >= 0) {
        alignas(inotify_event) char buf[4096];
        for (;;) {
            const ssize_t n = ::read(inotify_fd_, buf, sizeof buf);
            if (n <= 0) break;
            for (ssize_t off = 0; off < n;) {
                const auto* ie = reinterpret_cast<const inotify_event*>(buf + off);
                off += static_cast<ssize_t>(sizeof(inotify_event) + ie->len);
                if (ie->len == 0) continue;
                const std::string name = ie->name;
                if (name.rfind("event", 0) != 0) continue;
                const std::string path = options_.directory + "/" + name;
                if (ie->mask & IN_DELETE) {
                    for (size_t i = 0; i < devices_.size(); ++i) {
                        if (devices_[i]->path == path) {
                            remove_device(i, now, out);
                            break;
                        }
                    }
                } else {
                    add_device(path);
                }
            }
        }
    }
    for (size_t i = devices_.size(); i-- > 0;) read_device(i, now, out);
}

}  // namespace body::platform
