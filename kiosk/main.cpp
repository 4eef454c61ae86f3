// bodyview: the fullscreen GLES 3 kiosk viewer. This file wires the platform
// layer, model files and the renderer: headless screenshots, the benchmark and
// a plain interactive view (the kiosk app adds gestures, labels and LOD control).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "body/version.h"
#include "kiosk/app/kiosk_run.h"
#include "kiosk/render/benchmark.h"
#include "kiosk/render/image.h"
#include "kiosk/render/model_source.h"
#include "kiosk/render/renderer.h"
#include "platform/evdev_input.h"
#include "platform/platform.h"
#include "shared/cli_args.h"
#include "shared/error.h"
#include "shared/scene/scene.h"

namespace {

using namespace body;

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "bodyview %s - shows anatomy models on a touch screen (OpenGL ES 3.0)\n\n"
                 "usage: bodyview [options] [BUNDLE/]\n"
                 "       bodyview --headless --size 1280x800 --model X.bpm --style S --lod R --screenshot out.png\n"
                 "       bodyview --headless --benchmark [--model X.bpm]\n\noptions:\n"
                 "  --platform P      auto|glfw|drm|headless (compiled here:",
                 BODY_VERSION_STRING);
    for (auto b : platform::compiled_backends()) std::fprintf(out, " %s", platform::backend_name(b));
    std::fprintf(out,
                 ")\n"
                 "  --headless        same as --platform headless\n"
                 "  --size WxH        window/offscreen size (headless default 1280x800)\n"
                 "  --windowed        glfw: a window instead of fullscreen\n"
                 "  --mode WxH[@Hz]   drm: display mode (default: the preferred one)\n"
                 "  --device PATH     drm: /dev/dri/cardN (default: the first that works)\n"
                 "  --rotate DEG      touch panel rotation against the display: 0|90|180|270 (default 0)\n"
                 "  --model FILE      a .bpm progressive mesh or .obj file\n"
                 "  --scene FILE      a scene manifest (scene.json); BUNDLE/ means BUNDLE/scene.json\n"
                 "  --style S         smooth|wireframe|lines|hatching|hatching-2tone (overrides the scene)\n"
                 "  --lod R           level of detail, ratio of the full triangles in (0,1] (default 1)\n"
                 "  --select NAME     select a model (transparent purple + manipulation sphere)\n"
                 "  --xray            fade everything not selected\n"
                 "  --view AZ,POLAR   camera azimuth and polar angle in degrees (default 20,75)\n"
                 "  --line-width PX   silhouette width in pixels (default 2)\n"
                 "  --ssaa N          headless: render N times larger and downsample the screenshot\n"
                 "  --buffer-access A auto|in-place|staged: how GL buffers are patched (auto: staged\n"
                 "                    on NVIDIA and AMD, whose drivers draw a buffer mapped for writing\n"
                 "                    from host memory for a while; in place elsewhere)\n"
                 "  --screenshot PNG  render one frame, write it as PNG and exit\n"
                 "  --frames N        interactive: exit after N frames\n"
                 "  --replay FILE     scene: play scripted touch/mouse input (kiosk/app/replay.h), then exit\n"
                 "  --no-auto-lod     scene: keep the manifest's LOD (the automatic LOD controller off)\n"
                 "  --kiosk-stats     scene: print time to first frame / full detail and frame times\n"
                 "  --benchmark       time every style at LOD 100/40/10%% against a flat baseline\n"
                 "  --bench-triangles N  size of the generated benchmark model (default 1000000; the\n"
                 "                    nearest count a subdivision of the bunny or a sphere gives)\n"
                 "  --bench-frames N  at least N timed pairs per style and LOD, more up to 3 s (default 9)\n"
                 "  --help            this text\n  --version         print the version\n\n"
                 "A model that cannot be loaded is skipped with a one-line error (nothing drawn).\n"
                 "exit codes: 0 ok, 1 runtime failure, 2 bad usage or bad input\n");
}

int fail(const Error& e) {
    std::fprintf(stderr, "bodyview: %s\n", e.message.c_str());
    return e.exit_code;
}

struct Placed {
    render::ModelSource source;
    render::ModelId id = 0;
};

// Uploads every structure of one file; a failure is logged and skipped.
// Returns false when the file could not be used.
bool load_into(render::Renderer& renderer, const std::string& path, double lod, std::vector<Placed>& out,
               size_t& first) {
    first = out.size();
    auto sources = render::load_model_file(path);
    if (!sources) {
        std::fprintf(stderr, "bodyview: %s\n", sources.error().message.c_str());
        return false;
    }
    for (auto& src : sources.value()) {
        auto id = renderer.add_model(src.upload_mesh(), src.name());
        if (!id) {
            std::fprintf(stderr, "bodyview: %s: %s\n", path.c_str(), id.error().message.c_str());
            continue;
        }
        (void)src.take_dirty();
        if (lod < 1.0) {
            src.set_lod(lod);
            if (auto s = renderer.update_model(id.value(), src.upload_mesh(), src.take_dirty()); !s)
                std::fprintf(stderr, "bodyview: %s: %s\n", path.c_str(), s.error().message.c_str());
        }
        src.release_arrays();  // the renderer keeps its own copy
        // Files without a colour of their own (the OBJ default grey) keep the renderer's.
        if (src.color() != Vec3f(0.8f)) renderer.state(id.value())->color = src.color();
        out.push_back({std::move(src), id.value()});
    }
    return out.size() > first;
}

int run(const CliArgs& args) {
    // ---- options
    platform::SurfaceOptions so;
    if (args.has("headless")) so.backend = platform::Backend::Headless;
    if (auto p = args.get("platform")) {
        auto b = platform::parse_backend(*p);
        if (!b) return fail(b.error());
        if (args.has("headless") && b.value() != platform::Backend::Headless)
            return fail(input_error("--headless contradicts --platform " + *p));
        so.backend = b.value();
    }
    if (auto s = args.get("size")) {
        auto wh = platform::parse_size(*s);
        if (!wh) return fail(wh.error());
        so.width = wh->first;
        so.height = wh->second;
    }
    so.fullscreen = !args.has("windowed");
    so.mode = args.get_or("mode", "");
    so.drm_device = args.get_or("device", "");
    if (auto r = args.get("rotate")) {
        auto deg = platform::parse_rotation(*r);
        if (!deg) return fail(deg.error());
        so.touch_rotation = deg.value();
    }
    auto lod = args.get_double("lod", 1.0);
    if (!lod) return fail(lod.error());
    if (!(lod.value() > 0.0 && lod.value() <= 1.0)) return fail(input_error("--lod must be in (0, 1]"));
    auto ssaa = args.get_long("ssaa", 1);
    if (!ssaa) return fail(ssaa.error());
    if (ssaa.value() < 1 || ssaa.value() > 4) return fail(input_error("--ssaa must be 1..4"));
    auto line_width = args.get_double("line-width", 2.0);
    if (!line_width) return fail(line_width.error());
    auto frames = args.get_long("frames", 0);
    if (!frames) return fail(frames.error());
    std::optional<render::Style> style_override;
    if (auto s = args.get("style")) {
        auto st = render::parse_style(*s);
        if (!st) return fail(st.error());
        style_override = st.value();
    }
    float azimuth = 20.0f, polar = 75.0f;
    bool view_given = false;
    if (auto v = args.get("view")) {
        if (std::sscanf(v->c_str(), "%f,%f", &azimuth, &polar) != 2)
            return fail(input_error("--view expects AZIMUTH,POLAR in degrees, e.g. 20,75"));
        view_given = true;
    }
    render::RendererOptions renderer_options;
    if (auto a = args.get("buffer-access")) {
        auto access = render::parse_buffer_access(*a);
        if (!access) return fail(access.error());
        renderer_options.buffer_access = access.value();
    }
    std::string scene_path = args.get_or("scene", "");
    if (!args.positional().empty()) {
        if (args.positional().size() > 1 || !scene_path.empty())
            return fail(input_error("one scene or bundle at most"));
        scene_path = (std::filesystem::path(args.positional()[0]) / "scene.json").string();
    }
    const std::string model_path = args.get_or("model", "");
    const bool benchmark = args.has("benchmark");
    if (!benchmark && model_path.empty() && scene_path.empty())
        return fail(input_error("nothing to show: give --model FILE, --scene FILE or a BUNDLE/ (see --help)"));
    if (!model_path.empty() && !scene_path.empty()) return fail(input_error("--model and --scene exclude each other"));

    std::optional<scene::Scene> scene;
    if (!scene_path.empty()) {
        auto sc = scene::read_scene(scene_path);
        if (!sc) return fail(sc.error());
        scene = std::move(sc.value());
    }
    if (so.backend == platform::Backend::Headless) {
        if (so.width == 0) so.width = 1280, so.height = 800;
        so.width *= static_cast<int>(ssaa.value());
        so.height *= static_cast<int>(ssaa.value());
    }

    // ---- surface and renderer
    auto surface = platform::create_surface(so);
    if (!surface) return fail(surface.error());
    platform::Surface& surf = *surface.value();
    if (benchmark) {
        render::BenchmarkOptions bo;
        bo.model = model_path;
        bo.renderer = renderer_options;
        auto tris = args.get_long("bench-triangles", 1000000);
        if (!tris) return fail(tris.error());
        if (tris.value() < 1000) return fail(input_error("--bench-triangles must be at least 1000"));
        bo.target_triangles = static_cast<size_t>(tris.value());
        auto bench_frames = args.get_long("bench-frames", bo.frames);
        if (!bench_frames) return fail(bench_frames.error());
        if (bench_frames.value() < 1) return fail(input_error("--bench-frames must be at least 1"));
        bo.frames = static_cast<int>(bench_frames.value());
        auto s = render::run_benchmark(surf, bo);
        return s ? kExitOk : fail(s.error());
    }
    // Kiosk mode (kiosk/app): a scene shown live with gestures, labels and automatic
    // LOD, or driven by --replay; a plain --screenshot of a scene stays below.
    if (scene && (args.has("replay") || !args.has("screenshot"))) {
        kiosk::KioskRunOptions ko;
        ko.replay = args.get_or("replay", "");
        ko.screenshot = args.get_or("screenshot", "");
        ko.frames = frames.value();
        ko.auto_lod = !args.has("no-auto-lod");
        ko.verbose = args.has("kiosk-stats");
        ko.touch_rotation = so.touch_rotation;
        ko.renderer = renderer_options;
        return kiosk::run_kiosk(surf, *scene, ko);
    }
    render::Renderer renderer;
    if (auto s = renderer.init(renderer_options); !s) return fail(s.error());

    std::vector<Placed> placed;
    int exit_code = kExitOk;
    if (scene) {
        for (const auto& m : scene->models) {
            const scene::Group* g = m.group.empty() ? nullptr : scene->find_group(m.group);
            double r = lod.value();
            if (!args.has("lod")) {
                scene::Lod l = g && g->lod ? *g->lod : m.lod;
                r = l.automatic ? 1.0 : l.ratio;
            }
            size_t first = 0;
            if (!load_into(renderer, m.path, r, placed, first)) continue;
            for (size_t i = first; i < placed.size(); ++i) {
                render::ModelState* st = renderer.state(placed[i].id);
                st->color = Vec3f(m.colour[0], m.colour[1], m.colour[2]);
                st->transform = kiosk::to_model_matrix(m.transform);
                st->style = kiosk::to_render_style(g && g->style ? *g->style : m.style);
                if (style_override) st->style = *style_override;
                st->visible = g ? g->visible : true;
                st->selected = args.get("select") == m.name;
            }
        }
        if (!view_given) {
            azimuth = scene->camera.azimuth_deg;
            polar = scene->camera.polar_deg;
        }
    } else if (!model_path.empty()) {
        size_t first = 0;
        if (!load_into(renderer, model_path, lod.value(), placed, first)) exit_code = kExitBadInput;
        for (auto& p : placed) {
            render::ModelState* st = renderer.state(p.id);
            st->style = style_override.value_or(render::Style::Smooth);
            if (auto sel = args.get("select")) st->selected = *sel == p.source.name() || *sel == "all";
        }
    }

    // ---- camera: fit the visible models, from the requested direction
    Vec3f center;
    float radius = 0;
    renderer.scene_bounds(center, radius);
    const float az = glm::radians(azimuth), po = glm::radians(polar);
    Vec3f dir(std::sin(po) * std::sin(az), std::cos(po), std::sin(po) * std::cos(az));
    Vec3f lo(-1.0f), hi(1.0f);
    if (renderer.scene_box(lo, hi)) radius = 0.5f * glm::length(hi - lo);
    const float aspect = static_cast<float>(surf.width()) / static_cast<float>(std::max(1, surf.height()));
    render::Camera camera = render::Camera::framing_box(lo, hi, dir, aspect, scene ? scene->camera.fov_deg : 35.0f);
    if (scene && scene->camera.distance > 0) {
        camera.target = Vec3f(scene->camera.target[0], scene->camera.target[1], scene->camera.target[2]);
        camera.eye = camera.target + dir * scene->camera.distance;
        camera.near_plane = scene->camera.distance * 0.01f;
        camera.far_plane = scene->camera.distance * 10.0f + radius * 2.0f;
    }
    render::Lighting lighting;
    render::FrameOptions fo;
    fo.line_width_px = static_cast<float>(line_width.value()) * static_cast<float>(ssaa.value());
    fo.xray_unselected = args.has("xray");

    if (auto shot = args.get("screenshot")) {
        fo.width = surf.width();
        fo.height = surf.height();
        fo.framebuffer = surf.framebuffer();
        renderer.render(camera, lighting, fo);
        // Read before presenting: after a swap the back buffer is undefined.
        render::Image img;
        img.width = fo.width;
        img.height = fo.height;
        img.rgba = platform::read_pixels_rgba(fo.framebuffer, fo.width, fo.height);
        if (auto s = surf.present(); !s) return fail(s.error());
        img = render::downsample(img, static_cast<int>(ssaa.value()));
        if (auto s = render::write_png(*shot, img); !s) return fail(s.error());
        renderer.shutdown();
        return exit_code;
    }

    // ---- interactive: drag to orbit, wheel to zoom, Escape/close to quit
    std::vector<platform::InputEvent> events;
    bool dragging = false;
    float last_x = 0, last_y = 0, distance = glm::length(camera.eye - camera.target);
    for (long frame = 0; frames.value() <= 0 || frame < frames.value(); ++frame) {
        events.clear();
        bool keep = surf.poll_events(events);
        for (const auto& e : events) {
            using T = platform::InputEvent::Type;
            if (e.type == T::Key && e.key == platform::kKeyEscape && e.pressed) keep = false;
            if (e.type == T::MouseDown || e.type == T::TouchDown) dragging = true, last_x = e.x, last_y = e.y;
            if (e.type == T::MouseUp || e.type == T::TouchUp) dragging = false;
            if ((e.type == T::MouseMove || e.type == T::TouchMove) && dragging) {
                azimuth -= (e.x - last_x) * 0.3f;
                polar = std::clamp(polar - (e.y - last_y) * 0.3f, 5.0f, 175.0f);
                last_x = e.x, last_y = e.y;
            }
            if (e.type == T::Scroll) distance *= std::pow(0.9f, e.dy);
        }
        if (!keep) break;
        const float a = glm::radians(azimuth), p = glm::radians(polar);
        camera.eye =
            camera.target + Vec3f(std::sin(p) * std::sin(a), std::cos(p), std::sin(p) * std::cos(a)) * distance;
        camera.near_plane = std::max(distance - radius * 1.5f, distance * 0.01f);
        camera.far_plane = distance + radius * 1.5f;
        fo.width = surf.width();
        fo.height = surf.height();
        fo.framebuffer = surf.framebuffer();
        renderer.render(camera, lighting, fo);
        if (auto s = surf.present(); !s) return fail(s.error());
    }
    renderer.shutdown();
    return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> argv_list(argv + 1, argv + argc);
    for (const auto& a : argv_list) {
        if (a == "--help" || a == "-h") {
            print_help(stdout);
            return kExitOk;
        }
        if (a == "--version") {
            std::printf("bodyview %s\n", BODY_VERSION_STRING);
            return kExitOk;
        }
    }
    if (argv_list.empty()) {
        print_help(stderr);
        return kExitBadInput;
    }
    auto args = CliArgs::parse(
        argv_list,
        {"platform", "size", "mode", "device", "rotate", "model", "scene", "style", "lod", "select", "view",
         "line-width", "ssaa", "screenshot", "frames", "replay", "bench-triangles", "bench-frames", "buffer-access"},
        {"headless", "windowed", "xray", "benchmark", "no-auto-lod", "kiosk-stats"});
    if (!args) return fail(args.error());
    return run(args.value());
}
