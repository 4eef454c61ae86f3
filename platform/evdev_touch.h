#pragma once
// Touch input from Linux evdev devices (multitouch protocol B), with libevdev:
// the touchscreens of the DRM and GLFW backends (platform.h: poll_events).
//
// Split in two so the protocol logic is testable without a device:
//   - MtProtocolB: a pure state machine fed kernel `input_event`s. It keeps the
//     slot states, and on each SYN_REPORT emits TouchDown/Move/Up for the slots
//     that changed. After SYN_DROPPED it ignores events up to and including the
//     next SYN_REPORT (kernel contract) and waits for resync() with the device's
//     current slot states, from which it emits the differences (lifted fingers
//     go up, new ones go down, moved ones move).
//   - EvdevInput: opens every touchscreen under /dev/input (event*, with
//     ABS_MT_SLOT and ABS_MT_POSITION_X/Y), follows devices added and removed
//     while running (inotify), reads with libevdev and resyncs through it.
// Touch ids are unique across devices while a finger is down: device number
// * 65536 + tracking id (16 bits).
//
// Coordinates: raw axis ranges are normalised to [0, 1], calibrated by a 2x3
// matrix [a b c; d e f] (u' = a u + b v + c, v' = d u + e v + f: libinput's
// LIBINPUT_CALIBRATION_MATRIX convention; identity by default), clamped, and
// rotated into the screen. `rotation` (0, 90, 180, 270) is how far the picture is turned clockwise
// relative to the panel's native axes: at 90, the panel's top-left corner is
// the screen's top-right corner.
#include <linux/input.h>

#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "platform/platform.h"
#include "shared/error.h"

namespace body::platform {

struct TouchMapping {
    int min_x = 0, max_x = 4095, min_y = 0, max_y = 4095;  // raw axis ranges (inclusive)
    int width = 1280, height = 800;                        // screen pixels
    int rotation = 0;                                      // 0, 90, 180 or 270
    std::array<float, 6> calibration{1, 0, 0, 0, 1, 0};    // see above
};

// Raw device coordinates to screen pixels (origin top-left); clamps to the screen.
void map_touch(const TouchMapping& mapping, int raw_x, int raw_y, float& x, float& y);
Result<int> parse_rotation(const std::string& text);
// Six numbers separated by spaces or commas ("1 0 0 0 1 0"); finite, an invertible 2x2 part.
Result<std::array<float, 6>> parse_calibration(const std::string& text);

struct MtSlot {
    int tracking_id = -1;  // -1: no contact
    int x = 0, y = 0;      // raw
};

class MtProtocolB {
public:
    static constexpr int kMaxSlots = 64;
    explicit MtProtocolB(int slot_count = 16, int device_number = 0);
    void set_mapping(const TouchMapping& mapping) { mapping_ = mapping; }
    const TouchMapping& mapping() const { return mapping_; }

    // Feeds one event; on SYN_REPORT appends the frame's touch events to `out`.
    void feed(const input_event& event, double time, std::vector<InputEvent>& out);
    // True after SYN_DROPPED until resync().
    bool needs_resync() const { return dropped_; }
    // The device's slot states after a drop (index = slot); emits the differences.
    void resync(std::span<const MtSlot> slots, double time, std::vector<InputEvent>& out);
    // The device went away: every active contact goes up.
    void release_all(double time, std::vector<InputEvent>& out);
    int active_contacts() const;
    int slot_count() const { return static_cast<int>(reported_.size()); }

private:
    int contact_id(int tracking_id) const { return device_number_ * 65536 + (tracking_id & 0xFFFF); }
    void emit_frame(double time, std::vector<InputEvent>& out);

    std::vector<MtSlot> reported_;  // what the app was told
    std::vector<MtSlot> pending_;   // accumulating the current frame
    int slot_ = 0;
    int device_number_ = 0;
    bool dropped_ = false;   // SYN_DROPPED seen: waiting for resync()
    bool skipping_ = false;  // ignoring events up to and including the next SYN_REPORT
    TouchMapping mapping_;
};

struct EvdevOptions {
    std::string directory = "/dev/input";
    int width = 1280, height = 800;
    int rotation = 0;
    std::array<float, 6> calibration{1, 0, 0, 0, 1, 0};
    // How device nodes are opened and closed (the seat manager, platform/seat.h);
    // empty: open(2) read-only and close(2).
    std::function<int(const std::string& path)> open_device = {};
    std::function<void(int fd)> close_device = {};
};

class EvdevInput {
public:
    // Opens the touchscreens present now and starts watching for more. No device
    // is not an error (one may be plugged in later); an unreadable directory is.
    static Result<std::unique_ptr<EvdevInput>> open(const EvdevOptions& options);
    ~EvdevInput();
    EvdevInput(const EvdevInput&) = delete;
    EvdevInput& operator=(const EvdevInput&) = delete;

    // Non-blocking: handles hotplug and appends touch events. `now` is the
    // caller's clock (Surface::time()).
    void poll(double now, std::vector<InputEvent>& out);
    size_t device_count() const;
    std::vector<std::string> device_paths() const;

private:
    struct Device;
    EvdevInput() = default;
    void scan();
    void add_device(const std::string& path);
    void remove_device(size_t index, double now, std::vector<InputEvent>& out);
    void read_device(size_t index, double now, std::vector<InputEvent>& out);
    int open_node(const std::string& path) const;
    void close_node(int fd) const;

    EvdevOptions options_;
    int inotify_fd_ = -1;
    int next_number_ = 0;
    std::vector<std::unique_ptr<Device>> devices_;
};

}  // namespace body::platform
