// bodygen pack end to end: a valid scene becomes a bundle that reads back; bad
// references fail with exit 2 naming the JSON path and leave nothing behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../cli/cli_test.h"
#include "shared/scene/scene.h"
#include "tests/common/test_dir.h"

namespace body {
namespace {

namespace fs = std::filesystem;

class Pack : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::fresh_test_dir("body_pack");
        fs::create_directories(dir_ / "src" / "a");
        fs::create_directories(dir_ / "src" / "b");
        write("src/a/part.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
        write("src/b/part.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        // A real progressive mesh from the tetrahedron, and the same cut short.
        auto lod = test::run(test::bin("bodygen") + " lod " + (dir_ / "src/a/part.obj").string() + " -o " +
                             (dir_ / "src/brain.bpm").string());
        ASSERT_EQ(lod.exit_code, 0) << lod.output;
        std::ifstream in(dir_ / "src/brain.bpm", std::ios::binary);
        std::string bpm((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        write("src/cut.bpm", bpm.substr(0, bpm.size() / 2));
        write("src/bad.bpm", "OBJ? no");
        write("src/notes.txt", "hello");
    }
    void TearDown() override { fs::remove_all(dir_); }

    void write(const std::string& rel, const std::string& bytes) {
        std::ofstream(dir_ / rel, std::ios::binary) << bytes;
    }
    std::string scene(const std::string& models) {
        write("src/scene.json",
              R"({"models": [)" + models + R"(], "groups": [{"name": "g"}], "kiosk": {"languages": ["en", "de"]}})");
        return (dir_ / "src" / "scene.json").string();
    }
    test::RunResult pack(const std::string& scene_path, const std::string& out) {
        return test::run(test::bin("bodygen") + " pack " + scene_path + " -o " + out);
    }
    fs::path dir_;
};

TEST_F(Pack, WritesABundleThatReadsBack) {
    const std::string s = scene(R"({"name": "a", "file": "a/part.obj", "group": "g", "label": {"de": "Teil A"}},
        {"name": "b", "file": "b/part.obj"}, {"name": "brain", "file": "brain.bpm"})");
    const std::string out = (dir_ / "bundle").string() + "/";
    auto r = pack(s, out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    auto back = scene::read_scene((dir_ / "bundle" / "scene.json").string());
    ASSERT_TRUE(back) << back.error().message;
    ASSERT_EQ(back->models.size(), 3u);
    EXPECT_EQ(back->models[0].file, "models/part.obj");
    EXPECT_EQ(back->models[1].file, "models/part-2.obj");  // base-name clash renamed
    EXPECT_EQ(back->models[2].file, "models/brain.bpm");
    EXPECT_EQ(back->label(back->models[0], "de").title, "Teil A");
    for (const auto& m : back->models) EXPECT_TRUE(fs::is_regular_file(m.path)) << m.path;
    EXPECT_EQ(fs::file_size(back->models[1].path), fs::file_size(dir_ / "src" / "b" / "part.obj"));

    // Packing again replaces the bundle and leaves no temporary directories.
    r = pack(s, out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    size_t entries = 0;
    for (const auto& e : fs::directory_iterator(dir_)) entries += e.path().filename() != "src";
    EXPECT_EQ(entries, 1u);
}

TEST_F(Pack, BadReferencesExitTwoAndWriteNothing) {
    struct Case {
        std::string models, message;
    };
    for (const Case& c : {
             Case{R"({"name": "a", "file": "a/part.obj"}, {"name": "m", "file": "missing.obj"})",
                  "models[1].file: 'missing.obj': no such file"},
             Case{R"({"name": "x", "file": "bad.bpm"})", "models[0].file: 'bad.bpm': "},
             Case{R"({"name": "x", "file": "a/part.obj"}, {"name": "y", "file": "cut.bpm"})",
                  "models[1].file: 'cut.bpm': "},
             Case{R"({"name": "x", "file": "notes.txt"})", "not a model (expected .bpm or .obj)"},
             Case{R"({"name": "x", "file": "a/part.obj", "group": "nope"})", "models[0].group: no group named"},
         }) {
        auto r = pack(scene(c.models), (dir_ / "bundle").string());
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("scene.json"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir_ / "bundle"));
    }
    EXPECT_EQ(test::run(test::bin("bodygen") + " pack").exit_code, 2);
}

TEST_F(Pack, RefusesToReplaceSomethingThatIsNotABundle) {
    fs::create_directories(dir_ / "precious");
    write("precious/thesis.tex", "do not delete");
    auto r = pack(scene(R"({"name": "a", "file": "a/part.obj"})"), (dir_ / "precious").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("not a bundle"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir_ / "precious" / "thesis.tex"));
}

}  // namespace
}  // namespace body
