// bodygen: the offline builder. Dispatches to one subcommand per file in builder/cli/.
#include <malloc.h>
#include <sys/mman.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <span>
#include <string>

#include "body/version.h"
#include "builder/cli/commands.h"
#include "shared/atomic_file.h"
#include "shared/error.h"
#include "shared/input_file.h"

namespace body::cli {

int report(const Error& error) {
    std::fprintf(stderr, "bodygen: %s\n", error.message.c_str());
    return error.exit_code;
}

int run_contours_check(const Args& args);  // cmd_check.cpp
int run_slice(const Args& args);           // cmd_slice.cpp
int run_pack(const Args& args);            // cmd_pack.cpp
int run_build(const Args& args);           // cmd_build.cpp
int run_lod(const Args& args);             // cmd_lod.cpp
int run_extract(const Args& args);         // cmd_extract.cpp
int run_info(const Args& args);            // cmd_info.cpp
int run_contours(const Args& args);        // cmd_contours.cpp
int run_exhibit(const Args& args);         // cmd_exhibit.cpp
int run_export(const Args& args);          // cmd_export.cpp

}  // namespace body::cli

namespace {

using body::cli::Command;

// The subcommand table; each entry lives in builder/cli/cmd_<name>.cpp.
const Command kCommands[] = {
    {"contours", "extract contours from a NIfTI label volume or DICOM RT-STRUCT", body::cli::run_contours},
    {"check", "validate a contour stack and print its slices and contours", body::cli::run_contours_check},
    {"slice", "slice a closed OBJ mesh with parallel planes into a contour stack", body::cli::run_slice},
    {"build", "contours, label volume or RT-STRUCT -> one closed mesh per structure (OBJ, .bpm or OUT/)",
     body::cli::run_build},
    {"lod", "build progressive meshes (.bpm) from an OBJ, VRML97, STL, PLY or glTF file", body::cli::run_lod},
    {"extract", "write one level of a .bpm file as OBJ", body::cli::run_extract},
    {"info", "print the structures, levels, sizes and error curve of a .bpm file", body::cli::run_info},
    {"pack", "validate a kiosk scene.json and write a self-contained bundle", body::cli::run_pack},
    {"exhibit", "label volume, RT-STRUCT, contours or meshes -> a kiosk bundle, in one step", body::cli::run_exhibit},
    {"export", "a bundle, .bpm or OBJ -> glTF 2.0 (.glb/.gltf), VRML97, STL, PLY or OBJ", body::cli::run_export},
};

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "bodygen %s - turns anatomy traced on image slices into watertight progressive meshes\n\n"
                 "usage: bodygen <command> [options]\n\ncommands:\n",
                 BODY_VERSION_STRING);
    for (const Command& c : kCommands) std::fprintf(out, "  %-9s %s\n", c.name, c.summary);
    std::fprintf(out,
                 "\noptions:\n  --help     this text (also: bodygen <command> --help)\n"
                 "  --version  print the version\n\nexit codes: 0 ok, 1 runtime failure, 2 bad usage or bad input\n");
}

// The heap's first 128 MB grown at once and advised for transparent huge
// pages (the kernel here only gives them where advised), then freed to the
// heap, which keeps it (no trim): a large build's arrays then fault once per
// 2 MB instead of once per 4 KB. Address space only; pages come when touched.
void advise_heap_huge_pages() {
    constexpr size_t kChunk = 16 << 20, kChunks = 8;
    void* chunk[kChunks];
    for (size_t i = 0; i < kChunks; ++i) chunk[i] = std::malloc(kChunk);
    const auto first = reinterpret_cast<uintptr_t>(chunk[0]), last = reinterpret_cast<uintptr_t>(chunk[kChunks - 1]);
    constexpr uintptr_t kHuge = 2 << 20;
    const uintptr_t from = (first + kHuge - 1) & ~(kHuge - 1), to = (last + kChunk) & ~(kHuge - 1);
    if (chunk[0] && chunk[kChunks - 1] && to > from) madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE);
    for (size_t i = kChunks; i-- > 0;) std::free(chunk[i]);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        print_help(stderr);
        return body::kExitBadInput;
    }
    const std::string first = argv[1];
    if (first == "--help" || first == "-h" || first == "help") {
        print_help(stdout);
        return body::kExitOk;
    }
    if (first == "--version") {
        std::printf("bodygen %s\n", BODY_VERSION_STRING);
        return body::kExitOk;
    }
    // Arrays up to 32 MB (a large build's per-triangle arrays, allocated and
    // freed round after round) come from the heap, which keeps what is freed:
    // otherwise each one is a fresh mapping whose every page faults on first
    // touch, a sixth of an interpolated build's time. Costs a few % of peak RSS.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    advise_heap_huge_pages();
    body::remove_temporaries_on_signal();
    for (const Command& c : kCommands) {
        if (first != c.name) continue;
        // The last net under every command: a path the file system refuses
        // (too long, a loop) or memory running out is one line, not an abort.
        try {
            return c.run(body::cli::Args(argv + 2, argv + argc));
        } catch (const std::filesystem::filesystem_error& e) {
            std::fprintf(stderr, "bodygen: %s: %s\n", body::escape_for_message(e.path1().string()).c_str(),
                         e.code().message().c_str());
            return body::kExitBadInput;
        } catch (const std::bad_alloc&) {
            std::fprintf(stderr, "bodygen: %s: out of memory\n", c.name);
            return body::kExitRuntime;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "bodygen: %s: %s\n", c.name, body::escape_for_message(e.what(), 200).c_str());
            return body::kExitRuntime;
        }
    }
    std::fprintf(stderr, "bodygen: unknown command '%s' (see bodygen --help)\n", first.c_str());
    return body::kExitBadInput;
}
