// Snapshot fields: kinematic state, strain/stress measures, porosity, damage, crack area, pore fluid.
#include "solver/snapshot_fields.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include "solver/bond_breakage.hpp"
#include "solver/crack_area.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/plasticity/plastic_strain_measures.hpp"
#include "solver/symmetric_tensor.hpp"
#include "solver/viscoplastic_point.hpp"

namespace mppm::solver {

namespace {

// sigma as a full 3 x 3 tensor (row-major, 9 components) in 2-D and 3-D: in plane strain the
// out-of-plane normal stress sigma_zz = lambda tr(eps_e) + 2 mu eps_e,zz is not zero (eps_e,zz =
// -eps_vp,zz with viscoplasticity), and the postprocessor's invariants (von Mises, mean stress)
// need it. The same expressions as the kernel's, so the snapshot shows the stress it used.
template <int D>
void point_stress(const Model& m, std::size_t i, double* out) {
  using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
  const PointData& p = m.points;
  std::fill_n(out, 9, 0.0);
  const Mat eps = Eigen::Map<const Mat>(&p.strain[i * D * D]);
  if (!p.plastic_strain.empty()) {
    const auto stress =
        viscoplastic::elastic_stress<D>(viscoplastic::elastic_strain<D>(eps, &p.plastic_strain[i * 9]), m.constants);
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) out[r * 3 + c] = stress.in_plane(r, c);
    if constexpr (D == 2) out[8] = stress.zz;
    return;
  }
  const Mat sigma = cosserat_stress<D>(eps, m.constants);
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) out[r * 3 + c] = sigma(r, c);
  const CosseratConstants& c = m.constants;
  if constexpr (D == 2)  // plane strain: eps_zz = 0
    out[8] = plasticity::plane_strain_normal_stress(eps.trace(), 0.0, c.lambda, c.mu + c.mu_c, c.mu - c.mu_c);
}

// The weights of ebar of the run's model (the default ones for a model that has none).
plasticity::EquivalentStrainWeights equivalent_strain_weights(const Model& m) {
  if (const auto* dp = dynamic_cast<const plasticity::DruckerPragerPerzynaModel*>(m.viscoplastic_model.get()))
    return dp->constants().parameters.equivalent_strain;
  return {};
}

// sqrt(b1 e:e + b2 e:e^T + b3 l^2 kap_vp:kap_vp) of the accumulated plastic tensors.
// kap_vp as the return map holds it (a 2-vector in 2-D, 3 x 3 in 3-D; zero without micropolar).
template <int D>
double point_plastic_shear_strain(const Model& m, const plasticity::EquivalentStrainWeights& weights, std::size_t i) {
  using Wryness = plasticity::Curvature<D>;
  const PointData& p = m.points;
  const Eigen::Matrix3d eps_vp =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(&p.plastic_strain[i * 9]);
  Wryness kap_vp = Wryness::Zero();
  if (!p.plastic_wryness.empty()) {  // stored row-major, R x D
    const double* stored = &p.plastic_wryness[i * kap_vp.size()];
    if constexpr (D == 2)
      kap_vp = Eigen::Map<const Eigen::Vector2d>(stored);
    else
      kap_vp = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(stored);
  }
  return plasticity::equivalent_plastic_shear_strain(eps_vp, kap_vp, weights, m.constants.length_scale);
}

template <int D>
void point_couple_stress(const Model& m, std::size_t i, double* out) {
  constexpr int R = D == 2 ? 1 : 3;
  using RMat = Eigen::Matrix<double, R, D, Eigen::RowMajor>;
  const PointData& p = m.points;
  RMat kap = Eigen::Map<const RMat>(&p.wryness[i * R * D]);
  if (!p.plastic_wryness.empty()) kap -= Eigen::Map<const RMat>(&p.plastic_wryness[i * R * D]);
  Eigen::Map<RMat> target(out);
  target = couple_stress<D, R>(kap, m.constants);
}

// n = 1 - phi0 / J with J = det(1 + grad u), grad u from the same nonlocal operator.
template <int D>
double point_porosity(const Model& m, std::size_t i) {
  using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
  using Vec = Eigen::Matrix<double, D, 1>;
  const PointData& p = m.points;
  const BondFamilies& f = m.bonds;
  if (p.detached[i]) return 1.0 - m.constants.solid_fraction;
  Mat S = Mat::Zero();
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    if (!f.acting(b)) continue;
    const auto j = static_cast<std::size_t>(f.neighbor[b]);
    const Vec du = Eigen::Map<const Vec>(&p.displacement[j * D]) - Eigen::Map<const Vec>(&p.displacement[i * D]);
    Vec xi;
    bond_vector<D>(f, p.position.data(), i, b, xi.data());
    S += p.volume[j] * du * xi.transpose();
  }
  const Mat F = Mat::Identity() + S * unpack_symmetric<D>(&p.shape_inverse[i * symmetric_components<D>]);
  return 1.0 - m.constants.solid_fraction / F.determinant();
}

// A field whose value at point i is `value(i, out)` (components values into out). The points of a
// chunk are computed in parallel (the damage of a point sums over its bonds, the stress evaluates
// the constitutive law): each writes only its own values, so the bytes do not depend on the
// thread count.
template <class Value>
SnapshotFieldSource per_point(const std::string& name, int components, Value value) {
  return {name, components, [components, value](std::uint64_t first, std::uint64_t count, double* out) {
            const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static) if (thread_point_loop(count))
            for (std::int64_t k = 0; k < n; ++k)
              value(static_cast<std::size_t>(first) + static_cast<std::size_t>(k),
                    out + static_cast<std::uint64_t>(k) * static_cast<std::uint64_t>(components));
          }};
}

// A field that is a stored per-point array of the model (its owned points' part).
SnapshotFieldSource stored(const std::string& name, int components, const std::vector<double>& values) {
  return {name, components, [components, &values](std::uint64_t first, std::uint64_t count, double* out) {
            const auto c = static_cast<std::uint64_t>(components);
            std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(first * c), count * c, out);
          }};
}

}  // namespace

std::vector<std::string> available_fields(const Model& m) {
  std::vector<std::string> f{"displacement", "velocity", "stress", "strain", "porosity", "detached"};
  if (m.micropolar()) {
    for (const char* name : {"rotation", "rotation_rate", "couple_stress", "wryness"}) f.push_back(name);
  }
  if (m.effects.damage) f.push_back("damage");
  if (m.effects.damage && m.dimension() == 3) f.push_back("crack_area");
  if (m.effects.viscoplasticity)
    for (const char* name : {"plastic_strain", "plastic_shear_strain", "equivalent_plastic_strain"}) f.push_back(name);
  if (m.fluid)
    for (const char* name : {"pore_pressure", "fluid_content", "saturation", "darcy_velocity"}) f.push_back(name);
  return f;
}

std::vector<SnapshotFieldSource> snapshot_sources(const Model& m, const std::vector<std::string>& fields) {
  const PointData& p = m.points;
  const int D = p.dimension;
  const int R = p.rotation_components;
  const auto available = available_fields(m);
  std::vector<SnapshotFieldSource> sources;
  for (const std::string& name : fields) {
    if (std::find(available.begin(), available.end(), name) == available.end()) continue;
    if (name == "displacement") {
      sources.push_back(stored(name, D, p.displacement));
    } else if (name == "velocity") {
      sources.push_back(stored(name, D, p.velocity));
    } else if (name == "rotation") {
      sources.push_back(stored(name, R, p.rotation));
    } else if (name == "rotation_rate") {
      sources.push_back(stored(name, R, p.spin));
    } else if (name == "strain") {
      sources.push_back(stored(name, D * D, p.strain));
    } else if (name == "wryness") {
      sources.push_back(stored(name, R * D, p.wryness));
    } else if (name == "stress") {
      sources.push_back(per_point(name, 9, [&m, D](std::size_t i, double* out) {
        D == 2 ? point_stress<2>(m, i, out) : point_stress<3>(m, i, out);
      }));
    } else if (name == "couple_stress") {
      sources.push_back(per_point(name, R * D, [&m, D](std::size_t i, double* out) {
        D == 2 ? point_couple_stress<2>(m, i, out) : point_couple_stress<3>(m, i, out);
      }));
    } else if (name == "porosity") {
      sources.push_back(per_point(name, 1, [&m, D](std::size_t i, double* out) {
        *out = D == 2 ? point_porosity<2>(m, i) : point_porosity<3>(m, i);
      }));
    } else if (name == "plastic_strain") {
      sources.push_back(stored(name, 9, p.plastic_strain));  // eps_vp, 3 x 3 row-major (plane strain has an eps_vp,zz)
    } else if (name == "plastic_shear_strain") {
      sources.push_back(per_point(name, 1, [&m, D, weights = equivalent_strain_weights(m)](std::size_t i, double* out) {
        *out = D == 2 ? point_plastic_shear_strain<2>(m, weights, i) : point_plastic_shear_strain<3>(m, weights, i);
      }));
    } else if (name == "equivalent_plastic_strain") {
      sources.push_back(stored(name, 1, p.equivalent_plastic_strain));
    } else if (name == "detached") {
      sources.push_back(per_point(name, 1, [&p](std::size_t i, double* out) { *out = p.detached[i]; }));
    } else if (name == "pore_pressure") {
      sources.push_back(stored(name, 1, p.pore_pressure));
    } else if (name == "fluid_content") {
      // zeta = n0 + its change (PointData::fluid_content_change); the layers carry none.
      sources.push_back(per_point(name, 1, [&p, n0 = m.fluid->porosity](std::size_t i, double* out) {
        *out = p.region[i] == 0 ? n0 + p.fluid_content_change[i] : 0.0;
      }));
    } else if (name == "saturation") {
      // S_r(p) with a retention curve, else 1: the fluid fills the pores (the layers carry none).
      sources.push_back(per_point(name, 1, [&p, curve = m.fluid->retention](std::size_t i, double* out) {
        *out = p.region[i] != 0 ? 0.0 : (curve ? saturation(*curve, p.pore_pressure[i]) : 1.0);
      }));
    } else if (name == "darcy_velocity") {
      sources.push_back(per_point(name, D, [&m](std::size_t i, double* out) {
        darcy_velocity(m.points, m.bonds, *m.fluid, i, out, &m.drains);
      }));
    } else if (name == "damage") {
      // D_i = 1 - sum_j b V_j / sum_j V_j over the family before the pre-crack cuts.
      sources.push_back(
          per_point(name, 1, [&m](std::size_t i, double* out) { *out = point_damage(m.points, m.bonds, i); }));
    } else if (name == "crack_area") {
      // The point's share of the crack area of its broken and cut bonds [m^2] (crack_area.hpp).
      sources.push_back(per_point(name, 1, [&m](std::size_t i, double* out) {
        *out = point_crack_area(m.points, m.bonds, m.precrack_cuts, i);
      }));
    }
  }
  return sources;
}

Snapshot make_snapshot(const Model& m, const std::vector<std::string>& fields, std::int64_t step, double time) {
  Snapshot s;
  s.dimension = m.points.dimension;
  s.step = step;
  s.time = time;
  s.point_count = m.points.owned;
  for (const SnapshotFieldSource& source : snapshot_sources(m, fields)) {
    SnapshotField field{source.name, source.components,
                        std::vector<double>(s.point_count * static_cast<std::uint64_t>(source.components))};
    source.values(0, s.point_count, field.data.data());
    s.fields.push_back(std::move(field));
  }
  return s;
}

}  // namespace mppm::solver
