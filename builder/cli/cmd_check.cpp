// bodygen check INPUT: read a contour source, validate and repair it exactly as
// `bodygen build` does (same code path, same options), print each repair and
// a summary; exit 2 with the one line `build` would refuse with. With --links,
// also the correspondence build would use (builder/correspondence/link_table.h).
#include <cctype>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "builder/cli/commands.h"
#include "builder/contours/contour_stack.h"
#include "builder/contours/validate.h"
#include "builder/correspondence/link_overrides.h"
#include "builder/correspondence/link_table.h"
#ifdef BODY_WITH_IMPORT
#include "builder/import/import.h"
#endif
#include "shared/cli_args.h"

namespace body::cli {

#ifdef BODY_WITH_IMPORT
Result<ImportOptions> import_options_from_args(const CliArgs& args);  // cmd_contours.cpp
#endif

// Whether the one input is a contour stack (*.json) rather than a volume to import.
bool stack_input(const CliArgs& args) {
    if (args.positional().size() != 1) return false;
    std::string lower;
    for (char c : args.positional()[0]) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return lower.ends_with(".json");
}

// The repair options of check, build and contours (--strict, --repair-tolerance).
Result<RepairOptions> repair_options_from_args(const CliArgs& args) {
    RepairOptions o;
    o.strict = args.has("strict");
    auto tol = args.get_double("repair-tolerance", 0.0);
    if (!tol) return tol.error();
    if (!(*tol >= 0.0) || *tol > 1e9) return input_error("option --repair-tolerance: must be a distance >= 0");
    o.tolerance = *tol;
    // --min-area: for a contour stack an area in its units squared (for a
    // label volume the importer's voxel count, cmd_contours.cpp).
    if (stack_input(args)) {
        auto min_area = args.get_double("min-area", 0.0);
        if (!min_area) return min_area.error();
        if (!(*min_area >= 0.0) || *min_area > 1e18) return input_error("option --min-area: must be an area >= 0");
        o.min_area = *min_area;
    }
    return o;
}

// One "bodygen: warning:" line per repair, as build prints them.
void print_repairs(const RepairLog& log) {
    for (const std::string& line : log.lines) std::fprintf(stderr, "bodygen: warning: %s\n", line.c_str());
}

namespace {

constexpr const char* kUsage =
    "usage: bodygen check INPUT [options]\n"
    "  INPUT: STACK.contours.json"
#ifdef BODY_WITH_IMPORT
    ", a NIfTI label volume or a DICOM RT-STRUCT"
#endif
    "\n  Validates and repairs the contours exactly as `bodygen build` would, prints one line\n"
    "  per repair (file, slice, contour, place, what, how far points moved), exit 2 on a refusal.\n"
    "  --strict                  refuse on the first problem instead of repairing\n"
    "  --repair-tolerance D      largest distance a repair may move a point, in stack units\n"
    "                            (default 0.001 x the stack's x-y extent)\n"
    "  --min-area A              for a contour stack (.json): drop contours smaller than A (stack\n"
    "                            units squared) with a warning (default 0: keep all)\n"
    "  --json                    the summary and repair counts as JSON on stdout\n"
    "  --links                   also the correspondence build uses: one line per link between\n"
    "                            contours ([slice, contour] as in the file) and per end (cap),\n"
    "                            with the links section's cuts, joins and exclusions\n"
    "  --correspondence overlap|ellipse   the matching method, as for build (default overlap)\n"
#ifdef BODY_WITH_IMPORT
    "  --labels, --axis, --step, --only, --threshold, --tolerance, --min-area, --label-smooth\n"
    "                            import options for label volumes (see bodygen contours --help)\n"
#endif
    ;

Result<ContourStack> load(const std::string& path, const CliArgs& args) {
#ifdef BODY_WITH_IMPORT
    auto import = import_options_from_args(args);
    if (!import) return import.error();
    return load_any_contour_source(path, *import);
#else
    (void)args;
    return read_contour_stack(path);
#endif
}

std::string ref_text(const ContourRef& r) {
    char b[48];
    std::snprintf(b, sizeof b, "[%zu, %zu]", r.slice, r.contour);
    return b;
}

// The link table as JSON ("links", "ends", "excluded") for --json --links.
nlohmann::json table_json(const LinkTable& t) {
    nlohmann::json links = nlohmann::json::array(), ends = nlohmann::json::array(), excluded = nlohmann::json::array();
    for (const TableLink& l : t.links)
        links.push_back({{"structure", l.structure},
                         {"lower", {l.lower.slice, l.lower.contour}},
                         {"upper", {l.upper.slice, l.upper.contour}},
                         {"hole", l.hole},
                         {"kind", link_kind_name(l.kind)},
                         {"origin", link_origin_name(l.origin)}});
    for (const TableEnd& e : t.ends)
        ends.push_back({{"structure", e.structure},
                        {"contour", {e.contour.slice, e.contour.contour}},
                        {"side", e.up ? "top" : "bottom"}});
    for (const ContourRef& r : t.excluded) excluded.push_back({r.slice, r.contour});
    return {{"links", links}, {"ends", ends}, {"excluded", excluded}};
}

void print_table(const LinkTable& t) {
    for (const TableLink& l : t.links)
        std::printf("link %s %s -> %s %s%s (%s)\n", l.structure.c_str(), ref_text(l.lower).c_str(),
                    ref_text(l.upper).c_str(), link_kind_name(l.kind), l.hole ? " hole" : "",
                    link_origin_name(l.origin));
    for (const TableEnd& e : t.ends)
        std::printf("end %s %s %s\n", e.structure.c_str(), ref_text(e.contour).c_str(), e.up ? "top" : "bottom");
    for (const ContourRef& r : t.excluded) std::printf("excluded %s\n", ref_text(r).c_str());
}

}  // namespace

int run_contours_check(const Args& argv) {
    auto args = CliArgs::parse(argv,
                               {"repair-tolerance", "min-area", "correspondence",
#ifdef BODY_WITH_IMPORT
                                "labels", "axis", "step", "only", "threshold", "tolerance", "label-smooth"
#endif
                               },
                               {"help", "strict", "json", "links"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf("%s", kUsage);
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("check: expected one contour stack file"));
    auto repair = repair_options_from_args(*args);
    if (!repair) return report(repair.error());
    const std::string& input = args->positional()[0];
    const std::string method = args->get("correspondence").value_or("overlap");
    if (method != "overlap" && method != "ellipse")
        return report(input_error("option --correspondence: expected overlap or ellipse, got '" + method + "'"));
    auto stack = load(input, *args);
    if (!stack) return report(stack.error());
    std::optional<LinkTable> table;
    if (args->has("links")) {
        const auto m = method == "ellipse" ? CorrespondenceMethod::Ellipse : CorrespondenceMethod::Overlap;
        auto computed = compute_link_table(*stack, m, *repair, input);
        if (!computed) return report(computed.error());
        table = std::move(*computed);
    }
    drop_excluded_contours(*stack);  // as build does: an excluded contour is not validated
    RepairLog log;
    const double tolerance = repair_tolerance(*stack, *repair);
    Status valid = validate_contour_stack(*stack, input, *repair, log);
    if (!valid) return report(valid.error());  // the one line, as build shows it
    print_repairs(log);
    const auto [contours, points] = count_contours(*stack);
    if (args->has("json")) {
        nlohmann::json j = {{"input", input},
                            {"slices", stack->slices.size()},
                            {"contours", contours},
                            {"points", points},
                            {"structures", stack->structures.size()},
                            {"units", stack->units},
                            {"repair_tolerance", tolerance},
                            {"repairs", log.counts}};
        if (table) j.update(table_json(*table));
        std::printf("%s\n", j.dump(2).c_str());
        return kExitOk;
    }
    std::printf("%s: %zu slices, %zu contours, %zu points, %zu structures (units %s), %zu repair(s) or warning(s)\n",
                input.c_str(), stack->slices.size(), contours, points, stack->structures.size(), stack->units.c_str(),
                log.lines.size());
    if (table) print_table(*table);
    return kExitOk;
}

}  // namespace body::cli
