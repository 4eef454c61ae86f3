// bodygen lod IN.(obj|wrl|stl|ply|gltf|glb) -o OUT.bpm [--min-triangles N] [--chunk-splits N] [--no-normals] [--jobs N]
//   [--quiet] [--json] [--sizes]: one progressive mesh per OBJ object, written as a .bpm file;
//   --sizes also prints where the SPLT sections' bytes went, per field and split.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "builder/cli/commands.h"
#include "builder/lod/bpm_writer.h"
#include "builder/lod/simplify.h"
#include "builder/mesh_import/mesh_import.h"
#include "shared/cli_args.h"
#include "shared/input_file.h"

namespace body::cli {
// The progressive-mesh options from the command line (shared with `bodygen exhibit`).
Result<lod::LodOptions> lod_options_from_args(const CliArgs& args) {
    auto min_tris = args.get_long("min-triangles", 0);
    if (!min_tris) return min_tris.error();
    auto chunk = args.get_long("chunk-splits", 4096);
    if (!chunk) return chunk.error();
    if (*min_tris < 0 || *chunk < 1) return input_error("lod: --min-triangles >= 0 and --chunk-splits >= 1");
    auto jobs = args.get_jobs(0);
    if (!jobs) return jobs.error();
    lod::LodOptions options;
    options.min_triangles = size_t(*min_tris);
    options.chunk_splits = size_t(*chunk);
    options.normals = !args.has("no-normals");
    options.threads = *jobs;
    return options;
}

namespace {
// The SPLT bytes per field (FORMAT.md's values), per split and as a share.
void print_split_sizes(const pm::SplitSizes& z) {
    const double* c = z.context_bits;
    const struct {
        const char* name;
        double bits;
    } rows[] = {
        {"parent number", c[pm::kCtxParentDelta]},
        {"kind", c[pm::kCtxKind]},
        {"error step", c[pm::kCtxErrorStep]},
        {"fan topology (start, length)", c[pm::kCtxFanStart] + c[pm::kCtxFanLength]},
        {"general topology", z.topology_bits},
        {"child position", c[pm::kCtxChild0] + c[pm::kCtxChild0 + 1] + c[pm::kCtxChild0 + 2]},
        {"parent move", c[pm::kCtxParent0] + c[pm::kCtxParent0 + 1] + c[pm::kCtxParent0 + 2]},
        {"child normal", c[pm::kCtxNormal0] + c[pm::kCtxNormal0 + 1]},
        {"position grids", c[pm::kCtxChildCoarse] + c[pm::kCtxParentCoarse]},
        {"coder tables", z.table_bits},
        {"coder framing", z.framing_bits},
        {"section headers", z.header_bits},
    };
    const double n = double(std::max<uint64_t>(z.splits, 1)), total = z.total_bits();
    std::printf("SPLT bytes per split, %llu splits:\n", static_cast<unsigned long long>(z.splits));
    for (const auto& r : rows)
        std::printf("  %-30s %6.3f  %5.1f %%\n", r.name, r.bits / 8 / n, total > 0 ? 100 * r.bits / total : 0.0);
    std::printf("  %-30s %6.3f\n", "total", total / 8 / n);
}
}  // namespace

int run_lod(const Args& argv) {
    auto args = CliArgs::parse(argv, {"output", "min-triangles", "chunk-splits", "jobs"},
                               {"help", "no-normals", "quiet", "json", "sizes"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf(
            "usage: bodygen lod IN.(obj|wrl|stl|ply|gltf|glb) -o OUT.bpm [--min-triangles N] [--chunk-splits N]\n"
            "                 [--no-normals] [--jobs N]\n"
            "  one progressive mesh per OBJ object (VRML97: per Shape; STL, PLY, glTF: per mesh); the base\n"
            "  mesh keeps at least N triangles\n"
            "  (default: as few as the topology allows)\n"
            "  --jobs N   threads for the setup and a large mesh's first phase\n"
            "             (default: one per CPU; the same output for any N)\n"
            "  --quiet    no summary line\n"
            "  --json     the summary as JSON on stdout\n"
            "  --sizes    also print where the vertex splits' bytes go, per field\n");
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("lod: expected one input mesh file"));
    if (!args->has("output")) return report(input_error("lod: missing -o OUT.bpm"));
    auto options = lod_options_from_args(*args);
    if (!options) return report(options.error());
    if (Status apart = check_output_apart(*args->get("output"), {args->positional()[0]}); !apart)
        return report(apart.error());
    if (!args->get("output")->ends_with(".bpm"))
        return report(input_error(*args->get("output") + ": lod writes a .bpm file (-o OUT.bpm)"));
    if (isatty(STDERR_FILENO) && !args->has("quiet")) options->progress = progress_bar("faces removed");
    const auto start = std::chrono::steady_clock::now();
    auto meshes = read_mesh_file(args->positional()[0]);
    if (!meshes) return report(meshes.error());
    const std::string out = *args->get("output");
    pm::SplitSizes sizes;
    Status st = lod::write_bpm_from_meshes(out, *meshes, *options, args->has("sizes") ? &sizes : nullptr);
    if (!st) return report(st.error());
    size_t tris = 0;
    for (const Mesh& m : *meshes) tris += m.triangle_count();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (args->has("json")) {
        nlohmann::json j = {{"input", args->positional()[0]},
                            {"output", out},
                            {"structures", meshes->size()},
                            {"triangles", tris},
                            {"seconds", seconds}};
        std::printf("%s\n", j.dump(2).c_str());
    } else if (!args->has("quiet")) {
        std::printf("%s: %zu structures, %zu triangles\n", out.c_str(), meshes->size(), tris);
    }
    if (args->has("sizes")) print_split_sizes(sizes);
    return kExitOk;
}

}  // namespace body::cli
