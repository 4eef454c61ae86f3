#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

namespace body {

// Disjoint sets over ids 0..n-1 with path halving. unite(a, b) makes b's root
// the root of both, so the roots (and any order keyed by them) depend only on
// the sequence of unite calls.
struct UnionFind {
    std::vector<uint32_t> parent;

    explicit UnionFind(size_t n = 0) { reset(n); }
    void reset(size_t n) {
        parent.resize(n);
        std::iota(parent.begin(), parent.end(), 0u);
    }
    uint32_t find(uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(uint32_t a, uint32_t b) {
        const uint32_t ra = find(a), rb = find(b);
        if (ra != rb) parent[ra] = rb;
    }
    size_t size() const { return parent.size(); }
};

}  // namespace body
