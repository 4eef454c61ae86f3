#pragma once
// Input replay: timestamped input events that drive the kiosk headless
// (`bodyview --replay FILE`) and the replay tests. Two spellings of one format.
//
// Text, one event per line, '#' starts a comment, times in seconds, positions in
// pixels (origin top-left):
//   size 1280 800                  screen the positions refer to (optional, first)
//   0.000 down 1 640 400           touch down: id x y
//   0.016 move 1 650 400           touch move: id x y
//   0.100 up 1 650 400             touch up:   id x y
//   0.500 mouse-down left 100 80 shift    button (left|middle|right) x y [shift] [ctrl] [alt]
//   0.520 mouse-move 120 80
//   0.540 mouse-up left 120 80
//   0.600 wheel 640 400 1          x y notches
//   0.700 key 27                   platform key code (platform.h: ASCII, kKeyEscape, kKeyBackspace...)
//   0.710 text 252                 a typed character: its Unicode codepoint (here ü)
//   9.000 end                      keep running (idle) until this time, then stop
// JSON: {"size": [1280, 800], "events": [{"t": 0.0, "type": "down", "id": 1, "x": 640, "y": 400},
//        {"t": 0.5, "type": "mouse-down", "button": "left", "x": 100, "y": 80, "shift": true}, ...],
//        "end": 9.0}
// JSON spells a typed character {"t": 0.71, "type": "text", "key": 252}.
// Modifiers (shift, ctrl, alt; the keys held, as the glfw backend reports them)
// may follow any event's arguments in text and are boolean members in JSON; files
// without them stay valid and mean no modifier held.
// Events must be in non-decreasing time order, times (and `end`) within
// 0..kMaxReplaySeconds, so a replay always ends. Errors name the file and line
// (or event index).
#include <string>
#include <vector>

#include "kiosk/app/input.h"
#include "shared/error.h"

namespace body::kiosk {

inline constexpr double kMaxReplaySeconds = 3600.0;

struct Replay {
    int width = 0, height = 0;  // 0: not given
    std::vector<InputEvent> events;
    double end_time = 0.0;  // max(last event, `end`)
};

Result<Replay> parse_replay(const std::string& text, const std::string& source);
Result<Replay> read_replay(const std::string& path);

class KioskApp;
// Runs `replay` on `app` at `fps` frames per second from time `start`: events up to
// each frame's time are handled, then app.update(frame time). If `frame_cost_ms`
// is set it is called with the planned triangle count and its result reported as
// the frame time (simulated GPU cost). Returns the time of the last frame.
double run_replay(KioskApp& app, const Replay& replay, double fps = 60.0, double start = 0.0,
                  double (*frame_cost_ms)(size_t triangles) = nullptr);

}  // namespace body::kiosk
