#include "shared/pm/index_code.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "shared/pm/bpm_container.h"
#include "shared/pm/split_codec.h"

namespace body::pm {

namespace {
constexpr uint32_t kFifoSize = 16, kFifoBits = 4, kShortBits = 5;
static_assert(kFifoSize == 1u << kFifoBits);
// In-place packing needs every entry's code within its own 32 bits.
static_assert(2 + std::bit_width(2 * uint64_t(kMaxVertices - 1)) <= 32);

// The FIFO as a ring: slot head - 1 - age (mod 16) holds the value `age`
// places back. Starts with no vertex number (vertex numbers are < 2^32 - 1).
struct Fifo {
    uint32_t slot[kFifoSize];
    uint32_t head = 0;
    Fifo() { std::fill_n(slot, kFifoSize, UINT32_MAX); }
    // The age of v, or kFifoSize when v is not held (values held are distinct:
    // one enters only on a miss).
    uint32_t age_of(uint32_t v) const {
        uint32_t mask = 0;
#if defined(__GNUC__)
        // Four slots a compare (SSE2 / NEON): the packing's inner loop.
        typedef uint32_t U32x4 __attribute__((vector_size(16)));
        U32x4 m = {0, 0, 0, 0};
        for (uint32_t q = 0; q < kFifoSize / 4; ++q) {
            U32x4 s;
            std::memcpy(&s, slot + 4 * q, sizeof s);
            const U32x4 bit = {1u << (4 * q), 2u << (4 * q), 4u << (4 * q), 8u << (4 * q)};
            m |= U32x4(s == v) & bit;
        }
        mask = m[0] | m[1] | m[2] | m[3];
#else
        for (uint32_t s = 0; s < kFifoSize; ++s) mask |= uint32_t(slot[s] == v) << s;
#endif
        if (mask == 0) return kFifoSize;
        return (head - 1 - uint32_t(std::countr_zero(mask))) & (kFifoSize - 1);
    }
    uint32_t at_age(uint32_t age) const { return slot[(head - 1 - age) & (kFifoSize - 1)]; }
    void push(uint32_t v) {
        slot[head] = v;
        head = (head + 1) & (kFifoSize - 1);
    }
};
}  // namespace

size_t index_code_bits(size_t vertex_count) {
    // Wide enough for the zigzag of any difference between two vertex numbers.
    return std::max<size_t>(1, size_t(std::bit_width(2 * uint64_t(std::max<size_t>(vertex_count, 1) - 1))));
}

size_t pack_index_code(std::span<uint32_t> entries, size_t bits) {
    uint32_t* w = entries.data();
    const size_t n = entries.size();
    uint64_t acc = 0;
    size_t held = 0, out = 0;
    uint32_t prev_first = 0, first = 0;
    Fifo fifo;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t v = w[i];
        uint32_t reference = first;
        if (i % 3 == 0) {
            reference = prev_first;
            prev_first = first = v;
        }
        const uint32_t age = fifo.age_of(v);
        if (age < kFifoSize) {
            acc |= uint64_t(age) << (held + 1);  // 0
            held += 1 + kFifoBits;
        } else {
            fifo.push(v);
            const uint32_t z = zigzag(v, reference);  // split_codec.h: vertex numbers < 2^29, no wrap
            if (z < (1u << kShortBits)) {
                acc |= (uint64_t(3) | uint64_t(z) << 2) << held;  // 11
                held += 2 + kShortBits;
            } else {
                acc |= (uint64_t(1) | uint64_t(z) << 2) << held;  // 10
                held += 2 + bits;
            }
        }
        if (held >= 32) {
            w[out++] = uint32_t(acc);
            acc >>= 32;
            held -= 32;
        }
    }
    if (held > 0) w[out++] = uint32_t(acc);
    return out;
}

void unpack_index_code(std::span<const uint32_t> words, size_t bits, std::span<uint32_t> out) {
    size_t word = 0;
    uint64_t acc = 0;
    size_t held = 0;
    auto take = [&](size_t count) {  // the next `count` (<= 32) bits of the stream
        if (held < count) {
            acc |= uint64_t(word < words.size() ? words[word] : 0) << held;
            ++word;
            held += 32;
        }
        const uint32_t v = uint32_t(acc & ((uint64_t(1) << count) - 1));
        acc >>= count;
        held -= count;
        return v;
    };
    uint32_t prev_first = 0, first = 0;
    Fifo fifo;
    for (size_t i = 0; i < out.size(); ++i) {
        uint32_t v;
        if (take(1) == 0) {
            v = fifo.at_age(take(kFifoBits));
        } else {
            const uint32_t z = take(1) ? take(kShortBits) : take(bits);
            const uint32_t reference = i % 3 == 0 ? prev_first : first;
            v = unzigzag(z, reference);
            fifo.push(v);
        }
        if (i % 3 == 0) prev_first = first = v;
        out[i] = v;
    }
}

}  // namespace body::pm
