// bodygen lod IN.(obj|wrl|stl|ply|gltf|glb) -o OUT.bpm [--min-triangles N] [--chunk-splits N] [--no-normals] [--jobs N]
//   [--quiet] [--json]: one progressive mesh per OBJ object, written as a .bpm file.
#include <unistd.h>

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

int run_lod(const Args& argv) {
    auto args = CliArgs::parse(argv, {"output", "min-triangles", "chunk-splits", "jobs"},
                               {"help", "no-normals", "quiet", "json"});
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
            "  --json     the summary as JSON on stdout\n");
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
    Status st = lod::write_bpm_from_meshes(out, *meshes, *options);
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
    return kExitOk;
}

}  // namespace body::cli
