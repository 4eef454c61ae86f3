#pragma once
// The `.bpm` reader: a file (or bytes as they arrive) -> ProgressiveMesh per
// structure. Every section is checked (CRC, framing, every decoded value bounded)
// before it is used; errors name the section, the structure and the byte offset.
// Format: shared/pm/FORMAT.md; the decoder of a SPLT section is parse_splits.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/pm/progressive_mesh.h"

namespace body::pm {

// Reads a .bpm file from byte chunks as they arrive (network, disk, a test).
// Every complete section is decoded at once; a structure is drawable as soon as
// its BASE section is in, and refines up to its last complete SPLT chunk.
class BpmStream {
public:
    // Batched (default): faces in the batched cache order of draw_order.h, the
    // kiosk's; Refinement: in the file's order, every level an exact prefix.
    enum class FaceOrder { Batched, Refinement };
    explicit BpmStream(std::string source_name = "<stream>", FaceOrder order = FaceOrder::Batched);
    // Appends bytes. Returns an error (and stays failed) on a corrupt header or
    // section, naming the section, the structure and the byte offset in the file.
    Status feed(std::span<const uint8_t> bytes);
    // True when the END section arrived and was valid.
    bool complete() const { return complete_; }
    // Structures whose INFO has arrived (their declared count is structure_count_declared()).
    size_t structure_count() const { return meshes_.size(); }
    size_t structure_count_declared() const { return declared_structures_; }
    ProgressiveMesh& structure(size_t i) { return *meshes_[i]; }
    const ProgressiveMesh& structure(size_t i) const { return *meshes_[i]; }
    size_t bytes_consumed() const { return consumed_; }
    // Error for a stream that ended early: names the section being received and its offset.
    Status finish() const;

    // --- decoding on demand (the kiosk decodes a file only as far as its levels are wanted).
    // Splits of structure `structure` (< structure_count()) wanted. The stream stops
    // once every structure has what it wants: at the first batch boundary at or
    // above the want (draw_order.h; refinement order: at the want), inside a SPLT
    // section if need be. Raising a want lets it go on. A want never undecodes.
    // Default: every split (the whole file).
    void set_wanted_splits(size_t structure, size_t splits);
    // The want of every structure, those whose INFO has not arrived included.
    void set_wanted_splits_all(size_t splits);
    // True when a structure wants more than it has (or has not arrived).
    bool wants_more() const;
    // True when the last feed() stopped because nothing more was wanted. The bytes
    // from bytes_consumed() on were dropped: feed again from there once a want
    // rose. A stop inside a section keeps only the decoder's place (a few numbers,
    // no bytes): the section is read again, checked again, and decoding goes on
    // after its last decoded split, giving exactly what an uninterrupted decode gives.
    // A paused structure keeps no decoding state either (the replay, the codes
    // of the decoded level): rebuilt from its drawn arrays before its next split.
    bool paused() const { return paused_; }
    // The caller feeds the whole file and wants every split (read_bpm,
    // read_bpm_bytes): each structure's arrays are sized to the file's counts at
    // its first SPLT section instead of grown with the sections (no copies, fewer
    // page faults; the same final sizes). Streams without it hold what arrived.
    void expect_whole_file() { whole_file_ = true; }

private:
    Status parse_section(uint32_t tag, uint32_t structure, std::span<const uint8_t> payload, size_t offset);
    Status parse_info(std::span<const uint8_t> payload, const std::string& where);
    Status parse_base(ProgressiveMesh& m, std::span<const uint8_t> payload, const std::string& where);
    Status parse_splits(size_t structure, std::span<const uint8_t> payload, size_t offset, const std::string& where);
    size_t split_limit(size_t structure) const;  // where decoding on demand stops (set_wanted_splits)
    bool wants_more_except(size_t structure) const;
    void release_scratch();  // the per-section scratch, while paused and once complete
    // Appends a decoded split to m's arrays: its new faces, the corners it moved to
    // the child, its parent's move, the child's codes and the level's error.
    static void record_split(ProgressiveMesh& m, size_t j, uint32_t parent, uint32_t child,
                             std::span<const uint32_t> faces, std::span<const uint32_t> moved, const uint16_t from[3],
                             const uint16_t to[3], const uint16_t q[3], const uint8_t oct[2], uint16_t error_high);

    std::string source_;
    FaceOrder order_;
    std::vector<uint8_t> pending_;  // bytes of the section being received
    size_t consumed_ = 0;           // file offset of pending_[0]
    bool header_done_ = false, complete_ = false, failed_ = false;
    std::string failure_;
    size_t declared_structures_ = 0;
    std::vector<std::unique_ptr<ProgressiveMesh>> meshes_;
    std::vector<uint32_t> decoded_indices_;
    std::vector<uint32_t> split_parents_;  // parse_splits: the parents of a chunk's splits (reused)
    // Decoding on demand: per structure the splits wanted (default_wanted_ until set).
    std::vector<size_t> wanted_;
    size_t default_wanted_ = SIZE_MAX;
    bool paused_ = false;
    bool whole_file_ = false;  // expect_whole_file()
    // A SPLT section decoded part-way: its file offset (SIZE_MAX: none), the
    // splits of it decoded, the faces they added, the error bits of the last,
    // and where its value and topology streams stand.
    struct Parked {
        size_t offset = SIZE_MAX;
        uint32_t next = 0;
        size_t face_cursor = 0, topology_at = 0;
        uint32_t error_bits = 0;
        size_t rans_pos = 0, bit_pos = 0;
        uint32_t state = 0, other_state = 0;
    } parked_;
};

// Reads a whole file; errors name the path, section and byte offset.
Result<std::vector<std::unique_ptr<ProgressiveMesh>>> read_bpm(
    const std::string& path, BpmStream::FaceOrder order = BpmStream::FaceOrder::Batched);
// Reads from memory (the same checks as a file).
Result<std::vector<std::unique_ptr<ProgressiveMesh>>> read_bpm_bytes(
    std::span<const uint8_t> bytes, const std::string& source_name,
    BpmStream::FaceOrder order = BpmStream::FaceOrder::Batched);

}  // namespace body::pm
