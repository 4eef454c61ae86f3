// DICOM RT-STRUCT -> contour stack with DCMTK's dcmdata.
// - DICOM PS3.3 C.8.8.5 (Structure Set Module) and C.8.8.6 (ROI Contour
//   Module): ROIs, display colours and planar contours in patient mm.
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "builder/import/import.h"
#include "shared/input_file.h"

namespace body {
namespace {

std::string structure_id(const std::string& name, long number) {
    const std::string id = structure_id_from_name(name);
    return id.empty() ? "roi_" + std::to_string(number) : id;
}

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
    size_t i = 0;
    while (i < s.size() && s[i] == ' ') ++i;
    return s.substr(i);
}

struct Roi {
    long number = 0;
    std::string name;
    std::optional<Vec3> color;
};

struct PlanarContour {
    double z = 0.0;
    std::vector<Vec2> points;
};

// Phase 1: Structure Set ROI Sequence: number -> name.
std::map<long, Roi> read_rois(DcmDataset& ds) {
    std::map<long, Roi> rois;
    DcmSequenceOfItems* seq = nullptr;
    if (ds.findAndGetSequence(DCM_StructureSetROISequence, seq).bad() || !seq) return rois;
    for (unsigned long i = 0; i < seq->card(); ++i) {
        DcmItem* item = seq->getItem(i);
        Sint32 number = 0;
        if (!item || item->findAndGetSint32(DCM_ROINumber, number).bad()) continue;
        OFString name;
        item->findAndGetOFString(DCM_ROIName, name);
        rois[number] = Roi{number, trim(name.c_str()), std::nullopt};
    }
    return rois;
}

// Phase 2: one Contour Sequence item; an empty `reason` means a usable contour
// (or, with `skip` set, one to report and leave out).
std::string read_contour(DcmItem& item, const std::string& place, PlanarContour& out, std::string& skip) {
    OFString type;
    item.findAndGetOFString(DCM_ContourGeometricType, type);
    const std::string t = trim(type.c_str());
    if (t != "CLOSED_PLANAR") {
        skip = place + ": geometric type " + (t.empty() ? std::string("(missing)") : t) +
               ", only CLOSED_PLANAR is used; skipped";
        return {};
    }
    DcmElement* data = nullptr;
    if (item.findAndGetElement(DCM_ContourData, data).bad() || !data) return place + ": no Contour Data (3006,0050)";
    const unsigned long values = data->getVM();
    if (values % 3 != 0) return place + ": Contour Data has " + std::to_string(values) + " values, not x/y/z triples";
    const size_t n = values / 3;
    // Number of Contour Points must agree with the data (PS3.3 C.8.8.6.1).
    Sint32 declared = 0;
    if (item.findAndGetSint32(DCM_NumberOfContourPoints, declared).good() &&
        (declared < 0 || static_cast<size_t>(declared) != n)) {
        return place + ": Number of Contour Points (3006,0046) is " + std::to_string(declared) +
               " but Contour Data holds " + std::to_string(n) + " points";
    }
    std::vector<Vec3> pts(n);
    for (size_t i = 0; i < n; ++i) {
        for (size_t c = 0; c < 3; ++c) {
            Float64 v = 0.0;
            if (data->getFloat64(v, static_cast<unsigned long>(3 * i + c)).bad() || !std::isfinite(v)) {
                return place + ": Contour Data value " + std::to_string(3 * i + c) + " is not a number";
            }
            pts[i][static_cast<int>(c)] = v;
        }
    }
    if (n >= 2 && pts.front() == pts.back()) pts.pop_back();  // closed twice
    if (pts.size() < 3) {
        skip = place + ": " + std::to_string(pts.size()) + " points, too few for a closed contour; skipped";
        return {};
    }
    for (const Vec3& p : pts) {
        if (std::fabs(p.z - pts[0].z) > kSliceMergeTolerance) {
            return place + ": contour plane is not axial (z varies from " + std::to_string(pts[0].z) + " to " +
                   std::to_string(p.z) + " mm); only axial RT-STRUCT contours are supported";
        }
    }
    out.z = pts[0].z;
    out.points.clear();
    for (const Vec3& p : pts) out.points.emplace_back(p.x, p.y);
    if (signed_area2(out.points.data(), out.points.size()) == 0.0) {
        skip = place + ": zero-area contour; skipped";
    }
    return {};
}

}  // namespace

namespace {
Result<ContourStack> read_rtstruct(const std::string& path, const ImportOptions& options);
}

// The error is one line whatever the file holds: DCMTK's texts and the file's own strings
// (modality, ROI names) may carry control characters.
Result<ContourStack> import_rtstruct(const std::string& path, const ImportOptions& options) {
    auto stack = read_rtstruct(path, options);
    if (stack.ok()) return stack;
    Error e = stack.error();
    e.message = escape_control_characters(e.message);
    return e;
}

namespace {
Result<ContourStack> read_rtstruct(const std::string& path, const ImportOptions& options) {
    const std::string where = path + ": ";
    if (!std::filesystem::is_regular_file(path)) return input_error(where + "no such file");
    OFLog::configure(OFLogger::FATAL_LOG_LEVEL);  // errors come back as our message, not DCMTK's log
    DcmFileFormat file;
    const OFCondition loaded = file.loadFile(path.c_str());
    if (loaded.bad()) return input_error(where + "not a readable DICOM file (" + loaded.text() + ")");
    DcmDataset* ds = file.getDataset();
    if (!ds) return input_error(where + "no DICOM dataset");
    OFString modality;
    ds->findAndGetOFString(DCM_Modality, modality);
    if (trim(modality.c_str()) != "RTSTRUCT") {
        return input_error(where + "modality is '" + std::string(modality.c_str()) + "', not RTSTRUCT");
    }
    std::map<long, Roi> rois = read_rois(*ds);
    DcmSequenceOfItems* roi_contours = nullptr;
    if (ds->findAndGetSequence(DCM_ROIContourSequence, roi_contours).bad() || !roi_contours) {
        return input_error(where + "missing ROI Contour Sequence (3006,0039)");
    }

    ContourStack stack;
    std::vector<std::pair<PlanarContour, std::string>> contours;  // contour, structure id
    std::map<std::string, int> used_ids;
    for (unsigned long r = 0; r < roi_contours->card(); ++r) {
        DcmItem* item = roi_contours->getItem(r);
        if (!item) continue;
        Sint32 number = 0;
        if (item->findAndGetSint32(DCM_ReferencedROINumber, number).bad()) {
            return input_error(where + "ROI Contour item " + std::to_string(r) + ": no Referenced ROI Number");
        }
        if (!options.only.empty() &&
            std::find(options.only.begin(), options.only.end(), number) == options.only.end()) {
            continue;
        }
        Roi roi = rois.count(number) ? rois[number] : Roi{number, "", std::nullopt};
        if (roi.name.empty()) roi.name = std::string("ROI ").append(std::to_string(number));
        const std::string roi_place = where + "ROI " + std::to_string(number) + " '" + roi.name + "'";
        Sint32 rgb[3];
        bool has_color = true;
        for (unsigned long c = 0; c < 3; ++c) {
            if (item->findAndGetSint32(DCM_ROIDisplayColor, rgb[c], c).bad()) has_color = false;
        }
        StructureInfo s;
        s.name = roi.name;
        s.id = structure_id(roi.name, number);
        if (used_ids[s.id]++ > 0) s.id.append("_").append(std::to_string(number));
        if (has_color) {
            s.color = Vec3(std::clamp(rgb[0], 0, 255), std::clamp(rgb[1], 0, 255), std::clamp(rgb[2], 0, 255)) / 255.0;
        }
        DcmSequenceOfItems* seq = nullptr;
        size_t kept = 0;
        if (item->findAndGetSequence(DCM_ContourSequence, seq).good() && seq) {
            for (unsigned long c = 0; c < seq->card(); ++c) {
                DcmItem* ci = seq->getItem(c);
                if (!ci) continue;
                const std::string place = roi_place + " contour " + std::to_string(c);
                PlanarContour pc;
                std::string skip;
                const std::string reason = read_contour(*ci, place, pc, skip);
                if (!reason.empty()) return input_error(reason);
                if (!skip.empty()) {
                    if (options.note) options.note(skip);
                    continue;
                }
                contours.emplace_back(std::move(pc), s.id);
                ++kept;
            }
        }
        if (kept == 0) {
            if (options.note) options.note(roi_place + ": no closed planar contours; structure left out");
            continue;
        }
        stack.structures.push_back(std::move(s));
    }
    if (stack.structures.empty()) return input_error(where + "no ROI has CLOSED_PLANAR contours");

    // Group by real z: sorted, merged within kSliceMergeTolerance, no resampling.
    std::stable_sort(contours.begin(), contours.end(),
                     [](const auto& a, const auto& b) { return a.first.z < b.first.z; });
    for (auto& [pc, id] : contours) {
        if (stack.slices.empty() || pc.z - stack.slices.back().z >= kSliceMergeTolerance) {
            stack.slices.push_back(Slice{pc.z, {}, stack.slices.size()});
        }
        Slice& slice = stack.slices.back();
        slice.contours.push_back(Contour{std::move(pc.points), id, slice.source_index, slice.contours.size()});
    }
    // DICOM patient coordinates are LPS+: x toward the patient's left, y posterior.
    stack.ras_axes = std::array<Vec3, 3>{Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
    if (options.progress) options.progress(stack.structures.size(), stack.structures.size());
    return stack;
}

}  // namespace

}  // namespace body
