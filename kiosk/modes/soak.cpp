// The soak mode (contract in soak.h): the kiosk loop with randomised visitors,
// a minute-by-minute log of the process's resources and the verdict on them.
#include "kiosk/modes/soak.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/kiosk_run.h"
#include "kiosk/modes/benchmark.h"
#include "kiosk/modes/modes.h"
#include "kiosk/modes/soak_visitors.h"

namespace body::kiosk {
namespace {

using Clock = std::chrono::steady_clock;

int open_fds() {
    std::error_code ec;
    int n = 0;
    for (auto it = std::filesystem::directory_iterator("/proc/self/fd", ec);
         !ec && it != std::filesystem::directory_iterator(); it.increment(ec))
        ++n;
    return n - 1;  // the iterator's own descriptor
}

int thread_count() {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("Threads:", 0) == 0) return std::atoi(line.c_str() + 8);
    return 0;
}

// CPU time of the calling thread (the kiosk loop's), in milliseconds.
double thread_cpu_ms() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

double percentile(std::vector<double>& v, double q) {
    if (v.empty()) return 0.0;
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

// Frame statistics per minute, the pacing, the stop time.
class SoakMonitor {
public:
    explicit SoakMonitor(double minutes) : minutes_(minutes) {}

    bool frame_done(const FrameReport& r, const SoakVisitors& visitors) {
        if (r.gl_errors > 0 && gl_errors_total_ < 10)
            std::fprintf(stderr, "bodyview: soak: %d GL errors in frame %ld\n", r.gl_errors, r.frame);
        gl_errors_ += r.gl_errors, gl_errors_total_ += r.gl_errors;
        frame_ms_.push_back(r.frame_ms);
        // The loop thread's CPU time since the last frame's end: the frame's work
        // and the visitors' input (the pacing below sleeps).
        const double cpu = thread_cpu_ms();
        if (last_cpu_ms_ >= 0.0) cpu_ms_.push_back(cpu - last_cpu_ms_);
        if (r.heap_given_back != given_back_) {  // the heap was given back after a reset in this frame
            given_back_ = r.heap_given_back;
            rss_rest_mib_ = static_cast<double>(current_rss_kib()) / 1024.0;
        }
        const KioskMode mode = r.app->mode();
        if (mode == KioskMode::Attract && last_mode_ != KioskMode::Attract) ++attracts_;
        last_mode_ = mode;
        resets_ = r.app->resets();
        const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
        if (elapsed >= 60.0 * static_cast<double>(minutes_logged_ + 1)) log_minute(visitors);
        if (elapsed >= 60.0 * minutes_) return false;
        // Paced like a 60 Hz display: the loop waits for the next vsync.
        const double rest_ms = 1000.0 / 60.0 - r.frame_ms;
        if (rest_ms > 0) std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(rest_ms));
        last_cpu_ms_ = thread_cpu_ms();
        return true;
    }

    const std::vector<SoakMinute>& minutes() const { return log_; }
    long attracts() const { return attracts_; }
    int resets() const { return resets_; }

private:
    void log_minute(const SoakVisitors& visitors) {
        SoakMinute m;
        m.minute = ++minutes_logged_;
        m.rss_mib = static_cast<double>(current_rss_kib()) / 1024.0;
        m.frames = static_cast<long>(frame_ms_.size());
        m.p50_ms = percentile(frame_ms_, 0.50);
        m.p99_ms = percentile(frame_ms_, 0.99);
        m.cpu_p99_ms = percentile(cpu_ms_, 0.99);
        m.rss_rest_mib = rss_rest_mib_;
        m.gl_errors = gl_errors_;
        m.fds = open_fds();
        m.threads = thread_count();
#ifdef __GLIBC__
        const struct mallinfo2 mi = mallinfo2();
        m.heap_in_use_mib = static_cast<double>(mi.uordblks + mi.hblkhd) / (1024.0 * 1024.0);
        m.heap_free_mib = static_cast<double>(mi.fordblks) / (1024.0 * 1024.0);
#endif
        std::fprintf(
            stderr,
            "bodyview: soak minute %d: rss %.2f MiB, rss at rest %.2f MiB, %ld frames, p50 %.2f ms, p99 %.2f ms, "
            "cpu p99 %.2f ms, gl errors %ld, fds %d, threads %d, sessions %ld, actions %ld, attract %ld, "
            "resets %d, heap in use %.2f MiB, heap free %.2f MiB\n",
            m.minute, m.rss_mib, m.rss_rest_mib, m.frames, m.p50_ms, m.p99_ms, m.cpu_p99_ms, m.gl_errors, m.fds,
            m.threads, visitors.sessions(), visitors.actions(), attracts_, resets_, m.heap_in_use_mib, m.heap_free_mib);
        log_.push_back(m);
        frame_ms_.clear();
        cpu_ms_.clear();
        rss_rest_mib_ = 0.0;
        gl_errors_ = 0;
    }

    double minutes_;
    Clock::time_point start_ = Clock::now();
    std::vector<double> frame_ms_, cpu_ms_;
    double last_cpu_ms_ = -1.0;  // < 0: no frame yet
    long given_back_ = 0;
    double rss_rest_mib_ = 0.0;  // this minute's last RSS at rest; 0: none yet
    std::vector<SoakMinute> log_;
    int minutes_logged_ = 0;
    long gl_errors_ = 0, gl_errors_total_ = 0, attracts_ = 0;
    int resets_ = 0;
    KioskMode last_mode_ = KioskMode::Interactive;
};

uint64_t soak_seed() {
    const char* s = std::getenv("BODYVIEW_SOAK_SEED");
    return s && *s ? std::strtoull(s, nullptr, 10) : 1;
}

}  // namespace

int run_soak_mode(platform::Surface& surface, const ViewOptions& o, const scene::Scene& shown) {
    scene::Scene scene = shown;
    scene.kiosk.idle_seconds = kSoakIdleSeconds;
    scene.kiosk.reset_seconds = kSoakResetSeconds;
    // A second language makes the language control cycle (labels fall back to the first).
    if (scene.kiosk.languages.size() < 2) scene.kiosk.languages.push_back("de");
    const uint64_t seed = soak_seed();
    SoakVisitors visitors(seed, kSoakIdleSeconds, kSoakResetSeconds);
    SoakMonitor monitor(o.soak_minutes);
    std::fprintf(stderr, "bodyview: soak %.1f minutes of %s, seed %llu (BODYVIEW_SOAK_SEED)\n", o.soak_minutes,
                 scene.source.c_str(), static_cast<unsigned long long>(seed));
    KioskRunOptions ko;
    ko.auto_lod = o.auto_lod;
    ko.verbose = o.kiosk_stats;
    ko.renderer = o.renderer;
    ko.display_width_mm = o.display_width_mm;
    ko.load.file_colours = !o.model_path.empty();
    ko.hooks.input = [&](const KioskApp& app, double now, std::vector<platform::InputEvent>& events) {
        visitors.poll(app, now, events);
    };
    ko.hooks.frame_done = [&](const FrameReport& r) { return monitor.frame_done(r, visitors); };
    const int code = run_kiosk(surface, scene, ko);
    if (code != kExitOk) return code;
    const SoakVerdict v = soak_verdict(monitor.minutes());
    std::fprintf(stderr, "bodyview: soak: %ld sessions, %ld actions, %ld attract entries, %d resets\n",
                 visitors.sessions(), visitors.actions(), monitor.attracts(), monitor.resets());
    for (const auto& s : v.notes) std::fprintf(stderr, "bodyview: %s\n", s.c_str());
    for (const auto& s : v.failures) std::fprintf(stderr, "bodyview: FAILED %s\n", s.c_str());
    std::fprintf(stderr, "bodyview: soak %s\n", v.ok ? "passed" : "failed");
    return v.ok ? kExitOk : kExitRuntime;
}

}  // namespace body::kiosk
