// A .bpm's INFO sections without decoding (contract in bpm_summary.h).
#include "shared/pm/bpm_summary.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "shared/pm/bpm_container.h"

namespace body::pm {
namespace {

std::string at(const std::string& path, size_t offset) { return path + ": byte " + std::to_string(offset); }

// A file read by offset: the first kPrefix bytes in one read (every INFO of a
// small file), the rest by pread. Plain descriptors: a kiosk reads thousands of
// these at its start, and a stream's set-up cost more than the read.
class File {
public:
    static constexpr size_t kPrefix = 4096;
    explicit File(int fd) : fd_(fd) {
        const ssize_t n = fill(0, prefix_, kPrefix);
        prefix_size_ = n > 0 ? size_t(n) : 0;
    }
    ~File() { ::close(fd_); }
    File(const File&) = delete;
    File& operator=(const File&) = delete;

    // Reads exactly `n` bytes at `offset`; false at the end of the file or on an error.
    bool read(size_t offset, void* out, size_t n) {
        auto* dst = static_cast<uint8_t*>(out);
        if (offset < prefix_size_) {
            const size_t k = std::min(n, prefix_size_ - offset);
            std::memcpy(dst, prefix_ + offset, k);
            dst += k, offset += k, n -= k;
        }
        return n == 0 || fill(offset, dst, n) == ssize_t(n);
    }

private:
    ssize_t fill(size_t offset, uint8_t* dst, size_t n) {
        size_t done = 0;
        while (done < n) {
            const ssize_t r = ::pread(fd_, dst + done, n - done, off_t(offset + done));
            if (r < 0 && errno == EINTR) continue;
            if (r <= 0) break;
            done += size_t(r);
        }
        return ssize_t(done);
    }

    int fd_;
    uint8_t prefix_[kPrefix];
    size_t prefix_size_ = 0;
};

}  // namespace

Result<std::vector<StructureSummary>> read_bpm_summary(const std::string& path) {
    // Never open a FIFO or a device (the open itself could block the kiosk).
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return input_error(path + ": not a regular file");
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return input_error(path + ": cannot open");
    File in(fd);
    uint8_t h[kFileHeaderSize];
    if (!in.read(0, h, sizeof h)) return input_error(at(path, 0) + ": truncated file header");
    if (std::memcmp(h, kMagic, 4) != 0) return input_error(path + ": file header at byte 0: not a .bpm file");
    if (crc32({h, 12}) != get_u32(h + 12)) return input_error(path + ": file header at byte 0: checksum mismatch");
    if (get_u16(h + 4) != kVersion) return input_error(path + ": file header at byte 4: unsupported version");
    const uint32_t declared = get_u32(h + 8);
    if (declared == 0 || declared > 65535) return input_error(path + ": file header at byte 8: bad structure count");
    std::vector<StructureSummary> out;
    std::vector<uint8_t> section;
    size_t offset = kFileHeaderSize;
    while (out.size() < declared) {
        uint8_t s[kSectionHeaderSize];
        if (!in.read(offset, s, sizeof s))
            return input_error(at(path, offset) + ": truncated before every INFO section");
        const uint32_t tag = get_u32(s), structure = get_u16(s + 4), length = get_u32(s + 8);
        const auto where = [&] {
            return path + ": section " + tag_name(tag) + " of structure " + std::to_string(structure) + " at byte " +
                   std::to_string(offset);
        };
        if (length > (1u << 30)) return input_error(where() + ": section length too large");
        const size_t total = kSectionHeaderSize + size_t(length) + kSectionTrailerSize;
        if (tag == kTagInfo) {
            if (structure != out.size()) return input_error(where() + ": INFO out of order");
            section.assign(s, s + kSectionHeaderSize);
            section.resize(total);
            if (!in.read(offset + kSectionHeaderSize, section.data() + kSectionHeaderSize,
                         length + kSectionTrailerSize))
                return input_error(where() + ": truncated");
            if (crc32({section.data(), kSectionHeaderSize + length}) !=
                get_u32(section.data() + kSectionHeaderSize + length))
                return input_error(where() + ": checksum mismatch");
            InfoRecord info;
            if (const char* reason = read_info({section.data() + kSectionHeaderSize, length}, info))
                return input_error(where() + ": " + reason);
            StructureSummary summary;
            summary.box_min = Vec3f(info.box_min[0], info.box_min[1], info.box_min[2]);
            summary.box_max = Vec3f(info.box_max[0], info.box_max[1], info.box_max[2]);
            summary.base_triangles = info.base_faces;
            summary.full_triangles = info.faces;
            out.push_back(summary);
        } else if (tag != kTagBase && tag != kTagSplits) {
            return input_error(where() + ": unexpected section before every INFO");
        }
        offset += total;  // a BASE or SPLT payload is skipped unread
    }
    return out;
}

}  // namespace body::pm
