#pragma once
// The operator mode behind the admin gesture, when the manifest sets
// `kiosk.operator_pin` (without it the gesture exits at once, as before): a
// PIN keypad, then a panel with the kiosk's diagnostics (frame time, the
// triangles the LOD drew, resident memory, uptime) and two buttons, restart
// (the kiosk exits; its service manager starts it again) and close, and the
// language set: which languages the visitors' language button offers. Modal:
// while it is open, only its controls answer. Three wrong PINs close it.
// State and layout only, no GL; KioskApp drives it (kiosk_operator.cpp).
#include <optional>
#include <string>
#include <vector>

#include "kiosk/app/ui.h"

namespace body::kiosk {

struct Diagnostics {
    double frame_ms = 0.0;  // mean of the frames reported since the panel opened (or the last one)
    size_t triangles = 0;   // drawn in the last reported frame
    std::string lod;        // "auto" or "manual"
    long rss_kib = -1;      // resident memory, -1 when unknown
    double uptime_s = 0.0;
};

class OperatorMode {
public:
    static constexpr int kMaxFailures = 3;
    enum class State { Closed, Pin, Open };

    explicit OperatorMode(std::string pin = {}) : pin_(std::move(pin)) {}
    bool enabled() const { return !pin_.empty(); }
    State state() const { return state_; }
    bool active() const { return state_ != State::Closed; }
    const std::string& entered() const { return entered_; }

    void open();  // the admin gesture: the keypad
    void close();
    // A keypad key: 0-9 a digit, kCancel, kOk. Returns true when the PIN was just accepted.
    static constexpr int kCancel = 10, kOk = 11;
    bool key(int k);
    void note_frame(double frame_ms, size_t triangles);
    Diagnostics diagnostics(double uptime_s, bool lod_auto) const;

    // The keypad (Pin) or the panel (Open), centred, for `ui`'s size; the
    // panel ends with one toggle per language of `languages` (on: active),
    // ControlId::OperatorLanguage with `group` its index.
    std::vector<Control> controls(const UiState& ui, const Diagnostics& d,
                                  const std::vector<std::pair<std::string, bool>>& languages = {}) const;

private:
    std::string pin_, entered_;
    State state_ = State::Closed;
    int failures_ = 0;
    double frame_ms_sum_ = 0.0;
    long frames_ = 0;
    size_t triangles_ = 0;
};

// The languages the operator can switch on: the manifest's, then the UI
// table's others (ui_words.h), each once.
std::vector<std::string> offered_languages(const std::vector<std::string>& scene_languages);

// This process's resident set size in KiB (/proc/self/statm), or -1.
long resident_kib();

}  // namespace body::kiosk
