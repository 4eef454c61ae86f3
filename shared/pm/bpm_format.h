#pragma once
// Building blocks of the `.bpm` progressive-mesh format shared by the writer
// (builder/lod/bpm_writer.cpp) and the reader (shared/pm/progressive_mesh.cpp).
// The byte layout is documented in shared/pm/FORMAT.md; keep both in step.
//
// Everything here is integer or correctly rounded IEEE arithmetic so that the
// writer produces the same bytes on x86-64 and aarch64.
#include <cstddef>
#include <cstdint>
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
inline constexpr uint16_t kVersion = 2;             // 2: splits move their parents (optimal placement)
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

// Dequantization of 16-bit coordinates in [lo, hi] and decoding of 8-bit
// octahedral normals. The encoders live with the writer (builder/lod/bpm_writer.cpp),
// compiled without floating-point contraction so the bytes match on every platform.
float dequantize16(uint16_t q, float lo, float hi);
// The same with step = (double(hi) - double(lo)) / 65535.0 computed once (same result).
inline float dequantize16(uint16_t q, float lo, double step) { return float(double(lo) + double(q) * step); }
void oct_decode8(const uint8_t in[2], float out[3]);

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

// Packed vertex of the base chunk (meshopt vertex codec, stride 8).
struct BaseVertex {
    uint16_t q[3];
    uint8_t oct[2];
};
static_assert(sizeof(BaseVertex) == 8);

// Packed record of a vertex split (meshopt vertex codec, stride 24): the child's
// quantized position and normal as zig-zag differences from its parent's (the
// parent's position before the split), the parent's move (its position after
// the split minus before; 0 for a half-edge collapse), the distance child -
// parent in the vertex order, and the level error.
struct SplitVertex {
    uint16_t dq[3];
    uint8_t doct[2];
    uint16_t pdq[3];
    uint16_t reserved;  // 0
    uint32_t parent_delta;
    float error;
};
static_assert(sizeof(SplitVertex) == 24);

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
    uint32_t index(size_t corner) const { return indices_[corner]; }
    // Neighbour j of a vertex given its corners (as corners_of returned them): the
    // vertex after (j even) or before (j odd) corner j / 2 in its face; j < 2 * count.
    uint32_t neighbour(const uint32_t* corners, size_t j) const {
        const uint32_t c = corners[j / 2], f = c - c % 3;
        return indices_[f + (c - f + 1 + uint32_t(j % 2)) % 3];
    }
    // Cache hints for a split of parent `v` a few splits ahead: stage 0 its
    // region's descriptor, 1 the region, 2 the faces of its corners, 3 its
    // neighbours' descriptors (stages in this order, a few splits apart). No effect
    // on results; `v` must be a valid vertex.
    void prefetch(uint32_t v, int stage) const;

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
