// Stress and couple-stress invariants.
#include "postprocess/derived_fields.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace mppm::post {

namespace {

// `invariant` of each point's 3x3 tensor (9 values, row-major), one value per point.
template <class Invariant>
std::vector<double> per_tensor(const std::vector<double>& stress, const char* name, Invariant invariant) {
  if (stress.size() % 9 != 0) throw std::invalid_argument(std::string(name) + ": not 9 components per point");
  const auto n = static_cast<std::int64_t>(stress.size() / 9);
  std::vector<double> values(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    values[static_cast<std::size_t>(i)] = invariant(&stress[static_cast<std::size_t>(i) * 9]);
  return values;
}

}  // namespace

std::vector<double> von_mises_stress(const std::vector<double>& stress) {
  return per_tensor(stress, "von_mises_stress", [](const double* s) {
    const double p = (s[0] + s[4] + s[8]) / 3.0;
    const double dxx = s[0] - p, dyy = s[4] - p, dzz = s[8] - p;
    const double sxy = 0.5 * (s[1] + s[3]), sxz = 0.5 * (s[2] + s[6]), syz = 0.5 * (s[5] + s[7]);
    const double contraction = dxx * dxx + dyy * dyy + dzz * dzz + 2.0 * (sxy * sxy + sxz * sxz + syz * syz);
    return std::sqrt(1.5 * contraction);
  });
}

std::vector<double> mean_stress(const std::vector<double>& stress) {
  return per_tensor(stress, "mean_stress", [](const double* s) { return (s[0] + s[4] + s[8]) / 3.0; });
}

std::vector<double> magnitude(const std::vector<double>& data, int components) {
  if (components <= 0 || data.size() % static_cast<std::size_t>(components) != 0)
    throw std::invalid_argument("magnitude: data size is not a multiple of the component count");
  const auto c = static_cast<std::size_t>(components);
  const auto n = static_cast<std::int64_t>(data.size() / c);
  std::vector<double> m(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    double sum = 0.0;
    for (std::size_t k = 0; k < c; ++k) {
      const double v = data[static_cast<std::size_t>(i) * c + k];
      sum += v * v;
    }
    m[static_cast<std::size_t>(i)] = std::sqrt(sum);
  }
  return m;
}

}  // namespace mppm::post
