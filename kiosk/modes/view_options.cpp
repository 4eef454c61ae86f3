// bodyview's command line (contract in view_options.h).
#include "kiosk/modes/view_options.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "kiosk/author/author_run.h"
#include "kiosk/modes/modes.h"
#include "platform/evdev_touch.h"
#include "platform/log.h"

namespace body::kiosk {

int report(const Error& error) {
    std::fprintf(stderr, "bodyview: %s\n", error.message.c_str());
    return error.exit_code;
}

const std::set<std::string>& view_value_options() {
    static const std::set<std::string> names = {"platform",
                                                "size",
                                                "mode",
                                                "device",
                                                "rotate",
                                                "model",
                                                "contours",
                                                "scene",
                                                "style",
                                                "lod",
                                                "select",
                                                "view",
                                                "line-width",
                                                "ssaa",
                                                "screenshot",
                                                "frames",
                                                "replay",
                                                "bench-triangles",
                                                "bench-frames",
                                                "bench-seconds",
                                                "bench-only",
                                                "buffer-access",
                                                "soak",
                                                "touch-calibration",
                                                "display-width-mm",
                                                "log-level",
                                                "preview-screenshot"};
    return names;
}

const std::set<std::string>& view_flag_options() {
    static const std::set<std::string> names = {"headless",    "windowed",    "xray",  "benchmark",
                                                "no-auto-lod", "kiosk-stats", "author"};
    return names;
}

namespace {

Status parse_surface(const CliArgs& args, platform::SurfaceOptions& so) {
    if (args.has("headless")) so.backend = platform::Backend::Headless;
    if (auto p = args.get("platform")) {
        auto b = platform::parse_backend(*p);
        if (!b) return input_error("--platform: " + b.error().message);
        if (args.has("headless") && b.value() != platform::Backend::Headless)
            return input_error("--headless contradicts --platform " + *p);
        so.backend = b.value();
    }
    if (auto s = args.get("size")) {
        auto wh = platform::parse_size(*s);
        if (!wh) return input_error("--size: " + wh.error().message);
        so.width = wh->first;
        so.height = wh->second;
    }
    so.fullscreen = !args.has("windowed") && !args.has("author");  // authoring is a desktop window
    if (args.has("author") && so.width == 0) {
        so.width = 1280;
        so.height = 800;
    }
    so.mode = args.get_or("mode", "");
    if (!so.mode.empty()) {  // WxH[@Hz], checked here whatever the backend (only DRM uses it)
        int w = 0, h = 0, n = 0;
        float hz = 0;
        const bool sized = std::sscanf(so.mode.c_str(), "%dx%d%n", &w, &h, &n) == 2 && w > 0 && h > 0;
        const std::string rest = sized ? so.mode.substr(size_t(n)) : "";
        const bool rate = rest.empty() || (std::sscanf(rest.c_str(), "@%f", &hz) == 1 && hz > 0 && hz < 1000);
        if (!sized || !rate) return input_error("--mode: bad mode '" + so.mode + "' (expected WxH or WxH@Hz)");
    }
    so.drm_device = args.get_or("device", "");
    if (auto r = args.get("rotate")) {
        auto deg = platform::parse_rotation(*r);
        if (!deg) return deg.error();
        so.touch_rotation = deg.value();
    }
    if (auto c = args.get("touch-calibration")) {
        auto matrix = platform::parse_calibration(*c);
        if (!matrix) return matrix.error();
        so.touch_calibration = matrix.value();
    }
    return ok_status();
}

Status parse_picture(const CliArgs& args, ViewOptions& o) {
    auto mm = args.get_double("display-width-mm", 0.0);
    if (!mm) return mm.error();
    if (*mm != 0.0 && !(*mm >= 20.0 && *mm <= 10000.0))
        return input_error("option --display-width-mm: a screen's width between 20 and 10000 mm");
    o.display_width_mm = *mm;
    auto lod = args.get_double("lod", 1.0);
    if (!lod) return lod.error();
    if (!(lod.value() > 0.0 && lod.value() <= 1.0)) return input_error("--lod must be in (0, 1]");
    if (args.has("lod")) o.lod = lod.value();
    auto ssaa = args.get_long("ssaa", 1);
    if (!ssaa) return ssaa.error();
    if (ssaa.value() < 1 || ssaa.value() > 4) return input_error("--ssaa must be 1..4");
    o.ssaa = static_cast<int>(ssaa.value());
    auto line_width = args.get_double("line-width", 2.0);
    if (!line_width) return line_width.error();
    if (!(line_width.value() > 0.0 && line_width.value() <= 64.0))
        return input_error("--line-width must be in (0, 64] pixels");
    o.line_width = line_width.value();
    auto frames = args.get_long("frames", 0);
    if (!frames) return frames.error();
    if (args.has("frames") && frames.value() < 1) return input_error("--frames must be at least 1");
    o.frames = frames.value();
    if (auto s = args.get("style")) {
        o.style = parse_style(*s);
        if (!o.style)
            return input_error("--style: unknown style '" + *s +
                               "' (expected smooth, wireframe, lines, hatching, hatching-2tone)");
    }
    if (auto v = args.get("view")) {
        float azimuth = 0, polar = 0;
        int used = 0;
        if (std::sscanf(v->c_str(), "%f,%f%n", &azimuth, &polar, &used) != 2 || size_t(used) != v->size() ||
            !std::isfinite(azimuth) || !(polar >= 0.0f && polar <= 180.0f))
            return input_error("--view expects AZIMUTH,POLAR in degrees (polar 0..180), e.g. 20,75");
        o.view_deg = std::make_pair(azimuth, polar);
    }
    if (auto a = args.get("buffer-access")) {
        auto access = render::parse_buffer_access(*a);
        if (!access) return input_error("--buffer-access: " + access.error().message);
        o.renderer.buffer_access = access.value();
    }
    return ok_status();
}

Status parse_what_to_show(const CliArgs& args, ViewOptions& o) {
    if (args.has("author")) {  // BUNDLE/, scene.json, models: kiosk/author/author_run.h reads them
        o.author = true;
        o.author_inputs = args.positional();
        if (auto s = args.get("scene")) o.author_inputs.insert(o.author_inputs.begin(), *s);
        if (o.author_inputs.empty()) return input_error("--author: give BUNDLE/, scene.json or model files");
        o.preview_screenshot = args.get_or("preview-screenshot", "");
        return ok_status();
    }
    o.scene_path = args.get_or("scene", "");
    if (!args.positional().empty()) {
        if (args.positional().size() > 1 || !o.scene_path.empty()) return input_error("one scene or bundle at most");
        o.scene_path = (std::filesystem::path(args.positional()[0]) / "scene.json").string();
    }
    o.model_path = args.get_or("model", "");
    o.benchmark = args.has("benchmark");
    o.contours_path = args.get_or("contours", "");
    if (!o.contours_path.empty() && (!o.model_path.empty() || !o.scene_path.empty() || o.benchmark))
        return input_error("--contours excludes --model, --scene, a bundle and --benchmark");
    if (!o.benchmark && o.model_path.empty() && o.scene_path.empty() && o.contours_path.empty())
        return input_error("nothing to show: give --model FILE, --scene FILE or a BUNDLE/ (see --help)");
    if (!o.model_path.empty() && !o.scene_path.empty()) return input_error("--model and --scene exclude each other");
    return ok_status();
}

Status parse_benchmark(const CliArgs& args, ViewOptions& o) {
    auto tris = args.get_long("bench-triangles", o.bench_triangles);
    if (!tris) return tris.error();
    if (tris.value() < 1000) return input_error("--bench-triangles must be at least 1000");
    o.bench_triangles = tris.value();
    auto frames = args.get_long("bench-frames", o.bench_frames);
    if (!frames) return frames.error();
    if (frames.value() < 1) return input_error("--bench-frames must be at least 1");
    o.bench_frames = frames.value();
    auto seconds = args.get_double("bench-seconds", o.bench_seconds);
    if (!seconds) return seconds.error();
    if (!(seconds.value() >= 0.0 && seconds.value() <= 600.0))
        return input_error("--bench-seconds must be in [0, 600]");
    o.bench_seconds = seconds.value();
    o.bench_only = args.get_or("bench-only", "");
    if (!o.bench_only.empty() && o.bench_only != "cut" && o.bench_only != "pins" && o.bench_only != "order")
        return input_error("--bench-only expects cut, pins or order");
    return ok_status();
}

// --soak MINUTES: headless unless a platform was named.
Status parse_soak(const CliArgs& args, ViewOptions& o) {
    if (!args.has("soak")) return ok_status();
    auto minutes = args.get_double("soak", 0.0);
    if (!minutes) return minutes.error();
    if (!(minutes.value() > 0.0 && minutes.value() <= 60.0 * 24.0 * 7.0))
        return input_error("--soak expects MINUTES in (0, 10080]");
    if (!o.replay.empty() || !o.screenshot.empty() || o.benchmark)
        return input_error("--soak excludes --replay, --screenshot and --benchmark");
    o.soak_minutes = minutes.value();
    if (!args.has("platform")) o.surface.backend = platform::Backend::Headless;
    return ok_status();
}

}  // namespace

constexpr long kMaxPictureSide = 8192, kMaxPicturePixels = 64l << 20;

Result<ViewOptions> parse_view_options(const CliArgs& args) {
    ViewOptions o;
    if (auto s = parse_surface(args, o.surface); !s) return s.error();
    if (auto s = parse_picture(args, o); !s) return s.error();
    if (auto s = parse_what_to_show(args, o); !s) return s.error();
    // Checked whether or not --benchmark is given: a bad value never passes unnoticed.
    if (auto s = parse_benchmark(args, o); !s) return s.error();
    o.select = args.get("select");
    o.xray = args.has("xray");
    o.screenshot = args.get_or("screenshot", "");
    o.replay = args.get_or("replay", "");
    o.auto_lod = !args.has("no-auto-lod");
    o.kiosk_stats = args.has("kiosk-stats");
    if (auto l = args.get("log-level")) {
        auto level = platform::parse_log_level(*l);
        if (!level) return level.error();
        o.log_level = level.value();
        o.kiosk_stats = o.kiosk_stats || level.value() == platform::LogLevel::Debug;
    }
    if (auto s = parse_soak(args, o); !s) return s.error();
    if (o.surface.backend == platform::Backend::Headless) {
        if (o.surface.width == 0) o.surface.width = 1280, o.surface.height = 800;
        o.surface.width *= o.ssaa;
        o.surface.height *= o.ssaa;
    }
    // The picture is read back whole (screenshots) and GL limits renderbuffers:
    // past 8192 on a side or 64 Mpixel, refuse instead of failing to allocate.
    const long w = o.surface.width, h = o.surface.height;
    if (w > kMaxPictureSide || h > kMaxPictureSide || w * h > kMaxPicturePixels)
        return input_error("--size " + std::to_string(w) + "x" + std::to_string(h) +
                           " (after --ssaa) is over the limit of 8192 per side and 64 Mpixel");
    return o;
}

Result<scene::Scene> scene_to_show(const ViewOptions& o) {
    if (o.author) {
        auto start = author::open_for_authoring(o.author_inputs);
        if (!start) return start.error();
        return std::move(start.value().scene);
    }
    if (!o.scene_path.empty()) return scene::read_scene(o.scene_path);
    scene::Scene s;
    s.source = o.model_path;
    scene::Model m;
    m.name = std::filesystem::path(o.model_path).stem().string();
    m.file = m.path = o.model_path;
    if (o.style) m.style = *o.style;
    if (o.lod) m.lod = scene::Lod{false, static_cast<float>(*o.lod)};
    m.labels.push_back({"en", m.name, ""});
    s.models.push_back(std::move(m));
    s.camera.azimuth_deg = 20.0f;
    s.camera.polar_deg = 75.0f;
    s.camera.fov_deg = 35.0f;
    return s;
}

}  // namespace body::kiosk
