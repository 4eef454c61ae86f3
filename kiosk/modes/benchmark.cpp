// The renderer benchmark (see benchmark.h). Timing: glFinish after each frame,
// steady_clock, process CPU time and, where offered, a GPU timer query
// (gpu_timer.h); the ratio to the baseline is the median of per-pair ratios
// (see time_cell). The baseline is re-measured in every cell so ratios compare
// like with like.
#include "kiosk/modes/benchmark.h"

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>

#include "kiosk/modes/gpu_timer.h"
#include "kiosk/modes/modes.h"

namespace body::kiosk {
namespace {

long status_field_kib(const char* field) {
    std::ifstream in("/proc/self/status");
    std::string line;
    const std::string key = std::string(field) + ":";
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) return std::atol(line.c_str() + key.size());
    return -1;
}

// Linux: writing 5 to clear_refs resets VmHWM (the peak) to the current RSS.
void reset_peak_rss() {
    std::ofstream reset("/proc/self/clear_refs");
    reset << "5";
}

void trim_heap() {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

double mib(long kib) { return static_cast<double>(kib) / 1024.0; }

double cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
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

struct Timed {
    double wall_ms, cpu_ms, gpu_ms;
};

// The medians and spreads of a cell's timed pairs: style frame i against the
// mean of the baseline frames i and i + 1 around it.
Cell summarize(const std::vector<Timed>& styled, const std::vector<Timed>& base) {
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
}

// One benchmark run: the renderer, the measured model and the memory steps.
class Benchmark {
public:
    Benchmark(platform::Surface& surface, const BenchmarkOptions& options) : surface_(surface), options_(options) {}
    Status run();

private:
    void step(const char* what);
    Status draw_empty_scene();
    Status load_model();
    void print_header() const;
    Timed time_frame(Style style);
    Cell time_cell(Style style);
    Status run_lod(double lod);
    void print_cell(double lod, Style s, const Cell& c) const;
    void print_memory() const;
    Status run_cut_plane();
    Status full_detail();

    platform::Surface& surface_;
    const BenchmarkOptions& options_;
    render::Renderer renderer_;
    render::FrameOptions frame_;
    render::View camera_;
    GpuTimer* gpu_timer_ = nullptr;
    std::vector<ModelSource> loaded_;
    ModelSource* source_ = nullptr;
    render::ModelId id_ = 0;
    std::string steps_;  // current and peak RSS above the empty context after each step
    long empty_rss_ = 0, empty_file_rss_ = 0, empty_scene_rss_ = 0, empty_scene_peak_ = 0, source_rss_ = 0;
    long after_baseline_ = 0, after_baseline_current_ = 0, render_peak_ = 0, lod_peak_ = 0;
    std::vector<std::pair<Style, long>> style_added_;  // peak over the RSS resident before the style, LOD 100%
};

void Benchmark::step(const char* what) {
    char line[200];
    std::snprintf(line, sizeof(line), "  %-34s current %7.1f  peak %7.1f MiB  (file-backed %5.1f)\n", what,
                  mib(current_rss_kib() - empty_rss_), mib(peak_rss_kib() - empty_rss_),
                  mib(status_field_kib("RssFile") - empty_file_rss_));
    steps_ += line;
}

// The empty scene: the renderer initialised and every style drawn once on a
// one-triangle model (the driver compiles its shader variants at a program's
// first draw), before the measured model exists. What the peak adds over it is
// what the model costs; the empty scene itself is the fixed cost of the
// renderer and the driver.
Status Benchmark::draw_empty_scene() {
    if (auto s = renderer_.init(options_.renderer); !s) return s;
    step("renderer init");
    const Vec3f corners[] = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    const uint32_t triangle[] = {0, 1, 2};
    auto one = renderer_.add_model({corners, {}, triangle}, "one triangle");
    if (!one) return one.error();
    const render::View camera = render::View::framing(Vec3f(0.0f), 1.5f);
    for (Style s :
         {Style::Baseline, Style::Smooth, Style::Wireframe, Style::Lines, Style::Hatching, Style::Hatching2Tone}) {
        renderer_.state(one.value())->style = s;
        renderer_.render(camera, render::Lighting{}, frame_);
        glFinish();
    }
    renderer_.remove_model(one.value());
    step("empty scene (every style drawn once)");
    empty_scene_rss_ = current_rss_kib();
    empty_scene_peak_ = peak_rss_kib();  // of the renderer's init and the empty scene
    return ok_status();
}

// The measured model (the largest structure of the file, or the generated one), uploaded.
Status Benchmark::load_model() {
    if (!options_.model.empty()) {
        auto l = load_model_file(options_.model);
        if (!l) return l.error();
        loaded_ = std::move(l.value());
    } else {
        auto g = generated_model(options_.target_triangles);
        if (!g) return g.error();
        loaded_.push_back(std::move(g.value()));
    }
    trim_heap();  // the generator's / loader's freed scratch is not the model's memory
    // Peak RSS from here on: the model's CPU arrays plus everything the
    // renderer and the driver allocate for it (the transient cost of making
    // the test model is not counted; the peak of the empty scene, before, is).
    reset_peak_rss();
    source_rss_ = current_rss_kib();
    source_ = &*std::max_element(loaded_.begin(), loaded_.end(), [](const ModelSource& a, const ModelSource& b) {
        return a.full_triangles() < b.full_triangles();
    });
    step("model CPU arrays");
    auto id = renderer_.add_model(source_->upload_mesh(), source_->name());
    if (!id) return id.error();
    id_ = id.value();
    (void)source_->take_dirty();
    source_->release_arrays();  // the GL buffers have the level; set_lod decodes what it needs
    step("model uploaded");
    Vec3f center;
    float radius = 0;
    renderer_.bounds(id_, center, radius);
    camera_ = render::View::framing(center, radius);
    return ok_status();
}

void Benchmark::print_header() const {
    const char* gl_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    std::printf("bodyview benchmark: %s, %dx%d, GL_RENDERER %s\n", source_->name().c_str(), frame_.width, frame_.height,
                gl_renderer ? gl_renderer : "?");
    std::printf("model: %zu triangles (%s LOD); buffer writes %s\n", source_->full_triangles(),
                source_->progressive() ? "progressive-mesh" : "meshoptimizer preview",
                render::buffer_access_name(renderer_.buffer_access()));
    std::printf(
        "ratio: median over the timed pairs of style frame / mean of the two baseline frames around it; ratio_IQR: "
        "its quartiles; cpu_ratio, cpu_IQR: the same in process CPU time; gpu_ms, gpu_ratio, gpu_IQR: the same in "
        "GPU time, gpu_base the baseline's (GL_EXT_disjoint_timer_query%s)\n",
        gpu_timer_->available() ? "" : ": not offered by this driver, '-'");
    if (gpu_timer_->available())
        std::printf(
            "goals judged on the wall ratio (the frame a visitor waits for) and on the GPU ratio (what the style's "
            "shaders cost; a software rasterizer's timer may see only part of its work)\n");
    std::printf("%-5s %-9s %-15s %9s %11s %6s %11s %9s %11s %7s %8s %9s %11s %5s %s\n", "LOD", "triangles", "style",
                "median_ms", "baseline_ms", "ratio", "ratio_IQR", "cpu_ratio", "cpu_IQR", "gpu_ms", "gpu_base",
                "gpu_ratio", "gpu_IQR", "pairs", "goal");
}

Timed Benchmark::time_frame(Style style) {
    renderer_.state(id_)->style = style;
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_ms();
    gpu_timer_->begin();
    renderer_.render(camera_, render::Lighting{}, frame_);
    gpu_timer_->end();
    glFinish();
    const double c1 = cpu_ms();
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return Timed{wall, c1 - c0, gpu_timer_->milliseconds()};
}

// Frames of the baseline and of the style alternate, B0 S0 B1 S1 ... Sn-1 Bn,
// and each style frame is divided by the mean of the two baseline frames
// around it: a load change that drifts linearly over the three frames cancels
// out of that pair ratio, and one that hits a single frame spoils one pair
// only. The printed ratio is the median of the pair ratios, with their
// interquartile range as the spread. Pairs are taken until the cell's time
// budget is spent (and at least options.frames of them), so short frames get
// more pairs. cpu_ratio: the same in process CPU time (every rasterizer
// thread included), which other processes disturb much less than wall time.
Cell Benchmark::time_cell(Style style) {
    for (int i = 0; i < 2; ++i) {  // warm-up pairs: caches, the driver's shader variants
        (void)time_frame(Style::Baseline);
        (void)time_frame(style);
    }
    std::vector<Timed> base{time_frame(Style::Baseline)}, styled;
    const auto start = std::chrono::steady_clock::now();
    const auto spent = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    while (styled.size() < static_cast<size_t>(std::max(options_.frames, 1)) ||
           (spent() < options_.seconds_per_cell && styled.size() < options_.max_pairs)) {
        styled.push_back(time_frame(style));
        base.push_back(time_frame(Style::Baseline));
    }
    return summarize(styled, base);
}

void Benchmark::print_cell(double lod, Style s, const Cell& c) const {
    static const std::map<Style, double> goals = {{Style::Smooth, 1.1}, {Style::Hatching, 1.5}, {Style::Lines, 2.0}};
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
        std::snprintf(gpu, sizeof(gpu), "%7.3f %8.3f %9.2f %5.2f-%-5.2f", c.style_gpu_ms, c.base_gpu_ms, c.gpu.median,
                      c.gpu.q1, c.gpu.q3);
    std::printf("%3.0f%%  %-9zu %-15s %9.2f %11.2f %6.2f %5.2f-%-5.2f %9.2f %5.2f-%-5.2f %s %5zu %s\n", lod * 100,
                source_->triangles(), style_name(s), c.style_ms, c.base_ms, c.wall.median, c.wall.q1, c.wall.q3,
                c.cpu.median, c.cpu.q1, c.cpu.q3, gpu, c.pairs, goal);
    std::fflush(stdout);
}

// Every style at one LOD.
Status Benchmark::run_lod(double lod) {
    if (lod < 1.0) {
        // An OBJ's set_lod is a meshoptimizer simplification of the whole mesh
        // (a .bpm only moves along its splits): its transient memory is the
        // CPU's, not the renderer's, so it is reported apart and the peak
        // restarts after it.
        render_peak_ = std::max(render_peak_, peak_rss_kib());
        source_->set_lod(lod);
        trim_heap();  // hand the simplifier's freed scratch back before the peak restarts
        step(("LOD " + std::to_string(static_cast<int>(lod * 100)) + "% chosen").c_str());
        lod_peak_ = std::max(lod_peak_, peak_rss_kib());
        reset_peak_rss();
    }
    // Nothing to patch at the first pass (the upload has the full level).
    if (const render::Dirty dirty = source_->take_dirty();
        dirty.vertex_begin < dirty.vertex_end || dirty.index_begin < dirty.index_end) {
        if (auto s = renderer_.update_model(id_, source_->upload_mesh(), dirty); !s) return s;
        source_->release_arrays();
    }
    if (lod == 1.0) {
        step("LOD 100% patched in");
        // Memory of the model drawn with the simplest shader: CPU arrays, GL buffers, driver working set.
        renderer_.state(id_)->style = Style::Baseline;
        renderer_.render(camera_, render::Lighting{}, frame_);
        glFinish();
        after_baseline_ = peak_rss_kib();
        after_baseline_current_ = current_rss_kib();
        step("drawn in baseline");
    }
    (void)settle_level(renderer_, id_, camera_, frame_);  // timed as the kiosk draws a level that stays
    if (lod == 1.0) step("level settled (ordered)");      // the ordering's peak shows here
    // Per style: its first frame (building the lazily created edge list /
    // textures outside the timed frames), then its timed frames. At full detail
    // the peak restarts before each style, so the RSS each adds is known.
    for (Style s : kAllStyles) {
        const long before = current_rss_kib();
        if (lod == 1.0) {
            render_peak_ = std::max(render_peak_, peak_rss_kib());
            reset_peak_rss();
        }
        renderer_.state(id_)->style = s;
        renderer_.render(camera_, render::Lighting{}, frame_);
        glFinish();
        if (lod == 1.0) step((std::string("first frame in ") + style_name(s)).c_str());
        const Cell c = time_cell(s);
        if (lod == 1.0) style_added_.emplace_back(s, peak_rss_kib() - before);
        print_cell(lod, s, c);
    }
    step(("every style drawn at LOD " + std::to_string(static_cast<int>(lod * 100)) + "%").c_str());
    return ok_status();
}

void Benchmark::print_memory() const {
    std::printf("RSS above the empty context, step by step:\n%s", steps_.c_str());
    const long model_peak = std::max(render_peak_, peak_rss_kib());
    const long peak = std::max(model_peak, empty_scene_peak_);
    if (lod_peak_ > 0 && !source_->progressive())
        std::printf(
            "peak RSS above the empty context while the OBJ preview LOD was simplified (CPU, not rendering): %.1f "
            "MiB\n",
            mib(lod_peak_ - empty_rss_));
    std::printf(
        "RSS (MiB): empty context %.1f | + empty scene %.1f | + model CPU arrays %.1f | + drawn in baseline %.1f | "
        "+ every style and LOD (peak) %.1f\n",
        mib(empty_rss_), mib(empty_scene_rss_ - empty_rss_), mib(source_rss_ - empty_scene_rss_),
        mib(after_baseline_ - source_rss_), mib(std::max(0L, model_peak - after_baseline_)));
    std::printf(
        "peak RSS above the empty-context baseline: %.1f MiB (goal < 64 MiB: %s); GL data the renderer "
        "allocated: %.1f MiB\n",
        mib(peak - empty_rss_), (peak - empty_rss_) < 64 * 1024 ? "ok" : "MISSED",
        static_cast<double>(renderer_.gpu_bytes()) / 1048576.0);
    std::printf(
        "peak RSS above the empty scene (renderer initialised, every style drawn once on one triangle, before the "
        "model was loaded): %.1f MiB (what the model costs; the empty scene is %.1f MiB above the empty context)\n",
        mib(model_peak - empty_scene_rss_), mib(empty_scene_rss_ - empty_rss_));
    // File-backed pages: library code paged in, and with some drivers their
    // mappings of the copies they keep of GL buffers. The peak less their
    // growth at the end approximates the peak of private memory.
    const long file_kib = status_field_kib("RssFile") - empty_file_rss_;
    std::printf(
        "  of which file-backed pages added since the empty context (library code; NVIDIA's driver also maps its "
        "buffer copies so): %.1f MiB at the end; private memory: %.1f MiB\n",
        mib(file_kib), mib(peak - empty_rss_ - file_kib));
    const render::TransferStats& transfers = renderer_.transfer_stats();
    std::printf("buffer transfers (%s): %zu mapped in place (%zu of them for writing), %.1f MiB staged\n",
                render::buffer_access_name(renderer_.buffer_access()), transfers.in_place_maps,
                transfers.in_place_writes, static_cast<double>(transfers.staged_bytes) / 1048576.0);
    std::printf(
        "peak RSS per style at LOD 100%% (MiB): added over what was resident before it | alone = drawn in "
        "baseline + added\n");
    for (const auto& [s, added] : style_added_)
        std::printf("  %-15s %7.1f | %7.1f\n", style_name(s), mib(added),
                    mib(std::max(after_baseline_, after_baseline_current_ + added) - empty_rss_));
}

// The model back at full detail (the cut-plane and pins tables are timed there).
Status Benchmark::full_detail() {
    source_->set_lod(1.0);
    if (const render::Dirty d = source_->take_dirty(); d.vertex_begin < d.vertex_end || d.index_begin < d.index_end) {
        if (auto s = renderer_.update_model(id_, source_->upload_mesh(), d); !s) return s;
        source_->release_arrays();
    }
    return ok_status();
}

// The cut-plane table (benchmark_cut.cpp) at full detail.
Status Benchmark::run_cut_plane() {
    if (auto s = full_detail(); !s) return s;
    return compare_cut_plane(renderer_, id_, camera_, frame_, options_.frames, options_.seconds_per_cell);
}

Status Benchmark::run() {
    surface_.make_current();
    glFinish();
    empty_rss_ = peak_rss_kib();
    empty_file_rss_ = status_field_kib("RssFile");
    frame_.width = surface_.width();
    frame_.height = surface_.height();
    frame_.framebuffer = surface_.framebuffer();
    if (auto s = draw_empty_scene(); !s) return s;
    if (auto s = load_model(); !s) return s;
    GpuTimer gpu_timer;
    gpu_timer_ = &gpu_timer;
    print_header();
    if (options_.cut_only) {
        if (auto s = run_cut_plane(); !s) return s;
        renderer_.shutdown();
        return ok_status();
    }
    if (options_.pins_only) {
        if (auto s = full_detail(); !s) return s;
        if (auto s = compare_pins(renderer_, id_, *source_, frame_, std::max(options_.frames, 30),
                                  options_.seconds_per_cell);
            !s)
            return s;
        renderer_.shutdown();
        return ok_status();
    }
    for (double lod : {1.0, 0.4, 0.1})
        if (auto s = options_.order_only ? ok_status() : run_lod(lod); !s) return s;
    if (!options_.order_only) {
        step("after every style and LOD");
        print_memory();
        if (auto s = run_cut_plane(); !s) return s;
    }
    if (source_->progressive() && !options_.model.empty()) {
        renderer_.state(id_)->style = Style::Baseline;
        if (auto s = compare_with_static(renderer_, id_, *source_, options_.model, camera_, frame_, options_.frames,
                                         options_.seconds_per_cell);
            !s)
            return s;
    }
    if (options_.order_only) {
        renderer_.shutdown();
        return ok_status();
    }
    renderer_.state(id_)->style = Style::Smooth;
    if (auto s = full_detail(); !s) return s;
    if (auto s =
            compare_pins(renderer_, id_, *source_, frame_, std::max(options_.frames, 30), options_.seconds_per_cell);
        !s)
        return s;
    renderer_.shutdown();
    return ok_status();
}

}  // namespace

long peak_rss_kib() { return status_field_kib("VmHWM"); }
long current_rss_kib() { return status_field_kib("VmRSS"); }

Status run_benchmark(platform::Surface& surface, const BenchmarkOptions& options) {
    return Benchmark(surface, options).run();
}

int run_benchmark_mode(platform::Surface& surface, const ViewOptions& o, const scene::Scene&) {
    BenchmarkOptions bo;
    bo.model = o.model_path;
    bo.renderer = o.renderer;
    bo.target_triangles = static_cast<size_t>(o.bench_triangles);
    bo.frames = static_cast<int>(o.bench_frames);
    bo.seconds_per_cell = o.bench_seconds;
    bo.cut_only = o.bench_only == "cut";
    bo.pins_only = o.bench_only == "pins";
    bo.order_only = o.bench_only == "order";
    auto s = run_benchmark(surface, bo);
    return s ? kExitOk : report(s.error());
}

}  // namespace body::kiosk
