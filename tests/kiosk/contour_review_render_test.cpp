// `bodyview --contours` end to end (headless, llvmpipe): the review's picture
// shows the correspondence, and a replayed click on a branch link cuts it,
// is saved into the stack file and leaves no branch to draw.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../cli/cli_test.h"
#include "kiosk/app/contour_review.h"
#include "kiosk/render/image.h"
#include "tests/common/test_dir.h"

namespace body::kiosk {
namespace {

namespace fs = std::filesystem;
using body::test::bin;
using body::test::run;

// Pixels of the branch links' blue (kBranch in kiosk/modes/contour_review.cpp, lit).
size_t blue_pixels(const render::Image& img) {
    size_t n = 0;
    for (size_t i = 0; i + 3 < img.rgba.size(); i += 4)
        if (img.rgba[i + 2] > 120 && img.rgba[i] < 90 && img.rgba[i + 1] < 150 &&
            img.rgba[i + 2] > img.rgba[i + 1] + 40)
            ++n;
    return n;
}

TEST(ContourReviewRender, AReplayedClickCutsABranchLinkAndSavesIt) {
    const fs::path dir = body::test::fresh_test_dir("contour_review_render");
    // The repository's review stack without its overrides.
    nlohmann::json stack;
    std::ifstream(std::string(BODY_SOURCE_DIR) + "/tests/data/stacks/review.contours.json") >> stack;
    stack.erase("links");
    const std::string path = (dir / "review.contours.json").string();
    std::ofstream(path) << stack.dump();

    const std::string view = bin("bodyview") + " --headless --size 800x600 --contours " + path;
    const std::string before_png = (dir / "before.png").string();
    auto r = run(view + " --screenshot " + before_png);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    auto before = render::read_png(before_png);
    ASSERT_TRUE(before.ok());
    EXPECT_GT(blue_pixels(*before), 50u);  // the trunk's 1:2 branch

    // Where the click goes: the middle of the branch link to the second branch, as the review projects it.
    auto review = ContourReview::open(path, 800, 600);
    ASSERT_TRUE(review.ok()) << review.error().message;
    const auto& cs = review->contours();
    const auto& a = cs[*review->find({3, 0})];
    const auto& b = cs[*review->find({4, 1})];
    const glm::vec2 at = 0.5f * (*review->to_screen(ContourReview::world(a, a.centroid)) +
                                 *review->to_screen(ContourReview::world(b, b.centroid)));
    const std::string replay = (dir / "cut.replay").string();
    std::ofstream(replay) << "size 800 600\n0.1 mouse-down left " << at.x << " " << at.y << "\n0.15 mouse-up left "
                          << at.x << " " << at.y << "\n0.5 key 83\n";
    const std::string after_png = (dir / "after.png").string();
    r = run(view + " --replay " + replay + " --screenshot " + after_png);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    auto saved = read_contour_stack(path);
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    ASSERT_EQ(saved->links.size(), 1u);
    EXPECT_EQ(saved->links[0], (LinkOverride{LinkEdit::Cut, {3, 0}, {4, 1}}));
    auto after = render::read_png(after_png);
    ASSERT_TRUE(after.ok());
    EXPECT_LT(blue_pixels(*after), 5u);  // what is left is a 1:1 band

    // A bad stack is one line and exit 2.
    std::ofstream(dir / "bad.contours.json") << R"({"format": "bodygen.contours", "version": 9, "slices": []})";
    r = run(bin("bodyview") + " --headless --contours " + (dir / "bad.contours.json").string() + " --screenshot " +
            (dir / "bad.png").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.output,
              "bodyview: " + (dir / "bad.contours.json").string() + ": unsupported version (expected 1 or 2)\n");
    EXPECT_FALSE(fs::exists(dir / "bad.png"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace body::kiosk
