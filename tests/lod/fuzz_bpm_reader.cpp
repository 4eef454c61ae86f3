// libFuzzer target: the .bpm stream reader must reject or accept any bytes without
// crashing, fed whole or in two pieces, and a decoded structure must survive
// refining and coarsening over every level it has.
#include <cstddef>
#include <cstdint>
#include <span>

#include "shared/pm/progressive_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const size_t cut = size ? data[0] % (size + 1) : 0;
    body::pm::BpmStream stream("fuzz");
    std::span<const uint8_t> all(data, size);
    if (stream.feed(all.first(cut)).ok()) (void)stream.feed(all.subspan(cut));
    (void)stream.finish();
    for (size_t s = 0; s < stream.structure_count(); ++s) {
        body::pm::ProgressiveMesh& m = stream.structure(s);
        if (!m.base_ready()) continue;
        m.refine_to(m.available_level());
        m.coarsen_to(0);
        m.set_level(m.level_for_triangles(m.max_triangle_count() / 2));
        m.set_level(m.level_for_error(0.0f));
    }
    return 0;
}
