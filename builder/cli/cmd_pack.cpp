// bodygen pack scene.json -o BUNDLE/: the printing around scene::pack_scene
// (shared/scene/scene_pack.h, which the authoring window's Pack runs too).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "builder/cli/commands.h"
#include "shared/cli_args.h"

namespace body::cli {

int run_pack(const Args& argv) {
    auto args = CliArgs::parse(argv, {"o", "output"}, {"help", "quiet", "json"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf(
            "usage: bodygen pack SCENE.json -o BUNDLE/ [--quiet] [--json]\n"
            "validates the scene (shared/scene/SCENE.md), copies its models into BUNDLE/models/ and\n"
            "writes BUNDLE/scene.json; the bundle replaces BUNDLE/ atomically. Exit 2 on a bad reference.\n"
            "  --quiet  no summary line\n"
            "  --json   the summary as JSON on stdout\n");
        return kExitOk;
    }
    const auto out = args->has("o") ? args->get("o") : args->get("output");
    if (args->positional().size() != 1 || !out)
        return report(input_error("pack: usage: bodygen pack SCENE.json -o BUNDLE/"));
    const std::string scene_path = args->positional()[0];
    auto summary = pack_scene(scene_path, *out);
    if (!summary) return report(summary.error());
    if (args->has("json")) {
        nlohmann::json j = {{"scene", scene_path},       {"bundle", summary->bundle},       {"models", summary->models},
                            {"groups", summary->groups}, {"triangles", summary->triangles}, {"bytes", summary->bytes}};
        std::printf("%s\n", j.dump(2).c_str());
    } else if (!args->has("quiet")) {
        std::printf("%s: %zu models, %zu groups, %zu triangles at full detail -> %s\n", scene_path.c_str(),
                    summary->models, summary->groups, summary->triangles, summary->bundle.c_str());
    }
    return kExitOk;
}

}  // namespace body::cli
