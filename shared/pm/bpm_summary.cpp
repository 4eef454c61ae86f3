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
            InfoRecord info;
            if (const char* reason = read_info({section.data() + kSectionHeaderSize, length}, info))
                return input_error(where + ": " + reason);
            StructureSummary summary;
            summary.box_min = Vec3f(info.box_min[0], info.box_min[1], info.box_min[2]);
            summary.box_max = Vec3f(info.box_max[0], info.box_max[1], info.box_max[2]);
            summary.base_triangles = info.base_faces;
            summary.full_triangles = info.faces;
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
