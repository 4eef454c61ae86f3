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

// The figure's value in minute `m`; <= 0 means the minute has none.
double figure_of(const SoakMinute& m, SoakFigure f) {
    switch (f) {
        case SoakFigure::RssAtRest: return m.rss_rest_mib;
        case SoakFigure::RssAtMinuteEnd: return m.rss_mib;
        case SoakFigure::CpuP99: return m.cpu_p99_ms;
        case SoakFigure::WallP99: return m.p99_ms;
    }
    return 0.0;
}

const char* name_of(SoakFigure f) {
    switch (f) {
        case SoakFigure::RssAtRest: return "RSS at rest";
        case SoakFigure::RssAtMinuteEnd: return "RSS at the minute's end";
        case SoakFigure::CpuP99: return "p99 CPU time per frame";
        case SoakFigure::WallP99: return "p99 frame time (wall)";
    }
    return "";
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The warm-up in minutes: shrinks to half the run when the run is shorter than twice it.
double warmup_of(const std::vector<SoakMinute>& minutes, const SoakGoals& goals) {
    return std::min(goals.warmup_minutes, std::floor(static_cast<double>(minutes.size()) / 2.0));
}

// Minutes from `first` on that carry the figure.
std::vector<const SoakMinute*> with_figure(const std::vector<SoakMinute>& minutes, size_t first, SoakFigure f) {
    std::vector<const SoakMinute*> out;
    for (size_t i = first; i < minutes.size(); ++i)
        if (figure_of(minutes[i], f) > 0.0) out.push_back(&minutes[i]);
    return out;
}

double window_median(const std::vector<const SoakMinute*>& v, size_t from, size_t to, SoakFigure f) {
    std::vector<double> x;
    for (size_t i = from; i < to; ++i) x.push_back(figure_of(*v[i], f));
    return median(std::move(x));
}

// Judged RSS figure: at rest where two judged minutes have it (a run with resets), else at the minute's end.
SoakFigure rss_figure(const std::vector<SoakMinute>& minutes, const SoakGoals& goals) {
    const auto first = static_cast<size_t>(std::max(0.0, warmup_of(minutes, goals) - 1.0));
    return with_figure(minutes, first, SoakFigure::RssAtRest).size() >= 2 ? SoakFigure::RssAtRest
                                                                          : SoakFigure::RssAtMinuteEnd;
}

}  // namespace

SoakRssGrowth soak_rss_growth(const std::vector<SoakMinute>& minutes, const SoakGoals& goals, SoakFigure figure) {
    SoakRssGrowth g;
    if (minutes.size() < 2) return g;
    // The warm-up's last minute is the first one judged (minute 5 of the default).
    const auto first = static_cast<size_t>(std::max(0.0, warmup_of(minutes, goals) - 1.0));
    const std::vector<const SoakMinute*> judged = with_figure(minutes, first, figure);
    if (judged.size() < 2) return g;
    const size_t n = judged.size();
    const size_t w = std::clamp<size_t>(static_cast<size_t>(goals.rss_window_minutes), 1, n / 2);
    g.first_from = judged[0]->minute;
    g.first_to = judged[w - 1]->minute;
    g.last_from = judged[n - w]->minute;
    g.last_to = judged[n - 1]->minute;
    g.first_mib = window_median(judged, 0, w, figure);
    g.last_mib = window_median(judged, n - w, n, figure);
    // The windows' centres are this far apart.
    g.hours = static_cast<double>(g.last_from + g.last_to - g.first_from - g.first_to) / 120.0;
    g.growth_mib = g.last_mib - g.first_mib;
    g.allowed_mib = goals.rss_mib_per_hour * g.hours + goals.rss_noise_mib;
    // Least squares over every judged minute, for the log.
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const SoakMinute* m : judged) {
        const double x = m->minute / 60.0, y = figure_of(*m, figure);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const auto k = static_cast<double>(n);
    const double den = k * sxx - sx * sx;
    g.slope_mib_per_hour = den > 0 ? (k * sxy - sx * sy) / den : 0.0;
    g.judged = true;
    return g;
}

SoakP99Drift soak_p99_drift(const std::vector<SoakMinute>& minutes, const SoakGoals& goals, SoakFigure figure) {
    SoakP99Drift d;
    const auto w = static_cast<size_t>(goals.p99_window_minutes);
    const auto first = static_cast<size_t>(warmup_of(minutes, goals));
    if (w == 0 || minutes.size() < first + 2 * w) return d;
    std::vector<double> a, b;
    for (size_t i = first; i < first + w; ++i) a.push_back(figure_of(minutes[i], figure));
    for (size_t i = minutes.size() - w; i < minutes.size(); ++i) b.push_back(figure_of(minutes[i], figure));
    d.first_ms = median(std::move(a));
    d.last_ms = median(std::move(b));
    d.change = d.first_ms > 0 ? d.last_ms / d.first_ms - 1.0 : 0.0;
    d.judged = true;
    return d;
}

SoakVerdict soak_verdict(const std::vector<SoakMinute>& minutes, const SoakGoals& goals) {
    SoakVerdict v;
    char line[360];
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
    const SoakFigure judged_rss = rss_figure(minutes, goals);
    for (SoakFigure f : {SoakFigure::RssAtRest, SoakFigure::RssAtMinuteEnd}) {
        const SoakRssGrowth g = soak_rss_growth(minutes, goals, f);
        if (!g.judged) continue;
        std::snprintf(line, sizeof line,
                      "soak: %s, median %.2f MiB (minutes %d-%d) -> %.2f MiB (minutes %d-%d): %+.2f MiB, allowed "
                      "%.2f; least-squares slope %+.2f MiB/h%s",
                      name_of(f), g.first_mib, g.first_from, g.first_to, g.last_mib, g.last_from, g.last_to,
                      g.growth_mib, g.allowed_mib, g.slope_mib_per_hour,
                      f == judged_rss ? "" : " (logged, not judged)");
        if (f == judged_rss && g.growth_mib > g.allowed_mib)
            fail(line);
        else
            v.notes.emplace_back(line);
    }
    const double warmup = warmup_of(minutes, goals);
    const SoakMinute& base = minutes[static_cast<size_t>(std::max(0.0, warmup - 1.0))];
    const SoakMinute& last = minutes.back();
    if (last.fds > base.fds || last.threads > base.threads) {
        std::snprintf(line, sizeof line, "soak: file descriptors %d -> %d, threads %d -> %d after the warm-up",
                      base.fds, last.fds, base.threads, last.threads);
        fail(line);
    }
    // CPU time per frame where the log has it (the kiosk's own work), else wall time.
    const bool have_cpu =
        std::any_of(minutes.begin(), minutes.end(), [](const SoakMinute& m) { return m.cpu_p99_ms > 0; });
    const SoakFigure judged_p99 = have_cpu ? SoakFigure::CpuP99 : SoakFigure::WallP99;
    bool p99_judged = false;
    for (SoakFigure f : {SoakFigure::CpuP99, SoakFigure::WallP99}) {
        if (f == SoakFigure::CpuP99 && !have_cpu) continue;
        const SoakP99Drift d = soak_p99_drift(minutes, goals, f);
        if (!d.judged) continue;
        p99_judged = true;
        std::snprintf(line, sizeof line,
                      "soak: %s, median of the minutes' p99, first %.0f minutes after the warm-up vs the last %.0f: "
                      "%.2f vs %.2f ms (%+.1f %%)%s",
                      name_of(f), goals.p99_window_minutes, goals.p99_window_minutes, d.first_ms, d.last_ms,
                      100.0 * d.change, f == judged_p99 ? "" : " (logged, not judged)");
        if (f == judged_p99 && d.change > goals.p99_tolerance)
            fail(line);
        else
            v.notes.emplace_back(line);
    }
    if (!p99_judged)
        v.notes.emplace_back("soak: p99 stability not judged: the run is shorter than warm-up + two windows");
    return v;
}

}  // namespace body::kiosk
