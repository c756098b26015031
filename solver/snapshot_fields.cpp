// Snapshot fields: kinematic state, strain/stress measures, porosity, damage.
#include "solver/snapshot_fields.hpp"

#include <algorithm>

#include <Eigen/Dense>

#include "solver/bond_breakage.hpp"
#include "solver/symmetric_tensor.hpp"
#include "solver/plasticity/plastic_strain_measures.hpp"
#include "solver/viscoplastic_point.hpp"

namespace mppm::solver {

namespace {

// sigma as a full 3 x 3 tensor (row-major, 9 components) in 2-D and 3-D: in plane strain the
// out-of-plane normal stress sigma_zz = lambda tr(eps_e) + 2 mu eps_e,zz is not zero (eps_e,zz =
// -eps_vp,zz with viscoplasticity), and the postprocessor's invariants (von Mises, mean stress)
// need it. The same expressions as the kernel's, so the snapshot shows the stress it used.
template <int D>
void stress_field(const Model& m, std::vector<double>& out) {
  using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
  const PointData& p = m.points;
  out.assign(p.owned * 9, 0.0);
  for (std::size_t i = 0; i < p.owned; ++i) {
    const Mat eps = Eigen::Map<const Mat>(&p.strain[i * D * D]);
    if (!p.plastic_strain.empty()) {
      const auto stress =
          viscoplastic::elastic_stress<D>(viscoplastic::elastic_strain<D>(eps, &p.plastic_strain[i * 9]), m.constants);
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < D; ++c) out[i * 9 + r * 3 + c] = stress.in_plane(r, c);
      if constexpr (D == 2) out[i * 9 + 8] = stress.zz;
      continue;
    }
    const Mat sigma = cosserat_stress<D>(eps, m.constants);
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) out[i * 9 + r * 3 + c] = sigma(r, c);
    if constexpr (D == 2) out[i * 9 + 8] = m.constants.lambda * eps.trace();  // eps_zz = 0
  }
}

// The weights of ebar of the run's model (the default ones for a model that has none).
plasticity::EquivalentStrainWeights equivalent_strain_weights(const Model& m) {
  if (const auto* dp = dynamic_cast<const plasticity::DruckerPragerPerzynaModel*>(m.viscoplastic_model.get()))
    return dp->constants().parameters.equivalent_strain;
  return {};
}

// sqrt(b1 e:e + b2 e:e^T + b3 l^2 kap_vp:kap_vp) of the accumulated plastic tensors.
void plastic_shear_strain_field(const Model& m, std::vector<double>& out) {
  const PointData& p = m.points;
  const auto weights = equivalent_strain_weights(m);
  const int RD = p.rotation_components * p.dimension;
  out.resize(p.owned);
  for (std::size_t i = 0; i < p.owned; ++i) {
    const Eigen::Matrix3d eps_vp = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(&p.plastic_strain[i * 9]);
    Eigen::VectorXd kap_vp = Eigen::VectorXd::Zero(std::max(RD, 1));
    for (int k = 0; k < RD; ++k) kap_vp[k] = p.plastic_wryness[i * RD + k];
    out[i] = plasticity::equivalent_plastic_shear_strain(eps_vp, kap_vp, weights, m.constants.length_scale);
  }
}

template <int D>
void couple_stress_field(const Model& m, std::vector<double>& out) {
  constexpr int R = D == 2 ? 1 : 3;
  using RMat = Eigen::Matrix<double, R, D, Eigen::RowMajor>;
  const PointData& p = m.points;
  out.resize(p.owned * R * D);
  for (std::size_t i = 0; i < p.owned; ++i) {
    RMat kap = Eigen::Map<const RMat>(&p.wryness[i * R * D]);
    if (!p.plastic_wryness.empty()) kap -= Eigen::Map<const RMat>(&p.plastic_wryness[i * R * D]);
    Eigen::Map<RMat> target(&out[i * R * D]);
    target = couple_stress<D, R>(kap, m.constants);
  }
}

// n = 1 - phi0 / J with J = det(1 + grad u), grad u from the same nonlocal operator.
template <int D>
void porosity_field(const Model& m, std::vector<double>& out) {
  using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
  using Vec = Eigen::Matrix<double, D, 1>;
  const PointData& p = m.points;
  const BondFamilies& f = m.bonds;
  out.resize(p.owned);
  for (std::size_t i = 0; i < p.owned; ++i) {
    if (p.detached[i]) {
      out[i] = 1.0 - m.constants.solid_fraction;
      continue;
    }
    Mat S = Mat::Zero();
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      if (!f.intact.empty() && !f.intact[b]) continue;
      const auto j = static_cast<std::size_t>(f.neighbor[b]);
      const Vec du = Eigen::Map<const Vec>(&p.displacement[j * D]) - Eigen::Map<const Vec>(&p.displacement[i * D]);
      Vec xi;
      bond_vector<D>(f, p.position.data(), i, b, xi.data());
      S += p.volume[j] * du * xi.transpose();
    }
    const Mat F = Mat::Identity() + S * unpack_symmetric<D>(&p.shape_inverse[i * symmetric_components<D>]);
    out[i] = 1.0 - m.constants.solid_fraction / F.determinant();
  }
}

}  // namespace

std::vector<std::string> available_fields(const Model& m) {
  std::vector<std::string> f{"displacement", "velocity", "stress", "strain", "porosity", "detached"};
  if (m.micropolar()) {
    for (const char* name : {"rotation", "rotation_rate", "couple_stress", "wryness"}) f.push_back(name);
  }
  if (m.effects.damage) f.push_back("damage");
  if (m.effects.viscoplasticity)
    for (const char* name : {"plastic_strain", "plastic_shear_strain", "equivalent_plastic_strain"}) f.push_back(name);
  return f;
}

Snapshot make_snapshot(const Model& m, const std::vector<std::string>& fields, std::int64_t step, double time) {
  const PointData& p = m.points;
  const int D = p.dimension;
  const int R = p.rotation_components;
  Snapshot s;
  s.dimension = D;
  s.step = step;
  s.time = time;
  s.point_count = p.owned;
  const auto available = available_fields(m);
  auto head = [&](const std::vector<double>& v, int components) {
    return std::vector<double>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(p.owned * components));
  };
  for (const std::string& name : fields) {
    if (std::find(available.begin(), available.end(), name) == available.end()) continue;
    SnapshotField field;
    field.name = name;
    if (name == "displacement") {
      field.components = D;
      field.data = head(p.displacement, D);
    } else if (name == "velocity") {
      field.components = D;
      field.data = head(p.velocity, D);
    } else if (name == "rotation") {
      field.components = R;
      field.data = head(p.rotation, R);
    } else if (name == "rotation_rate") {
      field.components = R;
      field.data = head(p.spin, R);
    } else if (name == "strain") {
      field.components = D * D;
      field.data = head(p.strain, D * D);
    } else if (name == "wryness") {
      field.components = R * D;
      field.data = head(p.wryness, R * D);
    } else if (name == "stress") {
      field.components = 9;
      D == 2 ? stress_field<2>(m, field.data) : stress_field<3>(m, field.data);
    } else if (name == "couple_stress") {
      field.components = R * D;
      D == 2 ? couple_stress_field<2>(m, field.data) : couple_stress_field<3>(m, field.data);
    } else if (name == "porosity") {
      D == 2 ? porosity_field<2>(m, field.data) : porosity_field<3>(m, field.data);
    } else if (name == "plastic_strain") {
      field.components = 9;  // eps_vp, 3 x 3 row-major (plane strain has an eps_vp,zz)
      field.data = head(p.plastic_strain, 9);
    } else if (name == "plastic_shear_strain") {
      plastic_shear_strain_field(m, field.data);
    } else if (name == "equivalent_plastic_strain") {
      field.data = head(p.equivalent_plastic_strain, 1);
    } else if (name == "detached") {
      field.data.assign(p.detached.begin(), p.detached.begin() + static_cast<std::ptrdiff_t>(p.owned));
    } else if (name == "damage") {
      // D_i = 1 - sum_j b V_j / sum_j V_j over the family before the pre-crack cuts.
      field.data = damage_field(p, m.bonds);
    }
    s.fields.push_back(std::move(field));
  }
  return s;
}

}  // namespace mppm::solver
