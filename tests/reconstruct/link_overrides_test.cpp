// Correspondence overrides ("links" in the stack file) change the built mesh
// as asked: a cut splits a structure, a join makes a branch, an exclusion
// takes a contour's area away; the link table shows what build uses.
#include <gtest/gtest.h>

#include "builder/correspondence/link_table.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body::test {
namespace {

std::vector<StructureMesh> build_ok(const ContourStack& stack) {
    auto built = build_structures(stack, BuildOptions{}, "t.json");
    EXPECT_TRUE(built.ok()) << built.error().message;
    return built.ok() ? std::move(*built) : std::vector<StructureMesh>{};
}

// A column of circles on four slices (labelled "a" when `label`).
ContourStack column(bool label) {
    StackBuilder b;
    const std::string id = label ? "a" : "";
    for (int s = 0; s < 4; ++s) b.slice(2.0 * s, {circle(0, 0, 5)}, id);
    if (label) b.stack.structures.push_back({"a", "A", Vec3(0.8)});
    return b.stack;
}

// Slice 0: one circle at x = 0; slices 1 and 2: circles at x = 0 and x = 30
// (the far column overlaps nothing below it).
ContourStack two_columns() {
    StackBuilder b;
    b.slice(0, {circle(0, 0, 5)}, "a");
    b.slice(2, {circle(0, 0, 5), circle(30, 0, 5)}, "a");
    b.slice(4, {circle(0, 0, 5), circle(30, 0, 5)}, "a");
    b.stack.structures.push_back({"a", "A", Vec3(0.8)});
    return b.stack;
}

TEST(LinkOverrides, CuttingALinkSplitsAStructureIntoTwoClosedParts) {
    ContourStack stack = column(true);
    auto whole = build_ok(stack);
    ASSERT_EQ(whole.size(), 1u);
    EXPECT_EQ(whole[0].components, 1u);
    stack.links.push_back({LinkEdit::Cut, {1, 0}, {2, 0}});
    auto cut = build_ok(stack);
    ASSERT_EQ(cut.size(), 1u);
    EXPECT_EQ(cut[0].components, 2u);
    expect_good_structure(cut[0], stack, "a", /*check_reslice=*/false);
    // Each part is capped between slices 1 and 2: nothing of the mesh crosses z = 3.
    EXPECT_TRUE(slice_mesh(cut[0].mesh, 3.0).empty());
    EXPECT_FALSE(slice_mesh(whole[0].mesh, 3.0).empty());
}

TEST(LinkOverrides, CuttingUnlabelledContoursMakesTwoStructures) {
    ContourStack stack = column(false);
    ASSERT_EQ(build_ok(stack).size(), 1u);
    stack.links.push_back({LinkEdit::Cut, {2, 0}, {1, 0}});  // either order
    auto cut = build_ok(stack);
    ASSERT_EQ(cut.size(), 2u);
    EXPECT_EQ(cut[0].id, "auto_1");
    EXPECT_EQ(cut[1].id, "auto_2");
    for (const StructureMesh& s : cut) {
        EXPECT_EQ(s.contours, 2u);
        EXPECT_EQ(s.components, 1u);
        expect_good_structure(s, stack, "", /*check_reslice=*/false);
    }
}

TEST(LinkOverrides, JoiningTwoContoursMakesABranch) {
    ContourStack stack = two_columns();
    auto apart = build_ok(stack);
    ASSERT_EQ(apart.size(), 1u);
    EXPECT_EQ(apart[0].components, 2u);
    stack.links.push_back({LinkEdit::Join, {0, 0}, {1, 1}});
    auto joined = build_ok(stack);
    ASSERT_EQ(joined.size(), 1u);
    EXPECT_EQ(joined[0].components, 1u);
    EXPECT_EQ(joined[0].genus, 0);
    expect_good_structure(joined[0], stack, "a", /*check_reslice=*/false);
    // The branch reaches across: half way between slices 0 and 1 the mesh
    // goes half way to the far column (whose nearest side is at x = 25).
    auto max_x = [](const Mesh& m) {
        double x = -1e9;
        for (const Segment2& s : slice_mesh(m, 1.0)) x = std::max({x, s.a.x, s.b.x});
        return x;
    };
    EXPECT_LE(max_x(apart[0].mesh), 5.0 + 1e-9);
    EXPECT_GT(max_x(joined[0].mesh), 12.0);
}

TEST(LinkOverrides, ExcludingAContourRemovesItsArea) {
    ContourStack stack = two_columns();
    auto all = build_ok(stack);
    stack.links.push_back({LinkEdit::Exclude, {1, 1}, {}});
    auto less = build_ok(stack);
    ASSERT_EQ(all.size(), 1u);
    ASSERT_EQ(less.size(), 1u);
    EXPECT_EQ(less[0].contours, all[0].contours - 1);
    EXPECT_LT(less[0].volume, all[0].volume);
    expect_good_structure(less[0], stack, "a", /*check_reslice=*/false);
    // Nothing is left at the excluded contour's place on its slice (z = 2, x = 30).
    for (const Vec3& p : less[0].mesh.positions) EXPECT_FALSE(std::abs(p.z - 2.0) < 0.5 && p.x > 20.0);
}

TEST(LinkOverrides, TheLinkTableShowsCutsJoinsEndsAndExclusions) {
    ContourStack stack = two_columns();
    stack.links = {{LinkEdit::Join, {0, 0}, {1, 1}}, {LinkEdit::Cut, {1, 0}, {2, 0}}, {LinkEdit::Exclude, {2, 1}, {}}};
    auto table = compute_link_table(stack, CorrespondenceMethod::Overlap, {}, "t.json");
    ASSERT_TRUE(table.ok()) << table.error().message;
    auto find = [&](ContourRef lo, ContourRef up) -> const TableLink* {
        for (const TableLink& l : table->links)
            if (l.lower == lo && l.upper == up) return &l;
        return nullptr;
    };
    ASSERT_EQ(table->links.size(), 3u);
    const TableLink* computed = find({0, 0}, {1, 0});
    const TableLink* joined = find({0, 0}, {1, 1});
    const TableLink* cut = find({1, 0}, {2, 0});
    ASSERT_TRUE(computed && joined && cut);
    EXPECT_EQ(computed->origin, LinkOrigin::Computed);
    EXPECT_EQ(computed->kind, LinkKind::Branch);
    EXPECT_EQ(joined->origin, LinkOrigin::Joined);
    EXPECT_EQ(joined->kind, LinkKind::Branch);
    EXPECT_EQ(cut->origin, LinkOrigin::Cut);
    EXPECT_EQ(computed->structure, "a");
    ASSERT_EQ(table->excluded.size(), 1u);
    EXPECT_EQ(table->excluded[0], (ContourRef{2, 1}));
    // Ends: slice 0 below; both slice-1 contours above (one cut, one whose upper neighbour is excluded); slice 2's
    // remaining contour on both sides.
    size_t top = 0, bottom = 0;
    for (const TableEnd& e : table->ends) (e.up ? top : bottom) += 1;
    EXPECT_EQ(top, 3u);
    EXPECT_EQ(bottom, 2u);
}

}  // namespace
}  // namespace body::test
