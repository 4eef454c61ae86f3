// Replay files: the text and JSON spellings (format in replay.h), and the
// fixed-step driver that plays them into a KioskApp.
#include "kiosk/app/replay.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "kiosk/app/kiosk_app.h"
#include "shared/atomic_file.h"
#include "shared/input_file.h"

namespace body::kiosk {

namespace {

// Modifier words: trailing words on a text line, boolean members in JSON.
constexpr std::pair<const char*, uint32_t> kModifierNames[] = {
    {"shift", kModShift}, {"ctrl", kModCtrl}, {"alt", kModAlt}};

// A mouse event's button, kept in its id as the platform numbers buttons.
bool parse_button(const std::string& s, InputEvent& e) {
    MouseButton b;
    if (s == "left")
        b = MouseButton::Left;
    else if (s == "middle")
        b = MouseButton::Middle;
    else if (s == "right")
        b = MouseButton::Right;
    else
        return false;
    e.id = static_cast<int>(b);
    return true;
}

bool valid_codepoint(int c) { return c >= 0 && c <= 0x10FFFF && !(c >= 0xD800 && c < 0xE000); }

bool parse_kind(const std::string& s, InputEvent::Type& k) {
    static const std::pair<const char*, InputEvent::Type> kinds[] = {
        {"down", InputEvent::Type::TouchDown},
        {"move", InputEvent::Type::TouchMove},
        {"up", InputEvent::Type::TouchUp},
        {"mouse-down", InputEvent::Type::MouseDown},
        {"mouse-move", InputEvent::Type::MouseMove},
        {"mouse-up", InputEvent::Type::MouseUp},
        {"wheel", InputEvent::Type::Scroll},
        {"key", InputEvent::Type::Key},
        {"text", InputEvent::Type::Text},
    };
    for (const auto& [name, kind] : kinds) {
        if (s == name) {
            k = kind;
            return true;
        }
    }
    return false;
}

Result<Replay> parse_text(const std::string& text, const std::string& source) {
    Replay r;
    std::istringstream in(text);
    std::string line;
    int number = 0;
    double last = 0.0;
    while (std::getline(in, line)) {
        ++number;
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        std::istringstream ls(line);
        std::string first;
        if (!(ls >> first)) continue;
        const std::string where = source + ": line " + std::to_string(number) + ": ";
        if (first == "size") {
            if (!(ls >> r.width >> r.height) || r.width <= 0 || r.height <= 0) {
                return input_error(where + "expected 'size WIDTH HEIGHT'");
            }
            continue;
        }
        char* end = nullptr;
        const double t = std::strtod(first.c_str(), &end);
        if (*end != '\0' || !std::isfinite(t) || t < 0.0) return input_error(where + "expected a time in seconds");
        if (t > kMaxReplaySeconds)
            return input_error(where + "time " + escape_for_message(first) + " is over the 3600 s limit");
        if (t < last) return input_error(where + "time goes backwards");
        last = t;
        std::string word;
        if (!(ls >> word)) return input_error(where + "expected an event type");
        if (word == "end") {
            r.end_time = std::max(r.end_time, t);
            continue;
        }
        InputEvent e;
        e.time = t;
        if (!parse_kind(word, e.type))
            return input_error(where + "unknown event type '" + escape_for_message(word) + "'");
        bool ok = true;
        switch (e.type) {
            case InputEvent::Type::TouchDown:
            case InputEvent::Type::TouchMove:
            case InputEvent::Type::TouchUp: ok = static_cast<bool>(ls >> e.id >> e.x >> e.y); break;
            case InputEvent::Type::MouseDown:
            case InputEvent::Type::MouseUp: {
                std::string b;
                ok = (ls >> b >> e.x >> e.y) && parse_button(b, e);
                break;
            }
            case InputEvent::Type::MouseMove: ok = static_cast<bool>(ls >> e.x >> e.y); break;
            case InputEvent::Type::Scroll: ok = static_cast<bool>(ls >> e.x >> e.y >> e.dy); break;
            case InputEvent::Type::Key:
            case InputEvent::Type::Text: ok = static_cast<bool>(ls >> e.key); break;
            case InputEvent::Type::Quit: ok = false; break;  // not a replay event
        }
        if (!ok)
            return input_error(where + "bad arguments for '" + escape_for_message(word) + "' (see kiosk/app/replay.h)");
        std::string mod;
        while (ls >> mod) {
            const auto* it = std::find_if(std::begin(kModifierNames), std::end(kModifierNames),
                                          [&](const auto& m) { return mod == m.first; });
            if (it == std::end(kModifierNames)) {
                return input_error(where + "unexpected '" + escape_for_message(mod) +
                                   "' (modifiers: shift, ctrl, alt)");
            }
            e.modifiers |= it->second;
        }
        e.pressed = e.type == InputEvent::Type::Key || e.type == InputEvent::Type::Text;  // a replayed key is a press
        if (e.type == InputEvent::Type::Text && !valid_codepoint(e.key))
            return input_error(where + "'text' expects a Unicode codepoint (0..1114111, no surrogates)");
        r.events.push_back(e);
        r.end_time = std::max(r.end_time, t);
    }
    return r;
}

Result<Replay> parse_json(const std::string& text, const std::string& source) {
    using nlohmann::json;
    json root;
    try {
        root = json::parse(text);
    } catch (const json::parse_error& e) {
        return input_error(source + ": byte " + std::to_string(e.byte) + ": not valid JSON");
    } catch (const json::exception& e) {  // 406: a number too large for a double (found by fuzzing)
        return input_error(source + ": not valid JSON: " + escape_for_message(e.what(), 120));
    }
    Replay r;
    if (!root.is_object() || !root.contains("events") || !root["events"].is_array()) {
        return input_error(source + ": events: expected an array");
    }
    if (root.contains("size")) {
        const json& s = root["size"];
        if (!s.is_array() || s.size() != 2 || !s[0].is_number_integer() || !s[1].is_number_integer() ||
            s[0].get<int>() <= 0 || s[1].get<int>() <= 0) {
            return input_error(source + ": size: expected [WIDTH, HEIGHT]");
        }
        r.width = s[0].get<int>();
        r.height = s[1].get<int>();
    }
    double last = 0.0;
    const json& events = root["events"];
    for (size_t i = 0; i < events.size(); ++i) {
        const json& v = events[i];
        const std::string where = source + ": events[" + std::to_string(i) + "]";
        if (!v.is_object() || !v.contains("t") || !v["t"].is_number())
            return input_error(where + ".t: expected a time");
        if (!v.contains("type") || !v["type"].is_string()) return input_error(where + ".type: expected a string");
        InputEvent e;
        e.time = v["t"].get<double>();
        if (!std::isfinite(e.time) || e.time < last) return input_error(where + ".t: time goes backwards");
        if (e.time > kMaxReplaySeconds) return input_error(where + ".t: over the 3600 s limit");
        last = e.time;
        const std::string type = v["type"].get<std::string>();
        if (!parse_kind(type, e.type))
            return input_error(where + ".type: unknown event type '" + escape_for_message(type) + "'");
        auto num = [&](const char* key, float& out) {
            if (!v.contains(key)) return true;
            if (!v[key].is_number()) return false;
            out = v[key].get<float>();
            return true;
        };
        if (!num("x", e.x) || !num("y", e.y) || !num("wheel", e.dy)) {
            return input_error(where + ": x, y and wheel must be numbers");
        }
        if (v.contains("id")) {
            if (!v["id"].is_number_integer()) return input_error(where + ".id: expected an integer");
            e.id = v["id"].get<int>();
        }
        if (v.contains("key")) {
            if (!v["key"].is_number_integer()) return input_error(where + ".key: expected an integer");
            e.key = v["key"].get<int>();
        }
        if (v.contains("button") && (!v["button"].is_string() || !parse_button(v["button"].get<std::string>(), e))) {
            return input_error(where + ".button: expected left, middle or right");
        }
        for (const auto& [name, bit] : kModifierNames) {
            if (!v.contains(name)) continue;
            if (!v[name].is_boolean()) return input_error(where + "." + name + ": expected true or false");
            if (v[name].get<bool>()) e.modifiers |= bit;
        }
        e.pressed = e.type == InputEvent::Type::Key || e.type == InputEvent::Type::Text;  // a replayed key is a press
        if (e.type == InputEvent::Type::Text && !valid_codepoint(e.key))
            return input_error(where + ".key: a Unicode codepoint (0..1114111, no surrogates)");
        r.events.push_back(e);
        r.end_time = std::max(r.end_time, e.time);
    }
    if (root.contains("end")) {
        if (!root["end"].is_number()) return input_error(source + ": end: expected a time");
        const double end = root["end"].get<double>();
        if (!(end >= 0.0 && end <= kMaxReplaySeconds)) return input_error(source + ": end: not in 0..3600 s");
        r.end_time = std::max(r.end_time, root["end"].get<double>());
    }
    return r;
}

}  // namespace

Result<Replay> parse_replay(const std::string& text, const std::string& source) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && text[first] == '{') return parse_json(text, source);
    return parse_text(text, source);
}

Result<Replay> read_replay(const std::string& path) {
    auto text = read_file(path);
    if (!text) return text.error();
    return parse_replay(*text, path);
}

double run_replay(KioskApp& app, const Replay& replay, double fps, double start,
                  double (*frame_cost_ms)(size_t triangles)) {
    const double step = 1.0 / fps;
    size_t next = 0;
    double t = start;
    for (long frame = 0;; ++frame) {
        t = start + static_cast<double>(frame) * step;
        while (next < replay.events.size() && replay.events[next].time <= t) app.handle(replay.events[next++]);
        app.update(t);
        if (frame_cost_ms) {
            const size_t tris = app.triangles_planned();
            app.report_frame(frame_cost_ms(tris), tris);
        }
        if (t >= replay.end_time && next >= replay.events.size()) break;
        if (app.exit_requested()) break;
    }
    return t;
}

}  // namespace body::kiosk
