#pragma once
// `bodyview --soak MINUTES BUNDLE/`: the kiosk's one loop (kiosk/app/kiosk_run.h),
// headless by default, driven for MINUTES of wall time by randomised visitor
// sessions (taps on models and controls, one-finger drags, two-finger pinches,
// wheel turns, style, LOD, group and language changes), each followed by an idle
// period long enough for attract mode and, mostly, the reset. The soak shortens
// the manifest's idle timers (kSoakIdleSeconds, kSoakResetSeconds) so that every
// session ends that way; frames are paced at 60 Hz like a display's vsync.
//
// Every minute one line on stderr: RSS, RSS at rest, frames, frame time p50/p99
// (wall) and p99 of the loop thread's CPU time per frame, GL errors, open file
// descriptors, threads, sessions, attract entries, resets and the C heap (in
// use, and free but held). At the end the minutes are judged against the goals
// (soak_verdict, in soak_verdict.cpp); the exit code is 0 when every goal holds,
// 1 otherwise.
//
// Two figures exist because a shared machine moves the plain ones: the RSS at
// the minute's end depends on how many frames have re-touched the heap's free
// pages since the last reset's give-back (thousands on a quiet machine, a
// hundred on a loaded one), and wall frame times follow the neighbours. The RSS
// at rest (sampled in the frame that gave the heap back after a reset) and the
// CPU time per frame (with llvmpipe rasterizing on the loop thread, the whole
// frame's work) measure the kiosk alone; they are what the verdict judges.
#include <string>
#include <vector>

namespace body::kiosk {

inline constexpr float kSoakIdleSeconds = 6.0f;
inline constexpr float kSoakResetSeconds = 12.0f;

// One minute of a soak, as logged.
struct SoakMinute {
    int minute = 0;                     // 1-based, the minute just ended
    double rss_mib = 0.0;               // resident set size at the minute's end
    long frames = 0;                    // frames in this minute
    double p50_ms = 0.0, p99_ms = 0.0;  // this minute's frame times (wall)
    long gl_errors = 0;                 // glGetError() values other than GL_NO_ERROR, this minute
    int fds = 0, threads = 0;           // at the minute's end
    // The C heap at the minute's end (glibc's mallinfo2; 0 elsewhere): bytes
    // handed out, and bytes free but still held (arenas of every thread).
    double heap_in_use_mib = 0.0, heap_free_mib = 0.0;
    // Resident set size just after the minute's last idle give-back of the heap
    // (IdleMemory, after a reset); 0 when no give-back fell in this minute.
    double rss_rest_mib = 0.0;
    double cpu_p99_ms = 0.0;  // this minute's p99 of the loop thread's CPU time per frame
};

struct SoakGoals {
    double warmup_minutes = 5.0;       // RSS, fds and threads are compared from here on
    double rss_mib_per_hour = 1.0;     // allowed RSS growth after the warm-up
    double rss_window_minutes = 10.0;  // RSS: median of the first vs of the last window after the warm-up
    double rss_noise_mib = 1.0;        // allowed on top: allocator and page granularity
    double p99_window_minutes = 10.0;  // first vs last window after the warm-up ...
    double p99_tolerance = 0.10;       // ... within this fraction (judged only when both fit apart)
};

// Which of a minute's figures a rule reads: the verdict judges the kiosk's own
// (RSS at rest, CPU time per frame) and logs the machine-dependent ones.
enum class SoakFigure { RssAtRest, RssAtMinuteEnd, CpuP99, WallP99 };

struct SoakVerdict {
    bool ok = true;
    std::vector<std::string> failures;  // one line each
    std::vector<std::string> notes;     // goals measured but not judged (too short a run), figures
};

// RSS growth after the warm-up: the median of the first `rss_window_minutes`
// judged (from the warm-up's last minute on) against the median of the last
// as many (each at most half of the judged minutes), so that a one-minute
// spike decides nothing while a step that stays counts in full; the allowance
// grows with the time between the windows' centres.
// Minutes without the figure (no reset in the minute, for RSS at rest) are
// left out of the windows and the slope.
struct SoakRssGrowth {
    bool judged = false;                                           // false: fewer than two minutes
    int first_from = 0, first_to = 0, last_from = 0, last_to = 0;  // the windows' minutes
    double first_mib = 0.0, last_mib = 0.0, growth_mib = 0.0, allowed_mib = 0.0, hours = 0.0;
    double slope_mib_per_hour = 0.0;  // least squares over the judged minutes (logged, not judged)
};
SoakRssGrowth soak_rss_growth(const std::vector<SoakMinute>& minutes, const SoakGoals& goals = {},
                              SoakFigure figure = SoakFigure::RssAtRest);

// p99 stability: the median of the minutes' p99 in the first window after the
// warm-up against that of the last window (one minute disturbed by a neighbour
// decides nothing); judged only when the two windows fit apart.
struct SoakP99Drift {
    bool judged = false;
    double first_ms = 0.0, last_ms = 0.0;
    double change = 0.0;  // last / first - 1
};
SoakP99Drift soak_p99_drift(const std::vector<SoakMinute>& minutes, const SoakGoals& goals = {},
                            SoakFigure figure = SoakFigure::CpuP99);

// Judges a soak's minutes against `goals`. Warm-up shrinks to half the run when
// the run is shorter than twice the warm-up (a CI soak of two minutes compares
// minute 1 with minute 2); the p99 comparison needs two disjoint windows after it.
SoakVerdict soak_verdict(const std::vector<SoakMinute>& minutes, const SoakGoals& goals = {});

}  // namespace body::kiosk
