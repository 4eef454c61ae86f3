// --label-smooth: each label's indicator blurred in 3-D and traced between
// voxel centres (gaussian_blur.h, trace_field_isolines in marching_squares.h);
// labels that the full blur would shrink or split smoothed less, traced
// against their neighbours without overlap.
// - Joint smoothing of label maps by per-label Gaussian scores compared
//   against each other is the rule of 3D Slicer's "Joint smoothing" (one width
//   for all); here each label's score has its own width.
#include <algorithm>
#include <cassert>
#include <climits>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "builder/import/gaussian_blur.h"
#include "builder/import/label_volume.h"
#include "builder/slicing/marching_squares.h"

namespace body::label_import {

// A 1 x 1 x 3 mm volume is blurred 2/3 voxel along its 3 mm axis for s = 2: a
// sigma of s voxels there would take 3 s mm, three times the in-plane
// smoothing, and wipe out structures a few slices thick.
void axis_sigmas(const LabelVolume& vol, double s, int level, double out[3]) {
    const double finest = std::min({vol.spacing[0], vol.spacing[1], vol.spacing[2]});
    const double scale = std::ldexp(1.0, -level);
    for (int d = 0; d < 3; ++d) out[d] = s * scale * finest / vol.spacing[d];
}

namespace {

// A label's working box: its bounding box padded by twice the widest blur's
// radius on each axis (so blurs are exact where the level can lie, and memory
// follows the structure, not the volume).
struct Box {
    long lo[3] = {0, 0, 0};
    size_t size[3] = {0, 0, 0};
    size_t count() const { return size[0] * size[1] * size[2]; }
};

Box label_box(const Extent& e, const double sigma[3]) {
    Box b;
    for (int d = 0; d < 3; ++d) {
        const long pad = 2 * static_cast<long>(gaussian_radius(sigma[d]));
        b.lo[d] = static_cast<long>(e.lo[d]) - pad;
        b.size[d] = e.hi[d] - e.lo[d] + 1 + 2 * static_cast<size_t>(pad);
    }
    return b;
}

// Calls fn(box index, label) for every voxel of the box; beyond the volume the
// label is 0 (background).
template <typename Fn>
void for_box(const LabelVolume& vol, const Box& b, Fn&& fn) {
    // The box's x range inside the volume, [x0, x1) in box indices.
    const long x0 = std::clamp(-b.lo[0], 0L, long(b.size[0]));
    const long x1 = std::clamp(long(vol.dim[0]) - b.lo[0], x0, long(b.size[0]));
    size_t n = 0;
    for (size_t z = 0; z < b.size[2]; ++z) {
        for (size_t y = 0; y < b.size[1]; ++y, n += b.size[0]) {
            const long j = b.lo[1] + long(y), k = b.lo[2] + long(z);
            const bool in_volume = j >= 0 && k >= 0 && j < long(vol.dim[1]) && k < long(vol.dim[2]);
            // Three runs per row (before, inside and after the volume's x
            // range): no test per voxel.
            const long from = in_volume ? x0 : long(b.size[0]), to = in_volume ? x1 : long(b.size[0]);
            for (long x = 0; x < from; ++x) fn(n + size_t(x), 0);
            if (from < to) {
                const int32_t* row = &vol.labels[vol.index(0, size_t(j), size_t(k))] + b.lo[0];
                for (long x = from; x < to; ++x) fn(n + size_t(x), row[x]);
            }
            for (long x = to; x < long(b.size[0]); ++x) fn(n + size_t(x), 0);
        }
    }
}

// The thin labels' entries, looked up with the last answer kept (labels come
// in runs along x).
class ThinLookup {
public:
    explicit ThinLookup(const std::map<int32_t, ThinLabel>& thin) : thin_(thin) {}
    const ThinLabel* find(int32_t l) {
        if (l != last_) {
            last_ = l;
            const auto it = thin_.find(l);
            found_ = it == thin_.end() ? nullptr : &it->second;
        }
        return found_;
    }

private:
    const std::map<int32_t, ThinLabel>& thin_;
    int32_t last_ = 0;
    const ThinLabel* found_ = nullptr;
};

// The indicator of `pick(label)` over the box, blurred by `sigma`.
template <typename Pick>
std::vector<float> blurred(const LabelVolume& vol, const Box& b, const double sigma[3], Pick&& pick) {
    std::vector<float> field(b.count(), 0.0f);
    for_box(vol, b, [&](size_t n, int32_t l) { field[n] = pick(l) ? 1.0f : 0.0f; });
    gaussian_blur_3d(field, b.size, sigma);
    return field;
}

// The background blur (blur_background) over a label's box, which lies inside it.
std::vector<float> cropped(const BackgroundBlur& bg, const Box& b) {
    std::vector<float> field(b.count());
    float* out = field.data();
    for (size_t z = 0; z < b.size[2]; ++z)
        for (size_t y = 0; y < b.size[1]; ++y, out += b.size[0]) {
            const size_t at[3] = {size_t(b.lo[0] - bg.lo[0]), size_t(b.lo[1] - bg.lo[1] + long(y)),
                                  size_t(b.lo[2] - bg.lo[2] + long(z))};
            assert(at[0] + b.size[0] <= bg.size[0] && at[1] < bg.size[1] && at[2] < bg.size[2]);
            const float* row = bg.field.data() + (at[2] * bg.size[1] + at[1]) * bg.size[0] + at[0];
            std::copy(row, row + b.size[0], out);
        }
    return field;
}

// The weight c of the blurred background in the traced field f + c * bg: 0
// (f's 0.5 level: the blur shrinks convex and thin parts there), raised until
// as many voxel centres lie above 0.5 as the label has voxels, to at most
// kMostBackground. The background term moves only the boundary against
// unlabelled voxels: where another label is the neighbour bg is about 0.
// Voxels where `margin` (if any) is not positive never count.
float background_weight(const std::vector<float>& field, const std::vector<float>& bg, const std::vector<float>* margin,
                        size_t voxels) {
    constexpr float kMostBackground = 0.45f;
    size_t above = 0;
    std::vector<float> needed;  // per voxel below the level: the weight that lifts it to 0.5
    for (size_t i = 0; i < field.size(); ++i) {
        if (margin && (*margin)[i] <= 0.0f) continue;
        if (field[i] > 0.5f)
            ++above;
        else if (bg[i] > 0.0f && field[i] > 0.0f)
            needed.push_back((0.5f - field[i]) / bg[i]);
    }
    if (above >= voxels || needed.empty()) return 0.0f;
    const size_t k = std::min(voxels - above, needed.size()) - 1;
    std::nth_element(needed.begin(), needed.begin() + static_cast<long>(k), needed.end());
    return std::min(needed[k], kMostBackground);
}

// Calls fn(voxel indices) for every 6-connected piece of a box mask (consumed).
template <typename Fn>
void for_each_piece(std::vector<uint8_t> mask, const size_t size[3], Fn&& fn) {
    const size_t sx = size[0], sxy = size[0] * size[1];
    std::vector<size_t> stack;
    for (size_t start = 0; start < mask.size(); ++start) {
        if (!mask[start]) continue;
        std::vector<size_t> piece;
        mask[start] = 0;
        stack.push_back(start);
        while (!stack.empty()) {
            const size_t i = stack.back();
            stack.pop_back();
            piece.push_back(i);
            const size_t x = i % sx, y = (i / sx) % size[1], z = i / sxy;
            auto visit = [&](bool ok, size_t j) {
                if (ok && mask[j]) mask[j] = 0, stack.push_back(j);
            };
            visit(x > 0, i - 1), visit(x + 1 < sx, i + 1);
            visit(y > 0, i - sx), visit(y + 1 < size[1], i + sx);
            visit(z > 0, i - sxy), visit(z + 1 < size[2], i + sxy);
        }
        fn(std::move(piece));
    }
}

// 6-connected pieces of a box mask.
size_t count_pieces(const std::vector<uint8_t>& mask, const size_t size[3]) {
    size_t pieces = 0;
    for_each_piece(mask, size, [&](std::vector<size_t>&&) { ++pieces; });
    return pieces;
}

// A label's pieces under kMinPiece voxels removed from its mask (all but the
// largest when every piece is that small): specks the full blur removes, not
// parts a narrower blur must keep. Returns the pieces kept.
size_t keep_large_pieces(std::vector<uint8_t>& mask, const size_t size[3]) {
    std::vector<std::vector<size_t>> small;
    size_t kept = 0;
    for_each_piece(mask, size, [&](std::vector<size_t>&& piece) {
        if (piece.size() >= kMinPiece)
            ++kept;
        else
            small.push_back(std::move(piece));
    });
    if (kept == 0 && !small.empty()) {
        std::swap(*std::max_element(small.begin(), small.end(),
                                    [](const auto& a, const auto& b) { return a.size() < b.size(); }),
                  small.back());
        small.pop_back();
        kept = 1;
    }
    for (const auto& piece : small)
        for (size_t i : piece) mask[i] = 0;
    return kept;
}

// Whether the region {inside(i)} keeps the label: at least kKeptShare of its
// voxel centres, and its voxels in no more 6-connected pieces than the label
// has (a bridge thinner than the blur broken counts as lost).
template <typename Inside>
bool keeps_label(const std::vector<uint8_t>& own, size_t voxels, size_t own_pieces, const size_t size[3],
                 Inside&& inside) {
    constexpr double kKeptShare = 0.9;
    std::vector<uint8_t> kept(own.size(), 0);
    size_t count = 0;
    for (size_t i = 0; i < own.size(); ++i) {
        kept[i] = own[i] && inside(i);
        count += kept[i];
    }
    return double(count) >= kKeptShare * double(voxels) && count_pieces(kept, size) <= own_pieces;
}

// The traced plane values of one label: field f + c * bg at level 0.5, or
// with neighbours to beat 0.5 + min(f + c * bg - 0.5, margin).
struct LabelFields {
    Box box;
    std::vector<float> f, bg, margin;  // margin empty: none
    float c = 0.0f;
    bool half_rule = true;                  // false: the margin alone (thin labels)
    bool drop_specks = false;               // rings under kMinRingArea dropped (pass 2)
    long k_lo = LONG_MIN, k_hi = LONG_MAX;  // the slices traced (volume indices), within the box's
};

// Every sampled slice plane of the box traced where the label's value passes 0.5.
void trace_label(const LabelVolume& vol, const SliceFrame& fr, const LabelFields& lf, const ImportOptions& o,
                 LabelResult& out) {
    const Box& b = lf.box;
    // The level is never reached beyond the volume's slice range: the
    // indicator is 0 there and c < 0.5.
    const size_t w = b.size[fr.u], h = b.size[fr.v];
    std::vector<float> plane(w * h);
    std::vector<std::vector<Vec2>> rings;
    std::vector<std::pair<size_t, std::vector<std::vector<Vec2>>>> traced;  // slice -> rings
    size_t at[3];
    const long k_first = std::max({b.lo[fr.axis], 0L, lf.k_lo});
    const long k_last = std::min<long>(
        {b.lo[fr.axis] + static_cast<long>(b.size[fr.axis]) - 1, static_cast<long>(vol.dim[fr.axis]) - 1, lf.k_hi});
    for (long k = k_first; k <= k_last; ++k) {
        if (k % o.step != 0) continue;
        at[fr.axis] = static_cast<size_t>(k - b.lo[fr.axis]);
        bool any = false;
        for (size_t y = 0; y < h; ++y) {
            at[fr.v] = y;
            for (size_t x = 0; x < w; ++x) {
                at[fr.u] = x;
                const size_t i = (at[2] * b.size[1] + at[1]) * b.size[0] + at[0];
                float value = lf.f[i] + lf.c * lf.bg[i];
                if (!lf.margin.empty())
                    value = 0.5f + (lf.half_rule ? std::min(value - 0.5f, lf.margin[i]) : lf.margin[i]);
                plane[y * w + x] = value;
                any |= value > 0.5f;
            }
        }
        if (!any) continue;
        trace_field_isolines(plane, w, h, 0.5f, rings);
        traced.emplace_back(static_cast<size_t>(k), std::move(rings));
        rings = {};
    }
    // Pass 2 compares labels on blurs of 1/2 or 1/4 the width: a ragged edge's
    // single voxels come back as rings of a few voxel faces that meet
    // nothing on the next slice, each its own mesh piece (pinholes likewise):
    // dropped, unless the label has no larger ring (it must not vanish).
    constexpr double kMinRingArea = 4.0;  // voxel faces (2 x 2)
    auto small = [](const std::vector<Vec2>& r) {
        return std::fabs(signed_area2(r.data(), r.size())) < 2.0 * kMinRingArea;
    };
    const bool any_large = std::any_of(traced.begin(), traced.end(), [&](const auto& t) {
        return std::any_of(t.second.begin(), t.second.end(), [&](const auto& r) { return !small(r); });
    });
    for (auto& [k, slice_rings] : traced) {
        if (lf.drop_specks && any_large) std::erase_if(slice_rings, small);
        finish_rings(fr, static_cast<double>(b.lo[fr.u]), static_cast<double>(b.lo[fr.v]), k, o, slice_rings, out);
    }
}

// The area inside {g * s > others} summed over the slice planes of the box
// (the traced contours' area), in voxels: each voxel counts by how far its
// centre is inside along the in-plane gradient of the margin m = g * s -
// others, 0.5 + m / |grad m| clamped to [0, 1] (a line through a pixel splits
// it so), so the boundary's place between voxel centres counts. The terms
// that do not depend on g are taken once (InsideTerms) for the gain's search.
struct InsideTerms {
    // Per voxel with s > 0, in index order: s, others, and along the two
    // in-plane axes (in axis order) the differences of s and of others
    // across the voxel and the distance they span (0: the box is one voxel
    // wide there).
    std::vector<float> s, others, ds[2], dothers[2], span[2];
};

InsideTerms inside_terms(const std::vector<float>& s, const std::vector<float>& others, const size_t size[3],
                         int slice_axis) {
    InsideTerms t;
    const size_t step[3] = {1, size[0], size[0] * size[1]};
    int axes[2], na = 0;
    for (int d = 0; d < 3; ++d)
        if (d != slice_axis) axes[na++] = d;
    size_t i = 0, at[3];
    for (at[2] = 0; at[2] < size[2]; ++at[2])
        for (at[1] = 0; at[1] < size[1]; ++at[1])
            for (at[0] = 0; at[0] < size[0]; ++at[0], ++i) {
                if (s[i] == 0.0f) continue;
                t.s.push_back(s[i]);
                t.others.push_back(others[i]);
                for (int k = 0; k < 2; ++k) {
                    const int d = axes[k];
                    const size_t a = at[d] > 0 ? i - step[d] : i, b = at[d] + 1 < size[d] ? i + step[d] : i;
                    t.ds[k].push_back(s[b] - s[a]);
                    t.dothers[k].push_back(others[b] - others[a]);
                    t.span[k].push_back(float((b - a) / step[d]));
                }
            }
    return t;
}

double inside_volume(float g, const InsideTerms& t) {
    double volume = 0.0;
    for (size_t j = 0; j < t.s.size(); ++j) {
        const float m = g * t.s[j] - t.others[j];
        float grad2 = 0.0f;
        for (int k = 0; k < 2; ++k) {
            const float d = t.span[k][j] == 0.0f ? 0.0f : (g * t.ds[k][j] - t.dothers[k][j]) / t.span[k][j];
            grad2 += d * d;
        }
        const float grad = std::sqrt(grad2);
        volume += grad > 0.0f ? std::clamp(0.5f + m / grad, 0.0f, 1.0f) : (m > 0.0f ? 1.0f : 0.0f);
    }
    return volume;
}

// The gain g (1 to kMostGain) that gives {g * s > others} the label's volume.
float thin_gain(const std::vector<float>& s, const std::vector<float>& others, size_t voxels, const size_t size[3],
                int slice_axis) {
    constexpr float kMostGain = 2.0f;
    const double target = static_cast<double>(voxels);
    const InsideTerms terms = inside_terms(s, others, size, slice_axis);
    if (inside_volume(1.0f, terms) >= target) return 1.0f;
    if (inside_volume(kMostGain, terms) <= target) return kMostGain;
    float lo = 1.0f, hi = kMostGain;
    for (int step = 0; step < 12; ++step) {
        const float mid = 0.5f * (lo + hi);
        (inside_volume(mid, terms) < target ? lo : hi) = mid;
    }
    return hi;
}

}  // namespace

BackgroundBlur blur_background(const LabelVolume& vol, const Extent& labelled, double s) {
    double sigma[3];
    axis_sigmas(vol, s, 0, sigma);
    const Box b = label_box(labelled, sigma);
    BackgroundBlur bg;
    for (int d = 0; d < 3; ++d) bg.lo[d] = b.lo[d], bg.size[d] = b.size[d];
    bg.field = blurred(vol, b, sigma, [](int32_t l) { return l == 0; });
    return bg;
}

// Pass 1 of --label-smooth, one label: blurred by the full width, the level
// of f + c * bg traced (final unless a thin neighbour turns up, see
// extract_labels). Returns the smoothing level the label needs: 0 when the
// full width keeps it (keeps_label), else the first narrower level that keeps
// it against everything else labelled blurred alike (with the gain that gives
// it its voxel count), else the last. Pieces under 20 voxels are left out
// (specks the full blur removes).
ThinLabel extract_label_smoothed(const LabelVolume& vol, const SliceFrame& fr, int32_t label, const Extent& e,
                                 const ImportOptions& o, const BackgroundBlur& bg, LabelResult& out) {
    out.label = label;
    double sigma[3];
    axis_sigmas(vol, o.label_smooth, 0, sigma);
    LabelFields lf;
    lf.box = label_box(e, sigma);
    lf.f = blurred(vol, lf.box, sigma, [&](int32_t l) { return l == label; });
    lf.bg = cropped(bg, lf.box);
    lf.c = background_weight(lf.f, lf.bg, nullptr, e.voxels);
    std::vector<uint8_t> own(lf.box.count());
    for_box(vol, lf.box, [&](size_t n, int32_t l) { own[n] = l == label; });
    const size_t own_pieces = keep_large_pieces(own, lf.box.size);
    const size_t voxels = static_cast<size_t>(std::count(own.begin(), own.end(), uint8_t(1)));
    if (keeps_label(own, voxels, own_pieces, lf.box.size, [&](size_t i) { return lf.f[i] + lf.c * lf.bg[i] > 0.5f; })) {
        trace_label(vol, fr, lf, o, out);
        return {0, 1.0f, lf.c};
    }
    ThinLabel t;
    t.c = lf.c;
    for (t.level = 1; t.level < kSmoothLevels; ++t.level) {
        double narrow[3];
        axis_sigmas(vol, o.label_smooth, t.level, narrow);
        std::vector<float> s(own.begin(), own.end());
        gaussian_blur_3d(s, lf.box.size, narrow);
        const std::vector<float> others = blurred(vol, lf.box, narrow, [&](int32_t l) { return l != label; });
        t.gain = thin_gain(s, others, voxels, lf.box.size, fr.axis);
        auto inside = [&](size_t i) { return t.gain * s[i] > others[i]; };
        if (t.level + 1 == kSmoothLevels || keeps_label(own, voxels, own_pieces, lf.box.size, inside)) break;
    }
    return t;
}

namespace {

// Pass 2, a thin label. Two labels are compared with both blurred by the
// narrower of their two widths, each scaled by its own gain (1 at the full
// width): a label X at level x must beat, at its own width, the gain-weighted
// blur of the background and the other labels at level <= x (for x = 0 the
// 0.5 rule of f + c * bg instead, which already keeps two full-width labels
// apart), and at each narrower level y > x that of the labels at level y. The
// weighted blur of a set bounds each member's score, so for any two labels
// each compares the same two scores the other way round: their regions cannot
// overlap, and a thin label meets its neighbours at its own width: it keeps
// its voxels.
void extract_thin_label(const LabelVolume& vol, const SliceFrame& fr, int32_t label, const Extent& e,
                        const ImportOptions& o, const ThinLabel& own, const std::map<int32_t, ThinLabel>& thin,
                        LabelResult& out) {
    out = LabelResult{};
    out.label = label;
    double full[3], sigma[3];
    axis_sigmas(vol, o.label_smooth, 0, full);
    axis_sigmas(vol, o.label_smooth, own.level, sigma);
    LabelFields lf;
    lf.box = label_box(e, full);
    // Per voxel of the box: kOwn, kBackground or the level of its label, and
    // the gain of its label.
    constexpr int8_t kSpeck = -3, kOwn = -2, kBackground = -1;
    std::vector<int8_t> tag(lf.box.count());
    std::vector<float> gain(lf.box.count(), 1.0f);
    ThinLookup lookup(thin);
    for_box(vol, lf.box, [&](size_t n, int32_t l) {
        if (l == label || l == 0) {
            tag[n] = l == 0 ? kBackground : kOwn;
            return;
        }
        const ThinLabel* t = lookup.find(l);
        tag[n] = static_cast<int8_t>(t ? t->level : 0);
        if (t) gain[n] = t->gain;
    });
    {  // its specks go as in pass 1 (neither it nor a rival)
        std::vector<uint8_t> mask(tag.size());
        for (size_t i = 0; i < tag.size(); ++i) mask[i] = tag[i] == kOwn;
        keep_large_pieces(mask, lf.box.size);
        for (size_t i = 0; i < tag.size(); ++i)
            if (tag[i] == kOwn && !mask[i]) tag[i] = kSpeck;
    }
    auto tagged = [&](const double width[3], auto&& pick) {
        std::vector<float> field(tag.size());
        for (size_t i = 0; i < tag.size(); ++i) field[i] = pick(tag[i]) ? gain[i] : 0.0f;
        gaussian_blur_3d(field, lf.box.size, width);
        return field;
    };
    lf.f = tagged(sigma, [](int8_t t) { return t == kOwn; });
    lf.bg = tagged(sigma, [](int8_t t) { return t == kBackground; });
    lf.margin.assign(lf.box.count(), std::numeric_limits<float>::max());
    for (int level = own.level; level < kSmoothLevels; ++level) {
        auto rival = [&](int8_t t) {
            return level == own.level ? t == kBackground || (t >= 0 && t <= level) : t == level;
        };
        if (std::none_of(tag.begin(), tag.end(), rival)) continue;
        double width[3];
        axis_sigmas(vol, o.label_smooth, level, width);
        const std::vector<float> others = tagged(width, rival);
        const std::vector<float> self = level == own.level ? lf.f : tagged(width, [](int8_t t) { return t == kOwn; });
        for (size_t i = 0; i < others.size(); ++i)
            lf.margin[i] = std::min(lf.margin[i], own.gain * self[i] - others[i]);
    }
    lf.half_rule = false;
    lf.drop_specks = true;
    trace_label(vol, fr, lf, o, out);
}

// A box's sub-box [lo, hi] (box indices, inclusive) padded by `pad` voxels on
// each axis and clipped to the box, in volume indices.
Box sub_box(const Box& b, const long lo[3], const long hi[3], const long pad[3]) {
    Box s;
    for (int d = 0; d < 3; ++d) {
        const long a = std::max(lo[d] - pad[d], 0L), z = std::min(hi[d] + pad[d], long(b.size[d]) - 1);
        s.lo[d] = b.lo[d] + a;
        s.size[d] = static_cast<size_t>(z - a + 1);
    }
    return s;
}

// Pass 2, a full-width label with thin labels in its working box: the rule of
// extract_thin_label, which for it is the 0.5 rule of pass 1 (the same c)
// and, against the thin labels of each level y, its blur at y beating
// theirs. Only where a thin label's blur reaches does that differ from pass
// 1: only the slices within that reach are traced again, and the narrow blurs
// are taken over the thin labels' own box within its box.
void extract_label_beside_thin(const LabelVolume& vol, const SliceFrame& fr, int32_t label, const Extent& e,
                               const ImportOptions& o, const ThinLabel& own, const std::map<int32_t, ThinLabel>& thin,
                               const BackgroundBlur& bg, LabelResult& out) {
    double full[3];
    axis_sigmas(vol, o.label_smooth, 0, full);
    const Box b = label_box(e, full);
    // Per narrow level: the box of its labels' voxels (box indices).
    long lo[kSmoothLevels][3], hi[kSmoothLevels][3];
    ThinLookup lookup(thin);
    for (int y = 0; y < kSmoothLevels; ++y)
        for (int d = 0; d < 3; ++d) lo[y][d] = LONG_MAX, hi[y][d] = -1;
    for_box(vol, b, [&](size_t n, int32_t l) {
        const ThinLabel* t = l > 0 && l != label ? lookup.find(l) : nullptr;
        if (!t) return;
        const long at[3] = {long(n % b.size[0]), long((n / b.size[0]) % b.size[1]), long(n / (b.size[0] * b.size[1]))};
        for (int d = 0; d < 3; ++d)
            lo[t->level][d] = std::min(lo[t->level][d], at[d]), hi[t->level][d] = std::max(hi[t->level][d], at[d]);
    });
    // The slices a narrow blur reaches, and the slab of the box their
    // full-width blurs need.
    const int a = fr.axis;
    long k_lo = LONG_MAX, k_hi = -1;
    long reach[kSmoothLevels][3];
    for (int y = 1; y < kSmoothLevels; ++y) {
        double width[3];
        axis_sigmas(vol, o.label_smooth, y, width);
        for (int d = 0; d < 3; ++d) reach[y][d] = static_cast<long>(gaussian_radius(width[d]));
        if (hi[y][a] < 0) continue;
        k_lo = std::min(k_lo, lo[y][a] - reach[y][a]), k_hi = std::max(k_hi, hi[y][a] + reach[y][a]);
    }
    if (k_hi < 0) return;
    k_lo = std::max(k_lo, 0L), k_hi = std::min(k_hi, long(b.size[a]) - 1);
    long slab_lo[3] = {0, 0, 0}, slab_hi[3], pad[3] = {0, 0, 0};
    for (int d = 0; d < 3; ++d) slab_hi[d] = long(b.size[d]) - 1;
    slab_lo[a] = k_lo, slab_hi[a] = k_hi, pad[a] = static_cast<long>(gaussian_radius(full[a]));
    LabelFields lf;
    lf.box = sub_box(b, slab_lo, slab_hi, pad);
    lf.f = blurred(vol, lf.box, full, [&](int32_t l) { return l == label; });
    lf.bg = cropped(bg, lf.box);
    lf.c = own.c;
    lf.margin.assign(lf.box.count(), std::numeric_limits<float>::max());
    for (int y = 1; y < kSmoothLevels; ++y) {
        if (hi[y][a] < 0) continue;
        double width[3];
        axis_sigmas(vol, o.label_smooth, y, width);
        const long twice[3] = {2 * reach[y][0], 2 * reach[y][1], 2 * reach[y][2]};
        const Box r = sub_box(b, lo[y], hi[y], twice);
        const std::vector<float> self = blurred(vol, r, width, [&](int32_t l) { return l == label; });
        std::vector<float> others(r.count(), 0.0f);
        for_box(vol, r, [&](size_t n, int32_t l) {
            const ThinLabel* t = l > 0 && l != label ? lookup.find(l) : nullptr;
            if (t && t->level == y) others[n] = t->gain;
        });
        gaussian_blur_3d(others, r.size, width);
        size_t n = 0;
        for (size_t z = 0; z < r.size[2]; ++z)
            for (size_t yy = 0; yy < r.size[1]; ++yy)
                for (size_t x = 0; x < r.size[0]; ++x, ++n) {
                    const long at[3] = {r.lo[0] + long(x) - lf.box.lo[0], r.lo[1] + long(yy) - lf.box.lo[1],
                                        r.lo[2] + long(z) - lf.box.lo[2]};
                    if (others[n] <= 0.0f || at[2] < 0 || at[2] >= long(lf.box.size[2]) || at[1] < 0 ||
                        at[1] >= long(lf.box.size[1]) || at[0] < 0 || at[0] >= long(lf.box.size[0]))
                        continue;
                    float& m =
                        lf.margin[(size_t(at[2]) * lf.box.size[1] + size_t(at[1])) * lf.box.size[0] + size_t(at[0])];
                    m = std::min(m, self[n] - others[n]);
                }
    }
    lf.k_lo = b.lo[a] + k_lo, lf.k_hi = b.lo[a] + k_hi;
    lf.drop_specks = true;
    LabelResult fresh;
    trace_label(vol, fr, lf, o, fresh);
    std::erase_if(out.slices, [&](const auto& s) { return long(s.first) >= lf.k_lo && long(s.first) <= lf.k_hi; });
    for (auto& s : fresh.slices) out.slices.push_back(std::move(s));
    std::sort(out.slices.begin(), out.slices.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
}

}  // namespace

void extract_label_among_thin(const LabelVolume& vol, const SliceFrame& fr, int32_t label, const Extent& e,
                              const ImportOptions& o, const ThinLabel& own, const std::map<int32_t, ThinLabel>& thin,
                              const BackgroundBlur& bg, LabelResult& out) {
    if (own.level > 0)
        extract_thin_label(vol, fr, label, e, o, own, thin, out);
    else
        extract_label_beside_thin(vol, fr, label, e, o, own, thin, bg, out);
}

// Whether the label's working box holds a voxel of a thin label other than it.
bool box_meets_thin(const LabelVolume& vol, const Extent& e, int32_t label, const std::map<int32_t, ThinLabel>& thin,
                    double s) {
    double sigma[3];
    axis_sigmas(vol, s, 0, sigma);
    bool meets = false;
    ThinLookup lookup(thin);
    for_box(vol, label_box(e, sigma), [&](size_t, int32_t l) { meets |= l > 0 && l != label && lookup.find(l); });
    return meets;
}

}  // namespace body::label_import
