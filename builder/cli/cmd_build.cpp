// bodygen build STACK.contours.json -o OUT.obj [--caps flat|dome|none]
//   [--tiling optimal|multires] [--correspondence overlap|ellipse]
//   [--branching partition|overlap] [--normals] [--quiet] [--json]
// Contour stack -> one closed mesh per structure, written as OBJ (atomically).
// A per-structure summary goes to stderr (or JSON stats to stdout with --json);
// a progress bar is drawn when stderr is a terminal.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "builder/cli/commands.h"
#include "builder/pipeline/build_pipeline.h"
#include "shared/cli_args.h"
#include "shared/obj_io.h"

namespace body::cli {
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

void draw_progress(size_t done, size_t total) {
    const int width = 40;
    const int filled = total ? int(double(done) / double(total) * width) : width;
    std::fprintf(stderr, "\r[%.*s%*s] %zu/%zu slice pairs", filled, "########################################",
                 width - filled, "", done, total);
    if (done >= total) std::fprintf(stderr, "\r%*s\r", width + 40, "");
    std::fflush(stderr);
}

}  // namespace

int run_build(const Args& argv) {
    auto args = CliArgs::parse(argv, {"output", "caps", "tiling", "correspondence", "branching"},
                               {"help", "quiet", "json", "normals"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf(
            "usage: bodygen build STACK.contours.json -o OUT.obj [options]\n"
            "  --caps flat|dome|none              closing the ends (default flat)\n"
            "  --tiling optimal|multires          band tiling (default optimal)\n"
            "  --correspondence overlap|ellipse   matching contours across slices (default overlap)\n"
            "  --branching partition|overlap      branches: closed manifold, or the thesis'\n"
            "                                     overlapping bands for comparison (default partition)\n"
            "  --normals                          write vertex normals\n"
            "  --quiet                            no progress bar and no summary\n"
            "  --json                             statistics as JSON on stdout\n");
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("build: expected one contour stack file"));
    if (!args->has("output")) return report(input_error("build: missing -o OUT.obj"));
    BuildOptions options;
    auto caps = pick<CapStyle>(
        *args, "caps", {{"flat", CapStyle::Flat}, {"dome", CapStyle::Dome}, {"none", CapStyle::None}}, CapStyle::Flat);
    if (!caps) return report(caps.error());
    auto tiling =
        pick<TilingMethod>(*args, "tiling", {{"optimal", TilingMethod::Optimal}, {"multires", TilingMethod::Multires}},
                           TilingMethod::Optimal);
    if (!tiling) return report(tiling.error());
    auto corr = pick<CorrespondenceMethod>(
        *args, "correspondence",
        {{"overlap", CorrespondenceMethod::Overlap}, {"ellipse", CorrespondenceMethod::Ellipse}},
        CorrespondenceMethod::Overlap);
    if (!corr) return report(corr.error());
    auto branching = pick<BranchingMethod>(
        *args, "branching", {{"partition", BranchingMethod::Partition}, {"overlap", BranchingMethod::Overlap}},
        BranchingMethod::Partition);
    if (!branching) return report(branching.error());
    options.caps = *caps;
    options.tiling = *tiling;
    options.correspondence = *corr;
    options.branching = *branching;
    const bool quiet = args->has("quiet"), json_out = args->has("json");
    const std::string input = args->positional()[0], output = *args->get("output");
    if (!quiet)
        options.warning = [](const std::string& w) { std::fprintf(stderr, "bodygen: warning: %s\n", w.c_str()); };
    if (!quiet && isatty(STDERR_FILENO)) options.progress = draw_progress;

    const auto start = std::chrono::steady_clock::now();
    auto stack = read_contour_stack(input);
    if (!stack) return report(stack.error());
    auto built = build_structures(*stack, options, input);
    if (!built) return report(built.error());
    std::vector<Mesh> meshes;
    for (const StructureMesh& s : *built) meshes.push_back(s.mesh);
    ObjWriteOptions obj;
    obj.normals = args->has("normals");
    Status written = write_obj(output, meshes, obj);
    if (!written) return report(written.error());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    if (json_out) {
        nlohmann::json j;
        j["input"] = input;
        j["output"] = output;
        j["caps"] = cap_style_name(options.caps);
        j["tiling"] = tiling_method_name(options.tiling);
        j["correspondence"] = correspondence_method_name(options.correspondence);
        j["branching"] = branching_method_name(options.branching);
        j["seconds"] = seconds;
        nlohmann::json list = nlohmann::json::array();
        for (const StructureMesh& s : *built)
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
                            {"seconds", s.seconds}});
        j["structures"] = std::move(list);
        std::printf("%s\n", j.dump(2).c_str());
    }
    if (!quiet) {
        std::fprintf(stderr, "%-24s %10s %14s %14s %6s %9s\n", "structure", "triangles", "volume", "area", "genus",
                     "seconds");
        for (const StructureMesh& s : *built)
            std::fprintf(stderr, "%-24s %10zu %14.6g %14.6g %6ld %9.3f%s\n", s.mesh.name.c_str(), s.triangles, s.volume,
                         s.area, s.genus, s.seconds, s.closed_manifold ? "" : "  (not closed)");
        std::fprintf(stderr, "wrote %s: %zu structures in %.3f s\n", output.c_str(), built->size(), seconds);
    }
    return kExitOk;
}

}  // namespace body::cli
