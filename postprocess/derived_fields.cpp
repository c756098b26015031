// Stress and couple-stress invariants.
#include "postprocess/derived_fields.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace mppm::post {

std::vector<double> von_mises_stress(const std::vector<double>& stress) {
  if (stress.size() % 9 != 0) throw std::invalid_argument("von_mises_stress: not 9 components per point");
  const auto n = static_cast<std::int64_t>(stress.size() / 9);
  std::vector<double> q(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const double* s = &stress[static_cast<std::size_t>(i) * 9];
    const double p = (s[0] + s[4] + s[8]) / 3.0;
    const double dxx = s[0] - p, dyy = s[4] - p, dzz = s[8] - p;
    const double sxy = 0.5 * (s[1] + s[3]), sxz = 0.5 * (s[2] + s[6]), syz = 0.5 * (s[5] + s[7]);
    const double contraction = dxx * dxx + dyy * dyy + dzz * dzz + 2.0 * (sxy * sxy + sxz * sxz + syz * syz);
    q[static_cast<std::size_t>(i)] = std::sqrt(1.5 * contraction);
  }
  return q;
}

std::vector<double> mean_stress(const std::vector<double>& stress) {
  if (stress.size() % 9 != 0) throw std::invalid_argument("mean_stress: not 9 components per point");
  const auto n = static_cast<std::int64_t>(stress.size() / 9);
  std::vector<double> p(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const double* s = &stress[static_cast<std::size_t>(i) * 9];
    p[static_cast<std::size_t>(i)] = (s[0] + s[4] + s[8]) / 3.0;
  }
  return p;
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
