// The kiosk loop over the renderer (contract in kiosk_run.h).
#include "kiosk/app/kiosk_run.h"

#include <GLES3/gl3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/lod_controller.h"
#include "kiosk/app/overlay.h"
#include "kiosk/app/platform_input.h"
#include "kiosk/app/replay.h"
#include "kiosk/app/stream_loader.h"
#include "kiosk/render/image.h"
#include "kiosk/render/model_source.h"
#include "kiosk/render/renderer.h"
#include "platform/evdev_input.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"

namespace body::kiosk {

render::Style to_render_style(scene::Style s) {
    switch (s) {
        case scene::Style::Wireframe: return render::Style::Wireframe;
        case scene::Style::Smooth: return render::Style::Smooth;
        case scene::Style::Lines: return render::Style::Lines;
        case scene::Style::Hatching: return render::Style::Hatching;
        case scene::Style::Hatching2Tone: return render::Style::Hatching2Tone;
    }
    return render::Style::Smooth;
}

glm::mat4 to_model_matrix(const scene::Transform& t) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(t.translate[0], t.translate[1], t.translate[2]));
    m = glm::rotate(m, glm::radians(t.rotate_deg[2]), glm::vec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(t.rotate_deg[1]), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(t.rotate_deg[0]), glm::vec3(1, 0, 0));
    return glm::scale(m, glm::vec3(t.scale));
}

namespace {

// One structure of a scene model: an OBJ object (ModelSource) or a structure
// of a .bpm being streamed (owned by the model's BpmStream).
struct Part {
    std::unique_ptr<render::ModelSource> source;
    pm::ProgressiveMesh* pm = nullptr;
    render::ModelId id = 0;
    size_t base_triangles = 0;
    // Geomorphs (pm parts), over Geomorph::kSeconds, in the vertex shader. The
    // GPU's morph buffer holds the positions (mesh() passes them as the morph
    // sources) except, while a level change glides, the vertices it adds or moves
    // [morph_begin, morph_end): those hold where they are at the coarser of the
    // two levels, and the renderer draws mix(source, position, morph_factor). A
    // refinement glides 0 -> 1 at the new level; a coarsening glides 1 -> 0 and
    // drops the level when it arrives (`collapsing`, towards `pending_level`).
    // The CPU uploads the sources once when a morph starts and puts the positions
    // back once when it stops; nothing per frame.
    Geomorph morph;
    size_t morph_begin = 0, morph_end = 0;
    float morph_factor = 1.0f;
    bool collapsing = false;
    size_t pending_level = 0;
    std::vector<Vec3f> morph_sources;  // working memory of start_morph, kept to avoid reallocating

    size_t full_triangles() const { return pm ? pm->max_triangle_count() : source->full_triangles(); }
    size_t triangles() const { return pm ? pm->triangle_count() : source->triangles(); }
    render::MeshData mesh() const {
        if (!pm) return source->mesh();
        // Once the indices are handed over, with the hook that patches the element buffer.
        render::MeshData m = render::mesh_data_of(*pm);
        m.morph_at_rest = true;  // at rest: nothing displaced
        return m;
    }
    // Once every split has arrived (with normals: the renderer needs no indices
    // to compute them), the renderer's element buffer becomes the only copy of
    // the index array (12 bytes a triangle): what is still dirty goes up, then
    // the pm frees its array; picking reads the buffer back. Positions stay
    // (geomorph sources and picking read them).
    void hand_over_indices(render::Renderer& r) {
        if (!pm || pm->indices_released() || !pm->has_normals() || pm->available_level() != pm->max_level()) return;
        upload_dirty(r);
        pm->release_indices();
    }
    bool morphing() const { return morph_end > morph_begin; }
    // The renderer's morph state for this part.
    void apply_morph(render::ModelState& st) const {
        st.morph_begin = morphing() ? morph_begin : SIZE_MAX;
        st.morph = morphing() ? morph_factor : 1.0f;
    }
    // Uploads the pm's changes since the last upload.
    void upload_dirty(render::Renderer& r) {
        const pm::DirtyRange v = pm->dirty_vertices(), i = pm->dirty_indices();
        pm->clear_dirty();
        if (v.end <= v.begin && i.end <= i.begin) return;
        if (auto st = r.update_model(id, mesh(), render::Dirty{v.begin, v.end, i.begin, i.end}); !st)
            std::fprintf(stderr, "bodyview: %s\n", st.error().message.c_str());
    }
    // Starts gliding between level `lo` and the current level (above it).
    void start_morph(render::Renderer& r, size_t lo, double now) {
        upload_dirty(r);
        const size_t hi = pm->level();
        const size_t begin = pm->morph_sources(lo, morph_sources);
        if (auto st = r.set_morph_sources(id, begin, morph_sources); !st)
            std::fprintf(stderr, "bodyview: %s\n", st.error().message.c_str());
        morph.start(now, pm->triangles_at(collapsing ? hi : lo), pm->triangles_at(collapsing ? lo : hi));
        morph_begin = begin;
        morph_end = begin + morph_sources.size();
        morph_factor = collapsing ? 1.0f : 0.0f;
    }
    // Ends a morph where it is meant to end: the sources back to the positions.
    void stop_morph(render::Renderer& r) {
        if (morphing()) {
            morph_sources.resize(morph_end - morph_begin);  // the positions, as floats
            pm->positions(morph_begin, morph_sources);
            if (auto st = r.set_morph_sources(id, morph_begin, morph_sources); !st)
                std::fprintf(stderr, "bodyview: %s\n", st.error().message.c_str());
        }
        morph_begin = morph_end = 0;
        morph_factor = 1.0f;
        collapsing = false;
    }
    // The blend at `now`; a finished collapse drops the level.
    void step_morph(render::Renderer& r, double now) {
        const float f = morph.factor(now);
        morph_factor = collapsing ? 1.0f - f : f;
        if (f < 1.0f) return;
        const bool drop = collapsing;
        stop_morph(r);
        if (!drop) return;
        pm->set_level(pending_level);
        upload_dirty(r);
    }
    // Heads for `level`, uploading what changed.
    void update(render::Renderer& r, size_t level, double now) {
        if (collapsing && level == pending_level) {
            step_morph(r, now);
            return;
        }
        if (morphing()) stop_morph(r);  // a new target: land the old morph at once
        const size_t current = pm->level();
        if (level > current) {
            pm->set_level(level);
            start_morph(r, current, now);
        } else if (level < current) {
            collapsing = true;
            pending_level = level;
            start_morph(r, level, now);
        }
        step_morph(r, now);
    }
};

// A scene model: its parts (a file may hold several structures) and, for a
// .bpm, the loader thread still decoding its detail (its structures may only be
// touched while holding the loader's lock).
struct Loaded {
    std::vector<Part> parts;
    glm::mat4 transform{1.0f};
    std::unique_ptr<StreamLoader> loader;
    bool streaming = false;
};

// Notes, under the loader's lock, that a stream has ended, logging why when it
// ended early (what arrived before stays usable).
void check_stream(Loaded& l, const std::string& name) {
    if (!l.streaming || !l.loader->done()) return;
    l.streaming = false;
    if (!l.loader->error().empty())
        std::fprintf(stderr, "bodyview: %s: %s (keeping what arrived)\n", name.c_str(), l.loader->error().c_str());
}

// Loads a model: an OBJ at once; a .bpm once every structure's base mesh is in
// (its loader decodes the rest during the frames). Uploads the parts.
Status load_model(render::Renderer& renderer, const scene::Model& m, Loaded& l) {
    const std::string ext = std::filesystem::path(m.path).extension().string();
    std::unique_lock<std::mutex> stream_lock;
    if (ext == ".bpm") {
        if (!l.loader) l.loader = std::make_unique<StreamLoader>(m.path);
        l.loader->wait_for_bases();
        stream_lock = l.loader->lock();
        if (!l.loader->bases_ready()) {
            const std::string& why = l.loader->error();
            return input_error(why.empty() ? m.path + ": ended before every base mesh arrived" : why);
        }
        l.streaming = true;
        check_stream(l, m.name);  // a file that failed after its bases: show them
        pm::BpmStream& stream = l.loader->stream();
        for (size_t i = 0; i < stream.structure_count(); ++i) {
            Part p;
            p.pm = &stream.structure(i);
            p.base_triangles = p.pm->base_triangle_count();
            l.parts.push_back(std::move(p));
        }
    } else {
        auto sources = render::load_model_file(m.path);
        if (!sources) return sources.error();
        for (auto& src : sources.value()) {
            Part p;
            p.base_triangles = src.full_triangles();  // no LOD hierarchy: always full
            p.source = std::make_unique<render::ModelSource>(std::move(src));
            l.parts.push_back(std::move(p));
        }
    }
    if (l.parts.empty()) return input_error(m.path + ": no structures");
    for (Part& p : l.parts) {
        // Plain meshes go up as their 16-bit position codes (no float copy).
        render::MeshData data = p.pm ? p.mesh() : p.source->upload_mesh();
        data.prefix_only = p.pm != nullptr;  // the stream has not written the rest yet
        auto id = renderer.add_model(data, m.name);
        if (!id) return id.error();
        if (p.pm) {
            // add_model uploaded the base level only; splits decoded along with
            // the base go up now (what arrives later is uploaded as it is used).
            const pm::DirtyRange v = p.pm->dirty_vertices(), ix = p.pm->dirty_indices();
            p.pm->clear_dirty();
            if (v.end > v.begin || ix.end > ix.begin) {
                if (auto st =
                        renderer.update_model(id.value(), p.mesh(), render::Dirty{v.begin, v.end, ix.begin, ix.end});
                    !st)
                    return st.error();
            }
        } else {
            (void)p.source->take_dirty();
            p.source->release_arrays();  // the renderer has its copy; picking decodes them again
        }
        p.id = id.value();
    }
    return ok_status();
}

// Ray (world) against the current level of a part; distance along the ray.
std::optional<float> pick_part(const render::Renderer& r, const Part& p, const glm::mat4& transform, const Ray& ray) {
    const glm::mat4 inv = glm::inverse(transform);
    const glm::vec3 o = glm::vec3(inv * glm::vec4(ray.origin, 1.0f));
    const glm::vec3 d = glm::vec3(inv * glm::vec4(ray.direction, 0.0f));
    const render::MeshData mesh = p.mesh();
    // A pm keeps codes: dequantized per corner.
    const auto at = [&](uint32_t v) { return p.pm ? p.pm->position(v) : mesh.positions[v]; };
    float best = 1e30f;
    bool hit = false;
    const auto test = [&](std::span<const uint32_t> indices) {
        for (size_t i = 0; i + 2 < indices.size(); i += 3) {
            // Möller-Trumbore, both sides.
            const glm::vec3 a = at(indices[i]), b = at(indices[i + 1]), c = at(indices[i + 2]);
            const glm::vec3 e1 = b - a, e2 = c - a, pv = glm::cross(d, e2);
            const float det = glm::dot(e1, pv);
            if (std::abs(det) < 1e-12f) continue;
            const float inv_det = 1.0f / det;
            const glm::vec3 tv = o - a;
            const float u = glm::dot(tv, pv) * inv_det;
            if (u < 0.0f || u > 1.0f) continue;
            const glm::vec3 qv = glm::cross(tv, e1);
            const float v = glm::dot(d, qv) * inv_det;
            if (v < 0.0f || u + v > 1.0f) continue;
            const float t = glm::dot(e2, qv) * inv_det;
            if (t > 0.0f && t < best) {
                best = t;
                hit = true;
            }
        }
    };
    if (p.pm && p.pm->indices_released())
        r.read_indices(p.id, mesh.index_count, test);  // the renderer's buffer holds the only copy
    else
        test(mesh.indices.first(std::min(mesh.index_count, mesh.indices.size())));
    if (!hit) return std::nullopt;
    // t is in object units along d; convert to world distance.
    return best * glm::length(glm::vec3(transform * glm::vec4(d, 0.0f)));
}

// The level `want` triangles would give once the whole file has arrived.
size_t pm_level_wanted(const pm::ProgressiveMesh& m, size_t want) {
    if (want >= m.max_triangle_count()) return m.max_level();
    if (m.available_level() < m.max_level()) return m.max_level();  // unknown yet: assume it needs more
    return m.level_for_triangles(want);
}

bool replaying_requested(const KioskRunOptions& o) { return !o.replay.empty(); }

}  // namespace

int run_kiosk(platform::Surface& surface, const scene::Scene& scene, const KioskRunOptions& options) {
    Replay replay;
    if (!options.replay.empty()) {
        auto r = read_replay(options.replay);
        if (!r) {
            std::fprintf(stderr, "bodyview: %s\n", r.error().message.c_str());
            return r.error().exit_code;
        }
        replay = std::move(r).value();
    }
    // Start-up is timed from here: renderer init (the shaders) included; the
    // tonal art map is made later, at the first hatching draw.
    const auto load_start = std::chrono::steady_clock::now();
    // Every .bpm starts reading and decoding its base meshes at once, in
    // parallel and while the renderer compiles its shaders.
    std::vector<Loaded> loaded(scene.models.size());
    for (size_t i = 0; i < scene.models.size(); ++i) {
        if (std::filesystem::path(scene.models[i].path).extension() == ".bpm")
            loaded[i].loader = std::make_unique<StreamLoader>(scene.models[i].path);
    }
    render::Renderer renderer;
    if (auto s = renderer.init(options.renderer); !s) {
        std::fprintf(stderr, "bodyview: %s\n", s.error().message.c_str());
        return kExitRuntime;
    }
    const double init_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();

    // ---- load: a model that fails is skipped with its reason
    std::vector<ModelInfo> info(scene.models.size());
    std::string label_text;
    size_t ok_models = 0;
    for (size_t i = 0; i < scene.models.size(); ++i) {
        const scene::Model& m = scene.models[i];
        for (const auto& l : m.labels) label_text += l.title + l.description;
        Status st = load_model(renderer, m, loaded[i]);
        if (!st) {
            std::fprintf(stderr, "bodyview: %s: skipped: %s\n", m.name.c_str(), st.error().message.c_str());
            for (Part& p : loaded[i].parts) renderer.remove_model(p.id);
            loaded[i] = Loaded{};
            continue;
        }
        loaded[i].transform = to_model_matrix(m.transform);
        // World bounding sphere over the parts (a streamed structure's box is in its INFO).
        glm::vec3 lo(1e30f), hi(-1e30f);
        ModelInfo& mi = info[i];
        for (const Part& p : loaded[i].parts) {
            Vec3f c;
            float r = 0.0f;
            if (p.pm) {
                c = (p.pm->bounds_min() + p.pm->bounds_max()) * 0.5f;
                r = glm::length(p.pm->bounds_max() - p.pm->bounds_min()) * 0.5f;
            } else if (!renderer.bounds(p.id, c, r)) {
                continue;
            }
            const glm::vec3 wc = glm::vec3(loaded[i].transform * glm::vec4(c, 1.0f));
            const float wr = r * m.transform.scale;
            lo = glm::min(lo, wc - glm::vec3(wr));
            hi = glm::max(hi, wc + glm::vec3(wr));
            mi.full_triangles += p.full_triangles();
            mi.base_triangles += p.base_triangles;
        }
        mi.loaded = lo.x <= hi.x;
        mi.center = (lo + hi) * 0.5f;
        mi.radius = std::max(glm::length(hi - lo) * 0.5f / std::sqrt(3.0f), 1e-3f);
        if (mi.loaded) ++ok_models;
        for (const Part& p : loaded[i].parts) {
            renderer.state(p.id)->color = Vec3f(m.colour[0], m.colour[1], m.colour[2]);
        }
    }
    const double load_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();
    if (ok_models == 0) {
        std::fprintf(stderr, "bodyview: %s: no model could be loaded\n", scene.source.c_str());
        renderer.shutdown();
        return kExitBadInput;
    }

    const int width = replay.width > 0 ? replay.width : surface.width();
    const int height = replay.height > 0 ? replay.height : surface.height();
    KioskApp app(scene, info, surface.width(), surface.height());
    // Replay coordinates refer to replay.width x height; scale them to the surface.
    const float sx = static_cast<float>(surface.width()) / static_cast<float>(width);
    const float sy = static_cast<float>(surface.height()) / static_cast<float>(height);
    app.set_picker([&](int model, const Ray& ray) -> std::optional<float> {
        std::optional<float> best;
        const Loaded& l = loaded[static_cast<size_t>(model)];
        glm::mat4 t = glm::translate(glm::mat4(1.0f), app.model(model).offset) * l.transform;
        for (const Part& p : l.parts) {
            auto hit = pick_part(renderer, p, t, ray);
            if (hit && (!best || *hit < *best)) best = hit;
            if (p.source) p.source->release_arrays();  // what the pick decoded
        }
        return best;
    });

    Overlay overlay;
    const auto ui_start = std::chrono::steady_clock::now();
    const float ui_scale = std::max(1.0f, static_cast<float>(std::min(surface.width(), surface.height())) / 800.0f);
    if (auto s = overlay.init(options.font.empty() ? default_font_file() : options.font, ui_scale, label_text); !s) {
        std::fprintf(stderr, "bodyview: labels disabled: %s\n", s.error().message.c_str());
    }

    const double ui_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - ui_start).count();

    // ---- touch on boards without a display server: evdev, hotplugged
    std::unique_ptr<platform::EvdevInput> touch;
    if (surface.backend() == platform::Backend::Drm && !replaying_requested(options)) {
        auto t = platform::EvdevInput::open(
            platform::EvdevOptions{"/dev/input", surface.width(), surface.height(), options.touch_rotation});
        if (t) {
            touch = std::move(t).value();
        } else {
            std::fprintf(stderr, "bodyview: no touch input: %s\n", t.error().message.c_str());
        }
    }

    // ---- loop
    render::Lighting lighting;
    render::FrameOptions fo;
    std::vector<platform::InputEvent> events;
    size_t next_event = 0;
    const bool replaying = !options.replay.empty();
    const double step = 1.0 / 60.0;
    double frame_ms_sum = 0.0;
    long frames_counted = 0;
    int exit_code = kExitOk;
    double first_frame_ms = -1.0, full_detail_ms = -1.0;
    for (long frame = 0;; ++frame) {
        const auto frame_start = std::chrono::steady_clock::now();
        const double now = replaying ? static_cast<double>(frame) * step : surface.time();
        // The streamed structures are shared with their loaders: picking (in the
        // event handlers) and level changes read and write them.
        std::vector<std::unique_lock<std::mutex>> stream_locks;
        for (const Loaded& l : loaded)
            if (l.streaming) stream_locks.push_back(l.loader->lock());
        events.clear();
        bool keep = surface.poll_events(events);
        if (touch) touch->poll(surface.time(), events);
        if (replaying) {
            while (next_event < replay.events.size() && replay.events[next_event].time <= now) {
                InputEvent e = replay.events[next_event++];
                e.x *= sx;
                e.y *= sy;
                app.handle(e);
            }
        } else {
            for (const auto& e : events) {
                if (e.type == platform::InputEvent::Type::Quit) keep = false;
                // Modifiers included (Shift+click selects, thesis B.2); keys as in a replay.
                if (auto k = from_platform(e)) app.handle(*k);
            }
        }
        app.update(now);

        // Detail still arriving: its loaders decode beside this thread; what they
        // have decoded is taken under their locks (held until the draw).
        bool streaming = false;
        for (size_t i = 0; i < loaded.size(); ++i) {
            Loaded& l = loaded[i];
            if (!l.streaming) continue;
            check_stream(l, scene.models[i].name);
            streaming = streaming || l.streaming;
        }

        // Apply the app's state to the renderer.
        size_t triangles = 0;
        bool at_planned_detail = true;
        for (int i = 0; i < app.model_count(); ++i) {
            Loaded& l = loaded[static_cast<size_t>(i)];
            if (l.parts.empty()) continue;
            const ModelState& ms = app.model(i);
            const ModelInfo& mi = app.info(i);
            const bool vis = app.visible(i);
            const glm::mat4 t = glm::translate(glm::mat4(1.0f), ms.offset) * l.transform;
            const double ratio =
                !options.auto_lod
                    ? (ms.manual_lod ? *ms.manual_lod : 1.0)
                    : (mi.full_triangles ? static_cast<double>(ms.triangles) / static_cast<double>(mi.full_triangles)
                                         : 1.0);
            for (Part& p : l.parts) {
                render::ModelState* st = renderer.state(p.id);
                st->style = to_render_style(ms.style);
                st->visible = vis;
                st->selected = i == app.selected();
                st->transform = t;
                if (p.pm) {
                    // The level the app wants, as far as the stream has delivered it.
                    const auto want =
                        static_cast<size_t>(std::llround(static_cast<double>(p.full_triangles()) * ratio));
                    size_t level = p.pm->level_for_triangles(std::max<size_t>(want, 1));
                    const size_t wanted_full = pm_level_wanted(*p.pm, want);
                    // While detail streams in, refine in steps that at least quadruple
                    // the triangles: each step costs an upload and a geomorph, and
                    // frames of a half-way level compete with the decoding thread.
                    if (l.streaming && level > p.pm->level() && level < wanted_full &&
                        p.pm->triangles_at(level) < 4 * p.pm->triangle_count())
                        level = p.pm->level();
                    if (level < wanted_full || frame == 0) at_planned_detail = false;
                    // The first frame shows the base meshes: on screen as soon as possible.
                    if (frame > 0 && (level != p.pm->level() || p.morphing())) {
                        p.update(renderer, level, now);
                    }
                    if (!l.streaming) p.hand_over_indices(renderer);
                    p.apply_morph(*st);
                }
                if (vis) triangles += p.triangles();
            }
        }

        // Camera, with the anti burn-in drift as a pan of a few pixels.
        const OrbitCamera& cam = app.camera();
        const glm::vec2 drift = app.drift(now);
        const float units_per_px =
            2.0f * cam.pose().distance * std::tan(cam.fov_y() * 0.5f) / static_cast<float>(surface.height());
        const glm::mat4 view = cam.view();
        const glm::vec3 right(view[0][0], view[1][0], view[2][0]), up(view[0][1], view[1][1], view[2][1]);
        const glm::vec3 shift = (-drift.x * right + drift.y * up) * units_per_px;
        render::Camera rc;
        rc.eye = cam.eye() + shift;
        rc.target = cam.pose().target + shift;
        rc.fov_y_deg = glm::degrees(cam.fov_y());
        Vec3f sc;
        float sr = 0.0f;
        renderer.scene_bounds(sc, sr);
        const float dist = glm::length(rc.eye - sc);
        rc.near_plane = std::max(dist - sr * 1.5f, cam.pose().distance * 0.01f);
        rc.far_plane = dist + sr * 1.5f + cam.pose().distance;
        fo.width = surface.width();
        fo.height = surface.height();
        fo.framebuffer = surface.framebuffer();
        stream_locks.clear();  // drawing needs only the GL buffers
        renderer.render(rc, lighting, fo);

        LabelCard card;
        if (app.selected() >= 0) {
            const scene::Model& m = scene.models[static_cast<size_t>(app.selected())];
            const scene::LabelText& t = scene.label(m, app.language());
            card.visible = true;
            card.rect = label_card_rect(app.ui_state());
            card.title = t.title;
            card.description = t.description;
        }
        overlay.draw(app.controls(), card, fo.framebuffer, fo.width, fo.height);

        const bool last = app.exit_requested() || !keep ||
                          (replaying && next_event >= replay.events.size() && now >= replay.end_time) ||
                          (options.frames > 0 && frame + 1 >= options.frames);
        if (last && !options.screenshot.empty()) {
            render::Image img;
            img.width = fo.width;
            img.height = fo.height;
            img.rgba = platform::read_pixels_rgba(fo.framebuffer, fo.width, fo.height);
            if (auto s = render::write_png(options.screenshot, img); !s) {
                std::fprintf(stderr, "bodyview: %s\n", s.error().message.c_str());
                exit_code = kExitRuntime;
            }
        }
        if (auto s = surface.present(); !s) {
            std::fprintf(stderr, "bodyview: %s\n", s.error().message.c_str());
            exit_code = kExitRuntime;
            break;
        }
        const double frame_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame_start).count();
        const double since_start =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();
        if (first_frame_ms < 0.0) {
            first_frame_ms = since_start;
            // The first picture is up: detail may decode now (and its memory be
            // prefaulted beside it). A replay waits for all of it so that its
            // frames do not depend on the machine's speed.
            pm::start_background_prefault();
            for (Loaded& l : loaded) {
                if (!l.loader) continue;
                if (replaying)
                    l.loader->wait_until_done();
                else
                    l.loader->release_detail();
            }
            if (options.verbose) {
                std::fprintf(
                    stderr,
                    "bodyview: first frame %.1f ms after start (renderer init %.1f ms with the loaders starting, "
                    "%zu/%zu models, "
                    "base meshes in %.1f ms, "
                    "label atlases %.1f ms)\n",
                    first_frame_ms, init_ms, ok_models, scene.models.size(), load_ms - init_ms, ui_ms);
            }
        }
        if (full_detail_ms < 0.0 && !streaming && at_planned_detail) {
            full_detail_ms = since_start;
            if (options.verbose) {
                std::fprintf(stderr, "bodyview: full detail %.1f ms after start (%zu triangles drawn)\n",
                             full_detail_ms, triangles);
            }
        }
        if (!replaying || options.measure_frames_in_replay) app.report_frame(frame_ms, triangles);
        frame_ms_sum += frame_ms;
        ++frames_counted;
        if (options.verbose && frames_counted % 60 == 0) {
            std::fprintf(stderr, "bodyview: %.2f ms/frame, %zu triangles, budget %zu\n",
                         frame_ms_sum / static_cast<double>(frames_counted), triangles, app.lod_controller().budget());
        }
        if (last) break;
        // While detail streams in, the loader threads get the CPU for five times
        // as long as the frame took (at most 500 ms, or until they are done): a
        // renderer that runs on the CPU (llvmpipe) would otherwise starve them,
        // and the visitor sees full detail sooner (a GPU frame of ~16 ms still
        // leaves ~12 frames a second during the load).
        if (streaming && frame > 0 && !replaying) {
            const auto until = std::chrono::steady_clock::now() +
                               std::chrono::microseconds(static_cast<long>(std::min(5.0 * frame_ms, 500.0) * 1000.0));
            for (const Loaded& l : loaded)
                if (l.streaming && !l.loader->wait_done_until(until)) break;
        }
    }
    if (app.exit_requested()) std::fprintf(stderr, "bodyview: admin exit\n");
    if (options.verbose && frames_counted > 0) {
        std::fprintf(stderr, "bodyview: %ld frames, %.2f ms/frame mean, LOD controller %s, budget %zu triangles\n",
                     frames_counted, frame_ms_sum / static_cast<double>(frames_counted),
                     options.auto_lod ? "on" : "off", app.lod_controller().budget());
    }
    overlay.shutdown();
    renderer.shutdown();
    return exit_code;
}

}  // namespace body::kiosk
