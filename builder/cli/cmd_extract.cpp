// bodygen extract IN.bpm (--ratio R | --triangles N | --error E) -o OUT.obj:
// one level of every structure, written as OBJ objects.
#include <cmath>
#include <cstdio>

#include "builder/cli/commands.h"
#include "shared/cli_args.h"
#include "shared/input_file.h"
#include "shared/obj_io.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"

namespace body::cli {

int run_extract(const Args& argv) {
    auto args = CliArgs::parse(argv, {"output", "ratio", "triangles", "error"}, {"help", "normals"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf(
            "usage: bodygen extract IN.bpm (--ratio R | --triangles N | --error E) -o OUT.obj [--normals]\n"
            "  --ratio R      the finest level with at most R x the full triangle count (0..1)\n"
            "  --triangles N  the finest level with at most N triangles (per structure)\n"
            "  --error E      the coarsest level whose stored error is at most E (object units)\n");
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("extract: expected one input .bpm file"));
    if (!args->has("output")) return report(input_error("extract: missing -o OUT.obj"));
    const int selectors = int(args->has("ratio")) + int(args->has("triangles")) + int(args->has("error"));
    if (selectors != 1) return report(input_error("extract: give exactly one of --ratio, --triangles, --error"));
    auto ratio = args->get_double("ratio", 1.0);
    auto triangles = args->get_long("triangles", 0);
    auto error = args->get_double("error", 0.0);
    if (!ratio) return report(ratio.error());
    if (!triangles) return report(triangles.error());
    if (!error) return report(error.error());
    if (!(*ratio >= 0.0 && *ratio <= 1.0) || *triangles < 0 || !(*error >= 0.0))
        return report(input_error("extract: --ratio must be in [0, 1], --triangles and --error >= 0"));
    if (Status apart = check_output_apart(*args->get("output"), {args->positional()[0]}); !apart)
        return report(apart.error());
    // Refinement order: every level exact (the batched draw order would move it to a batch boundary).
    auto pms = pm::read_bpm(args->positional()[0], pm::BpmStream::FaceOrder::Refinement);
    if (!pms) return report(pms.error());
    std::vector<Mesh> meshes;
    for (auto& p : *pms) {
        size_t level = 0;
        if (args->has("ratio")) {
            level = p->level_for_triangles(size_t(std::floor(*ratio * double(p->max_triangle_count()) + 1e-9)));
        } else if (args->has("triangles")) {
            level = p->level_for_triangles(size_t(*triangles));
        } else {
            level = p->level_for_error(float(*error));
        }
        p->set_level(level);
        Mesh m;
        m.name = p->name();
        m.color = Vec3(p->color());
        for (size_t v = 0; v < p->vertex_count(); ++v) m.positions.push_back(Vec3(p->position(v)));
        if (p->has_normals())
            for (size_t v = 0; v < p->vertex_count(); ++v) m.normals.push_back(Vec3(p->normal(v)));
        m.indices.assign(p->indices().begin(), p->indices().begin() + ptrdiff_t(p->triangle_count() * 3));
        std::printf("%s: level %zu of %zu, %zu triangles, error %g\n", m.name.c_str(), level, p->max_level(),
                    m.triangle_count(), double(p->error_at(level)));
        meshes.push_back(std::move(m));
    }
    ObjWriteOptions options;
    options.normals = args->has("normals");
    Status st = write_obj(*args->get("output"), meshes, options);
    if (!st) return report(st.error());
    return kExitOk;
}

}  // namespace body::cli
