// Golden pictures of the structure tree through bodyview (headless, llvmpipe,
// 800x500; kiosk/app/structure_tree.h): a scene of 40 groups, too many for the
// group row, its tree opened and searched with a letter key, in the normal look,
// with high contrast and large text, and in Arabic (mirrored). Taps are placed
// by a KioskApp over the same scene, whose layout bodyview's is.
// BODY_UPDATE_GOLDENS=1 rewrites tests/render/golden/.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string_view>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/replay.h"
#include "kiosk/render/image.h"
#include "shared/obj_io.h"
#include "tests/cli/cli_test.h"
#include "tests/common/replay_fixture.h"
#include "tests/common/test_dir.h"
#include "tests/common/test_meshes.h"
#include "tests/render/render_fixture.h"
#include "tests/render/render_golden.h"

namespace body {
namespace {

namespace fs = std::filesystem;
using kiosk::ControlId;
constexpr int kWidth = 800, kHeight = 500;
const char* kWords[] = {"Arcuate", "Basal",   "Caudate", "Dentate", "Frontal", "Gyrus",
                        "Insula",  "Lingual", "Medial",  "Nucleus", "Optic",   "Pallidum"};

std::string tap_at(const kiosk::Rect& r, double t) { return test::replay_tap(r.x + r.w / 2, r.y + r.h / 2, t); }

class TreeGolden : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")) GTEST_SKIP() << "needs fonts-dejavu-core";
        dir_ = test::fresh_test_dir("body_tree_golden");
        const Mesh sphere = test::uv_sphere(8, 16, Vec3(0.0), 0.4);
        ASSERT_TRUE(write_obj((dir_ / "s.obj").string(), std::span<const Mesh>(&sphere, 1)).ok());
    }
    void TearDown() override {
        if (!dir_.empty()) fs::remove_all(dir_);
    }

    // 40 groups of two spheres on an 8 x 10 grid; `kiosk` the kiosk object.
    std::string scene_json(const std::string& kiosk) const {
        // Appends parts one by one (GCC 12 warns falsely on literal + string chains).
        const auto add = [](std::string& out, std::initializer_list<std::string_view> parts) {
            for (std::string_view p : parts) out.append(p);
        };
        std::string models, groups;
        for (int g = 0; g < 40; ++g) {
            std::string gname;
            add(gname, {kWords[g % 12], " ", std::to_string(g)});
            add(groups, {g ? "," : "", "{\"name\": \"", gname, "\"}"});
            for (int m = 0; m < 2; ++m) {
                const int i = 2 * g + m;
                add(models,
                    {i ? "," : "", "{\"name\": \"m", std::to_string(i), "\", \"file\": \"s.obj\", \"group\": \"", gname,
                     "\", \"transform\": {\"translate\": [", std::to_string(i % 10), ", ", std::to_string(i / 10),
                     ", 0]}, \"label\": {\"en\": \"", kWords[(g + m + 3) % 12], " ", std::to_string(m), "\"}}"});
            }
        }
        std::string json;
        add(json, {"{\"models\": [", models, "], \"groups\": [", groups, "], \"kiosk\": ", kiosk, "}"});
        return json;
    }

    // Opens the tree and taps the letter `letter` (placed by a KioskApp over the scene); the screenshot.
    render::Image open_and_search(const std::string& kiosk, char32_t letter, kiosk::Rect* first_row = nullptr) {
        const std::string json = scene_json(kiosk);
        std::ofstream(dir_ / "scene.json") << json;
        auto scene = scene::parse_scene(json, "scene.json", dir_.string());
        EXPECT_TRUE(scene) << scene.error().message;
        if (!scene) return {};
        std::vector<kiosk::ModelInfo> info(80, kiosk::ModelInfo{true, {0, 0, 0}, 1.0f, 100, 100});
        kiosk::KioskApp app(scene.value(), info, kWidth, kHeight);
        app.update(0.0);
        std::string replay;
        const auto find = [&](ControlId id, int group) -> const kiosk::Control* {
            for (const kiosk::Control& c : app.controls())
                if (c.id == id && (group < 0 || c.group == group)) return &c;
            return nullptr;
        };
        const auto tap = [&](ControlId id, int group, double t) {
            const kiosk::Control* c = find(id, group);
            EXPECT_NE(c, nullptr);
            if (!c) return;
            const std::string step = tap_at(c->rect, t);
            replay += step;
            auto r = kiosk::parse_replay(step, "step.replay");
            kiosk::run_replay(app, *r, 60.0, t);
        };
        tap(ControlId::TreeOpen, -1, 0.2);
        tap(ControlId::TreeLetter, static_cast<int>(letter), 0.4);
        EXPECT_TRUE(app.tree().open);
        if (const kiosk::Control* row = find(ControlId::TreeGroup, -1); row && first_row) *first_row = row->rect;
        std::ofstream(dir_ / "input.replay") << "size 800 500\n" << replay << "1.0 end\n";
        auto r =
            test::run(test::bin("bodyview") + " --headless --size 800x500 --scene " + (dir_ / "scene.json").string() +
                      " --replay " + (dir_ / "input.replay").string() + " --screenshot " + (dir_ / "out.png").string());
        EXPECT_EQ(r.exit_code, 0) << r.output;
        auto img = render::read_png((dir_ / "out.png").string());
        EXPECT_TRUE(img) << r.output;
        return img ? img.value() : render::Image{};
    }

    fs::path dir_;
};

// Pixels of a rectangle in the active rows' blue (a shown group's row).
size_t blue(const render::Image& img, const kiosk::Rect& r) {
    size_t n = 0;
    for (int y = static_cast<int>(r.y) + 4; y < static_cast<int>(r.y + r.h) - 4; ++y)
        for (int x = static_cast<int>(r.x) + 4; x < static_cast<int>(r.x + r.w) - 4; ++x) {
            const uint8_t* p = img.at(x, y);
            n += p[2] > p[0] + 15;
        }
    return n;
}

TEST_F(TreeGolden, SearchedByALetterKey) {
    const render::Image img = open_and_search(R"({"languages": ["en"]})", U'c');
    ASSERT_EQ(img.width, kWidth);
    test::expect_golden("tree_search_c", img);
}

TEST_F(TreeGolden, HighContrastAndLargeText) {
    const render::Image img =
        open_and_search(R"({"languages": ["en"], "high_contrast": true, "large_text": true})", U'b');
    ASSERT_EQ(img.width, kWidth);
    test::expect_golden("tree_high_contrast_large", img);
}

TEST_F(TreeGolden, ArabicMirrorsThePanel) {
    kiosk::Rect ar_row, en_row;
    const render::Image ar = open_and_search(R"({"languages": ["ar", "en"]})", U'c', &ar_row);
    const render::Image en = open_and_search(R"({"languages": ["en"]})", U'c', &en_row);
    ASSERT_EQ(ar.width, kWidth);
    ASSERT_EQ(en.width, kWidth);
    // The first group's row, in its shown blue, on the right in Arabic and on the left in English.
    EXPECT_GT(ar_row.x + ar_row.w, kWidth - 20.0f);
    EXPECT_LT(en_row.x, 20.0f);
    const size_t area = static_cast<size_t>((ar_row.w - 8) * (ar_row.h - 8));
    EXPECT_GT(blue(ar, ar_row), area / 2);
    EXPECT_GT(blue(en, en_row), area / 2);
    EXPECT_LT(blue(en, ar_row), blue(ar, ar_row) / 2);
    test::expect_golden("tree_arabic", ar);
}

}  // namespace
}  // namespace body
