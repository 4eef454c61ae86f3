// Reading and writing `*.contours.json` with nlohmann-json.
//
// Reading streams: a SAX handler driven by nlohmann::json::sax_parse builds the
// contour stack straight from the parser's events and never holds a DOM, so a
// file costs about its points (16 bytes each) plus the lexer's token buffer;
// read_contour_stack feeds the parser from the file in place of a copy of it.
//
// The handler keeps a stack of frames, one per open JSON container, with the
// meaning of each (root, structures, structure, color, slices, slice, contours,
// contour, points, point, or skipped). Members may come in any order, so each
// container's checks run when it closes, and a contour's structure label is
// checked once the structure list is known. The checks and messages are those
// of the document reader this replaced; when a file has several problems the
// one reported is the one that reader reported: a syntax error first (with its
// byte offset and the place it interrupted), then format, version, units,
// structures, and the first bad slice/contour/point in file order. Once an
// error is known nothing more is stored; parsing goes on to the end only to
// find a syntax error, which takes precedence. A number too large for a
// double ("1e999") is reported where it stands: slice, contour and point index
// and byte offset.
// The "links" section (version 2) is small: its value is captured as a JSON
// tree by nlohmann's own DOM builder and read by contour_links.cpp once the
// slices are known.
// Why one file: the reader is one state machine whose frames, slots and error
// order are only understood together; the links section's own reading and
// writing live in contour_links.cpp.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "builder/contours/contour_links.h"
#include "builder/contours/contour_stack.h"
#include "shared/atomic_file.h"
#include "shared/input_file.h"

namespace body {
namespace {

using nlohmann::json;

std::string place(const std::string& path, size_t slice) { return path + ": slice " + std::to_string(slice); }
std::string place(const std::string& path, size_t slice, size_t contour) {
    return place(path, slice) + " contour " + std::to_string(contour);
}

// What an open container is.
enum class Frame : uint8_t {
    Root,
    Structures,
    Structure,
    Color,
    Slices,
    Slice,
    Contours,
    Contour,
    Points,
    Point,
    Skip
};

// The member an object frame is reading.
enum class Member : uint8_t {
    Other,
    Format,
    Version,
    Units,
    Voxel,
    Structures,
    Slices,
    Links,
    Id,
    Name,
    Color,
    Z,
    Contours,
    Points,
    Label
};

// What the next value is, from the innermost frame.
enum class Slot : uint8_t {
    Document,
    Format,
    Version,
    Units,
    Voxel,
    StructureList,
    SliceList,
    Links,
    Ignored,
    StructureItem,
    Id,
    Name,
    Color,
    ColorComponent,
    SliceItem,
    Z,
    ContourList,
    ContourItem,
    PointList,
    Label,
    PointItem,
    Coordinate
};

struct OpenFrame {
    Frame kind;
    Member member = Member::Other;  // objects: the member being read
    size_t index = 0;               // position in the parent array
    size_t count = 0;               // arrays: elements seen so far
};

// One scalar event, whatever its JSON type.
struct Scalar {
    enum Kind : uint8_t { Null, Bool, Number, String } kind;
    double number = 0.0;
    bool is_version = false;  // an integer equal to a supported version (1 or 2)
    const std::string* text = nullptr;
};

// Orders errors so that the one the document reader reported wins: category
// (format, version, units, structures, missing slices, slice content), then
// position in the file (structure; slice, contour + 1, stage, point).
using ErrorKey = std::array<size_t, 5>;
enum Category : size_t { kFormat, kVersion, kUnits, kStructures, kSliceList, kSliceContent, kLinks };

// Long tokens (a fuzzer's megabyte of digits) are cut in messages.
std::string clip(std::string s, size_t max = 120) {
    if (s.size() > max) s = s.substr(0, max) + "...";
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20) c = ' ';
    return s;
}

// "[json.exception.parse_error.101] parse error at line 1, column 2: syntax error ..." -> "syntax error ...".
std::string parser_reason(const std::string& what) {
    std::string s = what;
    if (!s.empty() && s[0] == '[') {
        size_t close = s.find("] ");
        if (close != std::string::npos) s = s.substr(close + 2);
    }
    if (s.starts_with("parse error at line")) {
        size_t colon = s.find(": ");
        if (colon != std::string::npos) s = s.substr(colon + 2);
    }
    return clip(s, 200);
}

class StackReader {
public:
    explicit StackReader(const std::string& path) : path_(path) { frames_.reserve(16); }

    // --- nlohmann SAX interface ---
    bool null() { return links_depth_ ? links_->null() : scalar({Scalar::Null}); }
    bool boolean(bool b) { return links_depth_ ? links_->boolean(b) : scalar({Scalar::Bool}); }
    bool number_integer(json::number_integer_t v) {
        return links_depth_ ? links_->number_integer(v) : scalar({Scalar::Number, double(v), v == 1 || v == 2});
    }
    bool number_unsigned(json::number_unsigned_t v) {
        return links_depth_ ? links_->number_unsigned(v) : scalar({Scalar::Number, double(v), v == 1 || v == 2});
    }
    bool number_float(json::number_float_t v, const std::string& s) {
        return links_depth_ ? links_->number_float(v, s) : scalar({Scalar::Number, v});
    }
    bool string(std::string& s) { return links_depth_ ? links_->string(s) : scalar({Scalar::String, 0.0, false, &s}); }
    bool binary(json::binary_t&) { return scalar({Scalar::Null}); }
    bool start_object(size_t n) { return links_depth_ ? (++links_depth_, links_->start_object(n)) : open(true, n); }
    bool start_array(size_t n) { return links_depth_ ? (++links_depth_, links_->start_array(n)) : open(false, n); }
    bool end_object() { return links_depth_ ? (--links_depth_, links_->end_object()) : close(); }
    bool end_array() { return links_depth_ ? (--links_depth_, links_->end_array()) : close(); }
    bool key(std::string& k) {
        if (links_depth_) return links_->key(k);
        OpenFrame& f = frames_.back();
        f.member = classify(f.kind, k);
        return true;
    }
    bool parse_error(size_t byte, const std::string& token, const nlohmann::detail::exception& e) {
        syntax_error_ = describe_parse_error(byte, token, e);
        return false;
    }

    // After sax_parse: the stack or the error that matters most.
    Result<ContourStack> finish(bool parsed) {
        if (!parsed) return input_error(syntax_error_.empty() ? path_ + ": invalid JSON" : syntax_error_);
        if (error_) return input_error(error_->second);
        std::stable_sort(raw_.begin(), raw_.end(), [](const Slice& a, const Slice& b) { return a.z < b.z; });
        for (Slice& s : raw_) {
            if (!stack_.slices.empty() && s.z - stack_.slices.back().z < kSliceMergeTolerance) {
                auto& dst = stack_.slices.back().contours;
                std::move(s.contours.begin(), s.contours.end(), std::back_inserter(dst));
            } else {
                stack_.slices.push_back(std::move(s));
            }
        }
        if (links_) {
            auto links = parse_link_overrides(links_json_, path_);
            if (!links) return links.error();
            stack_.links = std::move(*links);
            if (auto checked = check_link_overrides(stack_, path_); !checked) return checked.error();
        }
        return std::move(stack_);
    }

private:
    static Member classify(Frame frame, const std::string& k) {
        switch (frame) {
            case Frame::Root:
                if (k == "format") return Member::Format;
                if (k == "version") return Member::Version;
                if (k == "units") return Member::Units;
                if (k == "voxel") return Member::Voxel;
                if (k == "structures") return Member::Structures;
                if (k == "slices") return Member::Slices;
                if (k == "links") return Member::Links;
                break;
            case Frame::Structure:
                if (k == "id") return Member::Id;
                if (k == "name") return Member::Name;
                if (k == "color") return Member::Color;
                break;
            case Frame::Slice:
                if (k == "z") return Member::Z;
                if (k == "contours") return Member::Contours;
                break;
            case Frame::Contour:
                if (k == "points") return Member::Points;
                if (k == "structure") return Member::Label;
                break;
            default: break;
        }
        return Member::Other;
    }

    Slot next_slot() const {
        if (frames_.empty()) return Slot::Document;
        const OpenFrame& f = frames_.back();
        switch (f.kind) {
            case Frame::Root:
                switch (f.member) {
                    case Member::Format: return Slot::Format;
                    case Member::Version: return Slot::Version;
                    case Member::Units: return Slot::Units;
                    case Member::Voxel: return Slot::Voxel;
                    case Member::Structures: return Slot::StructureList;
                    case Member::Slices: return Slot::SliceList;
                    case Member::Links: return Slot::Links;
                    default: return Slot::Ignored;
                }
            case Frame::Structures: return Slot::StructureItem;
            case Frame::Structure:
                switch (f.member) {
                    case Member::Id: return Slot::Id;
                    case Member::Name: return Slot::Name;
                    case Member::Color: return Slot::Color;
                    default: return Slot::Ignored;
                }
            case Frame::Color: return Slot::ColorComponent;
            case Frame::Slices: return Slot::SliceItem;
            case Frame::Slice:
                switch (f.member) {
                    case Member::Z: return Slot::Z;
                    case Member::Contours: return Slot::ContourList;
                    default: return Slot::Ignored;
                }
            case Frame::Contours: return Slot::ContourItem;
            case Frame::Contour:
                switch (f.member) {
                    case Member::Points: return Slot::PointList;
                    case Member::Label: return Slot::Label;
                    default: return Slot::Ignored;
                }
            case Frame::Points: return Slot::PointItem;
            case Frame::Point: return Slot::Coordinate;
            case Frame::Skip: return Slot::Ignored;
        }
        return Slot::Ignored;
    }

    // Index the next value takes in its array (0 outside arrays); counts it.
    size_t take_index() {
        if (frames_.empty()) return 0;
        return frames_.back().count++;
    }

    bool better(const ErrorKey& key) const { return !error_ || key < error_->first; }
    void fail(const ErrorKey& key, std::string message) {
        if (better(key)) error_.emplace(key, std::move(message));
    }
    ErrorKey point_key(size_t k) const { return {kSliceContent, slice_index_, contour_index_ + 1, 0, k}; }
    ErrorKey contour_key(size_t stage) const { return {kSliceContent, slice_index_, contour_index_ + 1, stage, 0}; }
    ErrorKey slice_key(size_t stage) const { return {kSliceContent, slice_index_, 0, stage, 0}; }
    std::string contour_place() const { return place(path_, slice_index_, contour_index_); }

    // --- scalars ---
    bool scalar(const Scalar& v) {
        const Slot slot = next_slot();
        const size_t index = take_index();
        const bool number = v.kind == Scalar::Number, text = v.kind == Scalar::String;
        switch (slot) {
            case Slot::Document: not_a_stack(); break;
            case Slot::Format: format_ok_ = text && *v.text == "bodygen.contours"; break;
            case Slot::Version: version_ok_ = v.is_version; break;
            case Slot::Units:
                if (text)
                    stack_.units = *v.text;
                else
                    fail({kUnits, 0, 0, 0, 0}, path_ + ": \"units\" must be a string");
                break;
            case Slot::Voxel:
                if (number && std::isfinite(v.number) && v.number > 0.0)
                    stack_.voxel = v.number;
                else
                    bad_voxel();
                break;
            case Slot::StructureList: structures_not_array(); break;
            case Slot::SliceList: slices_ok_ = false; break;
            case Slot::Links: fail({kLinks, 0, 0, 0, 0}, path_ + ": \"links\" must be an array"); break;
            case Slot::Ignored: break;
            case Slot::StructureItem: structure_needs_id(index); break;
            case Slot::Id:
                id_state_ = text ? IdState::String : IdState::Wrong;
                if (text) structure_.id = *v.text;
                break;
            case Slot::Name:
                name_ok_ = text;
                if (text) name_ = *v.text;
                break;
            case Slot::Color: color_problem_ = "color must be [r, g, b]"; break;  // not an array
            case Slot::ColorComponent: color_component(v, index); break;
            case Slot::SliceItem:
                slice_index_ = index, fail(slice_key(0), place(path_, index) + ": needs a numeric \"z\"");
                break;
            case Slot::Z:
                z_ok_ = number;
                z_ = v.number;
                break;
            case Slot::ContourList: contours_ok_ = false; break;
            case Slot::ContourItem:
                contour_index_ = index, fail(contour_key(0), contour_place() + ": needs a \"points\" array");
                break;
            case Slot::PointList:
                points_ok_ = false, fail(contour_key(0), contour_place() + ": needs a \"points\" array");
                break;
            case Slot::Label:
                label_state_ = text ? IdState::String : IdState::Wrong;
                if (text) contour_.structure = *v.text;
                break;
            case Slot::PointItem: bad_point(index); break;
            case Slot::Coordinate:
                if (number && index < 2)
                    xy_[index] = v.number;
                else
                    point_ok_ = false;
                break;
        }
        return true;
    }

    void not_a_stack() {
        fail({kFormat, 0, 0, 0, 0}, path_ + ": not a contour stack (\"format\" must be \"bodygen.contours\")");
    }
    void bad_voxel() { fail({kUnits, 1, 0, 0, 0}, path_ + ": \"voxel\" must be a positive number"); }
    void structures_not_array() { fail({kStructures, 0, 0, 0, 0}, path_ + ": \"structures\" must be an array"); }
    void structure_needs_id(size_t i) {
        fail({kStructures, i, 0, 0, 0}, path_ + ": structure " + std::to_string(i) + ": needs a string \"id\"");
    }
    void bad_point(size_t k) {
        if (better(point_key(k)))
            fail(point_key(k), contour_place() + ": point " + std::to_string(k) + " must be [x, y]");
    }
    void color_component(const Scalar& v, size_t i) {
        if (color_problem_) return;  // the first bad component is the one reported
        if (v.kind != Scalar::Number)
            color_problem_ = "color must be [r, g, b] numbers";
        else if (!(v.number >= 0.0 && v.number <= 1.0))
            color_problem_ = "color components must lie in [0, 1]";
        else if (i < 3)
            color_[int(i)] = v.number;
    }

    // --- containers ---
    bool open(bool object, size_t elements) {
        const Slot slot = next_slot();
        const size_t index = take_index();
        Frame kind = Frame::Skip;
        switch (slot) {
            case Slot::Links:  // the value goes to the DOM builder until it closes
                links_json_ = json();
                links_.emplace(links_json_, /*allow_exceptions=*/false);
                links_depth_ = 1;
                return object ? links_->start_object(elements) : links_->start_array(elements);
            case Slot::Document:
                if (object)
                    kind = Frame::Root;
                else
                    not_a_stack();
                break;
            case Slot::StructureList:
                if (object)
                    structures_not_array();
                else
                    kind = Frame::Structures, stack_.structures.clear(), structures_done_ = false;
                break;
            case Slot::StructureItem:
                if (!object)
                    structure_needs_id(index);
                else {
                    kind = Frame::Structure;
                    structure_ = StructureInfo{};
                    id_state_ = IdState::Absent;
                    name_ok_ = true;
                    name_.reset();
                    color_problem_.reset();
                }
                break;
            case Slot::Color:
                if (object)
                    color_problem_ = "color must be [r, g, b]";
                else
                    kind = Frame::Color, color_problem_.reset();
                break;
            case Slot::ColorComponent: color_component({Scalar::Null}, index); break;
            case Slot::SliceList:
                slices_ok_ = !object;
                if (!object) kind = Frame::Slices, raw_.clear();
                break;
            case Slot::SliceItem:
                slice_index_ = index;
                if (!object)
                    fail(slice_key(0), place(path_, index) + ": needs a numeric \"z\"");
                else {
                    kind = Frame::Slice;
                    slice_ = Slice{};
                    slice_.source_index = index;
                    z_ok_ = contours_ok_ = false;
                }
                break;
            case Slot::Z: z_ok_ = false; break;
            case Slot::ContourList:
                contours_ok_ = !object;
                if (!object) kind = Frame::Contours, slice_.contours.clear();
                break;
            case Slot::ContourItem:
                contour_index_ = index;
                if (!object)
                    fail(contour_key(0), contour_place() + ": needs a \"points\" array");
                else {
                    kind = Frame::Contour;
                    contour_ = Contour{};
                    contour_.source_slice = slice_index_;
                    contour_.source_contour = index;
                    points_ok_ = false;
                    label_state_ = IdState::Absent;
                }
                break;
            case Slot::PointList:
                points_ok_ = !object;
                if (object)
                    fail(contour_key(0), contour_place() + ": needs a \"points\" array");
                else
                    kind = Frame::Points, contour_.points.clear();
                break;
            case Slot::PointItem:
                point_index_ = index;
                if (object)
                    bad_point(index);
                else
                    kind = Frame::Point, point_ok_ = true;
                break;
            case Slot::Coordinate: point_ok_ = false; break;
            case Slot::Id: id_state_ = IdState::Wrong; break;
            case Slot::Name: name_ok_ = false; break;
            case Slot::Label: label_state_ = IdState::Wrong; break;
            case Slot::Units: fail({kUnits, 0, 0, 0, 0}, path_ + ": \"units\" must be a string"); break;
            case Slot::Voxel: bad_voxel(); break;
            case Slot::Format: format_ok_ = false; break;
            case Slot::Version: version_ok_ = false; break;
            case Slot::Ignored: break;
        }
        frames_.push_back({kind, Member::Other, index, 0});
        return true;
    }

    bool close() {
        const OpenFrame f = frames_.back();
        frames_.pop_back();
        switch (f.kind) {
            case Frame::Root: finish_root(); break;
            case Frame::Structures: structures_done_ = true; break;
            case Frame::Structure: finish_structure(f.index); break;
            case Frame::Color:
                if (f.count != 3) color_problem_ = "color must be [r, g, b]";
                if (!color_problem_) structure_.color = color_;
                break;
            case Frame::Slice: finish_slice(); break;
            case Frame::Contour: finish_contour(); break;
            case Frame::Point:
                if (!point_ok_ || f.count != 2)
                    bad_point(f.index);
                else if (!std::isfinite(xy_[0]) || !std::isfinite(xy_[1]))
                    fail(point_key(f.index), contour_place() + ": point " + std::to_string(f.index) + " is not finite");
                else if (!error_)
                    contour_.points.emplace_back(xy_[0], xy_[1]);
                break;
            default: break;
        }
        return true;
    }

    void finish_structure(size_t i) {
        const std::string where = path_ + ": structure " + std::to_string(i);
        const ErrorKey key{kStructures, i, 0, 0, 0};
        if (id_state_ != IdState::String) return fail(key, where + ": needs a string \"id\"");
        if (structure_.id.empty()) return fail(key, where + ": empty id");
        if (!name_ok_) return fail(key, where + ": \"name\" must be a string");
        if (color_problem_) return fail(key, where + ": " + *color_problem_);
        for (const auto& other : stack_.structures)
            if (other.id == structure_.id) return fail(key, where + ": duplicate id '" + structure_.id + "'");
        structure_.name = name_ ? *name_ : structure_.id;
        stack_.structures.push_back(std::move(structure_));
    }

    void finish_slice() {
        if (!z_ok_) return fail(slice_key(0), place(path_, slice_index_) + ": needs a numeric \"z\"");
        if (!std::isfinite(z_)) return fail(slice_key(0), place(path_, slice_index_) + ": z is not finite");
        if (!contours_ok_) return fail(slice_key(1), place(path_, slice_index_) + ": needs a \"contours\" array");
        slice_.z = z_;
        if (!error_) raw_.push_back(std::move(slice_));
    }

    bool known_structure(const std::string& id) const {
        return std::any_of(stack_.structures.begin(), stack_.structures.end(),
                           [&](const StructureInfo& s) { return s.id == id; });
    }

    void finish_contour() {
        if (!points_ok_) return fail(contour_key(0), contour_place() + ": needs a \"points\" array");
        if (label_state_ == IdState::Wrong)
            return fail(contour_key(1), contour_place() + ": \"structure\" must be a string");
        if (label_state_ == IdState::String) {
            if (!structures_done_) {
                pending_labels_.push_back({slice_index_, contour_index_, contour_.structure});
            } else if (!known_structure(contour_.structure)) {
                return fail(contour_key(1), contour_place() + ": unknown structure '" + contour_.structure + "'");
            }
        }
        if (!error_) slice_.contours.push_back(std::move(contour_));
    }

    void finish_root() {
        if (!format_ok_) not_a_stack();
        if (!version_ok_) fail({kVersion, 0, 0, 0, 0}, path_ + ": unsupported version (expected 1 or 2)");
        if (!slices_ok_) fail({kSliceList, 0, 0, 0, 0}, path_ + ": needs a \"slices\" array");
        for (const PendingLabel& l : pending_labels_)
            if (!known_structure(l.id))
                fail({kSliceContent, l.slice, l.contour + 1, 1, 0},
                     place(path_, l.slice, l.contour) + ": unknown structure '" + l.id + "'");
    }

    // Where the parser stopped, from the open frames: "slice 3 contour 0 point 17".
    std::string context() const {
        std::string out;
        auto add = [&](const char* what, size_t i) {
            if (!out.empty()) out += ' ';
            out += what + std::string(" ") + std::to_string(i);
        };
        for (const OpenFrame& f : frames_) {
            switch (f.kind) {
                case Frame::Structure: add("structure", f.index); break;
                case Frame::Slice: add("slice", f.index); break;
                case Frame::Contour: add("contour", f.index); break;
                case Frame::Point: add("point", f.index); break;
                default: break;
            }
        }
        if (!frames_.empty()) {
            const OpenFrame& top = frames_.back();
            if (top.kind == Frame::Structures) add("structure", top.count);
            if (top.kind == Frame::Slices) add("slice", top.count);
            if (top.kind == Frame::Contours) add("contour", top.count);
            if (top.kind == Frame::Points) add("point", top.count);
        }
        return out;
    }

    std::string describe_parse_error(size_t byte, const std::string& token, const nlohmann::detail::exception& e) {
        const std::string at = "byte " + std::to_string(byte);
        if (e.id == 406) {  // number overflow: the value is not finite, say where it stands
            const std::string why = " is not finite (number overflow at " + at + ": '" + clip(token, 40) + "')";
            const Slot slot = frames_.empty() ? Slot::Document : next_slot();
            if (slot == Slot::Coordinate) return contour_place() + ": point " + std::to_string(point_index_) + why;
            if (slot == Slot::Z) return place(path_, slice_index_) + ": z" + why;
        }
        const std::string where = context();
        return path_ + ": " + at + ": invalid JSON" + (where.empty() ? "" : " at " + where) + ": " +
               parser_reason(e.what());
    }

    enum class IdState : uint8_t { Absent, String, Wrong };
    struct PendingLabel {
        size_t slice, contour;
        std::string id;
    };

    const std::string& path_;
    std::vector<OpenFrame> frames_;
    ContourStack stack_;
    std::vector<Slice> raw_;  // slices in file order
    std::optional<std::pair<ErrorKey, std::string>> error_;
    std::string syntax_error_;
    // The "links" value while and after it is read (depth: its open containers).
    json links_json_;
    std::optional<nlohmann::detail::json_sax_dom_parser<json>> links_;
    size_t links_depth_ = 0;

    bool format_ok_ = false, version_ok_ = false, slices_ok_ = false;
    bool structures_done_ = false;
    std::vector<PendingLabel> pending_labels_;  // labels read before the structure list was complete

    // The structure being read.
    StructureInfo structure_;
    IdState id_state_ = IdState::Absent;
    bool name_ok_ = true;
    std::optional<std::string> name_, color_problem_;
    Vec3 color_{0.0};

    // The slice, contour and point being read.
    Slice slice_;
    size_t slice_index_ = 0, contour_index_ = 0, point_index_ = 0;
    double z_ = 0.0;
    bool z_ok_ = false, contours_ok_ = false;
    Contour contour_;
    bool points_ok_ = false;
    IdState label_state_ = IdState::Absent;
    double xy_[2] = {0.0, 0.0};
    bool point_ok_ = true;
};

}  // namespace

Status check_coordinate_range(const ContourStack& stack, const std::string& path) {
    auto outside = [](double v) { return !(std::fabs(v) <= kMaxCoordinate); };
    auto num = [](double v) {
        char b[32];
        std::snprintf(b, sizeof b, "%g", v);
        return std::string(b);
    };
    const std::string range = " is outside the coordinate range +-1e7 (mm)";
    for (const Slice& s : stack.slices) {
        if (outside(s.z)) return input_error(place(path, s.source_index) + ": z = " + num(s.z) + range);
        for (const Contour& c : s.contours) {
            for (size_t k = 0; k < c.points.size(); ++k) {
                const Vec2 p = c.points[k];
                if (outside(p.x) || outside(p.y))
                    return input_error(place(path, c.source_slice, c.source_contour) + ": point " + std::to_string(k) +
                                       " (" + num(p.x) + ", " + num(p.y) + ")" + range);
            }
        }
    }
    return ok_status();
}

Result<ContourStack> parse_contour_stack(const std::string& json_text, const std::string& path) {
    StackReader reader(path);
    const bool parsed = json::sax_parse(json_text, &reader);
    auto stack = reader.finish(parsed);
    if (stack) {
        if (auto range = check_coordinate_range(*stack, path); !range) return range.error();
    }
    return stack;
}

Result<ContourStack> read_contour_stack(const std::string& path) {
    if (auto regular = check_regular_file(path); !regular) return regular.error();
    std::ifstream in;
    std::vector<char> buffer(1 << 20);
    in.rdbuf()->pubsetbuf(buffer.data(), std::streamsize(buffer.size()));
    in.open(path, std::ios::binary);
    if (!in) return input_error(path + ": cannot open: " + std::strerror(errno));
    StackReader reader(path);
    const bool parsed = json::sax_parse(in, &reader);
    if (in.bad()) return input_error(path + ": read failed");
    auto stack = reader.finish(parsed);
    if (stack) {
        if (auto range = check_coordinate_range(*stack, path); !range) return range.error();
    }
    return stack;
}

std::string contour_stack_to_json(const ContourStack& stack) {
    json root;
    root["format"] = "bodygen.contours";
    root["version"] = stack.links.empty() ? 1 : 2;
    root["units"] = stack.units;
    if (stack.voxel) root["voxel"] = *stack.voxel;
    json structures = json::array();
    for (const auto& s : stack.structures)
        structures.push_back({{"id", s.id}, {"name", s.name}, {"color", {s.color.r, s.color.g, s.color.b}}});
    root["structures"] = structures;
    json slices = json::array();
    for (const auto& slice : stack.slices) {
        json contours = json::array();
        for (const auto& c : slice.contours) {
            json pts = json::array();
            for (const Vec2& p : c.points) pts.push_back({p.x, p.y});
            json jc = {{"points", std::move(pts)}};
            if (!c.structure.empty()) jc["structure"] = c.structure;
            contours.push_back(std::move(jc));
        }
        slices.push_back({{"z", slice.z}, {"contours", std::move(contours)}});
    }
    root["slices"] = std::move(slices);
    if (!stack.links.empty()) root["links"] = link_overrides_to_json(stack);
    return root.dump();
}

Status write_contour_stack(const std::string& path, const ContourStack& stack) {
    return write_file_atomically(path, [&](std::ostream& out) {
        out << contour_stack_to_json(stack) << '\n';
        return std::string();
    });
}

}  // namespace body
