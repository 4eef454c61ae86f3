#pragma once
// The in-memory code of a progressive mesh's packed index array
// (ProgressiveMesh::pack_indices / fill_indices; never written to a file).
// Each entry, read as a bit stream from the least significant bit of word 0:
//   0 + 4 bits    the entry equals the value `age` places back in a 16-entry
//                 FIFO of recent values (a value enters on a miss: every entry
//                 not coded this way)
//   10 + bits     the zigzag difference to a reference, in index_code_bits()
//   11 + 5 bits   that difference when below 32
// The reference: corner 0 of a face is coded against corner 0 of the face
// before, corners 1 and 2 against their face's corner 0 (a split's new faces
// share its child and parent, whose numbers are close).
#include <cstddef>
#include <cstdint>
#include <span>

namespace body::pm {

// Bits of the long difference for entries below vertex_count (>= 1).
size_t index_code_bits(size_t vertex_count);

// Codes `entries` (each below the vertex_count `bits` was made for) in place:
// returns the words written, a prefix of `entries` (every entry's code fits
// its own 32 bits, so words <= i are written only after entry i is read).
size_t pack_index_code(std::span<uint32_t> entries, size_t bits);

// Decodes out.size() entries from `words` (pack_index_code's output for the
// same `bits`) into `out`.
void unpack_index_code(std::span<const uint32_t> words, size_t bits, std::span<uint32_t> out);

}  // namespace body::pm
