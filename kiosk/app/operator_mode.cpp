// The operator mode's keypad, panel and PIN check (contract in operator_mode.h).
#include "kiosk/app/operator_mode.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "kiosk/app/ui_words.h"

namespace body::kiosk {

void OperatorMode::open() {
    if (!enabled()) return;
    state_ = State::Pin;
    entered_.clear();
}

void OperatorMode::close() {
    state_ = State::Closed;
    entered_.clear();
    failures_ = 0;
}

bool OperatorMode::key(int k) {
    if (state_ != State::Pin) return false;
    if (k == kCancel) {
        close();
    } else if (k == kOk) {
        if (entered_ == pin_) {
            state_ = State::Open;
            entered_.clear();
            failures_ = 0;
            frame_ms_sum_ = 0.0;
            frames_ = 0;
            return true;
        }
        entered_.clear();
        if (++failures_ >= kMaxFailures) close();
    } else if (k >= 0 && k <= 9 && entered_.size() < 16) {
        entered_.push_back(static_cast<char>('0' + k));
    }
    return false;
}

void OperatorMode::note_frame(double frame_ms, size_t triangles) {
    frame_ms_sum_ += frame_ms;
    ++frames_;
    triangles_ = triangles;
}

Diagnostics OperatorMode::diagnostics(double uptime_s, bool lod_auto) const {
    Diagnostics d;
    d.frame_ms = frames_ ? frame_ms_sum_ / static_cast<double>(frames_) : 0.0;
    d.triangles = triangles_;
    d.lod = lod_auto ? "auto" : "manual";
    d.rss_kib = resident_kib();
    d.uptime_s = uptime_s;
    return d;
}

std::vector<Control> OperatorMode::controls(const UiState& ui, const Diagnostics& d,
                                            const std::vector<std::pair<std::string, bool>>& languages) const {
    std::vector<Control> out;
    const float b = button_size(ui);
    const float gap = std::floor(b * 0.15f);
    const float w = static_cast<float>(ui.width), h = static_cast<float>(ui.height);
    auto add = [&](ControlId id, int group, Rect r, std::string text, bool active = false) {
        Control c;
        c.id = id;
        c.group = group;
        c.rect = r;
        c.text = std::move(text);
        c.active = active;
        out.push_back(std::move(c));
    };
    if (state_ == State::Pin) {
        // A display row, then 1-9 and cancel, 0, OK in a 3 x 4 grid.
        const float kw = std::floor(b * 1.4f), x0 = (w - 3 * kw - 2 * gap) * 0.5f;
        const float y0 = std::max(gap, (h - 5 * b - 4 * gap) * 0.5f);
        add(ControlId::OperatorInfo, -1, Rect{x0, y0, 3 * kw + 2 * gap, b}, "PIN " + std::string(entered_.size(), '*'),
            true);
        const int keys[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, kCancel, 0, kOk};
        for (int i = 0; i < 12; ++i) {
            const Rect r{x0 + static_cast<float>(i % 3) * (kw + gap), y0 + static_cast<float>(1 + i / 3) * (b + gap),
                         kw, b};
            const std::string text = keys[i] == kCancel ? "Cancel" : keys[i] == kOk ? "OK" : std::to_string(keys[i]);
            add(ControlId::OperatorKey, keys[i], r, text);
        }
    } else if (state_ == State::Open) {
        char lines[4][96];
        std::snprintf(lines[0], sizeof lines[0], "Frame %.1f ms", d.frame_ms);
        std::snprintf(lines[1], sizeof lines[1], "%zu triangles, LOD %s", d.triangles, d.lod.c_str());
        if (d.rss_kib >= 0) {
            std::snprintf(lines[2], sizeof lines[2], "Memory %.1f MiB", static_cast<double>(d.rss_kib) / 1024.0);
        } else {
            std::snprintf(lines[2], sizeof lines[2], "Memory unknown");
        }
        const long up = static_cast<long>(d.uptime_s);
        std::snprintf(lines[3], sizeof lines[3], "Uptime %ldh %02ldm %02lds", up / 3600, up / 60 % 60, up % 60);
        const float pw = std::floor(std::min(w - 2 * gap, b * 6.0f)), x0 = (w - pw) * 0.5f;
        const int per_row = std::max(1, static_cast<int>((pw + gap) / (b + gap)));
        const float rows = static_cast<float>(5 + (static_cast<int>(languages.size()) + per_row - 1) / per_row);
        const float y0 = std::max(gap, (h - rows * b - (rows - 1) * gap) * 0.5f);
        for (int i = 0; i < 4; ++i) {
            add(ControlId::OperatorInfo, i, Rect{x0, y0 + static_cast<float>(i) * (b + gap), pw, b}, lines[i]);
        }
        const float half = (pw - gap) * 0.5f, y = y0 + 4 * (b + gap);
        add(ControlId::OperatorRestart, -1, Rect{x0, y, half, b}, "Restart");
        add(ControlId::OperatorClose, -1, Rect{x0 + half + gap, y, half, b}, "Close");
        // The language set: square toggles in rows below, as many a row as fit the panel.
        for (size_t i = 0; i < languages.size(); ++i) {
            const int r = static_cast<int>(i) / per_row, k = static_cast<int>(i) % per_row;
            add(ControlId::OperatorLanguage, static_cast<int>(i),
                Rect{x0 + static_cast<float>(k) * (b + gap), y + static_cast<float>(1 + r) * (b + gap), b, b},
                languages[i].first, languages[i].second);
        }
    }
    return out;
}

std::vector<std::string> offered_languages(const std::vector<std::string>& scene_languages) {
    std::vector<std::string> out = scene_languages;
    for (std::string_view l : kUiLanguages)
        if (std::find(out.begin(), out.end(), l) == out.end()) out.emplace_back(l);
    return out;
}

long resident_kib() {
    std::ifstream in("/proc/self/statm");
    long size = 0, resident = 0;
    if (!(in >> size >> resident)) return -1;
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

}  // namespace body::kiosk
