// NIfTI label volume -> contour stack: read with niftilib, then per label and
// per slice marching squares (marching_squares.h; on the label's blurred
// indicator with --label-smooth, gaussian_blur.h) and topology-preserving
// Douglas-Peucker (ring_simplify.h). Structures are independent and run on
// `jobs` threads.
// - NIfTI-1 format: Cox et al., "A (sort of) new image data format standard:
//   NIfTI-1", NIH/NIMH DFWG, 2004 (qform/sform conventions).
#include <nifti1_io.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <thread>

#include "builder/import/gaussian_blur.h"
#include "builder/import/import.h"
#include "builder/import/label_table.h"
#include "builder/import/label_volume.h"
#include "builder/import/nifti_header.h"
#include "builder/import/ring_simplify.h"
#include "builder/slicing/marching_squares.h"
#include "shared/input_file.h"

namespace body {
using namespace label_import;
namespace {

struct NiftiDeleter {
    void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};
using NiftiPtr = std::unique_ptr<nifti_image, NiftiDeleter>;

// Raw voxels straight to int32 labels (no double copy of the volume): value
// * slope + inter must be a non-negative integer, or with a threshold the
// label is value >= threshold. Returns the first bad voxel or SIZE_MAX.
template <typename T>
size_t convert_labels(const void* data, size_t count, double slope, double inter,
                      const std::optional<double>& threshold, std::vector<int32_t>& out, double& bad_value) {
    const T* p = static_cast<const T*>(data);
    for (size_t i = 0; i < count; ++i) {
        const double v = static_cast<double>(p[i]) * slope + inter;
        if (threshold) {
            out[i] = v >= *threshold ? 1 : 0;
            continue;
        }
        if (!std::isfinite(v) || v != std::floor(v) || v < 0.0 || v > std::numeric_limits<int32_t>::max()) {
            bad_value = v;
            return i;
        }
        out[i] = static_cast<int32_t>(v);
    }
    return SIZE_MAX;
}

bool is_integer_type(int datatype) {
    switch (datatype) {
        case DT_UINT8:
        case DT_INT8:
        case DT_INT16:
        case DT_UINT16:
        case DT_INT32:
        case DT_UINT32:
        case DT_INT64:
        case DT_UINT64: return true;
        default: return false;
    }
}

}  // namespace

// niftilib fills a short read with zeros and only warns, so a truncated file
// would pass as a volume with a missing part: check the data length first
// (also used by grey_volume.cpp).
std::string check_data_length(const nifti_image& nim) {
    const std::string file = nim.iname ? nim.iname : "";
    const uint64_t needed = static_cast<uint64_t>(nim.iname_offset > 0 ? nim.iname_offset : 0) +
                            static_cast<uint64_t>(nim.nvox) * static_cast<uint64_t>(nim.nbyper);
    uint64_t have = 0;
    if (file.size() > 3 && file.ends_with(".gz")) {
        gzFile gz = gzopen(file.c_str(), "rb");
        if (!gz) return "cannot open the image data " + file;
        std::vector<char> buffer(1 << 16);
        int n = 0;
        // On to the stream's end (up to 64 MiB past the voxels), so that a
        // cut or corrupt gzip trailer (its CRC and length) is found too.
        const uint64_t limit = needed + (uint64_t(64) << 20);
        while (have < limit && (n = gzread(gz, buffer.data(), static_cast<unsigned>(buffer.size()))) > 0) {
            have += static_cast<uint64_t>(n);
        }
        int err = Z_OK;
        const char* message = gzerror(gz, &err);
        const bool broken = n < 0 || (err != Z_OK && err != Z_STREAM_END);
        const std::string reason = broken ? std::string(message ? message : "corrupt gzip stream") : "";
        gzclose(gz);
        if (broken && have < needed) {
            return "image data truncated (gzip: " + reason + "; " + std::to_string(have) + " of " +
                   std::to_string(needed) + " bytes)";
        }
        if (broken) return "gzip stream damaged after the image data (" + reason + ")";
    } else {
        std::error_code ec;
        have = std::filesystem::file_size(file, ec);
        if (ec) return "cannot read the image data " + file + " (" + ec.message() + ")";
    }
    if (have < needed) {
        return "image data truncated (" + std::to_string(have) + " of " + std::to_string(needed) + " bytes)";
    }
    return {};
}

namespace {

// Phase 1: header, dimensions, data and the voxel -> scanner transform.
Result<LabelVolume> read_label_volume(const std::string& path, const ImportOptions& options) {
    const std::string where = path + ": ";
    auto header = read_nifti_header(path);
    if (!header) return header.error();
    const uint64_t voxels = header->data_bytes / uint64_t(header->bytes_per_voxel);
    const uint64_t need = header->data_bytes + 4 * voxels, budget = label_volume_memory_budget();
    if (need > budget) {
        return runtime_error(where + "the volume (" + std::to_string(header->dim[0]) + "x" +
                             std::to_string(header->dim[1]) + "x" + std::to_string(header->dim[2]) + ") needs " +
                             std::to_string(need >> 20) + " MiB, over the memory budget of " +
                             std::to_string(budget >> 20) + " MiB");
    }
    // Deflate expands at most ~1032:1, so a .gz cannot hold more than that.
    if (auto size = regular_file_size(path);
        size && path.ends_with(".gz") && header->single_file && header->data_bytes / 1100 > *size) {
        return input_error(where + "declares " + std::to_string(header->data_bytes) + " bytes of voxels, more than " +
                           std::to_string(*size) + " compressed bytes can hold");
    }
    nifti_set_debug_level(0);
    NiftiPtr nim(nifti_image_read(path.c_str(), 0));
    if (!nim) return input_error(where + "not a readable NIfTI-1/ANALYZE header (corrupt, truncated or wrong dims)");
    for (int d = 1; d <= 3; ++d) {
        if (nim->dim[d] < 1)
            return input_error(where + "wrong dims: dim[" + std::to_string(d) + "] = " + std::to_string(nim->dim[d]));
    }
    for (int d = 4; d <= nim->dim[0] && d <= 7; ++d) {
        if (nim->dim[d] > 1) {
            return input_error(where + "wrong dims: a label volume is 3-D, but dim[" + std::to_string(d) +
                               "] = " + std::to_string(nim->dim[d]));
        }
    }
    const bool integral = is_integer_type(nim->datatype);
    const bool real = nim->datatype == DT_FLOAT32 || nim->datatype == DT_FLOAT64;
    if (!integral && !real) {
        return input_error(where + "unsupported data type " + nifti_datatype_string(nim->datatype) +
                           " (labels need an integer type)");
    }
    if (real && !options.threshold) {
        return input_error(where + "non-integer data type " + nifti_datatype_string(nim->datatype) +
                           " without --threshold: pass --threshold T to extract value >= T");
    }
    if (const std::string reason = check_data_length(*nim); !reason.empty()) return input_error(where + reason);
    if (nifti_image_load(nim.get()) != 0 || !nim->data) {
        return input_error(where + "image data truncated or unreadable (expected " +
                           std::to_string(nim->nvox * static_cast<size_t>(nim->nbyper)) + " bytes)");
    }
    LabelVolume vol;
    for (int d = 0; d < 3; ++d) vol.dim[d] = static_cast<size_t>(nim->dim[d + 1]);
    const size_t count = vol.dim[0] * vol.dim[1] * vol.dim[2];

    double slope = nim->scl_slope, inter = nim->scl_inter;
    if (slope == 0.0 || !std::isfinite(slope) || !std::isfinite(inter)) slope = 1.0, inter = 0.0;
    try {
        vol.labels.resize(count);
    } catch (const std::bad_alloc&) {
        return runtime_error(where + "out of memory for " + std::to_string(count) + " voxels");
    }
    double bad_value = 0.0;
    size_t bad = SIZE_MAX;
    const auto& th = options.threshold;
    switch (nim->datatype) {
        case DT_UINT8: bad = convert_labels<uint8_t>(nim->data, count, slope, inter, th, vol.labels, bad_value); break;
        case DT_INT8: bad = convert_labels<int8_t>(nim->data, count, slope, inter, th, vol.labels, bad_value); break;
        case DT_INT16: bad = convert_labels<int16_t>(nim->data, count, slope, inter, th, vol.labels, bad_value); break;
        case DT_UINT16:
            bad = convert_labels<uint16_t>(nim->data, count, slope, inter, th, vol.labels, bad_value);
            break;
        case DT_INT32: bad = convert_labels<int32_t>(nim->data, count, slope, inter, th, vol.labels, bad_value); break;
        case DT_UINT32:
            bad = convert_labels<uint32_t>(nim->data, count, slope, inter, th, vol.labels, bad_value);
            break;
        case DT_INT64: bad = convert_labels<int64_t>(nim->data, count, slope, inter, th, vol.labels, bad_value); break;
        case DT_UINT64:
            bad = convert_labels<uint64_t>(nim->data, count, slope, inter, th, vol.labels, bad_value);
            break;
        case DT_FLOAT32: bad = convert_labels<float>(nim->data, count, slope, inter, th, vol.labels, bad_value); break;
        default: bad = convert_labels<double>(nim->data, count, slope, inter, th, vol.labels, bad_value); break;
    }
    nifti_image_unload(nim.get());  // the raw data is no longer needed
    if (bad != SIZE_MAX) {
        return input_error(where + "voxel " + std::to_string(bad) + " has value " + std::to_string(bad_value) +
                           ", not a label (non-negative integer); use --threshold for masks");
    }

    const mat44* m = nullptr;
    if (nim->sform_code > 0)
        m = &nim->sto_xyz;
    else if (nim->qform_code > 0)
        m = &nim->qto_xyz;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) {
            if (m)
                vol.affine[r][c] = m->m[r][c];
            else
                vol.affine[r][c] = (r == c) ? std::fabs(nim->pixdim[r + 1] > 0 ? nim->pixdim[r + 1] : 1.0f) : 0.0;
        }
    }
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) {
            if (!std::isfinite(vol.affine[r][c])) return input_error(where + "non-finite voxel-to-scanner transform");
        }
    }
    const double det = vol.affine[0][0] * (vol.affine[1][1] * vol.affine[2][2] - vol.affine[1][2] * vol.affine[2][1]) -
                       vol.affine[0][1] * (vol.affine[1][0] * vol.affine[2][2] - vol.affine[1][2] * vol.affine[2][0]) +
                       vol.affine[0][2] * (vol.affine[1][0] * vol.affine[2][1] - vol.affine[1][1] * vol.affine[2][0]);
    if (!(std::abs(det) > 0.0)) return input_error(where + "singular voxel-to-scanner transform (voxels of no volume)");
    for (int c = 0; c < 3; ++c)
        vol.spacing[c] = std::sqrt(vol.affine[0][c] * vol.affine[0][c] + vol.affine[1][c] * vol.affine[1][c] +
                                   vol.affine[2][c] * vol.affine[2][c]);
    return vol;
}

// Phase 2: the output frame of a slicing axis (see import.h).
Result<SliceFrame> slice_frame(const LabelVolume& vol, int axis, const std::string& path) {
    SliceFrame f;
    f.axis = axis;
    f.u = (axis + 1) % 3;
    f.v = (axis + 2) % 3;
    for (int c = 0; c < 3; ++c) f.col[c] = Vec3(vol.affine[0][c], vol.affine[1][c], vol.affine[2][c]);
    f.origin = Vec3(vol.affine[0][3], vol.affine[1][3], vol.affine[2][3]);
    const Vec3 normal = glm::cross(f.col[f.u], f.col[f.v]);
    const double len = glm::length(normal);
    if (!(len > 0.0)) return input_error(path + ": singular voxel-to-scanner transform");
    int a = 0;
    for (int k = 1; k < 3; ++k) {
        if (std::fabs(normal[k]) > std::fabs(normal[a])) a = k;
    }
    const double off = std::hypot(normal[(a + 1) % 3], normal[(a + 2) % 3]);
    if (off <= 1e-6 * len) {
        f.n = Vec3(0.0), f.e1 = Vec3(0.0), f.e2 = Vec3(0.0);
        f.n[a] = 1.0, f.e1[(a + 1) % 3] = 1.0, f.e2[(a + 2) % 3] = 1.0;
    } else {
        f.oblique = true;
        f.n = normal / len;
        f.e1 = glm::normalize(f.col[f.u]);
        f.e2 = glm::cross(f.n, f.e1);
    }
    return f;
}

}  // namespace

// Phase 3: one slice's rings (label_volume.h).
void label_import::finish_rings(const SliceFrame& f, double u0, double v0, size_t k, const ImportOptions& o,
                                std::vector<std::vector<Vec2>>& rings, LabelResult& out) {
    if (o.min_area > 0.0) {
        std::erase_if(rings, [&](const std::vector<Vec2>& r) {
            return std::fabs(signed_area2(r.data(), r.size())) < 2.0 * o.min_area;
        });
    }
    if (rings.empty()) return;
    simplify_rings(rings, o.tolerance);
    for (auto& ring : rings) {
        for (Vec2& p : ring) p = f.in_plane(u0 + p.x, v0 + p.y, static_cast<double>(k));
    }
    out.slices.emplace_back(k, std::move(rings));
    rings = {};
}

namespace {

// One label, all its slices: the voxel-face boundary of its mask.
void extract_label(const LabelVolume& vol, const SliceFrame& f, int32_t label, const Extent& e, const ImportOptions& o,
                   LabelResult& out) {
    out.label = label;
    const size_t u0 = e.lo[f.u], v0 = e.lo[f.v];
    const size_t w = e.hi[f.u] - u0 + 1, h = e.hi[f.v] - v0 + 1;
    std::vector<uint8_t> mask(w * h);
    std::vector<std::vector<Vec2>> rings;
    size_t idx[3];
    for (size_t k = e.lo[f.axis]; k <= e.hi[f.axis]; ++k) {
        if (k % static_cast<size_t>(o.step) != 0) continue;
        idx[f.axis] = k;
        bool any = false;
        for (size_t y = 0; y < h; ++y) {
            idx[f.v] = v0 + y;
            for (size_t x = 0; x < w; ++x) {
                idx[f.u] = u0 + x;
                const bool in = vol.labels[vol.index(idx[0], idx[1], idx[2])] == label;
                mask[y * w + x] = in;
                any |= in;
            }
        }
        if (!any) continue;
        trace_mask_boundaries(mask, w, h, rings);
        finish_rings(f, static_cast<double>(u0), static_cast<double>(v0), k, o, rings, out);
    }
}

// Distinct colours for labels the table does not colour (golden-ratio hues).
Vec3 palette_color(int64_t label) {
    const double h = std::fmod(static_cast<double>(label) * 0.618033988749895, 1.0) * 6.0;
    const double s = 0.55, v = 0.9;
    const int i = static_cast<int>(h);
    const double fr = h - i, p = v * (1 - s), q = v * (1 - s * fr), t = v * (1 - s * (1 - fr));
    switch (i % 6) {
        case 0: return {v, t, p};
        case 1: return {q, v, p};
        case 2: return {p, v, t};
        case 3: return {p, q, v};
        case 4: return {t, p, v};
        default: return {v, p, q};
    }
}

Result<LabelTable> find_label_table(const std::string& path, const ImportOptions& options) {
    LabelTable table;
    if (!options.labels_path.empty()) {
        auto t = read_label_table(options.labels_path);
        if (!t) return t.error();
        table = std::move(*t);
    }
    // Beside the volume: <v>.nii.gz -> <v>.nii.txt, <v>.nii.lut, <v>.txt, <v>.lut.
    std::string base = path;
    if (base.size() > 3 && base.ends_with(".gz")) base.resize(base.size() - 3);
    std::vector<std::string> candidates = {base + ".txt", base + ".lut"};
    if (base.ends_with(".nii")) {
        const std::string stem = base.substr(0, base.size() - 4);
        candidates.push_back(stem + ".txt");
        candidates.push_back(stem + ".lut");
    }
    for (const std::string& c : candidates) {
        if (c == options.labels_path || !std::filesystem::is_regular_file(c)) continue;
        if (!options.labels_path.empty() && !c.ends_with(".lut")) continue;  // explicit names win
        auto t = read_label_table(c);
        if (!t) {
            if (options.note) options.note("ignoring " + t.error().message);
            continue;
        }
        merge_label_table(table, *t);
    }
    return table;
}

// Extents of every label in one pass.
std::map<int32_t, Extent> label_extents(const LabelVolume& vol) {
    std::map<int32_t, Extent> extents;
    for (size_t k = 0; k < vol.dim[2]; ++k) {
        for (size_t j = 0; j < vol.dim[1]; ++j) {
            for (size_t i = 0; i < vol.dim[0]; ++i) {
                const int32_t l = vol.labels[vol.index(i, j, k)];
                if (l == 0) continue;
                Extent& e = extents[l];
                const size_t at[3] = {i, j, k};
                for (int d = 0; d < 3; ++d) e.lo[d] = std::min(e.lo[d], at[d]), e.hi[d] = std::max(e.hi[d], at[d]);
                ++e.voxels;
            }
        }
    }
    return extents;
}

// The labels to extract, increasing: `--only` (each must occur) or every
// label present, with a note for named table labels that have no voxels.
Result<std::vector<int32_t>> labels_to_extract(const std::string& path, const ImportOptions& options,
                                               const std::map<int32_t, Extent>& extents, const LabelTable& table) {
    std::vector<int32_t> labels;
    if (!options.only.empty()) {
        for (int64_t l : options.only) {
            if (l <= 0 || l > std::numeric_limits<int32_t>::max() || !extents.count(static_cast<int32_t>(l))) {
                return input_error(path + ": label " + std::to_string(l) + " (--only) does not occur in the volume");
            }
            labels.push_back(static_cast<int32_t>(l));
        }
        std::sort(labels.begin(), labels.end());
        labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    } else {
        for (const auto& [l, e] : extents) labels.push_back(l);
        if (options.note && !options.threshold) {
            for (const auto& [l, entry] : table.entries) {
                if (l > 0 && !entry.name.empty() && !extents.count(static_cast<int32_t>(l))) {
                    options.note(path + ": label " + std::to_string(l) + " (" + entry.name + ") has no voxels");
                }
            }
        }
    }
    if (labels.empty()) return input_error(path + ": no labelled voxels (every voxel is 0)");
    return labels;
}

// Runs fn(i) for i in [0, n) on `jobs` threads; progress(done) from the
// calling thread as items finish.
void run_parallel(size_t n, int jobs_option, const std::function<void(size_t)>& fn,
                  const std::function<void(size_t)>& progress) {
    if (n == 0) return;
    std::atomic<size_t> next{0};
    size_t done = 0;
    std::mutex mutex;
    std::condition_variable cv;
    auto work = [&] {
        for (size_t i = next++; i < n; i = next++) {
            fn(i);
            std::lock_guard lock(mutex);
            ++done;
            cv.notify_one();
        }
    };
    const size_t jobs = std::clamp<size_t>(static_cast<size_t>(std::max(jobs_option, 1)), 1, n);
    std::vector<std::thread> threads;
    for (size_t t = 0; jobs > 1 && t < jobs; ++t) threads.emplace_back(work);
    if (jobs == 1) {
        for (size_t i = 0; i < n; ++i) {
            fn(i);
            if (progress) progress(i + 1);
        }
    } else {
        std::unique_lock lock(mutex);
        size_t reported = 0;
        while (reported < n) {
            cv.wait(lock, [&] { return done > reported; });
            reported = done;
            if (progress) {
                lock.unlock();
                progress(reported);
                lock.lock();
            }
        }
    }
    for (auto& t : threads) t.join();
}

// Phase 4: structures in parallel; results in label order, progress reported
// from the calling thread. With --label-smooth, labels the full blur would
// shrink or split (thin) are smoothed less, and they and the labels around
// them traced again against each other (extract_label_among_thin).
std::vector<LabelResult> extract_labels(const LabelVolume& vol, const SliceFrame& frame,
                                        const std::vector<int32_t>& labels, std::map<int32_t, Extent>& extents,
                                        const ImportOptions& options) {
    std::vector<LabelResult> results(labels.size());
    std::vector<ThinLabel> levels(labels.size());
    const bool smooth = options.label_smooth > 0.0;
    auto progress = [&](size_t done) {
        if (options.progress) options.progress(done, labels.size());
    };
    // The background's full-width blur is the same for every label: made once.
    Extent labelled;
    for (int32_t label : labels) {
        const Extent& e = extents.at(label);
        for (int d = 0; d < 3; ++d) labelled.lo[d] = std::min(labelled.lo[d], e.lo[d]);
        for (int d = 0; d < 3; ++d) labelled.hi[d] = std::max(labelled.hi[d], e.hi[d]);
    }
    const BackgroundBlur bg =
        smooth && !labels.empty() ? blur_background(vol, labelled, options.label_smooth) : BackgroundBlur{};
    run_parallel(
        labels.size(), options.jobs,
        [&](size_t i) {
            if (smooth)
                levels[i] =
                    extract_label_smoothed(vol, frame, labels[i], extents.at(labels[i]), options, bg, results[i]);
            else
                extract_label(vol, frame, labels[i], extents.at(labels[i]), options, results[i]);
        },
        progress);
    std::map<int32_t, ThinLabel> thin;
    for (size_t i = 0; i < labels.size(); ++i)
        if (levels[i].level > 0) thin[labels[i]] = levels[i];
    // Islands of the final rings (a piece cut off where a blur closes a
    // neck, a hole closed off into a cavity, rings joined only through a
    // speck since dropped) dropped: each would be a mesh piece of its own.
    auto drop_islands = [&] {
        if (!smooth) return;
        run_parallel(labels.size(), options.jobs,
                     [&](size_t i) { drop_small_islands(frame, options, double(kMinPiece), results[i]); }, {});
    };
    if (thin.empty()) {
        drop_islands();
        return results;
    }
    std::vector<size_t> again;
    for (size_t i = 0; i < labels.size(); ++i) {
        const Extent& e = extents.at(labels[i]);
        if (levels[i].level > 0 || box_meets_thin(vol, e, labels[i], thin, options.label_smooth)) again.push_back(i);
    }
    run_parallel(again.size(), options.jobs,
                 [&](size_t a) {
                     const size_t i = again[a];
                     extract_label_among_thin(vol, frame, labels[i], extents.at(labels[i]), options, levels[i], thin,
                                              bg, results[i]);
                 },
                 {});
    drop_islands();
    return results;
}

// Phase 5: assemble the stack.
ContourStack assemble_stack(const std::string& path, const ImportOptions& options,
                            const std::vector<LabelResult>& results, const LabelTable& table, const SliceFrame& frame) {
    ContourStack stack;
    std::map<size_t, Slice> slices;
    std::map<std::string, int> used_ids;
    for (const LabelResult& r : results) {
        if (r.slices.empty()) {
            if (options.note) {
                options.note(path + ": label " + std::to_string(r.label) + " has no voxels on the sampled slices");
            }
            continue;
        }
        StructureInfo s;
        auto it = table.entries.find(r.label);
        const bool named = it != table.entries.end() && !it->second.name.empty();
        if (options.threshold && !named)
            s.name = "mask";
        else
            s.name = named ? it->second.name : "label " + std::to_string(r.label);
        s.id = named ? structure_id_from_name(it->second.name)
                     : (options.threshold ? "mask" : "label_" + std::to_string(r.label));
        if (used_ids[s.id]++ > 0) s.id += "_" + std::to_string(r.label);
        s.color = (it != table.entries.end() && it->second.color) ? *it->second.color : palette_color(r.label);
        for (const auto& [k, rings] : r.slices) {
            Slice& slice = slices[k];
            slice.z = frame.z(static_cast<double>(k));
            for (const auto& ring : rings) slice.contours.push_back(Contour{ring, s.id, 0, 0});
        }
        stack.structures.push_back(std::move(s));
    }
    for (auto& [k, s] : slices) stack.slices.push_back(std::move(s));
    stack.ras_axes = std::array<Vec3, 3>{frame.e1, frame.e2, frame.n};  // NIfTI scanner space is RAS+
    stack.voxel = std::max(glm::length(frame.col[frame.u]), glm::length(frame.col[frame.v]));
    std::sort(stack.slices.begin(), stack.slices.end(), [](const Slice& a, const Slice& b) { return a.z < b.z; });
    for (size_t si = 0; si < stack.slices.size(); ++si) {
        stack.slices[si].source_index = si;
        for (size_t ci = 0; ci < stack.slices[si].contours.size(); ++ci) {
            stack.slices[si].contours[ci].source_slice = si;
            stack.slices[si].contours[ci].source_contour = ci;
        }
    }
    return stack;
}

}  // namespace

Result<ContourStack> import_nifti_labels(const std::string& path, const ImportOptions& options) {
    if (options.axis < 0 || options.axis > 2) return input_error("--axis must be x, y or z");
    if (options.step < 1) return input_error("--step must be at least 1");
    if (!(options.tolerance >= 0.0) || options.tolerance > 10.0) {
        return input_error("--tolerance must be between 0 and 10 voxels");
    }
    if (!(options.min_area >= 0.0) || options.min_area > 8.0) {
        return input_error("--min-area must be between 0 and 8 voxels");
    }
    if (!(options.label_smooth >= 0.0) || options.label_smooth > 4.0) {
        return input_error("--label-smooth must be between 0 and 4 voxels");
    }
    auto vol = read_label_volume(path, options);
    if (!vol) return vol.error();
    auto frame = slice_frame(*vol, options.axis, path);
    if (!frame) return frame.error();
    auto table = find_label_table(path, options);
    if (!table) return table.error();
    if (frame->oblique && options.note) {
        options.note(path + ": slice planes are oblique to the scanner axes; output is in a rigid slice frame");
    }
    std::map<int32_t, Extent> extents = label_extents(*vol);
    auto labels = labels_to_extract(path, options, extents, *table);
    if (!labels) return labels.error();
    const std::vector<LabelResult> results = extract_labels(*vol, *frame, *labels, extents, options);
    return assemble_stack(path, options, results, *table, *frame);
}

}  // namespace body
