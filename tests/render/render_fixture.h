#pragma once
// Shared set-up for the render tests: a headless surface + renderer, generated
// meshes (no data files needed), frame capture and the image metrics.
#include <memory>
#include <string>
#include <vector>

#include "kiosk/render/image.h"
#include "kiosk/render/renderer.h"
#include "platform/platform.h"

namespace body::test {

struct GenMesh {
    std::vector<Vec3f> positions;
    std::vector<uint32_t> indices;
    render::MeshData data() const { return {positions, {}, indices}; }
};
GenMesh icosphere(int subdivisions, float radius = 1.0f);
GenMesh cube(float half = 1.0f);  // 8 vertices, 12 triangles
GenMesh torus(int rings, int segments, float major, float minor);

class RenderFixture {
public:
    // Creates a headless surface; ok() is false (with why()) when EGL is unusable.
    RenderFixture(int width = 320, int height = 200, const render::RendererOptions& options = {});
    bool ok() const { return ok_; }
    const std::string& why() const { return why_; }
    render::Renderer& renderer() { return renderer_; }
    render::FrameOptions frame() const;
    render::Image draw(const render::View& camera, const render::Lighting& lighting = {});
    render::Image draw(const render::View& camera, const render::Lighting& lighting, const render::FrameOptions& o);

private:
    std::unique_ptr<platform::Surface> surface_;
    render::Renderer renderer_;
    bool ok_ = false;
    std::string why_;
};

// Tolerant comparison: both images box-filtered 4x4; reports the fraction of
// blocks whose largest channel difference exceeds `block_threshold` and the
// mean luminance difference (b - a) over the pixels that show an object in
// either image (background = the colour of the top-left pixel).
struct ImageDiff {
    double bad_block_fraction = 0;
    double mean_luma_delta = 0;
};
ImageDiff compare(const render::Image& a, const render::Image& b, int block_threshold = 24);

double luma(const uint8_t* p);
// Pixels that differ from the background colour by more than `threshold`.
std::vector<bool> foreground_mask(const render::Image& img, Vec3f background, int threshold = 12);

}  // namespace body::test
