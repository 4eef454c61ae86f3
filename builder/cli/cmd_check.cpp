// bodygen check STACK.contours.json: parse a contour stack and summarise it.
#include <cstdio>

#include "builder/cli/commands.h"
#include "builder/contours/contour_stack.h"
#include "shared/cli_args.h"

namespace body::cli {

int run_contours_check(const Args& argv) {
    auto args = CliArgs::parse(argv, {}, {"help"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf("usage: bodygen check STACK.contours.json\n");
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("check: expected one contour stack file"));
    auto stack = read_contour_stack(args->positional()[0]);
    if (!stack) return report(stack.error());
    const auto [contours, points] = count_contours(*stack);
    std::printf("%s: %zu slices, %zu contours, %zu points, %zu structures (units %s)\n", args->positional()[0].c_str(),
                stack->slices.size(), contours, points, stack->structures.size(), stack->units.c_str());
    return kExitOk;
}

}  // namespace body::cli
