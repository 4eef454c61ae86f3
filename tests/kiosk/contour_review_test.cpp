// The contour review driven by replayed mouse and key events (the kiosk's
// replay format): a click on a link cuts it, two clicks on contours join them,
// x excludes, s saves; the saved stack file holds those overrides and
// `bodygen build`'s pipeline honours them.
#include "kiosk/app/contour_review.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "builder/pipeline/build_pipeline.h"
#include "kiosk/app/contour_review_text.h"
#include "kiosk/app/replay.h"
#include "tests/common/test_dir.h"

namespace body::kiosk {
namespace {

namespace fs = std::filesystem;

std::string square(double cx, double cy, double r = 5) {
    char b[160];
    std::snprintf(b, sizeof b, R"({"points": [[%g,%g],[%g,%g],[%g,%g],[%g,%g]]})", cx - r, cy - r, cx + r, cy - r,
                  cx + r, cy + r, cx - r, cy + r);
    return b;
}

// Slice 0: one square; slices 1 and 2: that square and one far away (x = 40).
std::string two_columns() {
    return R"({"format": "bodygen.contours", "version": 1, "slices": [{"z": 0, "contours": [)" + square(0, 0) +
           R"(]}, {"z": 4, "contours": [)" + square(0, 0) + ", " + square(40, 0) + R"(]}, {"z": 8, "contours": [)" +
           square(0, 0) + ", " + square(40, 0) + "]}]}";
}

class ContourReviewReplay : public ::testing::Test {
protected:
    fs::path dir;
    std::string path;
    void SetUp() override {
        dir = body::test::fresh_test_dir("contour_review");
        path = (dir / "stack.contours.json").string();
        std::ofstream(path) << two_columns();
    }
    void TearDown() override { fs::remove_all(dir); }

    // Plays `lines` (replay text after the size line) on `review`.
    void play(ContourReview& review, const std::string& lines) {
        auto replay = parse_replay("size 640 480\n" + lines, "test.replay");
        ASSERT_TRUE(replay.ok()) << replay.error().message;
        for (const InputEvent& e : replay->events) review.handle(e);
    }
    static std::string click_at(double t, glm::vec2 p) {
        char b[160];
        std::snprintf(b, sizeof b, "%.3f mouse-down left %.1f %.1f\n%.3f mouse-up left %.1f %.1f\n", t, p.x, p.y,
                      t + 0.05, p.x, p.y);
        return b;
    }
    // A pixel where a click picks the link between contours a and b.
    static glm::vec2 on_link(const ContourReview& r, ContourRef a, ContourRef b) {
        const auto& l = r.table().links;
        for (size_t i = 0; i < l.size(); ++i)
            if (l[i].lower == a && l[i].upper == b) {
                const auto& ca = r.contours()[*r.find(a)];
                const auto& cb = r.contours()[*r.find(b)];
                const glm::vec2 m = 0.5f * (*r.to_screen(ContourReview::world(ca, ca.centroid)) +
                                            *r.to_screen(ContourReview::world(cb, cb.centroid)));
                EXPECT_EQ(r.pick(m.x, m.y).kind, ReviewHit::Kind::Link);
                return m;
            }
        ADD_FAILURE() << "no link between the contours";
        return {};
    }
    // A pixel on contour `ref`'s outline (a corner or edge middle) where a click picks that contour.
    static glm::vec2 on_contour(const ContourReview& r, ContourRef ref) {
        const size_t i = *r.find(ref);
        const auto& pts = r.contours()[i].source->points;
        for (size_t k = 0; k < pts.size(); ++k)
            for (double t : {0.0, 0.5}) {
                const Vec2 p = pts[k] * (1 - t) + pts[(k + 1) % pts.size()] * t;
                auto s = r.to_screen(ContourReview::world(r.contours()[i], p));
                if (!s) continue;
                const ReviewHit hit = r.pick(s->x, s->y);
                if (hit.kind == ReviewHit::Kind::Contour && hit.index == i) return *s;
            }
        ADD_FAILURE() << "contour not pickable";
        return {};
    }
    static size_t components(const ContourStack& stack) {
        auto built = build_structures(stack, BuildOptions{}, "saved");
        EXPECT_TRUE(built.ok());
        size_t n = 0;
        if (built.ok())
            for (const auto& s : *built) n += s.components;
        return n;
    }
};

TEST_F(ContourReviewReplay, ClickingALinkCutsItAndSavingWritesTheLinksSection) {
    auto review = ContourReview::open(path, 640, 480);
    ASSERT_TRUE(review.ok()) << review.error().message;
    EXPECT_EQ(review->table().links.size(), 3u);  // 0-1 and 1-2 in the near column, 1-2 in the far one
    const size_t before = components(review->stack());
    const glm::vec2 at = on_link(*review, {1, 0}, {2, 0});
    play(*review, click_at(0.1, at) + "0.500 key 83 ctrl\n");
    EXPECT_FALSE(review->dirty()) << review->status();

    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find(R"("links":[{"cut":[[1,0],[2,0]]}])"), std::string::npos) << text;
    EXPECT_NE(text.find(R"("version":2)"), std::string::npos);
    auto saved = read_contour_stack(path);
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    ASSERT_EQ(saved->links.size(), 1u);
    EXPECT_EQ(saved->links[0], (LinkOverride{LinkEdit::Cut, {1, 0}, {2, 0}}));
    EXPECT_EQ(components(*saved), before + 1);  // the near column is two pieces now
    // The table shows the link as cut; a second click restores it.
    const glm::vec2 again = on_link(*review, {1, 0}, {2, 0});
    play(*review, click_at(0.1, again));
    EXPECT_TRUE(review->stack().links.empty());
    EXPECT_TRUE(review->dirty());
}

TEST_F(ContourReviewReplay, TwoContourClicksJoinAndXExcludes) {
    auto review = ContourReview::open(path, 640, 480);
    ASSERT_TRUE(review.ok()) << review.error().message;
    const size_t before = components(review->stack());
    std::string events = click_at(0.1, on_contour(*review, {0, 0})) + click_at(0.3, on_contour(*review, {1, 1}));
    play(*review, events);
    ASSERT_EQ(review->stack().links.size(), 1u) << review->status();
    EXPECT_EQ(review->stack().links[0], (LinkOverride{LinkEdit::Join, {0, 0}, {1, 1}}));
    play(*review, click_at(0.1, on_contour(*review, {2, 1})) + "0.300 key 88\n0.400 key 83\n");
    auto saved = read_contour_stack(path);
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    ASSERT_EQ(saved->links.size(), 2u);
    EXPECT_EQ(saved->links[1].edit, LinkEdit::Exclude);
    EXPECT_EQ(saved->links[1].a, (ContourRef{2, 1}));
    EXPECT_EQ(components(*saved), before - 1);  // the far column hangs from the near one as a branch
}

TEST_F(ContourReviewReplay, DragsAndRefusedJoinsChangeNothing) {
    auto review = ContourReview::open(path, 640, 480);
    ASSERT_TRUE(review.ok()) << review.error().message;
    const glm::vec2 at = on_link(*review, {1, 0}, {2, 0});
    char drag[200];
    std::snprintf(drag, sizeof drag,
                  "0.1 mouse-down left %.1f %.1f\n0.2 mouse-move %.1f %.1f\n0.3 mouse-up left %.1f %.1f\n", at.x, at.y,
                  at.x + 30, at.y, at.x + 30, at.y);
    play(*review, drag);  // an orbit, not a click
    EXPECT_TRUE(review->stack().links.empty());
    // Slices 0 and 2 are not adjacent: no join, the second contour becomes the selection.
    play(*review, click_at(1.0, on_contour(*review, {0, 0})) + click_at(1.2, on_contour(*review, {2, 1})));
    EXPECT_TRUE(review->stack().links.empty());
    EXPECT_EQ(review->selected(), review->find({2, 1}));
    EXPECT_NE(review->status().find("not on adjacent slices"), std::string::npos);
    EXPECT_FALSE(review->dirty());
}

// The text overlay counts what the table holds and follows every edit; `?` shows the keys.
TEST_F(ContourReviewReplay, TheOverlayCountsLinksAndOverridesAndQuestionMarkShowsTheKeys) {
    auto review = ContourReview::open(path, 640, 480);
    ASSERT_TRUE(review.ok()) << review.error().message;
    ReviewCounts c = review_counts(*review);
    EXPECT_EQ(c.contours, 5u);
    EXPECT_EQ(c.bands, 3u);  // the left column's two bands and the far square's one
    EXPECT_EQ(c.cut + c.joined + c.excluded + c.branches, 0u);
    EXPECT_EQ(c.ends, 4u);  // each column ends at the top and at the bottom
    EXPECT_FALSE(review->help_visible());
    LabelCard card = review_card(*review, 640, 480);
    EXPECT_NE(card.description.find("3 band"), std::string::npos) << card.description;
    EXPECT_EQ(card.description.find("exclude the selected"), std::string::npos);

    play(*review, click_at(0.1, on_link(*review, {1, 0}, {2, 0})) + "0.5 text 63\n");
    c = review_counts(*review);
    EXPECT_EQ(c.cut, 1u);
    EXPECT_EQ(c.bands, 2u);
    EXPECT_TRUE(review->help_visible());
    card = review_card(*review, 640, 480);
    EXPECT_NE(card.description.find("1 cut"), std::string::npos) << card.description;
    EXPECT_NE(card.description.find("x  exclude the selected contour"), std::string::npos) << card.description;
    EXPECT_NE(card.title.find("unsaved"), std::string::npos);
    EXPECT_LE(card.rect.y + card.rect.h, 480.0f);
    play(*review, "0.1 key 267\n");  // F1 hides it again
    EXPECT_FALSE(review->help_visible());
}

}  // namespace
}  // namespace body::kiosk
