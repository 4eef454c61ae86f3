// Correspondence overrides applied to computed links (contract in link_overrides.h).
#include "builder/correspondence/link_overrides.h"

#include <algorithm>

namespace body {

void drop_excluded_contours(ContourStack& stack) {
    auto excluded = [&](const Contour& c) {
        return std::any_of(stack.links.begin(), stack.links.end(),
                           [&](const LinkOverride& o) { return o.edit == LinkEdit::Exclude && names(o.a, c); });
    };
    for (Slice& slice : stack.slices) std::erase_if(slice.contours, excluded);
}

void apply_link_overrides(std::span<const LinkOverride> overrides, std::span<const Contour* const> lower,
                          std::span<const Contour* const> upper, std::vector<ContourLink>& links) {
    // Whether override `o` names lower contour l and upper contour u (either way round).
    auto pairs = [&](const LinkOverride& o, uint32_t l, uint32_t u) {
        return (names(o.a, *lower[l]) && names(o.b, *upper[u])) || (names(o.b, *lower[l]) && names(o.a, *upper[u]));
    };
    for (const LinkOverride& o : overrides) {
        if (o.edit == LinkEdit::Cut) {
            std::erase_if(links, [&](const ContourLink& k) { return pairs(o, k.lower, k.upper); });
        } else if (o.edit == LinkEdit::Join) {
            for (uint32_t l = 0; l < lower.size(); ++l)
                for (uint32_t u = 0; u < upper.size(); ++u)
                    if (pairs(o, l, u)) links.push_back({l, u});
        }
    }
    std::sort(links.begin(), links.end());
    links.erase(std::unique(links.begin(), links.end()), links.end());
}

}  // namespace body
