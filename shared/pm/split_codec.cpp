// See split_codec.h.
#include "shared/pm/split_codec.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "shared/pm/bpm_container.h"

namespace body::pm {

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

namespace {
// SplitSizes of one finished chunk: `table_bytes` of tables, then the coded items.
void add_sizes(SplitSizes& sizes, size_t out_bytes, size_t table_bytes, const uint32_t (*freq)[kSymbolCount],
               std::span<const std::pair<uint32_t, uint32_t>> items) {
    double counted = 0;
    uint32_t last = 0;
    for (const auto& [context, value] : items) {
        uint32_t raw, bits;
        double b;
        if (context < kSplitContexts) {
            const uint32_t s = value_symbol(value, raw, bits);
            b = double(kRansBits) - std::log2(double(freq[context][s])) + bits;
            last = context;
        } else {
            b = context - kSplitContexts;  // raw bits of the value before
        }
        sizes.context_bits[last] += b;
        counted += b;
    }
    sizes.table_bits += 8.0 * double(table_bytes);
    sizes.framing_bits += 8.0 * double(out_bytes - table_bytes) - counted;
}
}  // namespace

void SplitEncoder::finish(std::vector<uint8_t>& out, SplitSizes* sizes) const {
    const size_t out_start = out.size();
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
    const size_t table_bytes = out.size() - out_start;
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
    if (sizes) {
        std::vector<std::pair<uint32_t, uint32_t>> items(values_.size());
        for (size_t i = 0; i < values_.size(); ++i)
            items[i] = values_[i].context < kRawContext
                           ? std::pair{values_[i].context, values_[i].value}
                           : std::pair{kSplitContexts + values_[i].context - kRawContext, 0u};
        add_sizes(*sizes, out.size() - out_start, table_bytes, freq, items);
    }
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

}  // namespace body::pm
