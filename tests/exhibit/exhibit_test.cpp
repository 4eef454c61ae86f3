// The exhibit stages one by one: orientation -> kiosk rotation, palette and its
// neighbour assignment, readable names, group and translation tables, and the
// parts of a contour stack through build_parts and scene_for.
#include "builder/exhibit/exhibit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "builder/exhibit/names.h"
#include "builder/exhibit/palette.h"

namespace body::exhibit {
namespace {

using Mat = std::array<std::array<double, 3>, 3>;

Mat euler_matrix(const std::array<float, 3>& deg) {
    // The kiosk's order (kiosk/scene/scene_models.cpp): Rz * Ry * Rx.
    const double a = glm::radians(double(deg[0])), b = glm::radians(double(deg[1])), c = glm::radians(double(deg[2]));
    const Mat rx = {{{1, 0, 0}, {0, std::cos(a), -std::sin(a)}, {0, std::sin(a), std::cos(a)}}};
    const Mat ry = {{{std::cos(b), 0, std::sin(b)}, {0, 1, 0}, {-std::sin(b), 0, std::cos(b)}}};
    const Mat rz = {{{std::cos(c), -std::sin(c), 0}, {std::sin(c), std::cos(c), 0}, {0, 0, 1}}};
    auto mul = [](const Mat& x, const Mat& y) {
        Mat r{};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k)
                    r[size_t(i)][size_t(j)] += x[size_t(i)][size_t(k)] * y[size_t(k)][size_t(j)];
        return r;
    };
    return mul(rz, mul(ry, rx));
}

Vec3 rotate_by(const Mat& m, const Vec3& v) {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

// Data point at patient direction `ras` (a RAS unit vector) expressed in the data's frame.
Vec3 data_coords(const std::array<Vec3, 3>& axes, const Vec3& ras) {
    return {glm::dot(axes[0], ras), glm::dot(axes[1], ras), glm::dot(axes[2], ras)};
}

TEST(ExhibitOrientation, EveryProperAxisFrameEndsHeadUpFacingTheAnteriorCamera) {
    const char* letters[3][2] = {{"R", "L"}, {"A", "P"}, {"S", "I"}};
    int frames = 0;
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (const auto& p : perms)
        for (int signs = 0; signs < 8; ++signs) {
            std::string o;
            for (int i = 0; i < 3; ++i) o += letters[p[i]][(signs >> i) & 1];
            auto axes = parse_orientation(o);
            ASSERT_TRUE(axes) << o;
            const int k = mirror_axis(*axes);
            if (k >= 0) {
                // Mirrored frames: after negating the named axis the frame is proper.
                (*axes)[size_t(k)] = -(*axes)[size_t(k)];
                EXPECT_EQ(mirror_axis(*axes), -1) << o;
                continue;
            }
            ++frames;
            const Mat m = euler_matrix(kiosk_rotation_deg(*axes));
            // Superior -> +Y (head up), anterior -> +Z (toward the azimuth-0 camera), left -> +X.
            const Vec3 up = rotate_by(m, data_coords(*axes, {0, 0, 1}));
            const Vec3 front = rotate_by(m, data_coords(*axes, {0, 1, 0}));
            const Vec3 left = rotate_by(m, data_coords(*axes, {-1, 0, 0}));
            EXPECT_NEAR(up.y, 1.0, 1e-5) << o;
            EXPECT_NEAR(front.z, 1.0, 1e-5) << o;
            EXPECT_NEAR(left.x, 1.0, 1e-5) << o;
        }
    EXPECT_EQ(frames, 24);
}

TEST(ExhibitOrientation, ObliqueFrameAndBadLetters) {
    // A slice frame tilted 30 degrees about R (as the NIfTI import makes for oblique planes).
    const double t = glm::radians(30.0);
    const std::array<Vec3, 3> axes = {Vec3(1, 0, 0), Vec3(0, std::cos(t), std::sin(t)),
                                      Vec3(0, -std::sin(t), std::cos(t))};
    const Mat m = euler_matrix(kiosk_rotation_deg(axes));
    const Vec3 up = rotate_by(m, data_coords(axes, {0, 0, 1}));
    EXPECT_NEAR(up.y, 1.0, 1e-5);
    EXPECT_FALSE(parse_orientation("RAR"));
    EXPECT_FALSE(parse_orientation("RA"));
    EXPECT_FALSE(parse_orientation("XYZ"));
    EXPECT_FLOAT_EQ(view_azimuth_deg(*parse_view("left")), 90.0f);  // eye at +X = the patient's left
    EXPECT_FALSE(parse_view("top"));
}

TEST(ExhibitPalette, DistinctColoursAndNeighboursApart) {
    const auto p = distinct_palette(24);
    double closest = 1e9;
    for (size_t i = 0; i < p.size(); ++i) {
        for (int k = 0; k < 3; ++k) EXPECT_TRUE(p[i][k] >= 0.0 && p[i][k] <= 1.0);
        for (size_t j = i + 1; j < p.size(); ++j) closest = std::min(closest, colour_distance(p[i], p[j]));
    }
    EXPECT_GT(closest, 0.02);  // no two alike even at 24 colours

    // A row of 12 touching boxes: the worst neighbouring pair must differ more than
    // the closest quarter of all pairs of the colours used (a random assignment
    // would put some neighbour among them with a probability near 96 %).
    std::vector<Box> boxes;
    for (int i = 0; i < 12; ++i) boxes.push_back({Vec3(i, 0, 0), Vec3(i + 1.0, 1, 1)});
    std::vector<std::optional<Vec3>> fixed(12);
    fixed[5] = Vec3(1, 0, 0);
    const auto c = assign_colours(boxes, fixed);
    EXPECT_EQ(c[5], Vec3(1, 0, 0));  // a source colour is kept
    std::vector<double> pairs;
    for (size_t i = 0; i < 12; ++i)
        for (size_t j = i + 1; j < 12; ++j) pairs.push_back(colour_distance(c[i], c[j]));
    std::sort(pairs.begin(), pairs.end());
    double worst = 1e9;
    for (size_t i = 0; i + 1 < 12; ++i) worst = std::min(worst, colour_distance(c[i], c[i + 1]));
    EXPECT_GT(worst, pairs[pairs.size() / 4]);
    EXPECT_FALSE(neighbours(boxes[0], boxes[5]));
    EXPECT_TRUE(neighbours(boxes[0], boxes[1]));
}

TEST(ExhibitNames, ReadableTitlesAndSides) {
    auto n = readable_name("Frontal_Sup_Orb_L");
    EXPECT_EQ(n.title, "Frontal sup orb");
    EXPECT_EQ(n.side, "left");
    EXPECT_EQ(n.with_side(), "Frontal sup orb (left)");
    EXPECT_EQ(readable_name("Left-Hippocampus").title, "Hippocampus");
    EXPECT_EQ(readable_name("ctx-rh-insula").side, "right");
    EXPECT_EQ(readable_name("ctx-rh-insula").title, "Insula");
    EXPECT_EQ(readable_name("Pontine_crossing_tract_(a_part_of_MCP)").title, "Pontine crossing tract (a part of MCP)");
    EXPECT_EQ(readable_name("Vermis_1_2").side, "");
    EXPECT_EQ(readable_name("Vermis_1_2").title, "Vermis 1 2");
    EXPECT_EQ(readable_name("kidney_right").side, "right");
    EXPECT_EQ(readable_name("Spinal cord").title, "Spinal cord");
    EXPECT_EQ(readable_name("Cerebellum_Crus1_R").title, "Cerebellum crus1");
}

TEST(ExhibitTables, GroupPatternsWithSides) {
    auto t = parse_group_table(
        "# c\npattern\tgroup\nFrontal_*\tfrontal-{side}\nVermis_*\tcerebellum-{side}\n*cord*\tspine\n", "g.tsv");
    ASSERT_TRUE(t) << t.error().message;
    EXPECT_EQ(t->group_of("Frontal_Sup_L", "left"), "frontal-left");
    EXPECT_EQ(t->group_of("Vermis_3", ""), "cerebellum");
    EXPECT_EQ(t->group_of("Spinal cord", ""), "spine");
    EXPECT_EQ(t->group_of("Liver", ""), "other");
    auto bad = parse_group_table("Frontal_* frontal\n", "g.tsv");
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().message, "g.tsv:1: expected 'PATTERN<TAB>GROUP'");
    EXPECT_FALSE(parse_group_table("# only comments\n", "g.tsv"));
}

TEST(ExhibitTables, Translations) {
    auto t = parse_translations(
        "name\tlang\ttitle\tdescription\nHippocampus_L\tde\tHippocampus (links)\tGedächtnis\n"
        "Hippocampus_L\tfr\tHippocampe (gauche)\n",
        "t.tsv");
    ASSERT_TRUE(t) << t.error().message;
    EXPECT_EQ(t->languages, (std::vector<std::string>{"de", "fr"}));
    EXPECT_EQ(t->rows["Hippocampus_L"]["de"].description, "Gedächtnis");
    EXPECT_EQ(t->rows["Hippocampus_L"]["fr"].description, "");
    auto dup = parse_translations("a\tde\tA\t\na\tde\tB\t\n", "t.tsv");
    ASSERT_FALSE(dup);
    EXPECT_EQ(dup.error().message, "t.tsv:2: a second row for 'a' in 'de'");
    EXPECT_FALSE(parse_translations("a\tde\n", "t.tsv"));
}

// Two square pillars in a contour stack, one with a degenerate contour that
// cannot build: the good one builds and lands in the scene, the bad one keeps
// its reason and is left out.
TEST(ExhibitParts, FailingStructureIsLeftOutOthersBuild) {
    ContourStack stack;
    stack.structures = {{"good", "Good_L", Vec3(0.8)}, {"bad", "Bad", Vec3(0.2, 0.4, 0.6)}};
    for (int z = 0; z < 4; ++z) {
        Slice s;
        s.z = z;
        s.contours.push_back({{{0, 0}, {4, 0}, {4, 4}, {0, 4}}, "good", size_t(z), 0});
        if (z == 1) s.contours.push_back({{{10, 0}, {11, 0}}, "bad", size_t(z), 1});  // two points: not a polygon
        s.source_index = size_t(z);
        stack.slices.push_back(s);
    }
    stack.voxel = 0.5;  // a label volume's: each part keeps it for --ring-voxel
    const auto parts = parts_from_stack(stack, "two.contours.json", *parse_orientation("RAS"));
    ASSERT_EQ(parts.size(), 2u);
    ASSERT_TRUE(parts[0].contours);
    EXPECT_EQ(parts[0].contours->voxel, std::optional<double>(0.5));
    EXPECT_FALSE(parts[0].colour);  // the format's default grey is no colour
    ASSERT_TRUE(parts[1].colour);
    PartOptions options;
    options.jobs = 2;
    size_t last_done = 0;
    options.progress = [&](size_t done, size_t) { last_done = done; };
    const auto built = build_parts(parts, options);
    EXPECT_EQ(last_done, 2u);
    ASSERT_FALSE(built[0].error) << built[0].error->message;
    EXPECT_TRUE(built[0].closed_manifold);
    EXPECT_FALSE(built[0].bpm.empty());
    ASSERT_TRUE(built[1].error);
    EXPECT_NE(built[1].error->message.find("two.contours.json"), std::string::npos) << built[1].error->message;

    const auto scene = scene_for(parts, built, {"models/Good_L.bpm", ""}, SceneOptions{});
    ASSERT_EQ(scene["models"].size(), 1u);
    EXPECT_EQ(scene["models"][0]["name"], "Good_L");
    EXPECT_EQ(scene["models"][0]["label"]["en"]["title"], "Good (left)");
    // RAS data turned so superior is +Y: Euler (90, 0, 180).
    EXPECT_EQ(scene["models"][0]["transform"]["rotate_deg"], nlohmann::json({90.0, 0.0, 180.0}));
    // Kiosk bounds: the pillar's z (superior) extent is now Y.
    EXPECT_NEAR(built[0].hi.y - built[0].lo.y, 3.0, 1.0);
    // The traced slices z = 0..3 turned with the model: planes dot(+Y, p) = z in the kiosk's world.
    const Mat m = euler_matrix(scene["models"][0]["transform"]["rotate_deg"].get<std::array<float, 3>>());
    const Vec3 n = rotate_by(m, Vec3(0, 0, 1));
    ASSERT_TRUE(scene.contains("cut_plane")) << scene.dump();
    EXPECT_EQ(scene["cut_plane"]["slices"], nlohmann::json({0.0, 1.0, 2.0, 3.0}));
    const auto sn = scene["cut_plane"]["slice_normal"].get<std::array<double, 3>>();
    EXPECT_NEAR(glm::length(Vec3(sn[0], sn[1], sn[2]) - n), 0.0, 1e-6);
    EXPECT_NEAR(n.y, 1.0, 1e-6);
    // SAR data is left-handed with z running left-right: z is mirrored (to L, kiosk +X), so the
    // planes' values flip sign.
    auto mirrored = parts;
    mirrored[0].ras_axes = *parse_orientation("SAR");
    ASSERT_EQ(mirror_axis(mirrored[0].ras_axes), 2);
    const auto flipped = scene_for(mirrored, built, {"models/Good_L.bpm", ""}, SceneOptions{});
    EXPECT_EQ(flipped["cut_plane"]["slices"], nlohmann::json({-3.0, -2.0, -1.0, 0.0}));
    EXPECT_EQ(flipped["cut_plane"]["slice_normal"], nlohmann::json({1.0, 0.0, 0.0}));
}

}  // namespace
}  // namespace body::exhibit
