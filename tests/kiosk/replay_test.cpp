// Replay files: both spellings parse to the same events; mistakes name the line.
#include "kiosk/app/replay.h"

#include <gtest/gtest.h>

namespace body::kiosk {
namespace {

TEST(Replay, TextAndJsonAgree) {
    auto text = parse_replay(
        "# a pinch\nsize 800 480\n0.0 down 1 10 20\n0.5 move 1 11.5 20\n0.6 mouse-down middle 5 6 shift ctrl\n"
        "0.7 wheel 1 2 -1\n0.8 key 65\n1.0 up 1 11.5 20\n3.5 end\n",
        "a.replay");
    ASSERT_TRUE(text) << text.error().message;
    auto json = parse_replay(
        R"({"size": [800, 480], "events": [{"t": 0, "type": "down", "id": 1, "x": 10, "y": 20},
        {"t": 0.5, "type": "move", "id": 1, "x": 11.5, "y": 20},
        {"t": 0.6, "type": "mouse-down", "button": "middle", "x": 5, "y": 6, "shift": true, "ctrl": true},
        {"t": 0.7, "type": "wheel", "x": 1, "y": 2, "wheel": -1}, {"t": 0.8, "type": "key", "key": 65},
        {"t": 1.0, "type": "up", "id": 1, "x": 11.5, "y": 20}], "end": 3.5})",
        "a.json");
    ASSERT_TRUE(json) << json.error().message;
    for (const Replay* r : {&text.value(), &json.value()}) {
        EXPECT_EQ(r->width, 800);
        EXPECT_EQ(r->height, 480);
        EXPECT_DOUBLE_EQ(r->end_time, 3.5);
        ASSERT_EQ(r->events.size(), 6u);
        EXPECT_EQ(r->events[1].type, InputEvent::Type::TouchMove);
        EXPECT_FLOAT_EQ(r->events[1].x, 11.5f);
        EXPECT_EQ(r->events[2].button(), MouseButton::Middle);
        EXPECT_EQ(r->events[2].modifiers, kModShift | kModCtrl);
        EXPECT_FLOAT_EQ(r->events[3].dy, -1.0f);
        EXPECT_EQ(r->events[4].key, 65);
        EXPECT_EQ(r->events[5].type, InputEvent::Type::TouchUp);
    }
}

TEST(Replay, ModifiersAreOptionalAndFollowAnyEvent) {
    // A replay written before modifiers existed: every event has none.
    auto old = parse_replay("0.0 mouse-down left 1 2\n0.1 mouse-move 3 4\n0.2 mouse-up left 3 4\n0.3 wheel 1 2 1\n",
                            "old.replay");
    ASSERT_TRUE(old) << old.error().message;
    ASSERT_EQ(old->events.size(), 4u);
    for (const InputEvent& e : old->events) EXPECT_EQ(e.modifiers, 0u);
    // Any order, any event kind; JSON false means not held.
    auto text = parse_replay("0.0 mouse-move 3 4 alt shift\n0.1 wheel 1 2 -1 ctrl\n0.2 down 1 5 6 shift\n", "m.replay");
    auto json = parse_replay(R"({"events": [{"t": 0, "type": "mouse-move", "x": 3, "y": 4, "alt": true, "shift": true},
        {"t": 0.1, "type": "wheel", "x": 1, "y": 2, "wheel": -1, "ctrl": true, "shift": false},
        {"t": 0.2, "type": "down", "id": 1, "x": 5, "y": 6, "shift": true}]})",
                             "m.json");
    for (const auto* r : {&text, &json}) {
        ASSERT_TRUE(*r) << r->error().message;
        ASSERT_EQ((*r)->events.size(), 3u);
        EXPECT_EQ((*r)->events[0].modifiers, kModShift | kModAlt);
        EXPECT_EQ((*r)->events[1].modifiers, static_cast<uint32_t>(kModCtrl));
        EXPECT_EQ((*r)->events[2].modifiers, static_cast<uint32_t>(kModShift));
    }
}

// Found by fuzz_replay_parser: nlohmann throws out_of_range (not parse_error) for 9e99999.
TEST(Replay, NumberOverflowIsAnErrorNotACrash) {
    auto r = parse_replay(R"({"events": [{"t": 9e99999999, "type": "down"}]})", "x.replay");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message.rfind("x.replay: not valid JSON: ", 0), 0u) << r.error().message;
    auto end = parse_replay("0.0 move 1 1 1\n1e9 end\n", "y.replay");
    ASSERT_FALSE(end.ok());
    EXPECT_EQ(end.error().message, "y.replay: line 2: time 1e9 is over the 3600 s limit");
}

// Found by fuzz_replay_parser: an event type with a newline made the one-line error two lines.
TEST(Replay, ControlCharactersInAnErrorAreEscaped) {
    auto r = parse_replay(R"({"events": [{"t": 0, "type": "dow\n"}]})", "x.replay");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "x.replay: events[0].type: unknown event type 'dow\\x0a'");
}

TEST(Replay, ErrorsNameTheLine) {
    auto bad = [](const std::string& text) {
        auto r = parse_replay(text, "x.replay");
        return r ? std::string("(parsed)") : r.error().message;
    };
    EXPECT_EQ(bad("0 down 1 2 3\n0.5 tap 1 2 3\n"), "x.replay: line 2: unknown event type 'tap'");
    EXPECT_EQ(bad("1 down 1 2 3\n0.5 up 1 2 3\n"), "x.replay: line 2: time goes backwards");
    EXPECT_EQ(bad("0 down 1 2\n"), "x.replay: line 1: bad arguments for 'down' (see kiosk/app/replay.h)");
    EXPECT_EQ(bad("abc down 1 2 3\n"), "x.replay: line 1: expected a time in seconds");
    EXPECT_EQ(bad("0 mouse-down left 1 2 meta\n"), "x.replay: line 1: unexpected 'meta' (modifiers: shift, ctrl, alt)");
    EXPECT_EQ(bad(R"({"events": [{"t": 0, "type": "mouse-down", "button": "left", "shift": 1}]})"),
              "x.replay: events[0].shift: expected true or false");
    EXPECT_EQ(bad(R"({"events": [{"t": 0, "type": "down"}, {"t": -1, "type": "up"}]})"),
              "x.replay: events[1].t: time goes backwards");
    EXPECT_EQ(bad(R"({"events": 3})"), "x.replay: events: expected an array");
}

}  // namespace
}  // namespace body::kiosk
