// The contour stack reader: streaming SAX (builder/contours/contour_io.cpp) vs
// the document (DOM) reader it replaced, kept below verbatim as the baseline.
// A large stack (default 2,000 slices x 1 contour x 2,000 points, ~100 MB of
// JSON) is written to a temporary file, then each reader runs once in its own
// forked child so that its peak resident set (wait4's ru_maxrss) is its own;
// time is the child's CPU seconds (user + system: the machine may be shared),
// wall seconds beside it. Printed with the ratio SAX / DOM from the same run.
//   DOM baseline    read_file + nlohmann::json::parse + walk (the old reader)
//   SAX from file   read_contour_stack(path): the parser reads the file itself
//   SAX from text   read_file + parse_contour_stack(text)
//   idle child      a child that only exits: the floor every child's RSS includes
//
// usage: bench_contour_io [--slices N] [--points M] [google-benchmark flags]
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "builder/contours/contour_stack.h"
#include "shared/atomic_file.h"

namespace dom_baseline {
using namespace body;
namespace {

using nlohmann::json;

// A string member, or `fallback` when absent; nullopt when present but not a string.
std::optional<std::string> string_member(const json& object, const char* key, const std::string& fallback) {
    auto it = object.find(key);
    if (it == object.end()) return fallback;
    if (!it->is_string()) return std::nullopt;
    return it->get<std::string>();
}

std::string place(const std::string& path, size_t slice) { return path + ": slice " + std::to_string(slice); }
std::string place(const std::string& path, size_t slice, size_t contour) {
    return place(path, slice) + " contour " + std::to_string(contour);
}

Result<Vec3> parse_color(const json& value, const std::string& where) {
    if (!value.is_array() || value.size() != 3) return input_error(where + ": color must be [r, g, b]");
    Vec3 c(0.0);
    for (int i = 0; i < 3; ++i) {
        if (!value[i].is_number()) return input_error(where + ": color must be [r, g, b] numbers");
        c[i] = value[i].get<double>();
        if (!(c[i] >= 0.0 && c[i] <= 1.0)) return input_error(where + ": color components must lie in [0, 1]");
    }
    return c;
}

Result<std::vector<StructureInfo>> parse_structures(const json& root, const std::string& path) {
    std::vector<StructureInfo> out;
    if (!root.contains("structures")) return out;
    const json& list = root["structures"];
    if (!list.is_array()) return input_error(path + ": \"structures\" must be an array");
    for (size_t i = 0; i < list.size(); ++i) {
        const std::string where = path + ": structure " + std::to_string(i);
        const json& s = list[i];
        if (!s.is_object() || !s.contains("id") || !s["id"].is_string())
            return input_error(where + ": needs a string \"id\"");
        StructureInfo info;
        info.id = s["id"].get<std::string>();
        if (info.id.empty()) return input_error(where + ": empty id");
        auto name = string_member(s, "name", info.id);
        if (!name) return input_error(where + ": \"name\" must be a string");
        info.name = *name;
        if (s.contains("color")) {
            auto c = parse_color(s["color"], where);
            if (!c) return c.error();
            info.color = *c;
        }
        for (const auto& other : out)
            if (other.id == info.id) return input_error(where + ": duplicate id '" + info.id + "'");
        out.push_back(std::move(info));
    }
    return out;
}

Result<Contour> parse_contour(const json& c, const std::string& path, size_t si, size_t ci,
                              const std::vector<StructureInfo>& structures) {
    const std::string where = place(path, si, ci);
    if (!c.is_object() || !c.contains("points") || !c["points"].is_array())
        return input_error(where + ": needs a \"points\" array");
    Contour contour;
    contour.source_slice = si;
    contour.source_contour = ci;
    const json& pts = c["points"];
    contour.points.reserve(pts.size());
    for (size_t k = 0; k < pts.size(); ++k) {
        const json& p = pts[k];
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
            return input_error(where + ": point " + std::to_string(k) + " must be [x, y]");
        Vec2 v(p[0].get<double>(), p[1].get<double>());
        if (!std::isfinite(v.x) || !std::isfinite(v.y))
            return input_error(where + ": point " + std::to_string(k) + " is not finite");
        contour.points.push_back(v);
    }
    if (c.contains("structure")) {
        if (!c["structure"].is_string()) return input_error(where + ": \"structure\" must be a string");
        contour.structure = c["structure"].get<std::string>();
        bool known = std::any_of(structures.begin(), structures.end(),
                                 [&](const StructureInfo& s) { return s.id == contour.structure; });
        if (!known) return input_error(where + ": unknown structure '" + contour.structure + "'");
    }
    return contour;
}

}  // namespace

Result<ContourStack> parse_dom(const std::string& json_text, const std::string& path) {
    json root = json::parse(json_text, nullptr, /*allow_exceptions=*/false);
    if (root.is_discarded()) {
        // Re-parse with a SAX-free check to get the byte offset of the syntax error.
        try {
            json probe = json::parse(json_text);
            (void)probe;
        } catch (const json::parse_error& e) {
            return input_error(path + ": byte " + std::to_string(e.byte) + ": invalid JSON");
        } catch (const json::exception& e) {
            return input_error(path + ": invalid JSON (" + std::string(e.what()) + ")");
        }
        return input_error(path + ": invalid JSON");
    }
    if (!root.is_object() || string_member(root, "format", "") != std::optional<std::string>("bodygen.contours"))
        return input_error(path + ": not a contour stack (\"format\" must be \"bodygen.contours\")");
    if (!root.contains("version") || !root["version"].is_number_integer() || root["version"].get<int>() != 1)
        return input_error(path + ": unsupported version (expected 1)");
    ContourStack stack;
    auto units = string_member(root, "units", "mm");
    if (!units) return input_error(path + ": \"units\" must be a string");
    stack.units = *units;
    auto structures = parse_structures(root, path);
    if (!structures) return structures.error();
    stack.structures = std::move(*structures);

    if (!root.contains("slices") || !root["slices"].is_array()) return input_error(path + ": needs a \"slices\" array");
    const json& slices = root["slices"];
    std::vector<Slice> raw;
    for (size_t si = 0; si < slices.size(); ++si) {
        const json& s = slices[si];
        if (!s.is_object() || !s.contains("z") || !s["z"].is_number())
            return input_error(place(path, si) + ": needs a numeric \"z\"");
        Slice slice;
        slice.z = s["z"].get<double>();
        slice.source_index = si;
        if (!std::isfinite(slice.z)) return input_error(place(path, si) + ": z is not finite");
        if (!s.contains("contours") || !s["contours"].is_array())
            return input_error(place(path, si) + ": needs a \"contours\" array");
        const json& contours = s["contours"];
        for (size_t ci = 0; ci < contours.size(); ++ci) {
            auto c = parse_contour(contours[ci], path, si, ci, stack.structures);
            if (!c) return c.error();
            slice.contours.push_back(std::move(*c));
        }
        raw.push_back(std::move(slice));
    }
    std::stable_sort(raw.begin(), raw.end(), [](const Slice& a, const Slice& b) { return a.z < b.z; });
    for (Slice& s : raw) {
        if (!stack.slices.empty() && s.z - stack.slices.back().z < kSliceMergeTolerance) {
            auto& dst = stack.slices.back().contours;
            std::move(s.contours.begin(), s.contours.end(), std::back_inserter(dst));
        } else {
            stack.slices.push_back(std::move(s));
        }
    }
    return stack;
}

}  // namespace dom_baseline

namespace {

using namespace body;

size_t g_slices = 2000, g_points = 2000;
std::string g_path;

// A wobbly circle per slice, written with printf so the parent stays small.
void write_stack(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) {
        std::perror(path.c_str());
        std::exit(1);
    }
    std::fprintf(
        f, "{\"format\": \"bodygen.contours\", \"version\": 1, \"units\": \"mm\", \"structures\": [], \"slices\": [");
    for (size_t s = 0; s < g_slices; ++s) {
        std::fprintf(f, "%s\n{\"z\": %.4f, \"contours\": [{\"points\": [", s ? "," : "", 0.5 * double(s));
        const double r = 40.0 + 10.0 * std::sin(0.01 * double(s));
        for (size_t k = 0; k < g_points; ++k) {
            const double t = 2.0 * M_PI * double(k) / double(g_points);
            const double w = r * (1.0 + 0.05 * std::sin(7.0 * t + 0.003 * double(s)));
            std::fprintf(f, "%s[%.6f,%.6f]", k ? "," : "", w * std::cos(t), w * std::sin(t));
        }
        std::fprintf(f, "]}]}");
    }
    std::fprintf(f, "]}\n");
    std::fclose(f);
}

struct ChildRun {
    double cpu_s = 0, wall_s = 0, peak_mb = 0;
    bool ok = false;
};

// Runs `work` in a forked child; its exit status says whether it succeeded.
ChildRun in_child(const std::function<bool()>& work) {
    const auto t0 = std::chrono::steady_clock::now();
    pid_t pid = ::fork();
    if (pid == 0) ::_exit(work() ? 0 : 1);
    int status = 0;
    rusage ru{};
    ::wait4(pid, &status, 0, &ru);
    ChildRun r;
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.cpu_s =
        double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
    r.peak_mb = double(ru.ru_maxrss) / 1024.0;
    r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    return r;
}

bool expected_shape(const Result<ContourStack>& s) {
    if (!s.ok()) {
        std::fprintf(stderr, "bench_contour_io: %s\n", s.error().message.c_str());
        return false;
    }
    return s->slices.size() == g_slices && s->slices.back().contours.size() == 1 &&
           s->slices.back().contours[0].points.size() == g_points;
}

std::map<std::string, ChildRun> g_results;

void run_variant(benchmark::State& state, const char* name, const std::function<bool()>& work) {
    ChildRun r;
    for (auto _ : state) {
        r = in_child(work);
        state.SetIterationTime(r.cpu_s);
    }
    if (!r.ok) state.SkipWithError("reader failed or gave the wrong shape");
    state.counters["peak_rss_MB"] = r.peak_mb;
    state.counters["wall_s"] = r.wall_s;
    state.counters["points"] = double(g_slices * g_points);
    g_results[name] = r;
}

void BM_IdleChild(benchmark::State& state) {
    run_variant(state, "idle child", [] { return true; });
}
void BM_DomBaseline(benchmark::State& state) {
    run_variant(state, "DOM baseline", [] {
        auto text = read_file(g_path);
        return text.ok() && expected_shape(dom_baseline::parse_dom(*text, g_path));
    });
}
void BM_SaxFromFile(benchmark::State& state) {
    run_variant(state, "SAX from file", [] { return expected_shape(read_contour_stack(g_path)); });
}
void BM_SaxFromText(benchmark::State& state) {
    run_variant(state, "SAX from text", [] {
        auto text = read_file(g_path);
        return text.ok() && expected_shape(parse_contour_stack(*text, g_path));
    });
}

BENCHMARK(BM_IdleChild)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DomBaseline)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SaxFromFile)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SaxFromText)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
    std::vector<char*> rest;
    for (int i = 0; i < argc; ++i) {
        if (i + 1 < argc && !std::strcmp(argv[i], "--slices"))
            g_slices = std::strtoul(argv[++i], nullptr, 10);
        else if (i + 1 < argc && !std::strcmp(argv[i], "--points"))
            g_points = std::strtoul(argv[++i], nullptr, 10);
        else
            rest.push_back(argv[i]);
    }
    int n = int(rest.size());
    benchmark::Initialize(&n, rest.data());
    g_path = (std::filesystem::temp_directory_path() / ("bench_contour_io_" + std::to_string(::getpid()) + ".json"))
                 .string();
    write_stack(g_path);
    const double mb = double(std::filesystem::file_size(g_path)) / (1024.0 * 1024.0);
    std::printf("bench_contour_io: %zu slices x 1 contour x %zu points, %.1f MiB of JSON\n", g_slices, g_points, mb);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    std::filesystem::remove(g_path);

    auto base = g_results.find("DOM baseline");
    if (base == g_results.end() || !base->second.ok) return 1;
    const ChildRun& b = base->second;
    std::printf("\n%-14s %12s %10s %10s %14s %12s\n", "reader", "peak RSS MB", "CPU s", "wall s", "RSS / DOM",
                "CPU / DOM");
    for (const char* name : {"idle child", "DOM baseline", "SAX from file", "SAX from text"}) {
        auto it = g_results.find(name);
        if (it == g_results.end()) continue;
        const ChildRun& r = it->second;
        std::printf("%-14s %12.1f %10.3f %10.3f %14.3f %12.3f\n", name, r.peak_mb, r.cpu_s, r.wall_s,
                    r.peak_mb / b.peak_mb, r.cpu_s / b.cpu_s);
    }
    std::printf("ratios: ours / DOM baseline, same run; RSS includes the idle child's floor\n");
    return 0;
}
