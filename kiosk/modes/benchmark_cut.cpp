// The benchmark's cut-plane table (contract in benchmark.h): per style, and
// with the model selected under x-ray, the same view with the cut plane and
// its caps against the view without it, in alternating pairs of one run.
#include <GLES3/gl3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "kiosk/modes/benchmark.h"

namespace body::kiosk {
namespace {

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double at = q * static_cast<double>(v.size() - 1);
    const size_t i = static_cast<size_t>(at);
    return i + 1 >= v.size() ? v.back() : v[i] + (at - static_cast<double>(i)) * (v[i + 1] - v[i]);
}

struct CutCell {
    double plain_ms = 0, cut_ms = 0, median = 0, q1 = 0, q3 = 0, cpu = 0;
    size_t pairs = 0;
};

struct Timed {
    double wall, cpu;
};
Timed timed_frame(render::Renderer& r, const render::View& camera, const render::FrameOptions& frame) {
    const double c0 = cpu_now_ms();
    const double wall = frame_ms(r, camera, frame);
    return Timed{wall, cpu_now_ms() - c0};
}

// Frames without and with the plane alternate, P0 C0 P1 ... Cn-1 Pn; each cut
// frame is divided by the mean of the two plain frames around it (as the
// style table does), in wall and in CPU time, at least `min_pairs` pairs,
// then more until `seconds`. `move` > 0: each cut frame's plane is `move`
// further along its normal than the last one's, back and forth (a visitor
// dragging it: the cap's section is found again every frame).
CutCell time_pairs(render::Renderer& r, const render::View& camera, const render::FrameOptions& plain,
                   render::FrameOptions cut, int min_pairs, double seconds, float move = 0.0f) {
    const float w0 = cut.cut.plane.w;
    size_t frame = 0;
    auto next_cut = [&]() -> const render::FrameOptions& {
        cut.cut.plane.w = w0 + move * static_cast<float>(frame++ % 8);
        return cut;
    };
    for (int i = 0; i < 2; ++i) {  // warm-up: the clipped programs' first draws
        (void)frame_ms(r, camera, plain);
        (void)frame_ms(r, camera, next_cut());
    }
    std::vector<Timed> p{timed_frame(r, camera, plain)}, c;
    std::vector<double> ratio, cpu_ratio;
    const auto start = std::chrono::steady_clock::now();
    const auto spent = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    while (c.size() < static_cast<size_t>(std::max(min_pairs, 1)) || (spent() < seconds && c.size() < 200)) {
        c.push_back(timed_frame(r, camera, next_cut()));
        p.push_back(timed_frame(r, camera, plain));
        const Timed &a = p[p.size() - 2], &b = p.back();
        ratio.push_back(c.back().wall / (0.5 * (a.wall + b.wall)));
        cpu_ratio.push_back(c.back().cpu / (0.5 * (a.cpu + b.cpu)));
    }
    std::vector<double> pw, cw;
    for (const Timed& t : p) pw.push_back(t.wall);
    for (const Timed& t : c) cw.push_back(t.wall);
    return CutCell{
        quantile(pw, 0.5),        quantile(cw, 0.5), quantile(ratio, 0.5), quantile(ratio, 0.25), quantile(ratio, 0.75),
        quantile(cpu_ratio, 0.5), c.size()};
}

}  // namespace

Status compare_cut_plane(render::Renderer& renderer, render::ModelId id, const render::View& camera,
                         const render::FrameOptions& frame, int min_pairs, double seconds) {
    render::ModelState* st = renderer.state(id);
    Vec3f center;
    float radius = 0.0f;
    if (!st || !renderer.bounds(id, center, radius)) return runtime_error("cut plane benchmark: no model");
    center = Vec3f(st->transform * glm::vec4(center, 1.0f));
    // Through the model's centre, its removed half toward the eye and tilted
    // off the view axis, so the cap is seen at an angle, as a visitor leaves it.
    const Vec3f to_eye = glm::normalize(camera.eye - center);
    const Vec3f n = glm::normalize(to_eye + Vec3f(0.0f, 0.6f, 0.0f));
    render::FrameOptions cut = frame;
    cut.cut.enabled = true;
    cut.cut.plane = glm::vec4(n, -glm::dot(n, center));
    render::FrameOptions clip_only = cut;
    clip_only.cut.caps = false;
    std::printf(
        "cut plane (wall ms on this GL_RENDERER): the same view with the plane through the model's centre and its "
        "cap vs without the plane; ratio: median over pairs of cut frame / mean of the plain frames around it, "
        "ratio_IQR its quartiles (goal <= 1.3); clip_only: the plane without caps, likewise; moving: the plane "
        "moved by 1/400 of the model's radius each frame (the section found again each frame), likewise; cpu_: "
        "the same ratios in process CPU time (all threads)\n");
    std::printf("%-15s %9s %9s %6s %11s %9s %6s %9s %12s %10s %5s %s\n", "style", "plain_ms", "cut_ms", "ratio",
                "ratio_IQR", "clip_only", "moving", "cpu_ratio", "cpu_clip_only", "cpu_moving", "pairs", "goal");
    const Style style_before = st->style;
    const bool selected_before = st->selected;
    auto row = [&](const char* name, const render::FrameOptions& plain) {
        const CutCell c = time_pairs(
            renderer, camera, plain,
            [&] {
                render::FrameOptions o = cut;
                o.xray_unselected = plain.xray_unselected;
                return o;
            }(),
            min_pairs, seconds);
        render::FrameOptions clip = clip_only;
        clip.xray_unselected = plain.xray_unselected;
        const CutCell k = time_pairs(renderer, camera, plain, clip, min_pairs, seconds * 0.5);
        render::FrameOptions moving = cut;
        moving.xray_unselected = plain.xray_unselected;
        const CutCell mv = time_pairs(renderer, camera, plain, moving, min_pairs, seconds * 0.5, radius / 400.0f);
        std::printf("%-15s %9.2f %9.2f %6.2f %5.2f-%-5.2f %9.2f %6.2f %9.2f %12.2f %10.2f %5zu <= 1.3x %s\n", name,
                    c.plain_ms, c.cut_ms, c.median, c.q1, c.q3, k.median, mv.median, c.cpu, k.cpu, mv.cpu, c.pairs,
                    c.median <= 1.3 ? "ok" : "MISSED");
        std::fflush(stdout);
    };
    for (Style s : kAllStyles) {
        st->style = s;
        row(style_name(s), frame);
    }
    st->style = Style::Smooth;
    st->selected = true;  // the transparent pass: selection purple, caps blended
    render::FrameOptions xray = frame;
    xray.xray_unselected = true;
    row("selected/x-ray", xray);
    st->style = style_before;
    st->selected = selected_before;
    return ok_status();
}

}  // namespace body::kiosk
