#pragma once
// How a SPLT section's values are coded (version 3, kept in versions 4 to 7): the
// contexts, the entropy coder (SplitEncoder, writer) and its decoder
// (SplitDecoder, reader), and the zig-zag residuals of 16- and 8-bit codes.
// What the values are and how they are predicted: prediction.h, FORMAT.md.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

namespace body::pm {

// Zig-zag mapping of the wrap-around difference of two codes of one width
// (uint16_t positions, uint8_t normals; FORMAT.md's zigzag16 and zigzag8).
template <class Code>
inline Code zigzag(Code to, Code from) {
    using Signed = std::make_signed_t<Code>;
    const Signed d = Signed(Code(to - from));
    return Code((Code(d) << 1) ^ Code(d >> (8 * sizeof(Code) - 1)));
}
template <class Code>
inline Code unzigzag(Code z, Code from) {
    const Code d = Code((z >> 1) ^ Code(-(z & 1)));
    return Code(from + d);
}

// Every value of a split is an unsigned integer coded in one of the contexts
// below: a small symbol (the value itself below 8, else its bit length and the
// bit after the leading one) entropy-coded with a static rANS table per context
// and chunk, plus the remaining low bits sent raw in a separate bit stream. So a
// value costs about its information content, and decoding is one table lookup
// plus one bit-field read.
enum SplitContext : uint32_t {
    kCtxKind,                           // split kind: topology form * 2 + parent moves
    kCtxParentDelta,                    // parent - previous parent (zig-zag)
    kCtxErrorStep,                      // (previous error bits - error bits) >> 16
    kCtxFanStart,                       // compact topology: ring position of the left wing
    kCtxFanLength,                      // compact topology: faces moving to the child
    kCtxChild0,                         // child position residual, 3 axes in coding order (zig-zag)
    kCtxParent0 = kCtxChild0 + 3,       // parent move residual, the same order (zig-zag)
    kCtxNormal0 = kCtxParent0 + 3,      // child normal residual, u v (zig-zag; files with normals)
    kCtxChildCoarse = kCtxNormal0 + 2,  // version 6: the child position's grid, log2 steps (0: exact)
    kCtxParentCoarse,                   // version 6: the moved parent's grid, log2 steps (0: exact)
    kSplitContexts,
};
// Version 6: a position that a later split moves again (an intermediate one,
// shown only at coarser levels) is coded on a grid of 2^e quantization steps,
// e <= kMaxCoarseShift, chosen by the writer so that 2^e times the largest step
// of the box is at most kCoarseFraction times the stored error of the split that
// moves it (the error of every level that shows it is at least that). So a
// decoded position is within ProgressiveMesh::position_bound() of the builder's.
inline constexpr uint32_t kMaxCoarseShift = 15;
inline constexpr double kCoarseFraction = 1.0 / 16;
// The writer's grid for a position that a split with stored error `error` moves
// again: the largest e <= kMaxCoarseShift with 2^e * largest_step <= kCoarseFraction
// * error (0 when none). largest_step: the box's largest extent / 65535.
inline uint32_t coarsest_grid(float error, double largest_step) {
    const double steps = double(error) * kCoarseFraction / largest_step;
    if (!(steps >= 1)) return 0;
    return uint32_t(std::min(std::ilogb(steps), int(kMaxCoarseShift)));
}
// The box's largest extent / 65535 (the extents in double, from the INFO floats).
inline double largest_step(const float lo[3], const float hi[3]) {
    double s = 0;
    for (int k = 0; k < 3; ++k) s = std::max(s, (double(hi[k]) - double(lo[k])) / 65535);
    return s;
}
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

// Where the bytes of SPLT payloads go (SplitEncoder::finish and the writer add to
// it): per context, its symbols at the chunk table's cost (log2(2^kRansBits / freq)
// each) plus its raw bits (a shift's low bits count with the value before them);
// the rest exactly. In bits; a measurement, not part of the format.
struct SplitSizes {
    double context_bits[kSplitContexts] = {};
    double table_bits = 0;     // the frequency tables
    double framing_bits = 0;   // the coder's sizes, final rANS states, rounding to bytes
    double topology_bits = 0;  // general-form topology records
    double header_bits = 0;    // section headers and checksums, first/count/faces, the two payload sizes
    uint64_t splits = 0;
    double total_bits() const {
        double t = table_bits + framing_bits + topology_bits + header_bits;
        for (double b : context_bits) t += b;
        return t;
    }
};

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
    // Appends the coded chunk to `out`; adds to `sizes` where its bytes went (if given).
    void finish(std::vector<uint8_t>& out, SplitSizes* sizes = nullptr) const;
    // Empties the encoder for the next chunk, keeping its storage (a chunk
    // holds some hundred thousand values: regrowing them was costly).
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
        // after each holds what one split can read (at most 22 values: 44 bytes
        // of rANS words, 83 bytes of raw bits): check this at least once per split.
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

}  // namespace body::pm
