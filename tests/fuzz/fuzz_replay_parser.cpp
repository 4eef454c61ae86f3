// libFuzzer target for replay files (text and JSON): a replay or one error
// line naming the file, never a crash; an accepted replay ends in time.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "kiosk/app/replay.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    auto replay = body::kiosk::parse_replay(text, "fuzz.replay");
    if (!replay.ok()) {
        const std::string& m = replay.error().message;
        if (m.rfind("fuzz.replay", 0) != 0 || m.find('\n') != std::string::npos) std::abort();
        return 0;
    }
    if (!(replay->end_time >= 0.0 && replay->end_time <= body::kiosk::kMaxReplaySeconds)) std::abort();
    return 0;
}
