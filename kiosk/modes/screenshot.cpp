// The screenshot mode: one frame of a scene, or of one model file, written as
// PNG. Every model at its fixed LOD (--lod, else its group's or its own; an
// automatic one at full detail), decoded whole first; the camera frames the
// visible models' box from the scene's direction (or --view), at the scene's
// distance when it gives one.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "kiosk/modes/modes.h"
#include "kiosk/render/image.h"
#include "kiosk/scene/scene_models.h"
#include "shared/input_file.h"

namespace body::kiosk {
namespace {

// A model's properties in the picture: the manifest's, under the command line's overrides.
ModelBinding binding_of(const SceneModels& models, size_t i, const ViewOptions& o) {
    const scene::Scene& scene = models.scene();
    const scene::Model& m = scene.models[i];
    const scene::Group* g = m.group.empty() ? nullptr : scene.find_group(m.group);
    ModelBinding b;
    const scene::Lod lod = g && g->lod ? *g->lod : m.lod;
    b.lod_ratio = o.lod ? *o.lod : (lod.automatic ? 1.0 : lod.ratio);
    b.glide = false;
    b.transform = models.transform(i);
    b.style = o.style ? *o.style : (g && g->style ? *g->style : m.style);
    b.visible = g ? g->visible : true;
    if (o.select) {
        // One model file: its name, one of its structures' names, or "all".
        const auto names = models.structure_names(i);
        b.selected = *o.select == m.name || (!o.model_path.empty() &&
                                             (*o.select == "all" || std::count(names.begin(), names.end(), *o.select)));
    }
    return b;
}

// Whether --select names something in the picture (see binding_of).
bool select_matches(const SceneModels& models, const ViewOptions& o) {
    if (!o.model_path.empty() && *o.select == "all") return true;
    for (size_t i = 0; i < models.size(); ++i) {
        if (*o.select == models.scene().models[i].name) return true;
        const auto names = models.structure_names(i);
        if (!o.model_path.empty() && std::count(names.begin(), names.end(), *o.select)) return true;
    }
    return false;
}

// The camera framing the visible models' box from the scene's direction.
render::View framing(const render::Renderer& renderer, const scene::Scene& scene, const ViewOptions& o, float aspect) {
    const auto [azimuth, polar] = o.view_deg.value_or(std::make_pair(scene.camera.azimuth_deg, scene.camera.polar_deg));
    Vec3f center;
    float radius = 0;
    renderer.scene_bounds(center, radius);
    const float az = glm::radians(azimuth), po = glm::radians(polar);
    const Vec3f dir(std::sin(po) * std::sin(az), std::cos(po), std::sin(po) * std::cos(az));
    Vec3f lo(-1.0f), hi(1.0f);
    if (renderer.scene_box(lo, hi)) radius = 0.5f * glm::length(hi - lo);
    render::View camera = render::View::framing_box(lo, hi, dir, aspect, scene.camera.fov_deg);
    if (scene.camera.distance > 0) {
        camera.target = Vec3f(scene.camera.target[0], scene.camera.target[1], scene.camera.target[2]);
        camera.eye = camera.target + dir * scene.camera.distance;
        camera.near_plane = scene.camera.distance * 0.01f;
        camera.far_plane = scene.camera.distance * 10.0f + radius * 2.0f;
    }
    return camera;
}

// Draws, reads back (before presenting: after a swap the back buffer is undefined), downsamples and writes.
Status shoot(platform::Surface& surface, render::Renderer& renderer, const render::View& camera, const ViewOptions& o) {
    render::FrameOptions fo;
    fo.line_width_px = static_cast<float>(o.line_width) * static_cast<float>(o.ssaa);
    fo.xray_unselected = o.xray;
    fo.width = surface.width();
    fo.height = surface.height();
    fo.framebuffer = surface.framebuffer();
    renderer.render(camera, render::Lighting{}, fo);
    render::Image img;
    img.width = fo.width;
    img.height = fo.height;
    img.rgba = platform::read_pixels_rgba(fo.framebuffer, fo.width, fo.height);
    if (auto s = surface.present(); !s) return s;
    return render::write_png(o.screenshot, render::downsample(img, o.ssaa));
}

}  // namespace

int run_screenshot_mode(platform::Surface& surface, const ViewOptions& o, const scene::Scene& scene) {
    if (Status apart = check_output_apart(o.screenshot, {o.model_path, o.scene_path, o.replay}); !apart)
        return report(apart.error());
    SceneModels models(scene);
    render::Renderer renderer;
    if (auto s = renderer.init(o.renderer); !s) return report(s.error());
    const size_t loaded = models.load(renderer, LoadOptions{.file_colours = !o.model_path.empty()});
    models.release_detail(true);
    // Nothing to show (every model failed, each reported): no picture, bad input.
    if (loaded == 0) {
        renderer.shutdown();
        if (!scene.models.empty()) return kExitBadInput;  // each failure has its line already
        return report(input_error(o.screenshot + ": not written: the scene has no models"));
    }
    if (o.select && !select_matches(models, o)) {
        renderer.shutdown();
        return report(input_error("--select '" + *o.select + "': no model or structure of that name"));
    }
    {
        auto lock = models.lock();
        models.poll_streams();
        for (size_t i = 0; i < models.size(); ++i) models.bind(i, binding_of(models, i, o), 0.0);
    }
    const float aspect = static_cast<float>(surface.width()) / static_cast<float>(std::max(1, surface.height()));
    const Status shot = shoot(surface, renderer, framing(renderer, scene, o, aspect), o);
    renderer.shutdown();
    if (!shot) return report(shot.error());
    return kExitOk;  // a scene shows what it can: the failed models were reported
}

}  // namespace body::kiosk
