// The link table (contract in link_table.h): the pipeline's stages up to the
// correspondence, recording links instead of building bands.
#include "builder/correspondence/link_table.h"

#include <algorithm>

#include "builder/contours/contour_links.h"
#include "builder/correspondence/grouping.h"
#include "builder/correspondence/link_overrides.h"
#include "builder/correspondence/material_regions.h"

namespace body {
namespace {

ContourRef ref_of(const Contour& c) { return {c.source_slice, c.source_contour}; }

// One structure's contours on one slice, with their nesting.
struct NestedMembers {
    std::vector<PolygonSpan> points;
    Nesting nesting;
    bool hole(uint32_t k) const { return nesting.depth[k] % 2 == 1; }
};

NestedMembers nested_members(const Slice& slice, const std::vector<uint32_t>& members) {
    NestedMembers out{{}, compute_nesting(slice, members)};
    for (uint32_t c : members) out.points.emplace_back(slice.contours[c].points);
    return out;
}

struct SlicePair {
    const ContourStack& stack;
    const std::string& structure;
    size_t s;
    const std::vector<uint32_t>& lower_members;
    const std::vector<uint32_t>& upper_members;
};

// Links of one kind (solids or holes) between slices s and s+1 (`computed`:
// positions in `lo` and `up`); marks the contours (positions in the members)
// that continue up or down.
void pair_links(const SlicePair& p, const std::vector<uint32_t>& lo, const std::vector<uint32_t>& up, bool hole,
                const std::vector<ContourLink>& computed, LinkTable& table, std::vector<bool>& linked_up,
                std::vector<bool>& linked_down) {
    const Slice& a = p.stack.slices[p.s];
    const Slice& b = p.stack.slices[p.s + 1];
    std::vector<const Contour*> sa, sb;
    for (uint32_t k : lo) sa.push_back(&a.contours[p.lower_members[k]]);
    for (uint32_t k : up) sb.push_back(&b.contours[p.upper_members[k]]);
    std::vector<ContourLink> built = computed;
    apply_link_overrides(p.stack.links, sa, sb, built);
    for (const LinkGroup& g : group_links(built, lo.size(), up.size())) {
        const LinkKind kind = g.lower.size() == 1 && g.upper.size() == 1 ? LinkKind::Band : LinkKind::Branch;
        for (const ContourLink& l : g.links) {
            const bool was = std::binary_search(computed.begin(), computed.end(), l);
            table.links.push_back({p.structure, p.s, ref_of(*sa[l.lower]), ref_of(*sb[l.upper]), hole, kind,
                                   was ? LinkOrigin::Computed : LinkOrigin::Joined});
            linked_up[lo[l.lower]] = true;
            linked_down[up[l.upper]] = true;
        }
    }
    for (const ContourLink& l : computed)
        if (!std::binary_search(built.begin(), built.end(), l))
            table.links.push_back(
                {p.structure, p.s, ref_of(*sa[l.lower]), ref_of(*sb[l.upper]), hole, LinkKind::Band, LinkOrigin::Cut});
}

void structure_links(const ContourStack& stack, const std::string& id,
                     const std::vector<std::vector<uint32_t>>& members, CorrespondenceMethod method, LinkTable& table) {
    const size_t S = stack.slices.size();
    std::vector<NestedMembers> nested(S);
    std::vector<std::vector<bool>> up(S), down(S);
    for (size_t s = 0; s < S; ++s) {
        nested[s] = nested_members(stack.slices[s], members[s]);
        up[s].assign(members[s].size(), false);
        down[s].assign(members[s].size(), false);
    }
    for (size_t s = 0; s + 1 < S; ++s) {
        const SlicePair pair{stack, id, s, members[s], members[s + 1]};
        const NestedMembers &a = nested[s], &b = nested[s + 1];
        const std::vector<ContourLink> all =
            correspond_nested({a.points, a.nesting.parent}, {b.points, b.nesting.parent}, method);
        for (int hole = 0; hole < 2; ++hole) {
            std::vector<uint32_t> lo, hi, at_lo(members[s].size()), at_hi(members[s + 1].size());
            for (uint32_t k = 0; k < members[s].size(); ++k)
                if (a.hole(k) == bool(hole)) at_lo[k] = uint32_t(lo.size()), lo.push_back(k);
            for (uint32_t k = 0; k < members[s + 1].size(); ++k)
                if (b.hole(k) == bool(hole)) at_hi[k] = uint32_t(hi.size()), hi.push_back(k);
            std::vector<ContourLink> computed;
            for (const ContourLink& l : all)
                if (a.hole(l.lower) == bool(hole)) computed.push_back({at_lo[l.lower], at_hi[l.upper]});
            if (!lo.empty() && !hi.empty()) pair_links(pair, lo, hi, bool(hole), computed, table, up[s], down[s + 1]);
        }
    }
    for (size_t s = 0; s < S; ++s)
        for (size_t k = 0; k < members[s].size(); ++k) {
            const ContourRef ref = ref_of(stack.slices[s].contours[members[s][k]]);
            if (!up[s][k]) table.ends.push_back({id, s, ref, true});
            if (!down[s][k]) table.ends.push_back({id, s, ref, false});
        }
}

// The cut overrides no structure's correspondence listed (their contours
// now in different structures, or never linked), so each cut can be seen.
void list_other_cuts(const ContourStack& stack, LinkTable& table) {
    for (const LinkOverride& o : stack.links) {
        if (o.edit != LinkEdit::Cut) continue;
        const bool listed = std::any_of(table.links.begin(), table.links.end(), [&](const TableLink& l) {
            return l.origin == LinkOrigin::Cut &&
                   ((l.lower == o.a && l.upper == o.b) || (l.lower == o.b && l.upper == o.a));
        });
        auto a = find_contour(stack, o.a), b = find_contour(stack, o.b);
        if (listed || !a || !b) continue;  // a contour a repair dropped: nothing to show
        if (a->slice > b->slice) std::swap(a, b);
        const Contour& lower = stack.slices[a->slice].contours[a->position];
        const Contour& upper = stack.slices[b->slice].contours[b->position];
        table.links.push_back(
            {lower.structure, a->slice, ref_of(lower), ref_of(upper), false, LinkKind::Band, LinkOrigin::Cut});
    }
}

}  // namespace

Result<LinkTable> compute_link_table(const ContourStack& input, CorrespondenceMethod method,
                                     const RepairOptions& repair, const std::string& path) {
    LinkTable table;
    for (const LinkOverride& o : input.links)
        if (o.edit == LinkEdit::Exclude) table.excluded.push_back(o.a);
    ContourStack stack = input;
    drop_excluded_contours(stack);
    RepairLog log;
    if (auto valid = validate_contour_stack(stack, path, repair, log); !valid) return valid.error();
    const StructureGroups groups = group_structures(stack, method);
    for (size_t i = 0; i < groups.infos.size(); ++i)
        structure_links(stack, groups.infos[i].id, groups.members[i], method, table);
    list_other_cuts(stack, table);
    return table;
}

const char* link_origin_name(LinkOrigin origin) {
    switch (origin) {
        case LinkOrigin::Computed: return "computed";
        case LinkOrigin::Joined: return "joined";
        case LinkOrigin::Cut: return "cut";
    }
    return "computed";
}

const char* link_kind_name(LinkKind kind) { return kind == LinkKind::Branch ? "branch" : "band"; }

}  // namespace body
