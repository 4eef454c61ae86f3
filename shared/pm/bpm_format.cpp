// Byte-level helpers of the .bpm format (see shared/pm/FORMAT.md).
#include "shared/pm/bpm_format.h"

#include <algorithm>
#include <array>
#include <bit>
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

namespace {
constexpr uint32_t kMinRegion = 8;  // corners: a typical vertex (valence 6) fits with room to grow
}  // namespace

void SplitReplay::reset(size_t vertex_capacity, size_t face_capacity) {
    regions_.assign(vertex_capacity, Region{});
    pool_.clear();
    // Every corner once plus the slack of each region; address space only until used.
    pool_.reserve(face_capacity * 3 + vertex_capacity * (kMinRegion + 2));
    indices_.clear();
    indices_.resize(face_capacity * 3);  // written by add_faces before anything reads them
}

uint32_t* SplitReplay::make_room(uint32_t v, size_t count) {
    Region& r = regions_[v];
    if (count > r.capacity) {
        const size_t capacity = std::max<size_t>({kMinRegion, 2 * size_t(r.capacity), count});
        const size_t offset = pool_.size();
        pool_.resize(offset + capacity);
        std::copy_n(pool_.begin() + r.offset, r.count, pool_.begin() + ptrdiff_t(offset));
        r.offset = uint32_t(offset);
        r.capacity = uint32_t(capacity);
    }
    return pool_.data() + r.offset;
}

void SplitReplay::add_faces(size_t first_face, std::span<const uint32_t> indices) {
    for (size_t i = 0; i < indices.size(); ++i) {
        const uint32_t c = uint32_t(first_face * 3 + i), v = indices[i];
        indices_[c] = v;
        const uint32_t n = regions_[v].count;
        make_room(v, n + 1)[n] = c;  // the highest corner so far: stays ascending
        regions_[v].count = n + 1;
    }
}

size_t SplitReplay::corners_of(uint32_t v, uint32_t* out, size_t capacity) const {
    const Region r = regions_[v];
    if (r.count > capacity) return SIZE_MAX;
    std::copy_n(pool_.data() + r.offset, r.count, out);
    return r.count;
}

void SplitReplay::corners_of(uint32_t v, std::vector<uint32_t>& out) const {
    const Region r = regions_[v];
    out.assign(pool_.data() + r.offset, pool_.data() + r.offset + r.count);
}

size_t SplitReplay::ring_of(const uint32_t* corners, size_t count, uint32_t* out) const {
    // Insertion into a sorted run: a ring has a handful of entries.
    size_t n = 0;
    for (size_t i = 0; i < count; ++i) {
        const uint32_t c = corners[i], f = c / 3 * 3;
        for (uint32_t k = 0; k < 3; ++k) {
            if (f + k == c) continue;
            const uint32_t x = indices_[f + k];
            size_t at = n;
            while (at > 0 && out[at - 1] > x) --at;
            if (at > 0 && out[at - 1] == x) continue;
            for (size_t m = n; m > at; --m) out[m] = out[m - 1];
            out[at] = x;
            ++n;
        }
    }
    return n;
}

void SplitReplay::ring_of(uint32_t v, std::vector<uint32_t>& out) const {
    std::vector<uint32_t> corners;
    corners_of(v, corners);
    out.resize(2 * corners.size());
    out.resize(ring_of(corners.data(), corners.size(), out.data()));
}

bool SplitReplay::apply_mask(uint32_t parent, uint32_t child, uint64_t mask, const uint32_t* corners, size_t count,
                             uint32_t* moved) {
    if (count < 64 && (mask >> count) != 0) return false;
    const size_t moving = size_t(std::popcount(mask));
    uint32_t* to = make_room(child, regions_[child].count + moving + 2);  // + the split's new faces
    uint32_t* from = pool_.data() + regions_[parent].offset;              // after make_room: the pool may have moved
    uint32_t kept = 0, m = regions_[child].count;
    for (size_t i = 0; i < count; ++i) {
        const uint32_t c = corners[i];
        if (i < 64 && (mask >> i) & 1) {
            indices_[c] = child;
            to[m++] = c;
        } else {
            from[kept++] = c;
        }
    }
    std::copy_n(to + regions_[child].count, moving, moved);
    regions_[child].count = m;
    regions_[parent].count = kept;
    return true;
}

bool SplitReplay::apply_mask(uint32_t parent, uint32_t child, uint64_t mask, std::vector<uint32_t>& scratch,
                             std::vector<uint32_t>& moved) {
    corners_of(parent, scratch);
    moved.resize(scratch.size());
    if (!apply_mask(parent, child, mask, scratch.data(), scratch.size(), moved.data())) {
        moved.clear();
        return false;
    }
    moved.resize(size_t(std::popcount(mask)));
    return true;
}

void SplitReplay::prefetch(uint32_t v, int stage) const {
#if defined(__GNUC__)
    if (stage == 0) {
        __builtin_prefetch(&regions_[v]);
        return;
    }
    const Region r = regions_[v];
    if (stage == 1) {
        __builtin_prefetch(pool_.data() + r.offset);
        if (r.count > 12) __builtin_prefetch(pool_.data() + r.offset + 16);
        return;
    }
    const uint32_t* c = pool_.data() + r.offset;
    if (stage == 2) {
        for (uint32_t i = 0; i < r.count && i < 16; ++i) __builtin_prefetch(&indices_[c[i] / 3 * 3]);
        return;
    }
    // Stage 3: the neighbours' regions (a new face adds a corner to one of them).
    for (uint32_t i = 0; i < r.count && i < 16; ++i) {
        const uint32_t* t = &indices_[c[i] / 3 * 3];
        for (int k = 0; k < 3; ++k) __builtin_prefetch(&regions_[t[k]]);
    }
#else
    (void)v;
    (void)stage;
#endif
}

}  // namespace body::pm
