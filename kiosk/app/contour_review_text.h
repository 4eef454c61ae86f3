#pragma once
// The contour review's text overlay, without GL (modes/contour_review.cpp draws
// it with the kiosk's Overlay as a card at the bottom left): the link counts
// and the reviewer's overrides, the last status, and with `?` (or F1) the keys.
#include <cstddef>
#include <string>
#include <vector>

#include "kiosk/app/contour_review.h"
#include "kiosk/app/label_card.h"

namespace body::kiosk {

// What the table holds now: built links by kind, the overrides in force, and the ends.
struct ReviewCounts {
    size_t contours = 0, bands = 0, branches = 0, joined = 0, cut = 0, excluded = 0, ends = 0;
};
ReviewCounts review_counts(const ContourReview& review);

// "14 contours · 9 band, 3 branch, 1 joined, 1 cut · 1 excluded · 4 ends"
std::string review_summary(const ContourReview& review);

// The help's lines (the keys and clicks of contour_review.h).
const std::vector<std::string>& review_help_lines();

// The card: the file and the summary (and "* unsaved"), the status, then the help when shown
// or a line saying `?` shows it. Placed at the bottom left of a width x height window.
LabelCard review_card(const ContourReview& review, int width, int height);

}  // namespace body::kiosk
