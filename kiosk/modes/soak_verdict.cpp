// The soak's verdict on its logged minutes (contract in soak.h). RSS growth is
// judged between the medians of two windows, the first and the last after the
// warm-up, so that one minute's spike (a texture or compiler scratch freed a
// moment later) neither fails a steady run nor hides a step that stayed.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "kiosk/modes/soak.h"

namespace body::kiosk {
namespace {

double median_rss(std::vector<SoakMinute>::const_iterator first, std::vector<SoakMinute>::const_iterator last) {
    std::vector<double> v;
    for (auto it = first; it != last; ++it) v.push_back(it->rss_mib);
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

SoakRssGrowth soak_rss_growth(const std::vector<SoakMinute>& minutes, const SoakGoals& goals) {
    SoakRssGrowth g;
    const double n = static_cast<double>(minutes.size());
    if (minutes.size() < 2) return g;
    // The warm-up's last minute is the first one judged (minute 5 of the default).
    const double warmup = std::min(goals.warmup_minutes, std::floor(n / 2.0));
    const auto first = minutes.begin() + static_cast<std::ptrdiff_t>(std::max(0.0, warmup - 1.0));
    const auto judged = static_cast<size_t>(minutes.end() - first);
    const size_t w = std::clamp<size_t>(static_cast<size_t>(goals.rss_window_minutes), 1, judged / 2);
    g.first_from = first->minute;
    g.first_to = (first + static_cast<std::ptrdiff_t>(w) - 1)->minute;
    g.last_from = (minutes.end() - static_cast<std::ptrdiff_t>(w))->minute;
    g.last_to = minutes.back().minute;
    g.first_mib = median_rss(first, first + static_cast<std::ptrdiff_t>(w));
    g.last_mib = median_rss(minutes.end() - static_cast<std::ptrdiff_t>(w), minutes.end());
    // The windows' centres are this far apart.
    g.hours = static_cast<double>(g.last_from + g.last_to - g.first_from - g.first_to) / 120.0;
    g.growth_mib = g.last_mib - g.first_mib;
    g.allowed_mib = goals.rss_mib_per_hour * g.hours + goals.rss_noise_mib;
    // Least squares over every judged minute, for the log.
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (auto it = first; it != minutes.end(); ++it) {
        const double x = it->minute / 60.0, y = it->rss_mib;
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const auto k = static_cast<double>(judged);
    const double den = k * sxx - sx * sx;
    g.slope_mib_per_hour = den > 0 ? (k * sxy - sx * sy) / den : 0.0;
    g.judged = true;
    return g;
}

SoakVerdict soak_verdict(const std::vector<SoakMinute>& minutes, const SoakGoals& goals) {
    SoakVerdict v;
    char line[320];
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
    const SoakRssGrowth g = soak_rss_growth(minutes, goals);
    std::snprintf(line, sizeof line,
                  "soak: RSS median %.2f MiB (minutes %d-%d) -> %.2f MiB (minutes %d-%d): %+.2f MiB, allowed %.2f; "
                  "least-squares slope %+.2f MiB/h",
                  g.first_mib, g.first_from, g.first_to, g.last_mib, g.last_from, g.last_to, g.growth_mib,
                  g.allowed_mib, g.slope_mib_per_hour);
    if (g.growth_mib > g.allowed_mib)
        fail(line);
    else
        v.notes.emplace_back(line);
    const double n = static_cast<double>(minutes.size());
    const double warmup = std::min(goals.warmup_minutes, std::floor(n / 2.0));
    const SoakMinute& base = minutes[static_cast<size_t>(std::max(0.0, warmup - 1.0))];
    const SoakMinute& last = minutes.back();
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
        if (b > a * (1.0 + goals.p99_tolerance))
            fail(line);
        else
            v.notes.emplace_back(line);
    } else {
        v.notes.emplace_back("soak: p99 stability not judged: the run is shorter than warm-up + two windows");
    }
    return v;
}

}  // namespace body::kiosk
