// A .bpm's INFO sections without decoding (contract in bpm_summary.h).
#include "shared/pm/bpm_summary.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "shared/pm/bpm_container.h"

namespace body::pm {
namespace {

std::string at(const std::string& path, size_t offset) { return path + ": byte " + std::to_string(offset); }

// One INFO payload's box and counts (the checks of BpmStream::parse_info).
Status parse_summary(std::span<const uint8_t> payload, const std::string& where, StructureSummary& out) {
    ByteReader r(payload);
    uint16_t name_length = 0;
    std::span<const uint8_t> name;
    float f[9];
    uint32_t flags, bv, bf, splits, faces, chunk;
    bool ok = r.u16(name_length) && r.bytes(name_length, name);
    for (float& x : f) ok = ok && r.f32(x);
    ok = ok && r.u32(flags) && r.u32(bv) && r.u32(bf) && r.u32(splits) && r.u32(faces) && r.u32(chunk);
    if (!ok) return input_error(where + ": INFO payload too short");
    for (float x : f)
        if (!std::isfinite(x)) return input_error(where + ": non-finite colour or bounds");
    if (uint64_t(bv) + splits > kMaxVertices || bv == 0 || bf == 0 || faces < bf || faces > kMaxFaces)
        return input_error(where + ": inconsistent counts");
    out.box_min = Vec3f(f[3], f[4], f[5]);
    out.box_max = Vec3f(f[6], f[7], f[8]);
    out.base_triangles = bf;
    out.full_triangles = faces;
    return ok_status();
}

}  // namespace

Result<std::vector<StructureSummary>> read_bpm_summary(const std::string& path) {
    // Never open a FIFO or a device (the open itself could block the kiosk).
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return input_error(path + ": not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) return input_error(path + ": cannot open");
    uint8_t h[kFileHeaderSize];
    if (!in.read(reinterpret_cast<char*>(h), sizeof h)) return input_error(at(path, 0) + ": truncated file header");
    if (std::memcmp(h, kMagic, 4) != 0) return input_error(path + ": file header at byte 0: not a .bpm file");
    if (crc32({h, 12}) != get_u32(h + 12)) return input_error(path + ": file header at byte 0: checksum mismatch");
    if (get_u16(h + 4) != kVersion) return input_error(path + ": file header at byte 4: unsupported version");
    const uint32_t declared = get_u32(h + 8);
    if (declared == 0 || declared > 65535) return input_error(path + ": file header at byte 8: bad structure count");
    std::vector<StructureSummary> out;
    std::vector<uint8_t> section;
    size_t offset = kFileHeaderSize;
    while (out.size() < declared) {
        uint8_t s[kSectionHeaderSize];
        if (!in.read(reinterpret_cast<char*>(s), sizeof s))
            return input_error(at(path, offset) + ": truncated before every INFO section");
        const uint32_t tag = get_u32(s), structure = get_u16(s + 4), length = get_u32(s + 8);
        const std::string where = path + ": section " + tag_name(tag) + " of structure " + std::to_string(structure) +
                                  " at byte " + std::to_string(offset);
        if (length > (1u << 30)) return input_error(where + ": section length too large");
        const size_t total = kSectionHeaderSize + size_t(length) + kSectionTrailerSize;
        if (tag == kTagInfo) {
            if (structure != out.size()) return input_error(where + ": INFO out of order");
            section.assign(s, s + kSectionHeaderSize);
            section.resize(total);
            if (!in.read(reinterpret_cast<char*>(section.data() + kSectionHeaderSize),
                         std::streamsize(length + kSectionTrailerSize)))
                return input_error(where + ": truncated");
            if (crc32({section.data(), kSectionHeaderSize + length}) !=
                get_u32(section.data() + kSectionHeaderSize + length))
                return input_error(where + ": checksum mismatch");
            StructureSummary summary;
            if (auto st = parse_summary({section.data() + kSectionHeaderSize, length}, where, summary); !st)
                return st.error();
            out.push_back(summary);
        } else if (tag == kTagBase || tag == kTagSplits) {
            if (!in.seekg(std::streamoff(length + kSectionTrailerSize), std::ios::cur))
                return input_error(where + ": truncated");
        } else {
            return input_error(where + ": unexpected section before every INFO");
        }
        offset += total;
    }
    return out;
}

}  // namespace body::pm
