// bodygen export (BUNDLE/ | SCENE.json | X.bpm | X.obj) -o OUT.{glb,gltf,wrl,obj,stl,ply} [--lod R]:
// models that travel to other tools (format contracts in builder/export/).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "builder/cli/commands.h"
#include "builder/export/export_scene.h"
#include "builder/export/gltf_writer.h"
#include "builder/export/mesh_writers.h"
#include "shared/cli_args.h"
#include "shared/input_file.h"

namespace body::cli {

int run_export(const Args& argv) {
    auto args = CliArgs::parse(argv, {"output", "lod"}, {"help", "quiet", "json", "meshopt"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf(
            "usage: bodygen export (BUNDLE/ | SCENE.json | X.bpm | X.obj) -o OUT.EXT [--lod R] [--quiet] [--json]\n"
            "  EXT: glb, gltf (glTF 2.0: a node per model under a node per group, colours as\n"
            "       materials, the scene's transforms), wrl (VRML97), stl (binary), ply (binary),\n"
            "       obj; stl/ply/obj/wrl have the scene's transforms applied to the vertices\n"
            "  --lod R   progressive meshes at R x their full triangle count, (0, 1] (default 1)\n"
            "  --meshopt .glb: KHR_mesh_quantization + EXT_meshopt_compression (smaller; needs a\n"
            "            viewer with both extensions)\n"
            "  --quiet   no summary line;  --json  the summary as JSON on stdout\n");
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("export: expected one input (see --help)"));
    if (!args->has("output")) return report(input_error("export: missing -o OUT.glb|gltf|wrl|obj|stl|ply"));
    auto lod = args->get_double("lod", 1.0);
    if (!lod) return report(lod.error());
    const std::string out = *args->get("output");
    const std::string ext = std::filesystem::path(out).extension().string();
    if (args->has("meshopt") && ext != ".glb") return report(input_error("export: --meshopt needs a .glb output"));
    if (ext != ".glb" && ext != ".gltf" && ext != ".wrl" && ext != ".obj" && ext != ".stl" && ext != ".ply")
        return report(input_error("export: " + out + ": the extension must be .glb, .gltf, .wrl, .obj, .stl or .ply"));
    if (Status apart = check_output_apart(out, {args->positional()[0]}); !apart) return report(apart.error());
    const auto start = std::chrono::steady_clock::now();
    auto scene = exporter::load_export_scene(args->positional()[0], *lod);
    if (!scene) return report(scene.error());
    Status st = ok_status();
    if (ext == ".glb" || ext == ".gltf")
#ifdef BODY_WITH_GLTF
        st = exporter::write_gltf(out, *scene, exporter::GltfOptions{ext == ".glb", args->has("meshopt")});
#else
        return report(runtime_error("export: this bodygen was built without glTF support (libtinygltf-dev)"));
#endif
    else if (ext == ".wrl")
        st = exporter::write_vrml(out, *scene);
    else if (ext == ".stl")
        st = exporter::write_stl(out, *scene);
    else if (ext == ".ply")
        st = exporter::write_ply(out, *scene);
    else
        st = exporter::write_placed_obj(out, *scene);
    if (!st) return report(st.error());
    size_t triangles = 0;
    for (const auto& m : scene->models) triangles += m.mesh.triangle_count();
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(out, ec);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (args->has("json")) {
        const nlohmann::json j = {{"input", args->positional()[0]}, {"output", out},
                                  {"models", scene->models.size()}, {"triangles", triangles},
                                  {"bytes", size_t(bytes)},         {"seconds", seconds}};
        std::printf("%s\n", j.dump(2).c_str());
    } else if (!args->has("quiet")) {
        std::printf("%s: %zu models, %zu triangles, %zu bytes\n", out.c_str(), scene->models.size(), triangles,
                    size_t(bytes));
    }
    return kExitOk;
}

}  // namespace body::cli
