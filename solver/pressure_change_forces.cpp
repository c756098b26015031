// The forces of a pore-pressure change (see pressure_change_forces.hpp).
#include "solver/pressure_change_forces.hpp"

#include <Eigen/Dense>

#include "solver/parallel_policy.hpp"
#include "solver/symmetric_tensor.hpp"
#include "solver/unsaturated_coupling.hpp"

namespace mppm::solver {

namespace {

// The pressure change of point j in the force state: none at a layer point or a detached one.
bool in_force_state(const PointData& p, std::size_t j) { return p.region[j] == 0 && !p.detached[j]; }

// change(j): the change of point j's pore stress (0 outside the force state).
template <int D, class Change>
void add_changes(PointData& p, const BondFamilies& f, double b, Change&& pressure_change) {
  using Vec = Eigen::Matrix<double, D, 1>;
  constexpr int S = symmetric_components<D>;
  const int R = p.rotation_components;
  const auto n = static_cast<std::int64_t>(p.owned);
  // The force tensors change last, in a loop of their own: the bond loop reads the neighbours'.
#pragma omp parallel for schedule(static) if (thread_bond_loop(f.bond_count()))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (p.detached[i]) continue;
    Vec m = Vec::Zero(), force = Vec::Zero();
    double moment[3] = {0.0, 0.0, 0.0};
    for (std::int64_t k = f.offset[i]; k < f.offset[i + 1]; ++k) {
      if (!f.acting(k)) continue;
      const auto j = static_cast<std::size_t>(f.neighbor[k]);
      double x[D];
      bond_vector<D>(f, p.position.data(), i, k, x);
      const Eigen::Map<const Vec> xi(x);
      m += p.volume[j] * xi;
      const double dp = pressure_change(j);
      if (dp == 0.0) continue;
      const Vec t = -b * dp * (unpack_symmetric<D>(&p.shape_inverse[j * S]) * xi);  // dA_j xi
      force += p.volume[j] * t;
      if (R > 0) {
        const double h = 0.5 * p.volume[j];
        if constexpr (D == 2) {
          moment[0] += h * (x[0] * t(1) - x[1] * t(0));
        } else {
          moment[0] += h * (x[1] * t(2) - x[2] * t(1));
          moment[1] += h * (x[2] * t(0) - x[0] * t(2));
          moment[2] += h * (x[0] * t(1) - x[1] * t(0));
        }
      }
    }
    const double dpi = pressure_change(i);
    if (dpi != 0.0) force += -b * dpi * (unpack_symmetric<D>(&p.shape_inverse[i * S]) * m);
    for (int a = 0; a < D; ++a) p.force[i * D + a] += force(a);
    for (int a = 0; a < R; ++a) p.moment[i * R + a] += moment[a];
  }
#pragma omp parallel for schedule(static) if (thread_point_loop(p.owned))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    const double dpi = pressure_change(i);
    if (dpi == 0.0) continue;
    // A as stored, by columns (point_data.hpp).
    Eigen::Map<Eigen::Matrix<double, D, D, Eigen::ColMajor>> a(&p.force_tensor[i * D * D]);
    a -= b * dpi * unpack_symmetric<D>(&p.shape_inverse[i * S]);
  }
}

}  // namespace

void add_pressure_change_forces(PointData& p, const BondFamilies& f, const CosseratConstants& c,
                                const std::vector<double>& before) {
  if (c.retention) {
    // Bishop's pore stress S_r(p) p is not linear in p: its change, once per point.
    std::vector<double> change(p.total(), 0.0);
    const auto n = static_cast<std::int64_t>(p.owned);
#pragma omp parallel for schedule(static) if (thread_point_loop(p.owned))
    for (std::int64_t s = 0; s < n; ++s) {
      const auto j = static_cast<std::size_t>(s);
      if (in_force_state(p, j))
        change[j] = bishop_pressure(*c.retention, p.pore_pressure[j]) - bishop_pressure(*c.retention, before[j]);
    }
    auto of = [&change](std::size_t j) { return change[j]; };
    if (p.dimension == 2)
      add_changes<2>(p, f, c.biot_coefficient, of);
    else
      add_changes<3>(p, f, c.biot_coefficient, of);
    return;
  }
  auto of = [&p, &before](std::size_t j) { return in_force_state(p, j) ? p.pore_pressure[j] - before[j] : 0.0; };
  if (p.dimension == 2)
    add_changes<2>(p, f, c.biot_coefficient, of);
  else
    add_changes<3>(p, f, c.biot_coefficient, of);
}

}  // namespace mppm::solver
