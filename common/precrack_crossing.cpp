// Exact bond / pre-crack intersection tests (see precrack_crossing.hpp). CGAL's
// Exact_predicates_inexact_constructions_kernel evaluates do_intersect with filtered exact
// predicates, so a bond through a crack tip or a mesh vertex is decided the same way everywhere.
#include "common/precrack_crossing.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>

namespace mppm {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

int vertices_per_element(int dimension) { return dimension == 2 ? 2 : 3; }

bool element_is_degenerate(int dimension, const double* v) {
  if (dimension == 2) return v[0] == v[3] && v[1] == v[4];
  const Kernel::Point_3 p(v[0], v[1], v[2]), q(v[3], v[4], v[5]), r(v[6], v[7], v[8]);
  return CGAL::collinear(p, q, r);
}

bool segment_crosses(int dimension, const double* v, const Point3& a, const Point3& b) {
  if (dimension == 2) {
    const Kernel::Segment_2 crack({v[0], v[1]}, {v[3], v[4]});
    if (a[0] == b[0] && a[1] == b[1]) return false;
    const Kernel::Segment_2 bond({a[0], a[1]}, {b[0], b[1]});
    return CGAL::do_intersect(crack, bond);
  }
  const Kernel::Triangle_3 crack({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]});
  if (a == b) return false;
  const Kernel::Segment_3 bond({a[0], a[1], a[2]}, {b[0], b[1], b[2]});
  return CGAL::do_intersect(crack, bond);
}

}  // namespace

bool bond_crosses_precrack(const Point3& a, const Point3& b, int dimension,
                           const std::vector<double>& precrack_vertices) {
  const std::size_t stride = 3 * static_cast<std::size_t>(vertices_per_element(dimension));
  for (std::size_t e = 0; e + stride <= precrack_vertices.size(); e += stride) {
    const double* v = precrack_vertices.data() + e;
    if (element_is_degenerate(dimension, v)) continue;
    if (segment_crosses(dimension, v, a, b)) return true;
  }
  return false;
}

PrecrackIndex::PrecrackIndex(int dimension, const std::vector<double>& precrack_vertices, double cell_size)
    : dimension_(dimension), cell_size_(cell_size > 0.0 ? cell_size : 1.0) {
  const int per = vertices_per_element(dimension);
  const std::size_t stride = 3 * static_cast<std::size_t>(per);
  for (std::size_t e = 0; e + stride <= precrack_vertices.size(); e += stride) {
    const double* v = precrack_vertices.data() + e;
    if (element_is_degenerate(dimension, v)) continue;
    vertices_.insert(vertices_.end(), v, v + stride);
  }
  elements_ = vertices_.size() / stride;
  low_ = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  high_ = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t e = 0; e < elements_; ++e) {
    std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int k = 0; k < per; ++k)
      for (int c = 0; c < 3; ++c) {
        const double value = vertices_[e * stride + 3 * k + c];
        lo[c] = std::min(lo[c], value);
        hi[c] = std::max(hi[c], value);
      }
    std::array<std::int64_t, 3> first{}, last{};
    for (int c = 0; c < 3; ++c) {
      low_[c] = std::min(low_[c], lo[c]);
      high_[c] = std::max(high_[c], hi[c]);
      first[c] = static_cast<std::int64_t>(std::floor(lo[c] / cell_size_));
      last[c] = static_cast<std::int64_t>(std::floor(hi[c] / cell_size_));
    }
    for (auto i = first[0]; i <= last[0]; ++i)
      for (auto j = first[1]; j <= last[1]; ++j)
        for (auto k = first[2]; k <= last[2]; ++k) entries_.push_back({{i, j, k}, static_cast<std::int32_t>(e)});
  }
  std::sort(entries_.begin(), entries_.end(), [](const CellEntry& l, const CellEntry& r) {
    return l.cell != r.cell ? l.cell < r.cell : l.element < r.element;
  });
}

bool PrecrackIndex::element_crosses(std::int32_t element, const Point3& a, const Point3& b) const {
  const std::size_t stride = 3 * static_cast<std::size_t>(vertices_per_element(dimension_));
  return segment_crosses(dimension_, vertices_.data() + static_cast<std::size_t>(element) * stride, a, b);
}

bool PrecrackIndex::may_cross_within(const Point3& a, double reach) const {
  if (elements_ == 0) return false;
  for (int c = 0; c < 3; ++c)
    if (a[c] + reach < low_[c] || a[c] - reach > high_[c]) return false;
  return true;
}

bool PrecrackIndex::crosses(const Point3& a, const Point3& b) const {
  if (elements_ == 0) return false;
  std::array<std::int64_t, 3> first{}, last{};
  for (int c = 0; c < 3; ++c) {
    const double lo = std::min(a[c], b[c]), hi = std::max(a[c], b[c]);
    if (hi < low_[c] || lo > high_[c]) return false;  // bounding boxes apart: no contact
    first[c] = static_cast<std::int64_t>(std::floor(lo / cell_size_));
    last[c] = static_cast<std::int64_t>(std::floor(hi / cell_size_));
  }
  // Cells are closed on the low side; an element touching a cell face is in both cells, so
  // every element that can touch the bond is among the candidates below.
  for (auto i = first[0]; i <= last[0]; ++i)
    for (auto j = first[1]; j <= last[1]; ++j)
      for (auto k = first[2]; k <= last[2]; ++k) {
        const std::array<std::int64_t, 3> cell{i, j, k};
        auto it =
            std::lower_bound(entries_.begin(), entries_.end(), cell,
                             [](const CellEntry& e, const std::array<std::int64_t, 3>& key) { return e.cell < key; });
        for (; it != entries_.end() && it->cell == cell; ++it)
          if (element_crosses(it->element, a, b)) return true;
      }
  return false;
}

}  // namespace mppm
