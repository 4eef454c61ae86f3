// bodygen build INPUT -o OUT [--caps flat|dome|none]
//   [--tiling optimal|multires] [--correspondence overlap|ellipse]
//   [--branching partition|overlap] [--smooth N] [--interpolate N] [--normals] [--quiet] [--json] [--jobs N]
// INPUT: a contour stack (*.contours.json), or, with import support, a NIfTI
// label volume or a DICOM RT-STRUCT (imported with the `contours` defaults).
// OUT: OUT.obj (one `o NAME` per structure), OUT.bpm (progressive meshes), or
// a directory OUT/ (one OBJ per structure). Every file is written atomically.
// A per-structure summary goes to stderr (or JSON stats to stdout with --json);
// a progress bar is drawn when stderr is a terminal.
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "builder/cli/commands.h"
#include "builder/lod/bpm_writer.h"
#include "builder/lod/simplify.h"
#include "builder/pipeline/build_pipeline.h"
#ifdef BODY_WITH_IMPORT
#include "builder/import/import.h"
#endif
#include "shared/atomic_file.h"
#include "shared/cli_args.h"
#include "shared/input_file.h"
#include "shared/obj_io.h"

namespace body::cli {

#ifdef BODY_WITH_IMPORT
Result<ImportOptions> import_options_from_args(const CliArgs& args);  // cmd_contours.cpp
#endif
Result<RepairOptions> repair_options_from_args(const CliArgs& args);  // cmd_check.cpp

namespace {

template <typename E>
Result<E> pick(const CliArgs& args, const char* option, std::initializer_list<std::pair<const char*, E>> choices,
               E fallback) {
    auto value = args.get(option);
    if (!value) return fallback;
    std::string known;
    for (const auto& [name, e] : choices) {
        if (*value == name) return e;
        known += known.empty() ? name : std::string("|") + name;
    }
    return input_error("build: --" + std::string(option) + " must be " + known + ", not '" + *value + "'");
}

enum class OutputKind { Obj, Bpm, Directory, Unknown };

OutputKind output_kind(const std::string& path) {
    if (path.ends_with("/") || std::filesystem::is_directory(path)) return OutputKind::Directory;
    if (path.ends_with(".bpm")) return OutputKind::Bpm;
    if (path.ends_with(".obj")) return OutputKind::Obj;
    return OutputKind::Unknown;
}

Result<ContourStack> load_input(const std::string& path, const CliArgs& args, bool quiet) {
#ifdef BODY_WITH_IMPORT
    auto import = import_options_from_args(args);  // same options as `bodygen contours`
    if (!import) return import.error();
    if (!quiet) import->note = [](const std::string& m) { std::fprintf(stderr, "bodygen: note: %s\n", m.c_str());
};
return load_any_contour_source(path, *import);
#else
    (void)args;
    (void)quiet;
    return read_contour_stack(path);
#endif
}  // namespace

// A file name for a structure: its id with anything but [A-Za-z0-9._-] replaced.
std::string file_stem(const StructureMesh& s) {
    std::string stem = s.id.empty() ? s.mesh.name : s.id;
    for (char& c : stem)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
    return stem.empty() ? std::string("structure") : stem;
}

Status write_output(const std::string& output, const std::vector<StructureMesh>& built, bool normals, unsigned jobs) {
    std::vector<Mesh> meshes;
    for (const StructureMesh& s : built) meshes.push_back(s.mesh);
    ObjWriteOptions obj;
    obj.normals = normals;
    obj.threads = jobs;
    switch (output_kind(output)) {
        case OutputKind::Obj: return write_obj(output, meshes, obj);
        case OutputKind::Bpm: return lod::write_bpm_from_meshes(output, meshes);
        case OutputKind::Directory: {
            // Staged and swapped in whole, as file outputs are; an existing
            // directory is replaced only when it holds nothing but OBJ files.
            auto fill = [&](const std::string& staged) -> Status {
                std::map<std::string, int> used;
                for (const StructureMesh& s : built) {
                    std::string stem = file_stem(s);
                    if (int n = used[stem]++) stem.append(1, '_').append(std::to_string(n));
                    std::span<const Mesh> one(&s.mesh, 1);
                    Status st = write_obj((std::filesystem::path(staged) / (stem + ".obj")).string(), one, obj);
                    if (!st) return runtime_error(output + ": " + st.error().message);
                }
                return ok_status();
            };
            auto replaceable = [](const std::string& dir) -> std::string {
                std::error_code ec;
                for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
                    if (!it->is_regular_file() || it->path().extension() != ".obj")
                        return "holds " + it->path().filename().string() + ", not only OBJ files";
                return {};
            };
            return write_directory_atomically(output, fill, replaceable);
        }
        case OutputKind::Unknown:
            return input_error(output + ": unknown output type (expected OUT.obj, OUT.bpm or OUT/)");
    }
    return ok_status();
}

void print_usage() {
    std::printf(
        "usage: bodygen build INPUT -o OUT [options]\n"
        "  INPUT: STACK.contours.json"
#ifdef BODY_WITH_IMPORT
        ", a NIfTI label volume (.nii/.nii.gz) or a DICOM RT-STRUCT (.dcm)"
#endif
        "\n  OUT:   OUT.obj (one object per structure), OUT.bpm (progressive meshes)\n"
        "         or OUT/ (a directory: one OBJ per structure)\n"
        "  --caps flat|dome|none              closing the ends (default dome)\n"
        "  --tiling optimal|multires          band tiling (default multires: on the sliced bunny as\n"
        "                                     accurate as optimal, 4-8x faster)\n"
        "  --correspondence overlap|ellipse   matching contours across slices (default overlap)\n"
        "  --branching partition|overlap      branches: closed manifold, or the thesis'\n"
        "                                     overlapping bands for comparison (default partition)\n"
        "  --smooth N                         N Taubin lambda|mu smoothing steps per mesh (default 0):\n"
        "                                     removes slice terraces and voxel stairs with little shrinking\n"
        "                                     (small thin structures lose the most volume);\n"
        "                                     vertices leave their slice planes\n"
        "  --interpolate N                    N intermediate rings per slice gap on C1 Hermite curves through\n"
        "                                     the traced contours (default 3; 0: linear bands); every traced\n"
        "                                     point stays on the mesh\n"
        "  --ring-tolerance F                 each curve between two slices takes the fewest of those N\n"
        "                                     points that keep it within F x the slice gap of their\n"
        "                                     polyline (default 0.004; 0: every curve gets N)\n"
        "  --ring-voxel G                     label volumes: no ring points where a curve stays within G x the\n"
        "                                     in-plane voxel of their polyline, the contours' own precision\n"
        "                                     (default 0.25; 0: the slice gap rule alone)\n"
        "  --strict                           refuse contours with any problem instead of repairing them\n"
        "  --repair-tolerance D               largest distance a contour repair may move a point, in stack\n"
        "                                     units (default 0.001 x the stack's x-y extent; see bodygen check)\n"
        "  --min-area A                       for a contour stack (.json): drop contours smaller than A\n"
        "                                     (stack units squared) with a warning (default 0: keep all)\n"
        "  --normals                          write vertex normals\n"
        "  --quiet                            no progress bar and no summary\n"
        "  --json                             statistics as JSON on stdout\n"
        "  --jobs N                           threads (default 1): structures built at once; those left\n"
        "                                     over search an interpolated mesh for crossings and write the\n"
        "                                     OBJ (the same output for any N)\n"
#ifdef BODY_WITH_IMPORT
        "  --labels, --axis, --step, --only, --threshold, --tolerance, --min-area, --label-smooth\n"
        "                                     import options for label volumes (see bodygen contours --help)\n"
#endif
    );
}

}  // namespace body::cli

// `--ring-voxel`'s default: rings only where a curve leaves its chord by more
// than a quarter voxel. A 1 mm label map's 1 mm gaps then get few rings, while
// the same map sliced every 3rd or 5th voxel keeps nearly all the gain of
// every ring (bench/RESULTS.md, seventeenth session); stacks without a voxel
// (sliced meshes, RT-STRUCTs, contour files written without one) keep the
// gap rule alone.
constexpr double kRingVoxel = 0.25;

// Intermediate rings per slice gap unless --interpolate says otherwise. The
// command line interpolates by default (the library's BuildOptions stays
// linear); `--interpolate 0` gives the linear bands.
constexpr long kDefaultInterpolate = 3;

// The pipeline's options from the command line; errors name the bad option
// (shared with `bodygen exhibit`).
Result<BuildOptions> build_options_from_args(const CliArgs& args) {
    auto jobs = args.get_jobs(1);
    if (!jobs) return jobs.error();
    auto smooth = args.get_long("smooth", 0);
    if (!smooth) return smooth.error();
    if (*smooth < 0 || *smooth > 1000) return input_error("build: --smooth must be between 0 and 1000");
    auto interpolate = args.get_long("interpolate", kDefaultInterpolate);
    if (!interpolate) return interpolate.error();
    if (*interpolate < 0 || *interpolate > 64) return input_error("build: --interpolate must be between 0 and 64");
    auto ring_tolerance = args.get_double("ring-tolerance", BuildOptions{}.ring_tolerance);
    if (!ring_tolerance) return ring_tolerance.error();
    if (!(*ring_tolerance >= 0.0 && *ring_tolerance <= 1.0))
        return input_error("build: --ring-tolerance must be between 0 and 1");
    auto ring_voxel = args.get_double("ring-voxel", kRingVoxel);
    if (!ring_voxel) return ring_voxel.error();
    if (!(*ring_voxel >= 0.0 && *ring_voxel <= 10.0))
        return input_error("build: --ring-voxel must be between 0 and 10");
    BuildOptions options;
    options.fairing.iterations = int(*smooth);
    options.ring_voxel = *ring_voxel;
    options.interpolate = int(*interpolate);
    options.ring_tolerance = *ring_tolerance;
    auto caps = pick<CapStyle>(
        args, "caps", {{"flat", CapStyle::Flat}, {"dome", CapStyle::Dome}, {"none", CapStyle::None}}, CapStyle::Dome);
    if (!caps) return caps.error();
    auto tiling =
        pick<TilingMethod>(args, "tiling", {{"optimal", TilingMethod::Optimal}, {"multires", TilingMethod::Multires}},
                           TilingMethod::Multires);
    if (!tiling) return tiling.error();
    auto corr = pick<CorrespondenceMethod>(
        args, "correspondence",
        {{"overlap", CorrespondenceMethod::Overlap}, {"ellipse", CorrespondenceMethod::Ellipse}},
        CorrespondenceMethod::Overlap);
    if (!corr) return corr.error();
    auto branching = pick<BranchingMethod>(
        args, "branching", {{"partition", BranchingMethod::Partition}, {"overlap", BranchingMethod::Overlap}},
        BranchingMethod::Partition);
    if (!branching) return branching.error();
    options.caps = *caps;
    options.tiling = *tiling;
    options.correspondence = *corr;
    options.branching = *branching;
    options.jobs = *jobs;
    auto repair = repair_options_from_args(args);
    if (!repair) return repair.error();
    options.repair = *repair;
    return options;
}

namespace {

void print_json(const std::string& input, const std::string& output, const BuildOptions& options, double seconds,
                const std::vector<StructureMesh>& built, const std::map<std::string, size_t>& repairs) {
    nlohmann::json j;
    j["input"] = input;
    j["output"] = output;
    j["caps"] = cap_style_name(options.caps);
    j["tiling"] = tiling_method_name(options.tiling);
    j["correspondence"] = correspondence_method_name(options.correspondence);
    j["branching"] = branching_method_name(options.branching);
    j["smooth"] = options.fairing.iterations;
    j["interpolate"] = options.interpolate;
    j["ring_tolerance"] = options.ring_tolerance;
    j["ring_voxel"] = options.ring_voxel;
    j["seconds"] = seconds;
    j["repairs"] = repairs;
    nlohmann::json list = nlohmann::json::array();
    for (const StructureMesh& s : built)
        list.push_back({{"id", s.id},
                        {"name", s.mesh.name},
                        {"contours", s.contours},
                        {"vertices", s.mesh.vertex_count()},
                        {"triangles", s.triangles},
                        {"volume", s.volume},
                        {"area", s.area},
                        {"genus", s.genus},
                        {"components", s.components},
                        {"closed_manifold", s.closed_manifold},
                        {"smooth_vertices_kept", s.fairing_restored},
                        {"interpolation_rungs_straight", s.interpolation_straightened},
                        {"seconds", s.seconds}});
    j["structures"] = std::move(list);
    std::printf("%s\n", j.dump(2).c_str());
}

void print_summary(const std::string& output, double seconds, const std::vector<StructureMesh>& built) {
    std::fprintf(stderr, "%-24s %10s %14s %14s %6s %9s\n", "structure", "triangles", "volume", "area", "genus",
                 "seconds");
    for (const StructureMesh& s : built)
        std::fprintf(stderr, "%-24s %10zu %14.6g %14.6g %6ld %9.3f%s\n", s.mesh.name.c_str(), s.triangles, s.volume,
                     s.area, s.genus, s.seconds, s.closed_manifold ? "" : "  (not closed)");
    std::fprintf(stderr, "wrote %s: %zu structures in %.3f s\n", output.c_str(), built.size(), seconds);
}

}  // namespace

int run_build(const Args& argv) {
    auto args = CliArgs::parse(argv,
                               {"output", "caps", "tiling", "correspondence", "branching", "jobs", "smooth",
                                "interpolate", "ring-tolerance", "ring-voxel", "repair-tolerance", "min-area",
#ifdef BODY_WITH_IMPORT
                                "labels", "axis", "step", "only", "threshold", "tolerance", "label-smooth"
#endif
                               },
                               {"help", "quiet", "json", "normals", "strict"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        print_usage();
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("build: expected one contour stack file"));
    if (!args->has("output")) return report(input_error("build: missing -o OUT.obj|OUT.bpm|OUT/"));
    auto options = build_options_from_args(*args);
    if (!options) return report(options.error());
    const bool quiet = args->has("quiet"), json_out = args->has("json");
    const std::string input = args->positional()[0], output = *args->get("output");
    if (output_kind(output) == OutputKind::Unknown)
        return report(input_error(output + ": unknown output type (expected OUT.obj, OUT.bpm or OUT/)"));
    if (Status apart = check_output_apart(output, {input, args->get_or("labels", "")}); !apart)
        return report(apart.error());
    if (!quiet)
        options->warning = [](const std::string& w) { std::fprintf(stderr, "bodygen: warning: %s\n", w.c_str()); };
    if (!quiet && isatty(STDERR_FILENO)) options->progress = progress_bar("slice pairs");
    std::map<std::string, size_t> repairs;
    options->repair_counts = [&repairs](const std::map<std::string, size_t>& counts) { repairs = counts; };

    const auto start = std::chrono::steady_clock::now();
    auto stack = load_input(input, *args, quiet);
    if (!stack) return report(stack.error());
    auto built = build_structures(*stack, *options, input);
    if (!built) return report(built.error());
    Status written = write_output(output, *built, args->has("normals"), options->jobs);
    if (!written) return report(written.error());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    if (json_out) print_json(input, output, *options, seconds, *built, repairs);
    if (!quiet) print_summary(output, seconds, *built);
    return kExitOk;
}

}  // namespace body::cli
