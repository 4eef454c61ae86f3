// The authoring window's tools without GL: Pack from the editor (saved first,
// the bundle validated and written atomically, a bad model named in the status
// line), STL/PLY added through bodygen into the scene's models/ folder, the
// manipulation sphere's rotate/scale/snap arithmetic, and the undoable pin
// move, tour reorder and whole-transform edits.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "kiosk/author/editor.h"
#include "kiosk/author/manipulation.h"
#include "kiosk/author/model_convert.h"
#include "kiosk/scene/scene_models.h"
#include "shared/atomic_file.h"
#include "shared/scene/scene_write.h"
#include "tests/common/test_dir.h"
#include "tests/kiosk/editor_events.h"

namespace body::kiosk::author {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* kTetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

using events::click;
using events::key;
using events::type;

// A scene of two tetrahedra in DIR/work/ (scene.json not yet written) and two tours.
Editor work_editor(const fs::path& dir) {
    fs::create_directories(dir / "work");
    std::ofstream(dir / "work" / "a.obj") << kTetra;
    std::ofstream(dir / "work" / "b.obj") << kTetra;
    const std::string text = R"({"models": [{"name": "a", "file": "a.obj"}, {"name": "b", "file": "b.obj"}],
        "tours": [{"name": "first", "steps": [{}]}, {"name": "second", "steps": [{}]}]})";
    auto s = scene::parse_scene(text, (dir / "work" / "scene.json").string(), (dir / "work").string());
    EXPECT_TRUE(s) << (s ? "" : s.error().message);
    Editor ed(Document(s.value(), (dir / "work" / "scene.json").string()));
    ed.set_viewport(1280, 800, 1.0f);
    return ed;
}

TEST(AuthorPack, CtrlPSavesThenPacksTheBundleBesideTheScene) {
    const fs::path dir = test::fresh_test_dir("body_author_pack");
    Editor ed = work_editor(dir);
    EXPECT_EQ(fs::path(ed.pack_to()), dir / "work-bundle");
    ASSERT_TRUE(ed.move_model(1, {5, 0, 0}));
    ed.handle(key('P', kModCtrl));
    EXPECT_FALSE(ed.document().dirty()) << ed.status();  // saved first
    EXPECT_NE(ed.status().find("packed 2 models"), std::string::npos) << ed.status();
    ASSERT_TRUE(fs::exists(dir / "work-bundle" / "scene.json"));
    EXPECT_TRUE(fs::exists(dir / "work-bundle" / "models" / "a.obj"));
    const json j = json::parse(read_file((dir / "work-bundle" / "scene.json").string()).value());
    EXPECT_EQ(j["models"][1]["file"], "models/b.obj");
    EXPECT_EQ(j["models"][1]["transform"]["translate"][0], 5.0);  // what the author saved
    auto bundle = scene::read_scene((dir / "work-bundle" / "scene.json").string());
    EXPECT_TRUE(bundle) << (bundle ? "" : bundle.error().message);

    // A model that does not read: the status names the manifest's entry; the old bundle stays whole.
    std::ofstream(dir / "work" / "b.obj", std::ios::trunc) << "this is not an OBJ\n";
    click(ed, "Pack");
    EXPECT_NE(ed.status().find("pack failed"), std::string::npos) << ed.status();
    EXPECT_NE(ed.status().find("models[1].file"), std::string::npos) << ed.status();
    EXPECT_EQ(json::parse(read_file((dir / "work-bundle" / "scene.json").string()).value()), j);
    fs::remove_all(dir);
}

TEST(AuthorAddModel, StlAndPlyBecomeProgressiveMeshesInTheModelsFolder) {
    const fs::path dir = test::fresh_test_dir("body_author_stl");
    Editor ed = work_editor(dir);
    std::ofstream(dir / "part.stl")
        << "solid t\n"
           "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\n"
           "endloop\nendfacet\nfacet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
           "vertex 0 0 1\nendloop\nendfacet\nfacet normal -1 0 0\nouter loop\nvertex 0 0 0\n"
           "vertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\nfacet normal 1 1 1\nouter loop\n"
           "vertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid t\n";
    ASSERT_TRUE(ed.add_model((dir / "part.stl").string())) << ed.status();
    const auto& models = ed.document().scene().models;
    ASSERT_EQ(models.size(), 3u);
    EXPECT_EQ(models[2].name, "part");
    EXPECT_EQ(models[2].file, "models/part.bpm");  // inside the scene's folder: relative
    EXPECT_TRUE(fs::is_regular_file(dir / "work" / "models" / "part.bpm"));
    ASSERT_TRUE(ed.add_model((dir / "part.stl").string()));  // again: a second file, a second name
    EXPECT_EQ(ed.document().scene().models[3].file, "models/part-2.bpm");
    EXPECT_EQ(ed.document().scene().models[3].name, "part-2");

    // A PLY that is not one: bodygen's reason, no model, no file left behind.
    std::ofstream(dir / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n0 0\n";
    const Status bad = ed.add_model((dir / "broken.ply").string());
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find("broken.ply"), std::string::npos) << bad.error().message;
    EXPECT_EQ(ed.document().scene().models.size(), 4u);
    EXPECT_FALSE(fs::exists(dir / "work" / "models" / "broken.bpm"));
    EXPECT_FALSE(ed.add_model((dir / "notes.txt").string()));
    fs::remove_all(dir);
}

TEST(AuthorEdits, PinMoveTourReorderAndTransformsAreOneUndoStepEach) {
    const fs::path dir = test::fresh_test_dir("body_author_edits");
    Editor ed = work_editor(dir);
    ed.set_surface_point(0, {0.1f, 0.1f, 0.0f});
    ASSERT_TRUE(ed.add_pin(0, {0.1f, 0.1f, 0.0f}));
    ASSERT_TRUE(ed.move_pin(0, 0, {0.0f, 0.2f, 0.3f}));
    EXPECT_EQ(ed.document().scene().models[0].pins[0].anchor, (std::array<float, 3>{0.0f, 0.2f, 0.3f}));
    ed.handle(key('Z', kModCtrl));
    EXPECT_EQ(ed.document().scene().models[0].pins[0].anchor, (std::array<float, 3>{0.1f, 0.1f, 0.0f}));
    EXPECT_FALSE(ed.move_pin(0, 3, {0, 0, 0}));

    ed.select_tour(1);
    click(ed, "Tour earlier");
    EXPECT_EQ(ed.document().scene().tours[0].name, "second") << ed.status();
    EXPECT_EQ(ed.selection().tour, 0);
    click(ed, "Tour earlier");  // already first: refused, nothing changes
    EXPECT_EQ(ed.document().scene().tours[0].name, "second");
    click(ed, "Tour later");
    EXPECT_EQ(ed.document().scene().tours[1].name, "second");
    ed.handle(key('Z', kModCtrl));
    EXPECT_EQ(ed.document().scene().tours[0].name, "second");

    ed.select_model(1);
    EXPECT_FALSE(ed.snap());
    ed.handle(key('G'));
    EXPECT_TRUE(ed.snap());
    click(ed, "Snap: on");
    EXPECT_FALSE(ed.snap());
    scene::Transform t;
    t.rotate_deg = {30, 0, 45};
    t.scale = 1.5f;
    ASSERT_TRUE(ed.set_transform(1, t, "rotate"));
    EXPECT_EQ(ed.document().scene().models[1].transform, t);
    click(ed, "Reset transform");
    EXPECT_EQ(ed.document().scene().models[1].transform, scene::Transform{});
    ed.handle(key('Z', kModCtrl));
    EXPECT_EQ(ed.document().scene().models[1].transform, t);
    fs::remove_all(dir);
}

// The scene's Euler angles (X then Y then Z) as SCENE.md and to_model_matrix define them.
glm::mat3 scene_rotation(const std::array<float, 3>& deg) {
    scene::Transform t;
    t.rotate_deg = deg;
    return glm::mat3(to_model_matrix(t));
}

float max_difference(const glm::mat3& a, const glm::mat3& b) {
    float d = 0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) d = std::max(d, std::abs(a[c][r] - b[c][r]));
    return d;
}

TEST(AuthorManipulation, EulerAnglesRoundTripIncludingGimbalLock) {
    for (const std::array<float, 3>& deg : std::vector<std::array<float, 3>>{
             {0, 0, 0}, {30, -20, 75}, {-170, 45, 10}, {12, 90, 33}, {5, -90, -60}, {179, 1, -179}}) {
        const glm::vec3 e = euler_degrees(scene_rotation(deg));
        EXPECT_LT(max_difference(scene_rotation({e.x, e.y, e.z}), scene_rotation(deg)), 1e-4f)
            << deg[0] << " " << deg[1] << " " << deg[2];
    }
}

TEST(AuthorManipulation, ArcballTurnsAboutTheSphereCentreAndSnaps) {
    // A quarter of the disc's width to the right turns about the view's up axis.
    const glm::vec3 a = arcball_point({100, 100}, {100, 100}, 50), b = arcball_point({150, 100}, {100, 100}, 50);
    EXPECT_NEAR(glm::length(b), 1.0f, 1e-6f);
    EXPECT_NEAR(b.z, 0.0f, 1e-6f);  // the rim
    const glm::mat3 r = rotation_between(a, b);
    EXPECT_LT(glm::length(r * a - b), 1e-5f);
    EXPECT_LT(glm::length(r * glm::vec3(0, 1, 0) - glm::vec3(0, 1, 0)), 1e-5f);  // the axis stays
    EXPECT_LT(max_difference(rotation_between(a, a), glm::mat3(1.0f)), 1e-6f);

    scene::Transform start;
    start.translate = {10, 0, 0};
    start.scale = 2.0f;
    const glm::vec3 centre(10, 4, 0);  // where the model's centre is placed
    const glm::mat3 turn = scene_rotation({0, 37, 0});
    const scene::Transform t = rotated(start, turn, centre, false);
    // The model's centre (local (0, 2, 0) at scale 2) stays where it was.
    const glm::vec3 local(0, 2, 0);
    const glm::vec3 moved = glm::vec3(to_model_matrix(t) * glm::vec4(local, 1.0f));
    EXPECT_LT(glm::length(moved - centre), 1e-4f);
    EXPECT_NEAR(t.rotate_deg[1], 37.0f, 1e-3f);
    EXPECT_EQ(t.scale, 2.0f);
    const scene::Transform s = rotated(start, turn, centre, true);
    EXPECT_NEAR(s.rotate_deg[1], 30.0f, 1e-3f);  // 37 snaps to 30
    EXPECT_LT(glm::length(glm::vec3(to_model_matrix(s) * glm::vec4(local, 1.0f)) - centre), 1e-4f);

    const scene::Transform big = scaled(start, 1.27f, centre, false);
    EXPECT_NEAR(big.scale, 2.54f, 1e-5f);
    EXPECT_LT(glm::length(glm::vec3(to_model_matrix(big) * glm::vec4(local, 1.0f)) - centre), 1e-4f);
    EXPECT_NEAR(scaled(start, 1.27f, centre, true).scale, 2.5f, 1e-5f);
    EXPECT_NEAR(scaled(start, 0.001f, centre, true).scale, kSnapScale, 1e-6f);  // never to nothing

    EXPECT_EQ(grid_step(80.0f), 10.0f);  // a brain: 10 mm
    EXPECT_NEAR(grid_step(0.8f), 0.1f, 1e-7f);
    EXPECT_EQ(snap_translate({12.4f, -7.6f, 0.0f}, 5.0f), (std::array<float, 3>{10.0f, -10.0f, 0.0f}));
}

}  // namespace
}  // namespace body::kiosk::author
