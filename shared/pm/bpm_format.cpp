// Byte-level helpers of the .bpm format (see shared/pm/FORMAT.md).
#include "shared/pm/bpm_format.h"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>

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

float dequantize16(uint16_t q, float lo, float hi) { return dequantize16(q, lo, quantization_step(lo, hi)); }

float float_at_or_below(double x) {
    const float f = float(x);
    return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

float float_at_or_above(double x) {
    const float f = float(x);
    return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

void oct_encode8(double x, double y, double z, uint8_t out[2]) {
    const double l1 = std::fabs(x) + std::fabs(y) + std::fabs(z);
    if (!(l1 > 0.0)) {
        out[0] = out[1] = 128;
        return;
    }
    x /= l1;
    y /= l1;
    z /= l1;
    if (z < 0.0) {
        const double ox = (1.0 - std::fabs(y)) * (x < 0.0 ? -1.0 : 1.0);
        const double oy = (1.0 - std::fabs(x)) * (y < 0.0 ? -1.0 : 1.0);
        x = ox;
        y = oy;
    }
    const auto unorm8 = [](double v) {
        return uint8_t(std::clamp(std::nearbyint((v * 0.5 + 0.5) * 255.0), 0.0, 255.0));
    };
    out[0] = unorm8(x);
    out[1] = unorm8(y);
}

void oct_decode8(const uint8_t in[2], float out[3]) {
    // Single precision, branch-free (the decoder runs this once per vertex).
    float x = float(in[0]) * (2.0f / 255.0f) - 1.0f, y = float(in[1]) * (2.0f / 255.0f) - 1.0f;
    const float z = 1.0f - std::fabs(x) - std::fabs(y);
    const float t = std::max(-z, 0.0f);  // folding the lower hemisphere back
    x += x >= 0.0f ? -t : t;
    y += y >= 0.0f ? -t : t;
    const float l = 1.0f / std::sqrt(x * x + y * y + z * z);
    out[0] = x * l;
    out[1] = y * l;
    out[2] = z * l;
}

void normal_axis_weights(const float lo[3], const float hi[3], int32_t out[3]) {
    double e[3], w[3];
    for (int k = 0; k < 3; ++k) e[k] = std::max(double(hi[k]) - double(lo[k]), 0.0);
    for (int k = 0; k < 3; ++k) w[k] = e[(k + 1) % 3] * e[(k + 2) % 3];
    const double top = std::max({w[0], w[1], w[2]});
    for (int k = 0; k < 3; ++k) {
        const double r = top > 0.0 ? std::nearbyint(w[k] / top * 256.0) : 1.0;
        out[k] = std::max(1, int32_t(r));
    }
}

void plane_axis_weights(const float lo[3], const float hi[3], int32_t out[3]) {
    double e[3];
    for (int k = 0; k < 3; ++k) e[k] = std::max(double(hi[k]) - double(lo[k]), 0.0);
    const double top = std::max({e[0], e[1], e[2]});
    for (int k = 0; k < 3; ++k) {
        const double r = top > 0.0 ? std::nearbyint(e[k] / top * 256.0) : 1.0;
        out[k] = std::max(1, int32_t(r));
    }
}

void predict_fan(const uint16_t* q, const uint32_t* ring, uint32_t k, uint32_t start, uint32_t length,
                 const uint16_t v[3], const int64_t* plane, FanPrediction& out) {
    // Absolute coordinates in the loops (v subtracted from the results): few running
    // values per loop, so none of them spills.
    uint32_t p[64][3];
    uint32_t lo[3] = {65535, 65535, 65535}, hi[3] = {0, 0, 0}, all[3] = {0, 0, 0};
    for (uint32_t t = 0; t < k; ++t) {
        const uint16_t* r = q + size_t(ring[t]) * 3;
        const uint32_t x = r[0], y = r[1], z = r[2];
        p[t][0] = x;
        p[t][1] = y;
        p[t][2] = z;
        lo[0] = std::min(lo[0], x);
        lo[1] = std::min(lo[1], y);
        lo[2] = std::min(lo[2], z);
        hi[0] = std::max(hi[0], x);
        hi[1] = std::max(hi[1], y);
        hi[2] = std::max(hi[2], z);
        all[0] += x;
        all[1] += y;
        all[2] += z;
    }
    // The child's ring ring[start .. start + length]: its sum, and the Newell sum of
    // its edges (predict_normal closes them into the child's loop; a closed loop's
    // sum does not depend on the origin, the open chain's is taken about v).
    const uint32_t end = start + length < k ? start + length : start + length - k;
    const int32_t v0 = v[0], v1 = v[1], v2 = v[2];
    int32_t px = int32_t(p[start][0]) - v0, py = int32_t(p[start][1]) - v1, pz = int32_t(p[start][2]) - v2;
    int32_t child[3] = {px, py, pz};  // relative to v
    int64_t area[3] = {0, 0, 0};
    for (uint32_t t = 0, i = start + 1 == k ? 0 : start + 1; t < length; ++t, i = i + 1 == k ? 0 : i + 1) {
        const int32_t x = int32_t(p[i][0]) - v0, y = int32_t(p[i][1]) - v1, z = int32_t(p[i][2]) - v2;
        child[0] += x;
        child[1] += y;
        child[2] += z;
        area[0] += int64_t(py - y) * (pz + z);
        area[1] += int64_t(pz - z) * (px + x);
        area[2] += int64_t(px - x) * (py + y);
        px = x;
        py = y;
        pz = z;
    }
    const uint32_t nc = length + 1, np = k - length + 1;
    int32_t child_centroid[3], parent_centroid[3];  // relative to v
    for (int a = 0; a < 3; ++a) {
        out.child_area[a] = area[a];
        out.left[a] = int32_t(p[start][a]) - int32_t(v[a]);
        out.right[a] = int32_t(p[end][a]) - int32_t(v[a]);
        const int width = std::bit_width(hi[a] - lo[a]);
        out.shift[a] = width > 4 ? uint32_t(width - 4) : 0;
        // Sums of absolute coordinates, as the centroid's definition has them.
        const uint32_t cs = uint32_t(child[a] + int32_t(nc) * v[a]);
        const uint32_t ps = all[a] - cs + p[start][a] + p[end][a];
        const uint32_t cc = divide_small(cs + nc / 2, nc), pc = divide_small(ps + np / 2, np);
        child_centroid[a] = int32_t(cc) - v[a];
        parent_centroid[a] = int32_t(pc) - v[a];
        out.child[a] = midpoint16(v[a], cc);
        out.parent_centroid[a] = uint16_t(pc);
    }
    const int64_t n0 = plane ? plane[0] : 0, n1 = plane ? plane[1] : 0, n2 = plane ? plane[2] : 0;
    const int64_t m0 = n0 < 0 ? -n0 : n0, m1 = n1 < 0 ? -n1 : n1, m2 = n2 < 0 ? -n2 : n2;
    const int64_t top = std::max({m0, m1, m2});
    if (top == 0) {
        out.axis = 3;
        out.axis_shift = 0;
        out.child_dot = out.parent_dot = 0;
        return;
    }
    // The ring's largest distance from the plane: max |n . (p - v)| = max(hmax - nv, nv - hmin).
    int64_t hmin = INT64_MAX, hmax = INT64_MIN;
    for (uint32_t t = 0; t < k; ++t) {
        const int64_t h = n0 * p[t][0] + n1 * p[t][1] + n2 * p[t][2];
        hmin = std::min(hmin, h);
        hmax = std::max(hmax, h);
    }
    const int64_t nv = n0 * v0 + n1 * v1 + n2 * v2;
    const int64_t far = std::max({hmax - nv, nv - hmin, int64_t(0)});
    out.normal[0] = n0;
    out.normal[1] = n1;
    out.normal[2] = n2;
    out.axis = m0 >= m1 && m0 >= m2 ? 0 : m1 >= m2 ? 1 : 2;
    const int width = int(std::bit_width(uint64_t(far))) - int(std::bit_width(uint64_t(top))) - 3;
    out.axis_shift = width > 0 ? uint32_t(width) : 0;
    out.child_dot = n0 * child_centroid[0] + n1 * child_centroid[1] + n2 * child_centroid[2];
    out.parent_dot = n0 * parent_centroid[0] + n1 * parent_centroid[1] + n2 * parent_centroid[2];
}

// ---- split stream coding

namespace {
// Frequencies summing to 2^kRansBits, each used symbol at least 1 (integer
// arithmetic only: the same tables on every platform).
void normalize(const uint32_t* counts, uint32_t m, uint64_t total, uint32_t* freq) {
    uint32_t sum = 0;
    for (uint32_t s = 0; s < m; ++s) {
        freq[s] = counts[s] == 0 ? 0 : uint32_t(std::max<uint64_t>(1, uint64_t(counts[s]) * (1u << kRansBits) / total));
        sum += freq[s];
    }
    while (sum != (1u << kRansBits)) {
        uint32_t best = 0;
        for (uint32_t s = 1; s < m; ++s)
            if (freq[s] > freq[best]) best = s;
        if (sum < (1u << kRansBits)) {
            freq[best] += (1u << kRansBits) - sum;
            sum = 1u << kRansBits;
        } else {
            const uint32_t take = std::min(sum - (1u << kRansBits), freq[best] - 1);
            freq[best] -= take;
            sum -= take;
            if (take == 0) break;  // cannot happen: m <= kSymbolCount symbols of at least 1
        }
    }
}
}  // namespace

void SplitEncoder::finish(std::vector<uint8_t>& out) const {
    uint32_t counts[kSplitContexts][kSymbolCount] = {};
    uint64_t totals[kSplitContexts] = {};
    for (const Item& it : values_) {
        if (it.context >= kRawContext) continue;
        uint32_t raw, bits;
        ++counts[it.context][value_symbol(it.value, raw, bits)];
        ++totals[it.context];
    }
    uint32_t freq[kSplitContexts][kSymbolCount] = {}, start[kSplitContexts][kSymbolCount] = {};
    for (uint32_t c = 0; c < kSplitContexts; ++c) {
        uint32_t m = kSymbolCount;
        while (m > 0 && counts[c][m - 1] == 0) --m;
        out.push_back(uint8_t(m));
        if (m == 0) continue;
        normalize(counts[c], m, totals[c], freq[c]);
        for (uint32_t s = 0, cum = 0; s < m; ++s) {
            start[c][s] = cum;
            cum += freq[c][s];
            put_varint(out, freq[c][s]);
        }
    }
    // rANS runs backwards: encode the last value first, reverse the bytes at the end.
    // Symbol i (raw items not counted) uses state i mod 2.
    std::vector<uint8_t> rans;
    uint32_t state[2] = {kRansLow, kRansLow};
    size_t symbols = 0;
    for (const Item& it : values_) symbols += it.context < kRawContext;
    for (size_t i = values_.size(); i-- > 0;) {
        if (values_[i].context >= kRawContext) continue;
        uint32_t raw, bits;
        const uint32_t c = values_[i].context, s = value_symbol(values_[i].value, raw, bits);
        const uint32_t f = freq[c][s];
        uint32_t& x = state[--symbols & 1];
        const uint64_t x_max = (uint64_t(kRansLow >> kRansBits) << 16) * f;
        if (x >= x_max) {  // once at most: x < 2^32
            rans.push_back(uint8_t(x >> 8));
            rans.push_back(uint8_t(x));
            x >>= 16;
        }
        x = ((x / f) << kRansBits) + (x % f) + start[c][s];
    }
    for (int lane = 1; lane >= 0; --lane)
        for (int k = 3; k >= 0; --k) rans.push_back(uint8_t(state[lane] >> (8 * k)));
    std::reverse(rans.begin(), rans.end());
    put_u32(out, uint32_t(rans.size()));
    out.insert(out.end(), rans.begin(), rans.end());
    // Raw bits in decoding order, least significant first.
    std::vector<uint8_t> raw_bytes;
    uint64_t buffer = 0;
    uint32_t count = 0;
    for (const Item& it : values_) {
        uint32_t raw = it.value, bits = it.context - kRawContext;
        if (it.context < kRawContext) value_symbol(it.value, raw, bits);
        buffer |= uint64_t(raw) << count;
        count += bits;
        while (count >= 8) {
            raw_bytes.push_back(uint8_t(buffer));
            buffer >>= 8;
            count -= 8;
        }
    }
    if (count > 0) raw_bytes.push_back(uint8_t(buffer));
    put_u32(out, uint32_t(raw_bytes.size()));
    out.insert(out.end(), raw_bytes.begin(), raw_bytes.end());
}

bool SplitDecoder::init(std::span<const uint8_t> bytes) {
    ByteReader r(bytes);
    slot_symbol_.assign(size_t(kSplitContexts) << kRansBits, 0);
    for (uint32_t c = 0; c < kSplitContexts; ++c) {
        uint8_t* lut = slot_symbol_.data() + (size_t(c) << kRansBits);
        std::span<const uint8_t> m_byte;
        if (!r.bytes(1, m_byte) || m_byte[0] > kSymbolCount) return false;
        const uint32_t m = m_byte[0];
        if (m == 0) {  // unused: decodes as symbol 0 without consuming anything (a valid file never asks)
            symbol_info_[c][0] = 1u << kRansBits;
            continue;
        }
        uint32_t cum = 0;
        for (uint32_t s = 0; s < m; ++s) {
            uint64_t f = 0;
            if (!r.varint(f) || f > (1u << kRansBits) - cum) return false;
            std::fill_n(lut + cum, f, uint8_t(s));
            symbol_info_[c][s] = uint32_t(f) | cum << 16;
            cum += uint32_t(f);
        }
        if (cum != (1u << kRansBits)) return false;
    }
    uint32_t rbytes = 0, bbytes = 0;
    std::span<const uint8_t> rans, raw;
    if (!r.u32(rbytes) || rbytes < 8 || !r.bytes(rbytes, rans) || !r.u32(bbytes) || !r.bytes(bbytes, raw) ||
        r.left() != 0)
        return false;
    data_.assign(size_t(rbytes) + kSlack + bbytes + kSlack, 0);
    std::copy(rans.begin(), rans.end(), data_.begin());
    std::copy(raw.begin(), raw.end(), data_.begin() + rbytes + kSlack);
    rans_end_ = rbytes;
    raw_begin_ = size_t(rbytes) + kSlack;
    bit_end_ = size_t(bbytes) * 8;
    return true;
}

SplitDecoder::Cursor SplitDecoder::begin() const {
    return Cursor{slot_symbol_.data(),
                  symbol_info_,
                  data_.data(),
                  8,
                  rans_end_,
                  raw_begin_,
                  0,
                  bit_end_,
                  get_u32(data_.data()),
                  get_u32(data_.data() + 4)};
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

size_t SplitReplay::ordered_fan(const uint32_t* corners, size_t count, uint32_t* ring, uint8_t* at) const {
    if (count < 3 || count > 64) return 0;
    // Faces by the vertex after v in them: a direct-mapped table on its low bits
    // (when two share a slot, a scan instead).
    constexpr uint32_t kSlots = 256;
    uint8_t slot_face[kSlots];
    uint32_t after[64], before[64];  // the vertices after and before v in each face
    for (size_t i = 0; i < count; ++i) {
        const uint32_t c = corners[i], f = c / 3 * 3, k = c - f;
        after[i] = indices_[f + (k == 2 ? 0 : k + 1)];
        before[i] = indices_[f + (k == 0 ? 2 : k - 1)];
        slot_face[after[i] % kSlots] = 0xff;
        slot_face[before[i] % kSlots] = 0xff;
    }
    bool hashed = true;
    for (size_t i = 0; i < count; ++i) {
        uint8_t& s = slot_face[after[i] % kSlots];
        hashed = hashed && s == 0xff;
        s = uint8_t(i);
    }
    // Walk from face 0 to the face that starts where this one ends. Returning to
    // face 0 first after exactly `count` steps means every face was visited once.
    uint32_t i = 0;
    for (size_t t = 0; t < count; ++t) {
        at[t] = uint8_t(i);
        ring[t] = after[i];
        uint32_t next = slot_face[before[i] % kSlots];
        if (!hashed) {
            next = 0;
            while (next < count && after[next] != before[i]) ++next;
        }
        if (next >= count || after[next] != before[i]) return 0;
        if (next == 0) return t + 1 == count ? count : 0;
        i = next;
    }
    return 0;
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

void SplitReplay::prefetch(uint32_t v, int stage, const uint16_t* qpos) const {
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
        // The vertex after v in each face: every neighbour once around an interior vertex.
        const uint32_t k = c[i] - c[i] / 3 * 3, n = t[k == 2 ? 0 : k + 1];
        __builtin_prefetch(&regions_[n]);
        if (qpos) __builtin_prefetch(qpos + size_t(n) * 3);
    }
#else
    (void)v;
    (void)stage;
    (void)qpos;
#endif
}

}  // namespace body::pm
