// The baseline of `bodygen lod`'s whole-process build time (bench/build_vs_meshopt.sh):
// a whole process that reads the OBJ with the same reader, builds a 10-level
// meshoptimizer chain (each level meshopt_simplify of the one before, to 70 % of
// its triangles, then ordered for the vertex cache) and writes the levels with
// meshoptimizer's codecs, as a discrete-LOD exporter would.
//
// usage: bench_meshopt_chain IN.obj OUT.bin
#include <meshoptimizer.h>

#include <cstdio>
#include <vector>

#include "shared/obj_io.h"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: bench_meshopt_chain IN.obj OUT.bin\n");
        return 2;
    }
    auto mesh = body::read_obj_merged(argv[1]);
    if (!mesh) {
        std::fprintf(stderr, "%s\n", mesh.error().message.c_str());
        return 2;
    }
    std::vector<float> pos;
    for (const auto& p : mesh->positions)
        for (int k = 0; k < 3; ++k) pos.push_back(float(p[k]));
    const size_t vertices = mesh->positions.size();
    std::vector<uint32_t> level = mesh->indices, next(level.size());
    std::vector<unsigned char> out, code;
    for (int k = 0; k < 10; ++k) {
        if (k > 0) {
            float error = 0.0f;
            const size_t target = level.size() / 3 * 7 / 10 * 3;
            next.resize(meshopt_simplify(next.data(), level.data(), level.size(), pos.data(), vertices,
                                         sizeof(float) * 3, target, 1e-1f, 0, &error));
            level.swap(next);
            next.resize(level.size());
        }
        meshopt_optimizeVertexCache(level.data(), level.data(), level.size(), vertices);
        code.resize(meshopt_encodeIndexBufferBound(level.size(), vertices));
        code.resize(meshopt_encodeIndexBuffer(code.data(), code.size(), level.data(), level.size()));
        out.insert(out.end(), code.begin(), code.end());
    }
    code.resize(meshopt_encodeVertexBufferBound(vertices, sizeof(float) * 3));
    code.resize(meshopt_encodeVertexBuffer(code.data(), code.size(), pos.data(), vertices, sizeof(float) * 3));
    out.insert(out.end(), code.begin(), code.end());
    FILE* f = std::fopen(argv[2], "wb");
    if (!f || std::fwrite(out.data(), 1, out.size(), f) != out.size() || std::fclose(f) != 0) {
        std::fprintf(stderr, "%s: cannot write\n", argv[2]);
        return 1;
    }
    std::printf("%s: 10 levels, %zu bytes\n", argv[2], out.size());
    return 0;
}
