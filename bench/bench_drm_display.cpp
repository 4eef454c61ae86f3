// The DRM display's own cost per frame and per hotplug, on the fake KMS device
// of the unit tests (tests/platform/drm_fake.h; no real device on the build
// machines, so the kernel's time is not in these figures):
//   fake flip alone     one flip through the fake's calls (commit, wait, event):
//                       the baseline
//   present atomic      DrmDisplay::present steady state, atomic flips
//   present legacy      the same with legacy page flips
//   reprobe unchanged   a hotplug event that changes nothing (probe, compare)
//   reprobe resized     a hotplug to another resolution and the mode set after it
// Ratios against the baseline are read off one run (bench/RESULTS.md).
#include <benchmark/benchmark.h>

#include "platform/drm_display.h"
#include "platform/log.h"
#include "tests/platform/drm_fake.h"

namespace {

using namespace body::platform;

std::unique_ptr<DrmDisplay> started(bool atomic) {
    set_log_level(LogLevel::Warning);  // the hotplug's info lines would be most of the time
    fake::reset();
    fake::g_kms.atomic = atomic;
    auto d = std::make_unique<DrmDisplay>(fake::ops(), 3, ModeRequest{});
    if (!d->pick() || !d->present(10)) std::abort();
    return d;
}

void fake_flip_alone(benchmark::State& state) {
    auto d = started(true);  // for the property ids the flip commit names
    const DrmOps& ops = fake::ops();
    drmEventContext context{};
    context.version = 2;
    context.page_flip_handler = [](int, unsigned, unsigned, unsigned, void*) {};
    const uint32_t plane_fb = ops.property_id(3, 31, DRM_MODE_OBJECT_PLANE, "FB_ID");
    const uint32_t plane_crtc = ops.property_id(3, 31, DRM_MODE_OBJECT_PLANE, "CRTC_ID");
    uint32_t fb = 11;
    for (auto _ : state) {
        const DrmAtomicProp props[] = {{31, plane_fb, fb++}, {31, plane_crtc, 41}};
        ops.atomic_commit(3, props, 2, DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT, nullptr);
        if (ops.wait_readable(3, 1000) > 0) ops.handle_event(3, &context);
    }
    fake::g_kms.commits.clear();
}

void present(benchmark::State& state, bool atomic) {
    auto d = started(atomic);
    uint32_t fb = 11;
    for (auto _ : state) {
        benchmark::DoNotOptimize(d->present(fb++));
        if (fake::g_kms.commits.size() > 4096) fake::g_kms.commits.clear();  // the fake's log, not ours
    }
}
void present_atomic(benchmark::State& state) { present(state, true); }
void present_legacy(benchmark::State& state) { present(state, false); }

void reprobe_unchanged(benchmark::State& state) {
    auto d = started(true);
    for (auto _ : state) benchmark::DoNotOptimize(d->reprobe());
}

void reprobe_resized(benchmark::State& state) {
    auto d = started(true);
    const auto big = fake::g_kms.connectors;
    const auto small = std::vector<DrmProbedConnector>{fake::connector(33, true, {fake::mode(1280, 800, 60, true)})};
    bool flip = false;
    uint32_t fb = 11;
    for (auto _ : state) {
        fake::g_kms.connectors = (flip = !flip) ? small : big;
        benchmark::DoNotOptimize(d->reprobe());
        benchmark::DoNotOptimize(d->present(fb++));
        if (fake::g_kms.commits.size() > 4096) fake::g_kms.commits.clear();
    }
}

}  // namespace

BENCHMARK(fake_flip_alone)->Name("fake flip alone");
BENCHMARK(present_atomic)->Name("present atomic");
BENCHMARK(present_legacy)->Name("present legacy");
BENCHMARK(reprobe_unchanged)->Name("reprobe unchanged");
BENCHMARK(reprobe_resized)->Name("reprobe resized + mode set");
BENCHMARK_MAIN();
