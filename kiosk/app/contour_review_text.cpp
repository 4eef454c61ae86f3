// The contour review's text overlay (contract in contour_review_text.h).
#include "kiosk/app/contour_review_text.h"

#include <algorithm>
#include <filesystem>

namespace body::kiosk {

ReviewCounts review_counts(const ContourReview& review) {
    ReviewCounts c;
    c.contours = review.contours().size();
    for (const TableLink& l : review.table().links) {
        if (l.origin == LinkOrigin::Cut)
            ++c.cut;
        else if (l.origin == LinkOrigin::Joined)
            ++c.joined;
        else if (l.kind == LinkKind::Branch)
            ++c.branches;
        else
            ++c.bands;
    }
    c.excluded = static_cast<size_t>(std::count_if(review.contours().begin(), review.contours().end(),
                                                   [](const ReviewContour& r) { return r.excluded; }));
    c.ends = review.table().ends.size();
    return c;
}

std::string review_summary(const ContourReview& review) {
    const ReviewCounts c = review_counts(review);
    return std::to_string(c.contours) + " contours · " + std::to_string(c.bands) + " band, " +
           std::to_string(c.branches) + " branch, " + std::to_string(c.joined) + " joined, " + std::to_string(c.cut) +
           " cut · " + std::to_string(c.excluded) + " excluded · " + std::to_string(c.ends) + " ends";
}

const std::vector<std::string>& review_help_lines() {
    static const std::vector<std::string> lines = {
        "click a link: cut it (a cut or joined link: restore it)",
        "click a contour, then one on the next slice: join them",
        "x  exclude the selected contour (again: include it)",
        "s / Ctrl+S  save the links into the stack file",
        "o  the built surface on or off",
        "left drag  orbit   right drag  pan   wheel  zoom",
        "?  this help   Esc  quit",
        "colours: grey band, blue branch, green joined, red cut, orange end",
    };
    return lines;
}

LabelCard review_card(const ContourReview& review, int width, int height) {
    LabelCard card;
    card.visible = true;
    card.title = std::filesystem::path(review.path()).filename().string() + (review.dirty() ? "  * unsaved" : "");
    std::string body = review_summary(review);
    if (!review.status().empty()) body += "\n" + review.status();
    if (review.help_visible()) {
        for (const std::string& line : review_help_lines()) body += "\n" + line;
    } else {
        body += "\n? help";
    }
    card.description = body;
    const float w = std::min(static_cast<float>(width) - 32.0f, 640.0f * std::max(1.0f, height / 800.0f));
    const float h = static_cast<float>(height) * 0.6f;
    card.rect = Rect{16.0f, static_cast<float>(height) - 16.0f - h, w, h};
    return card;
}

}  // namespace body::kiosk
