// Grouping of contours into structures and of links into branch groups, both
// as connected components (union-find).
#include "builder/correspondence/grouping.h"

#include <algorithm>
#include <map>
#include <string>

#include "builder/contours/validate.h"
#include "builder/correspondence/link_overrides.h"
#include "shared/union_find.h"

namespace body {
namespace {

const Vec3 kPalette[] = {{0.85, 0.33, 0.31}, {0.36, 0.62, 0.83}, {0.45, 0.75, 0.40}, {0.93, 0.70, 0.25},
                         {0.65, 0.45, 0.80}, {0.30, 0.75, 0.72}, {0.90, 0.55, 0.70}, {0.60, 0.60, 0.60}};

// Phase 1: labelled contours into their structures; the rest per slice.
std::vector<std::vector<uint32_t>> sort_labelled(const ContourStack& stack, StructureGroups& g) {
    const size_t S = stack.slices.size();
    std::map<std::string, size_t> index;
    for (size_t i = 0; i < g.infos.size(); ++i) index[g.infos[i].id] = i;
    g.members.assign(g.infos.size(), std::vector<std::vector<uint32_t>>(S));
    std::vector<std::vector<uint32_t>> unlabelled(S);
    for (uint32_t s = 0; s < S; ++s)
        for (uint32_t c = 0; c < stack.slices[s].contours.size(); ++c) {
            const Contour& contour = stack.slices[s].contours[c];
            if (contour.structure.empty())
                unlabelled[s].push_back(c);
            else
                g.members[index[contour.structure]][s].push_back(c);
        }
    return unlabelled;
}

// Phase 2: unlabelled contours joined to their parent (holes, and solids
// inside holes: a nest is one piece) and the outermost ones to those they
// correspond to on the next slice, by the area each encloses (with the stack's
// cuts and joins: a cut may split a structure, a join merges two). Nodes are
// numbered over all unlabelled contours, slice by slice from `first[s]`.
void join_unlabelled(const ContourStack& stack, const std::vector<std::vector<uint32_t>>& unlabelled,
                     const std::vector<uint32_t>& first, CorrespondenceMethod method, UnionFind& uf) {
    const size_t S = stack.slices.size();
    std::vector<std::vector<uint32_t>> outer(S);  // positions within unlabelled[s]
    for (size_t s = 0; s < S; ++s) {
        Nesting n = compute_nesting(stack.slices[s], unlabelled[s]);
        for (uint32_t k = 0; k < unlabelled[s].size(); ++k) {
            if (n.parent[k] < 0)
                outer[s].push_back(k);
            else
                uf.unite(first[s] + k, first[s] + uint32_t(n.parent[k]));
        }
    }
    for (size_t s = 0; s + 1 < S; ++s) {
        std::vector<PolygonSpan> lower, upper;
        for (uint32_t k : outer[s]) lower.emplace_back(stack.slices[s].contours[unlabelled[s][k]].points);
        for (uint32_t k : outer[s + 1]) upper.emplace_back(stack.slices[s + 1].contours[unlabelled[s + 1][k]].points);
        std::vector<ContourLink> links = correspond_contours(lower, upper, method);
        if (!stack.links.empty()) {
            std::vector<const Contour*> lower_src, upper_src;
            for (uint32_t k : outer[s]) lower_src.push_back(&stack.slices[s].contours[unlabelled[s][k]]);
            for (uint32_t k : outer[s + 1]) upper_src.push_back(&stack.slices[s + 1].contours[unlabelled[s + 1][k]]);
            apply_link_overrides(stack.links, lower_src, upper_src, links);
        }
        for (const ContourLink& l : links) uf.unite(first[s] + outer[s][l.lower], first[s + 1] + outer[s + 1][l.upper]);
    }
}

}  // namespace

StructureGroups group_structures(const ContourStack& stack, CorrespondenceMethod method) {
    StructureGroups g;
    g.infos = stack.structures;
    const size_t S = stack.slices.size();
    const std::vector<std::vector<uint32_t>> unlabelled = sort_labelled(stack, g);
    std::vector<uint32_t> first(S + 1, 0);
    for (size_t s = 0; s < S; ++s) first[s + 1] = first[s] + uint32_t(unlabelled[s].size());
    UnionFind uf(first[S]);
    join_unlabelled(stack, unlabelled, first, method, uf);
    // Phase 3: one automatic structure per component.
    std::map<uint32_t, size_t> auto_index;  // union-find root -> structure
    for (uint32_t s = 0; s < S; ++s)
        for (uint32_t k = 0; k < unlabelled[s].size(); ++k) {
            const uint32_t root = uf.find(first[s] + k);
            auto [it, inserted] = auto_index.emplace(root, g.infos.size());
            if (inserted) {
                const size_t n = auto_index.size();
                StructureInfo info;
                info.id = "auto_" + std::to_string(n);
                info.name = "structure " + std::to_string(n);
                info.color = kPalette[(n - 1) % (sizeof kPalette / sizeof kPalette[0])];
                g.infos.push_back(info);
                g.members.emplace_back(S);
            }
            g.members[it->second][s].push_back(unlabelled[s][k]);
        }
    return g;
}

std::vector<LinkGroup> group_links(std::span<const ContourLink> links, size_t lower_count, size_t upper_count) {
    UnionFind uf(lower_count + upper_count);
    for (const ContourLink& l : links) uf.unite(l.lower, uint32_t(lower_count) + l.upper);
    std::map<uint32_t, LinkGroup> groups;  // by root
    for (const ContourLink& l : links) {
        LinkGroup& g = groups[uf.find(l.lower)];
        g.lower.push_back(l.lower);
        g.upper.push_back(l.upper);
        g.links.push_back(l);
    }
    std::vector<LinkGroup> out;
    for (auto& [root, g] : groups) {
        std::sort(g.lower.begin(), g.lower.end());
        g.lower.erase(std::unique(g.lower.begin(), g.lower.end()), g.lower.end());
        std::sort(g.upper.begin(), g.upper.end());
        g.upper.erase(std::unique(g.upper.begin(), g.upper.end()), g.upper.end());
        out.push_back(std::move(g));
    }
    return out;
}

}  // namespace body
