// `bodygen export` end to end: an exhibit of two touching meshes in a group
// goes out as GLB/glTF (read back with tinygltf: names, groups as parents,
// colours, every vertex within the .bpm quantization step; and the Khronos
// glTF-Validator: 0 errors, 0 warnings), VRML97 (VTK's importer: shapes,
// triangles, colours; and our own reader through exhibit), binary STL and PLY (assimp: faces and vertices), OBJ.
// Tools that are not installed skip their check and name the package.
#include <gtest/gtest.h>
#include <unistd.h>

#ifdef BODY_WITH_GLTF
#include <tiny_gltf.h>
#endif

#include <meshoptimizer.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "builder/export/export_scene.h"
#include "builder/mesh_import/vrml_reader.h"
#include "shared/obj_io.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "tests/cli/cli_test.h"

namespace body {
namespace {

namespace fs = std::filesystem;

std::string bodygen() { return test::bin("bodygen"); }

class ExportTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = fs::temp_directory_path() / ("body_export_test_" + std::to_string(::getpid()));
        fs::create_directories(dir_ / "meshes");
        const std::string smoke = std::string(BODY_TEST_DATA_DIR) + "/models/smoke.obj";
        fs::copy_file(smoke, dir_ / "meshes" / "Left_kidney.obj");
        fs::copy_file(smoke, dir_ / "meshes" / "Right_kidney.obj");
        std::ofstream(dir_ / "groups.tsv") << "*kidney*\tkidneys\n";
        const auto r =
            test::run(bodygen() + " exhibit " + (dir_ / "meshes").string() + " --groups " +
                      (dir_ / "groups.tsv").string() + " --orientation LPS --quiet -o " + (dir_ / "bundle").string());
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    static std::string path(const std::string& name) { return (dir_ / name).string(); }
    static nlohmann::json scene() {
        std::ifstream in(dir_ / "bundle" / "scene.json");
        return nlohmann::json::parse(in);
    }
    static std::string export_to(const std::string& name) {
        const auto r = test::run(bodygen() + " export " + path("bundle") + " -o " + path(name) + " --quiet");
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_EQ(r.output, "");
        return path(name);
    }
    static fs::path dir_;
};

fs::path ExportTest::dir_;

#ifdef BODY_WITH_GLTF
TEST_F(ExportTest, GlbReadsBackWithNamesGroupsColoursAndVertices) {
    const std::string glb = export_to("scene.glb");
    tinygltf::Model g;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&g, &err, &warn, glb)) << err;
    const auto s = scene();
    // root (mm -> m) -> group "kidneys" -> the two models.
    ASSERT_EQ(g.scenes.size(), 1u);
    const auto& root = g.nodes[size_t(g.scenes[0].nodes[0])];
    EXPECT_EQ(root.scale, (std::vector<double>{0.001, 0.001, 0.001}));
    ASSERT_EQ(root.children.size(), 1u);
    const auto& group = g.nodes[size_t(root.children[0])];
    EXPECT_EQ(group.name, "kidneys");
    ASSERT_EQ(group.children.size(), 2u);

    // The source vertices and the .bpm's quantization step.
    auto source = read_obj(std::string(BODY_TEST_DATA_DIR) + "/models/smoke.obj");
    ASSERT_TRUE(source);
    auto pms = pm::read_bpm(path("bundle") + "/" + s["models"][0]["file"].get<std::string>());
    ASSERT_TRUE(pms);
    const double step = (*pms)[0]->quantization_bound();
    for (size_t k = 0; k < 2; ++k) {
        const auto& node = g.nodes[size_t(group.children[k])];
        EXPECT_EQ(node.name, s["models"][k]["name"]);
        EXPECT_EQ(node.matrix.size(), 16u);  // the LPS -> kiosk rotation travels as the node's matrix
        const auto& prim = g.meshes[size_t(node.mesh)].primitives[0];
        const auto& mat = g.materials[size_t(prim.material)];
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(mat.pbrMetallicRoughness.baseColorFactor[c], s["models"][k]["colour"][c].get<double>(), 1e-6);
        const auto& acc = g.accessors[size_t(prim.attributes.at("POSITION"))];
        const auto& view = g.bufferViews[size_t(acc.bufferView)];
        ASSERT_EQ(acc.count, (*source)[0].vertex_count());
        const auto* xyz = reinterpret_cast<const float*>(g.buffers[0].data.data() + view.byteOffset + acc.byteOffset);
        double worst = 0.0;
        for (size_t v = 0; v < acc.count; ++v) {
            const Vec3 p(xyz[v * 3], xyz[v * 3 + 1], xyz[v * 3 + 2]);
            double nearest = 1e300;
            for (const Vec3& q : (*source)[0].positions) nearest = std::min(nearest, glm::length(p - q));
            worst = std::max(worst, nearest);
        }
        EXPECT_LE(worst, step * 1.0001 + 1e-7) << "a vertex moved more than the .bpm quantization step";
    }
}

// Column-major 4x4 (glTF) applied to a point.
Vec3 transform_point(const std::vector<double>& m, const Vec3& p) {
    return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
            m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}

// The meshopt GLB, decoded with meshoptimizer's decoder and dequantized by each
// node's matrix, gives the placed source vertices back within the .bpm step.
TEST_F(ExportTest, MeshoptGlbDecodesToTheSameVertices) {
    const auto r = test::run(bodygen() + " export " + path("bundle") + " --meshopt -o " + path("mo.glb") + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::ifstream in(path("mo.glb"), std::ios::binary);
    const std::vector<uint8_t> glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    uint32_t json_len = 0;
    std::memcpy(&json_len, glb.data() + 12, 4);
    const auto j = nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + json_len);
    EXPECT_EQ(j["extensionsRequired"], nlohmann::json({"KHR_mesh_quantization", "EXT_meshopt_compression"}));
    const uint8_t* bin = glb.data() + 20 + json_len + 8;
    auto source = read_obj(std::string(BODY_TEST_DATA_DIR) + "/models/smoke.obj");
    ASSERT_TRUE(source);
    auto pms = pm::read_bpm(path("bundle") + "/" + scene()["models"][0]["file"].get<std::string>());
    ASSERT_TRUE(pms);
    const double step = (*pms)[0]->quantization_bound();
    // The placement of each model, from the plain export (same node order).
    tinygltf::Model plain;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&plain, &err, &warn, export_to("plain.glb"))) << err;
    size_t checked = 0;
    for (size_t n = 0; n < j["nodes"].size(); ++n) {
        const auto& node = j["nodes"][n];
        if (!node.contains("mesh")) continue;
        const auto& acc =
            j["accessors"]
             [j["meshes"][node["mesh"].get<size_t>()]["primitives"][0]["attributes"]["POSITION"].get<size_t>()];
        const auto& ext = j["bufferViews"][acc["bufferView"].get<size_t>()]["extensions"]["EXT_meshopt_compression"];
        const size_t count = ext["count"], stride = ext["byteStride"];
        std::vector<uint16_t> codes(count * stride / 2);
        ASSERT_EQ(meshopt_decodeVertexBuffer(codes.data(), count, stride, bin + ext["byteOffset"].get<size_t>(),
                                             ext["byteLength"].get<size_t>()),
                  0);
        const std::vector<double> m = node["matrix"].get<std::vector<double>>();
        const std::vector<double>& place = plain.nodes[n].matrix;
        ASSERT_EQ(place.size(), 16u);
        double worst = 0.0;
        for (size_t v = 0; v < count; ++v) {
            const Vec3 p = transform_point(m, Vec3(codes[v * 4], codes[v * 4 + 1], codes[v * 4 + 2]));
            double nearest = 1e300;
            for (const Vec3& q : (*source)[0].positions)
                nearest = std::min(nearest, glm::length(p - transform_point(place, q)));
            worst = std::max(worst, nearest);
        }
        EXPECT_LE(worst, step * 1.001 + 1e-6);
        ++checked;
    }
    EXPECT_EQ(checked, 2u);
}

TEST_F(ExportTest, KhronosValidatorFindsNoErrorsOrWarnings) {
    const std::string validator = std::string(BODY_SOURCE_DIR) + "/tools/node/node_modules/gltf-validator";
    if (test::run("command -v node").exit_code != 0) GTEST_SKIP() << "needs node (Debian nodejs)";
    if (!fs::exists(validator + "/package.json"))
        GTEST_SKIP() << "needs the npm package gltf-validator in tools/node (./setup.sh deps installs it)";
    test::run(bodygen() + " export " + path("bundle") + " --meshopt -o " + path("validate_mo.glb"));
    for (const char* name : {"scene.glb", "scene.gltf", "validate_mo.glb"}) {
        const std::string file = std::string(name) == "validate_mo.glb" ? path(name) : export_to(name);
        const auto r = test::run("node " + std::string(BODY_SOURCE_DIR) + "/tests/export/gltf_validate.js " +
                                 validator + " " + file);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        const auto j = nlohmann::json::parse(r.output, nullptr, false);
        ASSERT_FALSE(j.is_discarded()) << r.output;
        EXPECT_EQ(j["errors"], 0) << name << ": " << r.output;
        EXPECT_EQ(j["warnings"], 0) << name << ": " << r.output;
    }
}
#endif

TEST_F(ExportTest, VrmlReadsBackInVtkWithShapesAndColours) {
    const std::string wrl = export_to("scene.wrl");
    if (test::run("/usr/bin/python3 -c 'import vtk'").exit_code != 0) GTEST_SKIP() << "needs Debian python3-vtk9";
    const auto r = test::run("/usr/bin/python3 " + std::string(BODY_SOURCE_DIR) + "/tests/export/vrml_check.py " + wrl);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::istringstream lines(r.output);
    const auto s = scene();
    size_t shapes = 0, triangles = 0, points = 0;
    std::vector<std::array<double, 3>> colours;
    for (std::string line; std::getline(lines, line);) {
        std::istringstream f(line);
        std::array<double, 3> c{};
        f >> triangles >> points >> c[0] >> c[1] >> c[2];
        EXPECT_EQ(triangles, 320u) << line;
        EXPECT_EQ(points, 162u) << line;
        colours.push_back(c);
        ++shapes;
    }
    ASSERT_EQ(shapes, 2u) << r.output;
    for (size_t k = 0; k < 2; ++k) {
        bool found = false;
        for (const auto& c : colours) {
            bool same = true;
            for (size_t i = 0; i < 3; ++i)
                same = same && std::abs(c[i] - s["models"][k]["colour"][i].get<double>()) < 1e-3;
            found = found || same;
        }
        EXPECT_TRUE(found) << s["models"][k]["colour"];
    }
    std::ifstream in(wrl);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("DEF kidneys Transform"), std::string::npos);
    EXPECT_NE(text.find("DEF Left_kidney Transform"), std::string::npos);
}

TEST_F(ExportTest, StlAndPlyReadBackInAssimp) {
    const std::string stl = export_to("scene.stl"), ply = export_to("scene.ply");
    EXPECT_EQ(fs::file_size(stl), 84u + 50u * 640u);  // binary STL: header, count, 50 bytes a facet
    if (test::run("command -v assimp").exit_code != 0) GTEST_SKIP() << "needs Debian assimp-utils";
    const auto s = test::run("assimp info " + stl);
    EXPECT_NE(s.output.find("Faces:              640"), std::string::npos) << s.output;
    const auto p = test::run("assimp info " + ply + " --raw");  // --raw: no vertex joining
    EXPECT_NE(p.output.find("Faces:              640"), std::string::npos) << p.output;
    EXPECT_NE(p.output.find("Vertices:           324"), std::string::npos) << p.output;
}

TEST_F(ExportTest, ObjKeepsNamesAndBadInputsAreExitTwoWithNothingWritten) {
    auto meshes = read_obj(export_to("scene.obj"));
    ASSERT_TRUE(meshes) << meshes.error().message;
    ASSERT_EQ(meshes->size(), 2u);
    EXPECT_EQ((*meshes)[0].name, scene()["models"][0]["name"]);
    auto r = test::run(bodygen() + " export " + path("bundle") + " -o " + path("scene.fbx"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_FALSE(fs::exists(path("scene.fbx")));
    r = test::run(bodygen() + " export " + path("missing.bpm") + " -o " + path("m.glb"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_FALSE(fs::exists(path("m.glb")));
    r = test::run(bodygen() + " export " + path("bundle") + " -o " + path("l.glb") + " --lod 0");
    EXPECT_EQ(r.exit_code, 2) << r.output;
}

// Bounds of every vertex of every structure of a .bpm at full detail.
std::pair<Vec3, Vec3> bpm_bounds(const std::string& file, size_t& structures, size_t& triangles) {
    Vec3 lo(1e300), hi(-1e300);
    auto pms = pm::read_bpm(file);
    EXPECT_TRUE(pms) << (pms ? "" : pms.error().message);
    structures = triangles = 0;
    if (!pms) return {lo, hi};
    for (auto& p : *pms) {
        p->set_level(p->max_level());
        for (size_t v = 0; v < p->vertex_count(); ++v)
            lo = glm::min(lo, Vec3(p->position(v))), hi = glm::max(hi, Vec3(p->position(v)));
        ++structures;
        triangles += p->triangle_count();
    }
    return {lo, hi};
}

// What export writes, lod and exhibit read back: STL and PLY as millimetres,
// glTF's metres back to millimetres (same bounds), glTF names kept.
TEST_F(ExportTest, StlPlyGltfImportIntoLodAndExhibit) {
    const auto probe = test::run(bodygen() + " lod " + export_to("in.stl") + " -o " + path("probe.bpm") + " --quiet");
    if (probe.output.find("libassimp-dev") != std::string::npos) GTEST_SKIP() << "bodygen built without libassimp-dev";
    ASSERT_EQ(probe.exit_code, 0) << probe.output;
    size_t structures = 0, triangles = 0;
    const auto [lo, hi] = bpm_bounds(path("probe.bpm"), structures, triangles);
    EXPECT_EQ(triangles, 640u);
    for (const char* name : {"in.ply", "in.glb", "in.gltf"}) {
        const auto r = test::run(bodygen() + " lod " + export_to(name) + " -o " + path("r.bpm") + " --quiet");
        ASSERT_EQ(r.exit_code, 0) << name << ": " << r.output;
        const auto [l, h] = bpm_bounds(path("r.bpm"), structures, triangles);
        EXPECT_EQ(triangles, 640u) << name;
        EXPECT_LT(glm::length(l - lo) + glm::length(h - hi), 1e-2) << name;  // same place, same units
        if (std::string(name) != "in.ply") {
            EXPECT_EQ(structures, 2u) << name;
        }
    }
    fs::create_directories(path("glb_dir"));
    fs::copy_file(path("in.glb"), path("glb_dir/in.glb"), fs::copy_options::overwrite_existing);
    const auto ex = test::run(bodygen() + " exhibit " + path("glb_dir") + " --quiet -o " + path("re_bundle"));
    ASSERT_EQ(ex.exit_code, 0) << ex.output;
    std::ifstream in(path("re_bundle") + "/scene.json");
    const auto s = nlohmann::json::parse(in);
    ASSERT_EQ(s["models"].size(), 2u);
    EXPECT_EQ(s["models"][0]["name"], scene()["models"][0]["name"]);  // glTF node names survive

    std::ofstream(path("bad.ply")) << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n";
    const auto bad = test::run(bodygen() + " lod " + path("bad.ply") + " -o " + path("bad.bpm"));
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
    EXPECT_NE(bad.output.find(path("bad.ply") + ": "), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(path("bad.bpm")));
}

// Export -> .wrl -> exhibit: every name, colour and vertex comes back (vertices
// within the new .bpm's quantization step of the placed originals).
TEST_F(ExportTest, VrmlRoundTripsThroughExhibit) {
    const std::string wrl = export_to("rt.wrl");
    const auto r = test::run(bodygen() + " exhibit " + wrl + " --quiet -o " + path("re_wrl"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    auto before = exporter::load_export_scene(path("bundle"), 1.0);
    auto after = exporter::load_export_scene(path("re_wrl"), 1.0);
    ASSERT_TRUE(before && after);
    ASSERT_EQ(after->models.size(), before->models.size());
    for (size_t k = 0; k < before->models.size(); ++k) {
        const exporter::ExportModel& b = before->models[k];
        const exporter::ExportModel& a = after->models[k];
        EXPECT_EQ(a.name, b.name);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.mesh.color[c], b.mesh.color[c], 1e-3) << a.name;
        ASSERT_EQ(a.mesh.vertex_count(), b.mesh.vertex_count()) << a.name;
        ASSERT_EQ(a.mesh.triangle_count(), b.mesh.triangle_count()) << a.name;
        double worst = 0.0;
        for (const Vec3& p : a.mesh.positions) {
            double nearest = 1e300;
            for (const Vec3& q : b.mesh.positions)
                nearest = std::min(nearest, glm::length(p - exporter::place_point(b, q)));
            worst = std::max(worst, nearest);
        }
        EXPECT_GT(a.quantization_bound, 0.0f);
        EXPECT_LE(worst, a.quantization_bound * 1.0001 + 1e-6) << a.name << ": a vertex moved more than the step";
    }
}

// A hand-written scene: nested Transforms (translation, rotation, scale, center),
// a USE'd Shape and a USE'd geometry, comments; names from the nearest DEF.
TEST_F(ExportTest, VrmlReaderAppliesNestedTransformsAndUse) {
    std::ofstream(path("hand.wrl")) << R"(#VRML V2.0 utf8
# a tetrahedron, 10 mm edges, three times
DEF Outer Transform { translation 0.1 0 0 rotation 0 0 1 1.5707963267948966 scale 2 2 2
  children [ Transform { translation 0 0.01 0 children [
    DEF Tet Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }
      geometry DEF TetGeo IndexedFaceSet { ccw TRUE solid FALSE   # tolerated
        coord Coordinate { point [ 0 0 0, 0.01 0 0, 0 0.01 0, 0 0 0.01 ] }
        coordIndex [ 0 2 1 -1 0 1 3 -1 0 3 2 -1 1 2 3 -1 ] } }
  ] } ] }
DEF Copy Transform { translation 0 0 0.05 center 0.01 0 0 rotation 0 0 1 3.141592653589793 children [ USE Tet ] }
DEF Plain Transform { children [ Shape { geometry USE TetGeo } ] }
)";
    auto meshes = read_vrml(path("hand.wrl"));
    ASSERT_TRUE(meshes) << meshes.error().message;
    ASSERT_EQ(meshes->size(), 3u);
    const auto near = [](const Vec3& a, const Vec3& b) { return glm::length(a - b) < 1e-9; };
    const auto str = [](const Vec3& v) {
        return std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z);
    };
    const Mesh& outer = (*meshes)[0];
    EXPECT_EQ(outer.name, "Tet");
    EXPECT_EQ(outer.color, Vec3(1, 0, 0));
    EXPECT_EQ(outer.triangle_count(), 4u);
    // (x, y, z) -> +0.01 y, x2, 90 deg about z, +0.1 x; metres to mm.
    EXPECT_TRUE(near(outer.positions[0], Vec3(80, 0, 0))) << str(outer.positions[0]);
    EXPECT_TRUE(near(outer.positions[1], Vec3(80, 20, 0))) << str(outer.positions[1]);
    EXPECT_TRUE(near(outer.positions[3], Vec3(80, 0, 20))) << str(outer.positions[3]);
    const Mesh& copy = (*meshes)[1];
    EXPECT_EQ(copy.name, "Tet_2");
    EXPECT_TRUE(near(copy.positions[0], Vec3(20, 0, 50))) << str(copy.positions[0]);  // half-turn about the centre
    EXPECT_TRUE(near(copy.positions[1], Vec3(10, 0, 50))) << str(copy.positions[1]);  // the centre stays
    const Mesh& plain = (*meshes)[2];
    EXPECT_EQ(plain.name, "Plain");  // the Shape has no DEF: the enclosing Transform's
    EXPECT_EQ(plain.color, Vec3(0.8, 0.8, 0.8));
    EXPECT_EQ(plain.indices, outer.indices);

    // In an exhibit the file's colour is kept; the uncoloured Shape gets the palette's.
    const auto r = test::run(bodygen() + " exhibit " + path("hand.wrl") + " --quiet -o " + path("hand_bundle"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::ifstream in(path("hand_bundle") + "/scene.json");
    const auto s = nlohmann::json::parse(in);
    ASSERT_EQ(s["models"].size(), 3u);
    EXPECT_EQ(s["models"][0]["name"], "Tet");
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s["models"][0]["colour"][c].get<double>(), c == 0 ? 1.0 : 0.0, 1e-3);
    EXPECT_NE(s["models"][2]["colour"], (nlohmann::json{0.8, 0.8, 0.8}));
}

// Bad .wrl files: one line naming the file and the line, exit 2, nothing written.
TEST_F(ExportTest, BadVrmlIsOneLocatedLineAndExitTwo) {
    const std::string shape = "Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0 1 0 0 0 1 0 ] }\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"#VRML V1.0 ascii\nSeparator { }\n", ":1: not VRML97"},
        {"#VRML V2.0 utf8\n" + shape + "  coordIndex [ 0 1 3 -1 ] } }\n", ":3: bad1: coordIndex 3 out of range"},
        {"#VRML V2.0 utf8\nTransform { children [\n" + shape + " coordIndex [ 0 1 2 -1 ] } }\n", ":2: "},
    };
    for (size_t k = 0; k < cases.size(); ++k) {
        const std::string file = path("bad" + std::to_string(k) + ".wrl");
        std::ofstream(file) << cases[k].first;
        for (const std::string& cmd :
             {" exhibit " + file + " -o " + path("bad_bundle"), " lod " + file + " -o " + path("bad.bpm")}) {
            const auto r = test::run(bodygen() + cmd);
            EXPECT_EQ(r.exit_code, 2) << cmd << ": " << r.output;
            EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
            EXPECT_NE(r.output.find(file + cases[k].second), std::string::npos) << r.output;
        }
        EXPECT_FALSE(fs::exists(path("bad_bundle")));
        EXPECT_FALSE(fs::exists(path("bad.bpm")));
    }
}

}  // namespace
}  // namespace body
