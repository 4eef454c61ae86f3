#pragma once
// Building blocks of the `.bpm` progressive-mesh format shared by the writer
// (builder/lod/bpm_writer.cpp) and the reader (shared/pm/progressive_mesh.cpp).
// The byte layout is documented in shared/pm/FORMAT.md; keep both in step.
//
// Everything here is integer or correctly rounded IEEE arithmetic so that the
// writer produces the same bytes on x86-64 and aarch64.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace body::pm {

// An allocator whose value-less construct() default-initialises: resize() of a
// vector of trivial elements leaves them indeterminate instead of zeroing them,
// so capacity reserved for detail that has not arrived costs no page faults.
// Large arrays (a 1M-triangle structure's are 2-13 MB each) are asked for in
// transparent huge pages: decoding first-touches every page, and 4 KiB page
// faults cost the streaming thread more time than half its decoding.
void* allocate_large_array(size_t bytes);  // aligned to 2 MiB, huge pages advised; throws std::bad_alloc
void free_large_array(void* p);
// A cache hint, no effect on results: the split replay (reader and writer) and
// the simplifier's collapse loop are bound by memory latency, and their
// scattered lines are independent, so they are requested ahead of use.
inline void prefetch(const void* p) {
#if defined(__GNUC__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
}
// From now on a low-priority thread prefaults the large arrays allocated before
// and after the call (see shared/pm/large_array.cpp). Without it, nothing runs.
void start_background_prefault();
inline constexpr size_t kLargeArrayBytes = size_t(2) << 20;

template <class T>
struct UninitAllocator : std::allocator<T> {
    using std::allocator<T>::allocator;
    template <class U>
    struct rebind {
        using other = UninitAllocator<U>;
    };
    T* allocate(size_t n) {
        if (n * sizeof(T) >= kLargeArrayBytes) return static_cast<T*>(allocate_large_array(n * sizeof(T)));
        return std::allocator<T>::allocate(n);
    }
    void deallocate(T* p, size_t n) {
        if (n * sizeof(T) >= kLargeArrayBytes)
            free_large_array(p);
        else
            std::allocator<T>::deallocate(p, n);
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        if constexpr (sizeof...(Args) == 0)
            ::new (static_cast<void*>(p)) U;
        else
            ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};
// Elements past what was written are indeterminate: write before reading.
template <class T>
using UninitVector = std::vector<T, UninitAllocator<T>>;

inline constexpr char kMagic[4] = {'B', 'P', 'M', '\0'};
inline constexpr uint16_t kVersion = 4;             // 4: plane and normal predictions (3: entropy-coded values)
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

// Dequantization of 16-bit coordinates in [lo, hi], and 8-bit octahedral
// normals both ways (Meyer et al. 2010). The position quantizer lives with the
// writer (builder/lod/bpm_writer.cpp); everything is compiled without
// floating-point contraction so the bytes match on every platform.
float dequantize16(uint16_t q, float lo, float hi);
// The nearest float at or below / at or above x. An axis whose positions span [min, max]
// is quantized in [lo, hi] = [float_at_or_below(min), float_at_or_above(max)].
float float_at_or_below(double x);
float float_at_or_above(double x);
// The distance between adjacent codes in [lo, hi]. Two values at least this far apart
// always get different codes (rounding is monotonic).
inline double quantization_step(float lo, float hi) { return (double(hi) - double(lo)) / 65535.0; }
// The writer's quantizer: q = round((x - lo) / (hi - lo) * 65535), at most half a step from x.
inline uint16_t quantize16(double x, float lo, float hi) {
    const double range = double(hi) - double(lo);
    if (!(range > 0.0)) return 0;
    const double t = std::nearbyint((x - double(lo)) / range * 65535.0);
    return uint16_t(std::clamp(t, 0.0, 65535.0));
}
// The same with step = quantization_step(lo, hi) computed once (same result).
inline float dequantize16(uint16_t q, float lo, double step) { return float(double(lo) + double(q) * step); }
void oct_decode8(const uint8_t in[2], float out[3]);
// Any nonzero vector (normalized by its L1 norm); the zero vector gives (128, 128).
void oct_encode8(double x, double y, double z, uint8_t out[2]);

// Zig-zag mapping of the wrap-around difference of two 16/8-bit codes.
inline uint16_t zigzag16(uint16_t to, uint16_t from) {
    int16_t d = int16_t(uint16_t(to - from));
    return uint16_t((uint16_t(d) << 1) ^ uint16_t(d >> 15));
}
inline uint16_t unzigzag16(uint16_t z, uint16_t from) {
    uint16_t d = uint16_t((z >> 1) ^ uint16_t(-(z & 1)));
    return uint16_t(from + d);
}
inline uint8_t zigzag8(uint8_t to, uint8_t from) {
    int8_t d = int8_t(uint8_t(to - from));
    return uint8_t((uint8_t(d) << 1) ^ uint8_t(d >> 7));
}
inline uint8_t unzigzag8(uint8_t z, uint8_t from) {
    uint8_t d = uint8_t((z >> 1) ^ uint8_t(-(z & 1)));
    return uint8_t(from + d);
}

// ---- Split stream coding (SPLT, version 3, kept in version 4).
//
// Every value of a split is an unsigned integer coded in one of the contexts
// below: a small symbol (the value itself below 8, else its bit length and the
// bit after the leading one) entropy-coded with a static rANS table per context
// and chunk, plus the remaining low bits sent raw in a separate bit stream. So a
// value costs about its information content, and decoding is one table lookup
// plus one bit-field read.
enum SplitContext : uint32_t {
    kCtxKind,                       // split kind: topology form * 2 + parent moves
    kCtxParentDelta,                // child - parent - 1
    kCtxErrorStep,                  // (previous error bits - error bits) >> 16
    kCtxFanStart,                   // compact topology: ring position of the left wing
    kCtxFanLength,                  // compact topology: faces moving to the child
    kCtxChild0,                     // child position residual, 3 axes in coding order (zig-zag)
    kCtxParent0 = kCtxChild0 + 3,   // parent move residual, the same order (zig-zag)
    kCtxNormal0 = kCtxParent0 + 3,  // child normal residual, u v (zig-zag; files with normals)
    kSplitContexts = kCtxNormal0 + 2,
};
inline constexpr uint32_t kSymbolCount = 66;    // 8 small values + 2 per bit length 4..32
inline constexpr uint32_t kRansBits = 10;       // table precision: frequencies sum to 1024
inline constexpr uint32_t kRansLow = 1u << 16;  // rANS state normalisation interval [2^16, 2^32), 16-bit words
// Split kinds (kCtxKind >> 1): how the topology is coded.
inline constexpr uint32_t kTopoGeneral = 0;  // neighbour numbers and patch mask in the topology bytes
inline constexpr uint32_t kTopoFan = 1;      // manifold split, new faces (c, p, vl), (c, vr, p) in this order

// Symbol of `v` and its raw low bits (`bits` of them).
inline uint32_t value_symbol(uint32_t v, uint32_t& raw, uint32_t& bits) {
    if (v < 8) {
        raw = bits = 0;
        return v;
    }
    const uint32_t n = uint32_t(std::bit_width(v));  // 4 .. 32
    bits = n - 2;
    raw = v & ((1u << bits) - 1);
    return 8 + (n - 4) * 2 + ((v >> bits) & 1);
}

// Collects the values of one chunk in decoding order and writes them as
//   per context: u8 m, then m LEB128 frequencies of symbols 0 .. m-1 (sum 4096, or m = 0: unused)
//   u32 rbytes, u8 rans[rbytes]   rANS: two interleaved 32-bit states, then 16-bit words, read forward
//   u32 bbytes, u8 raw[bbytes]    raw bits, least significant first
class SplitEncoder {
public:
    void put(uint32_t context, uint32_t value) { values_.push_back({context, value}); }
    // `bits` (<= 30) low bits of `value`, raw, in the raw bit stream.
    void put_raw(uint32_t value, uint32_t bits) {
        if (bits > 0) values_.push_back({kRawContext + bits, value & ((1u << bits) - 1)});
    }
    // A residual whose magnitude scales with 2^shift: the high part entropy coded,
    // the low `shift` bits raw (about uniform).
    void put_scaled(uint32_t context, uint32_t value, uint32_t shift) {
        put(context, value >> shift);
        put_raw(value, shift);
    }
    void finish(std::vector<uint8_t>& out) const;
    // Empties the encoder for the next chunk, keeping its storage (a chunk
    // holds some hundred thousand values: regrowing them cost the bunny's
    // encoder ~14% of its time).
    void clear() { values_.clear(); }

private:
    static constexpr uint32_t kRawContext = 64;  // context kRawContext + n: n raw bits
    struct Item {
        uint32_t context, value;
    };
    std::vector<Item> values_;
};

// Reads what SplitEncoder wrote: init() checks the framing and builds the tables,
// then a Cursor (a small value the caller keeps in registers: it must not escape)
// decodes the values in order. A Cursor never reads out of bounds: past the end
// it returns garbage and ok() becomes false (the caller checks at the end of the
// chunk, and bounds-checks every decoded value it uses before that). Branch-free
// apart from the symbol size: both streams sit in one zero-padded copy, and the
// caller checks past_end() once per split.
class SplitDecoder {
public:
    // False when the tables or sizes are malformed (one allocation per chunk).
    bool init(std::span<const uint8_t> bytes);

    struct Cursor {
        const uint8_t* slot_symbol;                   // per context and slot: the symbol
        const uint32_t (*symbol_info)[kSymbolCount];  // per context and symbol: freq | cum << 16
        const uint8_t* data;                          // rANS words, kSlack zero bytes, raw bits, kSlack zero bytes
        size_t rans_pos, rans_end, raw_begin, bit_pos, bit_end;
        uint32_t state, other_state;  // the rANS states of the next symbol and of the one after

        [[gnu::always_inline]] uint32_t get(uint32_t context) {
            // Two rANS states take turns (symbol i uses state i mod 2): two independent
            // dependency chains, so consecutive symbols decode in parallel.
            uint32_t x = state;
            const uint32_t slot = x & ((1u << kRansBits) - 1);
            const uint32_t symbol = slot_symbol[(context << kRansBits) | slot];
            const uint32_t info = symbol_info[context][symbol];
            x = (info & 0xffff) * (x >> kRansBits) + slot - (info >> 16);
            // One 16-bit word brings the state back above kRansLow.
            const bool refill = x < kRansLow;
            const uint32_t word = uint32_t(data[rans_pos]) | uint32_t(data[rans_pos + 1]) << 8;
            x = refill ? (x << 16) | word : x;
            rans_pos += refill ? 2 : 0;
            state = other_state;
            other_state = x;
            if (symbol < 8) return symbol;
            const uint32_t bits = (symbol - 8) / 2 + 2;
            return ((2u | (symbol & 1)) << bits) | get_raw(bits);
        }
        // `bits` (<= 30) raw bits.
        [[gnu::always_inline]] uint32_t get_raw(uint32_t bits) {
            uint64_t window;
            std::memcpy(&window, data + raw_begin + (bit_pos >> 3), 8);
            const uint32_t v = uint32_t((window >> (bit_pos & 7)) & ((uint64_t(1) << bits) - 1));
            bit_pos += bits;
            return v;
        }
        [[gnu::always_inline]] uint32_t get_scaled(uint32_t context, uint32_t shift) {
            const uint32_t high = get(context);
            return (high << shift) | get_raw(shift);
        }
        // True once the cursor went past the end of either stream. The padding
        // after each holds what one split can read (at most 20 values: 40 bytes
        // of rANS words, 75 bytes of raw bits): check this at least once per split.
        bool past_end() const { return rans_pos > rans_end || bit_pos > bit_end; }
        // True when every byte was consumed exactly and nothing was read past the end.
        bool ok() const {
            return rans_pos == rans_end && state == kRansLow && other_state == kRansLow &&
                   (bit_pos + 7) / 8 * 8 == bit_end;
        }
    };
    static constexpr size_t kSlack = 128;  // zero bytes after each stream
    // The cursor at the first value (valid while this decoder lives).
    Cursor begin() const;

private:
    std::vector<uint8_t> slot_symbol_;
    uint32_t symbol_info_[kSplitContexts][kSymbolCount] = {};
    std::vector<uint8_t> data_;
    size_t rans_end_ = 0, raw_begin_ = 0, bit_end_ = 0;
};

// Division by a ring size n (1 .. 65) as a multiplication: x * (floor(2^24 / n) + 1) >> 24
// (x < 2^22: equal to x / n, rarely one more; this is the definition).
struct SmallReciprocals {
    uint32_t r[66];
    constexpr SmallReciprocals() : r{} {
        for (uint32_t n = 1; n < 66; ++n) r[n] = (1u << 24) / n + 1;
    }
};
inline constexpr SmallReciprocals kSmallReciprocals{};
inline uint32_t divide_small(uint32_t x, uint32_t n) { return uint32_t((uint64_t(x) * kSmallReciprocals.r[n]) >> 24); }
inline uint16_t midpoint16(uint32_t a, uint32_t b) { return uint16_t((a + b + 1) / 2); }
inline uint16_t reflect16(uint16_t about, uint16_t x) { return uint16_t(2u * about - x); }

// Predictions of a fan split's positions (quantized), from the positions at the
// level before it (`q`, 3 per vertex; `v` the parent's; ring, k, start, length as
// in SplitReplay::ordered_fan; integer arithmetic, wrap-around 16-bit results):
//   child  = midpoint(v, centroid of ring[start .. start + length])   (its future ring)
//   parent = midpoint(reflection of the child about v, parent_centroid) where
//            parent_centroid = centroid of ring[start + length .. start + k]
//            (both wings, ring[start] and ring[start + length], are in both rings)
//   shift per axis = max(0, bit_width(max - min of the ring) - 4): the low bits of
//            both residuals are about uniform below the ring's extent / 16.
// Version 4 adds a plane through v (when `plane` is given: the parent's normal in
// quantized space, plane_normal): `axis` = its component largest in magnitude (the
// lowest such), 3 when it is 0 or not given (no plane). Along `axis` the surface is
// flat to a fraction of the ring's extent, so that coordinate is coded last,
// predicted from the plane (plane_coordinate) with its own shift
//   axis_shift = max(0, bit_width(max over the ring of |plane . (ring[t] - v)|)
//                       - bit_width(|plane[axis]|) - 3)
// (about the ring's distance from the plane / 8). child_dot and parent_dot are
// plane . (centroid - v) for the two centroids above (the child's: rounded centroid).
// (A split that is not a fan: child = v, parent = reflection, shift 0, no plane.)
// centroid of n vertices = divide_small(sum + n / 2, n).
struct FanPrediction {
    uint16_t child[3];
    uint16_t parent_centroid[3];
    uint32_t shift[3];
    int64_t normal[3] = {0, 0, 0};
    uint32_t axis = 3, axis_shift = 0;
    int64_t child_dot = 0, parent_dot = 0;
    int64_t child_area[3] = {0, 0, 0};  // Newell sum of the edges of ring[start .. start + length], about v
    int32_t left[3] = {0, 0, 0}, right[3] = {0, 0, 0};  // ring[start] - v, ring[start + length] - v
};
inline int64_t floor_div(int64_t a, int64_t b) {  // b > 0
    const int64_t q = a / b;
    return q - ((a % b != 0) & (a < 0));
}
// a / b rounded to nearest (halves up), b != 0.
[[gnu::always_inline]] inline int64_t round_div(int64_t a, int64_t b) {
    if (b < 0) {
        a = -a;
        b = -b;
    }
    const int64_t num = 2 * a + b, den = 2 * b;
    // The same quotient with a 32-bit division when both fit (64-bit ones are slow on some CPUs).
    if (num >= 0 && num < (int64_t(1) << 31) && den < (int64_t(1) << 31)) return int64_t(uint32_t(num) / uint32_t(den));
    return floor_div(num, den);
}
// The plane normal of a vertex from its octahedral normal (8 bits per component):
// (u, w) = 2 oct - 255, z = 255 - |u| - |w|, folded like oct_decode8 when z < 0
// ((255 - |w|) sgn u, (255 - |u|) sgn w, sgn 0 = +1), not normalised; then per
// axis times `weight` (plane_axis_weights) into quantized space.
inline void plane_normal(const uint8_t oct[2], const int32_t weight[3], int64_t out[3]) {
    int32_t u = 2 * int32_t(oct[0]) - 255, w = 2 * int32_t(oct[1]) - 255;
    const int32_t z = 255 - std::abs(u) - std::abs(w);
    if (z < 0) {
        const int32_t fu = (255 - std::abs(w)) * (u < 0 ? -1 : 1), fw = (255 - std::abs(u)) * (w < 0 ? -1 : 1);
        u = fu;
        w = fw;
    }
    out[0] = int64_t(u) * weight[0];
    out[1] = int64_t(w) * weight[1];
    out[2] = int64_t(z) * weight[2];
}
void predict_fan(const uint16_t* q, const uint32_t* ring, uint32_t k, uint32_t start, uint32_t length,
                 const uint16_t v[3], const int64_t* plane, FanPrediction& out);
// The other two axes of pred.axis (< 3), ascending.
inline void plane_axes(uint32_t axis, uint32_t& a, uint32_t& b) {
    a = axis == 0 ? 1 : 0;
    b = axis == 2 ? 1 : 2;
}
// The coordinate along pred.axis (< 3) of the point whose other two coordinates are
// those of `t`, on the plane through v with normal pred.normal moved off it by
// `offset / scale` (offset in units of normal . (x - v)):
//   v[axis] + round_div(offset - scale * (n_a (t_a - v_a) + n_b (t_b - v_b)), scale * n[axis]).
// The child's uses offset = child_dot, scale 4 (a quarter of its centroid's
// distance); the parent's offset = parent_dot - 4 * normal . (child - v), scale 8
// (the reflection of the child's distance, halved, plus an eighth of its centroid's).
[[gnu::always_inline]] inline uint16_t plane_coordinate(const FanPrediction& pred, const uint16_t v[3],
                                                        const uint16_t t[3], int64_t offset, int64_t scale) {
    uint32_t a, b;
    plane_axes(pred.axis, a, b);
    const int64_t along =
        pred.normal[a] * (int32_t(t[a]) - int32_t(v[a])) + pred.normal[b] * (int32_t(t[b]) - int32_t(v[b]));
    return uint16_t(int64_t(v[pred.axis]) + round_div(offset - scale * along, scale * pred.normal[pred.axis]));
}
inline int64_t plane_dot(const FanPrediction& pred, const uint16_t v[3], const uint16_t t[3]) {
    return pred.normal[0] * (int32_t(t[0]) - int32_t(v[0])) + pred.normal[1] * (int32_t(t[1]) - int32_t(v[1])) +
           pred.normal[2] * (int32_t(t[2]) - int32_t(v[2]));
}

// Prediction of a fan split's child normal: the area-weighted normal of the child's
// faces after the split (the closed loop parent_after, ring[start .. start + length]
// around the child; the sum of (loop[i] - c) x (loop[i+1] - c), the same for any
// point in place of c: computed about the parent's position before the split `v`,
// by Newell's method: edge (a, b) adds ((a.y - b.y)(a.z + b.z), (a.z - b.z)(a.x + b.x),
// (a.x - b.x)(a.y + b.y))), taken from quantized to object space by `axis_weight`
// (normal_axis_weights), octahedral-encoded like the writer's normals but in
// integers: with l1 = |x| + |y| + |z|, (u, v) = (x, y) or, when z < 0,
// ((l1 - |y|) sgn x, (l1 - |x|) sgn y) (sgn 0 = +1), each mapped to
// floor((255 (u + l1) + l1) / (2 l1)); a zero normal gives (128, 128).
// Before weighting, the sum is halved (arithmetic shift) until every component is below 2^12.
[[gnu::always_inline]] inline void predict_normal(const FanPrediction& pred, const uint16_t v[3],
                                                  const uint16_t parent_after[3], const int32_t axis_weight[3],
                                                  uint8_t out[2]) {
    // The child ring's edges (predict_fan) closed by right -> parent_after -> left.
    const int64_t p0 = int32_t(parent_after[0]) - int32_t(v[0]), p1 = int32_t(parent_after[1]) - int32_t(v[1]),
                  p2 = int32_t(parent_after[2]) - int32_t(v[2]);
    const int32_t *l = pred.left, *r = pred.right;
    const int64_t n[3] = {pred.child_area[0] + (r[1] - p1) * (r[2] + p2) + (p1 - l[1]) * (p2 + l[2]),
                          pred.child_area[1] + (r[2] - p2) * (r[0] + p0) + (p2 - l[2]) * (p0 + l[0]),
                          pred.child_area[2] + (r[0] - p0) * (r[1] + p1) + (p0 - l[0]) * (p1 + l[1])};
    const uint64_t top = std::max({std::abs(n[0]), std::abs(n[1]), std::abs(n[2])});
    const int scale = std::max(0, int(std::bit_width(top)) - 12);
    // |x|, |y|, |z| < 2^20 (weights <= 256): l1 < 2^22 and the quotients below fit in 32 bits.
    int32_t x = int32_t(n[0] >> scale) * axis_weight[0], y = int32_t(n[1] >> scale) * axis_weight[1],
            z = int32_t(n[2] >> scale) * axis_weight[2];
    const int32_t l1 = std::abs(x) + std::abs(y) + std::abs(z);
    if (l1 == 0) {
        out[0] = out[1] = 128;
        return;
    }
    if (z < 0) {
        const int32_t ox = (l1 - std::abs(y)) * (x < 0 ? -1 : 1), oy = (l1 - std::abs(x)) * (y < 0 ? -1 : 1);
        x = ox;
        y = oy;
    }
    const uint32_t den = 2 * uint32_t(l1);
    out[0] = uint8_t(std::min<uint32_t>((255 * uint32_t(x + l1) + uint32_t(l1)) / den, 255));
    out[1] = uint8_t(std::min<uint32_t>((255 * uint32_t(y + l1) + uint32_t(l1)) / den, 255));
}
// Per axis, the factor taking a normal from quantized to object space: the product
// of the other two extents of the box (hi - lo, in double), scaled so the largest is
// 256 and rounded to nearest, at least 1.
void normal_axis_weights(const float lo[3], const float hi[3], int32_t out[3]);
// Per axis, the factor taking a normal from object to quantized space (plane_normal):
// the extent of the box (hi - lo, in double), scaled so the largest is 256 and
// rounded to nearest, at least 1.
void plane_axis_weights(const float lo[3], const float hi[3], int32_t out[3]);

// Packed vertex of the base chunk (meshopt vertex codec, stride 8).
struct BaseVertex {
    uint16_t q[3];
    uint8_t oct[2];
};
static_assert(sizeof(BaseVertex) == 8);

// The connectivity replay shared by writer and reader. It tracks, for the most
// refined level decoded so far, which corners (face * 3 + k) reference each
// vertex, so that a split's index patches can be sent as a bit mask over its
// parent's corners (sorted ascending) instead of explicit corner numbers.
//
// Storage is laid out for the reader's speed (it is memory-latency bound): each
// vertex's corners sit contiguously and ascending in one pool region (a vertex
// that outgrows its region moves to a twice larger one at the end of the pool),
// so listing them is one or two cache lines instead of a linked-list walk, and
// prefetch() can pull a split's data in ahead of use. The pointer forms below
// allocate nothing (the pool is reserved by reset() for the common case).
class SplitReplay {
public:
    void reset(size_t vertex_capacity, size_t face_capacity);
    // Appends faces [first_face, first_face + count) with the given indices; their
    // corners must be above every corner added before (faces arrive in order).
    void add_faces(size_t first_face, std::span<const uint32_t> indices);
    // The corners of `v`, ascending, into `out` (cleared first).
    void corners_of(uint32_t v, std::vector<uint32_t>& out) const;
    // The same into out[0 ..): returns the count, or SIZE_MAX (nothing usable)
    // when `v` has more than `capacity` corners.
    size_t corners_of(uint32_t v, uint32_t* out, size_t capacity) const;
    // Moves the corners selected by `mask` (bit i = i-th of corners_of(parent))
    // to `child` (a vertex without corners yet), writing them to `moved`. False if
    // the mask names a missing corner.
    bool apply_mask(uint32_t parent, uint32_t child, uint64_t mask, std::vector<uint32_t>& scratch,
                    std::vector<uint32_t>& moved);
    // The same given the parent's corners exactly as corners_of returned them
    // (count <= 64): the moved corners, ascending, go to moved[0 .. popcount(mask)).
    bool apply_mask(uint32_t parent, uint32_t child, uint64_t mask, const uint32_t* corners, size_t count,
                    uint32_t* moved);
    // The neighbours of `v` (vertices sharing a face with it), ascending, into `out`.
    void ring_of(uint32_t v, std::vector<uint32_t>& out) const;
    // The same from v's corners (as corners_of returned them) into out[0 .. 2 * count);
    // returns the number of distinct neighbours.
    size_t ring_of(const uint32_t* corners, size_t count, uint32_t* out) const;
    // The faces around a vertex as one closed fan, counter-clockwise seen from
    // outside, from its corners (as corners_of returned them, count <= 64): fan
    // face t is corners[at[t]] = (v, ring[t], ring[t + 1 mod k]), t = 0 at corners[0].
    // Returns k = count, or 0 when the faces are not one closed manifold fan (a
    // boundary or non-manifold vertex).
    size_t ordered_fan(const uint32_t* corners, size_t count, uint32_t* ring, uint8_t* at) const;
    uint32_t index(size_t corner) const { return indices_[corner]; }
    // Neighbour j of a vertex given its corners (as corners_of returned them): the
    // vertex after (j even) or before (j odd) corner j / 2 in its face; j < 2 * count.
    uint32_t neighbour(const uint32_t* corners, size_t j) const {
        const uint32_t c = corners[j / 2], f = c - c % 3;
        return indices_[f + (c - f + 1 + uint32_t(j % 2)) % 3];
    }
    // Cache hints for a split of parent `v` a few splits ahead: stage 0 its
    // region's descriptor, 1 the region, 2 the faces of its corners, 3 its
    // neighbours' descriptors and, given `qpos` (3 per vertex), their positions
    // (stages in this order, a few splits apart). No effect on results; `v` must be
    // a valid vertex.
    void prefetch(uint32_t v, int stage, const uint16_t* qpos = nullptr) const;

private:
    struct Region {
        uint32_t offset = 0, count = 0, capacity = 0;
    };
    uint32_t* make_room(uint32_t v, size_t count);  // v's region with room for `count` corners
    UninitVector<Region> regions_;                  // per vertex
    UninitVector<uint32_t> pool_;     // corners, ascending per region (entries past a region's count unused)
    UninitVector<uint32_t> indices_;  // per corner: the vertex at the replayed level (set by add_faces)
};

}  // namespace body::pm
