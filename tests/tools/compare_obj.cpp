// body_compare_obj A.obj B.obj [TOLERANCE]
// Checks that two OBJ files hold the same objects with the same triangles and
// vertex positions within TOLERANCE (absolute, default 1e-9). Exit 0 same, 1 differ, 2 bad input.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "shared/obj_io.h"

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: body_compare_obj A.obj B.obj [TOLERANCE]\n");
        return 2;
    }
    const double tolerance = argc > 3 ? std::atof(argv[3]) : 1e-9;
    auto a = body::read_obj(argv[1]);
    auto b = body::read_obj(argv[2]);
    if (!a || !b) {
        std::fprintf(stderr, "body_compare_obj: %s\n", (!a ? a.error() : b.error()).message.c_str());
        return 2;
    }
    if (a->size() != b->size()) {
        std::printf("object count differs: %zu vs %zu\n", a->size(), b->size());
        return 1;
    }
    double worst = 0;
    for (size_t m = 0; m < a->size(); ++m) {
        const body::Mesh &x = (*a)[m], &y = (*b)[m];
        if (x.name != y.name || x.indices != y.indices || x.positions.size() != y.positions.size()) {
            std::printf("object %zu (%s) differs in name or topology\n", m, x.name.c_str());
            return 1;
        }
        for (size_t i = 0; i < x.positions.size(); ++i)
            for (int c = 0; c < 3; ++c) worst = std::fmax(worst, std::fabs(x.positions[i][c] - y.positions[i][c]));
    }
    std::printf("same topology in %zu objects; largest coordinate difference %.3g (tolerance %.3g)\n", a->size(), worst,
                tolerance);
    return worst <= tolerance ? 0 : 1;
}
