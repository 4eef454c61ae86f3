// Byte-level helpers of the .bpm format (see shared/pm/FORMAT.md).
#include "shared/pm/bpm_format.h"

#include <algorithm>
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
std::array<uint32_t, 256> make_crc_table() {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
        uint32_t c = i;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
        t[i] = c;
    }
    return t;
}
}  // namespace

uint32_t crc32(std::span<const uint8_t> bytes, uint32_t crc) {
    static const std::array<uint32_t, 256> table = make_crc_table();
    crc = ~crc;
    for (uint8_t b : bytes) crc = table[(crc ^ b) & 0xff] ^ (crc >> 8);
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

float dequantize16(uint16_t q, float lo, float hi) {
    return float(double(lo) + double(q) * ((double(hi) - double(lo)) / 65535.0));
}

namespace {
double sign_not_zero(double v) { return v < 0.0 ? -1.0 : 1.0; }
}  // namespace

void oct_decode8(const uint8_t in[2], float out[3]) {
    double x = in[0] / 255.0 * 2.0 - 1.0, y = in[1] / 255.0 * 2.0 - 1.0;
    double z = 1.0 - std::fabs(x) - std::fabs(y);
    if (z < 0.0) {
        double ox = (1.0 - std::fabs(y)) * sign_not_zero(x);
        double oy = (1.0 - std::fabs(x)) * sign_not_zero(y);
        x = ox;
        y = oy;
    }
    double l = std::sqrt(x * x + y * y + z * z);
    out[0] = float(x / l);
    out[1] = float(y / l);
    out[2] = float(z / l);
}

void SplitReplay::reset(size_t vertex_capacity, size_t face_capacity) {
    head_.assign(vertex_capacity, kNone);
    // Corners are written by add_faces before anything reads them.
    next_.clear();
    next_.resize(face_capacity * 3);
    indices_.clear();
    indices_.resize(face_capacity * 3);
}

void SplitReplay::add_faces(size_t first_face, std::span<const uint32_t> indices) {
    for (size_t i = 0; i < indices.size(); ++i) {
        uint32_t c = uint32_t(first_face * 3 + i), v = indices[i];
        indices_[c] = v;
        next_[c] = head_[v];
        head_[v] = c;
    }
}

void SplitReplay::corners_of(uint32_t v, std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t c = head_[v]; c != kNone; c = next_[c]) out.push_back(c);
    std::sort(out.begin(), out.end());
}

void SplitReplay::ring_of(uint32_t v, std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t c = head_[v]; c != kNone; c = next_[c]) {
        const uint32_t f = c / 3 * 3;
        for (uint32_t k = 0; k < 3; ++k)
            if (f + k != c) out.push_back(indices_[f + k]);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

bool SplitReplay::apply_mask(uint32_t parent, uint32_t child, uint64_t mask, std::vector<uint32_t>& scratch,
                             std::vector<uint32_t>& moved) {
    corners_of(parent, scratch);
    moved.clear();
    if (scratch.size() < 64 && (mask >> scratch.size()) != 0) return false;
    head_[parent] = kNone;
    for (size_t i = scratch.size(); i-- > 0;) {
        uint32_t c = scratch[i];
        uint32_t& list = (i < 64 && (mask >> i) & 1) ? head_[child] : head_[parent];
        if (i < 64 && (mask >> i) & 1) {
            indices_[c] = child;
            moved.push_back(c);
        }
        next_[c] = list;
        list = c;
    }
    std::reverse(moved.begin(), moved.end());
    return true;
}

}  // namespace body::pm
