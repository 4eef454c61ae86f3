// bodygen info IN.bpm: structures, levels, sizes (beside static-mesh codecs) and the error curve.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "builder/cli/commands.h"
#include "builder/lod/codec_baselines.h"
#include "shared/atomic_file.h"
#include "shared/cli_args.h"
#include "shared/input_file.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"

namespace body::cli {

namespace {

// Bytes of each structure's sections (header, payload and checksum) in a file
// read_bpm accepted.
std::vector<size_t> structure_bytes(const std::string& bytes, size_t structures) {
    std::vector<size_t> out(structures, 0);
    const auto* b = reinterpret_cast<const uint8_t*>(bytes.data());
    for (size_t pos = pm::kFileHeaderSize; pos + pm::kSectionHeaderSize <= bytes.size();) {
        const size_t total = pm::kSectionHeaderSize + pm::get_u32(b + pos + 8) + pm::kSectionTrailerSize;
        const uint32_t s = pm::get_u16(b + pos + 4);
        if (pm::get_u32(b + pos) != pm::kTagEnd && s < structures) out[s] += total;
        pos += total;
    }
    return out;
}

// The structure's bytes per split (its sections' share of the file: INFO, BASE,
// SPLT) beside the full mesh through meshoptimizer's and Draco's codecs, per vertex.
void print_codec_baselines(pm::ProgressiveMesh& p, size_t structure_bytes) {
    p.set_level(p.max_level());
    const auto idx = p.indices().first(p.max_triangle_count() * 3);
    const uint8_t* oct = p.has_normals() ? p.normal_codes().data() : nullptr;
    const size_t n = p.max_vertex_count(), splits = std::max<size_t>(p.max_level(), 1);
    const size_t mo = lod::meshopt_codec_bytes(p.position_codes().data(), oct, n, idx.data(), idx.size());
    std::printf(
        "  size: %.2f bytes per split; full mesh, 16-bit positions%s: meshoptimizer codecs %.2f bytes per vertex",
        double(structure_bytes) / double(splits), oct ? ", 8-bit normals" : "", double(mo) / double(n));
    if (lod::draco_available())
        std::printf(
            ", Draco (level 10) %.2f",
            double(lod::draco_codec_bytes(p.position_codes().data(), oct, n, idx.data(), idx.size())) / double(n));
    else
        std::printf(", Draco: not built in");
    std::printf("\n");
}

}  // namespace

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
    auto bytes = read_file(path);
    if (!bytes) return report(bytes.error());
    const std::vector<size_t> section_bytes = structure_bytes(*bytes, pms->size());
    for (size_t s = 0; s < pms->size(); ++s) {
        pm::ProgressiveMesh& p = *(*pms)[s];
        const Vec3f c = p.color(), lo = p.bounds_min(), hi = p.bounds_max();
        std::printf(
            "structure %zu '%s': colour (%.3f %.3f %.3f), bounds (%g %g %g)-(%g %g %g), normals %s\n"
            "  base %zu vertices / %zu triangles, full %zu vertices / %zu triangles, %zu splits, quantization "
            "bound %g\n",
            s, p.name().c_str(), double(c.x), double(c.y), double(c.z), double(lo.x), double(lo.y), double(lo.z),
            double(hi.x), double(hi.y), double(hi.z), p.has_normals() ? "yes" : "no", p.base_vertex_count(),
            p.base_triangle_count(), p.max_vertex_count(), p.max_triangle_count(), p.max_level(),
            double(p.quantization_bound()));
        print_codec_baselines(p, section_bytes[s]);
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
