#pragma once
// Contour review without GL (`bodyview --contours STACK.contours.json`; the
// drawing is kiosk/modes/contour_review.cpp): a contour stack, the
// correspondence `bodygen build` would use (builder/correspondence/
// link_table.h) and the reviewer's overrides, edited by mouse and keys and
// saved into the stack's "links" section (builder/contours/contour_stack.h).
//
// Input (InputEvent, pixels, origin top-left):
//   left click (press and release within kClickSlopPx) on a link: cut it; on a
//     cut link: restore it; on a joined link: remove the join;
//   left click on a contour: select it; a click on a contour of an adjacent
//     slice then joins the two (or restores their cut link); on the selected
//     contour or on nothing: deselect;
//   x: exclude the selected contour (again: include it);
//   s or Ctrl+S: save (atomically; the file is read back, so references are
//     those of the written file); o: the built surface on or off;
//   left drag: orbit; right drag: pan; wheel: zoom;
//   ? or F1: the help overlay on or off (contour_review_text.h).
// Geometry: stack (x, y, z) is shown as world (x, z, -y), a rotation that
// stacks the slices along the camera's up axis.
//
// A stack whose contours do not validate is still shown (the table is empty
// and status() says why); a join of contours of different structures, or
// not on adjacent slices, is refused in status() and changes nothing.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "builder/correspondence/link_table.h"
#include "kiosk/app/camera.h"
#include "kiosk/app/input.h"
#include "shared/error.h"

namespace body::kiosk {

inline constexpr float kClickSlopPx = 4.0f;   // a press moving less than this is a click
inline constexpr float kPickRadiusPx = 8.0f;  // how near a click must be to a link or outline

struct ReviewContour {
    ContourRef ref;
    size_t slice = 0;  // in the sorted, merged stack
    double z = 0.0;
    const Contour* source = nullptr;
    Vec2 centroid{0.0};
    Vec3 color{0.8};
    bool excluded = false;
};

struct ReviewHit {
    enum class Kind : uint8_t { None, Link, Contour } kind = Kind::None;
    size_t index = 0;  // into table().links or contours()
    float distance_px = 0.0f;
};

class ContourReview {
public:
    // Move-only: contours() point into stack().
    ContourReview() = default;
    ContourReview(const ContourReview&) = delete;
    ContourReview& operator=(const ContourReview&) = delete;
    ContourReview(ContourReview&&) = default;
    ContourReview& operator=(ContourReview&&) = default;

    // Reads `path` (errors as bodygen reports them) and computes the table.
    static Result<ContourReview> open(const std::string& path, int width, int height);

    const std::string& path() const { return path_; }
    const ContourStack& stack() const { return stack_; }
    const std::vector<ReviewContour>& contours() const { return contours_; }
    const LinkTable& table() const { return table_; }
    std::optional<size_t> selected() const { return selected_; }
    bool show_surface() const { return show_surface_; }
    bool help_visible() const { return help_; }
    bool dirty() const { return dirty_; }
    const std::string& status() const { return status_; }
    // Bumped whenever contours, links or the stack change (the drawing rebuilds).
    uint64_t revision() const { return revision_; }

    OrbitCamera& camera() { return camera_; }
    const OrbitCamera& camera() const { return camera_; }
    Vec3f scene_center() const { return center_; }
    float scene_radius() const { return radius_; }
    // World position of a point of contour `c` (see the header's mapping).
    static Vec3f world(const ReviewContour& c, const Vec2& p);
    // A contour's index by file reference (the first piece), if shown.
    std::optional<size_t> find(const ContourRef& ref) const;
    // Pixel position (origin top-left) of a world point; nullopt behind the eye.
    std::optional<glm::vec2> to_screen(const Vec3f& world) const;

    ReviewHit pick(float x, float y) const;
    // Edits (each recomputes the table; false with status() saying why when refused).
    bool toggle_link(size_t link);
    bool join(size_t a, size_t b);
    bool toggle_exclude(size_t contour);
    Status save();

    // One input event; returns true when it changed what is shown.
    bool handle(const InputEvent& e);

private:
    void rebuild();  // contours_ and table_ from stack_
    void click(float x, float y);
    bool remove_overrides(LinkEdit edit, const ContourRef& a, const ContourRef& b);

    std::string path_;
    ContourStack stack_;
    std::vector<ReviewContour> contours_;
    LinkTable table_;
    std::optional<size_t> selected_;
    bool show_surface_ = false, dirty_ = false, help_ = false;
    std::string status_;
    uint64_t revision_ = 0;
    OrbitCamera camera_;
    Vec3f center_{0.0f};
    float radius_ = 1.0f;
    // The mouse: a press not yet known to be a click or a drag.
    bool left_down_ = false, right_down_ = false, dragged_ = false;
    glm::vec2 press_{0.0f}, last_{0.0f};
};

}  // namespace body::kiosk
