#pragma once
// Platform input events for tests: building them in one line and checking a
// delivered sequence (type, id and, where given, position).
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

#include "platform/platform.h"

namespace body::platform::test {

inline InputEvent input_event(InputEvent::Type type, int id, float x, float y, double time, uint32_t modifiers = 0) {
    InputEvent e;
    e.type = type;
    e.id = id;
    e.x = x;
    e.y = y;
    e.time = time;
    e.modifiers = modifiers;
    return e;
}

struct Expected {
    InputEvent::Type type;
    int id;
    float x = -1.0f, y = -1.0f;  // negative: not checked
};

// `events` is exactly `expected`, in order.
inline void expect_events(const std::vector<InputEvent>& events, std::initializer_list<Expected> expected) {
    ASSERT_EQ(events.size(), expected.size());
    size_t i = 0;
    for (const Expected& want : expected) {
        SCOPED_TRACE("event " + std::to_string(i));
        const InputEvent& got = events[i++];
        EXPECT_EQ(got.type, want.type);
        EXPECT_EQ(got.id, want.id);
        if (want.x >= 0.0f) {
            EXPECT_FLOAT_EQ(got.x, want.x);
        }
        if (want.y >= 0.0f) {
            EXPECT_FLOAT_EQ(got.y, want.y);
        }
    }
}

}  // namespace body::platform::test
