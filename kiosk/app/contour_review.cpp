// Contour review state (contract in contour_review.h): the stack, its link
// table and the overrides, picking in screen space, edits and saving.
#include "kiosk/app/contour_review.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "builder/contours/contour_links.h"

namespace body::kiosk {
namespace {

// Area centroid of a closed polygon (the mean of its points when degenerate).
Vec2 centroid_of(const std::vector<Vec2>& p) {
    double a = 0.0;
    Vec2 c(0.0), mean(0.0);
    for (size_t i = 0; i < p.size(); ++i) {
        const Vec2& u = p[i];
        const Vec2& v = p[(i + 1) % p.size()];
        const double w = u.x * v.y - v.x * u.y;
        a += w;
        c += (u + v) * w;
        mean += u;
    }
    if (std::abs(a) > 1e-12) return c / (3.0 * a);
    return p.empty() ? mean : mean / double(p.size());
}

float segment_distance(const glm::vec2& p, const glm::vec2& a, const glm::vec2& b) {
    const glm::vec2 ab = b - a;
    const float l2 = glm::dot(ab, ab);
    const float t = l2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / l2, 0.0f, 1.0f) : 0.0f;
    return glm::length(a + ab * t - p);
}

bool pair_is(const LinkOverride& o, const ContourRef& a, const ContourRef& b) {
    return (o.a == a && o.b == b) || (o.a == b && o.b == a);
}

}  // namespace

Result<ContourReview> ContourReview::open(const std::string& path, int width, int height) {
    auto stack = read_contour_stack(path);
    if (!stack) return stack.error();
    ContourReview r;
    r.path_ = path;
    r.stack_ = std::move(*stack);
    r.rebuild();
    // The camera frames the stack from the front and a little above.
    Vec3f lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const ReviewContour& c : r.contours_)
        for (const Vec2& p : c.source->points) {
            const Vec3f w = world(c, p);
            lo = glm::min(lo, w), hi = glm::max(hi, w);
        }
    if (r.contours_.empty()) lo = Vec3f(-1.0f), hi = Vec3f(1.0f);
    r.center_ = 0.5f * (lo + hi);
    r.radius_ = std::max(0.5f * glm::length(hi - lo), 1e-3f);
    r.camera_.set_viewport(std::max(width, 1), std::max(height, 1));
    r.camera_.configure(35.0f, r.radius_);
    r.camera_.set_pose({r.center_, 0.5f, 1.2f, 0.62f * r.camera_.fit_distance(r.radius_)});
    return r;
}

Vec3f ContourReview::world(const ReviewContour& c, const Vec2& p) { return Vec3f(float(p.x), float(c.z), float(-p.y)); }

void ContourReview::rebuild() {
    contours_.clear();
    for (size_t s = 0; s < stack_.slices.size(); ++s)
        for (const Contour& c : stack_.slices[s].contours) {
            ReviewContour rc;
            rc.ref = {c.source_slice, c.source_contour};
            rc.slice = s;
            rc.z = stack_.slices[s].z;
            rc.source = &c;
            rc.centroid = centroid_of(c.points);
            for (const StructureInfo& info : stack_.structures)
                if (info.id == c.structure) rc.color = info.color;
            rc.excluded = std::any_of(stack_.links.begin(), stack_.links.end(), [&](const LinkOverride& o) {
                return o.edit == LinkEdit::Exclude && o.a == rc.ref;
            });
            contours_.push_back(rc);
        }
    auto table = compute_link_table(stack_, CorrespondenceMethod::Overlap, {}, path_);
    table_ = table ? std::move(*table) : LinkTable{};
    if (!table) status_ = table.error().message;
    ++revision_;
}

std::optional<size_t> ContourReview::find(const ContourRef& ref) const {
    for (size_t i = 0; i < contours_.size(); ++i)
        if (contours_[i].ref == ref) return i;
    return std::nullopt;
}

std::optional<glm::vec2> ContourReview::to_screen(const Vec3f& w) const {
    const glm::vec4 clip = camera_.projection() * camera_.view() * glm::vec4(w, 1.0f);
    if (clip.w <= 1e-6f) return std::nullopt;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return glm::vec2((ndc.x + 1.0f) * 0.5f * float(camera_.width()) - 0.5f,
                     (1.0f - ndc.y) * 0.5f * float(camera_.height()) - 0.5f);
}

ReviewHit ContourReview::pick(float x, float y) const {
    const glm::vec2 at(x, y);
    ReviewHit best;
    best.distance_px = kPickRadiusPx;
    for (size_t i = 0; i < table_.links.size(); ++i) {
        const TableLink& l = table_.links[i];
        auto a = find(l.lower), b = find(l.upper);
        if (!a || !b) continue;
        auto pa = to_screen(world(contours_[*a], contours_[*a].centroid));
        auto pb = to_screen(world(contours_[*b], contours_[*b].centroid));
        if (!pa || !pb) continue;
        const float d = segment_distance(at, *pa, *pb);
        if (d <= best.distance_px) best = {ReviewHit::Kind::Link, i, d};
    }
    for (size_t i = 0; i < contours_.size(); ++i) {
        const auto& pts = contours_[i].source->points;
        for (size_t k = 0; k < pts.size(); ++k) {
            auto pa = to_screen(world(contours_[i], pts[k]));
            auto pb = to_screen(world(contours_[i], pts[(k + 1) % pts.size()]));
            if (!pa || !pb) continue;
            const float d = segment_distance(at, *pa, *pb);
            if (d < best.distance_px) best = {ReviewHit::Kind::Contour, i, d};  // links win ties
        }
    }
    return best;
}

bool ContourReview::remove_overrides(LinkEdit edit, const ContourRef& a, const ContourRef& b) {
    const size_t before = stack_.links.size();
    std::erase_if(stack_.links, [&](const LinkOverride& o) { return o.edit == edit && pair_is(o, a, b); });
    return stack_.links.size() != before;
}

bool ContourReview::toggle_link(size_t i) {
    if (i >= table_.links.size()) return false;
    const TableLink l = table_.links[i];
    const std::string what = "link [" + std::to_string(l.lower.slice) + ", " + std::to_string(l.lower.contour) +
                             "] - [" + std::to_string(l.upper.slice) + ", " + std::to_string(l.upper.contour) + "]";
    switch (l.origin) {
        case LinkOrigin::Computed:
            stack_.links.push_back({LinkEdit::Cut, l.lower, l.upper});
            status_ = what + " cut";
            break;
        case LinkOrigin::Cut:
            remove_overrides(LinkEdit::Cut, l.lower, l.upper);
            status_ = what + " restored";
            break;
        case LinkOrigin::Joined:
            remove_overrides(LinkEdit::Join, l.lower, l.upper);
            status_ = what + " no longer joined";
            break;
    }
    dirty_ = true;
    rebuild();
    return true;
}

bool ContourReview::join(size_t a, size_t b) {
    if (a >= contours_.size() || b >= contours_.size()) return false;
    const ReviewContour &ca = contours_[a], &cb = contours_[b];
    if (ca.slice + 1 != cb.slice && cb.slice + 1 != ca.slice) {
        status_ = "not joined: the contours are not on adjacent slices";
        return false;
    }
    if (ca.source->structure != cb.source->structure) {
        status_ = "not joined: the contours belong to different structures";
        return false;
    }
    // A cut link between them is restored; otherwise they are joined.
    if (remove_overrides(LinkEdit::Cut, ca.ref, cb.ref)) {
        status_ = "link restored";
    } else {
        const bool lower_first = ca.slice < cb.slice;
        stack_.links.push_back({LinkEdit::Join, lower_first ? ca.ref : cb.ref, lower_first ? cb.ref : ca.ref});
        status_ = "contours joined";
    }
    dirty_ = true;
    rebuild();
    return true;
}

bool ContourReview::toggle_exclude(size_t i) {
    if (i >= contours_.size()) return false;
    const ContourRef ref = contours_[i].ref;
    const size_t before = stack_.links.size();
    std::erase_if(stack_.links, [&](const LinkOverride& o) { return o.edit == LinkEdit::Exclude && o.a == ref; });
    if (stack_.links.size() == before) stack_.links.push_back({LinkEdit::Exclude, ref, {}});
    status_ = stack_.links.size() > before ? "contour excluded" : "contour included";
    dirty_ = true;
    rebuild();
    return true;
}

Status ContourReview::save() {
    if (auto written = write_contour_stack(path_, stack_); !written) {
        status_ = written.error().message;
        return written;
    }
    // Read back: the file's slices are now in the written order, and so are the references.
    auto again = read_contour_stack(path_);
    if (!again) {
        status_ = again.error().message;
        return again.error();
    }
    stack_ = std::move(*again);
    selected_.reset();
    dirty_ = false;
    rebuild();
    status_ = "saved " + std::to_string(stack_.links.size()) + " override(s) to " + path_;
    return ok_status();
}

void ContourReview::click(float x, float y) {
    const ReviewHit hit = pick(x, y);
    if (hit.kind == ReviewHit::Kind::Link) {
        toggle_link(hit.index);
        selected_.reset();
    } else if (hit.kind == ReviewHit::Kind::Contour) {
        if (!selected_ || *selected_ == hit.index) {
            selected_ = selected_ ? std::nullopt : std::optional<size_t>(hit.index);
        } else if (join(*selected_, hit.index)) {
            selected_.reset();
        } else {
            selected_ = hit.index;
        }
        ++revision_;
    } else if (selected_) {
        selected_.reset();
        ++revision_;
    }
}

bool ContourReview::handle(const InputEvent& e) {
    using T = InputEvent::Type;
    const uint64_t before = revision_;
    const glm::vec2 at(e.x, e.y);
    switch (e.type) {
        case T::MouseDown:
            if (e.button() == MouseButton::Left) left_down_ = true;
            if (e.button() == MouseButton::Right) right_down_ = true;
            press_ = last_ = at;
            dragged_ = false;
            break;
        case T::MouseMove:
            if ((left_down_ || right_down_) && glm::length(at - press_) >= kClickSlopPx) dragged_ = true;
            if (dragged_ && left_down_) camera_.orbit(at.x - last_.x, at.y - last_.y);
            if (dragged_ && right_down_) camera_.pan(at.x - last_.x, at.y - last_.y);
            last_ = at;
            return dragged_;
        case T::MouseUp:
            if (e.button() == MouseButton::Left && left_down_ && !dragged_ && glm::length(at - press_) < kClickSlopPx)
                click(e.x, e.y);
            if (e.button() == MouseButton::Left) left_down_ = false;
            if (e.button() == MouseButton::Right) right_down_ = false;
            break;
        case T::Scroll: camera_.zoom(std::pow(1.15f, e.dy)); return true;
        case T::Text:
            if (e.key != '?') break;
            help_ = !help_;
            return true;
        case T::Key: {
            if (!e.pressed) break;
            if (e.key == platform::kKeyF1) {
                help_ = !help_;
                return true;
            }
            const int k = std::tolower(e.key);
            if (k == 'x' && selected_) toggle_exclude(*selected_);
            if (k == 's') (void)save();
            if (k == 'o') show_surface_ = !show_surface_, ++revision_;
            break;
        }
        default: break;
    }
    return revision_ != before;
}

}  // namespace body::kiosk
