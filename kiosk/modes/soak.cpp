// The soak mode (contract in soak.h): the kiosk loop with randomised visitors,
// a minute-by-minute log of the process's resources and the verdict on them.
#include "kiosk/modes/soak.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

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
        m.gl_errors = gl_errors_;
        m.fds = open_fds();
        m.threads = thread_count();
        std::fprintf(stderr,
                     "bodyview: soak minute %d: rss %.2f MiB, %ld frames, p50 %.2f ms, p99 %.2f ms, gl errors %ld, "
                     "fds %d, threads %d, sessions %ld, actions %ld, attract %ld, resets %d\n",
                     m.minute, m.rss_mib, m.frames, m.p50_ms, m.p99_ms, m.gl_errors, m.fds, m.threads,
                     visitors.sessions(), visitors.actions(), attracts_, resets_);
        log_.push_back(m);
        frame_ms_.clear();
        gl_errors_ = 0;
    }

    double minutes_;
    Clock::time_point start_ = Clock::now();
    std::vector<double> frame_ms_;
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

SoakVerdict soak_verdict(const std::vector<SoakMinute>& minutes, const SoakGoals& goals) {
    SoakVerdict v;
    char line[256];
    auto fail = [&](const char* what) {
        v.ok = false;
        v.failures.emplace_back(what);
    };
    if (minutes.size() < 2) {
        fail("soak: fewer than two minutes logged: nothing to compare");
        return v;
    }
    long gl_errors = 0;
    for (const SoakMinute& m : minutes) gl_errors += m.gl_errors;
    if (gl_errors > 0) {
        std::snprintf(line, sizeof line, "soak: %ld GL errors (goal 0)", gl_errors);
        fail(line);
    }
    const double n = static_cast<double>(minutes.size());
    const double warmup = std::min(goals.warmup_minutes, std::floor(n / 2.0));
    const SoakMinute& base = minutes[static_cast<size_t>(std::max(0.0, warmup - 1.0))];
    const SoakMinute& last = minutes.back();
    const double hours = static_cast<double>(last.minute - base.minute) / 60.0;
    const double growth = last.rss_mib - base.rss_mib, allowed = goals.rss_mib_per_hour * hours + goals.rss_noise_mib;
    std::snprintf(line, sizeof line, "soak: RSS %.2f -> %.2f MiB from minute %d to %d (%+.2f MiB, allowed %.2f)",
                  base.rss_mib, last.rss_mib, base.minute, last.minute, growth, allowed);
    (growth > allowed ? v.failures : v.notes).emplace_back(line);
    if (growth > allowed) v.ok = false;
    if (last.fds > base.fds || last.threads > base.threads) {
        std::snprintf(line, sizeof line, "soak: file descriptors %d -> %d, threads %d -> %d after the warm-up",
                      base.fds, last.fds, base.threads, last.threads);
        fail(line);
    }
    const auto w = static_cast<size_t>(goals.p99_window_minutes), first = static_cast<size_t>(warmup);
    if (minutes.size() >= first + 2 * w) {
        double a = 0, b = 0;
        for (size_t i = 0; i < w; ++i) a = std::max(a, minutes[first + i].p99_ms);
        for (size_t i = minutes.size() - w; i < minutes.size(); ++i) b = std::max(b, minutes[i].p99_ms);
        std::snprintf(line, sizeof line,
                      "soak: p99 frame time, worst minute of the first %zu vs the last %zu: "
                      "%.2f vs %.2f ms (%+.1f %%)",
                      w, w, a, b, a > 0 ? 100.0 * (b - a) / a : 0.0);
        (b > a * (1.0 + goals.p99_tolerance) ? v.failures : v.notes).emplace_back(line);
        if (b > a * (1.0 + goals.p99_tolerance)) v.ok = false;
    } else {
        v.notes.emplace_back("soak: p99 stability not judged: the run is shorter than warm-up + two windows");
    }
    return v;
}

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
