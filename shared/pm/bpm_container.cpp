// See bpm_container.h (framing: shared/pm/FORMAT.md).
#include "shared/pm/bpm_container.h"

#include <array>
#include <cmath>
#include <cstring>

namespace body::pm {

std::string tag_name(uint32_t tag) {
    std::string s;
    for (int i = 0; i < 4; ++i) {
        char c = char((tag >> (8 * i)) & 0xff);
        s += (c >= 32 && c < 127) ? c : '?';
    }
    return s;
}

namespace {
// Slicing-by-8 tables: table[k][b] is the CRC of byte b followed by k zero bytes.
std::array<std::array<uint32_t, 256>, 8> make_crc_tables() {
    std::array<std::array<uint32_t, 256>, 8> t{};
    for (uint32_t i = 0; i < 256; ++i) {
        uint32_t c = i;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
        t[0][i] = c;
    }
    for (uint32_t i = 0; i < 256; ++i)
        for (size_t k = 1; k < 8; ++k) t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xff];
    return t;
}
}  // namespace

uint32_t crc32(std::span<const uint8_t> bytes, uint32_t crc) {
    static const std::array<std::array<uint32_t, 256>, 8> t = make_crc_tables();
    crc = ~crc;
    const uint8_t* p = bytes.data();
    size_t n = bytes.size();
    // Eight bytes per step (the reader checks every section it receives).
    for (; n >= 8; n -= 8, p += 8) {
        const uint32_t lo = crc ^ get_u32(p), hi = get_u32(p + 4);
        crc = t[7][lo & 0xff] ^ t[6][(lo >> 8) & 0xff] ^ t[5][(lo >> 16) & 0xff] ^ t[4][lo >> 24] ^ t[3][hi & 0xff] ^
              t[2][(hi >> 8) & 0xff] ^ t[1][(hi >> 16) & 0xff] ^ t[0][hi >> 24];
    }
    for (; n > 0; --n, ++p) crc = t[0][(crc ^ *p) & 0xff] ^ (crc >> 8);
    return ~crc;
}

void put_u16(std::vector<uint8_t>& out, uint16_t v) {
    out.push_back(uint8_t(v));
    out.push_back(uint8_t(v >> 8));
}
void put_u32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}
void put_f32(std::vector<uint8_t>& out, float v) {
    uint32_t u;
    std::memcpy(&u, &v, 4);
    put_u32(out, u);
}
void put_varint(std::vector<uint8_t>& out, uint64_t v) {
    while (v >= 0x80) {
        out.push_back(uint8_t(v | 0x80));
        v >>= 7;
    }
    out.push_back(uint8_t(v));
}
uint16_t get_u16(const uint8_t* p) { return uint16_t(p[0] | p[1] << 8); }
uint32_t get_u32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

bool ByteReader::u16(uint16_t& v) {
    if (left() < 2) return false;
    v = get_u16(bytes_.data() + pos_);
    pos_ += 2;
    return true;
}
bool ByteReader::u32(uint32_t& v) {
    if (left() < 4) return false;
    v = get_u32(bytes_.data() + pos_);
    pos_ += 4;
    return true;
}
bool ByteReader::f32(float& v) {
    uint32_t u;
    if (!u32(u)) return false;
    std::memcpy(&v, &u, 4);
    return true;
}
bool ByteReader::varint(uint64_t& v) {
    v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
        if (left() < 1) return false;
        uint8_t b = bytes_[pos_++];
        v |= uint64_t(b & 0x7f) << shift;
        if (!(b & 0x80)) return true;
    }
    return false;
}
bool ByteReader::bytes(size_t n, std::span<const uint8_t>& out) {
    if (left() < n) return false;
    out = bytes_.subspan(pos_, n);
    pos_ += n;
    return true;
}

const char* read_info(std::span<const uint8_t> payload, InfoRecord& out) {
    ByteReader r(payload);
    uint16_t name_length = 0;
    float f[9];
    bool ok = r.u16(name_length) && r.bytes(name_length, out.name);
    for (float& x : f) ok = ok && r.f32(x);
    ok = ok && r.u32(out.flags) && r.u32(out.base_vertices) && r.u32(out.base_faces) && r.u32(out.splits) &&
         r.u32(out.faces) && r.u32(out.chunk_splits);
    if (!ok) return "INFO payload too short";
    for (float x : f)
        if (!std::isfinite(x)) return "non-finite colour or bounds";
    for (int k = 0; k < 3; ++k)
        if (!(f[k] >= 0.0f && f[k] <= 1.0f)) return "colour component outside 0..1";
    if (out.flags & ~1u) return "unknown INFO flags";
    const uint32_t bv = out.base_vertices, bf = out.base_faces, faces = out.faces;
    if (bv == 0 || bf == 0 || faces < bf || uint64_t(bv) + out.splits > kMaxVertices || faces > kMaxFaces ||
        out.chunk_splits == 0 || uint64_t(faces - bf) > 3ull * out.splits)
        return "inconsistent counts";
    for (int k = 0; k < 3; ++k) {
        out.color[k] = f[k];
        out.box_min[k] = f[3 + k];
        out.box_max[k] = f[6 + k];
    }
    return nullptr;
}

}  // namespace body::pm
