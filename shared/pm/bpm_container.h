#pragma once
// The `.bpm` container: file header, sections (tag, structure, length, payload,
// CRC-32), the little-endian byte helpers both sides frame them with, and the
// packed vertex of the BASE section. Byte layout: shared/pm/FORMAT.md.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace body::pm {

inline constexpr char kMagic[4] = {'B', 'P', 'M', '\0'};
inline constexpr uint16_t kVersion =
    7;  // 7: the parent predicted from its ring and the plane (6: intermediate positions on coarser grids)
inline constexpr size_t kFileHeaderSize = 16;       // magic, version, flags, structure count, header crc
inline constexpr size_t kSectionHeaderSize = 12;    // tag, structure, reserved, payload length
inline constexpr size_t kSectionTrailerSize = 4;    // crc32 over header + payload
inline constexpr uint32_t kMaxPatchFan = 60;        // a split's parent has at most this many faces
inline constexpr uint32_t kMaxVertices = 1u << 22;  // per structure (bounds what a corrupt INFO can allocate)
inline constexpr uint32_t kMaxFaces = 1u << 23;     // per structure

// Section tags, four ASCII bytes read as a little-endian uint32.
constexpr uint32_t make_tag(const char (&s)[5]) {
    return uint32_t(uint8_t(s[0])) | uint32_t(uint8_t(s[1])) << 8 | uint32_t(uint8_t(s[2])) << 16 |
           uint32_t(uint8_t(s[3])) << 24;
}
inline constexpr uint32_t kTagInfo = make_tag("INFO");
inline constexpr uint32_t kTagBase = make_tag("BASE");
inline constexpr uint32_t kTagSplits = make_tag("SPLT");
inline constexpr uint32_t kTagEnd = make_tag("END.");
std::string tag_name(uint32_t tag);  // printable, e.g. "SPLT"

// CRC-32 (IEEE 802.3, the zlib one), `crc` is the running value (start at 0).
uint32_t crc32(std::span<const uint8_t> bytes, uint32_t crc = 0);

// Little-endian appends and reads; readers check bounds through ByteReader.
void put_u16(std::vector<uint8_t>& out, uint16_t v);
void put_u32(std::vector<uint8_t>& out, uint32_t v);
void put_f32(std::vector<uint8_t>& out, float v);
void put_varint(std::vector<uint8_t>& out, uint64_t v);  // LEB128
uint16_t get_u16(const uint8_t* p);
uint32_t get_u32(const uint8_t* p);

class ByteReader {
public:
    explicit ByteReader(std::span<const uint8_t> bytes) : bytes_(bytes) {}
    bool u16(uint16_t& v);
    bool u32(uint32_t& v);
    bool f32(float& v);
    bool varint(uint64_t& v);
    bool bytes(size_t n, std::span<const uint8_t>& out);
    size_t offset() const { return pos_; }
    size_t left() const { return bytes_.size() - pos_; }

private:
    std::span<const uint8_t> bytes_;
    size_t pos_ = 0;
};

// One structure's INFO payload (FORMAT.md), read and checked by the one rule
// both the decoder (bpm_reader.cpp) and the header-only summary
// (bpm_summary.cpp) apply.
struct InfoRecord {
    std::span<const uint8_t> name;
    float color[3];
    float box_min[3], box_max[3];  // quantization box
    uint32_t flags, base_vertices, base_faces, splits, faces, chunk_splits;
};
// nullptr when `payload` is a valid INFO, else the reason (without the place).
const char* read_info(std::span<const uint8_t> payload, InfoRecord& out);

// Packed vertex of the base chunk (meshopt vertex codec, stride 8).
struct BaseVertex {
    uint16_t q[3];
    uint8_t oct[2];
};
static_assert(sizeof(BaseVertex) == 8);

}  // namespace body::pm
