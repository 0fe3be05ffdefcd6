// Union–find whose elements carry a sign relative to their root: value(x) = sign · value(root).
// Used for strips (cubic coefficients equal up to sign) and for orientation (flips).
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

namespace pdesurf::detail {

class ParityUnionFind {
 public:
  explicit ParityUnionFind(std::size_t n) : parent_(n), sign_(n, 1), conflict_(n, 0), rank_(n, 0) {
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }

  struct Root {
    std::uint32_t root;
    std::int8_t sign;  ///< value(x) = sign · value(root)
  };

  Root find(std::uint32_t x) {
    // Two passes: find the root and the sign, then compress the path.
    std::int8_t s = 1;
    std::uint32_t r = x;
    while (parent_[r] != r) {
      s = static_cast<std::int8_t>(s * sign_[r]);
      r = parent_[r];
    }
    std::int8_t sx = s;
    while (parent_[x] != r) {
      const std::uint32_t next = parent_[x];
      const std::int8_t nextSign = static_cast<std::int8_t>(sx * sign_[x]);
      parent_[x] = r;
      sign_[x] = sx;
      x = next;
      sx = nextSign;
    }
    return {r, s};
  }

  /// Records value(b) = rel · value(a). A relation that contradicts earlier ones marks
  /// the set as conflicting (its only consistent value is 0).
  void unite(std::uint32_t a, std::uint32_t b, std::int8_t rel) {
    const Root ra = find(a), rb = find(b);
    const auto needed =
        static_cast<std::int8_t>(rb.sign * rel * ra.sign);  // value(rb) = needed·value(ra)
    if (ra.root == rb.root) {
      if (needed != 1) conflict_[ra.root] = 1;
      return;
    }
    std::uint32_t top = ra.root, below = rb.root;
    if (rank_[top] < rank_[below]) std::swap(top, below);
    if (rank_[top] == rank_[below]) ++rank_[top];
    parent_[below] = top;
    sign_[below] =
        needed;  // symmetric: value(rb) = needed·value(ra) ⇔ value(ra) = needed·value(rb)
    conflict_[top] = static_cast<std::uint8_t>(conflict_[top] | conflict_[below]);
  }

  void markConflict(std::uint32_t x) { conflict_[find(x).root] = 1; }
  bool conflicting(std::uint32_t x) { return conflict_[find(x).root] != 0; }

 private:
  std::vector<std::uint32_t> parent_;
  std::vector<std::int8_t> sign_;
  std::vector<std::uint8_t> conflict_;
  std::vector<std::uint8_t> rank_;
};

}  // namespace pdesurf::detail
