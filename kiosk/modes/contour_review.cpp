// `bodyview --contours STACK.contours.json`: the contour review's window over
// its GL-free state (kiosk/app/contour_review.h). The slices are drawn as
// stacked outlines (thin sticks along every contour edge, in the structure's
// colour; excluded contours pale, the selected one amber), the correspondence
// as sticks between contour centroids (grey: band, blue: branch, green:
// joined, red: cut) and the ends where a structure is capped as short orange
// stubs pointing out of it; `o` overlays the surface `bodygen build` makes, as
// wireframe. With --replay the events are applied first; with --screenshot one
// frame is written and the mode exits (the golden picture of the closing note).
// A card at the bottom left (app/contour_review_text.h) counts the links and
// overrides and, with `?`, lists the keys.
#include "kiosk/app/contour_review.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <tuple>

#include "builder/pipeline/build_pipeline.h"
#include "kiosk/app/contour_review_text.h"
#include "kiosk/app/overlay.h"
#include "kiosk/app/replay.h"
#include "kiosk/modes/modes.h"
#include "kiosk/render/image.h"
#include "shared/input_file.h"

namespace body::kiosk {
namespace {

const Vec3f kExcluded{0.78f, 0.78f, 0.76f}, kSelected{1.0f, 0.7f, 0.0f}, kUnlabelled{0.18f, 0.18f, 0.22f};
const Vec3f kBand{0.3f, 0.3f, 0.3f}, kBranch{0.15f, 0.4f, 0.9f}, kJoined{0.1f, 0.65f, 0.2f}, kCut{0.9f, 0.12f, 0.1f};
const Vec3f kEnd{0.95f, 0.55f, 0.1f};

// Triangles of one colour, made of thin boxes.
struct Sticks {
    std::vector<Vec3f> positions;
    std::vector<uint32_t> indices;
    // A box of half-width `t` from a to b.
    void add(const Vec3f& a, const Vec3f& b, float t) {
        const Vec3f d = b - a;
        if (glm::length(d) <= 0.0f) return;
        const Vec3f n = glm::normalize(d);
        const Vec3f side = std::abs(n.y) < 0.9f ? Vec3f(0, 1, 0) : Vec3f(1, 0, 0);
        const Vec3f u = glm::normalize(glm::cross(n, side)) * t, v = glm::normalize(glm::cross(n, u)) * t;
        const uint32_t base = uint32_t(positions.size());
        for (const Vec3f& end : {a, b})
            for (const Vec3f& c : {-u - v, u - v, u + v, -u + v}) positions.push_back(end + c);
        // Four sides (corners k, k+1 at both ends) and two end squares, outward.
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t k1 = (k + 1) % 4;
            indices.insert(indices.end(), {base + k, base + k1, base + 4 + k1, base + k, base + 4 + k1, base + 4 + k});
        }
        indices.insert(indices.end(), {base, base + 3, base + 2, base, base + 2, base + 1});
        indices.insert(indices.end(), {base + 4, base + 5, base + 6, base + 4, base + 6, base + 7});
    }
};

using ColorKey = std::tuple<float, float, float>;

// What the review shows, as sticks by colour.
std::map<ColorKey, Sticks> review_sticks(const ContourReview& r) {
    std::map<ColorKey, Sticks> out;
    auto sticks = [&](const Vec3f& c) -> Sticks& { return out[{c.x, c.y, c.z}]; };
    const float t = r.scene_radius() * 0.005f;
    const auto& cs = r.contours();
    for (size_t i = 0; i < cs.size(); ++i) {
        const ReviewContour& c = cs[i];
        const bool labelled = !c.source->structure.empty();
        const Vec3f color = r.selected() == i ? kSelected
                            : c.excluded      ? kExcluded
                            : labelled        ? Vec3f(c.color)
                                              : kUnlabelled;
        const auto& p = c.source->points;
        for (size_t k = 0; k < p.size(); ++k)
            sticks(color).add(ContourReview::world(c, p[k]), ContourReview::world(c, p[(k + 1) % p.size()]), t);
    }
    for (const TableLink& l : r.table().links) {
        auto a = r.find(l.lower), b = r.find(l.upper);
        if (!a || !b) continue;
        const Vec3f color = l.origin == LinkOrigin::Cut      ? kCut
                            : l.origin == LinkOrigin::Joined ? kJoined
                            : l.kind == LinkKind::Branch     ? kBranch
                                                             : kBand;
        sticks(color).add(ContourReview::world(cs[*a], cs[*a].centroid), ContourReview::world(cs[*b], cs[*b].centroid),
                          (l.origin == LinkOrigin::Cut ? 2.4f : 1.6f) * t);
    }
    const float stub = r.scene_radius() * 0.03f;
    for (const TableEnd& e : r.table().ends) {
        auto i = r.find(e.contour);
        if (!i) continue;
        const Vec3f at = ContourReview::world(cs[*i], cs[*i].centroid);
        sticks(kEnd).add(at, at + Vec3f(0, e.up ? stub : -stub, 0), 1.6f * t);
    }
    return out;
}

// The renderer's models for the review, rebuilt when it changes.
class ReviewDrawing {
public:
    explicit ReviewDrawing(render::Renderer& renderer) : renderer_(renderer) {}
    void rebuild(const ContourReview& r) {
        for (render::ModelId id : ids_) renderer_.remove_model(id);
        ids_.clear();
        for (auto& [key, s] : review_sticks(r)) {
            render::MeshData data;
            data.positions = s.positions;
            data.indices = s.indices;
            auto id = renderer_.add_model(data, "review");
            if (!id) continue;
            renderer_.state(*id)->color = Vec3f(std::get<0>(key), std::get<1>(key), std::get<2>(key));
            ids_.push_back(*id);
        }
        if (r.show_surface()) add_surface(r);
    }

private:
    // The built surface (as `bodygen build` makes it) in wireframe, stack coordinates turned to the world's.
    void add_surface(const ContourReview& r) {
        auto built = build_structures(r.stack(), BuildOptions{}, r.path());
        if (!built) {
            std::fprintf(stderr, "bodyview: %s\n", built.error().message.c_str());
            return;
        }
        for (const StructureMesh& m : *built) {
            std::vector<Vec3f> p;
            for (const Vec3& v : m.mesh.positions) p.emplace_back(float(v.x), float(v.z), float(-v.y));
            render::MeshData data;
            data.positions = p;
            data.indices = m.mesh.indices;
            auto id = renderer_.add_model(data, m.id);
            if (!id) continue;
            renderer_.state(*id)->style = Style::Wireframe;
            renderer_.state(*id)->color = Vec3f(m.mesh.color);
            ids_.push_back(*id);
        }
    }

    render::Renderer& renderer_;
    std::vector<render::ModelId> ids_;
};

render::FrameOptions frame_options(platform::Surface& surface, const ViewOptions& o) {
    render::FrameOptions fo;
    fo.width = surface.width();
    fo.height = surface.height();
    fo.framebuffer = surface.framebuffer();
    fo.line_width_px = float(o.line_width * o.ssaa);
    fo.manipulation_sphere = false;
    return fo;
}

void draw(render::Renderer& renderer, Overlay& overlay, ContourReview& review, const render::FrameOptions& fo) {
    review.camera().set_viewport(fo.width, fo.height);
    const render::View view = review.camera().render_view({0.0f, 0.0f}, review.scene_center(), review.scene_radius());
    renderer.render(view, render::Lighting{}, fo);
    overlay.draw({}, review_card(review, fo.width, fo.height), fo.framebuffer, fo.width, fo.height);
}

int screenshot(platform::Surface& surface, render::Renderer& renderer, Overlay& overlay, ContourReview& review,
               const ViewOptions& o) {
    const render::FrameOptions fo = frame_options(surface, o);
    draw(renderer, overlay, review, fo);
    render::Image img;
    img.width = fo.width;
    img.height = fo.height;
    img.rgba = platform::read_pixels_rgba(fo.framebuffer, fo.width, fo.height);
    if (auto s = surface.present(); !s) return report(s.error());
    if (auto s = render::write_png(o.screenshot, render::downsample(img, o.ssaa)); !s) return report(s.error());
    return kExitOk;
}

// The window: events to the review, a frame whenever something may have changed.
int live(platform::Surface& surface, render::Renderer& renderer, Overlay& overlay, ContourReview& review,
         ReviewDrawing& drawing, const ViewOptions& o) {
    std::vector<InputEvent> events;
    uint64_t shown = review.revision();
    std::string said = review.status();
    for (long frame = 0; o.frames <= 0 || frame < o.frames; ++frame) {
        events.clear();
        bool keep = surface.poll_events(events);
        for (const InputEvent& e : events) {
            if (e.type == InputEvent::Type::Quit || (e.type == InputEvent::Type::Key && e.key == platform::kKeyEscape))
                keep = false;
            review.handle(e);
        }
        if (review.status() != said) std::fprintf(stderr, "bodyview: %s\n", (said = review.status()).c_str());
        if (!keep) break;
        if (review.revision() != shown) drawing.rebuild(review), shown = review.revision();
        draw(renderer, overlay, review, frame_options(surface, o));
        if (auto s = surface.present(); !s) return report(s.error());
    }
    if (review.dirty())
        std::fprintf(stderr, "bodyview: %s: overrides not saved (press s to save)\n", o.contours_path.c_str());
    return kExitOk;
}

}  // namespace

int run_contour_review_mode(platform::Surface& surface, const ViewOptions& o, const scene::Scene&) {
    if (!o.screenshot.empty())
        if (Status apart = check_output_apart(o.screenshot, {o.contours_path, o.replay}); !apart)
            return report(apart.error());
    auto review = ContourReview::open(o.contours_path, surface.width(), surface.height());
    if (!review) return report(review.error());
    if (!review->status().empty()) std::fprintf(stderr, "bodyview: %s\n", review->status().c_str());
    if (!o.replay.empty()) {
        auto replay = read_replay(o.replay);
        if (!replay) return report(replay.error());
        for (const InputEvent& e : replay->events) review->handle(e);
    }
    render::Renderer renderer;
    if (auto s = renderer.init(o.renderer); !s) return report(s.error());
    Overlay overlay;
    const float scale = std::max(1.0f, float(std::min(surface.width(), surface.height())) / 800.0f);
    if (auto s = overlay.init(default_font_file(), scale); !s) {
        renderer.shutdown();
        return report(s.error());
    }
    ReviewDrawing drawing(renderer);
    drawing.rebuild(*review);
    const int code = o.screenshot.empty() ? live(surface, renderer, overlay, *review, drawing, o)
                                          : screenshot(surface, renderer, overlay, *review, o);
    overlay.shutdown();
    renderer.shutdown();
    return code;
}

}  // namespace body::kiosk
