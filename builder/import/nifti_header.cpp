// NIfTI-1 header layout: Cox et al., "A (sort of) new image data format
// standard: NIfTI-1", NIH/NIMH DFWG, 2004 (nifti1.h field offsets).
#include "builder/import/nifti_header.h"

#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "shared/input_file.h"

namespace body {
namespace {

struct HeaderView {
    std::span<const uint8_t> bytes;
    bool swapped = false;
    uint32_t u32(size_t at) const {
        uint32_t v;
        std::memcpy(&v, bytes.data() + at, 4);
        return swapped ? __builtin_bswap32(v) : v;
    }
    int16_t i16(size_t at) const {
        uint16_t v;
        std::memcpy(&v, bytes.data() + at, 2);
        return int16_t(swapped ? __builtin_bswap16(v) : v);
    }
    float f32(size_t at) const {
        const uint32_t bits = u32(at);
        float f;
        std::memcpy(&f, &bits, 4);
        return f;
    }
};

constexpr size_t kDimAt = 40, kDatatypeAt = 70, kPixdimAt = 76, kQformCodeAt = 252, kSformCodeAt = 254, kBitpixAt = 72,
                 kVoxOffsetAt = 108, kMagicAt = 344;

// nifti1.h's datatype codes and the bitpix each implies (0: not a datatype).
int bitpix_of(int datatype) {
    switch (datatype) {
        case 2:
        case 256: return 8;  // uint8, int8
        case 4:
        case 512: return 16;  // int16, uint16
        case 8:
        case 16:
        case 768:
        case 2304: return 32;  // int32, float32, uint32, rgba32
        case 32:
        case 64:
        case 1024:
        case 1280: return 64;  // complex64, float64, int64, uint64
        case 128: return 24;   // rgb24
        case 1536:
        case 1792: return 128;  // float128, complex128
        default: return 0;
    }
}

}  // namespace

Result<NiftiHeaderFacts> check_nifti_header(std::span<const uint8_t> header, const std::string& path) {
    auto bad = [&](size_t byte, const std::string& why) {
        return input_error(path + ": header byte " + std::to_string(byte) + ": " + why);
    };
    if (header.size() < kNiftiHeaderSize)
        return bad(header.size(), "file ends inside the 348-byte header (" + std::to_string(header.size()) + " bytes)");
    HeaderView h{header};
    if (h.u32(0) != kNiftiHeaderSize) {
        h.swapped = true;
        if (h.u32(0) != kNiftiHeaderSize) {
            h.swapped = false;
            return bad(0, "sizeof_hdr is " + std::to_string(h.u32(0)) + ", not 348 (not a NIfTI-1/ANALYZE header)");
        }
    }
    NiftiHeaderFacts facts;
    const uint8_t* magic = header.data() + kMagicAt;
    const bool analyze = magic[0] == 0 && magic[1] == 0 && magic[2] == 0 && magic[3] == 0;
    if (std::memcmp(magic, "n+1\0", 4) == 0)
        facts.single_file = true;
    else if (std::memcmp(magic, "ni1\0", 4) == 0 || analyze)
        facts.single_file = false;
    else
        return bad(kMagicAt, "magic is '" + escape_for_message({reinterpret_cast<const char*>(magic), 4}) +
                                 "', not 'n+1' or 'ni1'");
    const int rank = h.i16(kDimAt);
    if (rank < 1 || rank > 7) return bad(kDimAt, "wrong dims: dim[0] = " + std::to_string(rank) + ", must be 1 to 7");
    for (int d = 1; d <= 7; ++d) {
        const int v = h.i16(kDimAt + 2 * size_t(d));
        const size_t at = kDimAt + 2 * size_t(d);
        if (d <= 3 && d <= rank && v < 1)
            return bad(at,
                       "wrong dims: dim[" + std::to_string(d) + "] = " + std::to_string(v) + ", must be at least 1");
        if (d > 3 && d <= rank && v > 1)
            return bad(at, "wrong dims: dim[" + std::to_string(d) + "] = " + std::to_string(v) +
                               ": a label volume is 3-D (at most one time point)");
        if (d > 3 && d <= rank && v < 0)
            return bad(at, "dim[" + std::to_string(d) + "] = " + std::to_string(v) + " is negative");
        if (d <= 3) facts.dim[d - 1] = d <= rank ? v : 1;
    }
    const int bitpix = h.i16(kBitpixAt);
    if (bitpix <= 0 || bitpix % 8 != 0 || bitpix > 128)
        return bad(kBitpixAt, "bitpix = " + std::to_string(bitpix) + ", must be 8, 16, 32, 64 or 128");
    const int datatype = h.i16(kDatatypeAt);
    if (bitpix_of(datatype) == 0)
        return bad(kDatatypeAt, "datatype = " + std::to_string(datatype) + " is not a NIfTI-1 datatype");
    if (bitpix_of(datatype) != bitpix)
        return bad(kBitpixAt, "bitpix = " + std::to_string(bitpix) + ", but datatype " + std::to_string(datatype) +
                                  " has " + std::to_string(bitpix_of(datatype)));
    facts.bytes_per_voxel = bitpix / 8;
    facts.data_bytes =
        uint64_t(facts.dim[0]) * uint64_t(facts.dim[1]) * uint64_t(facts.dim[2]) * uint64_t(facts.bytes_per_voxel);
    // Without a qform or sform the voxel size is the only geometry: niftilib
    // would make a zero or non-finite one 1 mm, another volume than the file's.
    if (h.i16(kQformCodeAt) <= 0 && h.i16(kSformCodeAt) <= 0) {
        for (int d = 1; d <= std::min(rank, 3); ++d) {
            const float v = h.f32(kPixdimAt + 4 * size_t(d));
            if (!(std::isfinite(v) && v != 0.0f))
                return bad(kPixdimAt + 4 * size_t(d), "pixdim[" + std::to_string(d) + "] = " + std::to_string(v) +
                                                          ": the voxel size must be a non-zero number");
        }
    }
    if (facts.single_file) {
        const float off = h.f32(kVoxOffsetAt);
        if (!(off >= 0.0f) || off > 1e12f)
            return bad(kVoxOffsetAt, "vox_offset = " + std::to_string(off) + " is not a byte offset");
        if (off < 352.0f)  // a .nii's voxels follow the 348-byte header and its 4-byte extension flag
            return bad(kVoxOffsetAt, "vox_offset = " + std::to_string(off) + " points inside the header (below 352)");
        facts.data_offset = uint64_t(off);
    }
    return facts;
}

Result<NiftiHeaderFacts> read_nifti_header(const std::string& path) {
    if (auto regular = check_regular_file(path); !regular) return regular.error();
    gzFile gz = gzopen(path.c_str(), "rb");  // reads plain files too
    if (!gz) return input_error(path + ": cannot open");
    uint8_t header[kNiftiHeaderSize];
    const int n = gzread(gz, header, unsigned(kNiftiHeaderSize));
    gzclose(gz);
    if (n < 0) return input_error(path + ": header byte 0: unreadable (corrupt gzip stream)");
    return check_nifti_header({header, size_t(n)}, path);
}

uint64_t label_volume_memory_budget() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    uint64_t budget = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) / 2 : (uint64_t(4) << 30);
    rlimit as{};
    if (::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
        budget = std::min<uint64_t>(budget, uint64_t(as.rlim_cur) / 4 * 3);
    return budget;
}

}  // namespace body
