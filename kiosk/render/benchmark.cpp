// The renderer benchmark (see benchmark.h). Timing: glFinish after each frame,
// steady_clock, process CPU time and, where offered, a GPU timer query
// (GpuTimer); the ratio to the baseline is the median of per-pair ratios (see
// time_cell). The baseline is re-measured in every cell so ratios compare like
// with like.
#include "kiosk/render/benchmark.h"

#include <EGL/egl.h>
#include <GLES3/gl3.h>
// After gl3.h: the extension prototypes build on its types.
#include <GLES2/gl2ext.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <map>
#include <unordered_map>

#include "kiosk/render/model_source.h"
#include "kiosk/render/renderer.h"
#include "shared/obj_io.h"

namespace body::render {
namespace {

long status_field_kib(const char* field) {
    std::ifstream in("/proc/self/status");
    std::string line;
    const std::string key = std::string(field) + ":";
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) return std::atol(line.c_str() + key.size());
    return -1;
}

// Midpoint subdivision (each triangle -> 4) with shared edge midpoints.
void subdivide(std::vector<Vec3f>& p, std::vector<uint32_t>& idx) {
    std::unordered_map<uint64_t, uint32_t> mid;
    mid.reserve(idx.size());
    auto midpoint = [&](uint32_t a, uint32_t b) {
        uint64_t key = (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
        auto [it, inserted] = mid.emplace(key, static_cast<uint32_t>(p.size()));
        if (inserted) p.push_back((p[a] + p[b]) * 0.5f);
        return it->second;
    };
    std::vector<uint32_t> out;
    out.reserve(idx.size() * 4);
    for (size_t f = 0; f + 2 < idx.size(); f += 3) {
        uint32_t a = idx[f], b = idx[f + 1], c = idx[f + 2];
        uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        out.insert(out.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
    }
    idx = std::move(out);
}

// An icosphere with a smooth bumpy displacement (stands in when no bunny is installed).
void icosphere(std::vector<Vec3f>& p, std::vector<uint32_t>& idx) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    p = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    idx = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
           3, 9,  4, 3, 4, 2, 3, 2, 6, 3, 6, 8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
}

Result<ModelSource> generated_model(size_t target_triangles) {
    std::vector<Vec3f> p;
    std::vector<uint32_t> idx;
    std::string name;
    const char* bunny = "/usr/share/glmark2/models/bunny.obj";
    if (auto mesh = read_obj_merged(bunny); mesh) {
        for (const Vec3& v : mesh->positions) p.emplace_back(v);
        idx = mesh->indices;
        name = "bunny (subdivided)";
    } else {
        icosphere(p, idx);
        name = "bumpy sphere";
    }
    for (int k = subdivisions_toward(idx.size() / 3, target_triangles); k > 0; --k) subdivide(p, idx);
    if (name == "bumpy sphere")
        for (Vec3f& v : p) {
            Vec3f n = glm::normalize(v);
            v = n * (1.0f + 0.05f * std::sin(9.0f * n.x) * std::sin(7.0f * n.y) * std::sin(8.0f * n.z));
        }
    return ModelSource(name, Vec3f(0.85f, 0.62f, 0.55f), std::move(p), {}, std::move(idx));
}

// The q-quantile of v (0 <= q <= 1), linear between the order statistics.
double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double at = q * static_cast<double>(v.size() - 1);
    const size_t i = static_cast<size_t>(at);
    if (i + 1 >= v.size()) return v.back();
    return v[i] + (at - static_cast<double>(i)) * (v[i + 1] - v[i]);
}

// The median and the interquartile range of a cell's pair ratios.
struct Spread {
    double median, q1, q3;
    static Spread of(const std::vector<double>& v) { return {quantile(v, 0.5), quantile(v, 0.25), quantile(v, 0.75)}; }
};

// One style at one LOD: median frame times and the pair ratios' spread.
struct Cell {
    double style_ms, base_ms;
    Spread wall, cpu;
    size_t pairs;
    double style_gpu_ms, base_gpu_ms;  // NaN without a GPU timer
    Spread gpu;                        // empty (NaN) without a GPU timer
};

// The GPU time of one frame, where the driver offers GL_EXT_disjoint_timer_query.
// On a real GPU the wall time of a frame also holds the CPU's submission and
// the glFinish round trip, the same for every style, which pull the wall ratios
// toward 1; the GPU time is what the style's shaders cost. Every backend's
// context is an EGL one, so eglGetProcAddress finds the extension's entries.
class GpuTimer {
public:
    GpuTimer() {
        GLint count = 0;
        glGetIntegerv(GL_NUM_EXTENSIONS, &count);
        bool listed = false;
        for (GLint i = 0; i < count && !listed; ++i) {
            const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
            listed = e && std::string(e) == "GL_EXT_disjoint_timer_query";
        }
        if (!listed) return;
        gen_ = reinterpret_cast<PFNGLGENQUERIESEXTPROC>(eglGetProcAddress("glGenQueriesEXT"));
        delete_ = reinterpret_cast<PFNGLDELETEQUERIESEXTPROC>(eglGetProcAddress("glDeleteQueriesEXT"));
        begin_ = reinterpret_cast<PFNGLBEGINQUERYEXTPROC>(eglGetProcAddress("glBeginQueryEXT"));
        end_ = reinterpret_cast<PFNGLENDQUERYEXTPROC>(eglGetProcAddress("glEndQueryEXT"));
        result_ = reinterpret_cast<PFNGLGETQUERYOBJECTUI64VEXTPROC>(eglGetProcAddress("glGetQueryObjectui64vEXT"));
        if (!gen_ || !delete_ || !begin_ || !end_ || !result_) return;
        gen_(1, &query_);
    }
    ~GpuTimer() {
        if (query_) delete_(1, &query_);
    }
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;

    bool available() const { return query_ != 0; }
    void begin() {
        if (!query_) return;
        GLint disjoint = 0;
        glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);  // reading it clears the flag
        begin_(GL_TIME_ELAPSED_EXT, query_);
    }
    void end() {
        if (query_) end_(GL_TIME_ELAPSED_EXT);
    }
    // After glFinish: the frame's GPU milliseconds, NaN if unknown (no timer,
    // or a disjoint event such as a clock change spoiled the measurement).
    double milliseconds() {
        if (!query_) return std::numeric_limits<double>::quiet_NaN();
        GLuint64 ns = 0;
        result_(query_, GL_QUERY_RESULT_EXT, &ns);
        GLint disjoint = 0;
        glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
        return disjoint ? std::numeric_limits<double>::quiet_NaN() : static_cast<double>(ns) * 1e-6;
    }

private:
    GLuint query_ = 0;
    PFNGLGENQUERIESEXTPROC gen_ = nullptr;
    PFNGLDELETEQUERIESEXTPROC delete_ = nullptr;
    PFNGLBEGINQUERYEXTPROC begin_ = nullptr;
    PFNGLENDQUERYEXTPROC end_ = nullptr;
    PFNGLGETQUERYOBJECTUI64VEXTPROC result_ = nullptr;
};

// Linux: writing 5 to clear_refs resets VmHWM (the peak) to the current RSS.
void reset_peak_rss() {
    std::ofstream reset("/proc/self/clear_refs");
    reset << "5";
}

}  // namespace

int subdivisions_toward(size_t triangles, size_t target) {
    if (triangles == 0 || target == 0) return 0;
    // Each step multiplies the count by 4: taken while the count it gives is
    // nearer the target by ratio than the count before.
    int k = 0;
    const double t = static_cast<double>(target);
    for (double n = static_cast<double>(triangles); n * 4.0 / t < t / n; n *= 4.0) ++k;
    return k;
}

long peak_rss_kib() { return status_field_kib("VmHWM"); }
long current_rss_kib() { return status_field_kib("VmRSS"); }

Status run_benchmark(platform::Surface& surface, const BenchmarkOptions& options) {
    surface.make_current();
    glFinish();
    const long empty_rss = peak_rss_kib();
    const long empty_file_rss = status_field_kib("RssFile");
    const char* gl_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));

    // Where the memory goes: current and peak RSS above the empty context after each step.
    std::string steps;
    const auto step = [&](const char* what) {
        char line[200];
        std::snprintf(line, sizeof(line), "  %-34s current %7.1f  peak %7.1f MiB  (file-backed %5.1f)\n", what,
                      static_cast<double>(current_rss_kib() - empty_rss) / 1024.0,
                      static_cast<double>(peak_rss_kib() - empty_rss) / 1024.0,
                      static_cast<double>(status_field_kib("RssFile") - empty_file_rss) / 1024.0);
        steps += line;
    };
    FrameOptions frame;
    frame.width = surface.width();
    frame.height = surface.height();
    frame.framebuffer = surface.framebuffer();
    const Lighting lighting;

    // The empty scene: the renderer initialised and every style drawn once on
    // a one-triangle model (the driver compiles its shader variants at a
    // program's first draw), before the measured model exists. What the peak
    // adds over it is what the model costs; the empty scene itself is the
    // fixed cost of the renderer and the driver.
    Renderer renderer;
    if (auto s = renderer.init(options.renderer); !s) return s;
    step("renderer init");
    {
        const Vec3f corners[] = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
        const uint32_t triangle[] = {0, 1, 2};
        auto one = renderer.add_model({corners, {}, triangle}, "one triangle");
        if (!one) return one.error();
        const Camera camera = Camera::framing(Vec3f(0.0f), 1.5f);
        for (Style s :
             {Style::Baseline, Style::Smooth, Style::Wireframe, Style::Lines, Style::Hatching, Style::Hatching2Tone}) {
            renderer.state(one.value())->style = s;
            renderer.render(camera, lighting, frame);
            glFinish();
        }
        renderer.remove_model(one.value());
    }
    step("empty scene (every style drawn once)");
    const long empty_scene_rss = current_rss_kib();
    const long empty_scene_peak = peak_rss_kib();  // of the renderer's init and the empty scene

    ModelSource* source = nullptr;
    std::vector<ModelSource> loaded;
    if (!options.model.empty()) {
        auto l = load_model_file(options.model);
        if (!l) return l.error();
        loaded = std::move(l.value());
    } else {
        auto g = generated_model(options.target_triangles);
        if (!g) return g.error();
        loaded.push_back(std::move(g.value()));
    }
#ifdef __GLIBC__
    malloc_trim(0);  // the generator's / loader's freed scratch is not the model's memory
#endif
    // Peak RSS from here on: the model's CPU arrays plus everything the renderer
    // and the driver allocate for it (Linux: writing 5 to clear_refs resets VmHWM,
    // so the transient cost of generating the test model is not counted; the
    // peak of the renderer's init and the empty scene, before, is).
    reset_peak_rss();
    const long source_rss = current_rss_kib();
    // The largest structure is the one measured.
    source = &*std::max_element(loaded.begin(), loaded.end(), [](const ModelSource& a, const ModelSource& b) {
        return a.full_triangles() < b.full_triangles();
    });
    step("model CPU arrays");
    auto id = renderer.add_model(source->upload_mesh(), source->name());
    if (!id) return id.error();
    (void)source->take_dirty();
    source->release_arrays();  // the GL buffers have the level; set_lod decodes what it needs
    step("model uploaded");
    Vec3f center;
    float radius = 0;
    renderer.bounds(id.value(), center, radius);
    const Camera camera = Camera::framing(center, radius);

    std::printf("bodyview benchmark: %s, %dx%d, GL_RENDERER %s\n", source->name().c_str(), frame.width, frame.height,
                gl_renderer ? gl_renderer : "?");
    std::printf("model: %zu triangles (%s LOD); buffer writes %s\n", source->full_triangles(),
                source->progressive() ? "progressive-mesh" : "meshoptimizer preview",
                buffer_access_name(renderer.buffer_access()));
    GpuTimer gpu_timer;
    std::printf(
        "ratio: median over the timed pairs of style frame / mean of the two baseline frames around it; ratio_IQR: "
        "its quartiles; cpu_ratio, cpu_IQR: the same in process CPU time; gpu_ms, gpu_ratio, gpu_IQR: the same in "
        "GPU time, gpu_base the baseline's (GL_EXT_disjoint_timer_query%s)\n",
        gpu_timer.available() ? "" : ": not offered by this driver, '-'");
    if (gpu_timer.available())
        std::printf(
            "goals judged on the wall ratio (the frame a visitor waits for) and on the GPU ratio (what the style's "
            "shaders cost; a software rasterizer's timer may see only part of its work)\n");
    std::printf("%-5s %-9s %-15s %9s %11s %6s %11s %9s %11s %7s %8s %9s %11s %5s %s\n", "LOD", "triangles", "style",
                "median_ms", "baseline_ms", "ratio", "ratio_IQR", "cpu_ratio", "cpu_IQR", "gpu_ms", "gpu_base",
                "gpu_ratio", "gpu_IQR", "pairs", "goal");

    // Frames of the baseline and of the style alternate, B0 S0 B1 S1 ... Sn-1 Bn,
    // and each style frame is divided by the mean of the two baseline frames
    // around it: a load change on a shared machine that drifts linearly over
    // the three frames cancels out of that pair ratio, and one that hits a
    // single frame spoils one pair only. The printed ratio is the median of the
    // pair ratios (not the ratio of medians, which mixes frames taken under
    // different loads), with their interquartile range as the spread. Pairs
    // are taken until the cell's time budget is spent (and at least
    // options.frames of them), so short frames get more pairs.
    // cpu_ratio: the same for process CPU time (every rasterizer thread
    // included), which other processes on a shared machine disturb much less
    // than the wall time.
    auto cpu_ms = [] {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
    };
    struct Timed {
        double wall_ms, cpu_ms, gpu_ms;
    };
    auto time_frame = [&](Style style) {
        renderer.state(id.value())->style = style;
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpu_ms();
        gpu_timer.begin();
        renderer.render(camera, lighting, frame);
        gpu_timer.end();
        glFinish();
        const double c1 = cpu_ms();
        const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        return Timed{wall, c1 - c0, gpu_timer.milliseconds()};
    };
    auto time_cell = [&](Style style) {
        for (int i = 0; i < 2; ++i) {  // warm-up pairs: caches, the driver's shader variants
            (void)time_frame(Style::Baseline);
            (void)time_frame(style);
        }
        std::vector<Timed> base{time_frame(Style::Baseline)}, styled;
        const auto start = std::chrono::steady_clock::now();
        const auto spent = [&] {
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        };
        while (styled.size() < static_cast<size_t>(std::max(options.frames, 1)) ||
               (spent() < options.seconds_per_cell && styled.size() < options.max_pairs)) {
            styled.push_back(time_frame(style));
            base.push_back(time_frame(Style::Baseline));
        }
        std::vector<double> wall, cpu, gpu, style_ms, base_ms, style_gpu_ms, base_gpu_ms;
        for (size_t i = 0; i < styled.size(); ++i) {
            wall.push_back(styled[i].wall_ms / (0.5 * (base[i].wall_ms + base[i + 1].wall_ms)));
            cpu.push_back(styled[i].cpu_ms / (0.5 * (base[i].cpu_ms + base[i + 1].cpu_ms)));
            style_ms.push_back(styled[i].wall_ms);
            // NaN (no timer, or a disjoint frame) spoils that pair only.
            const double g = styled[i].gpu_ms / (0.5 * (base[i].gpu_ms + base[i + 1].gpu_ms));
            if (std::isfinite(g)) gpu.push_back(g);
            if (std::isfinite(styled[i].gpu_ms)) style_gpu_ms.push_back(styled[i].gpu_ms);
        }
        for (const Timed& b : base) {
            base_ms.push_back(b.wall_ms);
            if (std::isfinite(b.gpu_ms)) base_gpu_ms.push_back(b.gpu_ms);
        }
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const auto median_or_nan = [&](const std::vector<double>& v) { return v.empty() ? nan : quantile(v, 0.5); };
        return Cell{quantile(style_ms, 0.5),
                    quantile(base_ms, 0.5),
                    Spread::of(wall),
                    Spread::of(cpu),
                    styled.size(),
                    median_or_nan(style_gpu_ms),
                    median_or_nan(base_gpu_ms),
                    gpu.empty() ? Spread{nan, nan, nan} : Spread::of(gpu)};
    };
    const std::map<Style, double> goals = {{Style::Smooth, 1.1}, {Style::Hatching, 1.5}, {Style::Lines, 2.0}};
    long after_baseline = 0, after_baseline_current = 0, render_peak = 0, lod_peak = 0;
    std::vector<std::pair<Style, long>> style_added;  // peak over the RSS resident before the style, LOD 100%
    for (double lod : {1.0, 0.4, 0.1}) {
        if (lod < 1.0) {
            // An OBJ has no LOD hierarchy: set_lod runs a meshoptimizer
            // simplification of the whole mesh (the preview path; a .bpm only
            // moves along its splits). Its transient memory is the CPU's, not
            // the renderer's: reported apart, and the peak restarts after it.
            render_peak = std::max(render_peak, peak_rss_kib());
            source->set_lod(lod);
#ifdef __GLIBC__
            malloc_trim(0);  // hand the simplifier's freed scratch back before the peak restarts
#endif
            step(("LOD " + std::to_string(static_cast<int>(lod * 100)) + "% chosen").c_str());
            lod_peak = std::max(lod_peak, peak_rss_kib());
            reset_peak_rss();
        }
        // Nothing to patch at the first pass (the upload has the full level):
        // mesh() would only decode the released indices again.
        if (const Dirty dirty = source->take_dirty();
            dirty.vertex_begin < dirty.vertex_end || dirty.index_begin < dirty.index_end) {
            if (auto s = renderer.update_model(id.value(), source->upload_mesh(), dirty); !s) return s;
            source->release_arrays();
        }
        if (lod == 1.0) {
            step("LOD 100% patched in");
            // Memory of the model drawn with the simplest shader: CPU arrays, GL buffers, driver working set.
            renderer.state(id.value())->style = Style::Baseline;
            renderer.render(camera, lighting, frame);
            glFinish();
            after_baseline = peak_rss_kib();
            after_baseline_current = current_rss_kib();
            step("drawn in baseline");
        }
        // Per style: its first frame (building the lazily created edge list /
        // textures outside the timed frames), then its timed frames. At full
        // detail the peak restarts before each style, so the RSS each one adds
        // over what is resident before it is known.
        for (Style s : kAllStyles) {
            const long before = current_rss_kib();
            if (lod == 1.0) {
                render_peak = std::max(render_peak, peak_rss_kib());
                reset_peak_rss();
            }
            renderer.state(id.value())->style = s;
            renderer.render(camera, lighting, frame);
            glFinish();
            if (lod == 1.0) step((std::string("first frame in ") + style_name(s)).c_str());
            const Cell c = time_cell(s);
            if (lod == 1.0) style_added.emplace_back(s, peak_rss_kib() - before);
            auto g = goals.find(s);
            char goal[96] = "";
            const auto verdict = [&](const Spread& r) {
                return std::string(r.median <= g->second ? "ok" : "MISSED") +
                       (r.q1 <= g->second && g->second <= r.q3 ? " (within the IQR)" : "");
            };
            if (g != goals.end() && std::isfinite(c.gpu.median))
                std::snprintf(goal, sizeof(goal), "<= %.1fx wall %s, gpu %s", g->second, verdict(c.wall).c_str(),
                              verdict(c.gpu).c_str());
            else if (g != goals.end())
                std::snprintf(goal, sizeof(goal), "<= %.1fx %s", g->second, verdict(c.wall).c_str());
            char gpu[64] = "      -        -         -           -";
            if (std::isfinite(c.gpu.median))
                std::snprintf(gpu, sizeof(gpu), "%7.3f %8.3f %9.2f %5.2f-%-5.2f", c.style_gpu_ms, c.base_gpu_ms,
                              c.gpu.median, c.gpu.q1, c.gpu.q3);
            std::printf("%3.0f%%  %-9zu %-15s %9.2f %11.2f %6.2f %5.2f-%-5.2f %9.2f %5.2f-%-5.2f %s %5zu %s\n",
                        lod * 100, source->triangles(), style_name(s), c.style_ms, c.base_ms, c.wall.median, c.wall.q1,
                        c.wall.q3, c.cpu.median, c.cpu.q1, c.cpu.q3, gpu, c.pairs, goal);
            std::fflush(stdout);
        }
        step(("every style drawn at LOD " + std::to_string(static_cast<int>(lod * 100)) + "%").c_str());
    }
    step("after every style and LOD");
    std::printf("RSS above the empty context, step by step:\n%s", steps.c_str());
    const long model_peak = std::max(render_peak, peak_rss_kib());
    const long peak = std::max(model_peak, empty_scene_peak);
    const auto mib = [](long kib) { return static_cast<double>(kib) / 1024.0; };
    if (lod_peak > 0 && !source->progressive())
        std::printf(
            "peak RSS above the empty context while the OBJ preview LOD was simplified (CPU, not rendering): %.1f "
            "MiB\n",
            mib(lod_peak - empty_rss));
    std::printf(
        "RSS (MiB): empty context %.1f | + empty scene %.1f | + model CPU arrays %.1f | + drawn in baseline %.1f | "
        "+ every style and LOD (peak) %.1f\n",
        mib(empty_rss), mib(empty_scene_rss - empty_rss), mib(source_rss - empty_scene_rss),
        mib(after_baseline - source_rss), mib(std::max(0L, model_peak - after_baseline)));
    std::printf(
        "peak RSS above the empty-context baseline: %.1f MiB (goal < 64 MiB: %s); GL data the renderer "
        "allocated: %.1f MiB\n",
        mib(peak - empty_rss), (peak - empty_rss) < 64 * 1024 ? "ok" : "MISSED",
        static_cast<double>(renderer.gpu_bytes()) / 1048576.0);
    std::printf(
        "peak RSS above the empty scene (renderer initialised, every style drawn once on one triangle, before the "
        "model was loaded): %.1f MiB (what the model costs; the empty scene is %.1f MiB above the empty context)\n",
        mib(model_peak - empty_scene_rss), mib(empty_scene_rss - empty_rss));
    // File-backed pages: library code paged in (LLVM's JIT, the driver), which
    // only grows on an idle machine, and, with NVIDIA's driver, its mappings of
    // the copies it keeps of GL buffers, which come and go (measured on an
    // H200: +12.7 MiB at the upload of the 1.1M .bpm). The peak less their
    // growth at the end approximates the peak of private memory.
    const long file_kib = status_field_kib("RssFile") - empty_file_rss;
    std::printf(
        "  of which file-backed pages added since the empty context (library code; NVIDIA's driver also maps its "
        "buffer copies so): %.1f MiB at the end; private memory: %.1f MiB\n",
        mib(file_kib), mib(peak - empty_rss - file_kib));
    const TransferStats& transfers = renderer.transfer_stats();
    std::printf("buffer transfers (%s): %zu mapped in place (%zu of them for writing), %.1f MiB staged\n",
                buffer_access_name(renderer.buffer_access()), transfers.in_place_maps, transfers.in_place_writes,
                static_cast<double>(transfers.staged_bytes) / 1048576.0);
    std::printf(
        "peak RSS per style at LOD 100%% (MiB): added over what was resident before it | alone = drawn in "
        "baseline + added\n");
    for (const auto& [s, added] : style_added)
        std::printf("  %-15s %7.1f | %7.1f\n", style_name(s), mib(added),
                    mib(std::max(after_baseline, after_baseline_current + added) - empty_rss));
    renderer.shutdown();
    return ok_status();
}

}  // namespace body::render
