// Weighted recursive coordinate bisection (coordinate_bisection.hpp). Integer weights make every
// comparison of the cut exact, so no rounding can move a point across it.
#include "solver/coordinate_bisection.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace mppm::solver {

namespace {

class Bisection {
 public:
  Bisection(const PartitionPoints& points, std::vector<std::int32_t>& part) : p_(points), part_(part) {}

  // Splits order[first, last) into `parts` parts numbered from `first_part`.
  void split(std::vector<std::size_t>& order, std::size_t first, std::size_t last, int parts, int first_part) {
    if (parts == 1) {
      for (std::size_t k = first; k < last; ++k) part_[order[k]] = first_part;
      return;
    }
    sort_along_longest_axis(order, first, last);
    const int left_parts = parts / 2;
    const std::size_t cut = weighted_cut(order, first, last, left_parts, parts);
    split(order, first, cut, left_parts, first_part);
    split(order, cut, last, parts - left_parts, first_part + left_parts);
  }

 private:
  double coordinate(std::size_t i, int axis) const {
    return p_.position[i * static_cast<std::size_t>(p_.dimension) + static_cast<std::size_t>(axis)];
  }

  // The axis of the largest extent of the points' bounding box (the lowest axis on a tie).
  int longest_axis(const std::vector<std::size_t>& order, std::size_t first, std::size_t last) const {
    int best = 0;
    double best_extent = -1.0;
    for (int a = 0; a < p_.dimension; ++a) {
      double lo = coordinate(order[first], a), hi = lo;
      for (std::size_t k = first; k < last; ++k) {
        lo = std::min(lo, coordinate(order[k], a));
        hi = std::max(hi, coordinate(order[k], a));
      }
      if (hi - lo > best_extent) {
        best = a;
        best_extent = hi - lo;
      }
    }
    return best;
  }

  void sort_along_longest_axis(std::vector<std::size_t>& order, std::size_t first, std::size_t last) const {
    const int axis = longest_axis(order, first, last);
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(first), order.begin() + static_cast<std::ptrdiff_t>(last),
              [&](std::size_t a, std::size_t b) {
                const double xa = coordinate(a, axis), xb = coordinate(b, axis);
                return xa != xb ? xa < xb : p_.global_id[a] < p_.global_id[b];
              });
  }

  // The first index of the right side: the prefix whose weight is nearest to left_parts / parts of
  // the whole (the shorter prefix on a tie), leaving at least one point per part on each side.
  std::size_t weighted_cut(const std::vector<std::size_t>& order, std::size_t first, std::size_t last, int left_parts,
                           int parts) const {
    std::int64_t total = 0;
    for (std::size_t k = first; k < last; ++k) total += p_.weight[order[k]];
    // Compare prefix * parts with total * left_parts: integers, exact.
    const std::int64_t target = total * left_parts;
    const std::size_t lowest = first + static_cast<std::size_t>(left_parts);
    const std::size_t highest = last - static_cast<std::size_t>(parts - left_parts);
    std::int64_t prefix = 0;
    for (std::size_t k = first; k < lowest; ++k) prefix += p_.weight[order[k]];
    std::size_t best = lowest;
    std::int64_t best_miss = std::abs(prefix * parts - target);
    for (std::size_t cut = lowest + 1; cut <= highest; ++cut) {
      prefix += p_.weight[order[cut - 1]];
      const std::int64_t miss = std::abs(prefix * parts - target);
      if (miss < best_miss) {
        best = cut;
        best_miss = miss;
      }
      if (prefix * parts > target) break;  // the miss only grows from here
    }
    return best;
  }

  const PartitionPoints& p_;
  std::vector<std::int32_t>& part_;
};

}  // namespace

std::vector<std::int32_t> coordinate_bisection(const PartitionPoints& points, int parts) {
  const std::size_t n = points.global_id.size();
  if (points.dimension < 1 || points.dimension > 3 ||
      points.position.size() != n * static_cast<std::size_t>(points.dimension) || points.weight.size() != n)
    throw std::invalid_argument("coordinate_bisection: positions, weights and ids of different lengths");
  if (parts < 1 || n < static_cast<std::size_t>(parts))
    throw std::invalid_argument("coordinate_bisection: " + std::to_string(n) + " points cannot fill " +
                                std::to_string(parts) + " parts (one point at least per process)");
  for (const std::int64_t w : points.weight)
    if (w <= 0) throw std::invalid_argument("coordinate_bisection: a point's weight is not positive");
  std::vector<std::int32_t> part(n, 0);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  Bisection(points, part).split(order, 0, n, parts, 0);
  return part;
}

}  // namespace mppm::solver
