#pragma once
// Whether points are hidden by what a frame drew, asked of the GPU: after
// Renderer::render (its depth buffer still bound), test() draws each point as
// one pixel with the depth test on and colour and depth writes off, inside one
// GL_ANY_SAMPLES_PASSED query per point. collect() reads the answers: without
// waiting a frame or more later (a live kiosk never stalls on them), or at once
// (a replay's or a screenshot's frame shows its own answers).
//
// The answer is what was drawn: the level of detail on screen, the cut plane's
// removed part (a point behind it is seen), hidden and faded models. A point is
// first moved toward the eye by kNudge of its distance, so that a point on a
// drawn surface is not hidden by that surface (the same margin as the kiosk's
// CPU ray test, KioskApp::test_pin_occlusion). A point outside the view, or
// behind the eye, is answered hidden. One batch is in flight at a time.
#include <span>
#include <vector>

#include "kiosk/render/renderer.h"

namespace body::render {

class PointOcclusion {
public:
    static constexpr float kNudge = 0.01f;

    PointOcclusion() = default;
    PointOcclusion(const PointOcclusion&) = delete;
    PointOcclusion& operator=(const PointOcclusion&) = delete;
    ~PointOcclusion();

    Status init();    // a GLES 3.0 context must be current
    void shutdown();  // idem; frees the program, buffers and queries

    // Queues one query per point (world coordinates) against `frame`'s depth
    // buffer, seen from `camera` as Renderer::render saw it. False (nothing
    // queued) before init() or while the last batch is not collected. No
    // flush: the frame's swap submits them (a flush here would split a tiled
    // or software renderer's frame in two, the overlay's part reloading the tiles).
    bool test(const View& camera, const FrameOptions& frame, std::span<const Vec3f> points);
    // The last batch's answers, one per point in test()'s order: 1 hidden, 0 seen.
    // False (`hidden` untouched) when no batch is in flight, or when `wait` is
    // false and some answer is not ready yet.
    bool collect(bool wait, std::vector<char>& hidden);

private:
    unsigned program_ = 0, vao_ = 0, vbo_ = 0;
    std::vector<unsigned> queries_;
    size_t in_flight_ = 0;         // queries issued by the last test(); 0 once collected
    std::vector<glm::vec4> clip_;  // the nudged points in clip space, kept between frames
};

}  // namespace body::render
