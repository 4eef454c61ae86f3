#pragma once
// What the kiosk and authoring replay tests share: a sphere written as an OBJ
// model file, and a replay writer for the authoring side panel (rows 26 px high
// at 1280x800, UI scale 1, value boxes centred at x 284: kiosk/author/panel.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <span>
#include <sstream>
#include <string>

#include "shared/obj_io.h"
#include "tests/common/test_meshes.h"

namespace body::test {

// A closed UV sphere of `bands` latitude bands centred at (cx, 0, 0), written as OBJ.
inline void write_sphere_obj(const std::filesystem::path& path, float cx, float r, int bands = 16) {
    const Mesh sphere = uv_sphere(bands, 2 * bands, Vec3(cx, 0.0, 0.0), r);
    ASSERT_TRUE(write_obj(path.string(), std::span<const Mesh>(&sphere, 1)).ok());
}

// A one-finger tap at (x, y) lasting 0.05 s from time t, as replay lines.
inline std::string replay_tap(float x, float y, double t) {
    const std::string at = std::to_string(x) + " " + std::to_string(y);
    return std::to_string(t) + " down 1 " + at + "\n" + std::to_string(t + 0.05) + " up 1 " + at + "\n";
}

// Writes a replay event by event; `t` is the time of the next event.
struct AuthorScript {
    std::ostringstream out;
    double t = 0.2;
    AuthorScript() { out << "size 1280 800\n"; }
    void mouse(const char* what, float x, float y, const char* mods = "") {
        out << t << " mouse-" << what << (std::string(what) == "move" ? "" : " left") << " " << x << " " << y << " "
            << mods << "\n";
        t += 0.02;
    }
    void click(float x, float y) {
        mouse("down", x, y);
        mouse("up", x, y);
        t += 0.06;
    }
    void drag(float x0, float y0, float x1, float y1, const char* mods = "") {
        mouse("down", x0, y0, mods);
        for (int i = 1; i <= 5; ++i) mouse("move", x0 + (x1 - x0) * i / 5.0f, y0 + (y1 - y0) * i / 5.0f, mods);
        mouse("up", x1, y1, mods);
        t += 0.05;
    }
    void row(int index, float x = 284) { click(x, 26.0f * static_cast<float>(index) + 13.0f); }
    void key(int k, const char* mods = "") {
        out << t << " key " << k << " " << mods << "\n";
        t += 0.05;
    }
    void type(const std::u32string& s) {
        for (char32_t c : s) out << t << " text " << static_cast<unsigned>(c) << "\n";
        t += 0.05;
    }
    void type(const std::string& ascii) { type(std::u32string(ascii.begin(), ascii.end())); }
    // Selects row `index`'s text, types `value` and confirms it with Enter.
    void set(int index, const std::u32string& value) {
        row(index);
        key('A', "ctrl");
        type(value);
        key(265);  // Enter
    }
    // Ends on the last event: the screenshot is the frame that event was handled in.
    std::string done() {
        out << (t - 0.05) << " end\n";
        return out.str();
    }
    // Ends `after` seconds past the last event, so the frames in between are drawn too.
    std::string done_after(double after) {
        out << t + after << " end\n";
        return out.str();
    }
};

}  // namespace body::test
