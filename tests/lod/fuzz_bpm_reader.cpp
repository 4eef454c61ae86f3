// libFuzzer target: the .bpm stream reader must reject or accept any bytes without
// crashing, fed whole or in two pieces, and a decoded structure must survive
// refining and coarsening over every level it has. Each input is tried as is and
// with its checksums recomputed, so that mutations reach the section decoders.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "shared/pm/bpm_container.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"

namespace {

void fix_checksums(std::vector<uint8_t>& b) {
    using namespace body::pm;
    if (b.size() < kFileHeaderSize) return;
    const uint32_t h = crc32({b.data(), 12});
    for (int i = 0; i < 4; ++i) b[12 + i] = uint8_t(h >> (8 * i));
    size_t pos = kFileHeaderSize;
    while (pos + kSectionHeaderSize <= b.size()) {
        const size_t length = get_u32(&b[pos + 8]);
        const size_t end = pos + kSectionHeaderSize + length;
        if (end + kSectionTrailerSize > b.size()) break;
        const uint32_t c = crc32({&b[pos], kSectionHeaderSize + length});
        for (int i = 0; i < 4; ++i) b[end + i] = uint8_t(c >> (8 * i));
        pos = end + kSectionTrailerSize;
    }
}

void exercise(std::span<const uint8_t> all, size_t cut) {
    body::pm::BpmStream stream("fuzz");
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
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const size_t cut = size ? data[0] % (size + 1) : 0;
    exercise({data, size}, cut);
    std::vector<uint8_t> fixed(data, data + size);
    fix_checksums(fixed);
    exercise(fixed, cut);
    return 0;
}
