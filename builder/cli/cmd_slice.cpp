// bodygen slice IN.obj --planes N [--axis x|y|z] -o OUT.contours.json: slice a
// closed mesh into a contour stack (N planes evenly spaced strictly inside the
// mesh's extent along the axis), e.g. to make a test stack from a real mesh.
#include <cstdio>
#include <filesystem>

#include "builder/cli/commands.h"
#include "builder/contours/contour_stack.h"
#include "builder/slicing/mesh_slicer.h"
#include "shared/cli_args.h"
#include "shared/input_file.h"
#include "shared/obj_io.h"

namespace body::cli {

int run_slice(const Args& argv) {
    auto args = CliArgs::parse(argv, {"planes", "axis", "o", "output", "structure"},
                               {"help", "quiet", "avoid-self-intersections"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf(
            "usage: bodygen slice IN.obj --planes N [--axis x|y|z] [--structure ID] -o OUT.contours.json\n"
            "  slices a closed mesh (all objects merged) with N planes evenly spaced strictly inside its\n"
            "  extent along the axis (default z); contours are counter-clockwise around solid.\n"
            "  --avoid-self-intersections  move the planes that cross triangles of the mesh that intersect\n"
            "                              each other (their contours would cross) just past them, within\n"
            "                              0.45 of the gap; leave out those that cannot move that little\n");
        return kExitOk;
    }
    if (args->positional().size() != 1) return report(input_error("slice: expected one input OBJ file"));
    auto planes = args->get_long("planes", 0);
    if (!planes) return report(planes.error());
    if (*planes < 1 || *planes > 1000000) return report(input_error("slice: --planes must be in [1, 1000000]"));
    const std::string axis_name = args->get_or("axis", "z");
    if (axis_name != "x" && axis_name != "y" && axis_name != "z")
        return report(input_error("slice: --axis must be x, y or z"));
    const int axis = axis_name[0] - 'x';
    const std::string output = args->get_or("o", args->get_or("output", ""));
    if (output.empty()) return report(input_error("slice: -o OUT.contours.json is required"));
    const std::string& input = args->positional()[0];
    if (Status apart = check_output_apart(output, {input}); !apart) return report(apart.error());

    auto mesh = read_obj_merged(input);
    if (!mesh) return report(mesh.error());
    if (mesh->triangle_count() == 0) return report(input_error("slice: " + input + ": no triangles"));
    Aabb box = mesh_bounds(mesh->positions);
    std::vector<double> heights = evenly_spaced_planes(box.min[axis], box.max[axis], size_t(*planes));
    if (args->has("avoid-self-intersections")) {
        const PlaneMoves moves = move_planes_off_self_intersections(mesh->positions, mesh->indices, axis, heights);
        if (moves.moved && !args->has("quiet"))
            std::fprintf(stderr,
                         "%s: moved %zu of %ld planes off the mesh's self-intersections (at most %.2f of the gap)\n",
                         input.c_str(), moves.moved, *planes, moves.largest_move);
        if (moves.dropped && !args->has("quiet"))
            std::fprintf(stderr, "%s: left out %zu of %ld planes that cross the mesh's self-intersections\n",
                         input.c_str(), moves.dropped, *planes);
        if (heights.empty())
            return report(input_error("slice: " + input + ": every plane crosses a self-intersection"));
    }
    std::string structure = args->get_or("structure", std::filesystem::path(input).stem().string());
    auto stack = slice_mesh(mesh->positions, mesh->indices, axis, heights, structure);
    if (!stack) return report(input_error(input + ": " + stack.error().message));
    if (auto s = write_contour_stack(output, *stack); !s) return report(s.error());
    if (!args->has("quiet")) {
        const auto [contours, points] = count_contours(*stack);
        std::fprintf(stderr, "%s: %zu slices, %zu contours, %zu points -> %s\n", input.c_str(), stack->slices.size(),
                     contours, points, output.c_str());
    }
    return kExitOk;
}

}  // namespace body::cli
