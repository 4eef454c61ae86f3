// bodygen contours LABELS.nii[.gz]|RTSTRUCT.dcm -o OUT.contours.json: extract a
// contour stack from a label volume or an RT structure set.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "builder/cli/commands.h"
#include "shared/error.h"

#ifdef BODY_WITH_IMPORT
#include "builder/contours/contour_stack.h"
#include "builder/contours/validate.h"
#include "builder/import/import.h"
#include "shared/cli_args.h"
#include "shared/input_file.h"
#endif

namespace body::cli {

namespace {

constexpr const char* kUsage =
    "usage: bodygen contours LABELS.nii[.gz]|RTSTRUCT.dcm -o OUT.contours.json [options]\n"
    "  --labels FILE     label table (index name lines, FSL/MRIcron .txt or .lut);\n"
    "                    default: <volume>.txt / <volume>.lut beside the volume\n"
    "  --axis z|y|x      slicing axis of the volume (default z)\n"
    "  --step K          every K-th slice (default 1)\n"
    "  --only 3,7,12     only these labels (RT-STRUCT: ROI numbers)\n"
    "  --threshold T     non-integer volumes: extract value >= T as one mask\n"
    "  --tolerance V     simplification tolerance in voxels (default 0.1, with --label-smooth 0\n"
    "                    0.5; 0 keeps every vertex)\n"
    "  --min-area A      drop islands and fill holes smaller than A voxels per slice (0-8, default 0)\n"
    "  --label-smooth S  label volumes: blur each label by a Gaussian of S voxels (0-4; voxels of\n"
    "                    the finest axis, the same in mm on every axis) and trace it between voxel\n"
    "                    centres, keeping its voxel volume; labels the blur would shrink or split\n"
    "                    (thin ones) are blurred less (default 2; 0: the voxel faces, terraced)\n"
    "  --jobs N          structures extracted in parallel (default 1)\n"
    "  --strict          refuse extracted contours with any problem instead of repairing them\n"
    "  --repair-tolerance D  largest distance a contour repair may move a point (see bodygen check)\n"
    "  --quiet           no progress bar, notes or summary\n"
    "  --json            the summary as JSON on stdout\n";

}  // namespace

#ifdef BODY_WITH_IMPORT

Result<RepairOptions> repair_options_from_args(const CliArgs& args);  // cmd_check.cpp
bool stack_input(const CliArgs& args);                                // cmd_check.cpp
void print_repairs(const RepairLog& log);                             // cmd_check.cpp

namespace {

// --label-smooth's default and --tolerance's default with it, in voxels
// (chosen on the AAL atlas: bench/RESULTS.md, issue 23 labels).
constexpr double kDefaultLabelSmooth = 2.0;
constexpr double kSmoothTolerance = 0.1;

Result<std::vector<int64_t>> parse_only(const std::string& text) {
    std::vector<int64_t> out;
    size_t pos = 0;
    while (pos <= text.size()) {
        size_t comma = text.find(',', pos);
        if (comma == std::string::npos) comma = text.size();
        const std::string item = text.substr(pos, comma - pos);
        char* end = nullptr;
        const long long v = std::strtoll(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || v <= 0) {
            return input_error("option --only: '" + item + "' is not a positive label number");
        }
        out.push_back(v);
        pos = comma + 1;
    }
    return out;
}

}  // namespace

// Shared with other commands that take the same import options.
Result<ImportOptions> import_options_from_args(const CliArgs& args) {
    ImportOptions o;
    o.labels_path = args.get_or("labels", "");
    const std::string axis = args.get_or("axis", "z");
    if (axis == "x")
        o.axis = 0;
    else if (axis == "y")
        o.axis = 1;
    else if (axis == "z")
        o.axis = 2;
    else
        return input_error("option --axis: '" + axis + "' is not x, y or z");
    auto step = args.get_long("step", 1);
    if (!step) return step.error();
    if (*step < 1 || *step > 100000) return input_error("option --step: must be a positive integer");
    o.step = static_cast<int>(*step);
    if (auto only = args.get("only")) {
        auto list = parse_only(*only);
        if (!list) return list.error();
        o.only = std::move(*list);
    }
    if (args.has("threshold")) {
        auto t = args.get_double("threshold", 0.0);
        if (!t) return t.error();
        o.threshold = *t;
    }
    auto min_area = args.get_double("min-area", 0.0);
    if (!min_area) return min_area.error();
    if (!stack_input(args) && (*min_area < 0.0 || *min_area > 8.0))
        return input_error("option --min-area: must be between 0 and 8 voxels");
    o.min_area = *min_area;
    auto label_smooth = args.get_double("label-smooth", kDefaultLabelSmooth);
    if (!label_smooth) return label_smooth.error();
    if (!(*label_smooth >= 0.0) || *label_smooth > 4.0)
        return input_error("option --label-smooth: must be between 0 and 4 voxels");
    o.label_smooth = *label_smooth;
    // Smooth contours simplified by half a voxel become facets that differ
    // from slice to slice and show as streaks.
    auto tol = args.get_double("tolerance", o.label_smooth > 0.0 ? kSmoothTolerance : o.tolerance);
    if (!tol) return tol.error();
    if (*tol < 0.0 || *tol > 10.0) return input_error("option --tolerance: must be between 0 and 10 voxels");
    o.tolerance = *tol;
    auto jobs = args.get_jobs(1);
    if (!jobs) return jobs.error();
    o.jobs = static_cast<int>(*jobs);
    return o;
}

int run_contours(const Args& argv) {
    auto args = CliArgs::parse(argv,
                               {"labels", "axis", "step", "only", "threshold", "tolerance", "min-area", "label-smooth",
                                "jobs", "output", "repair-tolerance"},
                               {"help", "quiet", "json", "strict"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf("%s", kUsage);
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("contours: expected one input file (see --help)"));
    const auto output = args->get("output");
    if (!output || output->empty()) return report(input_error("contours: -o OUT.contours.json is required"));
    auto options = import_options_from_args(*args);
    if (!options) return report(options.error());
    const bool quiet = args->has("quiet");
    if (!quiet) {
        options->note = [](const std::string& m) { std::fprintf(stderr, "bodygen: note: %s\n", m.c_str()); };
        if (::isatty(2)) options->progress = progress_bar("structures");
    }
    const std::string& input = args->positional()[0];
    if (Status apart = check_output_apart(*output, {input, args->get_or("labels", "")}); !apart)
        return report(apart.error());
    const SourceKind kind = detect_source_kind(input);
    if (kind == SourceKind::ContourStack) {
        return report(input_error(input + ": already a contour stack (use bodygen check)"));
    }
    const auto start = std::chrono::steady_clock::now();
    auto repair = repair_options_from_args(*args);
    if (!repair) return report(repair.error());
    auto stack = load_any_contour_source(input, *options);
    if (!stack) return report(stack.error());
    // The same validation and repair as check and build: the written stack needs none.
    RepairLog log;
    Status valid = validate_contour_stack(*stack, input, *repair, log);
    if (!valid) return report(valid.error());
    if (!quiet) print_repairs(log);
    if (auto written = write_contour_stack(*output, *stack); !written) return report(written.error());
    const auto [contours, points] = count_contours(*stack);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (args->has("json")) {
        const nlohmann::json j = {{"input", input},
                                  {"output", *output},
                                  {"structures", stack->structures.size()},
                                  {"slices", stack->slices.size()},
                                  {"contours", contours},
                                  {"points", points},
                                  {"seconds", seconds}};
        std::printf("%s\n", j.dump(2).c_str());
    } else if (!quiet) {
        std::printf("%s: %zu structures, %zu slices, %zu contours, %zu points in %.2f s\n", output->c_str(),
                    stack->structures.size(), stack->slices.size(), contours, points, seconds);
    }
    return kExitOk;
}

#else

int run_contours(const Args& argv) {
    for (const std::string& a : argv) {
        if (a == "--help") {
            std::printf("%s", kUsage);
            return kExitOk;
        }
    }
    return report(input_error("contours: this bodygen was built without import support (BODY_WITH_IMPORT=OFF)"));
}

#endif

}  // namespace body::cli
