// bodygen info IN.bpm: structures, levels, sizes and the error curve.
#include <cstdio>

#include "builder/cli/commands.h"
#include "shared/cli_args.h"
#include "shared/input_file.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"

namespace body::cli {

int run_info(const Args& argv) {
    auto args = CliArgs::parse(argv, {}, {"help"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf("usage: bodygen info IN.bpm\n");
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("info: expected one input .bpm file"));
    const std::string& path = args->positional()[0];
    // Checks the file type and the 16-byte header before reading on; every level exact (refinement order).
    auto pms = pm::read_bpm(path, pm::BpmStream::FaceOrder::Refinement);
    if (!pms) return report(pms.error());
    auto file_size = regular_file_size(path);
    if (!file_size) return report(file_size.error());
    const size_t size = size_t(*file_size);
    size_t splits = 0;
    for (auto& p : *pms) splits += p->max_level();
    std::printf("%s: %zu bytes, %zu structures, %zu vertex splits (%.2f bytes per split overall)\n", path.c_str(), size,
                pms->size(), splits, splits ? double(size) / double(splits) : 0.0);
    for (size_t s = 0; s < pms->size(); ++s) {
        const pm::ProgressiveMesh& p = *(*pms)[s];
        const Vec3f c = p.color(), lo = p.bounds_min(), hi = p.bounds_max();
        std::printf(
            "structure %zu '%s': colour (%.3f %.3f %.3f), bounds (%g %g %g)-(%g %g %g), normals %s\n"
            "  base %zu vertices / %zu triangles, full %zu vertices / %zu triangles, %zu splits, quantization "
            "bound %g\n",
            s, p.name().c_str(), double(c.x), double(c.y), double(c.z), double(lo.x), double(lo.y), double(lo.z),
            double(hi.x), double(hi.y), double(hi.z), p.has_normals() ? "yes" : "no", p.base_vertex_count(),
            p.base_triangle_count(), p.max_vertex_count(), p.max_triangle_count(), p.max_level(),
            double(p.quantization_bound()));
        std::printf("  error curve (triangles -> stored error):");
        for (double r : {0.0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0}) {
            const size_t level = p.level_for_triangles(size_t(r * double(p.max_triangle_count())));
            std::printf(" %zu:%g", p.triangles_at(level), double(p.error_at(level)));
        }
        std::printf("\n");
    }
    return kExitOk;
}

}  // namespace body::cli
